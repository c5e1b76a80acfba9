#include "compare/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "model/fields.hpp"
#include "model/interfaces.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt(double x, int prec = 4) {
  if (!std::isfinite(x)) return "n/a";
  std::ostringstream o;
  o.precision(prec);
  o << x;
  return o.str();
}

// Linear interpolation of y(x) at q on sorted x (clamped at the ends). At repeated x the later
// record wins, which is the state after any jump at that d.
double interp(const std::vector<double>& x, const std::vector<double>& y, double q) {
  if (x.empty()) return kNaN;
  if (q <= x.front()) return y.front();
  if (q >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), q);
  const size_t k = size_t(it - x.begin());
  const double x0 = x[k - 1], x1 = x[k];
  if (x1 <= x0) return y[k];
  const double t = (q - x0) / (x1 - x0);
  return y[k - 1] + t * (y[k] - y[k - 1]);
}

// Fewest ring steps from hinge h of run r to one of `others` (of the other run) at the same
// blocks and corner, -1 beyond kMaxHingeShift. Matching is by (unordered block pair, corner
// point), so the runs' joint numbering need not agree. With `mirror`, h's places are mapped
// through the mirror image about x = xc first.
int ring_distance(const Case& c, const RunResult& r, const Hinge& h, const std::vector<Hinge>& others, const std::vector<int>* mirror, double xc,
                  double tol) {
  for (const RingSpot& s : ring_neighbours(c, r, h.joint, h.corner, kMaxHingeShift)) {  // nearest first
    const JointInfo& ji = r.joints[size_t(s.joint)];
    int i = ji.i, j = ji.j;
    Vec2 p = s.corner == 0 ? ji.a : ji.b;
    if (mirror) {
      i = (*mirror)[size_t(i)];
      j = (*mirror)[size_t(j)];
      p.x() = 2 * xc - p.x();
    }
    for (const Hinge& g : others)
      if (((g.i == i && g.j == j) || (g.i == j && g.j == i)) && (g.point - p).norm() <= tol) return s.steps;
  }
  return -1;
}

// Two hinge sets agree within n joints when every hinge of either run has one of the other's
// within n: the set's shift is the largest distance, -1 when some hinge has none within
// kMaxHingeShift.
int worst_of(int worst, int n) { return worst < 0 || n < 0 ? -1 : std::max(worst, n); }

// The shift of two hinge sets as mirror images: a's places mirrored meet b's hinges, b's meet
// a's (the mirror map is its own inverse).
int mirrored_shift(const Case& c, const RunResult& ra, const RunResult& rb, const std::vector<Hinge>& a, const std::vector<Hinge>& b,
                   const std::vector<int>& mirror, double xc, double tol) {
  int worst = 0;
  for (const Hinge& h : a) worst = worst_of(worst, ring_distance(c, ra, h, b, &mirror, xc, tol));
  for (const Hinge& g : b) worst = worst_of(worst, ring_distance(c, rb, g, a, &mirror, xc, tol));
  return worst;
}

void bbox(const Case& c, Vec2& lo, Vec2& hi) {
  lo = Vec2(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  hi = -lo;
  for (const Block& b : c.blocks)
    for (const Vec2& v : b.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
}

// Why a comparison needs what `a` or `b` does not give ("DEM gives no reactions"), or empty.
std::string missing(const RunResult& a, const RunResult& b, const Comparison& k, const char* what,
                    const std::function<bool(const RunResult&)>& gives) {
  std::string who;
  if (!gives(a)) who = k.a.label;
  if (!gives(b)) who += (who.empty() ? "" : " and ") + k.b.label;
  return who.empty() ? "" : "not compared: " + who + " give" + (who.find(" and ") == std::string::npos ? "s" : "") + " no " + what;
}

RunSummary summarise(const RunResult& r, const std::string& label, int min_state_records) {
  RunSummary s;
  s.method = r.method;
  s.label = label.empty() ? method_label(r) : label;
  s.capacity = r.capacity;
  s.collapsed = r.collapsed;
  s.status = r.status;
  s.step = record_step(stable_records(r));
  s.time_s = r.timing.total_s;
  s.changes = mechanism_changes(r, min_state_records);
  return s;
}

ojson summary_json(const RunSummary& s) {
  ojson j;
  j["label"] = s.label;
  j["method"] = s.method;
  j["capacity"] = json_number(s.capacity);
  j["collapsed"] = s.collapsed;
  j["stopped"] = status_name(s.status);
  j["step"] = json_number(s.step);
  j["time_s"] = json_number(s.time_s);
  ojson ch = ojson::array();
  for (double d : s.changes) ch.push_back(json_number(d));
  j["mechanism_changes"] = ch;
  return j;
}

}  // namespace

std::vector<const StepRecord*> stable_records(const RunResult& r) {
  std::vector<const StepRecord*> out;
  const double cap = r.capacity;
  const double eps = 1e-9 * std::max(1.0, std::abs(cap));
  for (const StepRecord& s : r.steps) {
    if (!std::isfinite(s.d)) continue;
    if (!is_equilibrium(r, s)) continue;  // a DEM's failed state, even at d = 0
    if (std::isfinite(cap) && s.d > cap + eps) continue;
    if (!out.empty() && s.d < out.back()->d) continue;  // records run forward in d
    out.push_back(&s);
  }
  return out;
}

const StepRecord* record_at(const std::vector<const StepRecord*>& recs, double d) {
  const StepRecord* best = recs.empty() ? nullptr : recs.front();
  const double eps = 1e-9 * std::max(1.0, std::abs(d));
  for (const StepRecord* s : recs)
    if (s->d <= d + eps) best = s;
  return best;
}

double record_step(const std::vector<const StepRecord*>& recs) { return recs.size() >= 2 ? recs[1]->d - recs[0]->d : 0.0; }

namespace {

// The corners of record s open wider than min_gap, by block ids and corner (joint numbers may
// differ between runs), with their gaps.
std::map<std::string, double> wide_open(const Case& c, const RunResult& r, const StepRecord& s, double min_gap) {
  std::map<std::string, double> out;
  const std::vector<int> nth = pair_ordinals(r.joints);
  for (const OpenCorner& o : s.open_corners) {
    if (!(o.gap > min_gap) || o.joint < 0 || o.joint >= int(r.joints.size())) continue;
    const JointInfo& ji = r.joints[o.joint];
    out[corner_name(c, ji.i, ji.j, o.corner, nth[size_t(o.joint)])] = o.gap;
  }
  return out;
}

std::vector<std::string> only_in(const std::map<std::string, double>& x, const std::map<std::string, double>& y) {
  std::vector<std::string> out;
  for (const auto& [k, gap] : x)
    if (!y.count(k)) out.push_back(k + " (" + fmt(gap * 1e3, 3) + " mm)");
  return out;
}

}  // namespace

std::optional<Parting> hinges_part(const Case& c, const RunResult& a, const RunResult& b, double min_gap) {
  const std::vector<const StepRecord*> ra = stable_records(a), rb = stable_records(b);
  if (ra.empty() || rb.empty()) return std::nullopt;
  const double end = std::min(ra.back()->d, rb.back()->d);
  std::optional<Parting> p;
  int apart = 0;  // records since p
  for (const StepRecord* s : ra) {
    if (s->d > end) break;
    // The settled state is not a mechanism: a DEM records its absolute elastic gaps there
    // (dem.hpp, DemModel::record), the increments their growth beyond them.
    if (s->index == 0) continue;
    const StepRecord* t = record_at(rb, s->d);
    const auto x = wide_open(c, a, *s, min_gap), y = wide_open(c, b, *t, min_gap);
    if (x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin(), [](const auto& u, const auto& v) { return u.first == v.first; })) {
      p.reset();  // together again: an earlier difference was not a parting
      apart = 0;
      continue;
    }
    if (!p) {
      p.emplace();
      p->d = s->d;
      p->only_a = only_in(x, y);
      p->only_b = only_in(y, x);
    }
    p->end_d = s->d;
    p->end_only_a = only_in(x, y);
    p->end_only_b = only_in(y, x);
    ++apart;
  }
  // A difference at the last record alone is the approach to collapse seen at slightly
  // different d, not another mechanism.
  if (apart < 2) return std::nullopt;
  return p;
}

double settled_gap(const RunResult& r) {
  double g = 0.0;
  if (!r.steps.empty() && is_equilibrium(r, r.steps.front()))
    for (const OpenCorner& o : r.steps.front().open_corners)
      if (std::isfinite(o.gap)) g = std::max(g, o.gap);
  return g;
}

std::string milli(const std::string& unit) { return std::string(1, 'm').append(unit); }  // (not "m" +: GCC 12's false -Wrestrict)

std::string joint_motion_text(const JointMotion& m) {
  // mm and mrad without an exponent; below half a micrometre (microradian) is 0: round-off of the
  // coordinates or elastic noise.
  const auto v = [](double x) {
    const double y = x * 1e3;
    if (!std::isfinite(y)) return std::string("n/a");
    if (std::abs(y) < 5e-4) return std::string("0");
    char b[32];
    std::snprintf(b, sizeof b, std::abs(y) >= 100 ? "%.0f" : "%.3g", y);
    return std::string(b);
  };
  return "turns " + v(m.rotation) + " mrad, opens " + v(m.open_a) + " mm at A and " + v(m.open_b) + " mm at B, slides " + v(m.slip) + " mm";
}

std::string interval_text(const MotionCheck& m, const std::string& d_unit, const std::string& label_a, const std::string& label_b) {
  const auto d = [&](double x) { return fmt(x * 1e3, 4); };
  if (m.collapse)
    return "at collapse (" + label_a + " from d = " + d(m.a_from) + ", " + label_b + " from d = " + d(m.b_from) + " " + milli(d_unit) + ")";
  return "from d = " + d(m.from) + " to " + d(m.to) + " " + milli(d_unit);
}

std::string joints_text(int n) { return std::to_string(n) + (n == 1 ? " joint" : " joints"); }

std::vector<RingSpot> ring_neighbours(const Case& c, const RunResult& r, int joint, int corner, int shift) {
  std::vector<RingSpot> out;
  if (joint < 0 || joint >= int(r.joints.size())) return out;
  const int nb = int(c.blocks.size());
  std::vector<std::vector<int>> joints_of(c.blocks.size());
  for (size_t k = 0; k < r.joints.size(); ++k)
    for (int b : {r.joints[k].i, r.joints[k].j})
      if (b >= 0 && b < nb) joints_of[size_t(b)].push_back(int(k));
  std::vector<bool> seen(r.joints.size(), false);
  seen[size_t(joint)] = true;
  out.push_back({joint, corner, 0});
  // Breadth first, so spots come nearest first.
  for (size_t q = 0; q < out.size(); ++q) {
    const RingSpot cur = out[q];  // a copy: out grows below
    if (cur.steps >= shift) continue;
    const JointInfo& from = r.joints[size_t(cur.joint)];
    const Vec2 m1 = 0.5 * (from.a + from.b);
    const Vec2 p1 = cur.corner == 0 ? from.a : from.b;
    for (int blk : {from.i, from.j}) {
      if (blk < 0 || blk >= nb || c.blocks[size_t(blk)].support || joints_of[size_t(blk)].size() != 2) continue;
      const int next = joints_of[size_t(blk)][0] == cur.joint ? joints_of[size_t(blk)][1] : joints_of[size_t(blk)][0];
      if (seen[size_t(next)]) continue;
      const JointInfo& to = r.joints[size_t(next)];
      // The side of the line from this joint's midpoint to the next one's.
      const Vec2 u = 0.5 * (to.a + to.b) - m1;
      const auto side = [&](const Vec2& p) { return cross(u, p - m1); };
      const double s1 = side(p1), sa = side(to.a), sb = side(to.b);
      const int nc = s1 * sa >= s1 * sb ? 0 : 1;
      if (!(s1 * (nc == 0 ? sa : sb) > 0)) continue;  // no corner clearly on that side
      seen[size_t(next)] = true;
      out.push_back({next, nc, cur.steps + 1});
    }
  }
  return out;
}

std::vector<Hinge> hinges_of(const Case& c, const RunResult& r, const StepRecord& s, double min_opening) {
  std::map<std::pair<int, int>, double> settled;  // (joint, corner) -> gap at d = 0
  if (!r.steps.empty() && &s != &r.steps.front())
    for (const OpenCorner& o : r.steps.front().open_corners) settled[{o.joint, o.corner}] = o.gap;
  std::map<int, std::vector<std::pair<int, double>>> open;  // joint -> (open corner, opening)
  for (const OpenCorner& o : s.open_corners) {
    const auto it = settled.find({o.joint, o.corner});
    const double opening = o.gap - (it == settled.end() ? 0.0 : it->second);
    if (min_opening > 0 && !(opening > min_opening)) continue;
    open[o.joint].push_back({o.corner, opening});
  }
  std::vector<Hinge> out;
  const std::vector<int> nth = open.empty() ? std::vector<int>() : pair_ordinals(r.joints);
  for (const auto& [joint, ends] : open) {
    if (ends.size() != 1 || joint < 0 || joint >= int(r.joints.size())) continue;
    const JointInfo& ji = r.joints[joint];
    Hinge h;
    h.joint = joint;
    h.i = ji.i;
    h.j = ji.j;
    h.corner = 1 - ends[0].first;
    h.point = h.corner == 0 ? ji.a : ji.b;
    h.label = corner_name(c, ji.i, ji.j, h.corner, nth[size_t(joint)]);
    h.opening = ends[0].second;
    out.push_back(h);
  }
  return out;
}

std::vector<double> mechanism_changes(const RunResult& r, int min_state_records) {
  const auto recs = stable_records(r);
  // Runs of equal open-corner sets: (first record, length).
  struct Run {
    std::set<std::pair<int, int>> state;
    size_t first, count;
  };
  std::vector<Run> runs;
  for (size_t k = 0; k < recs.size(); ++k) {
    std::set<std::pair<int, int>> st;
    for (const OpenCorner& o : recs[k]->open_corners) st.insert({o.joint, o.corner});
    if (!runs.empty() && runs.back().state == st)
      ++runs.back().count;
    else
      runs.push_back({st, k, 1});
  }
  // Flicker: a short state between two others is folded into the one before; the first and the
  // last state are always kept (the last one may be short because the run ends there).
  std::vector<Run> kept;
  for (size_t k = 0; k < runs.size(); ++k) {
    const bool last = k + 1 == runs.size();
    if (!kept.empty() && !last && int(runs[k].count) < min_state_records) {
      kept.back().count += runs[k].count;
      continue;
    }
    if (!kept.empty() && kept.back().state == runs[k].state) {
      kept.back().count += runs[k].count;
      continue;
    }
    kept.push_back(runs[k]);
  }
  std::vector<double> out;
  for (size_t k = 1; k < kept.size(); ++k) out.push_back(recs[kept[k].first]->d);
  return out;
}

std::vector<int> mirror_blocks(const Case& c) {
  Vec2 lo, hi;
  bbox(c, lo, hi);
  const double xc = 0.5 * (lo.x() + hi.x());
  const double tol = 1e-6 * std::max(1.0, scene_size(c));
  std::vector<int> m(c.blocks.size(), -1);
  for (size_t a = 0; a < c.blocks.size(); ++a) {
    const Block& A = c.blocks[a];
    for (size_t b = 0; b < c.blocks.size() && m[a] < 0; ++b) {
      const Block& B = c.blocks[b];
      if (A.support != B.support || A.vertices.size() != B.vertices.size()) continue;
      bool all = true;
      for (const Vec2& v : A.vertices) {
        const Vec2 w(2 * xc - v.x(), v.y());
        bool hit = false;
        for (const Vec2& u : B.vertices) hit = hit || (u - w).norm() <= tol;
        if (!hit) {
          all = false;
          break;
        }
      }
      if (all) m[a] = int(b);
    }
    if (m[a] < 0) return {};
  }
  // The dead loads mirror too: a block's weight (density and depth) equal to its mirror's, and
  // every point load matched by its mirror image on the mirror block (a 2 kN load on one
  // voussoir of the pointed arch read as symmetric).
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y)); };
  for (size_t a = 0; a < c.blocks.size(); ++a) {
    const Block &A = c.blocks[a], &B = c.blocks[size_t(m[a])];
    if (!A.support && (!same(A.density, B.density) || !same(A.depth, B.depth))) return {};
  }
  for (const Load& l : c.loads) {
    bool matched = false;
    for (const Load& k : c.loads)
      matched = matched || (k.block == m[size_t(l.block)] && (k.point - Vec2(2 * xc - l.point.x(), l.point.y())).norm() <= tol &&
                            (k.force - Vec2(-l.force.x(), l.force.y())).norm() <= 1e-9 * l.force.norm());
    if (!matched) return {};
  }
  // The mirror image of a mechanism is the same answer only where the supports' motion is its
  // own mirror image too, up to one translation of the whole scene (which moves no joint and,
  // under gravity, changes the work of every mechanism alike): one support spreading outwards is
  // the other spreading (the paper's Remark 3), but the right support settling is not the left
  // one settling, and a slab tilting one way is not one tilting the other. Per support, its
  // rotation and the velocity of its centroid per unit of d, against its mirror's mirrored.
  std::vector<double> rot(c.blocks.size(), 0.0);
  std::vector<Vec2> vel(c.blocks.size(), Vec2(0, 0));
  std::vector<Vec2> cen(c.blocks.size());
  for (size_t b = 0; b < c.blocks.size(); ++b) cen[b] = centroid(c.blocks[b].vertices);
  for (const SupportMotion& s : c.motion.supports) {
    const size_t b = size_t(s.block);
    rot[b] = s.rotation;
    vel[b] = s.translation + s.rotation * perp(cen[b] - s.about);
  }
  std::optional<Vec2> common;
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    if (!c.blocks[b].support) continue;
    const size_t o = size_t(m[b]);
    if (std::abs(-rot[o] - rot[b]) > 1e-9 * (1 + std::abs(rot[b]))) return {};
    const Vec2 diff = Vec2(-vel[o].x(), vel[o].y()) - vel[b];
    if (!common) common = diff;
    // The blocks match within tol (m), so a turning support's centroid velocity within its turn
    // times tol.
    if ((diff - *common).norm() > 1e-9 * (1 + vel[b].norm()) + 2 * std::abs(rot[b]) * tol) return {};
  }
  return m;
}

Comparison compare_runs(const Case& c, const RunResult& a, const RunResult& b, const CompareOptions& o, const std::string& label_a,
                        const std::string& label_b) {
  Comparison k;
  k.case_name = c.name;
  k.total_weight = a.total_weight > 0 ? a.total_weight : b.total_weight;
  k.a = summarise(a, label_a, o.min_state_records);
  k.b = summarise(b, label_b, o.min_state_records);
  if (k.a.label == k.b.label) {  // two runs of one method: keep them apart in every table
    k.a.label += " (a)";
    k.b.label += " (b)";
  }
  if (a.capacity != 0)
    k.capacity_rel_diff = (b.capacity - a.capacity) / a.capacity;
  else
    k.capacity_rel_diff = b.capacity == 0 ? 0.0 : kNaN;
  k.time_ratio = a.timing.total_s > 0 ? b.timing.total_s / a.timing.total_s : kNaN;

  const auto ra = stable_records(a), rb = stable_records(b);
  k.d_max = std::min(std::isfinite(a.capacity) ? a.capacity : 0.0, std::isfinite(b.capacity) ? b.capacity : 0.0);
  k.d_max = std::max(k.d_max, 0.0);

  // Common grid: every record of either run inside [0, d_max], so neither run's jumps are
  // smoothed away by a coarser grid (or the coarser run's records alone, ThrustGrid); points
  // closer than a billionth of the range are one.
  std::vector<double> grid;
  const auto in_range = [&](const StepRecord* s) { return s->d >= 0 && s->d <= k.d_max * (1 + 1e-12) + 1e-15; };
  const auto count = [&](const std::vector<const StepRecord*>& recs) { return std::count_if(recs.begin(), recs.end(), in_range); };
  std::vector<const std::vector<const StepRecord*>*> sources{&ra, &rb};
  if (o.thrust_grid == ThrustGrid::coarser_run) sources = {count(rb) < count(ra) ? &rb : &ra};
  for (const auto* recs : sources)
    for (const StepRecord* s : *recs)
      if (in_range(s)) grid.push_back(std::min(s->d, k.d_max));
  std::sort(grid.begin(), grid.end());
  const double merge = 1e-9 * std::max(k.d_max, 1e-9);
  for (double x : grid)
    if (k.d.empty() || x - k.d.back() > merge) k.d.push_back(x);

  // Thrust curves, support by support (matched by id), over the total weight.
  const double W = k.total_weight > 0 ? k.total_weight : 1.0;
  k.thrust_skipped = missing(a, b, k, "reactions", [](const RunResult& r) {
    for (const StepRecord& s : r.steps)
      if (!s.reactions.empty()) return true;
    return false;
  });
  k.hinges_skipped = missing(a, b, k, "joints", [](const RunResult& r) { return !r.joints.empty(); });
  // A run with no equilibrium at all (it did not settle as drawn: it collapsed, or still moved
  // at the hold's cap) has nothing to compare.
  const std::string stands =
      missing(a, b, k, "equilibrium at d = 0: it did not settle as drawn", [](const RunResult& r) { return !stable_records(r).empty(); });
  if (!stands.empty()) k.thrust_skipped = k.hinges_skipped = stands;
  // The mechanism agreement moves the joints' corners with the blocks' poses and weights each
  // joint by the force it carries: without forces every weight is 0 and no agreement exists.
  k.mechanism_skipped = !stands.empty() ? stands : missing(a, b, k, "joints, poses and forces at every record", [&](const RunResult& r) {
    if (r.joints.empty()) return false;
    for (const StepRecord* s : stable_records(r))
      if (s->poses.size() != c.blocks.size() || s->forces.empty()) return false;
    return true;
  });
  std::vector<std::string> supports;
  if (!ra.empty() && k.thrust_skipped.empty())
    for (const Reaction& x : ra.front()->reactions) supports.push_back(x.support);
  double sum2 = 0.0, where_diff = -1.0;
  size_t n2 = 0;
  const auto series = [&](const std::vector<const StepRecord*>& recs, const std::string& id, int comp, std::vector<double>& xs,
                          std::vector<double>& ys) {
    for (const StepRecord* s : recs)
      for (const Reaction& x : s->reactions)
        if (x.support == id) {
          xs.push_back(s->d);
          ys.push_back((comp == 0 ? x.force.x() : x.force.y()) / W);
        }
  };
  for (const std::string& id : supports) {
    SupportCurve sc;
    sc.support = id;
    for (int comp = 0; comp < 2; ++comp) {
      std::vector<double> xa, ya, xb, yb;
      series(ra, id, comp, xa, ya);
      series(rb, id, comp, xb, yb);
      auto& outa = comp == 0 ? sc.h_a : sc.v_a;
      auto& outb = comp == 0 ? sc.h_b : sc.v_b;
      for (double q : k.d) {
        const double va = interp(xa, ya, q), vb = interp(xb, yb, q);
        outa.push_back(va);
        outb.push_back(vb);
        if (std::isfinite(va) && std::isfinite(vb)) {
          const double diff = std::abs(vb - va);
          sc.max_diff = std::max(sc.max_diff, diff);
          if (diff > where_diff) {
            where_diff = diff;
            k.thrust_max_d = q;
            k.thrust_max_where = (comp == 0 ? "H of " : "V of ") + id;
          }
          sum2 += diff * diff;
          ++n2;
        } else {
          sc.max_diff = kNaN;  // a support missing from one run: the curves cannot agree
        }
      }
    }
    k.thrust_max_diff = std::isnan(sc.max_diff) || std::isnan(k.thrust_max_diff) ? kNaN : std::max(k.thrust_max_diff, sc.max_diff);
    k.supports.push_back(std::move(sc));
  }
  k.thrust_rms_diff = n2 ? std::sqrt(sum2 / double(n2)) : kNaN;
  if (k.supports.empty() || k.d.empty()) k.thrust_max_diff = kNaN;

  // Hinges at a few common d.
  const std::vector<int> mirror = mirror_blocks(c);
  k.symmetric = !mirror.empty();
  Vec2 lo, hi;
  bbox(c, lo, hi);
  const double xc = 0.5 * (lo.x() + hi.x());
  const double tol = 1e-6 * std::max(1.0, scene_size(c));
  k.hinge_gap = std::max(settled_gap(a), settled_gap(b));
  k.d_unit = path_unit(c);
  if (!ra.empty() && !rb.empty() && k.mechanism_skipped.empty()) {
    std::vector<double> ds;
    for (double f : o.hinge_fractions) ds.push_back(f * k.d_max);
    k.motion = mechanism_checks(c, a, b, ds, o.ring_shift);
    k.ring_shift = o.ring_shift;
    k.sliding = slip_check(c, a, b, k.d_max, std::max(k.hinge_gap, c.prd.contact_tolerance));
  }
  k.jumps_a = jumps(c, a);  // a run without poses has none to read
  k.jumps_b = jumps(c, b);
  if (!ra.empty() && !rb.empty() && k.hinges_skipped.empty()) {
    std::set<double> done;
    for (double f : o.hinge_fractions) {
      HingeCheck h;
      h.d = f * k.d_max;
      const StepRecord* sa = record_at(ra, h.d);
      const StepRecord* sb = record_at(rb, h.d);
      h.d_a = sa->d;
      h.d_b = sb->d;
      if (!done.insert(h.d).second) continue;
      // Both runs by the same rule: a hinge PRD opens by less than the DEM's elastic scale would
      // be invisible in the DEM.
      h.a = hinges_of(c, a, *sa, k.hinge_gap);
      h.b = hinges_of(c, b, *sb, k.hinge_gap);
      int direct = 0;
      for (Hinge& x : h.a) direct = worst_of(direct, x.apart = ring_distance(c, a, x, h.b, nullptr, xc, tol));
      for (Hinge& x : h.b) direct = worst_of(direct, x.apart = ring_distance(c, b, x, h.a, nullptr, xc, tol));
      const int mirrored = k.symmetric ? mirrored_shift(c, a, b, h.a, h.b, mirror, xc, tol) : -1;
      h.match = direct == 0;
      h.mirror = !h.match && mirrored == 0;
      h.shift = direct < 0 ? mirrored : mirrored < 0 ? direct : std::min(direct, mirrored);
      k.hinges.push_back(std::move(h));
    }
  }
  return k;
}

ojson to_json(const Comparison& k) {
  ojson j;
  j["case"] = k.case_name;
  j["d_unit"] = k.d_unit;
  j["a"] = summary_json(k.a);
  j["b"] = summary_json(k.b);
  j["total_weight"] = json_number(k.total_weight);
  j["capacity"] = {{"a", json_number(k.a.capacity)},
                   {"b", json_number(k.b.capacity)},
                   {"relative_difference", json_number(k.capacity_rel_diff)},
                   {"difference", json_number(k.b.capacity - k.a.capacity)}};
  ojson t;
  t["compared"] = k.thrust_skipped.empty();
  if (!k.thrust_skipped.empty()) t["note"] = k.thrust_skipped;
  t["common_range"] = ojson::array({0.0, json_number(k.d_max)});
  t["max_difference"] = json_number(k.thrust_max_diff);
  t["max_difference_at"] = {{"d", json_number(k.thrust_max_d)}, {"component", k.thrust_max_where}};
  t["rms_difference"] = json_number(k.thrust_rms_diff);
  ojson d = ojson::array();
  for (double x : k.d) d.push_back(json_number(x));
  t["d"] = d;
  ojson sup = ojson::array();
  const auto arr = [](const std::vector<double>& v) {
    ojson a = ojson::array();
    for (double x : v) a.push_back(json_number(x));
    return a;
  };
  for (const SupportCurve& s : k.supports)
    sup.push_back({{"support", s.support},
                   {"max_difference", json_number(s.max_diff)},
                   {"H_a", arr(s.h_a)},
                   {"V_a", arr(s.v_a)},
                   {"H_b", arr(s.h_b)},
                   {"V_b", arr(s.v_b)}});
  t["supports"] = sup;
  j["thrust"] = t;
  ojson hc = ojson::array();
  for (const HingeCheck& h : k.hinges) {
    ojson ha = ojson::array(), hb = ojson::array(), oa = ojson::array(), ob = ojson::array(), pa = ojson::array(), pb = ojson::array();
    const auto apart = [](int n) { return n < 0 ? ojson(nullptr) : ojson(n); };
    for (const Hinge& x : h.a) {
      ha.push_back(x.label);
      oa.push_back(json_number(x.opening));
      pa.push_back(apart(x.apart));
    }
    for (const Hinge& x : h.b) {
      hb.push_back(x.label);
      ob.push_back(json_number(x.opening));
      pb.push_back(apart(x.apart));
    }
    hc.push_back({{"d", json_number(h.d)},
                  {"d_a", json_number(h.d_a)},
                  {"d_b", json_number(h.d_b)},
                  {"a", ha},
                  {"b", hb},
                  {"a_opening", oa},
                  {"b_opening", ob},
                  {"a_joints_apart", pa},
                  {"b_joints_apart", pb},
                  {"match", h.match},
                  {"mirror", h.mirror},
                  {"joints_apart", apart(h.shift)}});
  }
  j["hinges"] = {{"compared", k.hinges_skipped.empty()}};
  if (!k.hinges_skipped.empty()) j["hinges"]["note"] = k.hinges_skipped;
  j["hinges"].update(
      ojson{{"symmetric", k.symmetric}, {"min_opening", json_number(k.hinge_gap)}, {"max_joints_apart", kMaxHingeShift}, {"checks", hc}});
  ojson ma = ojson::array();
  const auto motion_json = [](const JointMotion& m) {
    return ojson{
        {"rotation", json_number(m.rotation)}, {"open_a", json_number(m.open_a)}, {"open_b", json_number(m.open_b)}, {"slip", json_number(m.slip)}};
  };
  for (const MotionCheck& m : k.motion) {
    ojson differ = ojson::array();
    for (const MotionDiff& x : m.differ)
      differ.push_back(
          {{"joint", x.label}, {"share", json_number(x.share)}, {"weight", json_number(x.weight)}, {"a", motion_json(x.a)}, {"b", motion_json(x.b)}});
    ma.push_back({{"from", json_number(m.from)},
                  {"to", m.collapse ? ojson(nullptr) : json_number(m.to)},
                  {"collapse", m.collapse},
                  {"a_from", json_number(m.a_from)},
                  {"a_to", json_number(m.a_to)},
                  {"b_from", json_number(m.b_from)},
                  {"b_to", json_number(m.b_to)},
                  {"a_moves", m.a_moves},
                  {"b_moves", m.b_moves},
                  {"agreement", json_number(m.agreement)},
                  {"agreement_same_joints", json_number(m.same_joints)},
                  {"mirror", m.mirror},
                  {"differ_most", differ}});
  }
  j["mechanism_agreement"] = ma;
  if (!k.mechanism_skipped.empty()) j["mechanism_note"] = k.mechanism_skipped;
  if (k.mechanism_skipped.empty()) j["mechanism_joints_apart"] = k.ring_shift;
  if (k.sliding) {
    const auto one = [](const JointSlip& x) {
      return ojson{{"joint", x.joint >= 0 ? ojson(x.label) : ojson(nullptr)}, {"a", json_number(x.a)}, {"b", json_number(x.b)}};
    };
    j["sliding"] = ojson{{"to", json_number(k.sliding->to)},
                         {"a_to", json_number(k.sliding->a_to)},
                         {"b_to", json_number(k.sliding->b_to)},
                         {"largest_a", one(k.sliding->largest_a)},
                         {"largest_b", one(k.sliding->largest_b)}};
  }
  const auto jumps_json = [](const std::vector<Jump>& v) {
    ojson out = ojson::array();
    for (const Jump& x : v) out.push_back({{"from", json_number(x.from)}, {"to", json_number(x.to)}, {"drift", json_number(x.drift)}, {"block", x.block}});
    return out;
  };
  j["jumps"] = ojson{{"a", jumps_json(k.jumps_a)}, {"b", jumps_json(k.jumps_b)}};
  j["timing"] = {{"a_s", json_number(k.a.time_s)}, {"b_s", json_number(k.b.time_s)}, {"ratio", json_number(k.time_ratio)}};
  return j;
}

std::vector<std::string> check_tolerances(const Comparison& k, const Tolerances& t) {
  std::vector<std::string> out;
  if (t.capacity || t.capacity_abs) {
    const double diff = std::abs(k.b.capacity - k.a.capacity);
    const double limit = std::max(t.capacity_abs.value_or(0.0), t.capacity.value_or(0.0) * std::abs(k.a.capacity));
    std::string limits;
    if (t.capacity) limits = fmt(*t.capacity * 100, 3) + "%";
    if (t.capacity_abs) limits += (limits.empty() ? "" : " or ") + fmt(*t.capacity_abs) + " " + k.d_unit;
    if (!std::isfinite(diff) || diff > limit)
      out.push_back("capacity: " + k.a.label + " " + fmt(k.a.capacity) + " " + k.d_unit + ", " + k.b.label + " " + fmt(k.b.capacity) + " " + k.d_unit +
                    ": difference " + fmt(diff) + " " + k.d_unit + ", relative " + fmt(std::abs(k.capacity_rel_diff) * 100, 3) + "% > limit " + limits);
  }
  if (t.thrust && k.thrust_skipped.empty()) {
    const double m = k.thrust_max_diff;
    if (!std::isfinite(m) || m > *t.thrust)
      out.push_back("thrust: largest support reaction difference " + fmt(m, 3) + " W (" + k.thrust_max_where + " at d = " + fmt(k.thrust_max_d) +
                    " " + k.d_unit + ") > limit " + fmt(*t.thrust, 3) + " W");
  }
  const auto motion_violation = [&](const MotionCheck& m, const std::string& key, double limit) {
    std::string most;
    for (const MotionDiff& x : m.differ)
      most += (most.empty() ? "" : "; ") + x.label + " (" + k.a.label + " " + joint_motion_text(x.a) + ", " + k.b.label + " " +
              joint_motion_text(x.b) + (m.mirror ? ", mirrored" : "") + ")";
    out.push_back(key + ": " + interval_text(m, k.d_unit, k.a.label, k.b.label) + " the joints move differently: agreement " + fmt(m.agreement, 3) +
                  " < least " + fmt(limit, 3) + (most.empty() ? "" : "; most at " + most));
  };
  if (t.mechanism && k.mechanism_skipped.empty()) {
    const bool any = std::any_of(k.motion.begin(), k.motion.end(), [](const MotionCheck& m) { return !m.collapse; });
    if (!any) out.push_back("mechanism: no common range to compare the runs' motions on");
    for (const MotionCheck& m : k.motion)
      if (!m.collapse && m.agreement < *t.mechanism) motion_violation(m, "mechanism", *t.mechanism);  // NaN: not determined
  }
  if (t.collapse_mechanism && k.mechanism_skipped.empty()) {
    const auto it = std::find_if(k.motion.begin(), k.motion.end(), [](const MotionCheck& m) { return m.collapse; });
    if (it == k.motion.end())
      out.push_back("collapse_mechanism: the runs did not both collapse (or one recorded no collapse state)");
    else if (it->agreement < *t.collapse_mechanism)
      motion_violation(*it, "collapse_mechanism", *t.collapse_mechanism);
  }
  if (t.hinges && k.hinges_skipped.empty()) {
    if (k.hinges.empty()) out.push_back("hinges: no common range to compare hinge locations on");
    const std::string why = t.hinge_shift == 0 ? (k.symmetric ? " (not mirror images either)" : "")
                                               : " (none within " + joints_text(t.hinge_shift) + " of the other's along a ring" +
                                                     (k.symmetric ? ", nor as mirror images)" : ")");
    for (const HingeCheck& h : k.hinges) {
      if (h.ok(t.hinge_shift)) continue;
      // Name only the hinges without a partner: a cathedral has a dozen, most of them shared.
      // With their openings since d = 0, so a hinge just past the threshold reads as such.
      const auto alone = [&](const std::vector<Hinge>& hs) {
        std::string l;
        for (const Hinge& x : hs)
          if (x.apart < 0 || x.apart > t.hinge_shift) l += (l.empty() ? "" : ", ") + x.label + " (" + fmt(x.opening * 1e3, 2) + " mm)";
        return l;
      };
      out.push_back("hinges: at d = " + fmt(h.d) + " " + k.d_unit + " only " + k.a.label + " has {" + alone(h.a) + "}, only " + k.b.label + " has {" + alone(h.b) +
                    "}" + why);
    }
  }
  return out;
}

Tolerances parse_tolerances(const std::string& text, const std::string& source) {
  // A key given twice is refused: nlohmann keeps the last one, and {"capacity": 0.5, "capacity":
  // 0.001} gated at 0.1%, the two keys reversed at 50%.
  const ojson j = parse_document<std::runtime_error, ojson>(text, source);
  if (!j.is_object()) throw std::runtime_error(source + ": expected an object like {\"capacity\": 0.05, \"thrust\": 0.10, \"hinges\": true}");
  Tolerances t;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    const ojson& v = it.value();
    if (key == "capacity" || key == "capacity_abs" || key == "thrust") {
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
        throw std::runtime_error(source + ": \"" + key + "\" must be a non-negative number");
      (key == "capacity" ? t.capacity : key == "capacity_abs" ? t.capacity_abs : t.thrust) = v.get<double>();
    } else if (key == "mechanism" || key == "collapse_mechanism") {
      if (!v.is_number() || !(v.get<double>() >= 0 && v.get<double>() <= 1))
        throw std::runtime_error(source + ": \"" + key + "\" must be a number from 0 to 1 (the least mechanism agreement)");
      (key == "mechanism" ? t.mechanism : t.collapse_mechanism) = v.get<double>();
    } else if (key == "hinges") {
      if (!v.is_boolean()) throw std::runtime_error(source + ": \"hinges\" must be true or false");
      t.hinges = v.get<bool>();
    } else if (key == "hinge_shift") {
      if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > kMaxHingeShift)
        throw std::runtime_error(source + ": \"hinge_shift\" must be a whole number of joints from 0 to " + std::to_string(kMaxHingeShift));
      t.hinge_shift = int(v.get<long long>());
    } else if (key == "comment" || key == "description") {
      if (!v.is_string()) throw std::runtime_error(source + ": \"" + key + "\" must be text (a note for people)");
    } else {
      throw std::runtime_error(source + ": unknown key \"" + key +
                               "\" (known: capacity, capacity_abs, thrust, mechanism, collapse_mechanism, hinges, hinge_shift, comment)");
    }
  }
  // A gate that checks nothing passes everything: {} (or a comment alone) was a PASS.
  if (!t.capacity && !t.capacity_abs && !t.thrust && !t.mechanism && !t.collapse_mechanism && !t.hinges)
    throw std::runtime_error(source + ": sets no limit (give at least one of capacity, capacity_abs, thrust, mechanism, collapse_mechanism, or hinges: true)");
  return t;
}

namespace {
std::string read_or_throw(const std::string& path) {
  std::optional<std::string> text = read_text(path);
  if (!text) throw std::runtime_error(path + ": cannot read");
  return std::move(*text);
}
}  // namespace

Tolerances load_tolerances(const std::string& path) { return parse_tolerances(read_or_throw(path), path); }

}  // namespace masonry
