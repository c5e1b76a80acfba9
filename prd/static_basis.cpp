// A first basis built from the statics of the structure as it stands: every column basic and,
// per free block, three of its rows nonbasic whose forces carry the block's loads, and those of
// the blocks resting on it, into blocks further down (prd/README.md, "The load path").
//
// Where every block finds such rows with compressive normal forces, the basis is dual feasible
// (its duals are an admissible force state: equilibrium, no tension), and GLPK's dual simplex
// can start from it. The blocks are taken from the top down (against gravity's direction, y),
// so each block's loads are known when it is reached and the basis matrix is block triangular:
// each block's 3 x 3 system must be regular. Among a block's admissible choices the one with the
// least sum of |force| is taken (for a brick on two, its outer corners and a shear).
#include <glpk.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "prd/internal.hpp"

namespace masonry::prd_detail {

bool set_static_basis(Model& m) {
  const Case& c = *m.c;
  const size_t nb = c.blocks.size();
  if (m.row_coef.empty() || m.ncols == 0) return false;
  // Top down.
  std::vector<int> order;
  for (size_t b = 0; b < nb; ++b)
    if (m.col[b] > 0) order.push_back(static_cast<int>(b));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return m.cen[a].y() > m.cen[b].y(); });
  // The rows that can carry a force, per block: closed corners' and no-sliding rows.
  std::vector<std::vector<int>> rows_of(nb);
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Interface& jt = m.joints[m.ends[e].joint];
    for (int r = 0; r < 2; ++r) {
      const int row = 2 * static_cast<int>(e) + r;  // 0-based
      if (m.row_type[row] == GLP_FR || (r == 0 && !m.ends[e].closed)) continue;
      rows_of[jt.i].push_back(row);
      rows_of[jt.j].push_back(row);
    }
  }
  std::vector<char> chosen(m.row_type.size(), 0);
  // Per block, the loads still to carry: the objective's coefficients less the chosen rows' share.
  std::vector<Eigen::Vector3d> rest(nb, Eigen::Vector3d::Zero());
  for (int b : order) rest[b] = Eigen::Vector3d(m.obj_coef[m.col[b]], m.obj_coef[m.col[b] + 1], m.obj_coef[m.col[b] + 2]);
  for (int b : order) {
    const int k = m.col[b];
    std::vector<int> cand;
    std::vector<Eigen::Vector3d> a;
    for (int row : rows_of[b]) {
      const Interface& jt = m.joints[m.ends[row / 2].joint];
      const int other = jt.i == b ? jt.j : jt.i;
      // Only rows to supports and to blocks lower down: rows to blocks above are theirs to
      // choose, and a neighbour at the same height (a head joint) would pass loads sideways from
      // block to block along a course.
      if (m.col[other] > 0 && !(m.cen[other].y() < m.cen[b].y() - 1e-9 * m.radius[b])) continue;
      cand.push_back(row);
      a.push_back(m.row_on_block(static_cast<size_t>(row), k));
    }
    const Eigen::Vector3d r = rest[b];
    double best = -std::numeric_limits<double>::infinity();
    int pick[3] = {-1, -1, -1};
    Eigen::Vector3d best_f;
    const size_t n = cand.size();
    for (size_t p = 0; p < n; ++p)
      for (size_t q = p + 1; q < n; ++q)
        for (size_t s = q + 1; s < n; ++s) {
          Eigen::Matrix3d A;
          A.col(0) = a[p], A.col(1) = a[q], A.col(2) = a[s];
          const double det = A.determinant();
          if (!(std::abs(det) > 1e-9)) continue;  // the coefficients are O(1)
          const Eigen::Vector3d f = A.partialPivLu().solve(r);
          double least = std::numeric_limits<double>::infinity();
          const int idx[3] = {cand[p], cand[q], cand[s]};
          for (int t = 0; t < 3; ++t)
            if (idx[t] % 2 == 0 && m.row_type[idx[t]] == GLP_LO) least = std::min(least, f[t]);
          if (!(least >= 0)) continue;
          // The smallest forces: |f|'s sum, which a pair of opposed forces only adds to. This
          // also keeps the basis well conditioned: a block's errors reach the blocks below it
          // multiplied by its forces over its loads. Taking instead the choice whose smallest
          // normal force is largest made GLPK's duals of a 70-course wall's basis differ from
          // these by 10% and its simplex fail at once.
          const double score = -f.cwiseAbs().sum();
          if (score > best) best = score, best_f = f, pick[0] = idx[0], pick[1] = idx[1], pick[2] = idx[2];
        }
    if (pick[0] < 0) return false;
    for (int t = 0; t < 3; ++t) {
      const int row = pick[t];
      chosen[row] = 1;
      const Interface& jt = m.joints[m.ends[row / 2].joint];
      const int other = jt.i == b ? jt.j : jt.i;
      if (m.col[other] > 0) rest[other] -= best_f[t] * m.row_on_block(static_cast<size_t>(row), m.col[other]);
    }
  }
  glp_prob* lp = m.lp.get();
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_stat(lp, j, GLP_BS);
  for (size_t i = 0; i < m.row_type.size(); ++i)
    glp_set_row_stat(lp, static_cast<int>(i) + 1, !chosen[i] ? GLP_BS : m.row_type[i] == GLP_FX ? GLP_NS : GLP_NL);
  return true;
}

}  // namespace masonry::prd_detail
