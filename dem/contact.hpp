// Contact geometry of the DEM in double precision: convex decomposition of blocks and the
// polygon-polygon manifold. The manifold is Box2D's b2CollidePolygons algorithm (separating axis
// with a preferred reference face, incident edge, clipping to the reference face's side planes)
// ported to double, because joint overlaps (1e-7..1e-6 m) are below float resolution at scene
// coordinates (see shared/docs/dem-method.md, "Precision"). Units: m.
#pragma once

#include <array>
#include <vector>

#include "model/case.hpp"

namespace masonry::dem {

// Box2D's limit on polygon vertices (b2_maxPolygonVertices); checked against box2d in contact.cpp.
constexpr int kMaxPieceVertices = 8;

// Splits a simple polygon (counter-clockwise) into convex pieces of at most kMaxPieceVertices
// vertices each: the polygon itself when it already qualifies, else an ear-clipping triangulation
// whose triangles are merged greedily while the union stays convex and small enough.
// Straight-angle vertices (a drawing's vertex in the middle of an edge) are dropped first.
std::vector<std::vector<Vec2>> convex_pieces(const std::vector<Vec2>& poly);

// The polygon without its straight-angle vertices (collinear neighbours, same direction): the
// faces the contacts see.
std::vector<Vec2> without_straight_vertices(const std::vector<Vec2>& p);

struct ManifoldPoint {
  Vec2 point{0, 0};         // midway between the two surfaces, world frame
  double separation = 0.0;  // < 0: overlap
  int slot = 0;             // which end of the clipped incident edge (0: its first vertex's side)
};

struct Manifold {
  int count = 0;             // 0, 1 or 2 points with separation <= 0
  Vec2 normal{0, 0};         // unit, from polygon A into polygon B
  bool flip = false;         // the reference face belongs to B
  int ref_edge = -1;         // reference edge index (in the reference polygon)
  int inc_edge = -1;         // incident edge index (in the other polygon)
  double clip_length = 0.0;  // length of the incident edge clipped to the reference face, m
  std::array<ManifoldPoint, 2> points;
};

// Polygons as counter-clockwise world vertices with outward unit edge normals (edge i runs from
// vertex i to vertex i+1). Returns false (count 0) when the polygons are apart.
bool collide(const Vec2* va, const Vec2* na, int ca, const Vec2* vb, const Vec2* nb, int cb, Manifold& m);

// What the separating-axis search of the last call decided, so the next call on the same pair can
// skip the search while it provably comes out the same (temporal coherence: between two DEM
// cycles the blocks move by nanometres, and the search is most of the cost of a contact).
struct SatCache {
  enum State : unsigned char { kNone, kApartA, kApartB, kTouching };
  State state = kNone;
  bool flip = false;
  unsigned char edge_a = 0, edge_b = 0, inc = 0;  // best edges of A and B, incident edge
  // How much more relative motion (m, in the units of `motion` below) the cached state can take
  // before it might change: touching, the decisions (best edges, flip, incident edge); apart,
  // the separation itself.
  double slack = 0.0;
  // Touching: how much more relative motion both separations (of the best edges of A and of B)
  // can take and still be <= 0, so the pair is still touching without computing them.
  double touch = 0.0;
};

// Same result as collide(), bit for bit. `motion` bounds how much any separation n_i . (w_j - u_i)
// between an edge of one polygon and a vertex of the other can have changed since the last call
// on this pair: |dx_a| + |dth_a| r_a + |dx_b| + |dth_b| r_b + (|dth_a| + |dth_b|) L, r the
// distance of the vertices from their block's centre of rotation and L the largest distance
// between a vertex of A and a vertex of B (see DemModel's step()). `lever` is that L, which also
// converts the incident-edge choice (a dot product of unit normals) into a length.
bool collide_cached(const Vec2* va, const Vec2* na, int ca, const Vec2* vb, const Vec2* nb, int cb, double motion, double lever, SatCache& cache,
                    Manifold& m);

}  // namespace masonry::dem
