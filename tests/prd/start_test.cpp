// A PRD run started from a configuration another run recorded (PrdStart, `masonry prd --from`).
// Expected values from outside the code under test: PRD's own uninterrupted run (a rigid run
// restarted from its own record must go on as it did), the rigid block's closed-form toppling
// tilt atan(b/h) (the DEM's elastic offsets taken back), and the DEM's own located collapse (its
// offsets kept: the two methods on the same deformed geometry).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "common.hpp"
#include "dem/dem.hpp"
#include "model/case.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

const std::string kBlock = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";
const std::string kArch = std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json";

PrdStart start_at(const StepRecord& s, StartOffsets o) { return {s.d, s.poses, o, "test record"}; }

TEST(PrdStart, RestartedFromItsOwnRecordARigidRunGoesOnAsItDid) {
  const Case c = load_case(kArch);
  const PrdSettings s = PrdSettings::from_case(c);
  const RunResult whole = prd_run(c, s);
  ASSERT_EQ(whole.status, RunStatus::collapse) << whole.message;
  ASSERT_GT(whole.steps.size(), 10u);
  const StepRecord& mid = whole.steps[whole.steps.size() / 2];
  for (StartOffsets o : {StartOffsets::keep, StartOffsets::take_back}) {
    PrdSettings from = s;
    from.start = start_at(mid, o);
    const RunResult r = prd_run(c, from);
    ASSERT_EQ(r.status, RunStatus::collapse) << start_offsets_name(o) << ": " << r.message;
    // The path counts on from the record's d on the same grid of steps, from the same poses.
    ASSERT_FALSE(r.steps.empty());
    EXPECT_DOUBLE_EQ(r.steps[0].d, mid.d);
    for (size_t b = 0; b < c.blocks.size(); ++b) {
      EXPECT_DOUBLE_EQ(r.steps[0].poses[b].x, mid.poses[b].x);
      EXPECT_DOUBLE_EQ(r.steps[0].poses[b].angle, mid.poses[b].angle);
    }
    EXPECT_NEAR(r.steps[1].d - mid.d, s.step, 1e-12);
    // PRD's own closed corners are within the contact tolerance, so nothing is taken back or
    // kept that could move the mechanism: the same capacity.
    EXPECT_NEAR(r.capacity, whole.capacity, 1e-9 + 1e-9 * whole.capacity) << start_offsets_name(o);
    EXPECT_EQ(r.settings["start"]["offsets"], start_offsets_name(o));
  }
}

// The tilting block on joints ten times softer than the case's: the DEM topples visibly before
// the rigid block's atan(b/h) (dem/README.md, "Joint stiffness"). From a DEM record well before
// that, PRD with the DEM's elastic offsets taken back is the rigid block again (the first step
// sets it flush on the slab) and topples at atan(b/h); from the DEM's last equilibrium with the
// offsets kept as the joint's geometry it topples where the DEM did: the difference is the
// geometry the soft joint deforms to. From the early record with the offsets kept, the block
// stands turned on its joint by the DEM's elastic rotation there, which grows with the tilt as
// the weight's moment does: it topples before the rigid block and after the DEM. (Taken back at
// the last equilibrium, the LP is unbounded at once: the block stands turned on its joint beyond
// atan(b/h), and whether the LP has a collapse mechanism is a matter of the configuration, not of
// the gaps the first step takes back.)
TEST(PrdStart, FromTheDemsSoftTiltedBlockPrdTopplesWhereTheDemDidOrAtTheRigidTiltAsCut) {
  const Case c = with_option(load_case(kBlock), "dem.stiffness_reduction", 10.0);
  const RunResult dem = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(dem.status, RunStatus::collapse) << dem.message;
  const double rigid = std::atan(0.2 / 0.4);
  const double width = dem.collapse_bracket.value().width;
  ASSERT_GT(rigid - dem.capacity, 20 * width) << "the soft block topples visibly early";
  // The DEM's last record is the failed state closing the run, not an equilibrium.
  ASSERT_FALSE(is_equilibrium(dem, dem.steps.back()));
  const StepRecord* last = last_equilibrium(dem, dem.steps.back().d);
  ASSERT_NE(last, nullptr);
  EXPECT_DOUBLE_EQ(last->d, dem.capacity);

  PrdSettings s = PrdSettings::from_case(c);
  s.adaptive = true;
  s.event_tolerance = width;
  const StepRecord* early = last_equilibrium(dem, 0.6 * rigid);
  ASSERT_NE(early, nullptr);
  ASSERT_GT(early->d, 0.5 * rigid);
  s.start = start_at(*early, StartOffsets::take_back);
  const RunResult cut = prd_run(c, s);
  ASSERT_EQ(cut.status, RunStatus::collapse) << cut.message;
  EXPECT_NEAR(cut.capacity, rigid, 2 * width);

  s.start = start_at(*early, StartOffsets::keep);
  const RunResult turned = prd_run(c, s);
  ASSERT_EQ(turned.status, RunStatus::collapse) << turned.message;
  const double theta = early->poses[1].angle - early->poses[0].angle;  // block against slab
  ASSERT_GT(theta, 10 * width);
  EXPECT_LT(turned.capacity, rigid - 5 * width);
  EXPECT_GT(turned.capacity, dem.capacity + 5 * width);

  s.start = start_at(*last, StartOffsets::keep);
  const RunResult kept = prd_run(c, s);
  ASSERT_EQ(kept.status, RunStatus::collapse) << kept.message;
  EXPECT_GE(kept.capacity, dem.capacity);
  EXPECT_LE(kept.capacity, dem.capacity + 2 * width) << "PRD on the DEM's deformed geometry: rigid " << rigid;
}

TEST(PrdStart, AStartThatDoesNotFitTheCaseIsRefusedNamingWhat) {
  const Case c = load_case(kBlock);
  PrdSettings s = PrdSettings::from_case(c);
  s.start = PrdStart{0.1, {Pose{}}, StartOffsets::keep, "one pose"};
  try {
    prd_run(c, s);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 poses for 2 blocks (one pose)"), std::string::npos) << e.what();
  }
  s.start = PrdStart{0.1, {Pose{0, -0.05, 0}, Pose{0, 0.2, NAN}}, StartOffsets::keep, "nan"};
  try {
    prd_run(c, s);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("block 'block': the start pose is not a number"), std::string::npos) << e.what();
  }
}

TEST(PrdStart, TheCommandStartsFromAResultsFileAndRefusesADBeforeItsRecords) {
  test::Scratch d("prd-start");
  const std::string exe = MASONRY_EXE, a = (d.path / "a").string(), b = (d.path / "b").string();
  ASSERT_EQ(test::run(exe + " prd " + kArch + " --out " + a + " 2>/dev/null"), 0);
  ASSERT_EQ(test::run(exe + " prd " + kArch + " --out " + b + " --from " + a + "/results.json --from-d 0.1 2>/dev/null"), 0);
  const nlohmann::json whole = nlohmann::json::parse(test::read(d.path / "a" / "results.json"));
  const nlohmann::json from = nlohmann::json::parse(test::read(d.path / "b" / "results.json"));
  EXPECT_NEAR(from["capacity"].get<double>(), whole["capacity"].get<double>(), 1e-9);
  EXPECT_LE(from["steps"][0]["d"].get<double>(), 0.1 + 1e-12);
  EXPECT_EQ(from["settings"]["start"]["offsets"], "keep");
  const std::string err = (d.path / "err").string();
  EXPECT_EQ(test::run(exe + " prd " + kArch + " --out " + b + " --from " + a + "/results.json --from-d -1 2>" + err), 2);
  const std::string msg = test::read(err);
  EXPECT_NE(msg.find(a + "/results.json: no equilibrium record at or before d = -1 m"), std::string::npos) << msg;
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
}

}  // namespace
}  // namespace masonry
