// runs/: the one way to run a case. Its writing rule (every finished step reaches the directory,
// the end always), its turning a refusal into a result for studies, and running many at once in
// order.
#include "runs/run.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "common.hpp"
#include "compare/compare.hpp"
#include "model/case.hpp"
#include "runs/parallel.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;

const std::string kArch = std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json";

TEST(RunsMethod, NamesRoundTrip) {
  for (Method m : {Method::prd, Method::dem}) EXPECT_EQ(parse_method(method_name(m)), m);
  EXPECT_FALSE(parse_method("PRD").has_value());  // names in files are lower case
  EXPECT_STREQ(method_label(Method::dem), "DEM");
}

// A results file names its method as text: ours read back as the type, an outside solver's
// (validate --solver) stays its own name, with no method of ours.
TEST(RunsMethod, ResultsNameTheirMethod) {
  RunResult r;
  r.method = method_name(Method::prd);
  EXPECT_EQ(known_method(r), Method::prd);
  EXPECT_EQ(method_label(r), "PRD");
  r.method = "toppling";
  EXPECT_FALSE(known_method(r).has_value());
  EXPECT_EQ(method_label(r), "toppling");
}

// While the run goes, the directory holds a prefix of it (never more steps than were recorded,
// the first step from the start); at the end it holds the run itself.
TEST(RunsWriting, EveryFinishedStepReachesTheDirectoryAndTheEndAlways) {
  const test::Scratch scratch("runs-writing");
  const Case c = with_option(load_case(kArch), "motion.max_steps", 60);
  size_t calls = 0, seen_on_disk = 0;
  RunOutput out;
  out.dir = scratch.path.string();
  out.on_step = [&](const RunResult& part) {
    ++calls;
    ASSERT_TRUE(fs::exists(scratch.path / "results.json")) << "the first step is written at once";
    const RunResult disk = load_results((scratch.path / "results.json").string(), c);
    EXPECT_LE(disk.steps.size(), part.steps.size());
    seen_on_disk = std::max(seen_on_disk, disk.steps.size());
  };
  const RunResult r = run_case(c, Method::prd, out);
  EXPECT_GT(calls, 10u);
  EXPECT_GE(seen_on_disk, 1u);
  const RunResult disk = load_results((scratch.path / "results.json").string(), c);
  EXPECT_EQ(disk.steps.size(), r.steps.size());
  EXPECT_EQ(disk.status, r.status);
  EXPECT_DOUBLE_EQ(disk.capacity, r.capacity);
  EXPECT_TRUE(fs::exists(scratch.path / "steps.csv"));
}

// A run killed at any moment leaves a results.json that agrees with itself: its capacity is its
// last equilibrium record (the DEM hands a step out as it records it, and once wrote capacity
// 0.028 m beside its equilibrium record at 0.029 m). Read raw, as another program would.
TEST(RunsWriting, TheFileAtEveryStepHasTheCapacityOfItsLastEquilibrium) {
  const test::Scratch scratch("runs-killed");
  const Case c = with_option(load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json"), "motion.max_steps", 6);
  int checked = 0;
  RunOutput out;
  out.dir = scratch.path.string();
  out.on_step = [&](const RunResult&) {
    const nlohmann::json j = nlohmann::json::parse(test::read(scratch.path / "results.json"));
    ASSERT_EQ(j["stopped"], "running");
    double last = -1;
    int equilibria = 0;
    for (const auto& s : j["steps"])
      if (s.value("settled", false)) last = s["d"].get<double>(), ++equilibria;
    ASSERT_GE(last, 0);
    EXPECT_EQ(j["capacity"].get<double>(), last);
    EXPECT_EQ(j["stable_steps"].get<int>(), equilibria - 1);  // the start's settling is no step
    checked += last > 0;
    // The writer skips a step that comes sooner than four times its last write's cost after it
    // (runs/run.cpp): this DEM run takes milliseconds, so without a pause only the first record
    // was ever written and nothing past d = 0 was checked.
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
  };
  const RunResult r = run_case(c, Method::dem, out);
  EXPECT_GE(checked, 3);
  EXPECT_EQ(r.stable_steps, 6);
}

// A capacity run needs a loading path: a case whose supports do not move is refused before any
// step (it ran 1000 steps and reported "max_steps, capacity 1 m"), for both methods and studies.
TEST(RunsRefusal, SupportsThatDoNotMoveAreRefused) {
  Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  c.motion.supports.clear();
  for (Method m : {Method::prd, Method::dem}) {
    try {
      run_case(c, m);
      ADD_FAILURE() << method_name(m) << " ran";
    } catch (const CaseError& e) {
      EXPECT_NE(std::string(e.what()).find("no support moves"), std::string::npos) << e.what();
    }
    EXPECT_EQ(run_case_in_study(c, m).status, RunStatus::error);
  }
  c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  c.motion.supports[0].rotation = 0;
  EXPECT_THROW(run_case(c, Method::prd), CaseError);
  // No step asked for: the structure only settles (validate's "stands").
  c.motion.max_steps = 0;
  EXPECT_EQ(run_case(c, Method::prd).status, RunStatus::max_steps);
}

// A study goes on past a run its solver refuses: the refusal is a run stopped by "error", with
// the solver's message, written like any other. run_case itself throws (nothing ran).
TEST(RunsInStudy, ARefusalIsAnErrorRunWithTheMessage) {
  const test::Scratch scratch("runs-refusal");
  Case c = load_case(kArch);
  c.blocks[c.block_index("v3")].density = 0;  // past the loader: the DEM cannot give it a mass
  EXPECT_THROW(run_case(c, Method::dem), std::exception);
  RunOutput out;
  out.dir = scratch.path.string();
  const RunResult r = run_case_in_study(c, Method::dem, out);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("v3"), std::string::npos) << r.message;
  const RunResult disk = load_results((scratch.path / "results.json").string(), c);
  EXPECT_EQ(disk.status, RunStatus::error);
  EXPECT_EQ(disk.message, r.message);
}

TEST(RunsParallel, ResultsInOrderWhateverFinishesFirst) {
  std::atomic<int> running{0}, most{0};
  const std::vector<RunResult> out = run_parallel(7, 3, [&](size_t i) {
    const int now = ++running;
    int m = most;
    while (now > m && !most.compare_exchange_weak(m, now)) {
    }
    RunResult r;
    r.capacity = double(i);
    // Later runs finish first.
    std::this_thread::sleep_for(std::chrono::milliseconds(5 * (7 - int(i))));
    --running;
    return r;
  });
  ASSERT_EQ(out.size(), 7u);
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i].capacity, double(i));
  EXPECT_LE(most.load(), 3);
  EXPECT_GE(most.load(), 2);
}

}  // namespace
}  // namespace masonry
