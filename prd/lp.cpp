// The layer over GLPK, its only user: the PRD LP built, rewritten for each configuration,
// solved, and read; and the sliding check's feasibility LP (at the end of this file).
//
// Variables: per free block b, U'_b = (u_x, u_y, theta * L_b) / step, the rigid increment at
// the current centroid in units of the step (so GLPK's tolerances are relative to the step)
// with the rotation scaled by the block's radius L_b (so all coefficients are O(1)).
// Rows: per joint endpoint k, a no-penetration row  n.[u]_k >= -g_k  and a no-sliding row
// t.[u]_k = 0. For a rigid relative motion t.[u] is the same at both ends of a joint, so the
// two no-sliding rows of a closed joint are one constraint written twice; kept both, their
// right-hand sides differ by round-off and the simplex cycles between phases. So a joint has
// one active no-sliding row, at its first closed endpoint; the others are made free. The row
// duals are then the endpoint forces in N: f_n >= 0 on the first, f_t on the second.
#include <glpk.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "prd/internal.hpp"
#include "prd/kept_basis.hpp"

namespace masonry::prd_detail {

Model build_model(const Case& c, double tol) {
  Model m;
  m.c = &c;
  m.tol = tol;
  m.joints = detect_interfaces(c, tol);
  const size_t nb = c.blocks.size();
  m.col.assign(nb, -1);
  m.radius.assign(nb, 1.0);
  m.c0.resize(nb);
  m.weight.assign(nb, 0.0);
  m.motion_of.assign(nb, -1);
  for (size_t k = 0; k < c.motion.supports.size(); ++k) m.motion_of[c.motion.supports[k].block] = static_cast<int>(k);
  for (size_t b = 0; b < nb; ++b) {
    const Block& bl = c.blocks[b];
    m.c0[b] = centroid(bl.vertices);
    double r = 0;
    for (const Vec2& v : bl.vertices) r = std::max(r, (v - m.c0[b]).norm());
    m.radius[b] = r;
    if (!bl.support) {
      m.col[b] = m.ncols + 1;
      m.ncols += 3;
      m.weight[b] = block_mass(bl) * c.gravity;
    }
  }
  m.cen = m.c0;
  m.angle.assign(nb, 0.0);
  // The LP's force unit: the largest generalised load at the start, so that the objective's
  // coefficients are at most 1 whatever the weights' scale. GLPK's optimality tolerances are
  // absolute below 1 (a reduced cost under 1e-7 is zero): in newtons, a block of density 1e-3
  // under gravity 1e-6 weighs 1e-9 N and never topples (issue 33).
  double largest = 0;
  for (double f : generalised_loads(m)) largest = std::max(largest, std::abs(f));
  m.force_unit = largest > 0 && std::isfinite(largest) ? largest : 1.0;
  for (size_t k = 0; k < m.joints.size(); ++k) {
    m.ends.push_back({static_cast<int>(k), 0, m.joints[k].a, m.joints[k].a});
    m.ends.push_back({static_cast<int>(k), 1, m.joints[k].b, m.joints[k].b});
  }

  m.lp = new_glp_problem();
  glp_prob* lp = m.lp.get();
  glp_set_obj_dir(lp, GLP_MIN);
  if (m.ncols > 0) glp_add_cols(lp, m.ncols);
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_FR, 0, 0);
  if (!m.ends.empty()) glp_add_rows(lp, 2 * static_cast<int>(m.ends.size()));
  return m;
}

// Generalised loads on the current configuration: (F_x, F_y, M / L_b) per free block, so the
// objective is -F.U' in the scaled variables.
std::vector<double> generalised_loads(const Model& m) {
  std::vector<double> f(m.ncols + 1, 0.0);
  const Case& c = *m.c;
  for (size_t b = 0; b < c.blocks.size(); ++b)
    if (m.col[b] > 0) f[m.col[b] + 1] -= m.weight[b];
  for (const Load& l : c.loads) {
    const int k = m.col[l.block];
    const Vec2 p = m.pos(l.block, l.point);
    f[k] += l.force.x();
    f[k + 1] += l.force.y();
    f[k + 2] += cross(p - m.cen[l.block], l.force) / m.radius[l.block];
  }
  return f;
}

// Rewrites every row, bound and objective coefficient for the current configuration and a
// support step h (0 for the analysis as it stands). The problem's structure never changes.
// Closed corners take back their residual gap over h; open corners must not penetrate over
// h_open (<= h; 0: h), so that an event-driven run can plan a long step without the bound of
// a corner that closes part way changing the mechanism: the step is cut short there instead.
void update_lp(Model& m, double h, double scale, double h_open) {
  // GLPK aborts the process on a non-finite or zero scale; this is the one place to stop it.
  if (!(scale > 0) || !std::isfinite(scale) || !(h >= 0) || !std::isfinite(h))
    throw std::logic_error(std::string("prd: invalid step for the LP (m): ").append(std::to_string(h)));
  const std::vector<double> f = generalised_loads(m);
  m.obj_coef.assign(m.ncols + 1, 0.0);
  for (int j = 1; j <= m.ncols; ++j) m.obj_coef[j] = -f[j] / m.force_unit;
  m.glpk_behind = true;
  std::vector<Increment> inc(m.c->blocks.size());
  for (size_t b = 0; b < inc.size(); ++b)
    if (m.col[b] < 0) inc[b] = support_increment(m, static_cast<int>(b), h);

  int ind[7];
  double val[7];
  if (m.row_coef.empty()) {
    m.row_coef.assign(7 * 2 * m.ends.size(), -1.0);  // count -1: not written yet
    m.row_cols.assign(6 * 2 * m.ends.size(), 0);
    m.row_lb.assign(2 * m.ends.size(), 0.0);
    m.row_type.assign(2 * m.ends.size(), GLP_FR);
    m.row_dirty.assign(2 * m.ends.size(), 0);
  }
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const Vec2 pi = m.on_i(ep), pj = m.on_j(ep);
    const Vec2 n = m.normal(ep), t = perp(n);
    // Both blocks' velocities are taken at the midpoint of the corner's two material points:
    // they coincide up to the second-order drift of the finite update, and one point makes the
    // duals an exact equilibrium of forces applied where read_forces reports them.
    const Vec2 p = 0.5 * (pi + pj);
    for (int r = 0; r < 2; ++r) {
      const Vec2 d = r == 0 ? n : t;
      int cnt = 0;
      double known = 0;  // d.[u] from the supports' prescribed increments
      for (int side = 0; side < 2; ++side) {
        const int b = side == 0 ? jt.i : jt.j;
        const double sgn = side == 0 ? -1.0 : 1.0;
        if (m.col[b] > 0) {
          const int k = m.col[b];
          ind[++cnt] = k, val[cnt] = sgn * d.x();
          ind[++cnt] = k + 1, val[cnt] = sgn * d.y();
          ind[++cnt] = k + 2, val[cnt] = sgn * cross(p - m.cen[b], d) / m.radius[b];
        } else {
          known += sgn * d.dot(inc[b].at_point(p));
        }
      }
      const int row = 2 * static_cast<int>(e) + 1 + r;
      // GLPK rebuilds a row it is given and drops the basis factorisation: rows whose
      // coefficients are those it holds (the blocks of both sides did not move) are left alone.
      double* held = &m.row_coef[7 * (row - 1)];
      bool same = held[0] == cnt;
      for (int k = 1; same && k <= cnt; ++k) same = held[k] == val[k];
      if (!same) {
        held[0] = cnt;
        for (int k = 1; k <= cnt; ++k) held[k] = val[k], m.row_cols[6 * (row - 1) + k - 1] = ind[k];
        m.row_dirty[row - 1] = 1;
      }
      if (r == 0) {
        double gap = (pj - pi).dot(n);
        if (!ep.closed && h_open > 0 && h_open < h) gap *= h / h_open;
        // A held corner's gap is closed at the end of every step: no opening, and a tension if
        // the loads ask for one.
        m.row_lb[row - 1] = (-gap - known) / scale, m.row_type[row - 1] = ep.held ? GLP_FX : GLP_LO;
      } else if (m.sliding_row(e)) {
        // The tangential offset left by earlier finite updates is taken back here, so that
        // the drift of a closed corner never accumulates over the run.
        const double slip = (pj - pi).dot(t);
        m.row_lb[row - 1] = (-slip - known) / scale, m.row_type[row - 1] = GLP_FX;
      } else {
        m.row_lb[row - 1] = 0, m.row_type[row - 1] = GLP_FR;
      }
    }
  }
}

// Gives GLPK the LP update_lp made: the rows whose coefficients changed, every bound and the
// objective. Deferred to where GLPK is asked (solve, evaluate_basis), since most LPs are solved
// by the kept basis without it (kept_basis.hpp).
void sync_glpk(Model& m) {
  if (!m.glpk_behind) return;
  glp_prob* lp = m.lp.get();
  for (int j = 1; j <= m.ncols; ++j) glp_set_obj_coef(lp, j, m.obj_coef[j]);
  int ind[7];
  double val[7];
  for (size_t i = 0; i < m.row_type.size(); ++i) {
    const int row = static_cast<int>(i) + 1;
    if (m.row_dirty[i]) {
      const double* held = &m.row_coef[7 * i];
      const int cnt = static_cast<int>(held[0]);
      for (int k = 1; k <= cnt; ++k) ind[k] = m.row_cols[6 * i + k - 1], val[k] = held[k];
      glp_set_mat_row(lp, row, cnt, ind, val);
      m.row_dirty[i] = 0;
    }
    const double lb = m.row_lb[i];
    glp_set_row_bnds(lp, row, m.row_type[i], lb, m.row_type[i] == GLP_FX ? lb : 0);
  }
  m.glpk_behind = false;
}

// GLPK's solves, where the numbers can fail its internal checks: guarded, so that such a failure
// is the run's error (prd/glpk_hooks.hpp).
int simplex(glp_prob* lp, const glp_smcp& parm) {
  return prd::glpk_guarded([&] { return glp_simplex(lp, &parm); });
}
int exact(glp_prob* lp, const glp_smcp& parm) {
  return prd::glpk_guarded([&] { return glp_exact(lp, &parm); });
}

// GLPK's basis set to the structure's load path (set_static_basis) and evaluated: true where that
// basis is dual feasible by GLPK's own test (an admissible force state), so that the LP is
// bounded and the dual simplex can start from it.
bool start_from_statics(Model& m) {
  glp_prob* lp = m.lp.get();
  if (!set_static_basis(m)) return false;
  if (prd::glpk_guarded([&] { return glp_warm_up(lp); }) != 0) return false;
  return glp_get_dual_stat(lp) == GLP_FEAS;
}

// glp_adv_basis prints whatever msg_lev says; the harness's output is its own.
void quiet_adv_basis(glp_prob* lp) {
  const int was = glp_term_out(GLP_OFF);
  prd::glpk_guarded([&] {
    glp_adv_basis(lp, 0);
    return 0;
  });
  glp_term_out(was);
}

// Whether direction du (per column, 1-based; the columns' units) is a collapse mechanism of the
// LP update_lp wrote: no corner penetrates and no closed joint slides along it (every
// no-penetration row's rate at least 0, every no-sliding row's 0, within kRayTolerance of the
// largest increment: the coefficients are O(1)), and the loads do work on it (the objective
// falls). Computed from the model's rows, not from GLPK's factorisation, so that it checks what
// the simplex claimed.
bool is_mechanism(const Model& m, const std::vector<double>& du) {
  if (du.size() != static_cast<size_t>(m.ncols) + 1) return false;
  double size = 0, work = 0;
  for (int j = 1; j <= m.ncols; ++j) size = std::max(size, std::abs(du[j])), work += m.obj_coef[j] * du[j];
  if (!(size > 0) || !std::isfinite(size) || !(work < 0)) return false;
  for (size_t i = 0; i < m.row_type.size(); ++i) {
    if (m.row_type[i] == GLP_FR) continue;
    const double rate = m.row_activity(i, du);
    if (rate < -kRayTolerance * size) return false;
    if (m.row_type[i] == GLP_FX && rate > kRayTolerance * size) return false;
  }
  return true;
}

// GLPK's certificate of an unbounded LP as a direction of the columns: the nonbasic variable
// whose move improves the objective without bound (glp_get_unbnd_ray) moves by one unit the
// way its reduced cost improves, and the basic columns with it (its column of the simplex
// table). Empty where GLPK names no such variable.
std::vector<double> unbounded_ray(const Model& m) {
  glp_prob* lp = m.lp.get();
  const int rows = glp_get_num_rows(lp), k = glp_get_unbnd_ray(lp);
  if (k <= 0 || !glp_bf_exists(lp)) return {};
  if ((k <= rows ? glp_get_row_stat(lp, k) : glp_get_col_stat(lp, k - rows)) == GLP_BS) return {};
  const double d = k <= rows ? glp_get_row_dual(lp, k) : glp_get_col_dual(lp, k - rows);
  const double way = d < 0 ? 1.0 : -1.0;  // minimisation: a negative reduced cost improves upwards
  std::vector<double> du(m.ncols + 1, 0.0);
  if (k > rows) du[k - rows] = way;
  std::vector<int> ind(rows + 1);
  std::vector<double> val(rows + 1);
  const int len = prd::glpk_guarded([&] { return glp_eval_tab_col(lp, k, ind.data(), val.data()); });
  for (int t = 1; t <= len; ++t)
    if (ind[t] > rows) du[ind[t] - rows] = way * val[t];
  return du;
}

// Runs the primal simplex from the previous step's basis (the warm start that makes a run
// fast). Degenerate LPs can stall; an iteration limit catches that, and the solve is repeated
// from a fresh advanced basis with the textbook ratio test; then, on an LP small enough for it
// to end in reasonable time (kExactRows), in exact rational arithmetic, and on a larger one from
// GLPK's standard basis (prd/README.md, "Known limits": where the simplex fails from the
// advanced basis on large walls, it solved them from the standard one); so a run never hangs
// and never reports a status GLPK did not prove. An unbounded LP (a collapse) counts as proved
// only where GLPK's ray is a mechanism of the LP's rows (is_mechanism): a simplex that lost its
// accuracy can miss the row that bounds it.
LpStatus solve(Model& m, bool confirm_infeasible) {
  glp_prob* lp = m.lp.get();
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.meth = GLP_PRIMAL;
  // Fifty pivots per variable catch a stall on an LP the exact simplex can take next; on a
  // larger one that would be hours (a pivot costs milliseconds there), so one per variable: the
  // first LP of walls takes a tenth of that from the advanced basis, a quarter from the standard.
  const int vars = glp_get_num_rows(lp) + glp_get_num_cols(lp);
  parm.it_lim = glp_get_num_rows(lp) <= kExactRows ? 1000 + 50 * vars : vars;
  // The exact simplex's statuses are proved in rational arithmetic (and it names no ray).
  // "No feasible point" ends the run as an error, so in double precision it is taken only where
  // the simplex found it from two starts of GLPK's own (the advanced and the standard basis),
  // or from one where the other failed: from the previous step's basis, and once also from the
  // advanced basis, GLPK's first phase has called feasible LPs infeasible (stack-bond walls
  // whose settling half lands on its ground; an elastic LP over the same rows met every row,
  // and the standard basis solved them).
  int no_feasible_starts = 0;
  auto conclusive = [&](int rc, bool rational = false, bool own_start = true) {
    if (rc != 0) return false;
    const int st = glp_get_status(lp);
    if (st == GLP_UNBND) return rational || is_mechanism(m, unbounded_ray(m));
    if (st == GLP_NOFEAS) return rational || !confirm_infeasible || (own_start && ++no_feasible_starts >= 2);
    return st == GLP_OPT;
  };
  const auto t0 = cpu_now();
  // A fresh LP: GLPK's standard basis (every row slack basic) makes the simplex bring each
  // block's columns in one pivot at a time, about two pivots per block, each costing in
  // proportion to the rows, so the first LP grows with the square of the blocks. Bixby's
  // advanced basis starts with most columns basic and halves the pivots (a wall of 4000 blocks:
  // 8000 pivots, 3.4 s, became 4040, 1.9 s; the first step of a run on a 2,049-block wall:
  // 13.8 s of CPU became 4.0 s, a 497-block wall's 0.56 s 0.13 s); the growth stays quadratic,
  // which is the simplex's. Runs start from it from kAdvancedBasisBlocks free blocks up only: a
  // statically indeterminate structure has many admissible force states, the start decides
  // which one the LP's duals are, and the standard scenes (at most 276 blocks) keep theirs (the
  // cathedral's aisles: 1.3% of the weight apart; mechanisms and capacities are the same from
  // either start, tests/prd/first_basis_test.cpp).
  const bool large = m.ncols >= 3 * kAdvancedBasisBlocks;
  const bool advanced =
      m.first_basis == FirstBasis::advanced || m.first_basis == FirstBasis::statics || (m.first_basis == FirstBasis::by_size && large);
  m.interior.own = false;
  // Most LPs after the first are solved by the basis of the one before (kept_basis.hpp).
  if (!m.fresh && m.kept_basis_allowed && !m.columns_boxed && t_use_kept_basis && solve_by_kept_basis(m)) {
    m.lp_s += seconds_since(t0);
    ++m.lp_solves;
    ++m.kept_basis_solves;
    return LpStatus::optimal;
  }
  // A large structure's LP in a fixed-step run: by the interior point's solution of the LP
  // before where it still holds (a wall hanging from its still half), else by the interior point
  // (interior.hpp); GLPK where that fails, an unbounded LP (a collapse) among them.
  if (m.kept_basis_allowed && !m.columns_boxed && m.ncols >= 3 * t_interior_blocks) {
    // Off with the kept basis (the tests' GLPK reference): the last solution is a kept one too.
    const bool kept = t_use_kept_basis && interior_still_optimal(m);
    if (kept || solve_interior(m)) {
      m.kept.own = false;
      m.lp_s += seconds_since(t0);
      ++m.lp_solves;
      ++(kept ? m.kept_basis_solves : m.interior_solves);
      return LpStatus::optimal;
    }
  }
  sync_glpk(m);
  const int rows = glp_get_num_rows(lp);
  int rc = 0;
  bool done = false;
  auto try_simplex = [&](const glp_smcp& how, bool own_start = true) {
    rc = simplex(lp, how);
    done = conclusive(rc, false, own_start);
  };
  // A large structure whose own load path (static_basis.cpp) is still admissible after the step
  // is solved by it: GLPK's dual simplex confirms it without a pivot (`check` on a standing wall
  // of 10,052 blocks: 0.5 s in all; 68 s before, where the advanced basis fails and the standard
  // one solves it; prd/README.md, "The load path"). Not on the smaller ones: the standard scenes
  // keep the force states of their starts, as above. Where the step makes the load path
  // infeasible the primal simplex from the advanced basis goes on: the dual simplex from the
  // load path solved the settling 10,052-block wall's first LP in 16,769 pivots and 141 s, but
  // ended on another optimum of that degenerate LP (on a 12-course wall: the wall turning about a
  // point over its centre of gravity, which stands over the still ground's edge, at no work),
  // from which the second LP took minutes. FirstBasis::statics (the tests): from the load path
  // by the dual simplex wherever it is admissible.
  const bool statics = m.first_basis == FirstBasis::statics;
  if (m.fresh && (statics || (advanced && large)) && start_from_statics(m) && (statics || glp_get_prim_stat(lp) == GLP_FEAS)) {
    glp_smcp dual = parm;
    dual.meth = GLP_DUAL;
    try_simplex(dual);
    // Where it failed, the LP stays fresh: the advanced basis next, which also drops the factors
    // GLPK keeps of the basis a failed simplex stopped at.
    if (done) m.fresh = false, ++m.load_path_solves;
  }
  const bool started_standard = m.fresh && !advanced;
  bool warm = false;  // the simplex started from the previous LP's basis
  if (!done) {
    warm = !m.fresh;
    if (m.fresh && advanced) quiet_adv_basis(lp);
    m.fresh = false;
    try_simplex(parm, !warm);
  }
  // Where the simplex failed from the previous basis (not a stall: that goes on to the textbook
  // ratio test), or found no feasible point from it, the same simplex from the advanced basis
  // (stack-bond walls of 100 blocks whose settling half lands on its ground: it then solved the
  // LP at once, where the textbook ratio test failed and the exact simplex took 40-60 s). "No
  // feasible point" from one of GLPK's own starts is checked from the standard basis.
  if (!done && warm && rc != GLP_EITLIM) {
    quiet_adv_basis(lp);
    try_simplex(parm);
  }
  // The check is the other of GLPK's own starts: the advanced basis after the standard one.
  bool no_feasible = false;  // found by one of GLPK's own starts, and no start found a feasible point
  if (!done && rc == 0 && glp_get_status(lp) == GLP_NOFEAS) {
    if (started_standard) {
      quiet_adv_basis(lp);
    } else {
      glp_std_basis(lp);
      prd::glpk_guarded([&] { return glp_factorize(lp); });  // drops the factors of the basis it stopped at
    }
    try_simplex(parm);
    // Where that start failed, the first one's finding stands (the exact simplex next took
    // minutes on a 9-course wall's LP that GLPK had found infeasible twice).
    if (!done && rc != 0) done = no_feasible = true;
  }
  if (!done) {
    quiet_adv_basis(lp);
    parm.r_test = GLP_RT_STD;
    try_simplex(parm);
  }
  if (!done && rows <= kExactRows) {
    quiet_adv_basis(lp);
    rc = exact(lp, parm);
    done = conclusive(rc, true);
  }
  // Too large for the exact simplex: GLPK's standard basis, where the first try did not start
  // from it. On walls of 6,000 blocks and more the simplex fails from the advanced basis after
  // some 2,000 pivots, and from the standard one it solved the 6,442-block wall's first LP in
  // 24,888 pivots, a quarter of its rows and columns.
  const bool standard_tried = !done && !started_standard && rows > kExactRows;
  if (standard_tried) {
    glp_smcp standard = parm;
    standard.r_test = GLP_RT_HAR;
    glp_std_basis(lp);
    // A failed try leaves GLPK holding the factors of the basis it failed at; should the
    // standard basis be the one it started from, glp_std_basis would not drop them.
    prd::glpk_guarded([&] { return glp_factorize(lp); });
    try_simplex(standard);
    // The advanced basis failed: the standard one's "no feasible point" stands alone.
    if (!done && rc == 0 && glp_get_status(lp) == GLP_NOFEAS) done = no_feasible = true;
  }
  keep_basis(m);
  m.lp_s += seconds_since(t0);
  ++m.lp_solves;
  if (!done) {
    std::string why = "GLPK could not solve the step's LP (" + std::to_string(rows) + " rows, " + std::to_string(m.ncols) + " columns): ";
    if (rc == 0 && glp_get_status(lp) == GLP_UNBND)
      why += "its simplex called it unbounded, but its ray is no mechanism (a corner penetrates or a closed joint slides along it)";
    else
      why += "its simplex failed (code " + std::to_string(rc) + ") from its start and from GLPK's advanced basis" +
             (standard_tried ? " and standard basis" : "");
    if (rows > kExactRows)
      why += "; too large for the exact fallback (at most " + std::to_string(kExactRows) + " rows): prd/README.md, \"Known limits\"";
    else
      why += ", and so did its exact simplex";
    throw std::runtime_error(why);
  }
  if (no_feasible) return LpStatus::infeasible;
  switch (glp_get_status(lp)) {
    case GLP_OPT: return LpStatus::optimal;
    case GLP_UNBND: return LpStatus::unbounded;
    default: return LpStatus::infeasible;  // GLP_NOFEAS: conclusive() admits nothing else
  }
}

// The last solve's values: GLPK's, or those of the kept basis or the interior point where that
// solved it.
double row_prim(const Model& m, int row) {
  return m.interior.own ? interior_row(m, row) : m.kept.own ? kept_row(m, row) : glp_get_row_prim(m.lp.get(), row);
}
double row_dual(const Model& m, int row) {
  return m.interior.own ? interior_dual(m, row) : m.kept.own ? kept_dual(m, row) : glp_get_row_dual(m.lp.get(), row);
}
double objective(const Model& m) {
  return (m.interior.own ? interior_objective(m) : m.kept.own ? kept_objective(m) : glp_get_obj_val(m.lp.get())) * m.force_unit;
}
double col_value(const Model& m, int j) {
  return m.interior.own ? interior_col(m, j) : m.kept.own ? kept_col(m, j) : glp_get_col_prim(m.lp.get(), j);
}
double corner_force(const Model& m, size_t e) { return row_dual(m, 2 * static_cast<int>(e) + 1) * m.force_unit; }
double corner_slack(const Model& m, size_t e) {
  const int row = 2 * static_cast<int>(e) + 1;
  return row_prim(m, row) - m.row_lb[row - 1];
}

// Forces from the row duals: joint resultants and support reactions, on the current geometry.
void read_forces(const Model& m, StepRecord& rec) {
  const Case& c = *m.c;
  std::vector<Reaction> reac;
  std::vector<int> reac_of(c.blocks.size(), -1);
  for (size_t b = 0; b < c.blocks.size(); ++b)
    if (c.blocks[b].support) {
      reac_of[b] = static_cast<int>(reac.size());
      reac.push_back({c.blocks[b].id, Vec2(0, 0), 0.0});
    }
  for (size_t k = 0; k < m.joints.size(); ++k) {
    const Interface& jt = m.joints[k];
    double N = 0, T = 0;
    Vec2 moment_point(0, 0);
    Vec2 n(0, 0);
    Vec2 at[2], f_at[2];  // each corner's point and force on block j
    int shear_corner = 0;
    for (int corner = 0; corner < 2; ++corner) {
      const size_t e = 2 * k + corner;
      const Endpoint& ep = m.ends[e];
      const double fn = corner_force(m, e);
      const double ft = m.sliding_row(e) ? row_dual(m, 2 * static_cast<int>(e) + 2) * m.force_unit : 0.0;
      n = m.normal(ep);
      const Vec2 p = 0.5 * (m.on_i(ep) + m.on_j(ep));
      N += fn;
      T += ft;
      moment_point += fn * p;
      const Vec2 fk = fn * n + ft * perp(n);  // on block j
      at[corner] = p, f_at[corner] = fk;
      if (ft != 0) shear_corner = corner;
      // Reactions: the force the structure receives from the support, and its moment.
      for (int side = 0; side < 2; ++side) {
        const int b = side == 0 ? jt.i : jt.j;
        if (reac_of[b] < 0) continue;
        const Vec2 on_structure = side == 0 ? fk : Vec2(-fk);
        Reaction& r = reac[reac_of[b]];
        r.force += on_structure;
        const Vec2 about = m.motion_of[b] >= 0 ? m.pos(b, c.motion.supports[m.motion_of[b]].about) : m.cen[b];
        r.moment += cross(p - about, on_structure);
      }
    }
    if (N > 0 || T != 0) {
      JointForce jf;
      jf.joint = static_cast<int>(k);
      jf.normal = N;
      jf.shear = T;
      jf.n = n;
      // The resultant on its line of action (on_line_of_action), nearest to the normal forces'
      // centre, or without normal force to the corner that carries the shear. The shear acts at
      // its no-sliding row's corner, which stands off the line through that centre by the gap
      // or overlap across the joint where the corners are at different levels (a block that
      // landed again): placed at the centre, the resultant's moment about a block was off by
      // the shear times that offset (up to 1.2 N m on hanging stack-bond walls).
      const Vec2 centre = N > 0 ? Vec2(moment_point / N) : at[shear_corner];
      double moment = 0;
      for (int corner = 0; corner < 2; ++corner) moment += cross(at[corner] - centre, f_at[corner]);
      jf.point = on_line_of_action(centre, f_at[0] + f_at[1], moment);  // N > 0 or T != 0: R is not zero
      rec.forces.push_back(jf);
    }
  }
  rec.reactions = std::move(reac);
}

// Slack of each no-penetration row in m: the endpoint's gap at the end of the increment,
// to first order.
std::vector<double> slacks(const Model& m, double scale) {
  std::vector<double> s(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const int row = 2 * static_cast<int>(e) + 1;
    s[e] = (row_prim(m, row) - m.row_lb[row - 1]) * scale;
  }
  return s;
}

// The collapse mechanism: the same LP with every increment boxed to one unit, so that it has
// an optimum whose open corners show the mechanism. The columns are freed again afterwards.
// `moved`, where given, gets every block's pose after the mechanism's own boxed increment (the
// supports held; each increment at most `scale`).
Mechanism collapse_mechanism(Model& m, double scale, std::vector<Pose>* moved) {
  glp_prob* lp = m.lp.get();
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_DB, -1, 1);
  m.kept.rows.clear();  // its vertex ignores the boxes
  m.columns_boxed = true;
  Mechanism out;
  // GLPK's first "no feasible point" is taken here, unconfirmed: the ray below is solved then,
  // and its LP is always feasible (zero meets every row), so nothing is lost by a wrong one.
  LpStatus st = solve(m, false);
  // Where the step's own motion does not fit in the boxes (the settling cathedral: some
  // increment over a unit of the step), the mechanism is the LP's ray itself: the directions
  // in which every row's left-hand side keeps its sign, the LP with every bound at zero, boxed.
  // The step's bounds go back to GLPK at its next solve.
  const auto solve_ray = [&] {
    for (size_t i = 0; i < m.row_type.size(); ++i)
      if (m.row_type[i] != GLP_FR) glp_set_row_bnds(lp, static_cast<int>(i) + 1, m.row_type[i], 0, 0);
    const LpStatus ray_status = solve(m);
    m.glpk_behind = true;  // after the solve: the step's bounds go back to GLPK at its next one
    return ray_status;
  };
  const bool ray = st != LpStatus::optimal;
  if (ray) st = solve_ray();
  if (st == LpStatus::optimal) {
    // Open: at the end of the boxed step; along the ray, where it opens or is open already.
    std::vector<double> s(m.ends.size());
    if (ray)
      for (size_t e = 0; e < m.ends.size(); ++e) s[e] = std::max(row_prim(m, 2 * static_cast<int>(e) + 1) * scale, m.gap(m.ends[e]) - m.tol);
    else
      s = slacks(m, scale);
    for (size_t e = 0; e < m.ends.size(); ++e)
      if (s[e] > 1e-6 * scale) out.open_corners.push_back({m.ends[e].joint, m.ends[e].corner});
    for (size_t b = 0; b < m.col.size(); ++b) {
      if (m.col[b] < 0) continue;
      double v = 0;
      for (int k = 0; k < 3; ++k) v = std::max(v, std::abs(col_value(m, m.col[b] + k)));
      if (v > 1e-6) out.moving_blocks.push_back(static_cast<int>(b));
    }
  }
  if (moved && st == LpStatus::optimal) {
    // A configuration that shows the mechanism itself: where the last step's motion alone
    // moves no joint (a block carried by its slab up to its tipping tilt), the collapse
    // configuration cannot. The ray's LP (every bound at zero, boxed), without the step's
    // imposed motion: the boxed step's optimum mixes the motion the step drives with the free
    // mechanism, and which corner of the boxes it takes is not unique.
    if (!ray) st = solve_ray();
    if (st == LpStatus::optimal) {
      const std::vector<double> U = column_values(m), none;
      moved->clear();
      for (size_t b = 0; b < m.cen.size(); ++b) {
        Pose p{m.cen[b].x(), m.cen[b].y(), m.angle[b]};
        if (m.col[b] > 0) {
          Vec2 cen;
          pose_after(m, Path{U, none}, b, scale, cen, p.angle);
          p.x = cen.x();
          p.y = cen.y();
        }
        moved->push_back(p);
      }
    }
  }
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_FR, 0, 0);
  m.columns_boxed = false;
  return out;
}

void lp_check_fields(const Model& m, double scale, StepRecord& rec) {
  // Strong duality: the primal optimum equals sum(dual * bound) over the active rows.
  double dual = 0;
  for (size_t i = 0; i < m.row_type.size(); ++i)
    if (m.row_type[i] != GLP_FR) dual += row_dual(m, static_cast<int>(i) + 1) * m.row_lb[i];
  rec.lp = LpOptima{objective(m) * scale, dual * m.force_unit * scale};
}

std::vector<double> column_values(const Model& m) {
  std::vector<double> U(m.ncols + 1, 0.0);
  for (int j = 1; j <= m.ncols; ++j) U[j] = col_value(m, j);
  return U;
}

void save_basis(const Model& m, Accepted& a) {
  glp_prob* lp = m.lp.get();
  a.row_stat.resize(glp_get_num_rows(lp) + 1);
  a.col_stat.resize(m.ncols + 1);
  for (size_t i = 1; i < a.row_stat.size(); ++i) a.row_stat[i] = glp_get_row_stat(lp, static_cast<int>(i));
  for (int j = 1; j <= m.ncols; ++j) a.col_stat[j] = glp_get_col_stat(lp, j);
  a.slack.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const int row = 2 * static_cast<int>(e) + 1;
    a.slack[e] = row_prim(m, row) - m.row_lb[row - 1];
  }
}

// The LP of the current configuration and contact state for a step h (open corners held over
// h_open) with a's basis, evaluated without a simplex iteration (glp_warm_up's code).
int evaluate_basis(Model& m, const Accepted& a, double h, double h_open) {
  glp_prob* lp = m.lp.get();
  update_lp(m, h, h, h_open);
  const auto t0 = cpu_now();
  sync_glpk(m);
  for (size_t i = 1; i < a.row_stat.size(); ++i) glp_set_row_stat(lp, static_cast<int>(i), a.row_stat[i]);
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_stat(lp, j, a.col_stat[j]);
  const int rc = prd::glpk_guarded([&] { return glp_warm_up(lp); });
  keep_basis(m);  // the restored basis, and GLPK's values of it
  m.interior.own = false;
  m.lp_s += seconds_since(t0);
  ++m.basis_evaluations;
  return rc;
}

// ---- The sliding check's feasibility LP (FrictionProblem in internal.hpp).

void load_friction_lp(SlidingLp& S, const FrictionProblem& p) {
  glp_prob* lp = S.lp.get();
  glp_erase_prob(lp);
  S.fresh = true;
  glp_add_cols(lp, p.ncols);
  for (int j = 1; j <= p.ncols; ++j) glp_set_col_bnds(lp, j, GLP_LO, 0, 0);
  for (int jt : p.joints_in_contact) glp_set_col_bnds(lp, p.ft_col[jt], GLP_FR, 0, 0);
  glp_add_rows(lp, p.nrows_eq + 2 * static_cast<int>(p.joints_in_contact.size()));
  for (int r = 1; r <= p.nrows_eq; ++r) glp_set_row_bnds(lp, r, GLP_FX, -p.loads[r], -p.loads[r]);
  for (size_t q = 0; q < p.joints_in_contact.size(); ++q)
    for (int s = 0; s < 2; ++s) glp_set_row_bnds(lp, p.nrows_eq + 2 * static_cast<int>(q) + 1 + s, GLP_UP, 0, 0);
  glp_load_matrix(lp, static_cast<int>(p.ia.size()) - 1, p.ia.data(), p.ja.data(), p.ar.data());
}

bool friction_feasible(SlidingLp& S, const FrictionProblem& p, double mu) {
  glp_prob* lp = S.lp.get();
  // The friction rows at this mu:  f_t - mu sum f_n <= 0  and  -f_t - mu sum f_n <= 0.
  std::vector<int> ind;
  std::vector<double> val;
  for (size_t q = 0; q < p.joints_in_contact.size(); ++q) {
    const int jt = p.joints_in_contact[q];
    for (int s = 0; s < 2; ++s) {
      ind.assign(1, 0);
      val.assign(1, 0.0);
      ind.push_back(p.ft_col[jt]), val.push_back(s == 0 ? 1.0 : -1.0);
      for (int c = 0; c < 2; ++c)
        if (p.fn_col[2 * jt + c]) ind.push_back(p.fn_col[2 * jt + c]), val.push_back(-mu);
      glp_set_mat_row(lp, p.nrows_eq + 2 * static_cast<int>(q) + 1 + s, static_cast<int>(ind.size()) - 1, ind.data(), val.data());
    }
  }
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.it_lim = 1000 + 50 * (glp_get_num_rows(lp) + p.ncols);
  if (S.fresh) glp_std_basis(lp), S.fresh = false;
  ++S.solves;
  int rc = simplex(lp, parm);
  if (rc != 0) {  // a stalled warm start: once more from the standard basis
    glp_std_basis(lp);
    rc = simplex(lp, parm);
  }
  return rc == 0 && glp_get_status(lp) == GLP_OPT;
}

double friction_col_value(const SlidingLp& S, int j) { return glp_get_col_prim(S.lp.get(), j); }

}  // namespace masonry::prd_detail
