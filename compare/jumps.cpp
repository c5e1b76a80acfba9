// Jumps: where a run's structure snapped through between two of its records (compare/README.md,
// "Jumps"). A structure on a mechanism moves a few times as far as its supports carry it; one
// that snaps to another equilibrium (a hinge passing to another joint) moves a finite distance
// for almost no support travel. PRD's step then moves the blocks until an open corner closes, the
// DEM's landing stage holds on until it comes to rest, and a method that calls such a motion a
// collapse ends there: a capacity that parts from the other run's at one of its jumps is a snap
// read two ways, not two mechanisms.
#include <algorithm>
#include <cmath>

#include "compare/compare.hpp"

namespace masonry {

std::vector<Jump> jumps(const Case& c, const RunResult& r) {
  std::vector<Jump> out;
  const std::vector<const StepRecord*> recs = stable_records(r);
  const double travel = path_travel_per_d(c);  // m of support point travel per unit of d
  const double floor = kJumpFloor * scene_size(c);
  for (size_t k = 1; k < recs.size(); ++k) {
    const StepRecord &p = *recs[k - 1], &q = *recs[k];
    if (p.poses.size() != q.poses.size()) continue;
    Jump j{p.d, q.d, 0.0, ""};
    for (size_t b = 0; b < q.poses.size() && b < c.blocks.size(); ++b) {
      if (c.blocks[b].support) continue;  // carried by the imposed motion, never a snap
      const double m = std::hypot(q.poses[b].x - p.poses[b].x, q.poses[b].y - p.poses[b].y);
      if (m > j.drift) j.drift = m, j.block = c.blocks[b].id;
    }
    if (j.drift > floor && j.drift > kJumpRatio * travel * std::abs(q.d - p.d)) out.push_back(std::move(j));
  }
  return out;
}

}  // namespace masonry
