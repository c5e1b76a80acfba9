// The sliding check (PrdSettings::sliding_check) of one configuration, and its summaries.
#include <cmath>
#include <utility>

#include "model/interfaces.hpp"
#include "prd/internal.hpp"

namespace masonry::prd_detail {

namespace {

// The dual state's friction demand: the largest |T|/N over the joint resultants, as an angle
// (rad), and its joint.
std::pair<double, int> demand_of(const StepRecord& rec) {
  double demand = 0;
  int joint = -1;
  for (const JointForce& f : rec.forces) {
    const double a = f.normal > 0 ? std::atan(std::abs(f.shear) / f.normal) : (f.shear != 0 ? M_PI / 2 : 0.0);
    if (a > demand) demand = a, joint = f.joint;
  }
  return {demand, joint};
}

// The feasibility problem of the current configuration: each closed corner's normal force and
// each joint's shear, acting on both blocks at the corner's current position.
FrictionProblem friction_problem(const Model& m) {
  FrictionProblem p;
  p.nrows_eq = m.ncols;
  p.fn_col.assign(m.ends.size(), 0);
  p.ft_col.assign(m.joints.size(), 0);
  auto add_force = [&](int col, int b, const Vec2& F, const Vec2& x) {
    if (m.col[b] < 0) return;
    const int k = m.col[b];
    const double v[3] = {F.x(), F.y(), cross(x - m.cen[b], F) / m.radius[b]};
    for (int r = 0; r < 3; ++r)
      if (v[r] != 0) p.ia.push_back(k + r), p.ja.push_back(col), p.ar.push_back(v[r]);
  };
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (!m.ends[e].closed) continue;
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const Vec2 n = m.normal(ep), x = 0.5 * (m.on_i(ep) + m.on_j(ep));
    p.fn_col[e] = ++p.ncols;
    add_force(p.ncols, jt.j, n, x);
    add_force(p.ncols, jt.i, -n, x);
    if (m.sliding_row(e)) {  // the joint's shear acts along its line, at any of its points
      p.ft_col[ep.joint] = ++p.ncols;
      add_force(p.ncols, jt.j, perp(n), x);
      add_force(p.ncols, jt.i, -perp(n), x);
      p.joints_in_contact.push_back(ep.joint);
    }
  }
  // In the LP's force unit, for GLPK's absolute tolerances (build_model); only ratios of the
  // forces are read back.
  p.loads = generalised_loads(m);
  for (double& f : p.loads) f /= m.force_unit;
  return p;
}

// The binding joint of the last feasible state: the largest |T|/N.
int binding_joint(const SlidingLp& S, const FrictionProblem& p) {
  int best = -1;
  double worst = -1;
  for (int jt : p.joints_in_contact) {
    double N = 0;
    for (int c = 0; c < 2; ++c)
      if (p.fn_col[2 * jt + c]) N += friction_col_value(S, p.fn_col[2 * jt + c]);
    const double T = std::abs(friction_col_value(S, p.ft_col[jt]));
    const double ratio = N > 0 ? T / N : (T > 0 ? 1e300 : 0);
    if (ratio > worst) worst = ratio, best = jt;
  }
  return best;
}

}  // namespace

void sliding_check(const Model& m, SlidingLp& S, StepRecord& rec) {
  const auto [demand, demand_joint] = demand_of(rec);
  const FrictionProblem p = friction_problem(m);
  if (p.ncols == 0 || p.nrows_eq == 0) return;
  load_friction_lp(S, p);
  auto feasible = [&](double mu) { return friction_feasible(S, p, mu); };

  // Where the force state is unique (a mechanism leaves the moving part statically
  // determinate) no state does better than the dual one: one LP just below its demand shows it.
  constexpr double resolution = 0.01 / kDeg;  // rad
  double lo = 0, hi = std::tan(std::min(demand, 89.9 / kDeg));
  int required_joint = demand_joint;
  if (demand > resolution && !feasible(std::tan(demand - resolution))) {
    lo = hi;
  } else if (feasible(0)) {
    hi = 0;  // no shear needed anywhere
  } else {
    // The dual state is admissible, so hi is feasible but for round-off; widen it if needed.
    bool ok = false;
    for (int widen = 0; !(ok = feasible(hi)) && widen < 20; ++widen) hi = std::max(2 * hi, 1e-3);
    if (!ok) return;  // no admissible state found: leave the field out rather than guess
    required_joint = binding_joint(S, p);
    while (std::atan(hi) - std::atan(lo) > resolution) {
      const double mid = 0.5 * (lo + hi);
      if (feasible(mid)) {
        hi = mid;
        required_joint = binding_joint(S, p);
      } else {
        lo = mid;
      }
    }
  }
  rec.sliding = SlidingCheck{demand * kDeg, demand_joint, std::atan(hi) * kDeg, required_joint};
}

}  // namespace masonry::prd_detail

namespace masonry {

SlidingSummary sliding_summary(const Case& c, const RunResult& r) {
  SlidingSummary out;
  const std::vector<int> nth = pair_ordinals(r.joints);
  auto name_of = [&](int k) {
    if (k < 0 || k >= static_cast<int>(r.joints.size())) return std::string();
    return joint_name(c, r.joints[k].i, r.joints[k].j, nth[size_t(k)]);
  };
  const StepRecord* req = nullptr;
  const StepRecord* dem = nullptr;
  for (const StepRecord& s : r.steps) {
    if (!s.sliding) continue;
    if (!req || s.sliding->required_angle > req->sliding->required_angle) req = &s;
    if (!dem || s.sliding->demand_angle > dem->sliding->demand_angle) dem = &s;
  }
  if (!req) return out;
  out.any = true;
  out.required_friction_angle = req->sliding->required_angle;
  out.d = req->d;
  out.step = req->index;
  out.joint = name_of(req->sliding->required_joint);
  out.max_demand_angle = dem->sliding->demand_angle;
  out.demand_d = dem->d;
  out.demand_joint = name_of(dem->sliding->demand_joint);
  return out;
}

std::optional<SlidingExceedance> first_sliding(const Case& c, const RunResult& r, double angle_deg, bool required) {
  for (const StepRecord& s : r.steps) {
    if (!s.sliding) continue;
    const double angle = required ? s.sliding->required_angle : s.sliding->demand_angle;
    if (angle <= angle_deg) continue;
    SlidingExceedance e;
    e.step = s.index;
    e.d = s.d;
    e.angle = angle;
    e.joint = required ? s.sliding->required_joint : s.sliding->demand_joint;
    if (e.joint >= 0) e.blocks = joint_name(c, r.joints[e.joint].i, r.joints[e.joint].j, pair_ordinals(r.joints)[size_t(e.joint)]);
    return e;
  }
  return std::nullopt;
}

}  // namespace masonry
