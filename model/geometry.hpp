// The plane's small vector helpers, one definition each for every library (validation, PRD,
// the DEM, the case generators' tests).
#pragma once

#include <Eigen/Core>

namespace masonry {

using Vec2 = Eigen::Vector2d;

// The z component of a x b: positive where b turns counter-clockwise from a.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
// v turned a quarter counter-clockwise: the velocity omega x r of a unit rotation rate.
inline Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }
// Where a joint's resultant R is reported (both solvers): the point of its line of action nearest
// to c, given its moment about c (the forces' own, summed where each acts). On the line of
// action the resultant's moment about any block is exact; the nearest point stays within
// |moment| / |R| of c. R must not be zero. (x - c) x R = moment with x - c along perp(R), and
// perp(R) x R = -|R|^2.
inline Vec2 on_line_of_action(const Vec2& c, const Vec2& R, double moment) { return c - (moment / R.squaredNorm()) * perp(R); }

}  // namespace masonry
