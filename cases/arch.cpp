#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cases/generators.hpp"

namespace masonry {

namespace {
Vec2 polar(double r, double phi) { return Vec2(r * std::cos(phi), r * std::sin(phi)); }

void make_ccw(std::vector<Vec2>& v) {
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
}

// A support block under a springing joint a-b (intrados and extrados corners): its top face is
// the joint, its base horizontal, `drop` below the lower corner.
Block springing_support(const std::string& id, const Vec2& a, const Vec2& b, double drop, double depth) {
  const double base = std::min(a.y(), b.y()) - drop;
  Block s;
  s.id = id;
  s.support = true;
  s.depth = depth;
  s.vertices = {a, b, Vec2(b.x(), base), Vec2(a.x(), base)};
  make_ccw(s.vertices);
  return s;
}

// The last block is the right support; with `spreading` it moves outward (+x) per unit of d.
void finish_arch(Case& c, bool spreading, double step, int max_steps) {
  c.motion.step = step;
  c.motion.max_steps = max_steps;
  if (spreading) {
    SupportMotion m;
    m.block = static_cast<int>(c.blocks.size()) - 1;
    m.translation = Vec2(1, 0);
    m.about = centroid(c.blocks.back().vertices);
    c.motion.supports.push_back(m);
  }
  validate_geometry(c);
}
}  // namespace

Case circular_arch(const CircularArch& p) {
  if (!std::isfinite(p.radius) || !(p.radius > 0) || !(p.thickness > 0) || !(p.thickness < 2 * p.radius))
    throw CaseError("circular arch: need a finite radius > 0 and 0 < thickness < 2 radius");
  if (!(p.embrace > 0) || !(p.embrace < 2 * M_PI)) throw CaseError("circular arch: embrace must lie in (0, 2 pi)");
  if (p.voussoirs < 1) throw CaseError("circular arch: need at least one voussoir");
  // A voussoir is the quadrilateral of its four corners: spanning half a turn or more, its
  // intrados and extrados chords cross or meet (one voussoir over a semicircle has no area).
  if (!(p.embrace / p.voussoirs < M_PI)) throw CaseError("circular arch: voussoirs: each must span less than half a turn (embrace / voussoirs)");
  Case c;
  c.source = "circular-arch";
  c.name = "circular arch";
  const double ri = p.radius - p.thickness / 2, re = p.radius + p.thickness / 2;
  const double phi0 = M_PI / 2 + p.embrace / 2, dphi = p.embrace / p.voussoirs;
  auto support = [&](const std::string& id, double phi) { return springing_support(id, polar(ri, phi), polar(re, phi), p.thickness, p.depth); };
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
  finish_arch(c, p.spreading, p.step, p.max_steps);
  return c;
}

Case pointed_arch(const PointedArch& p) {
  const double e = p.eccentricity, t = p.thickness;
  if (!(p.rcirc > 0) || !(t > 0)) throw CaseError("pointed arch: need rcirc > 0 and thickness > 0");
  if (!(e >= 0)) throw CaseError("pointed arch: the eccentricity must be >= 0");
  if (!(p.embrace > 0) || !(p.embrace < 2 * M_PI)) throw CaseError("pointed arch: embrace must lie in (0, 2 pi)");
  if (p.voussoirs < 1) throw CaseError("pointed arch: need at least one voussoir");
  const double rp = p.rcirc + e;  // Rpoint
  const double ri = rp - t / 2, re = rp + t / 2;
  // The intrados must reach the axis, or the two halves would not meet.
  if (!(ri > e)) throw CaseError("pointed arch: need Rcirc - t/2 > 0 (the intrados must reach the axis)");
  const double gamma = std::asin(e / rp);  // crown angle above pi/2 (left half)
  const double beta = p.embrace / 2 - gamma;
  if (!(beta > 0)) throw CaseError("pointed arch: the embrace is too small for this eccentricity (alpha/2 <= asin(e/Rpoint))");
  const int n = p.voussoirs;
  const double phi0 = M_PI / 2 + p.embrace / 2, dphi = 2 * beta / n;
  const Vec2 cl(e, 0), cr(-e, 0);
  // Corner of joint k (0 = left springing .. n = right springing) on the circle of radius r.
  // Left of the crown the angle is about the left centre; right of it, about the right centre,
  // shifted by 2 gamma so that one formula runs over both halves (and gamma = 0 gives exactly
  // the circular arch's angles).
  auto corner = [&](int k, double r) -> Vec2 {
    if (2 * k < n) return cl + polar(r, phi0 - k * dphi);
    if (2 * k > n) return cr + polar(r, (phi0 - k * dphi) - 2 * gamma);
    // Crown joint (n even): on the axis, vertical; with e = 0 the radial joint of the circle.
    if (e == 0) return polar(r, phi0 - k * dphi);
    return Vec2(0.0, std::sqrt(r * r - e * e));
  };
  Case c;
  c.source = "pointed-arch";
  c.name = "pointed arch";
  auto support = [&](const std::string& id, int k) { return springing_support(id, corner(k, ri), corner(k, re), t, p.depth); };
  c.blocks.push_back(support("left", 0));
  for (int k = 0; k < n; ++k) {
    Block v;
    v.id = "v";
    v.id += std::to_string(k);
    v.depth = p.depth;
    v.density = p.density;
    if (n % 2 == 1 && 2 * k + 1 == n && e > 0) {
      // Keystone across the axis: extrados apex as a vertex, intrados as a chord (convexity).
      v.vertices = {corner(k, ri), corner(k + 1, ri), corner(k + 1, re), Vec2(0.0, std::sqrt(re * re - e * e)), corner(k, re)};
    } else {
      v.vertices = {corner(k, ri), corner(k + 1, ri), corner(k + 1, re), corner(k, re)};
    }
    make_ccw(v.vertices);
    c.blocks.push_back(v);
  }
  c.blocks.push_back(support("right", n));
  finish_arch(c, p.spreading, p.step, p.max_steps);
  return c;
}

}  // namespace masonry
