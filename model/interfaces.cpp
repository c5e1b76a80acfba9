#include "model/interfaces.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace masonry {

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& poly) {
  bool inside = false;
  for (size_t i = 0, n = poly.size(), k = n - 1; i < n; k = i++) {
    const Vec2 &u = poly[i], &v = poly[k];
    if ((u.y() > p.y()) != (v.y() > p.y())) {
      const double x = u.x() + (p.y() - u.y()) * (v.x() - u.x()) / (v.y() - u.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double s = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& poly) {
  double best = INFINITY;
  for (size_t i = 0, n = poly.size(); i < n; ++i) best = std::min(best, distance_to_segment(p, poly[i], poly[(i + 1) % n]));
  return best;
}

namespace {

struct Edge {
  int block;
  Vec2 p, q;        // counter-clockwise order along the block
  double lo, hi;    // extent along the sweep axis
  double lo2, hi2;  // extent along the other axis
};

// Interface of edge e (block i) and edge f (block j) if they are collinear, opposite and
// overlap; A and B lie on e's line.
bool edge_pair(const Edge& e, const Edge& f, double tol, Interface& out) {
  const Vec2 de = e.q - e.p;
  const double le = de.norm();
  if (le <= tol) return false;
  const Vec2 u = de / le;
  const Vec2 n(u.y(), -u.x());              // outward for a counter-clockwise block
  if (u.dot(f.q - f.p) >= 0) return false;  // not opposite
  if (std::abs((f.p - e.p).dot(n)) > tol || std::abs((f.q - e.p).dot(n)) > tol) return false;
  const double s0 = (f.p - e.p).dot(u), s1 = (f.q - e.p).dot(u);
  const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(le, std::max(s0, s1));
  if (hi - lo <= tol) return false;
  out.i = e.block;
  out.j = f.block;
  out.a = e.p + lo * u;
  out.b = e.p + hi * u;
  out.normal = n;
  return true;
}

}  // namespace

double corner_gap(const Vec2& pi, const Vec2& ni, const Vec2& pj, const Vec2& nj) { return std::min((pj - pi).dot(ni), (pi - pj).dot(nj)); }

std::string corner_letter(int corner, int nth) {
  const int k = 2 * nth + (corner == 0 ? 0 : 1);
  if (nth >= 0 && k < 26) return std::string(1, char('A' + k));
  return std::string(corner == 0 ? "A" : "B") + std::to_string(nth + 1);
}

std::string joint_name(const Case& c, int i, int j, int nth) {
  const auto id = [&](int b) { return b >= 0 && b < int(c.blocks.size()) ? c.blocks[b].id : std::string("?"); };
  std::string s = id(i) + "/" + id(j);
  if (nth > 0) s.append(":").append(corner_letter(0, nth)).append(corner_letter(1, nth));  // (not ":" + ...: GCC 12 warns falsely, PR105651)
  return s;
}

std::string corner_name(const Case& c, int i, int j, int corner, int nth) {
  return joint_name(c, i, j) + ":" + corner_letter(corner, nth);
}

std::vector<Interface> detect_interfaces(const Case& c, double tol) {
  // Sweep along the longer axis of the scene.
  const Vec2 extent = scene_bounds(c).extent();
  const int ax = extent.x() >= extent.y() ? 0 : 1, ay = 1 - ax;

  std::vector<Edge> edges;
  for (size_t bi = 0; bi < c.blocks.size(); ++bi) {
    const auto& vs = c.blocks[bi].vertices;
    for (size_t k = 0; k < vs.size(); ++k) {
      const Vec2 &p = vs[k], &q = vs[(k + 1) % vs.size()];
      edges.push_back({static_cast<int>(bi), p, q, std::min(p[ax], q[ax]) - tol, std::max(p[ax], q[ax]) + tol, std::min(p[ay], q[ay]) - tol,
                       std::max(p[ay], q[ay]) + tol});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo < b.lo || (a.lo == b.lo && (a.block < b.block || (a.block == b.block && a.hi < b.hi))); });

  std::vector<Interface> raw;
  for (size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    for (size_t m = k + 1; m < edges.size() && edges[m].lo <= e.hi; ++m) {
      const Edge& f = edges[m];
      if (f.block == e.block || f.hi2 < e.lo2 || f.lo2 > e.hi2) continue;
      if (c.blocks[e.block].support && c.blocks[f.block].support) continue;
      Interface itf;
      // The lower-indexed block owns the normal.
      const bool ok = e.block < f.block ? edge_pair(e, f, tol, itf) : edge_pair(f, e, tol, itf);
      if (ok) raw.push_back(itf);
    }
  }

  // Merge collinear pieces of one block pair (a block edge split by a vertex in its middle).
  std::map<std::pair<int, int>, std::vector<Interface>> by_pair;
  for (const Interface& f : raw) by_pair[{f.i, f.j}].push_back(f);
  std::vector<Interface> out;
  for (auto& [key, list] : by_pair) {
    std::sort(list.begin(), list.end(), [](const Interface& x, const Interface& y) {
      if (x.normal.x() != y.normal.x()) return x.normal.x() < y.normal.x();
      if (x.normal.y() != y.normal.y()) return x.normal.y() < y.normal.y();
      return x.a.dot(Vec2(-x.normal.y(), x.normal.x())) < y.a.dot(Vec2(-y.normal.y(), y.normal.x()));
    });
    for (const Interface& f : list) {
      if (!out.empty()) {
        Interface& g = out.back();
        const Vec2 t(-g.normal.y(), g.normal.x());
        const bool same_line = g.i == f.i && g.j == f.j && g.normal.dot(f.normal) > 1 - 1e-9 && std::abs((f.a - g.a).dot(g.normal)) <= tol;
        if (same_line && (f.a - g.b).dot(t) <= tol) {
          if ((f.b - g.b).dot(t) > 0) g.b = f.b;
          continue;
        }
      }
      out.push_back(f);
    }
  }
  return out;
}

}  // namespace masonry
