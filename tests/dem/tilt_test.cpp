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

// Four 0.25 m cubes stacked 1 m high on a slab that turns 5 mrad per increment (the joints at
// the default E / h, stiff against these weights) topple as one at atan(b/H) = atan(0.25): the
// part above any joint is as wide and lower, so it needs more tilt. Friction 35 degrees > 14:
// no sliding. What this checks is the supports' acceleration: at the servo's relative rates
// alone (up to 1.5 g at the top of the stack with these stiff joints; with joints ten times
// softer the time step is longer and nothing of this shows) the stack rocked off one corner in
// its first move, its top block walked 7.7 mm downhill by 0.24 rad, and it toppled 2% early.
// With the supports' acceleration capped at 0.01 g the top block still walks about 1 mm
// (partial slip at the joints' unloaded uphill corners under the servo's small chatter, gone at
// 0.003 g), and the stack topples 0.17% early: within a quarter of the old error.
TEST(DemLoading, AStackOnATurningBaseToppleAsOne) {
  Case c = test::slab_case();
  c.dem = DemOptions{};  // the default joints, E / h
  // Names spelled out: building them with std::string's operator+ trips GCC 12's -Wrestrict
  // false positive (GCC bug 105329).
  const char* const names[] = {"s0", "s1", "s2", "s3"};
  for (int k = 0; k < 4; ++k) c.blocks.push_back(test::rect(names[k], -0.125, 0.25 * k, 0.125, 0.25 * (k + 1), 2000, false));
  SupportMotion m;
  m.block = 0;
  m.rotation = 1.0;
  m.about = Vec2(0, -0.05);
  c.motion.supports.push_back(m);
  c.motion.step = 0.005;
  c.motion.max_steps = 60;
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  // Above: the bracket (1% of the step) and the equilibrium tolerance's reach of the tipping
  // point (1e-4 r / (half the diagonal) for the whole stack, 3e-5 rad).
  EXPECT_LE(r.capacity, std::atan(0.25) + 1e-4);
  EXPECT_GE(r.capacity, std::atan(0.25) * (1 - 0.005));
  // Every block turned with the slab until then: none walked along the joints by 2 mm.
  const StepRecord& last = r.steps[r.steps.size() - 2];
  for (int k = 0; k < 4; ++k) {
    const double rad = 0.175 + 0.25 * k, th = last.d;
    const Pose& p = last.poses[1 + k];
    const double along = (p.x + rad * std::sin(th)) * std::cos(th) + (p.y + 0.05 - rad * std::cos(th)) * std::sin(th);
    EXPECT_LT(std::abs(along), 0.002) << "block " << k;
  }
}

}  // namespace
