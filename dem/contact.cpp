#include "dem/contact.hpp"

#include <box2d/b2_common.h>
#include <box2d/b2_settings.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace masonry::dem {

static_assert(kMaxPieceVertices == b2_maxPolygonVertices, "piece size must follow Box2D's polygon limit");

namespace {

// Convex, collinear vertices allowed (convex_pieces removes them: see without_straight_vertices).
bool is_convex(const std::vector<Vec2>& p) {
  const size_t n = p.size();
  const double scale = 1e-12 * std::max(1.0, std::abs(signed_area(p)));
  for (size_t i = 0; i < n; ++i)
    if (cross(p[(i + 1) % n] - p[i], p[(i + 2) % n] - p[(i + 1) % n]) < -scale) return false;
  return true;
}

bool point_in_triangle(const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross(b - a, q - a) >= 0 && cross(c - b, q - b) >= 0 && cross(a - c, q - c) >= 0;
}

std::vector<std::vector<Vec2>> triangulate(const std::vector<Vec2>& poly) {
  std::vector<int> idx(poly.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::vector<std::vector<Vec2>> tris;
  size_t guard = 0;
  while (idx.size() > 3) {
    const size_t n = idx.size();
    bool clipped = false;
    for (size_t k = 0; k < n; ++k) {
      const Vec2& a = poly[idx[(k + n - 1) % n]];
      const Vec2& b = poly[idx[k]];
      const Vec2& c = poly[idx[(k + 1) % n]];
      if (cross(b - a, c - b) <= 0) continue;  // reflex or flat: not an ear
      bool empty = true;
      for (size_t m = 0; m < n && empty; ++m) {
        if (m == k || m == (k + n - 1) % n || m == (k + 1) % n) continue;
        const Vec2& q = poly[idx[m]];
        if (q != a && q != b && q != c && point_in_triangle(q, a, b, c)) empty = false;
      }
      if (!empty) continue;
      tris.push_back({a, b, c});
      idx.erase(idx.begin() + static_cast<long>(k));
      clipped = true;
      break;
    }
    if (!clipped || ++guard > 100000) throw std::runtime_error("cannot split a block into convex pieces");
  }
  tris.push_back({poly[idx[0]], poly[idx[1]], poly[idx[2]]});
  return tris;
}

// Union of two convex CCW polygons sharing the edge a->b of p (b->a of q), or empty if they
// do not share an edge.
std::vector<Vec2> merge_on_shared_edge(const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
  const size_t np = p.size(), nq = q.size();
  for (size_t i = 0; i < np; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % np];
    for (size_t j = 0; j < nq; ++j) {
      if (q[j] != b || q[(j + 1) % nq] != a) continue;
      std::vector<Vec2> out;
      for (size_t k = 0; k < np; ++k) out.push_back(p[(i + 1 + k) % np]);  // b ... a
      for (size_t k = 2; k < nq; ++k) out.push_back(q[(j + k) % nq]);      // after a, before b
      return out;
    }
  }
  return {};
}

}  // namespace

// The polygon without its straight-angle vertices (collinear neighbours, same direction). A
// Box2D manifold is built on one reference face and clipped to that face's ends: a face split by
// a collinear vertex (a drawing's vertex where two blocks meet one edge) would carry contact on
// one part only, and a block standing on half its base topples at once.
std::vector<Vec2> without_straight_vertices(const std::vector<Vec2>& p) {
  std::vector<Vec2> out;
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 e0 = p[i] - p[(i + n - 1) % n], e1 = p[(i + 1) % n] - p[i];
    const bool straight = std::abs(cross(e0, e1)) <= 1e-9 * e0.norm() * e1.norm() && e0.dot(e1) > 0;
    if (!straight) out.push_back(p[i]);
  }
  return out.size() >= 3 ? out : p;
}

std::vector<std::vector<Vec2>> convex_pieces(const std::vector<Vec2>& poly_in) {
  const std::vector<Vec2> poly = without_straight_vertices(poly_in);
  if (poly.size() <= static_cast<size_t>(kMaxPieceVertices) && is_convex(poly)) return {poly};
  std::vector<std::vector<Vec2>> pieces = triangulate(poly);
  // Greedy Hertel-Mehlhorn style merging: few pieces means few contact pairs.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < pieces.size() && !merged; ++i)
      for (size_t j = i + 1; j < pieces.size() && !merged; ++j) {
        std::vector<Vec2> u = merge_on_shared_edge(pieces[i], pieces[j]);
        if (!u.empty()) u = without_straight_vertices(u);  // merged along a line: one face, not two
        if (u.empty() || u.size() > static_cast<size_t>(kMaxPieceVertices) || !is_convex(u)) continue;
        pieces[i] = std::move(u);
        pieces.erase(pieces.begin() + static_cast<long>(j));
        merged = true;
      }
  }
  return pieces;
}

namespace {

// Smallest signed distance of 2's vertices from edge i of 1.
inline double edge_separation(int i, const Vec2* v1, const Vec2* n1, const Vec2* v2, int c2) {
  double si = INFINITY;
  for (int j = 0; j < c2; ++j) si = std::min(si, n1[i].dot(v2[j] - v1[i]));
  return si;
}

// Largest over the edges of 1 of the smallest signed distance of 2's vertices (b2FindMaxSeparation);
// `second` is the largest over the other edges, so best - second says how firm the choice is.
double max_separation(int& edge, double& second, const Vec2* v1, const Vec2* n1, int c1, const Vec2* v2, int c2) {
  double best = -INFINITY;
  second = -INFINITY;
  edge = 0;
  for (int i = 0; i < c1; ++i) {
    const double si = edge_separation(i, v1, n1, v2, c2);
    if (si > best) {
      second = best;
      best = si;
      edge = i;
    } else {
      second = std::max(second, si);
    }
  }
  return best;
}

struct ClipVertex {
  Vec2 v;
  int slot;
};

// Keeps the part of the segment with normal . x <= offset; a cut point inherits the slot of the
// vertex it replaces, so slots name the ends of the incident edge whatever the clipping did.
// Inlined: called twice per touching pair per cycle.
inline __attribute__((always_inline)) int clip_segment(ClipVertex out[2], const ClipVertex in[2], const Vec2& normal, double offset) {
  int n = 0;
  const double d0 = normal.dot(in[0].v) - offset, d1 = normal.dot(in[1].v) - offset;
  if (d0 <= 0) out[n++] = in[0];
  if (d1 <= 0) out[n++] = in[1];
  if (d0 * d1 < 0) {
    const double t = d0 / (d0 - d1);
    out[n].v = in[0].v + t * (in[1].v - in[0].v);
    out[n].slot = d0 > 0 ? in[0].slot : in[1].slot;
    ++n;
  }
  return n;
}

// How much relative motion a touching pair can take before either separation could reach zero:
// half the depth of the shallower, the half for rounding, less an absolute 1e-12 of the lever
// (the vertices are rotated copies, whose rounding the motion bound, taken from the stored poses,
// does not count: a few ulps of the coordinates).
inline double touch_margin(double sep_a, double sep_b, double lever) { return -0.5 * std::max(sep_a, sep_b) - 1e-12 * lever; }

}  // namespace

bool collide(const Vec2* va, const Vec2* na, int ca, const Vec2* vb, const Vec2* nb, int cb, Manifold& m) {
  SatCache fresh;
  return collide_cached(va, na, ca, vb, nb, cb, 0.0, 0.0, fresh, m);
}

bool collide_cached(const Vec2* va, const Vec2* na, int ca, const Vec2* vb, const Vec2* nb, int cb, double motion, double lever, SatCache& cache,
                    Manifold& m) {
  m.count = 0;
  // Box2D's hysteresis: face A unless B is clearly better, so the choice does not flicker.
  const double k_tol = 0.1 * b2_linearSlop;
  int edge_a = 0, edge_b = 0, inc = 0;
  double sep_a = 0, sep_b = 0;
  bool flip = false, searched = false;
  // A separating edge found last time proves the polygons apart again if it still separates them
  // (the full search would find this or a larger separation). When touching, the best edges, the
  // flip and the incident edge are reused while the motion since the search is below a quarter
  // of the margin by which each choice won (each separation moves by at most `motion`, so a
  // difference of two by at most twice that; the factor 2 left over covers rounding).
  switch (cache.state) {
    case SatCache::kApartA:
    case SatCache::kApartB: {
      // Apart by at least the slack (half the separation last measured, the half for rounding):
      // no separation can have closed by more than the motion since, so nothing to compute.
      cache.slack -= motion;
      if (cache.slack > 0) return false;
      const double sep =
          cache.state == SatCache::kApartA ? edge_separation(cache.edge_a, va, na, vb, cb) : edge_separation(cache.edge_b, vb, nb, va, ca);
      if (sep > 0) {
        cache.slack = 0.5 * sep;
        return false;
      }
      break;
    }
    case SatCache::kTouching:
      cache.slack -= motion;
      cache.touch -= motion;
      if (cache.slack > 0 && cache.touch > 0) {
        // Each separation was at least twice the touch it started with below zero, and has
        // moved by less than that since: still touching, and the flip is the cached one (slack).
        edge_a = cache.edge_a;
        edge_b = cache.edge_b;
        flip = cache.flip;
        inc = cache.inc;
        searched = true;
      } else if (cache.slack > 0) {
        edge_a = cache.edge_a;
        edge_b = cache.edge_b;
        sep_a = edge_separation(edge_a, va, na, vb, cb);
        if (sep_a > 0) return false;
        sep_b = edge_separation(edge_b, vb, nb, va, ca);
        if (sep_b > 0) return false;
        flip = sep_b > sep_a + k_tol;
        inc = cache.inc;
        searched = flip == cache.flip;  // always, by the slack; a mismatch would mean a bad bound
        cache.touch = touch_margin(sep_a, sep_b, lever);
      }
      break;
    case SatCache::kNone: break;
  }
  if (!searched) {
    double second_a = 0, second_b = 0;
    sep_a = max_separation(edge_a, second_a, va, na, ca, vb, cb);
    if (sep_a > 0) {
      cache.state = SatCache::kApartA;
      cache.edge_a = static_cast<unsigned char>(edge_a);
      cache.slack = 0.5 * sep_a;
      return false;
    }
    sep_b = max_separation(edge_b, second_b, vb, nb, cb, va, ca);
    if (sep_b > 0) {
      cache.state = SatCache::kApartB;
      cache.edge_b = static_cast<unsigned char>(edge_b);
      cache.slack = 0.5 * sep_b;
      return false;
    }
    flip = sep_b > sep_a + k_tol;
    const Vec2* n1 = flip ? nb : na;
    const Vec2* n2 = flip ? na : nb;
    const int c2 = flip ? ca : cb;
    const Vec2 normal = n1[flip ? edge_b : edge_a];
    double min_dot = INFINITY, second_dot = INFINITY;
    for (int i = 0; i < c2; ++i) {
      const double d = normal.dot(n2[i]);
      if (d < min_dot) {
        second_dot = min_dot;
        min_dot = d;
        inc = i;
      } else {
        second_dot = std::min(second_dot, d);
      }
    }
    cache.state = SatCache::kTouching;
    cache.flip = flip;
    cache.edge_a = static_cast<unsigned char>(edge_a);
    cache.edge_b = static_cast<unsigned char>(edge_b);
    cache.inc = static_cast<unsigned char>(inc);
    // The incident edge's lead is a difference of dot products of unit normals; it changes by at
    // most twice the relative rotation, and the lever turns rotation into motion.
    cache.touch = touch_margin(sep_a, sep_b, lever);
    cache.slack = 0.25 * std::min({sep_a - second_a, sep_b - second_b, std::abs(sep_b - (sep_a + k_tol)), (second_dot - min_dot) * lever});
  }
  const Vec2 *v1 = flip ? vb : va, *n1 = flip ? nb : na, *v2 = flip ? va : vb;
  const int c1 = flip ? cb : ca, c2 = flip ? ca : cb, e1 = flip ? edge_b : edge_a;

  const Vec2 normal = n1[e1];
  // The next vertex without an integer division (two per touching pair per cycle were 7% of it).
  const ClipVertex incident[2] = {{v2[inc], 0}, {v2[inc + 1 == c2 ? 0 : inc + 1], 1}};
  const Vec2 v11 = v1[e1], v12 = v1[e1 + 1 == c1 ? 0 : e1 + 1];
  const Vec2 tangent = (v12 - v11).normalized();
  ClipVertex c1p[2], c2p[2];
  if (clip_segment(c1p, incident, -tangent, -tangent.dot(v11)) < 2) return false;
  if (clip_segment(c2p, c1p, tangent, tangent.dot(v12)) < 2) return false;

  m.normal = flip ? Vec2(-normal) : normal;
  m.flip = flip;
  m.ref_edge = e1;
  m.inc_edge = inc;
  m.clip_length = (c2p[0].v - c2p[1].v).norm();
  const double front = normal.dot(v11);
  for (int i = 0; i < 2; ++i) {
    const double s = normal.dot(c2p[i].v) - front;
    if (s > 0) continue;
    ManifoldPoint& p = m.points[m.count++];
    p.point = c2p[i].v - 0.5 * s * normal;
    p.separation = s;
    p.slot = c2p[i].slot;
  }
  return m.count > 0;
}

}  // namespace masonry::dem
