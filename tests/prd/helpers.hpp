// Independent checks on PRD output: equilibrium of every free block recomputed from the
// reported forces, poses and the case's own weights (nothing taken from the solver's internals).
#pragma once

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry::testing {

inline Eigen::Matrix2d rotation(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// Largest force (N) and moment (N m) residual over the free blocks of one step.
struct Residual {
  double force = 0, moment = 0;
};

inline Residual equilibrium_residual(const Case& c, const RunResult& r, const StepRecord& s) {
  const size_t nb = c.blocks.size();
  std::vector<Vec2> f(nb, Vec2(0, 0));
  std::vector<double> m(nb, 0.0);
  std::vector<Vec2> cen(nb);
  for (size_t b = 0; b < nb; ++b) cen[b] = Vec2(s.poses[b].x, s.poses[b].y);
  for (size_t b = 0; b < nb; ++b) {
    if (c.blocks[b].support) continue;
    f[b].y() -= block_mass(c.blocks[b]) * c.gravity;
  }
  for (const Load& l : c.loads) {
    const Pose& p = s.poses[l.block];
    const Vec2 x = cen[l.block] + rotation(p.angle) * (l.point - centroid(c.blocks[l.block].vertices));
    f[l.block] += l.force;
    m[l.block] += cross(x - cen[l.block], l.force);
  }
  for (const JointForce& jf : s.forces) {
    const JointInfo& ji = r.joints[jf.joint];
    const Vec2 t(-jf.n.y(), jf.n.x());
    const Vec2 on_j = jf.normal * jf.n + jf.shear * t;
    for (int side = 0; side < 2; ++side) {
      const int b = side == 0 ? ji.i : ji.j;
      const Vec2 F = side == 0 ? Vec2(-on_j) : on_j;
      f[b] += F;
      const Vec2 arm = jf.point - cen[b];
      m[b] += cross(arm, F);
    }
  }
  Residual res;
  for (size_t b = 0; b < nb; ++b) {
    if (c.blocks[b].support) continue;
    res.force = std::max(res.force, f[b].norm());
    res.moment = std::max(res.moment, std::abs(m[b]));
  }
  return res;
}

// The open corners of a step as a sorted set of "joint:corner" strings.
inline std::set<std::string> open_set(const StepRecord& s) {
  std::set<std::string> out;
  for (const OpenCorner& o : s.open_corners) out.insert(std::to_string(o.joint) + (o.corner == 0 ? "A" : "B"));
  return out;
}

// Joints with exactly one open corner: hinges.
inline int hinge_count(const StepRecord& s) {
  std::vector<int> n;
  for (const OpenCorner& o : s.open_corners) {
    if (static_cast<int>(n.size()) <= o.joint) n.resize(o.joint + 1, 0);
    ++n[o.joint];
  }
  int h = 0;
  for (int k : n) h += k == 1;
  return h;
}

// Distinct consecutive mechanisms of a run and the d at which each starts.
struct Mechanism {
  double d;
  std::set<std::string> open;
};
inline std::vector<Mechanism> mechanism_sequence(const RunResult& r) {
  std::vector<Mechanism> seq;
  for (const StepRecord& s : r.steps) {
    if (s.index == 0) continue;
    auto o = open_set(s);
    if (seq.empty() || seq.back().open != o) seq.push_back({s.d, o});
  }
  return seq;
}

}  // namespace masonry::testing
