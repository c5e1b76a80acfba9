// Mechanism agreement: whether two runs move the same way over a checked interval of d, from the
// joints' relative motion weighted by the forces they carry (compare/README.md, "Mechanism
// agreement"). Threshold-free: a cosine between the two runs' weighted joint motions.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "compare/compare.hpp"
#include "model/energy.hpp"
#include "model/interfaces.hpp"

namespace masonry {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The relative displacement of a joint corner's two material copies: where the higher-indexed
// block's copy of p is, less where the lower-indexed block's copy is, in the lower block's own
// frame (its initial orientation), so a rigid motion of the pair (the supports' imposed motion
// carried along) gives none.
Vec2 corner_offset(const std::vector<Vec2>& c0, const std::vector<Pose>& poses, int lo, int hi, const Vec2& p) {
  const Pose& L = poses[size_t(lo)];
  const Vec2 rel = placed(c0[size_t(hi)], poses[size_t(hi)], p) - placed(c0[size_t(lo)], L, p);
  const double cs = std::cos(L.angle), sn = std::sin(L.angle);
  return Vec2(cs * rel.x() + sn * rel.y(), -sn * rel.x() + cs * rel.y());
}

// A run's poses, or their mirror image about x = xc with every block in its mirror's place: the
// run a symmetric structure would make with the mirror mechanism (material point p of block
// m(k) at the mirror of where block k's point M(p) is).
std::vector<Pose> poses_of(const StepRecord& s, const std::vector<int>* mirror, double xc) {
  if (!mirror) return s.poses;
  std::vector<Pose> out(s.poses.size());
  for (size_t k = 0; k < s.poses.size() && k < mirror->size(); ++k)
    out[size_t((*mirror)[k])] = {2 * xc - s.poses[k].x, s.poses[k].y, -s.poses[k].angle};
  return out;
}

// For every joint of run x, the joint of run a with the same blocks and end points (through the
// mirror image when `mirror` is given), -1 when a has none: the runs' joint numbering need not agree.
std::vector<int> joint_map(const RunResult& a, const RunResult& x, const std::vector<int>* mirror, double xc, double tol) {
  std::vector<int> out(x.joints.size(), -1);
  for (size_t k = 0; k < x.joints.size(); ++k) {
    const JointInfo& g = x.joints[k];
    int i = g.i, j = g.j;
    Vec2 p = g.a, q = g.b;
    if (mirror) {
      if (i < 0 || j < 0 || size_t(i) >= mirror->size() || size_t(j) >= mirror->size()) continue;
      i = (*mirror)[size_t(i)];
      j = (*mirror)[size_t(j)];
      p.x() = 2 * xc - p.x();
      q.x() = 2 * xc - q.x();
    }
    for (size_t m = 0; m < a.joints.size(); ++m) {
      const JointInfo& f = a.joints[m];
      const bool pair = (f.i == i && f.j == j) || (f.i == j && f.j == i);
      const bool ends = ((f.a - p).norm() <= tol && (f.b - q).norm() <= tol) || ((f.a - q).norm() <= tol && (f.b - p).norm() <= tol);
      if (pair && ends) {
        out[k] = int(m);
        break;
      }
    }
  }
  return out;
}

// The joint geometry of run a's joints: blocks ordered (lo < hi), the unit normal from lo towards
// hi and the tangent from corner A to B, initial configuration.
struct JointFrame {
  int lo = -1, hi = -1;
  Vec2 pa{0, 0}, pb{0, 0}, n{0, 1}, t{1, 0};
};

std::vector<JointFrame> frames_of(const Case& c, const RunResult& a) {
  std::vector<JointFrame> out;
  for (const JointInfo& ji : a.joints) {
    JointFrame f;
    f.lo = std::min(ji.i, ji.j);
    f.hi = std::max(ji.i, ji.j);
    f.pa = ji.a;
    f.pb = ji.b;
    const Vec2 ab = ji.b - ji.a;
    if (ab.norm() > 0) f.t = ab / ab.norm();
    f.n = Vec2(-f.t.y(), f.t.x());
    if (f.hi >= 0 && size_t(f.hi) < c.blocks.size() && (centroid(c.blocks[size_t(f.hi)].vertices) - 0.5 * (ji.a + ji.b)).dot(f.n) < 0) f.n = -f.n;
    out.push_back(f);
  }
  return out;
}

// One run's side of an interval: its joints' relative motion (both corners' offset increments,
// per joint of run a) between two records.
struct Side {
  std::vector<Vec2> da, db;  // per joint of a: corner A's and B's offset increment, m
  std::vector<double> rot;   // per joint of a: the hi block's turn relative to the lo block's, rad
  double largest = 0.0;      // m, the largest corner offset increment
};

Side side_of(const Case& c, const std::vector<JointFrame>& frames, const std::vector<Vec2>& c0, const StepRecord& s0, const StepRecord& s1,
             const std::vector<int>* mirror, double xc) {
  Side out;
  const std::vector<Pose> p0 = poses_of(s0, mirror, xc), p1 = poses_of(s1, mirror, xc);
  const size_t nb = c.blocks.size();
  for (const JointFrame& f : frames) {
    if (f.lo < 0 || size_t(f.hi) >= nb || p0.size() != nb || p1.size() != nb) {
      out.da.emplace_back(0, 0);
      out.db.emplace_back(0, 0);
      out.rot.push_back(0);
      continue;
    }
    out.da.push_back(corner_offset(c0, p1, f.lo, f.hi, f.pa) - corner_offset(c0, p0, f.lo, f.hi, f.pa));
    out.db.push_back(corner_offset(c0, p1, f.lo, f.hi, f.pb) - corner_offset(c0, p0, f.lo, f.hi, f.pb));
    out.rot.push_back((p1[size_t(f.hi)].angle - p1[size_t(f.lo)].angle) - (p0[size_t(f.hi)].angle - p0[size_t(f.lo)].angle));
    out.largest = std::max({out.largest, out.da.back().norm(), out.db.back().norm()});
  }
  return out;
}

// Adds each joint's normal force at record s of run x (over W) to `sum`, per joint of run a.
void add_forces(const StepRecord& s, const std::vector<int>& to_a, double W, std::vector<double>& sum, std::vector<int>& count) {
  if (s.forces.empty()) return;  // a record without forces (PRD's collapse configuration)
  std::vector<double> n(sum.size(), 0.0);
  for (const JointForce& f : s.forces)
    if (f.joint >= 0 && size_t(f.joint) < to_a.size() && to_a[size_t(f.joint)] >= 0 && std::isfinite(f.normal))
      n[size_t(to_a[size_t(f.joint)])] += std::max(0.0, f.normal) / W;
  for (size_t k = 0; k < sum.size(); ++k) {
    sum[k] += n[k];
    ++count[k];
  }
}

JointMotion motion_of(const Side& s, const JointFrame& f, size_t k) {
  JointMotion m;
  m.rotation = s.rot[k];
  m.open_a = s.da[k].dot(f.n);
  m.open_b = s.db[k].dot(f.n);
  m.slip = 0.5 * (s.da[k] + s.db[k]).dot(f.t);
  return m;
}

// One run's weighted motion: per joint of run a, four numbers in the joint's own frame, corner
// A's opening and slip, then corner B's, each times the joint's weight (a work scale, N m / W).
using Motion = std::vector<std::array<double, 4>>;

Motion weighted(const Side& s, const std::vector<JointFrame>& frames, const std::vector<double>& w) {
  Motion out(frames.size());
  for (size_t k = 0; k < frames.size(); ++k)
    out[k] = {w[k] * s.da[k].dot(frames[k].n), w[k] * s.da[k].dot(frames[k].t), w[k] * s.db[k].dot(frames[k].n), w[k] * s.db[k].dot(frames[k].t)};
  return out;
}

double dot(const Motion& u, const Motion& v) {
  double x = 0;
  for (size_t k = 0; k < u.size(); ++k)
    for (int q = 0; q < 4; ++q) x += u[k][size_t(q)] * v[k][size_t(q)];
  return x;
}

double dot(const std::array<double, 4>& u, const std::array<double, 4>& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2] + u[3] * v[3]; }

// `from`'s motion with each joint's motion moved to the joint within `shift` joints along its
// ring (ring_neighbours: the same side of the ring) where it best meets `to`'s: a hinge that
// sits one voussoir or course along from the other run's is the same mechanism (compare/README.md,
// "Hinges one joint apart"). A moved motion keeps each corner's opening at the corner on the
// same side, and its slip the same way along the ring: the slip's sign follows the joint's
// normal (lower- to higher-indexed block, reversed along the ring when the two joints' normals
// point apart) and the order of the corners.
Motion relocated(const Case& c, const RunResult& a, const std::vector<JointFrame>& frames, const Motion& from, const Motion& to, int shift) {
  Motion out(from.size(), {0, 0, 0, 0});
  for (size_t k = 0; k < from.size(); ++k) {
    const std::array<double, 4>& v = from[k];
    if (v == std::array<double, 4>{0, 0, 0, 0}) continue;
    size_t best = k;
    std::array<double, 4> moved = v;
    double gain = dot(to[k], v);
    for (const RingSpot& sp : ring_neighbours(c, a, int(k), 0, shift)) {
      if (sp.steps == 0) continue;
      const size_t j = size_t(sp.joint);
      const double along = frames[k].n.dot(frames[j].n) < 0 ? -1.0 : 1.0;  // the higher block lies the other way along the ring
      const double order = sp.corner == 0 ? 1.0 : -1.0;                    // k's A lands on j's B: the tangent turns round
      const double f = along * order;
      // Corner A's opening and slip go to the spot's corner, B's to the other.
      const std::array<double, 4> m =
          sp.corner == 0 ? std::array<double, 4>{v[0], f * v[1], v[2], f * v[3]} : std::array<double, 4>{v[2], f * v[3], v[0], f * v[1]};
      const double g = dot(to[j], m);
      if (g > gain) {
        gain = g;
        best = j;
        moved = m;
      }
    }
    for (int q = 0; q < 4; ++q) out[best][size_t(q)] += moved[size_t(q)];
  }
  return out;
}

double cosine(const Motion& u, const Motion& v) {
  const double uu = dot(u, u), vv = dot(v, v);
  return uu > 0 && vv > 0 ? std::clamp(dot(u, v) / std::sqrt(uu * vv), 0.0, 1.0) : std::numeric_limits<double>::quiet_NaN();
}

// The endpoints of one interval: each run's two records.
struct Ends {
  const StepRecord *a0 = nullptr, *a1 = nullptr, *b0 = nullptr, *b1 = nullptr;
};

MotionCheck check_interval(const Case& c, const RunResult& a, const RunResult& b, const Ends& e, const std::vector<int>& mirror, double xc,
                           double tol, int shift) {
  MotionCheck m;
  m.a_from = e.a0->d;
  m.a_to = e.a1->d;
  m.b_from = e.b0->d;
  m.b_to = e.b1->d;
  const std::vector<JointFrame> frames = frames_of(c, a);
  const std::vector<int> nth = pair_ordinals(a.joints);
  std::vector<Vec2> c0;
  for (const Block& blk : c.blocks) c0.push_back(centroid(blk.vertices));
  const double W = a.total_weight > 0 ? a.total_weight : b.total_weight > 0 ? b.total_weight : 1.0;
  // Motions below round-off of the coordinates are no motion (a PRD block carried rigidly by
  // its support moves by 1e-15 of the scene against it).
  const double floor = 1e-9 * std::max(1.0, scene_size(c));
  const Side sa = side_of(c, frames, c0, *e.a0, *e.a1, nullptr, xc);
  m.a_moves = sa.largest > floor;
  std::vector<int> ident(a.joints.size());
  std::iota(ident.begin(), ident.end(), 0);
  double best = -1.0;
  for (int mirrored = 0; mirrored < (mirror.empty() ? 1 : 2); ++mirrored) {
    const std::vector<int>* mp = mirrored ? &mirror : nullptr;
    const Side sb = side_of(c, frames, c0, *e.b0, *e.b1, mp, xc);
    if (!mirrored) m.b_moves = sb.largest > floor;
    if (!m.a_moves || !m.b_moves) continue;
    // The weights: each joint's normal force over W, averaged over both runs' records at both
    // ends (b's joints mapped onto a's, through the mirror when b is mirrored).
    const std::vector<int> b_to_a = joint_map(a, b, mp, xc, tol);
    std::vector<double> w(frames.size(), 0.0);
    std::vector<int> count(frames.size(), 0);
    for (const StepRecord* s : {e.a0, e.a1}) add_forces(*s, ident, W, w, count);
    for (const StepRecord* s : {e.b0, e.b1}) add_forces(*s, b_to_a, W, w, count);
    for (size_t k = 0; k < w.size(); ++k) w[k] = count[k] ? w[k] / count[k] : 0.0;
    const Motion u = weighted(sa, frames, w), v = weighted(sb, frames, w);
    const double same = cosine(u, v);
    if (!std::isfinite(same)) continue;  // only unloaded joints move
    // Along rings, a hinge may sit `shift` joints from the other run's: each run's motion moved
    // onto the other's, whichever meets it better.
    Motion uu = u, vv = v;
    double agreement = same;
    if (shift > 0) {
      const Motion v_on_u = relocated(c, a, frames, v, u, shift), u_on_v = relocated(c, a, frames, u, v, shift);
      const double x = cosine(u, v_on_u), y = cosine(u_on_v, v);
      if (x > agreement) agreement = x, vv = v_on_u, uu = u;
      if (y > agreement) agreement = y, uu = u_on_v, vv = v;
    }
    if (agreement <= best) continue;
    best = agreement;
    m.agreement = agreement;
    m.same_joints = same;
    m.mirror = mirrored;
    // Where the two motions differ: each joint's share of the squared difference of the unit
    // vectors (which sums to 2 - 2 cos).
    std::vector<std::pair<double, size_t>> share;
    double total = 0;
    const double nu = std::sqrt(dot(uu, uu)), nv = std::sqrt(dot(vv, vv));
    for (size_t k = 0; k < frames.size(); ++k) {
      double e2 = 0;
      for (int q = 0; q < 4; ++q) e2 += std::pow(uu[k][size_t(q)] / nu - vv[k][size_t(q)] / nv, 2);
      total += e2;
      share.push_back({e2, k});
    }
    std::sort(share.begin(), share.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    m.differ.clear();
    // 2 - 2 cos below 1e-6: the motions are the same to round-off, and no joint differs.
    for (size_t n = 0; n < share.size() && n < 3 && total > 1e-6; ++n) {
      const size_t k = share[n].second;
      MotionDiff d;
      d.joint = int(k);
      d.label = joint_name(c, a.joints[k].i, a.joints[k].j, nth[k]);
      d.share = share[n].first / total;
      d.weight = w[k];
      d.a = motion_of(sa, frames[k], k);
      d.b = motion_of(sb, frames[k], k);
      m.differ.push_back(d);
    }
  }
  return m;
}

}  // namespace

std::optional<StepRecord> collapse_state(const RunResult& r) {
  if (r.status != RunStatus::collapse) return std::nullopt;
  // The DEM records the state its last hold failed in, past the capacity.
  const double eps = 1e-9 * std::max(1.0, std::abs(r.capacity));
  for (auto it = r.steps.rbegin(); it != r.steps.rend(); ++it)
    if (it->d > r.capacity + eps && !is_equilibrium(r, *it)) return *it;
  // PRD writes the configuration it found unbounded, and that configuration moved along its
  // collapse mechanism by up to one step (moved_poses): the latter where it has it, since the
  // last step's own motion may move no joint at all (a block carried by its slab to its tipping
  // tilt), and otherwise the former: where the last step's mechanism took it.
  if (r.collapse && !r.steps.empty() && std::isfinite(r.collapse->d)) {
    const size_t nb = r.steps.front().poses.size();
    const std::vector<Pose>& poses = r.collapse->moved_poses.size() == nb ? r.collapse->moved_poses : r.collapse->poses;
    if (!poses.empty() && poses.size() == nb) {
      StepRecord s;
      s.index = -1;
      s.d = r.collapse->d;
      s.poses = poses;
      return s;
    }
  }
  return std::nullopt;
}

SlipCheck slip_check(const Case& c, const RunResult& a, const RunResult& b, double to, double min_gap) {
  SlipCheck out;
  out.to = to;
  const std::vector<const StepRecord*> ra = stable_records(a), rb = stable_records(b);
  if (ra.empty() || rb.empty()) return out;
  const std::vector<JointFrame> frames = frames_of(c, a);
  std::vector<Vec2> c0;
  for (const Block& blk : c.blocks) c0.push_back(centroid(blk.vertices));
  const StepRecord *ea = record_at(ra, to), *eb = record_at(rb, to);
  out.a_to = ea->d;
  out.b_to = eb->d;
  const Side sa = side_of(c, frames, c0, *ra.front(), *ea, nullptr, 0.0), sb = side_of(c, frames, c0, *rb.front(), *eb, nullptr, 0.0);
  // Along the joint at the corner that opened less: the one still in contact. Where that one
  // opened by more than min_gap too, the joint came apart, and its travel is no slip (NaN).
  const auto slip = [&](const Side& s, size_t k) {
    const JointFrame& f = frames[k];
    const Vec2& x = s.da[k].dot(f.n) <= s.db[k].dot(f.n) ? s.da[k] : s.db[k];
    return x.dot(f.n) > min_gap ? std::numeric_limits<double>::quiet_NaN() : std::abs(x.dot(f.t));
  };
  const std::vector<int> nth = pair_ordinals(a.joints);
  for (size_t k = 0; k < frames.size(); ++k) {
    if (frames[k].lo < 0 || size_t(frames[k].hi) >= c.blocks.size()) continue;
    const double x = slip(sa, k), y = slip(sb, k);
    const std::string label = joint_name(c, a.joints[k].i, a.joints[k].j, nth[k]);
    if (std::isfinite(x) && !(x <= out.largest_a.a)) out.largest_a = {int(k), label, x, y};
    if (std::isfinite(y) && !(y <= out.largest_b.b)) out.largest_b = {int(k), label, x, y};
  }
  return out;
}

std::vector<MotionCheck> mechanism_checks(const Case& c, const RunResult& a, const RunResult& b, const std::vector<double>& ds, int shift) {
  std::vector<MotionCheck> out;
  const std::vector<const StepRecord*> ra = stable_records(a), rb = stable_records(b);
  if (ra.empty() || rb.empty()) return out;
  const std::vector<int> mirror = mirror_blocks(c);
  const Bounds box = scene_bounds(c);
  const double xc = 0.5 * (box.lo.x() + box.hi.x());
  const double tol = 1e-6 * std::max(1.0, scene_size(c));
  double from = 0.0;
  for (double to : ds) {
    if (!(to > from)) continue;
    MotionCheck m = check_interval(c, a, b, {record_at(ra, from), record_at(ra, to), record_at(rb, from), record_at(rb, to)}, mirror, xc, tol, shift);
    m.from = from;
    m.to = to;
    out.push_back(std::move(m));
    from = to;
  }
  // The mechanism each run collapses by, from its last equilibrium to its collapse state.
  const std::optional<StepRecord> ca = collapse_state(a), cb = collapse_state(b);
  if (ca && cb) {
    MotionCheck m = check_interval(c, a, b, {ra.back(), &*ca, rb.back(), &*cb}, mirror, xc, tol, shift);
    m.collapse = true;
    m.from = ra.back()->d;
    m.to = kNaN;
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace masonry
