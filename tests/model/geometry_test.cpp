// The joint resultant's point (model/geometry.hpp, on_line_of_action), against its definition:
// the resultant placed there has the moment of the forces it sums, about any point, and the
// point is the one of its line of action nearest to the reference point.
#include "model/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace masonry {
namespace {

TEST(Geometry, TheResultantOnItsLineOfActionHasTheForcesOwnMoment) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    // Two corner forces of a joint along x: normal forces up, a shear along the joint at one
    // corner, the corners at different levels across the joint (up to a millimetre), and a
    // reference point where the normal forces' centre would be.
    const Vec2 p[2] = {Vec2(0.0, 1e-3 * u(rng)), Vec2(0.5, 1e-3 * u(rng))};
    const Vec2 f[2] = {Vec2(1e3 * u(rng), 1e3 * (1.5 + u(rng))), Vec2(0.0, 1e3 * (1.5 + u(rng)))};
    const Vec2 c(0.25 + 0.2 * u(rng), 0.0);
    const Vec2 R = f[0] + f[1];
    const double moment = cross(p[0] - c, f[0]) + cross(p[1] - c, f[1]);
    const Vec2 x = on_line_of_action(c, R, moment);
    // About any other point q: the resultant at x has the forces' moment.
    const Vec2 q(u(rng), u(rng));
    const double own = cross(p[0] - q, f[0]) + cross(p[1] - q, f[1]);
    EXPECT_NEAR(cross(x - q, R), own, 1e-9 * R.norm());
    // The nearest point of that line: x - c is perpendicular to R, |x - c| = |moment| / |R|.
    EXPECT_NEAR((x - c).dot(R), 0.0, 1e-12 * R.norm());
    EXPECT_NEAR((x - c).norm(), std::abs(moment) / R.norm(), 1e-12);
  }
  // A force through the reference point stays there.
  EXPECT_EQ(on_line_of_action(Vec2(1, 2), Vec2(3, 4), 0.0), Vec2(1, 2));
}

}  // namespace
}  // namespace masonry
