// The interior point (prd/interior.hpp) against GLPK's simplex, the reference (issue 33): a run
// whose LPs the interior point solves must be the run GLPK gives: the same stop and capacity,
// and at every step the same mechanism (open corners, cracked joints) and energy (LP optimality
// is unique in value). The joint forces may differ, since a statically indeterminate structure
// has many admissible force states (the interior point's is the middle of them, GLPK's a
// vertex); both must be in equilibrium: strong duality in every record (the loads' work on the
// step equals the corner forces' work over the bounds) and the support reactions carrying the
// whole weight. Walls of each bond with the ground settling and turning, one split at its middle
// (no unique optimum: of the optimal motions the least, rest, as GLPK's start gives), openings
// with an arch and a lintel, and the pointed arch, whose blocks move at every step until it
// collapses (the collapse is GLPK's: an unbounded LP has no optimum the interior point can pass).
// The interior point is taken here from one free block up (t_interior_blocks), in runs from
// kInteriorPointBlocks.
#include <gtest/gtest.h>

#include <string>

#include "cases/generators.hpp"
#include "model/case.hpp"
#include "prd/internal.hpp"

namespace masonry {
namespace {

RunResult run(const Case& c, bool interior) {
  struct Restore {
    ~Restore() { prd_detail::t_interior_blocks = kInteriorPointBlocks; }
  } restore;
  prd_detail::t_interior_blocks = interior ? 1 : 1 << 28;
  return prd_run(c, PrdSettings::from_case(c));
}

void expect_same_run(const Case& c, const std::string& what) {
  const RunResult ref = run(c, false), ip = run(c, true);
  EXPECT_EQ(ref.timing.interior_solves, 0) << what;
  EXPECT_GT(ip.timing.interior_solves, 0) << what;
  ASSERT_EQ(ip.status, ref.status) << what << ": " << ip.message;
  EXPECT_EQ(ip.stable_steps, ref.stable_steps) << what;
  ASSERT_EQ(ip.steps.size(), ref.steps.size()) << what;
  const double W = ref.total_weight, L = scene_size(c);
  EXPECT_NEAR(ip.capacity, ref.capacity, 1e-9 * L) << what;
  for (size_t k = 0; k < ref.steps.size(); ++k) {
    const StepRecord &a = ref.steps[k], &b = ip.steps[k];
    const std::string at = what + ", step " + std::to_string(k);
    EXPECT_NEAR(b.d, a.d, 1e-9 * L) << at;
    EXPECT_NEAR(b.energy, a.energy, 1e-7 * W * c.motion.step) << at;
    ASSERT_EQ(b.open_corners.size(), a.open_corners.size()) << at;
    for (size_t q = 0; q < a.open_corners.size(); ++q) {
      EXPECT_EQ(b.open_corners[q].joint, a.open_corners[q].joint) << at;
      EXPECT_EQ(b.open_corners[q].corner, a.open_corners[q].corner) << at;
      EXPECT_NEAR(b.open_corners[q].gap, a.open_corners[q].gap, 1e-7 * c.motion.step) << at;
    }
    EXPECT_EQ(b.cracked, a.cracked) << at;
    if (b.lp) {
      EXPECT_NEAR(b.lp->primal, b.lp->dual, 1e-7 * W * c.motion.step) << at << ": strong duality";
    }
    Vec2 carried(0, 0);
    for (const Reaction& r : b.reactions) carried += r.force;
    if (!b.forces.empty()) {
      EXPECT_NEAR((carried - Vec2(0, W)).norm(), 0.0, 1e-7 * W) << at << ": the reactions carry the weight";
    }
  }
}

BrickWall small_wall() {
  BrickWall w;
  w.courses = 12;
  w.bricks = 12;
  w.max_steps = 20;
  return w;
}

TEST(Interior, RunningBondSettlingOffItsMiddleIsGlpksRun) {
  BrickWall w = small_wall();
  w.ground_split = 1.8;
  expect_same_run(brick_wall(w), "running bond, right ground settling, split at 1.8 m");
}

TEST(Interior, RunningBondSplitAtItsMiddleStaysAtRestAsGlpk) {
  // The centre of gravity over the still ground's edge: turning the whole wall about it does no
  // work, and the interior point's own optimum is the wall half turned; the least motion is rest.
  expect_same_run(brick_wall(small_wall()), "running bond, right ground settling, split at the middle");
}

TEST(Interior, StackBondOnTurningGroundIsGlpksRun) {
  BrickWall w = small_wall();
  w.bond = WallBond::stack;
  w.settlement_step = 0;
  w.rotation_step = -0.001;
  expect_same_run(brick_wall(w), "stack bond, right ground turning");
}

TEST(Interior, HeaderBondWithAnArchAndALintelIsGlpksRun) {
  BrickWall w = small_wall();
  w.bond = WallBond::header;
  w.bricks = 24;
  w.courses = 14;
  w.moving = MovingGround::left;
  w.openings = {parse_wall_opening("0.5,0.25,0.5,0.5,arch"), parse_wall_opening("2.0,0.25,0.5,0.5,lintel")};
  expect_same_run(brick_wall(w), "header bond, arch and lintel, left ground settling");
}

TEST(Interior, ThePointedArchMovesEveryStepAndCollapsesAsInGlpk) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  expect_same_run(c, "pointed arch");
}

// The tests a solution must pass before it is taken (prd/interior.hpp), each shown to refuse
// what it is there for: on the first LP of a wall hanging from its still half, the interior
// point's solution passes; a force on a corner the step opens (complementarity, and the duality
// gap it makes), a pull on a loaded corner (a tension), a motion into a closed joint (a
// penetration), or every force one percent larger (no equilibrium) does not.
TEST(Interior, ItsOptimalityTestsRefuseWhatTheyAreFor) {
  BrickWall w = small_wall();
  w.ground_split = 1.8;
  const Case c = brick_wall(w);
  prd_detail::Model m = prd_detail::build_model(c, c.prd.contact_tolerance);
  const double h = c.motion.step;
  prd_detail::update_lp(m, h, h, h);
  ASSERT_TRUE(prd_detail::solve_interior(m));
  const size_t rows = m.row_type.size();
  std::vector<double> x(m.ncols + 1), y(rows);
  for (int j = 1; j <= m.ncols; ++j) x[j] = prd_detail::interior_col(m, j);
  for (size_t i = 0; i < rows; ++i) y[i] = prd_detail::interior_dual(m, static_cast<int>(i) + 1);
  ASSERT_TRUE(prd_detail::interior_optimal(m, x, y));
  size_t open = rows, loaded = rows;
  for (size_t i = 0; i < rows; ++i) {
    if (m.row_type[i] != GLP_LO) continue;
    const double slack = prd_detail::interior_row(m, static_cast<int>(i) + 1) - m.row_lb[i];
    if (open == rows && slack > 0.5) open = i;
    if (loaded == rows && y[i] > 1e-3) loaded = i;
  }
  ASSERT_LT(open, rows) << "no corner the step opens";
  ASSERT_LT(loaded, rows) << "no loaded corner";
  std::vector<double> yo = y;
  yo[open] = 1e-3;
  EXPECT_FALSE(prd_detail::interior_optimal(m, x, yo)) << "a force across an open corner";
  std::vector<double> yt = y;
  yt[loaded] = -1e-3;
  EXPECT_FALSE(prd_detail::interior_optimal(m, x, yt)) << "a tension";
  std::vector<double> xp = x;
  for (int q = 0; q < static_cast<int>(m.row_coef[7 * loaded]); ++q) xp[m.row_cols[6 * loaded + q]] -= 1e-5 * m.row_coef[7 * loaded + 1 + q];
  EXPECT_FALSE(prd_detail::interior_optimal(m, xp, y)) << "a penetration";
  std::vector<double> ys = y;
  for (double& f : ys) f *= 1.01;
  EXPECT_FALSE(prd_detail::interior_optimal(m, x, ys)) << "no equilibrium";
}

}  // namespace
}  // namespace masonry
