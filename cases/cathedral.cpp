// The Gothic cathedral cross-section of the paper's Section 4 (an approximation of Amiens).
//
// Geometry (right half; the left half is its mirror image in x = 0). Ground y = 0, axis x = 0.
// Plan positions follow from the widths, outwards from the axis:
//   x1 = nave_span / 2              inner face of the nave pier (nave arch intrados springs here)
//   x2 = x1 + pier_width            outer face of the pier shaft (flyer heads bear on it)
//   x3 = x2 + aisle_thickness       outer face of the pier below the aisle springing
//   x4 = x3 + aisle_span            inner face of the buttress below the aisle springing
//   x5 = x4 + aisle_thickness       inner face of the buttress above it (lower flyer's foot)
//   x6 = x5 + buttress_width        outer face of the buttress
// Vertical elements are cut by horizontal joints into courses of about `course`:
//   pier:     [x1, x3] from 0 to the aisle springing (the pier with the aisle-vault respond: the
//             aisle arch springs from its ledge [x2, x3]); then the shaft [x1, x2] up to the
//             nave springing, with courses that end exactly at each flyer head, so a head joint
//             is one whole course face;
//   buttress: [x4, x6] up to the aisle springing (ledge [x4, x5] for the aisle arch); then three
//             stages stepping back at each flyer foot: [x5, x6] up to the lower flyer's seat,
//             [Pe1.x, x6] up to the upper seat, [Pe2.x, x6] up to buttress_height. The top course
//             of a stage is the seat: a convex pentagon whose sloping top edge is the flyer's foot
//             joint Pi-Pe (Pi on the stage's inner face, Pe on its top), the step back of the
//             stage above starts at Pe. Gothic buttresses do step back upwards.
// Arches (nave: between the piers; aisles: between pier and buttress) are two-centred pointed
// arches with horizontal springing joints (vertical tangents at springing, the usual Gothic
// profile: an embrace of 180 degrees in Romano & Ochsendorf's terms), radial joints about each
// half's centre, and a vertical crown joint on the arch's axis (an even number of voussoirs).
// The clear span S and the intrados rise f (crown height minus springing) fix the eccentricity:
// (S/2 + e)^2 - e^2 = f^2, so e = (f^2 - S^2/4) / S; f >= S/2 is required (pointed or round).
// Flying buttresses are quarter-arch segments: each is an arc of a circle whose top is the head,
// so the head joint (radial at 90 degrees) is vertical and lies on the pier's face, and which
// passes through the foot intrados point on the buttress face: with s the horizontal distance
// head-foot and h the drop, the intrados radius is (s^2 + h^2) / (2 h); joints are radial.
// All shared joints are computed once and used by both blocks, so interfaces are exact.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cases/generators.hpp"

namespace masonry {

namespace {

Vec2 polar(double r, double phi) { return Vec2(r * std::cos(phi), r * std::sin(phi)); }

void make_ccw(std::vector<Vec2>& v) {
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
}

std::vector<Vec2> rect(double xl, double xr, double y0, double y1) { return {Vec2(xl, y0), Vec2(xr, y0), Vec2(xr, y1), Vec2(xl, y1)}; }

// Course levels from y0 to y1 (both included, exactly), about `course` apart.
std::vector<double> levels(double y0, double y1, double course) {
  const int n = std::max(1, static_cast<int>(std::lround((y1 - y0) / course)));
  std::vector<double> y(n + 1);
  for (int k = 0; k < n; ++k) y[k] = y0 + (y1 - y0) * k / n;
  y[n] = y1;
  return y;
}

std::string id2(const std::string& prefix, int k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", k);
  return prefix + buf;
}

struct Half {
  std::vector<Block> blocks;
  void add(const std::string& id, std::vector<Vec2> v, double depth, double density) {
    make_ccw(v);
    Block b;
    b.id = id;
    b.vertices = std::move(v);
    b.depth = depth;
    b.density = density;
    blocks.push_back(std::move(b));
  }
};

// A flying buttress from its head (xh, yh: intrados, on a vertical face, arc top) down to its
// foot intrados (xf, yf). Returns the foot's extrados corner Pe (the seat's upper corner).
Vec2 flyer(Half& out, const std::string& prefix, double xh, double yh, double yh_top, double xf, double yf, double t, int n, double depth,
           double density) {
  const double s = xf - xh, h = yh - yf;
  if (!(h > 0) || !(s > h)) throw CaseError("cathedral: a flyer must drop (head above foot) by less than its span");
  const double ri = (s * s + h * h) / (2 * h), re = ri + t;
  const Vec2 c(xh, yh - ri);
  const double psi = std::atan2(yf - c.y(), s);  // foot angle about the centre
  auto corner = [&](int k, bool outer) -> Vec2 {
    if (k == 0) return outer ? Vec2(xh, yh_top) : Vec2(xh, yh);  // on the pier face, exactly
    if (k == n && !outer) return Vec2(xf, yf);                   // on the buttress face, exactly
    const double th = M_PI / 2 - k * (M_PI / 2 - psi) / n;
    return c + polar(outer ? re : ri, th);
  };
  for (int k = 0; k < n; ++k) out.add(id2(prefix, k), {corner(k, false), corner(k + 1, false), corner(k + 1, true), corner(k, true)}, depth, density);
  return corner(n, true);
}

// Right half of a two-centred pointed arch with horizontal springing joints: springing intrados
// at (xa, y0), extrados at (xb, y0) (xb = xa + t), axis at x = xm < xa, intrados rise f.
// Voussoirs from the springing (k = 0) to the crown joint on the axis.
std::vector<std::vector<Vec2>> pointed_half(double xm, double xa, double xb, double y0, double f, int m) {
  const double t = xb - xa, a = xa - xm;  // half clear span
  const double e = (f * f - a * a) / (2 * a);
  if (e < 0) throw CaseError("cathedral: an arch's rise must be at least half its clear span");
  const double ri = a + e, re = ri + t, rp = ri + t / 2;
  const double gamma = std::asin(e / rp);
  const Vec2 c(xm - e, y0);
  auto corner = [&](int k, bool outer) -> Vec2 {
    const double r = outer ? re : ri;
    if (k == 0) return Vec2(outer ? xb : xa, y0);                // springing
    if (k == m) return Vec2(xm, y0 + std::sqrt(r * r - e * e));  // crown, on the axis
    return c + polar(r, k * (M_PI / 2 - gamma) / m);
  };
  std::vector<std::vector<Vec2>> v;
  for (int k = 0; k < m; ++k) v.push_back({corner(k, false), corner(k + 1, false), corner(k + 1, true), corner(k, true)});
  return v;
}

std::vector<Vec2> mirror(const std::vector<Vec2>& v, double xm) {
  std::vector<Vec2> w;
  for (const Vec2& p : v) {
    const double x = 2 * xm - p.x();
    w.push_back(Vec2(x == 0 ? 0.0 : x, p.y()));  // no "-0.0" in the files
  }
  return w;
}

}  // namespace

Case gothic_cathedral(const GothicCathedral& p) {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw CaseError(std::string("cathedral: ") + what);
  };
  need(p.nave_span > 0 && p.pier_width > 0 && p.aisle_span > 0 && p.buttress_width > 0, "widths must be positive");
  need(p.nave_thickness > 0 && p.aisle_thickness > 0 && p.flyer_thickness > 0, "thicknesses must be positive");
  need(p.nave_thickness < p.pier_width, "the nave arch must be thinner than the pier it sits on");
  need(p.course > 0 && p.foundation_height > 0, "course and foundation height must be positive");
  need(p.bay > 0 && p.pier_depth > 0 && p.buttress_depth > 0 && p.flyer_depth > 0 && p.density > 0, "depths and density must be positive");
  need(p.nave_voussoirs >= 2 && p.nave_voussoirs % 2 == 0, "nave_voussoirs must be even and >= 2");
  need(p.aisle_voussoirs >= 2 && p.aisle_voussoirs % 2 == 0, "aisle_voussoirs must be even and >= 2");
  need(p.flyer_voussoirs >= 1, "flyer_voussoirs must be >= 1");
  need(p.moving_support >= 1 && p.moving_support <= 4, "moving_support must be 1..4");
  need(p.step > 0 && p.max_steps >= 0, "step must be positive");
  const double ya = p.aisle_springing, yn = p.nave_springing, ta = p.aisle_thickness, tf = p.flyer_thickness;
  const double lh = p.lower_flyer_head, uh = p.upper_flyer_at_springing ? yn - tf : p.upper_flyer_head;
  need(0 < ya && ya < p.aisle_height && ya < lh, "need 0 < aisle springing < aisle height and < lower flyer head");
  need(lh + tf < uh, "the upper flyer's head must lie above the lower one's");
  need(uh + tf <= yn + 1e-9, "the upper flyer's head must lie below the nave springing");
  need(yn < p.nave_height, "the nave springing must lie below the nave height");

  const double x1 = p.nave_span / 2, x2 = x1 + p.pier_width, x3 = x2 + ta, x4 = x3 + p.aisle_span, x5 = x4 + ta, x6 = x5 + p.buttress_width;
  const double rho = p.density;
  // Flyer head levels, shared by the pier courses and the flyers' head joints.
  const double lh_top = lh + tf;
  const double uh_top = std::abs(uh + tf - yn) < 1e-9 ? yn : uh + tf;

  Half right;
  // Nave pier: the wide lower part, then the shaft in segments that end at the flyer heads.
  {
    int k = 0;
    const auto lo = levels(0, ya, p.course);
    for (size_t i = 0; i + 1 < lo.size(); ++i) right.add(id2("pier-", k++), rect(x1, x3, lo[i], lo[i + 1]), p.pier_depth, rho);
    const double seg[] = {ya, lh, lh_top, uh, uh_top, yn};
    for (int s = 0; s + 1 < 6; ++s) {
      if (seg[s + 1] - seg[s] <= 1e-9) continue;
      const auto y = levels(seg[s], seg[s + 1], p.course);
      for (size_t i = 0; i + 1 < y.size(); ++i) right.add(id2("pier-", k++), rect(x1, x2, y[i], y[i + 1]), p.pier_depth, rho);
    }
  }
  // Aisle arch: right half from the buttress ledge, left half (mirror about its axis) from the
  // pier ledge; listed from the pier to the buttress.
  {
    const double xm = (x3 + x4) / 2;
    const auto half = pointed_half(xm, x4, x5, ya, p.aisle_height - ya, p.aisle_voussoirs / 2);
    const int m = static_cast<int>(half.size());
    int k = 0;
    for (int j = 0; j < m; ++j) {
      std::vector<Vec2> v = mirror(half[j], xm);
      if (j == 0) v = {Vec2(x3, ya), v[1], v[2], Vec2(x2, ya)};  // springing on the pier ledge, exactly
      right.add(id2("aisle-", k++), v, p.bay, rho);
    }
    for (int j = m - 1; j >= 0; --j) right.add(id2("aisle-", k++), half[j], p.bay, rho);
  }
  // Buttress: lower part, then three stages stepping back at the two flyer seats.
  Vec2 pe1, pe2;
  {
    int k = 0;
    const auto lo = levels(0, ya, p.course);
    for (size_t i = 0; i + 1 < lo.size(); ++i) right.add(id2("buttress-", k++), rect(x4, x6, lo[i], lo[i + 1]), p.buttress_depth, rho);
    Half flyers;
    pe1 = flyer(flyers, "flyer-low-", x2, lh, lh_top, x5, p.lower_flyer_foot, tf, p.flyer_voussoirs, p.flyer_depth, rho);
    need(p.lower_flyer_foot > p.aisle_height + ta, "the lower flyer's foot must clear the aisle arch's extrados");
    need(pe1.x() < x6, "the lower flyer's seat must lie within the buttress");
    need(p.upper_flyer_foot > pe1.y(), "the upper flyer's foot must lie above the lower flyer's seat");
    pe2 = flyer(flyers, "flyer-up-", x2, uh, uh_top, pe1.x(), p.upper_flyer_foot, tf, p.flyer_voussoirs, p.flyer_depth, rho);
    need(pe2.x() < x6, "the upper flyer's seat must lie within the buttress");
    need(p.buttress_height > pe2.y(), "the buttress must rise above the upper flyer's seat");
    // A stage [xin, x6] from y0 up; with a seat, courses up to the foot intrados pi, the last of
    // them raised into the seat (its top edge the foot joint pi-pe, then flat at pe.y to x6), so a
    // seat is always taller than the sloping joint; without, flat courses up to y1.
    auto stage = [&](double xin, double y0, double y1, const Vec2* pi, const Vec2* pe) {
      const auto y = levels(y0, pi ? pi->y() : y1, p.course);
      for (size_t i = 0; i + 1 < y.size(); ++i) {
        if (pe && i + 2 == y.size()) {
          right.add(id2("buttress-", k++), {Vec2(xin, y[i]), Vec2(x6, y[i]), Vec2(x6, pe->y()), *pe, *pi}, p.buttress_depth, rho);
        } else {
          right.add(id2("buttress-", k++), rect(xin, x6, y[i], y[i + 1]), p.buttress_depth, rho);
        }
      }
    };
    const Vec2 pi1(x5, p.lower_flyer_foot), pi2(pe1.x(), p.upper_flyer_foot);
    stage(x5, ya, 0.0, &pi1, &pe1);
    stage(pe1.x(), pe1.y(), 0.0, &pi2, &pe2);
    stage(pe2.x(), pe2.y(), p.buttress_height, nullptr, nullptr);
    for (Block& b : flyers.blocks) right.blocks.push_back(std::move(b));
  }

  Case c;
  c.source = "cathedral";
  c.name = "Gothic cathedral cross-section";
  auto support = [&](int number, double xl, double xr) {
    Block s;
    s.id = "support-" + std::to_string(number);
    s.support = true;
    s.depth = xl < -x3 || xr > x3 ? p.buttress_depth : p.pier_depth;
    s.vertices = rect(xl, xr, -p.foundation_height, 0);
    c.blocks.push_back(s);
  };
  // Foundations, numbered from the left as the paper's pillars.
  support(1, -x6, -x4);
  support(2, -x3, -x1);
  support(3, x1, x3);
  support(4, x4, x6);
  for (const Block& b : right.blocks) {
    Block l = b;
    l.id = "L-" + b.id;
    l.vertices = mirror(b.vertices, 0.0);
    make_ccw(l.vertices);
    c.blocks.push_back(l);
  }
  {
    const auto half = pointed_half(0.0, x1, x1 + p.nave_thickness, yn, p.nave_height - yn, p.nave_voussoirs / 2);
    const int m = static_cast<int>(half.size());
    int k = 0;
    for (int j = 0; j < m; ++j) {
      Block b;
      b.id = id2("nave-", k++);
      b.vertices = mirror(half[j], 0.0);
      make_ccw(b.vertices);
      b.depth = p.bay;
      b.density = rho;
      c.blocks.push_back(b);
    }
    for (int j = m - 1; j >= 0; --j) {
      Block b;
      b.id = id2("nave-", k++);
      b.vertices = half[j];
      make_ccw(b.vertices);
      b.depth = p.bay;
      b.density = rho;
      c.blocks.push_back(b);
    }
  }
  for (const Block& b : right.blocks) {
    Block r = b;
    r.id = "R-" + b.id;
    c.blocks.push_back(r);
  }

  c.motion.step = p.step;
  c.motion.max_steps = p.max_steps;
  if (p.settlement_step != 0 || p.rotation_step != 0) {
    SupportMotion m;
    m.block = p.moving_support - 1;  // supports come first, in order
    m.translation = Vec2(0, -p.settlement_step / p.step);
    m.rotation = p.rotation_step / p.step;
    m.about = centroid(c.blocks[m.block].vertices);
    c.motion.supports.push_back(m);
  }
  validate_geometry(c);
  return c;
}

}  // namespace masonry
