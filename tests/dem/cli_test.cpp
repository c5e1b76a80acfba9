// `masonry dem CASE --out DIR`: results.json and steps.csv written, exit codes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cases/generators.hpp"
#include "model/case.hpp"

namespace {

using namespace masonry;
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Dir {
  fs::path path;
  Dir() {
    path = fs::temp_directory_path() / ("masonry-dem-cli-" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Dir() { fs::remove_all(path); }
};

fs::path write_arch(const Dir& d) {
  CircularArch p;
  p.voussoirs = 8;
  p.thickness = 0.2;
  p.step = 0.01;
  p.max_steps = 3;
  Case c = circular_arch(p);
  c.dem.stiffness_reduction = 10;
  c.dem.hold_time = 0.3;
  const fs::path f = d.path / "arch.json";
  std::ofstream(f) << case_to_json(c);
  return f;
}

int run(const std::string& args, const fs::path& err) {
  const std::string cmd = std::string(MASONRY_EXE) + " dem " + args + " 2>" + err.string() + " >/dev/null";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(DemCli, WritesResultsAndProgress) {
  Dir d;
  const fs::path c = write_arch(d), out = d.path / "out", err = d.path / "err.txt";
  ASSERT_EQ(run(c.string() + " --out " + out.string() + " --max-steps 2 --damping 0.7", err), 0) << slurp(err);
  const auto j = nlohmann::json::parse(slurp(out / "results.json"));
  EXPECT_EQ(j["method"], "dem");
  EXPECT_EQ(j["stopped"], "max_steps");
  EXPECT_EQ(j["steps"].size(), 3u);  // step 0 and two increments
  EXPECT_NEAR(j["capacity"].get<double>(), 0.02, 1e-12);
  EXPECT_GT(j["timing"]["cycles"].get<long long>(), 0);
  EXPECT_GT(j["settings"]["dt"].get<double>(), 0);
  EXPECT_EQ(j["settings"]["damping"].get<double>(), 0.7);
  EXPECT_EQ(j["steps"][1]["reactions"].size(), 2u);
  const std::string csv = slurp(out / "steps.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  const std::string progress = slurp(err);
  EXPECT_NE(progress.find("step 2"), std::string::npos) << progress;
  EXPECT_NE(progress.find("unbalanced"), std::string::npos) << progress;
}

TEST(DemCli, RefusesAnUnstableTimeStep) {
  Dir d;
  const fs::path c = write_arch(d), err = d.path / "err.txt";
  EXPECT_NE(run(c.string() + " --out " + (d.path / "out").string() + " --timestep-factor 2", err), 0);
  const std::string msg = slurp(err);
  EXPECT_NE(msg.find("stability limit"), std::string::npos) << msg;
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
}

// The exit-code policy (README, "Commands"): a run that ends without a located answer exits 1,
// after writing its results with the reason; bad options exit 2 (above).
TEST(DemCli, ARunWithoutAnAnswerExitsOne) {
  Dir d;
  const fs::path c = write_arch(d), out = d.path / "out", err = d.path / "err.txt";
  // A hold far too short to settle the arch under gravity: neither settled nor ran away.
  EXPECT_EQ(run(c.string() + " --out " + out.string() + " --hold-time 0.001", err), 1) << slurp(err);
  const auto j = nlohmann::json::parse(slurp(out / "results.json"));
  EXPECT_EQ(j["stopped"], "undecided");
  EXPECT_FALSE(j["message"].get<std::string>().empty());
}

// A flag is the case option of the same meaning (app/flags.hpp): a bad value gets the case
// loader's one-line refusal naming the option and the field, and a good one reaches the run as
// the case field would.
TEST(DemCli, AFlagIsTheCaseOptionItSets) {
  Dir d;
  const fs::path c = write_arch(d), err = d.path / "err.txt";
  EXPECT_EQ(run(c.string() + " --out " + (d.path / "bad").string() + " --damping 1.5", err), 2);
  const std::string msg = slurp(err);
  EXPECT_NE(msg.find("[dem.damping=1.5]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("field 'damping'"), std::string::npos) << msg;
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
  const fs::path out = d.path / "out";
  ASSERT_EQ(run(c.string() + " --out " + out.string() + " --max-steps 1 --open-gap 0.002 --quiet", err), 0) << slurp(err);
  const auto j = nlohmann::json::parse(slurp(out / "results.json"));
  EXPECT_EQ(j["settings"]["open_gap"].get<double>(), 0.002);
  EXPECT_EQ(j["settings"]["max_steps"].get<int>(), 1);
}

// Usage errors (an unknown option, options that exclude each other) are refusals like any bad
// input: exit code 2 with CLI11's message, not CLI11's own codes.
TEST(DemCli, AUsageErrorExitsTwo) {
  Dir d;
  const fs::path c = write_arch(d), err = d.path / "err.txt";
  EXPECT_EQ(run(c.string() + " --out " + (d.path / "a").string() + " --no-such-option", err), 2) << slurp(err);
  EXPECT_EQ(run(c.string() + " --out " + (d.path / "b").string() + " --convergence --stiffness-study", err), 2) << slurp(err);
  EXPECT_NE(slurp(err).find("excludes"), std::string::npos) << slurp(err);
}

}  // namespace
