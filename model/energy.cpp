#include "model/energy.hpp"

#include <cmath>

namespace masonry {

Vec2 placed(const Vec2& c0, const Pose& q, const Vec2& p) {
  const double co = std::cos(q.angle), si = std::sin(q.angle);
  const Vec2 r = p - c0;
  return Vec2(q.x + co * r.x() - si * r.y(), q.y + si * r.x() + co * r.y());
}

double potential_energy(const Case& c, const std::vector<Pose>& poses) {
  if (poses.size() != c.blocks.size()) return NAN;
  double e = 0;
  for (size_t b = 0; b < c.blocks.size(); ++b)
    if (!c.blocks[b].support) e += block_mass(c.blocks[b]) * c.gravity * (poses[b].y - centroid(c.blocks[b].vertices).y());
  for (const Load& l : c.loads) {
    const Block& B = c.blocks[l.block];
    e -= l.force.dot(placed(centroid(B.vertices), poses[l.block], l.point) - l.point);
  }
  return e;
}

}  // namespace masonry
