// Contact geometry: the double-precision manifold against Box2D's b2CollidePolygons, convex
// decomposition of blocks Box2D cannot take as one polygon, and a compound block at rest.
#include <box2d/b2_collision.h>
#include <box2d/b2_polygon_shape.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dem/contact.hpp"
#include "dem/dem.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

struct Poly {
  std::vector<Vec2> v, n;
};

Poly place(const std::vector<Vec2>& local, const Vec2& x, double th) {
  Poly p;
  const double c = std::cos(th), s = std::sin(th);
  for (size_t i = 0; i < local.size(); ++i) {
    const Vec2& a = local[i];
    p.v.push_back(x + Vec2(c * a.x() - s * a.y(), s * a.x() + c * a.y()));
  }
  for (size_t i = 0; i < p.v.size(); ++i) {
    const Vec2 e = p.v[(i + 1) % p.v.size()] - p.v[i];
    p.n.push_back(Vec2(e.y(), -e.x()).normalized());
  }
  return p;
}

b2PolygonShape shape(const std::vector<Vec2>& local) {
  b2Vec2 pts[8];
  for (size_t i = 0; i < local.size(); ++i) pts[i].Set(static_cast<float>(local[i].x()), static_cast<float>(local[i].y()));
  b2PolygonShape s;
  s.Set(pts, static_cast<int32>(local.size()));
  s.m_radius = 0;
  return s;
}

TEST(DemGeometry, ManifoldMatchesBox2dWhereFloatSuffices) {
  // Overlaps of millimetres near the origin, where float is accurate to ~1e-7 m.
  const std::vector<Vec2> box = {Vec2(-0.2, -0.1), Vec2(0.2, -0.1), Vec2(0.2, 0.1), Vec2(-0.2, 0.1)};
  const std::vector<Vec2> tri = {Vec2(-0.15, -0.1), Vec2(0.15, -0.1), Vec2(0.0, 0.15)};
  struct Pose2 {
    double x, y, th;
  };
  const Pose2 poses[] = {{0.05, 0.198, 0.0}, {0.1, 0.195, 0.05}, {-0.3, 0.19, -0.1}, {0.0, 0.18, 3.0}, {0.39, 0.0, 1.5}};
  int compared = 0;
  for (const Pose2& q : poses) {
    const Poly A = place(box, Vec2(0, 0), 0), B = place(tri, Vec2(q.x, q.y), q.th);
    dem::Manifold m;
    dem::collide(A.v.data(), A.n.data(), 4, B.v.data(), B.n.data(), 3, m);
    b2Manifold bm;
    b2Transform xa, xb;
    xa.SetIdentity();
    xb.Set(b2Vec2(static_cast<float>(q.x), static_cast<float>(q.y)), static_cast<float>(q.th));
    const b2PolygonShape sa = shape(box), sb = shape(tri);
    b2CollidePolygons(&bm, &sa, xa, &sb, xb);
    ASSERT_EQ(m.count, bm.pointCount) << "pose " << q.x << " " << q.y << " " << q.th;
    if (m.count == 0) continue;
    ++compared;
    b2WorldManifold wm;
    wm.Initialize(&bm, xa, 0, xb, 0);
    EXPECT_NEAR(m.normal.x(), wm.normal.x, 1e-5);
    EXPECT_NEAR(m.normal.y(), wm.normal.y, 1e-5);
    EXPECT_EQ(m.flip, bm.type == b2Manifold::e_faceB);
    for (int i = 0; i < m.count; ++i) {
      // Box2D's world point is midway between the surfaces too (zero radii).
      bool found = false;
      for (int k = 0; k < bm.pointCount; ++k)
        if (std::abs(m.points[i].point.x() - wm.points[k].x) < 1e-5 && std::abs(m.points[i].point.y() - wm.points[k].y) < 1e-5) {
          found = true;
          EXPECT_NEAR(m.points[i].separation, wm.separations[k], 1e-5);
        }
      EXPECT_TRUE(found) << "point " << i;
    }
  }
  EXPECT_GE(compared, 4);
}

TEST(DemGeometry, JointOverlapOfAMicronFarFromTheOrigin) {
  // Where float cannot resolve it (see dem-method.md): two boxes at (10, 20), overlap 1e-7 m.
  const std::vector<Vec2> box = {Vec2(-0.2, -0.1), Vec2(0.2, -0.1), Vec2(0.2, 0.1), Vec2(-0.2, 0.1)};
  const Poly A = place(box, Vec2(10, 20), 0), B = place(box, Vec2(10, 20.2 - 1e-7), 0);
  dem::Manifold m;
  ASSERT_TRUE(dem::collide(A.v.data(), A.n.data(), 4, B.v.data(), B.n.data(), 4, m));
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -1e-7, 1e-12);
  EXPECT_NEAR(m.clip_length, 0.4, 1e-12);
  EXPECT_NEAR(m.normal.y(), 1.0, 1e-15);
}

double area(const std::vector<std::vector<Vec2>>& pieces) {
  double a = 0;
  for (const auto& p : pieces) {
    EXPECT_GT(signed_area(p), 0);
    EXPECT_LE(p.size(), static_cast<size_t>(dem::kMaxPieceVertices));
    a += signed_area(p);
  }
  return a;
}

TEST(DemGeometry, ConvexPieces) {
  const std::vector<Vec2> L = {Vec2(0, 0), Vec2(0.6, 0), Vec2(0.6, 0.2), Vec2(0.2, 0.2), Vec2(0.2, 0.6), Vec2(0, 0.6)};
  const auto pl = dem::convex_pieces(L);
  EXPECT_GE(pl.size(), 2u);
  EXPECT_NEAR(area(pl), signed_area(L), 1e-12);
  std::vector<Vec2> circle;
  for (int k = 0; k < 20; ++k) circle.push_back(Vec2(std::cos(k * M_PI / 10), std::sin(k * M_PI / 10)));
  const auto pc = dem::convex_pieces(circle);
  EXPECT_GE(pc.size(), 3u);
  EXPECT_NEAR(area(pc), signed_area(circle), 1e-12);
  const std::vector<Vec2> quad = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  EXPECT_EQ(dem::convex_pieces(quad).size(), 1u);
}

TEST(DemGeometry, CompoundBlockRestsWithItsWeight) {
  // An L-shaped block (two convex pieces) on the slab: the reaction is its weight, applied at
  // its centroid's abscissa.
  Case c = test::slab_case();
  Block b;
  b.id = "L";
  b.vertices = {Vec2(-0.3, 0), Vec2(0.3, 0), Vec2(0.3, 0.1), Vec2(-0.2, 0.1), Vec2(-0.2, 0.5), Vec2(-0.3, 0.5)};
  b.density = 2000;
  c.blocks.push_back(b);
  c.dem.hold_time = 2.0;
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.steps.size(), 1u);
  const StepRecord& s = r.steps[0];
  ASSERT_TRUE(s.settled.value_or(false));
  const double W = block_mass(b) * c.gravity;
  EXPECT_NEAR(s.reactions[0].force.y(), W, 1e-3 * W);
  EXPECT_NEAR(s.reactions[0].force.x(), 0, 1e-3 * W);
  // Moment about the slab centroid (0, -0.05) of an upward force W at x = xc: W xc.
  const double xc = centroid(b.vertices).x();
  EXPECT_NEAR(s.reactions[0].moment, W * xc, 2e-3 * W * std::abs(xc));
  ASSERT_EQ(s.forces.size(), 1u);
  EXPECT_NEAR(s.forces[0].point.x(), xc, 1e-3);
}

// Vertices in the middle of an edge (drawings put them where two blocks meet one edge) change
// neither the body nor its contacts: the tilting block with such vertices on its base, its sides
// and the slab's top topples where the plain block does, at atan(b/h) within the bracket and the
// soft joints' elastic lean (tests/dem/tilt_test.cpp).
TEST(DemGeometry, StraightAngleVerticesChangeNothing) {
  const double b = 0.2, h = 0.4;
  Case plain = test::tilt_case(b, h, 35);
  Case marked = plain;
  marked.blocks[0].vertices = {Vec2(-0.6, -0.1), Vec2(0.6, -0.1), Vec2(0.6, 0), Vec2(0.05, 0), Vec2(0, 0), Vec2(-0.6, 0)};
  marked.blocks[1].vertices = {Vec2(-0.1, 0),  Vec2(0, 0),   Vec2(0.1, 0),    Vec2(0.1, 0.2),
                               Vec2(0.1, 0.4), Vec2(0, 0.4), Vec2(-0.1, 0.4), Vec2(-0.1, 0.2)};
  validate_geometry(marked);
  EXPECT_EQ(dem::convex_pieces(marked.blocks[1].vertices).front().size(), 4u);
  const RunResult r0 = test::tilt_run(plain), r1 = test::tilt_run(marked);
  ASSERT_EQ(r0.status, RunStatus::collapse) << r0.message;
  ASSERT_EQ(r1.status, RunStatus::collapse) << r1.message;
  EXPECT_NEAR(r1.capacity, std::atan(b / h), 2e-3);
  EXPECT_NEAR(r1.capacity, r0.capacity, 0.01 * plain.motion.step);
}

// Two blocks side by side on one slab edge, the slab with a vertex where they meet and each block
// with one in the middle of its base: each stands on its whole base, its weight carried under its
// centroid.
TEST(DemGeometry, BlocksMeetingOneEdgeStandOnTheirWholeBase) {
  Case c = test::slab_case();
  c.blocks[0].vertices = {Vec2(-0.6, -0.1), Vec2(0.6, -0.1), Vec2(0.6, 0), Vec2(0, 0), Vec2(-0.6, 0)};
  for (double x0 : {-0.3, 0.0}) {
    Block k;
    k.id = x0 < 0 ? "left" : "right";
    k.vertices = {Vec2(x0, 0), Vec2(x0 + 0.15, 0), Vec2(x0 + 0.3, 0), Vec2(x0 + 0.3, 0.4), Vec2(x0, 0.4)};
    k.density = 2000;
    c.blocks.push_back(k);
  }
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.steps.size(), 1u);
  const StepRecord& s = r.steps[0];
  ASSERT_TRUE(s.settled.value_or(false)) << r.message;
  const double W = block_mass(c.blocks[1]) * c.gravity;
  EXPECT_NEAR(s.reactions[0].force.y(), 2 * W, 1e-3 * W);
  int on_slab = 0;
  for (const JointForce& f : s.forces) {
    const JointInfo& J = r.joints[f.joint];
    if (J.i != 0 && J.j != 0) continue;  // the joint between the two blocks
    const int blk = J.i == 0 ? J.j : J.i;
    EXPECT_NEAR(f.normal, W, 1e-3 * W) << c.blocks[blk].id;
    EXPECT_NEAR(f.point.x(), centroid(c.blocks[blk].vertices).x(), 1e-3) << c.blocks[blk].id;
    ++on_slab;
  }
  EXPECT_EQ(on_slab, 2);
}

TEST(DemGeometry, CachedManifoldIsCollidesAlongRandomPaths) {
  // The cache (dem::collide_cached) reuses the separating-axis decisions of the last call while
  // the motion since provably cannot have changed them, and skips a pair found apart while the
  // motion cannot have closed its gap: the manifold must be collide()'s, bit for bit, at every
  // step of a path that approaches, touches, slides, turns and separates, with the motion bound
  // the model uses (|dx| + |dy| + |dth| r per block, plus the turns times the lever).
  const std::vector<Vec2> box = {Vec2(-0.2, -0.1), Vec2(0.2, -0.1), Vec2(0.2, 0.1), Vec2(-0.2, 0.1)};
  const std::vector<Vec2> quad = {Vec2(-0.18, -0.1), Vec2(0.16, -0.1), Vec2(0.2, 0.08), Vec2(-0.15, 0.1)};
  double r_a = 0, r_b = 0;
  for (const Vec2& v : box) r_a = std::max(r_a, v.norm());
  for (const Vec2& v : quad) r_b = std::max(r_b, v.norm());
  const double lever = 2.5 * (r_a + r_b);
  std::mt19937 rng(12);
  std::normal_distribution<double> gauss(0.0, 1.0);
  long long compared = 0, touching = 0;
  for (int path = 0; path < 24; ++path) {
    const double step = std::pow(10.0, -8 + 4 * (path % 3) / 2.0);  // 1e-8, 1e-6, 1e-4 m
    const int n = 3000;
    // B slides across A's top face (y = 0.1) from beyond one end to beyond the other, rocking by
    // up to 0.9 rad (so its incident edge changes): its lowest corner starts some 1e-4 m above
    // the face, sinks 1e-4 m into it by mid-path and rises again, so the pair goes from apart to
    // touching on a corner, on a face, on another corner, and apart. Jitter of the step's size in
    // every coordinate, A's included.
    const double g0 = 1e-4 * std::abs(gauss(rng)), x0 = 0.35 + 0.02 * gauss(rng);
    Vec2 xa(0, 0), xb(-x0, 0.3);
    double tha = 0, thb = 0;
    dem::SatCache cache;
    for (int k = 0; k <= n; ++k) {
      const Vec2 xa0 = xa, xb0 = xb;
      const double tha0 = tha, thb0 = thb;
      const double u = static_cast<double>(k) / n, f = std::abs(1.0 - 2.0 * u);  // f: 1 -> 0 -> 1
      thb = 0.9 * std::sin(2 * M_PI * u) + 0.1 * step * gauss(rng);
      double low = INFINITY;  // B's lowest vertex below its centre at this turn
      for (const Vec2& v : quad) low = std::min(low, std::sin(thb) * v.x() + std::cos(thb) * v.y());
      xb = Vec2(-x0 + 2 * x0 * u + step * gauss(rng), 0.1 - low + (-1e-4 + f * (g0 + 1e-4)) + step * gauss(rng));
      xa += 0.1 * step * Vec2(gauss(rng), gauss(rng));
      tha += 0.01 * step * gauss(rng);
      const Poly A = place(box, xa, tha), B = place(quad, xb, thb);
      const double turned_a = std::abs(tha - tha0), turned_b = std::abs(thb - thb0);
      const double motion =
          (xa - xa0).cwiseAbs().sum() + turned_a * r_a + (xb - xb0).cwiseAbs().sum() + turned_b * r_b + (turned_a + turned_b) * lever;
      dem::Manifold got, want;
      const bool hit = dem::collide_cached(A.v.data(), A.n.data(), 4, B.v.data(), B.n.data(), 4, motion, lever, cache, got);
      const bool hit_fresh = dem::collide(A.v.data(), A.n.data(), 4, B.v.data(), B.n.data(), 4, want);
      SCOPED_TRACE("path " + std::to_string(path) + ", step " + std::to_string(k));
      ASSERT_EQ(hit, hit_fresh);
      ASSERT_EQ(got.count, want.count);
      ++compared;
      if (!hit) continue;
      ++touching;
      ASSERT_EQ(got.normal, want.normal);
      ASSERT_EQ(got.flip, want.flip);
      ASSERT_EQ(got.ref_edge, want.ref_edge);
      ASSERT_EQ(got.inc_edge, want.inc_edge);
      ASSERT_EQ(got.clip_length, want.clip_length);
      for (int i = 0; i < got.count; ++i) {
        ASSERT_EQ(got.points[i].point, want.points[i].point);
        ASSERT_EQ(got.points[i].separation, want.points[i].separation);
        ASSERT_EQ(got.points[i].slot, want.points[i].slot);
      }
    }
  }
  // Both regimes were exercised: apart for much of each path, touching around its middle.
  EXPECT_GT(touching, compared / 10);
  EXPECT_LT(touching, compared * 9 / 10);
}

}  // namespace
