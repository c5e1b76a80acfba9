// A block on a support that tilts slowly: it slides when the tilt reaches phi if tan(phi) < b/h,
// and topples at atan(b/h) otherwise; the capacity (the last tilt at which the block was found
// at rest) lies within one increment below the closed-form angle.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dem/dem.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

constexpr double kDeg = M_PI / 180;

TEST(DemTilt, SlidesAtTheFrictionAngle) {
  const double b = 0.4, h = 0.2, phi = 20.5;  // tan(phi) = 0.37 < b/h = 2
  const RunResult r = test::tilt_run(test::tilt_case(b, h, phi));
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double cap = r.capacity / kDeg;
  EXPECT_LE(cap, phi);
  EXPECT_GT(cap, phi - 1.0);
  // Sliding, not toppling: the block still lies flat on the slab (turned with it).
  const StepRecord& last = r.steps.back();
  const double tilt = last.d;
  EXPECT_NEAR(last.poses[1].angle, tilt, 0.02);
}

TEST(DemTilt, ToppleAtAtanBOverH) {
  const double b = 0.2, h = 0.4, phi = 45;  // tan(phi) = 1 > b/h = 0.5
  const RunResult r = test::tilt_run(test::tilt_case(b, h, phi));
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double topple = std::atan(b / h) / kDeg;  // 26.57 degrees
  const double cap = r.capacity / kDeg;
  EXPECT_LE(cap, topple);
  EXPECT_GT(cap, topple - 1.0);
  // Toppling: the block has turned well past the slab.
  const StepRecord& last = r.steps.back();
  EXPECT_GT(std::abs(last.poses[1].angle - last.d), 0.05);
}

// Kinetic damping in the holds (every free block stopped when the kinetic energy passes a peak)
// changes how a hold comes to rest, not where: the block still topples at atan(b/h).
TEST(DemTilt, KineticHoldsToppleAtAtanBOverHToo) {
  const double b = 0.2, h = 0.4, phi = 45;
  Case c = test::tilt_case(b, h, phi);
  c.dem.hold_damping = HoldDamping::kinetic;
  const RunResult r = test::tilt_run(c);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_EQ(r.settings["hold_damping"], "kinetic");
  const double topple = std::atan(b / h) / kDeg;
  EXPECT_LE(r.capacity / kDeg, topple);
  EXPECT_GT(r.capacity / kDeg, topple - 1.0);
}

// The results a run hands out while it goes (and a command writes as it goes) say "running":
// a run stopped from outside must not look finished. Only the end says how it ended.
TEST(DemTilt, ResultsSayRunningUntilTheRunEnds) {
  Case c = test::tilt_case(0.4, 0.2, 35);  // 2 degrees: far from sliding (35) and toppling (63)
  c.motion.max_steps = 2;
  std::vector<RunStatus> seen;
  const RunResult r = test::tilt_run(c, [&](const RunResult& partial) { seen.push_back(partial.status); });
  EXPECT_EQ(r.status, RunStatus::max_steps) << r.message;
  EXPECT_EQ(r.stable_steps, 2);
  ASSERT_EQ(seen.size(), 3u);  // the initial configuration and two increments
  for (RunStatus st : seen) EXPECT_EQ(st, RunStatus::running);
}

}  // namespace
