// Checks shared by the generator tests: what every generated case must satisfy, whatever the
// structure. Expected values come from the case's own definition (Box2D's limits, convexity,
// the model's parser), never from the generator's output.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/interfaces.hpp"

namespace masonry::test {

// Box2D 2.4 (Debian) allows at most b2_maxPolygonVertices = 8 vertices per convex polygon; the
// DEM builds one b2PolygonShape per block.
constexpr int kBox2DMaxVertices = 8;

// Strictly convex and counter-clockwise (every turn a left turn, no collinear vertex: Box2D
// would drop it and the joints would no longer match).
inline bool strictly_convex_ccw(const std::vector<Vec2>& v) {
  const size_t n = v.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 d1 = v[(k + 1) % n] - v[k], d2 = v[(k + 2) % n] - v[(k + 1) % n];
    if (!(cross(d1, d2) > 1e-10 * d1.norm() * d2.norm())) return false;
  }
  return true;
}

// Union-find over blocks joined by interfaces: is the scene one piece?
inline bool all_connected(const Case& c, const std::vector<Interface>& ifs) {
  std::vector<int> parent(c.blocks.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  for (const Interface& f : ifs) parent[find(f.i)] = find(f.j);
  for (size_t i = 0; i < parent.size(); ++i)
    if (find(static_cast<int>(i)) != find(0)) return false;
  return true;
}

inline double free_area(const Case& c) {
  double a = 0;
  for (const Block& b : c.blocks)
    if (!b.support) a += std::abs(signed_area(b.vertices));
  return a;
}

// Everything a generated case must satisfy before any method sees it.
inline void expect_valid_case(const Case& c) {
  for (const Block& b : c.blocks) {
    EXPECT_GE(b.vertices.size(), 3u) << b.id;
    EXPECT_LE(static_cast<int>(b.vertices.size()), kBox2DMaxVertices) << b.id;
    EXPECT_TRUE(strictly_convex_ccw(b.vertices)) << b.id << " is not a strictly convex counter-clockwise polygon";
    EXPECT_GT(b.depth, 0) << b.id;
    if (!b.support) {
      EXPECT_GT(b.density, 0) << b.id;
    }
  }
  // The parser validates fully: overlaps, self-intersections, every free block touching another.
  EXPECT_NO_THROW(parse_case(case_to_json(c), c.name));
  const auto ifs = detect_interfaces(c, c.prd.contact_tolerance);
  EXPECT_TRUE(all_connected(c, ifs)) << c.name << ": the blocks do not form one connected structure";
}

// Blocks (by index) that share an interface with block b.
inline std::vector<int> neighbours(const std::vector<Interface>& ifs, int b) {
  std::vector<int> n;
  for (const Interface& f : ifs) {
    if (f.i == b) n.push_back(f.j);
    if (f.j == b) n.push_back(f.i);
  }
  return n;
}

// Simpson's rule: the closed-form integrals of the exact shapes below have no elementary
// antiderivative worth writing out; 2000 panels give 1e-12 relative accuracy on these smooth
// integrands.
inline double simpson(const std::function<double(double)>& f, double a, double b, int n = 2000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4 : 2) * f(a + k * h);
  return s * h / 3;
}

// Area of one half of a two-centred arch bounded by the axis: the ring ri <= r <= re about a
// centre e from the axis (on the far side), between the springing ray at angle `spring` from the
// horizontal through the centre (pi: horizontal springing, pi/2 + alpha/2 for embrace alpha) and
// the axis. In polar coordinates about the centre the axis is cos(phi) = -e/r.
inline double pointed_half_area(double e, double ri, double re, double spring) {
  return simpson([&](double r) { return r * (spring - std::acos(-e / r)); }, ri, re);
}

}  // namespace masonry::test
