// Interfaces (joints) between blocks: the overlap segment of two collinear, opposite edges.
// Found once, in the initial configuration; both methods name joints by them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/case.hpp"

namespace masonry {

struct Interface {
  int i = -1, j = -1;     // blocks, i < j; the normal points from i into j
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
// index outside the case reads "?"), as reports print it and `--hold` takes it. Two blocks may
// meet at more than one joint (a block seated in a support's notch touches its floor and both
// sides): the joint that is `nth` between them (0 the first, in the joints' order) has the
// corners C and D, E and F, and so on (past Z: A14, B14, the joint's number after the letter).
std::string corner_name(const Case& c, int i, int j, int corner, int nth = 0);
// The letters corner_name gives corner `corner` (0 or 1) of the `nth` joint between two blocks.
std::string corner_letter(int corner, int nth);
// A joint's name: "BLOCK/BLOCK", and for a further joint between the same blocks its corners'
// letters after a colon, "base/post:CD".
std::string joint_name(const Case& c, int i, int j, int nth = 0);

// For each joint of `joints` (anything with block indices i and j), how many joints before it
// join the same two blocks: corner_name's `nth`.
template <class Joint>
std::vector<int> pair_ordinals(const std::vector<Joint>& joints);

// The normal gap at one joint corner, m, from the two blocks' copies of it (world frame: pi on
// block i, pj on block j) and their outward joint normals (ni of i, nj of j): the smaller of the
// two copies' stand-off from the other block's face (negative: overlap). A corner is open only
// when neither block touches the other there. A joint corner is a corner of at least one of its
// blocks; where the other block's face runs on past it (a pier's top under a voussoir), that
// block's copy is a point of its face, which slides away under the turning corner as the joint
// slips, and its stand-off from the turned face is slip x sin(theta), not an opening: 12-25 um at
// the settlement cathedral's springing hinge with joints 30 times stiffer (0.2-0.3 mm of slip at
// 60-80 mrad) while the voussoir's corner pressed into the pier by 2.7 um (dem/README.md,
// "Hinges: measured from the settled state"). A real opening stands both copies off by the same
// amount to within that term.
double corner_gap(const Vec2& pi, const Vec2& ni, const Vec2& pj, const Vec2& nj);

// Geometry predicates shared by validation and detection.
bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& poly);
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);
double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& poly);

template <class Joint>
std::vector<int> pair_ordinals(const std::vector<Joint>& joints) {
  std::vector<int> out(joints.size(), 0);
  std::unordered_map<std::uint64_t, int> seen;
  for (size_t k = 0; k < joints.size(); ++k) {
    const auto lo = std::uint32_t(std::min(joints[k].i, joints[k].j)), hi = std::uint32_t(std::max(joints[k].i, joints[k].j));
    out[k] = seen[(std::uint64_t(lo) << 32) | hi]++;
  }
  return out;
}

}  // namespace masonry
