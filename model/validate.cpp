// Geometric validation of a case's blocks: every message names the file, the block and the field.
#include <algorithm>
#include <cmath>

#include "model/case.hpp"
#include "model/interfaces.hpp"

namespace masonry {

namespace {

// Proper or touching intersection of closed segments pq and rs.
bool segments_intersect(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s, double tol) {
  const Vec2 d1 = q - p, d2 = s - r;
  const double den = cross(d1, d2);
  if (std::abs(den) <= 1e-14 * d1.norm() * d2.norm()) {
    // Parallel: they meet only if collinear and overlapping.
    if (distance_to_segment(r, p, q) > tol && distance_to_segment(s, p, q) > tol && distance_to_segment(p, r, s) > tol &&
        distance_to_segment(q, r, s) > tol)
      return false;
    return std::abs(cross(d1, r - p)) <= tol * d1.norm();
  }
  const double t = cross(r - p, d2) / den, u = cross(r - p, d1) / den;
  const double et = tol / d1.norm(), eu = tol / d2.norm();
  return t >= -et && t <= 1 + et && u >= -eu && u <= 1 + eu;
}

// Proper crossing: interior to both segments, away from their ends by more than tol.
bool segments_cross(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s, double tol) {
  const Vec2 d1 = q - p, d2 = s - r;
  const double den = cross(d1, d2);
  if (std::abs(den) <= 1e-9 * d1.norm() * d2.norm()) return false;
  const double t = cross(r - p, d2) / den, u = cross(r - p, d1) / den;
  const double et = tol / d1.norm(), eu = tol / d2.norm();
  return t > et && t < 1 - et && u > eu && u < 1 - eu;
}

// A point of `a` lies inside `b` deeper than tol, or their edges cross.
bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  auto deep_inside = [&](const Vec2& p, const std::vector<Vec2>& poly) { return point_in_polygon(p, poly) && distance_to_boundary(p, poly) > tol; };
  for (int pass = 0; pass < 2; ++pass) {
    const auto& P = pass == 0 ? a : b;
    const auto& Q = pass == 0 ? b : a;
    for (size_t k = 0, n = P.size(); k < n; ++k) {
      const Vec2 &p = P[k], &q = P[(k + 1) % n];
      const Vec2 mid = 0.5 * (p + q);
      const Vec2 d = q - p;
      // A point just inside P next to the middle of the edge (P is counter-clockwise).
      const Vec2 in = mid + 0.01 * perp(d);
      if (deep_inside(p, Q) || deep_inside(mid, Q) || (point_in_polygon(in, P) && deep_inside(in, Q))) return true;
    }
  }
  for (size_t k = 0; k < a.size(); ++k)
    for (size_t m = 0; m < b.size(); ++m)
      if (segments_cross(a[k], a[(k + 1) % a.size()], b[m], b[(m + 1) % b.size()], tol)) return true;
  return false;
}

}  // namespace

void validate_geometry(const Case& c) {
  const double tol = c.prd.contact_tolerance;
  auto fail = [&](const Block& b, const std::string& what) { throw CaseError(c.source + ": block '" + printable(b.id) + "': " + what); };
  for (const Block& b : c.blocks) {
    const auto& v = b.vertices;
    const size_t n = v.size();
    if (n < 3) fail(b, "field 'vertices': fewer than 3 vertices");
    for (const Vec2& p : v)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y())) fail(b, "field 'vertices': not a finite number");
    const Bounds bx = bounds(v);
    const double size = (bx.hi - bx.lo).maxCoeff();
    for (size_t k = 0; k < n; ++k)
      if ((v[(k + 1) % n] - v[k]).norm() <= 1e-12 * size)
        fail(b, "field 'vertices': vertices " + std::to_string(k) + " and " + std::to_string((k + 1) % n) + " coincide");
    // All vertices on one line: no area (checked before self-intersection, which it also is).
    double spread = 0;
    const Vec2 axis = (v[1] - v[0]).normalized();
    for (const Vec2& p : v) spread = std::max(spread, std::abs(cross(axis, p - v[0])));
    if (spread <= 1e-12 * size) fail(b, "field 'vertices': zero area");
    for (size_t k = 0; k < n; ++k) {
      // Adjacent edges folding back on each other.
      const Vec2 &p = v[k], &q = v[(k + 1) % n], &r = v[(k + 2) % n];
      const Vec2 d1 = q - p, d2 = r - q;
      if (std::abs(cross(d1, d2)) <= 1e-12 * d1.norm() * d2.norm() && d1.dot(d2) < 0)
        fail(b, "field 'vertices': self-intersecting (edges " + std::to_string(k) + " and " + std::to_string((k + 1) % n) + " fold back)");
    }
    // Non-adjacent edges that meet. A sweep along x: edges sorted by their lowest x, each compared
    // only with the later ones that start before it ends, so a block of 100,000 vertices takes
    // milliseconds, not the minutes of comparing every pair.
    const double eps = 1e-12 * size;
    std::vector<std::pair<double, size_t>> order(n);
    for (size_t k = 0; k < n; ++k) order[k] = {std::min(v[k].x(), v[(k + 1) % n].x()), k};
    std::sort(order.begin(), order.end());
    for (size_t a = 0; a < n; ++a) {
      const size_t k = order[a].second;
      const double k_hi = std::max(v[k].x(), v[(k + 1) % n].x()) + eps;
      for (size_t z = a + 1; z < n && order[z].first <= k_hi; ++z) {
        const size_t m = order[z].second;
        const size_t lo = std::min(k, m), hi = std::max(k, m);
        if (hi - lo == 1 || (lo == 0 && hi == n - 1)) continue;  // adjacent
        if (segments_intersect(v[lo], v[(lo + 1) % n], v[hi], v[(hi + 1) % n], eps))
          fail(b, "field 'vertices': self-intersecting (edges " + std::to_string(lo) + " and " + std::to_string(hi) + " cross)");
      }
    }
    if (!(std::abs(signed_area(v)) > 1e-12 * size * size) || size <= 0) fail(b, "field 'vertices': zero area");
  }

  // Overlaps: sort by the lower x of the bounding box, compare boxes that overlap in x.
  std::vector<std::pair<Bounds, size_t>> boxes;
  for (size_t i = 0; i < c.blocks.size(); ++i) boxes.push_back({bounds(c.blocks[i].vertices), i});
  std::sort(boxes.begin(), boxes.end(), [](const auto& x, const auto& y) {
    return x.first.lo.x() < y.first.lo.x() || (x.first.lo.x() == y.first.lo.x() && x.second < y.second);
  });
  for (size_t k = 0; k < boxes.size(); ++k)
    for (size_t m = k + 1; m < boxes.size() && boxes[m].first.lo.x() < boxes[k].first.hi.x() - tol; ++m) {
      const Bounds &p = boxes[k].first, &q = boxes[m].first;
      if (q.lo.y() >= p.hi.y() - tol || q.hi.y() <= p.lo.y() + tol) continue;
      const size_t i = std::min(boxes[k].second, boxes[m].second), j = std::max(boxes[k].second, boxes[m].second);
      if (polygons_overlap(c.blocks[i].vertices, c.blocks[j].vertices, tol))
        fail(c.blocks[j], "field 'vertices': overlaps block '" + printable(c.blocks[i].id) + "'");
    }
}

}  // namespace masonry
