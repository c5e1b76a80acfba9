// The PRD LP of a large structure solved by an interior-point method (prd/README.md, "The LP at
// scale": "The interior point").
//
// GLPK's simplex pays for the first LP of a large wall in pivots: about one per block, each
// costing in proportion to the rows, so its time grows as the blocks squared (a 10,052-block
// wall: minutes, and from its advanced basis it fails). The optimum of such an LP is mostly a
// force state (the blocks stay where they are; what must be found is an admissible set of joint
// forces that proves it), and an interior point finds that by a few tens of sparse Cholesky
// factorisations of the blocks' contact graph (CHOLMOD), whatever the size.
//
// The LP's optimum need not be unique: where a wall's centre of gravity stands over the edge of
// its still ground, turning the whole wall about that edge does no work, and an interior point
// converges to the middle of the optimal face (the wall half turned), where the simplex ends on
// one of its vertices. Of the optimal motions the one that moves the blocks least is taken: the
// interior point's motion is moved along the optimal face (keeping every joint its forces hold
// closed) towards rest, as far as the rows allow. Where the optimum is unique (a vertex) that
// changes nothing.
//
// A solution is taken only where it passes the kept basis's tests of optimality (kept_basis.hpp):
// every row within 0.5e-7 of its bound (the LP's units: the step), the corner forces compressive
// and each that carries a force at its bound (complementarity), every block in equilibrium under
// the loads and its joint forces (also within 1e-10 of the forces that meet at it), and the
// duality gap within 1e-7 of the loads. Otherwise GLPK solves. The forces are an interior state,
// not a vertex, and may carry self-stress of any size (prd/README.md, "The interior point").
#pragma once

#include <memory>
#include <vector>

#include "prd/prd.hpp"

namespace masonry::prd_detail {

struct Model;

// From kInteriorPointBlocks (prd.hpp) free blocks up. Below, GLPK's simplex is faster over a run
// where the blocks move at every step (its later LPs are solved by the kept basis in
// milliseconds, the interior point's solution holds only while nothing moves; prd/README.md).
// The tests lower it on their thread to compare the interior point with GLPK on smaller walls.
inline thread_local int t_interior_blocks = kInteriorPointBlocks;

struct InteriorValues;  // CHOLMOD's analysis of the contact graph and the last solution
struct InteriorSolution {
  bool own = false;  // the last solve was the interior point's (the values below)
  bool held = false;  // a solution is kept for the next LP (interior_still_optimal)
  std::shared_ptr<InteriorValues> v;
};

// Solves the LP update_lp wrote by the interior point: true, the values in m.interior, where the
// solution passes the tests above; false otherwise (an unbounded LP, a collapse, never passes).
bool solve_interior(Model& m);
// The last interior solution tested against the LP update_lp wrote now (a wall hanging from its
// still half: the same forces hold it step after step): true, the values in m.interior, where it
// passes the tests above.
bool interior_still_optimal(Model& m);
// The tests a solution must pass (above) of column values x (1-based) and row duals y (one per
// LP row), against the LP update_lp wrote: for the tests of the tests.
bool interior_optimal(const Model& m, const std::vector<double>& x, const std::vector<double>& y);
double interior_objective(const Model& m);
double interior_col(const Model& m, int j);    // 1-based
double interior_row(const Model& m, int row);  // 1-based: the row's activity
double interior_dual(const Model& m, int row);

}  // namespace masonry::prd_detail
