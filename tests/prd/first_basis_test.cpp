// GLPK from its standard basis is the reference for the faster starts of large LPs (issue 33):
// from GLPK's advanced basis the first LP of a run must reach the same optimum (LP optimality is
// unique in value), the same mechanism (open corners, moving blocks) wherever the optimum is
// unique, on the standard scenes and on walls of every bond, with openings, settling and turning
// ground. The forces may differ: a statically indeterminate structure has many admissible force
// states; both must be in equilibrium (LP duality: the dual objective equals the primal one).
#include <gtest/gtest.h>

#include <set>
#include <string>

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
};

FirstLp first_lp(const Case& c, FirstBasis start) {
  Model m = build_model(c, c.prd.contact_tolerance);
  m.first_basis = start;
  const double h = c.motion.step;
  update_lp(m, h, h, h);
  FirstLp out;
  out.status = solve(m);
  out.lp_s = m.lp_s;
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

void expect_same_first_lp(const Case& c, const std::string& what) {
  const FirstLp ref = first_lp(c, FirstBasis::standard), fast = first_lp(c, FirstBasis::advanced);
  ASSERT_EQ(static_cast<int>(fast.status), static_cast<int>(ref.status)) << what;
  if (ref.status != LpStatus::optimal) return;
  const double scale = std::max(1.0, std::abs(ref.energy));
  EXPECT_NEAR(fast.energy, ref.energy, 1e-9 * scale) << what;
  EXPECT_NEAR(fast.dual_energy, fast.energy, 1e-9 * scale) << what;
  EXPECT_EQ(fast.open, ref.open) << what;
  EXPECT_EQ(fast.moving, ref.moving) << what;
}

Case standard_file(const std::string& name) { return load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

TEST(PrdFirstBasis, StandardScenesSameOptimumAndMechanismFromEitherStart) {
  for (const char* name : {"pointed-arch", "cathedral-settlement", "cathedral-settlement-rotation", "tilting-block"})
    expect_same_first_lp(standard_file(name), name);
}

TEST(PrdFirstBasis, WallsSameOptimumAndMechanismFromEitherStart) {
  BrickWall running;
  running.courses = 12;
  running.bricks = 12;
  expect_same_first_lp(brick_wall(running), "running bond, right ground settling");
  BrickWall stack = running;
  stack.bond = WallBond::stack;
  stack.settlement_step = 0;
  stack.rotation_step = -0.001;  // the right ground turns away, about the split
  expect_same_first_lp(brick_wall(stack), "stack bond, right ground turning");
  BrickWall header = running;
  header.bond = WallBond::header;
  header.bricks = 24;
  header.courses = 14;
  header.moving = MovingGround::left;
  header.openings = {parse_wall_opening("0.5,0.25,0.5,0.5,arch"), parse_wall_opening("2.0,0.25,0.5,0.5,lintel")};
  expect_same_first_lp(brick_wall(header), "header bond, arch and lintel, left ground settling");
}

}  // namespace
}  // namespace masonry
