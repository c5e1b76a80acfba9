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

}  // namespace masonry
