// The brick wall generator (generators.hpp, cases/README.md "Brick wall"): courses of bricks in
// a bond, openings under lintels or arches, two ground blocks of which one settles or turns.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "cases/generators.hpp"

namespace masonry {

const char* wall_bond_name(WallBond b) {
  switch (b) {
    case WallBond::running: return "running";
    case WallBond::stack: return "stack";
    case WallBond::header: return "header";
  }
  return "?";
}

WallOpening parse_wall_opening(const std::string& text) {
  WallOpening o;
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string s; std::getline(in, s, ',');) parts.push_back(s);
  const auto bad = [&](const std::string& why) {
    return CaseError("wall: opening '" + printable(text) + "': " + why + " (X,SILL,WIDTH,HEIGHT[,lintel|arch], m)");
  };
  if (parts.size() != 4 && parts.size() != 5) throw bad("four numbers and an optional top expected");
  double* fields[4] = {&o.x, &o.sill, &o.width, &o.height};
  for (int k = 0; k < 4; ++k) {
    size_t used = 0;
    try {
      *fields[k] = std::stod(parts[k], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != parts[k].size() || !std::isfinite(*fields[k])) throw bad("'" + printable(parts[k]) + "' is not a number");
  }
  if (parts.size() == 5) {
    if (parts[4] == "lintel")
      o.top = OpeningTop::lintel;
    else if (parts[4] == "arch")
      o.top = OpeningTop::arch;
    else
      throw bad("the top must be 'lintel' or 'arch'");
  }
  return o;
}

namespace {

void make_ccw(std::vector<Vec2>& v) {
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
}

Block rectangle(const std::string& id, double x0, double y0, double x1, double y1, double depth, double density) {
  Block b;
  b.id = id;
  b.depth = depth;
  b.density = density;
  b.vertices = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
  return b;
}

// A course's stretch reserved by an opening: left void (no block), or filled by the opening's
// own blocks (lintel, arch and spandrels).
struct Band {
  double lo, hi;
  int opening;
};

// One opening laid out on the course grid.
struct Laid {
  WallOpening o;
  int c_sill = 0, c_top = 0;  // courses [c_sill, c_top) are cut by the void
  int c_end = 0;              // courses [c_top, c_end) are cut by the lintel or the arch's zone
  double lo = 0, hi = 0;      // the band of the courses [c_top, c_end), m
};

// The arch's voussoirs and the spandrel pieces between its extrados and the rectangle
// [cx - X, cx + X] x [ys, ytop]: each spandrel piece lies between the same two radial lines as
// its voussoir, so it is convex (a cone, the rectangle and the half-plane beyond the extrados
// chord) and rests on the voussoir's extrados along one joint. Every shared point is computed
// once: the joints match exactly.
void add_arch(Case& c, const BrickWall& p, const Laid& L, int o) {
  const double ri = 0.5 * L.o.width, re = ri + p.arch_thickness;
  const double cx = L.o.x + ri, ys = L.c_top * p.course_height, ytop = L.c_end * p.course_height;
  const double X = 0.5 * (L.hi - L.lo);
  int n = p.arch_voussoirs;
  if (n == 0) n = std::max(3, static_cast<int>(std::lround(M_PI * (ri + 0.5 * p.arch_thickness) / p.course_height)));
  // Directions of the joints, from the left springing (k = 0) to the right one (k = n), mirrored
  // so the arch is symmetric bit for bit.
  std::vector<Vec2> dir(n + 1);
  for (int k = 0; 2 * k <= n; ++k) {
    const double a = k * M_PI / n;
    dir[k] = k == 0 ? Vec2(-1, 0) : 2 * k == n ? Vec2(0, 1) : Vec2(-std::cos(a), std::sin(a));
    dir[n - k] = Vec2(-dir[k].x(), dir[k].y());
  }
  const Vec2 ctr(cx, ys);
  // Where each joint's line meets the rectangle's sides or top, and its place along that path
  // (left side up, top, right side down) to order the rectangle's corners.
  const double rise = ytop - ys;
  std::vector<Vec2> hit(n + 1);
  std::vector<double> along(n + 1);
  for (int k = 0; k <= n; ++k) {
    const Vec2 d = dir[k];
    const double to_side = d.x() != 0 ? X / std::abs(d.x()) : INFINITY, to_top = d.y() > 0 ? rise / d.y() : INFINITY;
    if (to_side <= to_top) {
      hit[k] = Vec2(d.x() < 0 ? cx - X : cx + X, ys + to_side * d.y());
      along[k] = d.x() < 0 ? hit[k].y() - ys : 2 * rise + 2 * X - (hit[k].y() - ys);
    } else {
      hit[k] = Vec2(cx + to_top * d.x(), ytop);
      along[k] = rise + hit[k].x() - (cx - X);
    }
  }
  const Vec2 corner[2] = {Vec2(cx - X, ytop), Vec2(cx + X, ytop)};
  const double corner_along[2] = {rise, rise + 2 * X};
  const std::string base = "arch-" + std::to_string(o);
  for (int k = 0; k < n; ++k) {
    Block v;
    v.id = base + "-v" + std::to_string(k);
    v.depth = p.depth;
    v.density = p.density;
    const Vec2 i0 = ctr + ri * dir[k], i1 = ctr + ri * dir[k + 1], e0 = ctr + re * dir[k], e1 = ctr + re * dir[k + 1];
    v.vertices = {i0, i1, e1, e0};
    make_ccw(v.vertices);
    c.blocks.push_back(v);
    Block s;
    s.id = base + "-s" + std::to_string(k);
    s.depth = p.depth;
    s.density = p.density;
    s.vertices = {e0, hit[k]};
    const double eps = 1e-9 * X;
    for (int q = 0; q < 2; ++q)
      if (corner_along[q] > along[k] + eps && corner_along[q] < along[k + 1] - eps) s.vertices.push_back(corner[q]);
    s.vertices.push_back(hit[k + 1]);
    s.vertices.push_back(e1);
    make_ccw(s.vertices);
    c.blocks.push_back(s);
  }
}

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

Case brick_wall(const BrickWall& p) {
  const auto fail = [](const std::string& why) { return CaseError("wall: " + why); };
  if (p.courses < 1 || p.bricks < 1) throw fail("need at least one course and one brick per course");
  if (!(p.brick_length > 0) || !(p.header_length > 0) || !(p.course_height > 0) || !(p.depth > 0) || !(p.ground_height > 0))
    throw fail("brick length, header length, course height, depth and ground height must be positive");
  if (!(p.density > 0)) throw fail("the density must be positive");
  if (!(p.step > 0) || p.max_steps < 0) throw fail("need step > 0 and max_steps >= 0");
  if (!(p.arch_thickness > 0) || !(p.lintel_bearing > 0)) throw fail("the arch thickness and the lintel bearing must be positive");
  // Two voussoirs are the fewest: the joints run from the left springing (k = 0) to the right
  // one (k = n), so a single voussoir's four corners all lie on the springing line (no area,
  // refused by the geometry check as "zero area"); two meet at a vertical crown joint.
  if (p.arch_voussoirs < 0 || p.arch_voussoirs == 1)
    throw fail("arch-voussoirs " + std::to_string(p.arch_voussoirs) +
               ": must be 0 (about one per course height) or at least 2 (one voussoir's two joints are both springings, on one line: it "
               "has no area)");
  // A moving ground with neither a settlement nor a rotation step would be written as a case
  // with no support motion, which every run then refuses ("no support moves").
  if (p.moving != MovingGround::none && p.settlement_step == 0 && p.rotation_step == 0)
    throw fail(std::string("moving ") + (p.moving == MovingGround::left ? "left" : "right") +
               ", but settlement-step and rotation-step are both 0: the ground would not move (give either step, or moving none)");
  const double H = p.course_height;
  const double unit = p.bond == WallBond::header ? p.header_length : p.brick_length;
  const double length = p.bricks * unit;
  const double split = p.ground_split < 0 ? 0.5 * length : p.ground_split;
  if (!(split > 0 && split < length)) throw fail("the ground split must lie inside the wall (0 < x < " + number(length) + " m)");
  const double sliver = 0.25 * unit;  // shorter pieces are merged into a neighbour

  // The openings on the course grid, and the bands they reserve in each course.
  std::vector<Laid> laid;
  std::vector<std::vector<Band>> bands(p.courses);
  for (size_t o = 0; o < p.openings.size(); ++o) {
    const WallOpening& w = p.openings[o];
    const std::string name = "opening " + std::to_string(o + 1);
    Laid L;
    L.o = w;
    if (!(w.width > 0) || !(w.height > 0) || !(w.sill >= 0)) throw fail(name + ": need width > 0, height > 0, sill >= 0");
    L.c_sill = static_cast<int>(std::lround(w.sill / H));
    L.c_top = static_cast<int>(std::lround((w.sill + w.height) / H));
    if (L.c_top <= L.c_sill) throw fail(name + ": lower than half a course");
    if (w.top == OpeningTop::lintel) {
      L.c_end = L.c_top + 1;
      L.lo = w.x - p.lintel_bearing;
      L.hi = w.x + w.width + p.lintel_bearing;
    } else {
      const double re = 0.5 * w.width + p.arch_thickness, cx = w.x + 0.5 * w.width;
      L.c_end = static_cast<int>(std::ceil((L.c_top * H + re + 0.5 * H) / H - 1e-9));
      L.lo = cx - re - H;
      L.hi = cx + re + H;
    }
    if (L.c_end > p.courses)
      throw fail(name + ": its " + (w.top == OpeningTop::lintel ? "lintel" : "arch") + " needs " + std::to_string(L.c_end) +
                 " courses, the wall has " + std::to_string(p.courses));
    if (L.lo < sliver || L.hi > length - sliver)
      throw fail(name + ": it and its " + (w.top == OpeningTop::lintel ? "lintel's bearings" : "arch") + " span " + number(L.lo) + ".." +
                 number(L.hi) + " m, closer than a quarter unit to the wall's ends (0.." + number(length) + " m)");
    for (int r = L.c_sill; r < L.c_top; ++r) bands[r].push_back({w.x, w.x + w.width, static_cast<int>(o)});
    for (int r = L.c_top; r < L.c_end; ++r) bands[r].push_back({L.lo, L.hi, static_cast<int>(o)});
    laid.push_back(L);
  }
  for (int r = 0; r < p.courses; ++r) {
    auto& b = bands[r];
    std::sort(b.begin(), b.end(), [](const Band& x, const Band& y) { return x.lo < y.lo; });
    for (size_t k = 1; k < b.size(); ++k)
      if (b[k].lo < b[k - 1].hi + sliver)
        throw fail("openings " + std::to_string(b[k - 1].opening + 1) + " and " + std::to_string(b[k].opening + 1) +
                   " leave less than a quarter unit of wall between them in course " + std::to_string(r));
  }

  Case c;
  c.source = "wall";
  c.name = "brick wall";
  std::ostringstream what;
  what << wall_bond_name(p.bond) << " bond, " << p.courses << " courses of " << p.bricks << " units (" << number(unit) << " x " << number(H)
       << " m), " << p.openings.size() << " openings; ground "
       << (p.moving == MovingGround::none   ? "fixed"
           : p.moving == MovingGround::left ? "left of "
                                            : "right of ")
       << (p.moving == MovingGround::none ? "" : number(split) + " m moving");
  c.description = what.str();
  // Supports first, as in the other generators.
  Block gl = rectangle("ground-left", 0, -p.ground_height, split, 0, p.depth, 0);
  Block gr = rectangle("ground-right", split, -p.ground_height, length, 0, p.depth, 0);
  gl.support = gr.support = true;
  c.blocks.push_back(gl);
  c.blocks.push_back(gr);

  for (int r = 0; r < p.courses; ++r) {
    // Head joints of the bond, then the bands' edges; `fixed` ones (the wall's ends, the
    // bands' edges) stay where a sliver is merged away.
    struct Cut {
      double x;
      bool fixed;
    };
    const double offset = p.bond == WallBond::stack ? 0.0 : (r % 2) * 0.5 * unit;
    std::vector<Cut> cuts{{0.0, true}, {length, true}};
    for (int k = 0; offset + k * unit < length - 1e-9 * unit; ++k)
      if (offset + k * unit > 1e-9 * unit) cuts.push_back({offset + k * unit, false});
    const auto inside_band = [&](double x) {
      for (const Band& b : bands[r])
        if (x > b.lo && x < b.hi) return true;
      return false;
    };
    cuts.erase(std::remove_if(cuts.begin(), cuts.end(), [&](const Cut& q) { return inside_band(q.x); }), cuts.end());
    for (const Band& b : bands[r]) cuts.push_back({b.lo, true}), cuts.push_back({b.hi, true});
    std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.x < b.x; });
    for (bool merged = true; merged;) {
      merged = false;
      for (size_t k = 0; k + 1 < cuts.size() && !merged; ++k) {
        if (cuts[k + 1].x - cuts[k].x >= sliver || inside_band(0.5 * (cuts[k].x + cuts[k + 1].x))) continue;
        if (!cuts[k + 1].fixed)
          cuts.erase(cuts.begin() + k + 1), merged = true;
        else if (!cuts[k].fixed)
          cuts.erase(cuts.begin() + k), merged = true;
      }
    }
    int piece = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double x0 = cuts[k].x, x1 = cuts[k + 1].x;
      if (inside_band(0.5 * (x0 + x1))) continue;
      std::string id = "c";  // (not "c" + ...: GCC 12 warns falsely, PR105651)
      id += std::to_string(r) + "-" + std::to_string(piece++);
      c.blocks.push_back(rectangle(id, x0, r * H, x1, (r + 1) * H, p.depth, p.density));
    }
  }
  for (size_t o = 0; o < laid.size(); ++o) {
    const Laid& L = laid[o];
    if (L.o.top == OpeningTop::lintel)
      c.blocks.push_back(rectangle("lintel-" + std::to_string(o + 1), L.lo, L.c_top * H, L.hi, L.c_end * H, p.depth, p.density));
    else
      add_arch(c, p, L, static_cast<int>(o + 1));
  }

  c.motion.step = p.step;
  c.motion.max_steps = p.max_steps;
  if (p.moving != MovingGround::none) {
    SupportMotion m;
    m.block = p.moving == MovingGround::left ? 0 : 1;
    m.translation = Vec2(0, -p.settlement_step / p.step);
    m.rotation = p.rotation_step / p.step;
    m.about = Vec2(split, 0);
    c.motion.supports.push_back(m);
  }
  validate_geometry(c);
  return c;
}

}  // namespace masonry
