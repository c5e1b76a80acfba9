// The previous step's basis, solved again without GLPK where it is still optimal (kept_basis.hpp).
#include "prd/kept_basis.hpp"

#include <klu.h>

#include <algorithm>
#include <cmath>

#include "prd/internal.hpp"

namespace masonry::prd_detail {

// Everything a solve by the kept basis needs, kept between LPs so that a run's solves allocate
// nothing once the first has sized it.
struct KeptBasisValues {
  std::vector<int> basic_of;  // per column (1-based): its index among the basic columns, -1 nonbasic
  // A_N in compressed columns: row k is nonbasic row rows[k], column b the b-th basic column.
  std::vector<int> ap, ai, fill, pattern;              // pattern: ap and ai when the ordering was made
  std::vector<double> ax, factorised, rhs, xb, cb, y;  // factorised: the ax of the factors
  // KLU (SuiteSparse): its ordering, made once per pattern, and the numeric factors.
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  std::vector<double> x, row, dual, reduced;  // per column (1-based), per LP row (index row - 1)
  std::vector<char> nonbasic;                 // per LP row
  double obj = 0;
  KeptBasisValues() { klu_defaults(&common); }
  ~KeptBasisValues() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
  KeptBasisValues(const KeptBasisValues&) = delete;
  KeptBasisValues& operator=(const KeptBasisValues&) = delete;
};

namespace {

// GLPK's primal simplex's own tests of a basis, or tighter: a basis taken here is one GLPK's
// simplex stops at without a pivot, up to the round-off between its factorisation and this one.
// GLPK shifts every bound to zero before its tests, so its primal test is absolute: it starts a
// phase 1 where a basic variable is below its bound by more than 0.97 tol_bnd (tol_bnd 1e-7);
// this one takes half of that. Its dual test is tol_dj (1e-7) plus 1e-10 times the cost. The
// LP's units are a step and the force unit, so its values are of order one.
double dual_eps(double cost) { return kDualEps + 1e-10 * std::abs(cost); }
// Factors whose ratio of smallest to largest diagonal entry of U (klu_rcond) is below this are
// not used: GLPK refuses a basis whose condition estimate passes 1 / DBL_EPSILON.
constexpr double kLeastRcond = 1e-12;

// A_N in compressed columns from the rows as update_lp holds them.
void build_matrix(const Model& m, KeptBasisValues& v, const std::vector<int>& rows) {
  const int n = static_cast<int>(rows.size());
  v.ap.assign(n + 1, 0);
  for (int row : rows) {
    const double* held = &m.row_coef[7 * (row - 1)];
    const int* cols = &m.row_cols[6 * (row - 1)];
    for (int q = 0; q < static_cast<int>(held[0]); ++q)
      if (const int b = v.basic_of[cols[q]]; b >= 0) ++v.ap[b + 1];
  }
  for (int b = 0; b < n; ++b) v.ap[b + 1] += v.ap[b];
  v.ai.resize(v.ap[n]);
  v.ax.resize(v.ap[n]);
  v.rhs.resize(n);
  v.fill.assign(v.ap.begin(), v.ap.end() - 1);  // the next free place in each column
  for (int r = 0; r < n; ++r) {
    const int row = rows[r];
    const double* held = &m.row_coef[7 * (row - 1)];
    const int* cols = &m.row_cols[6 * (row - 1)];
    for (int q = 0; q < static_cast<int>(held[0]); ++q)
      if (const int b = v.basic_of[cols[q]]; b >= 0) v.ai[v.fill[b]] = r, v.ax[v.fill[b]++] = held[q + 1];
    // A nonbasic row stands at its lower bound (rows are bounded below or fixed), a free one at
    // zero (GLPK's status NF).
    v.rhs[r] = m.row_type[row - 1] == GLP_FR ? 0.0 : m.row_lb[row - 1];
  }
}

// KLU's factors of A_N: a refactorisation in the last pivot order where the pattern is the last
// one's and that order still serves, else an ordering and a factorisation with pivoting.
bool factorise(KeptBasisValues& v, int n) {
  const bool same = v.symbolic && v.numeric && v.pattern.size() == v.ap.size() + v.ai.size() &&
                    std::equal(v.ap.begin(), v.ap.end(), v.pattern.begin()) && std::equal(v.ai.begin(), v.ai.end(), v.pattern.begin() + v.ap.size());
  // Blocks that did not move leave their rows as they were: where none of A_N's changed (a wall
  // hanging from its fixed half), the factors are those of the last solve.
  if (same && v.ax == v.factorised) return true;
  v.factorised = v.ax;
  if (same && klu_refactor(v.ap.data(), v.ai.data(), v.ax.data(), v.symbolic, v.numeric, &v.common) && klu_rcond(v.symbolic, v.numeric, &v.common) &&
      v.common.rcond > kLeastRcond)
    return true;
  if (v.numeric) klu_free_numeric(&v.numeric, &v.common);
  if (!same) {
    if (v.symbolic) klu_free_symbolic(&v.symbolic, &v.common);
    v.symbolic = klu_analyze(n, v.ap.data(), v.ai.data(), &v.common);
    if (!v.symbolic) return false;
    v.pattern.assign(v.ap.begin(), v.ap.end());
    v.pattern.insert(v.pattern.end(), v.ai.begin(), v.ai.end());
  }
  v.numeric = klu_factor(v.ap.data(), v.ai.data(), v.ax.data(), v.symbolic, &v.common);
  if (v.numeric && v.common.status == KLU_OK && klu_rcond(v.symbolic, v.numeric, &v.common) && v.common.rcond > kLeastRcond) return true;
  v.factorised.clear();
  return false;
}

}  // namespace

void keep_basis(Model& m) {
  KeptBasis& k = m.kept;
  k.rows.clear();
  k.own = false;
  glp_prob* lp = m.lp.get();
  if (!k.v) k.v = std::make_shared<KeptBasisValues>();
  KeptBasisValues& v = *k.v;
  // Free columns only, basic or nonbasic at zero (a degenerate direction GLPK left out of the
  // basis); boxed ones (collapse_mechanism) have bounds this solve does not check.
  v.basic_of.assign(m.ncols + 1, -1);
  int basic = 0;
  for (int j = 1; j <= m.ncols; ++j) {
    if (glp_get_col_type(lp, j) != GLP_FR) return;
    const int stat = glp_get_col_stat(lp, j);
    if (stat == GLP_BS)
      v.basic_of[j] = basic++;
    else if (stat != GLP_NF)
      return;
  }
  const int nr = glp_get_num_rows(lp);
  for (int i = 1; i <= nr; ++i)
    if (glp_get_row_stat(lp, i) != GLP_BS) k.rows.push_back(i);
  if (static_cast<int>(k.rows.size()) != basic) k.rows.clear();  // not a square system: GLPK decides
}

bool solve_by_kept_basis(Model& m) {
  KeptBasis& k = m.kept;
  k.own = false;
  if (k.rows.empty() || !k.v) return false;
  KeptBasisValues& v = *k.v;
  const int n = static_cast<int>(k.rows.size());
  const int nr = static_cast<int>(m.row_type.size());
  build_matrix(m, v, k.rows);
  if (!factorise(v, n)) return false;
  v.xb = v.rhs;
  if (!klu_solve(v.symbolic, v.numeric, n, 1, v.xb.data(), &v.common)) return false;
  v.x.assign(m.ncols + 1, 0.0);
  for (int j = 1; j <= m.ncols; ++j)
    if (v.basic_of[j] >= 0) {
      v.x[j] = v.xb[v.basic_of[j]];
      if (!std::isfinite(v.x[j])) return false;
    }
  // Primal feasibility: every basic row within its bounds.
  v.nonbasic.assign(nr, 0);
  for (int row : k.rows) v.nonbasic[row - 1] = 1;
  v.row.resize(nr);
  for (int i = 0; i < nr; ++i) {
    const double s = m.row_activity(i, v.x);
    // A nonbasic row's activity is its bound (or zero, free), exactly, as GLPK gives it.
    v.row[i] = !v.nonbasic[i] ? s : m.row_type[i] == GLP_FR ? 0.0 : m.row_lb[i];
    if (v.nonbasic[i] || m.row_type[i] == GLP_FR) continue;
    const double lb = m.row_lb[i];
    if (!std::isfinite(s) || s < lb - kPrimalEps) return false;
    if (m.row_type[i] == GLP_FX && s > lb + kPrimalEps) return false;
  }
  // Dual feasibility: A_N^T y = c_B; y >= 0 on the rows held at a lower bound (a fixed row's
  // dual is free, a free row's zero); a nonbasic free column's reduced cost c_j - y.A_j zero.
  v.cb.resize(n);
  for (int j = 1; j <= m.ncols; ++j)
    if (v.basic_of[j] >= 0) v.cb[v.basic_of[j]] = m.obj_coef[j];
  v.y = v.cb;
  if (!klu_tsolve(v.symbolic, v.numeric, n, 1, v.y.data(), &v.common)) return false;
  v.dual.assign(nr, 0.0);
  v.reduced.assign(m.obj_coef.begin(), m.obj_coef.end());
  for (int r = 0; r < n; ++r) {
    const int i = k.rows[r] - 1;
    if (!std::isfinite(v.y[r])) return false;
    if (m.row_type[i] == GLP_LO && v.y[r] < -dual_eps(0)) return false;
    if (m.row_type[i] == GLP_FR && std::abs(v.y[r]) > dual_eps(0)) return false;
    v.dual[i] = v.y[r];
    const double* held = &m.row_coef[7 * i];
    const int* cols = &m.row_cols[6 * i];
    for (int q = 0; q < static_cast<int>(held[0]); ++q) v.reduced[cols[q]] -= v.y[r] * held[q + 1];
  }
  for (int j = 1; j <= m.ncols; ++j)
    if (v.basic_of[j] < 0 && std::abs(v.reduced[j]) > dual_eps(m.obj_coef[j])) return false;
  v.obj = 0;
  for (int j = 1; j <= m.ncols; ++j) v.obj += m.obj_coef[j] * v.x[j];
  k.own = true;
  return true;
}

double kept_objective(const Model& m) { return m.kept.v->obj; }
double kept_col(const Model& m, int j) { return m.kept.v->x[j]; }
double kept_row(const Model& m, int row) { return m.kept.v->row[row - 1]; }
double kept_dual(const Model& m, int row) { return m.kept.v->dual[row - 1]; }

}  // namespace masonry::prd_detail
