// The interior point for large LPs (interior.hpp).
//
// The LP as update_lp writes it: columns x free (the blocks' increments over the step), rows
// a_i x >= b_i (no penetration: GLP_LO), a_i x = b_i (no sliding, held corners: GLP_FX) and free
// rows (GLP_FR, ignored); minimise c x. Its dual: A' y = c, y >= 0 on the LO rows, the corner
// forces.
//
// Mehrotra's predictor-corrector on the primal-dual equations, with slacks s on the LO rows,
// s o y = mu driven to zero. Each Newton step eliminates s and y and solves the normal equations
// (A' W A + beta I) dx = r, W = y / s on the LO rows, by CHOLMOD's supernodal Cholesky: A' W A is
// the blocks' contact graph (a block couples to the blocks it touches), whose ordering is
// analysed once per model and reused. The equality rows enter with a weight 1 / kDelta (a dual
// regularisation: each step meets a_i dx + kDelta dz_i = residual_i, the residual left for the
// next step), since a free dual has no slack to weigh it by. Each solve is refined twice against
// the matrix, whose weights span twenty orders of magnitude near the optimum.
#include "prd/interior.hpp"

#include <cholmod.h>
#include <glpk.h>

#include <algorithm>
#include <cmath>

#include "prd/internal.hpp"

namespace masonry::prd_detail {

struct InteriorValues {
  cholmod_common cc;
  cholmod_sparse* F = nullptr;  // A' with each LP row's coefficients times sqrt(its weight): F F' = A' W A
  cholmod_factor* L = nullptr;  // the analysis of F F' (made once: the rows' columns never change) and its factors
  cholmod_dense* B = nullptr;   // a right-hand side, then its solution
  std::vector<int> counts;      // per LP row, its coefficient count when F was made
  // The last solution: x per column (1-based), the activity and dual of each LP row (0-based).
  std::vector<double> x, row, dual;
  double obj = 0;
  // The optimality test's work (per LP row, per column), kept so that testing the last solution at
  // every step of a run allocates nothing once sized.
  std::vector<double> ax, g, size;
  InteriorValues() {
    cholmod_start(&cc);
    cc.print = 0;  // a failed factorisation is handled here (more regularisation), not printed
  }
  ~InteriorValues() {
    if (B) cholmod_free_dense(&B, &cc);
    if (L) cholmod_free_factor(&L, &cc);
    if (F) cholmod_free_sparse(&F, &cc);
    cholmod_finish(&cc);
  }
  InteriorValues(const InteriorValues&) = delete;
  InteriorValues& operator=(const InteriorValues&) = delete;
};

namespace {

// The tests a solution must pass (interior.hpp): the kept basis's (kept_basis.hpp), and the
// equilibrium also within kDualRel of the forces that meet at a block, since a wall hanging from
// its still half carries corner forces of 1e5 of its heaviest brick, whose sum round-off alone
// leaves at 1e-11 of them.
constexpr double kDualRel = 1e-10;
// The equality rows' dual regularisation: their weight in the normal equations.
constexpr double kDelta = 1e-8;
constexpr int kMaxIterations = 80;
// A motion this many steps long at the interior point's iterate: the LP is unbounded (a
// collapse), which GLPK then proves and whose mechanism it finds.
constexpr double kDiverged = 1e6;

bool is_lo(const Model& m, size_t i) { return m.row_type[i] == GLP_LO; }
bool is_fx(const Model& m, size_t i) { return m.row_type[i] == GLP_FX; }
int count(const Model& m, size_t i) { return static_cast<int>(m.row_coef[7 * i]); }

// ax_i = a_i x for every LP row (x 1-based).
void activities(const Model& m, const std::vector<double>& x, std::vector<double>& ax) {
  ax.resize(m.row_type.size());
  for (size_t i = 0; i < ax.size(); ++i) ax[i] = m.row_activity(i, x);
}

// g = A' y (1-based), and per column the sum of |a_ij y_i|: the size of the forces that meet there.
void transposed(const Model& m, const std::vector<double>& y, std::vector<double>& g, std::vector<double>* size = nullptr) {
  g.assign(m.ncols + 1, 0.0);
  if (size) size->assign(m.ncols + 1, 0.0);
  for (size_t i = 0; i < m.row_type.size(); ++i) {
    if (y[i] == 0) continue;
    const double* held = &m.row_coef[7 * i];
    const int* cols = &m.row_cols[6 * i];
    for (int q = 0; q < count(m, i); ++q) {
      g[cols[q]] += held[q + 1] * y[i];
      if (size) (*size)[cols[q]] += std::abs(held[q + 1] * y[i]);
    }
  }
}

// F's pattern from the LP's rows, and CHOLMOD's analysis of F F' (a fill-reducing ordering of the
// contact graph), made once per model.
bool analyse(const Model& m, InteriorValues& v) {
  const size_t rows = m.row_type.size();
  std::vector<int> counts(rows);
  for (size_t i = 0; i < rows; ++i) counts[i] = count(m, i);
  if (v.L && counts == v.counts) return true;
  if (v.L) cholmod_free_factor(&v.L, &v.cc);
  if (v.F) cholmod_free_sparse(&v.F, &v.cc);
  if (v.B) cholmod_free_dense(&v.B, &v.cc);
  v.counts = counts;
  size_t nnz = 0;
  for (int c : counts) nnz += static_cast<size_t>(std::max(c, 0));
  v.F = cholmod_allocate_sparse(m.ncols, rows, nnz, 0, 1, 0, CHOLMOD_REAL, &v.cc);
  v.B = cholmod_allocate_dense(m.ncols, 1, m.ncols, CHOLMOD_REAL, &v.cc);
  if (!v.F || !v.B) return false;
  int* p = static_cast<int*>(v.F->p);
  int* r = static_cast<int*>(v.F->i);
  p[0] = 0;
  for (size_t i = 0; i < rows; ++i) {
    const int* cols = &m.row_cols[6 * i];
    p[i + 1] = p[i];
    for (int q = 0; q < counts[i]; ++q) r[p[i + 1]++] = cols[q] - 1;
  }
  v.L = cholmod_analyze(v.F, &v.cc);
  return v.L != nullptr;
}

// Factorises F F' + beta I with the rows weighted by w, raising beta where round-off leaves a
// pivot that is not positive (the weights span twenty orders of magnitude near the optimum).
bool factorise(const Model& m, InteriorValues& v, const std::vector<double>& w, double& beta) {
  double* fx = static_cast<double*>(v.F->x);
  size_t k = 0;
  for (size_t i = 0; i < m.row_type.size(); ++i) {
    const double sw = std::sqrt(w[i]);
    const double* held = &m.row_coef[7 * i];
    for (int q = 0; q < v.counts[i]; ++q) fx[k++] = held[q + 1] * sw;
  }
  // Not beyond 1e-4: a ceiling relative to the largest weight (1e-12 of it; near the optimum the
  // weights reach 1e17) kept failing iterates going on regularised, and a 2,049-block wall on
  // turning ground took 45 s where it took 14 s, some of its LPs handed to GLPK (2026-11-27).
  for (; beta <= 1e-4; beta *= 100) {
    double b[2] = {beta, 0};
    if (cholmod_factorize_p(v.F, b, nullptr, 0, v.L, &v.cc) && v.cc.status == CHOLMOD_OK) return true;
  }
  return false;
}

// (A' W A + beta I) dx = rhs, refined twice against that matrix (dx 1-based).
void normal_solve(const Model& m, InteriorValues& v, const std::vector<double>& w, double beta, const std::vector<double>& rhs,
                  std::vector<double>& dx) {
  const int n = m.ncols;
  double* bx = static_cast<double*>(v.B->x);
  dx.assign(n + 1, 0.0);
  std::vector<double> r(rhs), ax, g;
  for (int pass = 0; pass < 3; ++pass) {
    for (int j = 0; j < n; ++j) bx[j] = r[j + 1];
    cholmod_dense* X = cholmod_solve(CHOLMOD_A, v.L, v.B, &v.cc);
    if (!X) return;
    const double* xx = static_cast<const double*>(X->x);
    for (int j = 0; j < n; ++j) dx[j + 1] += xx[j];
    cholmod_free_dense(&X, &v.cc);
    if (pass == 2) break;
    activities(m, dx, ax);
    for (size_t i = 0; i < ax.size(); ++i) ax[i] *= w[i];
    transposed(m, ax, g);
    for (int j = 1; j <= n; ++j) r[j] = rhs[j] - g[j] - beta * dx[j];
  }
}

// Whether (x, y) is optimal for the LP update_lp wrote (the tests of interior.hpp); the rows'
// activities in ax.
// g and size: work space of the equilibrium test.
bool optimal(const Model& m, const std::vector<double>& x, const std::vector<double>& y, std::vector<double>& ax, std::vector<double>& g,
             std::vector<double>& size) {
  activities(m, x, ax);
  for (size_t i = 0; i < ax.size(); ++i) {
    if (!std::isfinite(ax[i]) || !std::isfinite(y[i])) return false;
    const double slack = ax[i] - m.row_lb[i];
    if (is_lo(m, i)) {
      if (slack < -kPrimalEps || y[i] < -kDualEps) return false;
      // A corner that carries a force stands at its bound (complementarity), as a nonbasic row does.
      if (y[i] > kDualEps && slack > kPrimalEps) return false;
    } else if (is_fx(m, i)) {
      if (std::abs(slack) > kPrimalEps) return false;
    } else if (y[i] != 0) {
      return false;
    }
  }
  transposed(m, y, g, &size);
  for (int j = 1; j <= m.ncols; ++j)
    if (!(std::abs(m.obj_coef[j] - g[j]) <= kDualEps + kDualRel * size[j])) return false;
  // The duality gap, the loads' work on the step against the corner forces' work over the bounds:
  // the rows' tests above let each corner's force stand across up to kPrimalEps of gap, which
  // with corner forces of 1e4 of the force unit would add up; the gap is held to kDualEps of the
  // loads (the kept basis's vertex has none: its forces sit on rows at their bounds).
  double primal = 0, dual = 0, loads = 1;
  for (int j = 1; j <= m.ncols; ++j) primal += m.obj_coef[j] * x[j], loads += std::abs(m.obj_coef[j]);
  for (size_t i = 0; i < ax.size(); ++i)
    if (y[i] != 0) dual += y[i] * m.row_lb[i];
  return std::abs(primal - dual) <= kDualEps * loads;
}

void keep(Model& m, InteriorValues& v, const std::vector<double>& ax) {
  v.row = ax;
  v.obj = 0;
  for (int j = 1; j <= m.ncols; ++j) v.obj += m.obj_coef[j] * v.x[j];
  m.interior.own = m.interior.held = true;
}

}  // namespace

bool solve_interior(Model& m) {
  InteriorSolution& is = m.interior;
  is.own = is.held = false;
  if (!is.v) is.v = std::make_shared<InteriorValues>();
  InteriorValues& v = *is.v;
  if (m.ncols == 0 || !analyse(m, v)) return false;
  const size_t rows = m.row_type.size();
  const int n = m.ncols;
  size_t lo = 0;
  for (size_t i = 0; i < rows; ++i) lo += is_lo(m, i);
  std::vector<double> x(n + 1, 0.0), s(rows, 0.0), y(rows, 0.0), ax;
  std::vector<double> w(rows), rp(rows), rd(n + 1), rc(rows), g, size, rhs(n + 1), vrow(rows);
  // Start (Mehrotra's): the motion that meets the rows best and the least forces in equilibrium
  // with the loads, both by least squares on the rows (A'A + beta I, one factorisation), then the
  // slacks and corner forces shifted positive and balanced. From rest with unit slacks and
  // forces instead, the iterates of a wall on turning ground wandered to motions of 1e6 steps.
  for (size_t i = 0; i < rows; ++i) w[i] = is_lo(m, i) || is_fx(m, i) ? 1.0 : 0.0;
  double start_beta = 1e-8;
  if (!factorise(m, v, w, start_beta)) return false;
  for (size_t i = 0; i < rows; ++i) vrow[i] = w[i] * m.row_lb[i];
  transposed(m, vrow, rhs);
  normal_solve(m, v, w, start_beta, rhs, x);
  std::vector<double> u;
  for (int j = 1; j <= n; ++j) rhs[j] = m.obj_coef[j];
  normal_solve(m, v, w, start_beta, rhs, u);
  activities(m, x, ax);
  activities(m, u, y);  // y = A u: A'y = A'A u = c
  double least_s = 0, least_y = 0;
  for (size_t i = 0; i < rows; ++i) {
    if (!is_lo(m, i)) {
      if (!is_fx(m, i)) y[i] = 0;
      continue;
    }
    s[i] = ax[i] - m.row_lb[i];
    least_s = std::min(least_s, s[i]);
    least_y = std::min(least_y, y[i]);
  }
  double sum_s = 0, sum_y = 0, sy = 0;
  for (size_t i = 0; i < rows; ++i)
    if (is_lo(m, i)) {
      s[i] += -1.5 * least_s + 1e-8;
      y[i] += -1.5 * least_y + 1e-8;
      sum_s += s[i], sum_y += y[i], sy += s[i] * y[i];
    }
  if (sum_s > 0 && sum_y > 0)
    for (size_t i = 0; i < rows; ++i)
      if (is_lo(m, i)) s[i] += 0.5 * sy / sum_y, y[i] += 0.5 * sy / sum_s;
  std::vector<double> dx, ds(rows), dy(rows), dxa, dsa(rows), dya(rows), adx;
  // The direction for complementarity target rc (per LO row): ds, dy from dx.
  auto direction = [&](double beta, std::vector<double>& dxo, std::vector<double>& dso, std::vector<double>& dyo) {
    for (size_t i = 0; i < rows; ++i) vrow[i] = is_fx(m, i) ? rp[i] / kDelta : is_lo(m, i) ? rc[i] / s[i] + w[i] * rp[i] : 0.0;
    transposed(m, vrow, rhs);
    for (int j = 1; j <= n; ++j) rhs[j] -= rd[j];
    normal_solve(m, v, w, beta, rhs, dxo);
    activities(m, dxo, adx);
    for (size_t i = 0; i < rows; ++i) {
      dso[i] = dyo[i] = 0;
      if (is_fx(m, i)) {
        dyo[i] = (rp[i] - adx[i]) / kDelta;
      } else if (is_lo(m, i)) {
        dso[i] = adx[i] - rp[i];
        dyo[i] = (rc[i] - y[i] * dso[i]) / s[i];
      }
    }
  };
  // The longest step in [0, 1] that keeps the LO rows' values u + a du nonnegative.
  auto boundary = [&](const std::vector<double>& u, const std::vector<double>& du) {
    double a = 1.0;
    for (size_t i = 0; i < rows; ++i)
      if (is_lo(m, i) && du[i] < 0) a = std::min(a, -u[i] / du[i]);
    return a;
  };
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    activities(m, x, ax);
    double rp_max = 0, mu = 0, x_max = 0;
    for (size_t i = 0; i < rows; ++i) {
      rp[i] = is_lo(m, i) ? m.row_lb[i] - ax[i] + s[i] : is_fx(m, i) ? m.row_lb[i] - ax[i] : 0.0;
      rp_max = std::max(rp_max, std::abs(rp[i]));
      if (is_lo(m, i)) mu += s[i] * y[i];
    }
    mu /= static_cast<double>(std::max<size_t>(lo, 1));
    transposed(m, y, g, &size);
    bool dual_met = true;
    for (int j = 1; j <= n; ++j) {
      rd[j] = m.obj_coef[j] - g[j];
      dual_met = dual_met && std::abs(rd[j]) <= 1e-2 * (kDualEps + kDualRel * size[j]);
      x_max = std::max(x_max, std::abs(x[j]));
    }
    if (!std::isfinite(mu) || x_max > kDiverged) return false;
    if (rp_max < 1e-2 * kPrimalEps && dual_met && mu < 1e-14) break;
    for (size_t i = 0; i < rows; ++i) w[i] = is_fx(m, i) ? 1.0 / kDelta : is_lo(m, i) ? y[i] / s[i] : 0.0;
    double beta = 1e-10;
    if (!factorise(m, v, w, beta)) break;
    // Predictor: the affine direction, towards s o y = 0.
    for (size_t i = 0; i < rows; ++i) rc[i] = is_lo(m, i) ? -s[i] * y[i] : 0.0;
    direction(beta, dxa, dsa, dya);
    const double ap = boundary(s, dsa), ad = boundary(y, dya);
    double mu_aff = 0;
    for (size_t i = 0; i < rows; ++i)
      if (is_lo(m, i)) mu_aff += (s[i] + ap * dsa[i]) * (y[i] + ad * dya[i]);
    mu_aff /= static_cast<double>(std::max<size_t>(lo, 1));
    // Corrector: centred by Mehrotra's sigma, with the predictor's second-order term.
    const double sigma = std::pow(std::clamp(mu_aff / mu, 0.0, 1.0), 3);
    for (size_t i = 0; i < rows; ++i) rc[i] = is_lo(m, i) ? sigma * mu - s[i] * y[i] - dsa[i] * dya[i] : 0.0;
    direction(beta, dx, ds, dy);
    const double step_p = std::min(1.0, 0.995 * boundary(s, ds)), step_d = std::min(1.0, 0.995 * boundary(y, dy));
    for (int j = 1; j <= n; ++j) x[j] += step_p * dx[j];
    for (size_t i = 0; i < rows; ++i) {
      if (is_lo(m, i)) s[i] += step_p * ds[i];
      y[i] += step_d * dy[i];
    }
  }
  // The corners whose forces hold them closed (strict complementarity: the force beyond the
  // slack), with every no-sliding and held row; the other corners' forces are the barrier's
  // remainder and are set to zero.
  std::vector<char> tight(rows, 0);
  for (size_t i = 0; i < rows; ++i) {
    tight[i] = is_fx(m, i) || (is_lo(m, i) && y[i] > s[i]);
    if (!tight[i]) y[i] = 0;
  }
  // Of the optimal motions, the least: the motion nearest rest that meets every tight row (the
  // face's affine hull), by proximal iterations from rest, x_k+1 = argmin |A_T x - b_T|^2 +
  // eps |x - x_k|^2, each (eps I + A_T' A_T) dx = A_T'(b_T - A_T x_k): a component of the motion
  // that the tight rows fix converges by eps / (eps + lambda) an iteration, one they leave free
  // (turning the wall about the still ground's edge) stays at rest's, zero. Then from the interior
  // point's motion towards it, as far as an open corner allows (an open corner does not close).
  constexpr double kFace = 1e-9;
  constexpr int kFaceIterations = 4;
  for (size_t i = 0; i < rows; ++i) w[i] = tight[i] ? 1.0 : 0.0;
  double beta = kFace;
  v.x = x;
  if (factorise(m, v, w, beta) && beta == kFace) {
    std::vector<double> near(n + 1, 0.0), d;
    for (int k = 0; k < kFaceIterations; ++k) {
      activities(m, near, ax);
      for (size_t i = 0; i < rows; ++i) vrow[i] = tight[i] ? m.row_lb[i] - ax[i] : 0.0;
      transposed(m, vrow, rhs);
      normal_solve(m, v, w, beta, rhs, d);
      for (int j = 1; j <= n; ++j) near[j] += d[j];
    }
    for (int j = 1; j <= n; ++j) d[j] = near[j] - x[j];
    activities(m, d, adx);
    activities(m, x, ax);
    double a = 1.0;
    for (size_t i = 0; i < rows; ++i)
      if (is_lo(m, i) && !tight[i] && adx[i] < 0) a = std::min(a, std::max(0.0, ax[i] - m.row_lb[i]) / -adx[i]);
    std::vector<double> moved(n + 1);
    for (int j = 0; j <= n; ++j) moved[j] = x[j] + a * d[j];
    if (optimal(m, moved, y, ax, g, size)) {
      v.x = moved;
      v.dual = y;
      keep(m, v, ax);
      return true;
    }
  }
  // Where the face could not be followed, the interior point's own optimum, if it is one.
  if (!optimal(m, x, y, ax, g, size)) return false;
  v.dual = y;
  keep(m, v, ax);
  return true;
}

bool interior_optimal(const Model& m, const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> ax, g, size;
  return x.size() == static_cast<size_t>(m.ncols) + 1 && y.size() == m.row_type.size() && optimal(m, x, y, ax, g, size);
}

bool interior_still_optimal(Model& m) {
  InteriorSolution& is = m.interior;
  is.own = false;
  if (!is.held || !is.v) return false;
  InteriorValues& v = *is.v;
  if (v.x.size() != static_cast<size_t>(m.ncols) + 1 || v.dual.size() != m.row_type.size()) {
    is.held = false;
    return false;
  }
  // A joint's shear is the dual of its one no-sliding row, at its first closed corner
  // (Model::sliding_row); where that corner opened, the row is the other corner's now, the same
  // constraint for a rigid relative motion, and the shear goes with it.
  for (size_t k = 0; 4 * k + 3 < v.dual.size(); ++k) {
    double& a = v.dual[4 * k + 1];
    double& b = v.dual[4 * k + 3];
    if (m.row_type[4 * k + 1] == GLP_FR && m.row_type[4 * k + 3] == GLP_FX && b == 0) std::swap(a, b);
    if (m.row_type[4 * k + 3] == GLP_FR && m.row_type[4 * k + 1] == GLP_FX && a == 0) std::swap(a, b);
  }
  // A row the contact state has freed since (a joint that opened: its no-sliding row) carries no
  // force; the shear the interior point left on it is the barrier's remainder where it is within
  // the dual tolerance, and the equilibrium test below sees what setting it to zero does.
  for (size_t i = 0; i < v.dual.size(); ++i)
    if (m.row_type[i] == GLP_FR && std::abs(v.dual[i]) <= kDualEps) v.dual[i] = 0;
  if (!optimal(m, v.x, v.dual, v.ax, v.g, v.size)) {
    is.held = false;
    return false;
  }
  keep(m, v, v.ax);
  return true;
}

double interior_objective(const Model& m) { return m.interior.v->obj; }
double interior_col(const Model& m, int j) { return m.interior.v->x[j]; }
double interior_row(const Model& m, int row) { return m.interior.v->row[row - 1]; }
double interior_dual(const Model& m, int row) { return m.interior.v->dual[row - 1]; }

}  // namespace masonry::prd_detail
