// A stack of blocks at rest: reactions equal the weight, each joint's overlap is the weight above
// it over kn * area, the unbalanced force ratio falls below tolerance, and a long hold does not
// drift.
#include <gtest/gtest.h>

#include "dem/dem.hpp"
#include "prd/prd.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

Case stack_case() {
  Case c = test::slab_case();
  for (int k = 0; k < 3; ++k) {
    std::string id = "b";
    id += std::to_string(k);  // (not "b" + ...: GCC 12 warns falsely, PR105651)
    c.blocks.push_back(test::rect(id, -0.2, 0.2 * k, 0.2, 0.2 * (k + 1), 2000, false));
  }
  c.dem.friction_angle = 35;
  c.dem.hold_time = 2.0;
  return c;
}

TEST(DemStack, ReactionsEqualWeightAndOverlapsMatchSprings) {
  const Case c = stack_case();
  DemSettings s = DemSettings::from_case(c);
  const RunResult r = dem_run(c, s);
  ASSERT_EQ(r.steps.size(), 1u);
  const StepRecord& st = r.steps[0];
  ASSERT_TRUE(st.settled.value_or(false)) << "unbalanced " << (st.hold ? st.hold->unbalanced_ratio : -1.0);
  ASSERT_TRUE(st.hold);
  EXPECT_LT(st.hold->unbalanced_ratio, s.equilibrium_tolerance);
  EXPECT_EQ(r.status, RunStatus::max_steps);
  EXPECT_EQ(r.capacity, 0.0);

  const double W = 2000 * 0.4 * 0.2 * 1.0 * c.gravity;  // one block
  ASSERT_EQ(st.reactions.size(), 1u);
  EXPECT_NEAR(st.reactions[0].force.y(), 3 * W, 1e-3 * W);
  EXPECT_NEAR(st.reactions[0].force.x(), 0, 1e-3 * W);
  EXPECT_NEAR(r.total_weight, 3 * W, 1e-9 * W);

  // Joint k (from the ground up) carries the (3 - k) blocks above it: overlap (3 - k) W / (kn A).
  const double kn = *c.dem.kn, A = 0.4 * 1.0;
  double expected_drop = 0;
  for (int k = 0; k < 3; ++k) {
    expected_drop += (3 - k) * W / (kn * A);
    const Pose& p = st.poses[1 + k];
    EXPECT_NEAR(0.2 * k + 0.1 - p.y, expected_drop, 2e-3 * expected_drop) << "block " << k;
    EXPECT_NEAR(p.x, 0, 1e-9);
    EXPECT_NEAR(p.angle, 0, 1e-9);
  }
  // Joint resultants: normal = weight above, at the middle of the joint, no shear, no opening.
  ASSERT_EQ(r.joints.size(), 3u);
  ASSERT_EQ(st.forces.size(), 3u);
  for (const JointForce& f : st.forces) {
    const int above = 3 - f.joint;  // detect_interfaces orders by block pair: (ground,b0), (b0,b1), (b1,b2)
    EXPECT_NEAR(f.normal, above * W, 1e-3 * W);
    EXPECT_NEAR(f.shear, 0, 1e-6 * W);
    EXPECT_NEAR(f.point.x(), 0, 1e-6);
  }
  EXPECT_TRUE(st.open_corners.empty());
}

TEST(DemStack, NoDriftOverALongHold) {
  const Case c = stack_case();
  const DemSettings s = DemSettings::from_case(c);
  DemModel m(c, s);
  long long n = 0;
  while (!(m.unbalanced_ratio() < s.equilibrium_tolerance && m.max_speed() < s.velocity_tolerance)) {
    m.cycle();
    ASSERT_LT(++n, 1000000);
  }
  std::vector<DemBlockState> before;
  for (int b = 0; b < 4; ++b) before.push_back(m.block(b));
  const long long hold = static_cast<long long>(5.0 / m.dt());  // 5 s of model time
  m.cycle(hold);
  EXPECT_LT(m.unbalanced_ratio(), s.equilibrium_tolerance);
  for (int b = 1; b < 4; ++b) {
    EXPECT_NEAR((m.block(b).position - before[b].position).norm(), 0, 1e-8) << "block " << b;
    EXPECT_NEAR(m.block(b).angle - before[b].angle, 0, 1e-8) << "block " << b;
  }
}

// One W for both methods (model::total_weight): with an upward and a sideways point load, PRD and
// the DEM report the weight of the blocks minus the upward load (the vertical part of the dead-load
// resultant, what the supports carry vertically), and the settled DEM's reactions carry exactly it.
// PRD once left the upward load out (3 m g) and the DEM counted it, so thrusts over W differed.
TEST(DemStack, BothMethodsReportTheSameWeightWithUpwardAndSidewaysLoads) {
  Case c = stack_case();
  const double mg = 2000 * 0.4 * 0.2 * 1.0 * c.gravity;  // one block
  Load up;
  up.block = 3;  // the top block
  up.force = Vec2(0, 300.0);
  up.point = Vec2(0, 0.5);
  Load side;
  side.block = 2;
  side.force = Vec2(50.0, 0);
  side.point = Vec2(0, 0.3);
  c.loads = {up, side};
  const double W = 3 * mg - 300.0;
  EXPECT_NEAR(total_weight(c), W, 1e-12 * W);
  const RunResult d = dem_run(c, DemSettings::from_case(c));
  const RunResult p = prd_run(c, PrdSettings::from_case(c));
  EXPECT_NEAR(d.total_weight, W, 1e-9 * W);
  EXPECT_NEAR(p.total_weight, W, 1e-9 * W);
  ASSERT_FALSE(d.steps.empty());
  ASSERT_TRUE(d.steps[0].settled.value_or(false));
  ASSERT_EQ(d.steps[0].reactions.size(), 1u);
  EXPECT_NEAR(d.steps[0].reactions[0].force.y(), W, 1e-3 * W);
  EXPECT_NEAR(d.steps[0].reactions[0].force.x(), -50.0, 1e-3 * W);
}

// A post seated in a support's notch meets it at three joints (the right wall, the floor and the
// left wall, in the joints' order): each contact point's force is recorded at the joint whose face
// it lies on, so the three joints' forces hold the post's weight up (equilibrium, 1e-3 of W) at
// rest and with the support tilted, the floor carrying the weight's component across it. Until
// 2026-11-28 every point went to the pair's first joint (the right wall) and no forces were
// recorded at all.
TEST(DemStack, APostInANotchHasItsForcesOnEachFace) {
  const Case c = parse_case(R"({"format": "masonry-case/1", "name": "notch", "gravity": 9.81, "blocks": [
    {"id": "base", "support": true, "vertices": [[-1, -0.5], [1, -0.5], [1, 0.5], [0.25, 0.5], [0.25, 0], [-0.25, 0], [-0.25, 0.5], [-1, 0.5]]},
    {"id": "post", "density": 2000, "vertices": [[-0.25, 0], [0.25, 0], [0.25, 1], [-0.25, 1]]}],
    "motion": {"step": 0.02, "max_steps": 3, "supports": [{"block": "base", "rotation": 1, "about": [0, -0.5]}]}})",
                            "notch.json");
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.joints.size(), 3u);
  ASSERT_EQ(r.steps.size(), 4u) << r.message;
  const double W = 0.5 * 1.0 * 1.0 * 2000 * 9.81;
  for (const StepRecord& s : r.steps) {
    const double t = s.poses[0].angle;  // the support's tilt
    Vec2 sum(0, 0);
    double floor = 0;
    for (const JointForce& f : s.forces) {
      const JointInfo& j = r.joints[size_t(f.joint)];
      const Vec2 along = (j.b - j.a).normalized();
      const Vec2 tangent(std::cos(t) * along.x() - std::sin(t) * along.y(), std::sin(t) * along.x() + std::cos(t) * along.y());
      sum += f.normal * f.n + f.shear * tangent;  // on the post (out of the base)
      if (std::abs(j.a.y()) < 1e-9 && std::abs(j.b.y()) < 1e-9) floor = f.normal;
    }
    EXPECT_NEAR(sum.x(), 0.0, 1e-3 * W) << "d = " << s.d;
    EXPECT_NEAR(sum.y(), W, 1e-3 * W) << "d = " << s.d;
    EXPECT_GT(floor, 0.9 * W * std::cos(t)) << "d = " << s.d;
  }
}

}  // namespace
