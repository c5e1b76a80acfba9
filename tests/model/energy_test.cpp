// The shared quantities of a configuration against closed forms: a block tipped about its corner,
// a point load carried with it, and the scene's bounds.
#include "model/energy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "model/case.hpp"

namespace masonry {
namespace {

// A 1 m x 2 m block (density 2000 kg/m^3, depth 0.5 m, so 19,620 N at g = 9.81) on a ground.
Case tipping_block() {
  return parse_case(R"({"format": "masonry-case/1", "name": "b", "gravity": 9.81, "blocks": [
      {"id": "ground", "vertices": [[-2, -0.5], [2, -0.5], [2, 0], [-2, 0]], "support": true},
      {"id": "b", "vertices": [[0, 0], [1, 0], [1, 2], [0, 2]], "density": 2000, "depth": 0.5}],
      "loads": [{"block": "b", "force": [300, -500], "point": [0, 2]}]})",
                    "b.json");
}

// The pose of block b turned by `angle` about its corner (1, 0).
Pose turned_about_corner(const Case& c, double angle) {
  const Vec2 c0 = centroid(c.blocks[1].vertices), o(1, 0), r = c0 - o;
  const double co = std::cos(angle), si = std::sin(angle);
  return {o.x() + co * r.x() - si * r.y(), o.y() + si * r.x() + co * r.y(), angle};
}

TEST(PotentialEnergy, BlockTippedAboutItsCornerAgainstTheClosedForm) {
  const Case c = tipping_block();
  const double W = 2000 * 2 * 0.5 * 9.81, a = -0.1;  // clockwise: tips to the right
  const std::vector<Pose> poses = {Pose{}, turned_about_corner(c, a)};
  // The centroid (0.5, 1) about (1, 0): rises by -0.5 sin(a) + cos(a) - 1.
  const double rise = -0.5 * std::sin(a) + std::cos(a) - 1;
  // The load's point (0, 2): r = (-1, 2) about the corner, moved by (R - I) r.
  const Vec2 u(-std::cos(a) - 2 * std::sin(a) + 1, -std::sin(a) + 2 * std::cos(a) - 2);
  const double expected = W * rise - Vec2(300, -500).dot(u);
  EXPECT_NEAR(potential_energy(c, poses), expected, 1e-9 * W);
  // The load's point, placed, is the corner-turned point.
  EXPECT_NEAR((placed(centroid(c.blocks[1].vertices), poses[1], Vec2(0, 2)) - (Vec2(0, 2) + u)).norm(), 0.0, 1e-12);
  // At the start, nothing has moved: zero; a support's motion carries no weight of the structure.
  EXPECT_EQ(potential_energy(c, {Pose{}, turned_about_corner(c, 0)}), 0.0);
  EXPECT_NEAR(potential_energy(c, {Pose{0, -1, 0}, turned_about_corner(c, 0)}), 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(potential_energy(c, {Pose{}})));  // a pose per block, or no number
}

TEST(SceneBounds, EveryVertexInsideAndTheSizeTheLargerSide) {
  const Case c = tipping_block();
  const Bounds b = scene_bounds(c);
  EXPECT_EQ(b.lo, Vec2(-2, -0.5));
  EXPECT_EQ(b.hi, Vec2(2, 2));
  EXPECT_DOUBLE_EQ(scene_size(c), 4.0);
  EXPECT_TRUE(Bounds{}.empty());
  EXPECT_FALSE(b.empty());
}

}  // namespace
}  // namespace masonry
