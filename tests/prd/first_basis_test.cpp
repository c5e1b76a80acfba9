// GLPK from its standard basis is the reference for the faster starts of large LPs (issue 33):
// from GLPK's advanced basis the first LP of a run must reach the same optimum (LP optimality is
// unique in value), the same mechanism (open corners, moving blocks) wherever the optimum is
// unique, on the standard scenes and on walls of every bond, with openings, settling and turning
// ground. The forces may differ: a statically indeterminate structure has many admissible force
// states; both must be in equilibrium (LP duality: the dual objective equals the primal one).
// The same from the structure's load path by the dual simplex (static_basis.cpp), and that load
// path an admissible force state of a wall standing on still ground: the safe theorem, so the
// LP of the structure as it stands is solved by it without a pivot.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cases/generators.hpp"
#include "prd/internal.hpp"

namespace masonry {
namespace {

using namespace prd_detail;

struct FirstLp {
  LpStatus status;
  double energy = 0;        // J per unit of h
  double dual_energy = 0;   // the same from the duals (strong duality)
  std::set<size_t> open;    // corners the step opens by more than 1e-6 h
  std::set<size_t> moving;  // free blocks that move by more than 1e-6 h
  double lp_s = 0;
  bool from_load_path = false;  // solved by the dual simplex from the load path
  int pivots = 0;
};

FirstLp first_lp(const Case& c, FirstBasis start) {
  Model m = build_model(c, c.prd.contact_tolerance);
  m.first_basis = start;
  const double h = c.motion.step;
  update_lp(m, h, h, h);
  FirstLp out;
  out.status = solve(m);
  out.lp_s = m.lp_s;
  out.from_load_path = m.load_path_solves > 0;
  out.pivots = glp_get_it_cnt(m.lp.get());
  if (out.status != LpStatus::optimal) return out;
  out.energy = objective(m);
  StepRecord rec;
  lp_check_fields(m, 1.0, rec);
  out.dual_energy = rec.lp.value().dual;
  for (size_t e = 0; e < m.ends.size(); ++e)
    if (corner_slack(m, e) > 1e-6) out.open.insert(e);
  for (size_t b = 0; b < m.col.size(); ++b)
    if (m.col[b] > 0)
      for (int k = 0; k < 3; ++k)
        if (std::abs(col_value(m, m.col[b] + k)) > 1e-6) out.moving.insert(b);
  return out;
}

FirstLp expect_same_first_lp(const Case& c, const std::string& what, FirstBasis start = FirstBasis::advanced) {
  const FirstLp ref = first_lp(c, FirstBasis::standard), fast = first_lp(c, start);
  EXPECT_EQ(static_cast<int>(fast.status), static_cast<int>(ref.status)) << what;
  if (ref.status != LpStatus::optimal || fast.status != ref.status) return fast;
  const double scale = std::max(1.0, std::abs(ref.energy));
  EXPECT_NEAR(fast.energy, ref.energy, 1e-9 * scale) << what;
  EXPECT_NEAR(fast.dual_energy, fast.energy, 1e-9 * scale) << what;
  EXPECT_EQ(fast.open, ref.open) << what;
  EXPECT_EQ(fast.moving, ref.moving) << what;
  return fast;
}

Case standard_file(const std::string& name) { return load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

TEST(PrdFirstBasis, StandardScenesSameOptimumAndMechanismFromEitherStart) {
  for (const char* name : {"pointed-arch", "cathedral-settlement", "cathedral-settlement-rotation", "tilting-block"})
    expect_same_first_lp(standard_file(name), name);
}

struct Wall {
  Case c;
  std::string what;
  bool load_path;  // the load path of the wall as it stands exists (no opening)
};

std::vector<Wall> walls() {
  std::vector<Wall> out;
  BrickWall running;
  running.courses = 12;
  running.bricks = 12;
  // Split off the middle: split at it, the wall's centre of gravity stands right above the still
  // ground's edge, and a rigid rotation about a point on that vertical does no work, so the
  // optimum is not unique (the load path's dual simplex ends there, the standard basis at rest).
  running.ground_split = 1.8;
  out.push_back({brick_wall(running), "running bond, right ground settling", true});
  running.ground_split = -1;
  BrickWall stack = running;
  stack.bond = WallBond::stack;
  stack.settlement_step = 0;
  stack.rotation_step = -0.001;  // the right ground turns away, about the split
  out.push_back({brick_wall(stack), "stack bond, right ground turning", true});
  BrickWall header = running;
  header.bond = WallBond::header;
  header.bricks = 24;
  header.courses = 14;
  header.moving = MovingGround::left;
  header.openings = {parse_wall_opening("0.5,0.25,0.5,0.5,arch"), parse_wall_opening("2.0,0.25,0.5,0.5,lintel")};
  out.push_back({brick_wall(header), "header bond, arch and lintel, left ground settling", false});
  return out;
}

TEST(PrdFirstBasis, WallsSameOptimumAndMechanismFromEitherStart) {
  for (const Wall& w : walls()) expect_same_first_lp(w.c, w.what);
  BrickWall middle;  // split at the middle, as the benchmarks: here both starts end at rest
  middle.courses = 12;
  middle.bricks = 12;
  expect_same_first_lp(brick_wall(middle), "running bond split at the middle");
}

// The dual simplex from the load path where it exists (the walls without openings; the standard
// scenes' arches and the header wall's openings have none that the greedy construction finds,
// and they start from the advanced basis): the standard basis's optimum and mechanism.
TEST(PrdFirstBasis, SameOptimumAndMechanismFromTheLoadPath) {
  for (const char* name : {"pointed-arch", "cathedral-settlement", "cathedral-settlement-rotation", "tilting-block"})
    expect_same_first_lp(standard_file(name), name, FirstBasis::statics);
  for (const Wall& w : walls()) {
    const FirstLp fast = expect_same_first_lp(w.c, w.what, FirstBasis::statics);
    if (w.load_path) {
      EXPECT_TRUE(fast.from_load_path) << w.what;
    }
  }
  // The settling wall's load path is not its optimum: the dual simplex pivots to it.
  EXPECT_GT(first_lp(walls()[0].c, FirstBasis::statics).pivots, 0);
}

// A run's own choice from 300 free blocks up: a wall of 20 courses of 16 bricks (330 free
// blocks). Standing, its load path is its optimum and is taken without a pivot; with its ground
// settling, the load path is not primal feasible and the run starts from the advanced basis,
// to the standard basis's optimum and mechanism.
TEST(PrdFirstBasis, RunsTakeTheLoadPathWhereItIsTheOptimum) {
  BrickWall w;
  w.courses = 20;
  w.bricks = 16;
  w.ground_split = 2.4;
  const Case settling = brick_wall(w);
  Case standing = settling;
  standing.motion.supports.clear();
  int free_blocks = 0;
  for (const Block& b : standing.blocks) free_blocks += !b.support;
  ASSERT_GE(free_blocks, kAdvancedBasisBlocks);
  const FirstLp still = expect_same_first_lp(standing, "standing", FirstBasis::by_size);
  EXPECT_TRUE(still.from_load_path);
  EXPECT_EQ(still.pivots, 0);
  const FirstLp moving = expect_same_first_lp(settling, "settling", FirstBasis::by_size);
  EXPECT_FALSE(moving.from_load_path);
}

// Walls without openings as they stand, their ground still: each block's weight and the loads
// from above go down through the joints below it (for a running-bond brick, its two outer
// corners), so the load path exists, GLPK finds it dual and primal feasible, and its dual simplex
// stops there without a pivot. (Over openings the greedy construction may find none: the header
// wall's arch above; solve() then starts from the advanced basis.)
TEST(PrdFirstBasis, LoadPathOfAStandingWallIsOptimalAsItStands) {
  std::vector<std::pair<Case, std::string>> standing;
  for (WallBond bond : {WallBond::running, WallBond::stack, WallBond::header}) {
    BrickWall w;
    w.bond = bond;
    w.courses = 12;
    w.bricks = bond == WallBond::header ? 24 : 12;
    standing.emplace_back(brick_wall(w), std::string(wall_bond_name(bond)) + " bond");
  }
  for (const auto& [moving, what] : standing) {
    Case c = moving;
    c.motion.supports.clear();
    Model m = build_model(c, c.prd.contact_tolerance);
    m.first_basis = FirstBasis::statics;
    update_lp(m, 0.0, c.motion.step);
    sync_glpk(m);
    ASSERT_TRUE(set_static_basis(m)) << what;
    glp_prob* lp = m.lp.get();
    ASSERT_EQ(glp_warm_up(lp), 0) << what;
    EXPECT_EQ(glp_get_dual_stat(lp), GLP_FEAS) << what;
    EXPECT_EQ(glp_get_prim_stat(lp), GLP_FEAS) << what;
    ASSERT_EQ(static_cast<int>(solve(m)), static_cast<int>(LpStatus::optimal)) << what;
    EXPECT_EQ(glp_get_it_cnt(lp), 0) << what;
    EXPECT_NEAR(objective(m), 0.0, 1e-9 * total_weight(c)) << what;
  }
}

}  // namespace
}  // namespace masonry
