// The sliding check (PrdSettings::sliding_check) of one configuration, and its summaries.
#include <glpk.h>

#include "internal.hpp"

namespace masonry::prd_detail {

void sliding_check(const Model& m, SlidingLp& S, StepRecord& rec) {
  // Demand of the dual state.
  double demand = 0;
  int demand_joint = -1;
  for (const JointForce& f : rec.forces) {
    const double a = f.normal > 0 ? std::atan(std::abs(f.shear) / f.normal) : (f.shear != 0 ? M_PI / 2 : 0.0);
    if (a > demand) demand = a, demand_joint = f.joint;
  }

  // The feasibility LP: columns f_n per closed corner, then f_t per joint in contact; rows:
  // equilibrium of each free block (numbered as the PRD LP's columns), then two friction rows
  // per joint in contact.
  glp_prob* lp = S.lp.get();
  glp_erase_prob(lp);
  const int nrows_eq = m.ncols;
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  std::vector<int> fn_col(m.ends.size(), 0), ft_col(m.joints.size(), 0);
  std::vector<int> joints_in_contact;
  int ncols = 0;
  auto add_force = [&](int col, int b, const Vec2& F, const Vec2& p) {
    if (m.col[b] < 0) return;
    const int k = m.col[b];
    const double v[3] = {F.x(), F.y(), cross(p - m.cen[b], F) / m.radius[b]};
    for (int r = 0; r < 3; ++r)
      if (v[r] != 0) ia.push_back(k + r), ja.push_back(col), ar.push_back(v[r]);
  };
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (!m.ends[e].closed) continue;
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const Vec2 n = m.normal(ep), p = 0.5 * (m.pos(jt.i, ep.X) + m.pos(jt.j, ep.X));
    fn_col[e] = ++ncols;
    add_force(ncols, jt.j, n, p);
    add_force(ncols, jt.i, -n, p);
    if (m.sliding_row(e)) {  // the joint's shear acts along its line, at any of its points
      ft_col[ep.joint] = ++ncols;
      add_force(ncols, jt.j, perp(n), p);
      add_force(ncols, jt.i, -perp(n), p);
      joints_in_contact.push_back(ep.joint);
    }
  }
  if (ncols == 0 || nrows_eq == 0) return;
  glp_add_cols(lp, ncols);
  for (int j = 1; j <= ncols; ++j) glp_set_col_bnds(lp, j, GLP_LO, 0, 0);
  for (int jt : joints_in_contact) glp_set_col_bnds(lp, ft_col[jt], GLP_FR, 0, 0);
  glp_add_rows(lp, nrows_eq + 2 * static_cast<int>(joints_in_contact.size()));
  const std::vector<double> f = generalised_loads(m);
  for (int r = 1; r <= nrows_eq; ++r) glp_set_row_bnds(lp, r, GLP_FX, -f[r], -f[r]);
  for (size_t q = 0; q < joints_in_contact.size(); ++q)
    for (int s = 0; s < 2; ++s) glp_set_row_bnds(lp, nrows_eq + 2 * static_cast<int>(q) + 1 + s, GLP_UP, 0, 0);
  glp_load_matrix(lp, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());

  std::vector<int> ind;
  std::vector<double> val;
  auto set_mu = [&](double mu) {
    for (size_t q = 0; q < joints_in_contact.size(); ++q) {
      const int jt = joints_in_contact[q];
      for (int s = 0; s < 2; ++s) {
        ind.assign(1, 0);
        val.assign(1, 0.0);
        ind.push_back(ft_col[jt]), val.push_back(s == 0 ? 1.0 : -1.0);
        for (int c = 0; c < 2; ++c)
          if (fn_col[2 * jt + c]) ind.push_back(fn_col[2 * jt + c]), val.push_back(-mu);
        glp_set_mat_row(lp, nrows_eq + 2 * static_cast<int>(q) + 1 + s, static_cast<int>(ind.size()) - 1, ind.data(),
                        val.data());
      }
    }
  };
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.it_lim = 1000 + 50 * (glp_get_num_rows(lp) + ncols);
  bool fresh = true;
  auto feasible = [&](double mu) {
    set_mu(mu);
    if (fresh) glp_std_basis(lp), fresh = false;
    ++S.solves;
    int rc = glp_simplex(lp, &parm);
    if (rc != 0) {  // a stalled warm start: once more from the standard basis
      glp_std_basis(lp);
      rc = glp_simplex(lp, &parm);
    }
    return rc == 0 && glp_get_status(lp) == GLP_OPT;
  };
  // The binding joint of a feasible state: the largest |T|/N.
  auto binding = [&]() {
    int best = -1;
    double worst = -1;
    for (int jt : joints_in_contact) {
      double N = 0;
      for (int c = 0; c < 2; ++c)
        if (fn_col[2 * jt + c]) N += glp_get_col_prim(lp, fn_col[2 * jt + c]);
      const double T = std::abs(glp_get_col_prim(lp, ft_col[jt]));
      const double ratio = N > 0 ? T / N : (T > 0 ? 1e300 : 0);
      if (ratio > worst) worst = ratio, best = jt;
    }
    return best;
  };

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
    required_joint = binding();
    while (std::atan(hi) - std::atan(lo) > resolution) {
      const double mid = 0.5 * (lo + hi);
      if (feasible(mid)) {
        hi = mid;
        required_joint = binding();
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
  auto joint_name = [&](int k) {
    if (k < 0 || k >= static_cast<int>(r.joints.size())) return std::string();
    return c.blocks[r.joints[k].i].id + "/" + c.blocks[r.joints[k].j].id;
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
  out.joint = joint_name(req->sliding->required_joint);
  out.max_demand_angle = dem->sliding->demand_angle;
  out.demand_d = dem->d;
  out.demand_joint = joint_name(dem->sliding->demand_joint);
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
    if (e.joint >= 0) e.blocks = c.blocks[r.joints[e.joint].i].id + "/" + c.blocks[r.joints[e.joint].j].id;
    return e;
  }
  return std::nullopt;
}

}  // namespace masonry
