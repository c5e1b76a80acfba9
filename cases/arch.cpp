#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "generators.hpp"

namespace masonry {

namespace {
Vec2 polar(double r, double phi) { return Vec2(r * std::cos(phi), r * std::sin(phi)); }

void make_ccw(std::vector<Vec2>& v) {
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
}
}  // namespace

Case circular_arch(const CircularArch& p) {
  if (!(p.radius > 0) || !(p.thickness > 0) || !(p.thickness < 2 * p.radius))
    throw CaseError("circular arch: need radius > 0 and 0 < thickness < 2 radius");
  if (!(p.embrace > 0) || !(p.embrace < 2 * M_PI)) throw CaseError("circular arch: embrace must lie in (0, 2 pi)");
  if (p.voussoirs < 1) throw CaseError("circular arch: need at least one voussoir");
  Case c;
  c.source = "circular-arch";
  c.name = "circular arch";
  const double ri = p.radius - p.thickness / 2, re = p.radius + p.thickness / 2;
  const double phi0 = M_PI / 2 + p.embrace / 2, dphi = p.embrace / p.voussoirs;
  auto support = [&](const std::string& id, double phi) {
    const Vec2 a = polar(ri, phi), b = polar(re, phi);
    const double base = std::min(a.y(), b.y()) - p.thickness;
    Block s;
    s.id = id;
    s.support = true;
    s.depth = p.depth;
    s.vertices = {a, b, Vec2(b.x(), base), Vec2(a.x(), base)};
    make_ccw(s.vertices);
    return s;
  };
  c.blocks.push_back(support("left", phi0));
  for (int k = 0; k < p.voussoirs; ++k) {
    // Angles from the joints' own formula, so that neighbours share their joint exactly.
    const double a0 = phi0 - k * dphi, a1 = phi0 - (k + 1) * dphi;
    Block v;
    v.id = "v";
    v.id += std::to_string(k);  // (not "v" + ...: GCC 12 warns falsely, PR105651)
    v.depth = p.depth;
    v.density = p.density;
    v.vertices = {polar(ri, a0), polar(ri, a1), polar(re, a1), polar(re, a0)};
    make_ccw(v.vertices);
    c.blocks.push_back(v);
  }
  c.blocks.push_back(support("right", phi0 - p.voussoirs * dphi));
  c.motion.step = p.step;
  c.motion.max_steps = p.max_steps;
  if (p.spreading) {
    SupportMotion m;
    m.block = static_cast<int>(c.blocks.size()) - 1;
    m.translation = Vec2(1, 0);
    m.about = centroid(c.blocks.back().vertices);
    c.motion.supports.push_back(m);
  }
  validate_geometry(c);
  return c;
}

}  // namespace masonry
