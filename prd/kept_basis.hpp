// The previous step's basis, solved again without GLPK where it is still optimal (kept_basis.cpp).
//
// A run's LPs change little from one step to the next: on the standard scenes nine in ten of
// them are solved by the basis of the one before with no simplex pivot. GLPK still spends most
// of such a solve factorising its whole basis matrix (one row per corner and sliding row: 2,400
// on the cathedral) and copying the problem into the simplex's own storage, about 0.8 ms of the
// cathedral's 1 ms per LP. With every column basic (the increments are free variables, so once
// the first solve has brought them in they stay), the basis is the square system of the
// nonbasic rows, A_N U = b_N, one row per degree of freedom of the free blocks: factorised
// here once per LP by a sparse LU (KLU's) of that n x n system, it gives the same vertex. The
// vertex is taken only if it is primal and dual feasible by the tests GLPK's primal simplex
// applies (its tolerances), so that GLPK, given it, would stop without a pivot: the answer is
// GLPK's up to round-off, and whenever the basis is not optimal GLPK solves as before.
#pragma once

#include <memory>
#include <vector>

namespace masonry::prd_detail {

struct Model;

// The tests a vertex or a solution must pass to be taken without GLPK (kept_basis.cpp, the
// interior point's interior.cpp), in the LP's units (the step, the force unit): every basic row
// within kPrimalEps of its bound, where GLPK, which shifts bounds to zero first, starts a phase 1
// beyond 0.97 of its tol_bnd (1e-7); dual signs and reduced costs within kDualEps, GLPK's tol_dj.
constexpr double kPrimalEps = 0.5e-7;
constexpr double kDualEps = 1e-7;

struct KeptBasisValues;  // the factorisation and the values of the last solve by the kept basis
struct KeptBasis {
  std::vector<int> rows;  // the nonbasic rows (1-based) of GLPK's last basis; empty: none kept
  bool own = false;       // the last solve was this one's (the values below), not GLPK's
  std::shared_ptr<KeptBasisValues> v;
};

// Remembers GLPK's basis as it stands after a solve or a restore, where every column is basic and
// free (otherwise keeps none); the values are GLPK's again.
void keep_basis(Model& m);
// Solves the current LP by the kept basis: true, with the values kept in m.kept, where that basis
// is optimal; false otherwise (GLPK must solve).
bool solve_by_kept_basis(Model& m);
// The values of the last solve by the kept basis (only while m.kept.own).
double kept_objective(const Model& m);
double kept_col(const Model& m, int j);
double kept_row(const Model& m, int row);   // the row's activity, as glp_get_row_prim
double kept_dual(const Model& m, int row);  // as glp_get_row_dual

}  // namespace masonry::prd_detail
