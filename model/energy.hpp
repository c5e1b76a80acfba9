// Quantities both solvers report from a configuration, defined once so PRD and DEM cannot drift
// apart (as their total weights once did): where a block's material point is at a pose, and the
// potential energy of the dead loads.
#pragma once

#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// Where the material point p (initial coordinates) of a block whose initial centroid is c0 is,
// at pose q (q's x, y: the centroid's position; angle: the rotation since the start).
Vec2 placed(const Vec2& c0, const Pose& q, const Vec2& p);

// Potential energy of the dead loads at `poses` (one per block) relative to the start, J: each
// free block's weight times the rise of its centroid, less the work of the point loads over
// their points' displacement. Support blocks carry no weight of the structure's (their motion is
// imposed). Negative: energy released by the motion.
double potential_energy(const Case& c, const std::vector<Pose>& poses);

}  // namespace masonry
