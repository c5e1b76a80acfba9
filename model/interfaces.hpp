// Interfaces (joints) between blocks: the overlap segment of two collinear, opposite edges.
// Found once, in the initial configuration; both methods name joints by them.
#pragma once

#include <string>
#include <vector>

#include "model/case.hpp"

namespace masonry {

struct Interface {
  int i = -1, j = -1;  // blocks, i < j; the normal points from i into j
  Vec2 a{0, 0}, b{0, 0};  // endpoints A and B (initial configuration), B - A along the tangent
  Vec2 normal{0, 0};      // unit, out of block i
  double length() const { return (b - a).norm(); }
};

// Collinear (within `tol`, m), opposite, overlapping (by more than `tol`) edge pairs of distinct
// blocks, partial overlaps included; interfaces between two supports are skipped. Collinear
// pieces of the same block pair that touch are merged into one interface. A sorted sweep along
// the longer axis of the scene pairs edges, so the cost is far below quadratic for real scenes.
// The order is deterministic: by (i, j), then along the tangent.
std::vector<Interface> detect_interfaces(const Case& c, double tol);

// A joint corner's name, "BLOCK/BLOCK:A" (the joint's blocks i and j, corner 0 = A, 1 = B; an
// index outside the case reads "?"), as reports print it and `masonry check --hold` takes it.
std::string corner_name(const Case& c, int i, int j, int corner);

// Geometry predicates shared by validation and detection.
bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& poly);
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);
double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& poly);

}  // namespace masonry
