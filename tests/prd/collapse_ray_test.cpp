// A collapse is reported only where GLPK's unbounded ray is a mechanism of the LP's rows
// (prd/lp.cpp, is_mechanism): no corner penetrates, no closed joint slides, the loads do work.
// The expected answers are rigid-body kinematics: a slender block (b = 0.5, h = 1 m) on a fixed
// slope of 0.6 rad, steeper than atan(b/h) = 0.4636, falls by rocking about its downhill corner;
// rocking about the uphill corner lifts its centroid, sliding down the slope slides its joint,
// and moving into the slope penetrates it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "model/io.hpp"
#include "prd/internal.hpp"

namespace masonry {
namespace {

using namespace prd_detail;

constexpr double kSlope = 0.6, kB = 0.5, kH = 1.0;

Vec2 turned(double x, double y) { return Vec2(std::cos(kSlope) * x - std::sin(kSlope) * y, std::sin(kSlope) * x + std::cos(kSlope) * y); }

std::string point(const Vec2& p) {
  char text[64];
  std::snprintf(text, sizeof text, "[%.17g, %.17g]", p.x(), p.y());
  return text;
}

// The ground and the block turned by kSlope about the origin: the block's downhill corner is the
// origin, its uphill one (kB, 0) turned.
Case block_on_slope() {
  const std::string ground = point(turned(-2, -0.5)) + ", " + point(turned(2, -0.5)) + ", " + point(turned(2, 0)) + ", " + point(turned(-2, 0));
  const std::string block = point(turned(0, 0)) + ", " + point(turned(kB, 0)) + ", " + point(turned(kB, kH)) + ", " + point(turned(0, kH));
  return parse_case(R"({"format": "masonry-case/1", "name": "block on a slope", "gravity": 9.81,
    "blocks": [{"id": "ground", "vertices": [)" + ground + R"(], "support": true},
               {"id": "block", "vertices": [)" + block + R"(], "density": 2000.0}],
    "motion": {"step": 0.001, "max_steps": 10, "supports": [{"block": "ground"}]}})",
                    "block-on-slope.json");
}

// The block's columns for a rigid velocity field: translation v of the centroid and rotation w,
// in the LP's units (the rotation times the block's radius).
std::vector<double> motion(const Model& m, const Vec2& v, double w) {
  std::vector<double> du(m.ncols + 1, 0.0);
  const int k = m.col[1];
  du[k] = v.x(), du[k + 1] = v.y(), du[k + 2] = w * m.radius[1];
  return du;
}
// Rotation w about point p: the centroid moves w perp(c - p).
std::vector<double> rocking(const Model& m, const Vec2& p, double w) { return motion(m, w * perp(m.cen[1] - p), w); }

TEST(PrdCollapseRay, OnlyARigidFallWithoutSlidingOrPenetrationIsAMechanism) {
  const Case c = block_on_slope();
  Model m = build_model(c, c.prd.contact_tolerance);
  update_lp(m, c.motion.step, c.motion.step, c.motion.step);
  const Vec2 downhill = turned(0, 0), uphill = turned(kB, 0);
  const Vec2 along = turned(1, 0) - turned(0, 0), normal = turned(0, 1) - turned(0, 0);
  EXPECT_TRUE(is_mechanism(m, rocking(m, downhill, 1.0)));    // toppling downhill
  EXPECT_TRUE(is_mechanism(m, rocking(m, downhill, 1e-6)));   // its size does not matter
  EXPECT_FALSE(is_mechanism(m, rocking(m, downhill, -1.0)));  // into the slope
  EXPECT_FALSE(is_mechanism(m, rocking(m, uphill, -1.0)));    // rocking uphill: the centroid rises
  EXPECT_FALSE(is_mechanism(m, motion(m, -along, 0)));        // sliding down the slope
  EXPECT_FALSE(is_mechanism(m, motion(m, -normal, 0)));       // into the slope
  EXPECT_FALSE(is_mechanism(m, motion(m, normal, 0)));        // lifted off: the loads do no work on it
  EXPECT_FALSE(is_mechanism(m, motion(m, Vec2(0, 0), 0)));
  EXPECT_FALSE(is_mechanism(m, {}));
}

// The tolerance is relative to the motion's size and tight: a toppling with a slip of 1e-5 of
// its size along the joint is refused, one of 1e-10 (round-off) accepted, at any size.
TEST(PrdCollapseRay, ASlipAboveRoundOffIsRefusedAtAnySize) {
  const Case c = block_on_slope();
  Model m = build_model(c, c.prd.contact_tolerance);
  update_lp(m, c.motion.step, c.motion.step, c.motion.step);
  const Vec2 along = turned(1, 0) - turned(0, 0);
  for (const double size : {1.0, 1e-6}) {
    const std::vector<double> topple = rocking(m, turned(0, 0), size);
    for (const double slip : {1e-5, 1e-10}) {
      std::vector<double> du = topple;
      const std::vector<double> sliding = motion(m, -slip * size * along, 0);
      for (size_t j = 0; j < du.size(); ++j) du[j] += sliding[j];
      EXPECT_EQ(is_mechanism(m, du), slip < 1e-7) << "size " << size << ", slip " << slip;
    }
  }
}

// GLPK's own ray, read from its final basis, passes the check and is the rocking about the
// downhill corner: its velocity there is zero and it turns the block downhill.
TEST(PrdCollapseRay, GlpksRayOfAnUnstableBlockIsItsToppling) {
  const Case c = block_on_slope();
  Model m = build_model(c, c.prd.contact_tolerance);
  update_lp(m, c.motion.step, c.motion.step, c.motion.step);
  ASSERT_EQ(solve(m), LpStatus::unbounded);
  const std::vector<double> du = unbounded_ray(m);
  ASSERT_EQ(du.size(), static_cast<size_t>(m.ncols) + 1);
  EXPECT_TRUE(is_mechanism(m, du));
  const int k = m.col[1];
  const double w = du[k + 2] / m.radius[1];
  EXPECT_GT(w, 0);  // counter-clockwise: over the downhill corner
  const Vec2 at_corner = Vec2(du[k], du[k + 1]) + w * perp(turned(0, 0) - m.cen[1]);
  EXPECT_LT(at_corner.norm(), 1e-9 * std::abs(w) * m.radius[1]);
}

}  // namespace
}  // namespace masonry
