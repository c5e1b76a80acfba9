// The kept basis (prd/kept_basis.hpp) against GLPK's simplex, the reference: a run whose LPs are
// solved by the previous LP's basis wherever it is still optimal must be the run GLPK gives
// solving every LP itself: the same steps, capacity and mechanisms (open corners, cracked
// joints) and, up to round-off, the same energies, joint forces and reactions, on the standard
// scenes and on a wall; and it must actually take many LPs (a third of them at least, else this
// test would compare GLPK with itself). Event-driven runs do not use it (internal.hpp, Model).
#include <gtest/gtest.h>

#include <string>

#include "cases/generators.hpp"
#include "prd/internal.hpp"

namespace masonry {
namespace {

RunResult run(const Case& c, bool adaptive, bool kept) {
  PrdSettings s = PrdSettings::from_case(c);
  s.adaptive = adaptive;
  // Restored whatever the run does, so that no later test on this thread runs without it.
  struct Restore {
    ~Restore() { prd_detail::t_use_kept_basis = true; }
  } restore;
  prd_detail::t_use_kept_basis = kept;
  return prd_run(c, s);
}

void expect_same_run(const Case& c, const std::string& what) {
  const RunResult ref = run(c, false, false), kept = run(c, false, true);
  EXPECT_EQ(ref.timing.kept_basis_solves, 0) << what;
  EXPECT_GT(kept.timing.kept_basis_solves, kept.timing.lp_solves / 3) << what << ": " << kept.timing.lp_solves << " LPs";
  ASSERT_EQ(kept.status, ref.status) << what;
  EXPECT_EQ(kept.stable_steps, ref.stable_steps) << what;
  ASSERT_EQ(kept.steps.size(), ref.steps.size()) << what;
  const double W = ref.total_weight, L = scene_size(c);
  EXPECT_NEAR(kept.capacity, ref.capacity, 1e-9 * L) << what;
  for (size_t k = 0; k < ref.steps.size(); ++k) {
    const StepRecord &a = ref.steps[k], &b = kept.steps[k];
    const std::string at = what + ", step " + std::to_string(k);
    EXPECT_NEAR(b.d, a.d, 1e-9 * L) << at;
    EXPECT_NEAR(b.energy, a.energy, 1e-9 * W * L) << at;
    ASSERT_EQ(b.open_corners.size(), a.open_corners.size()) << at;
    for (size_t q = 0; q < a.open_corners.size(); ++q) {
      EXPECT_EQ(b.open_corners[q].joint, a.open_corners[q].joint) << at;
      EXPECT_EQ(b.open_corners[q].corner, a.open_corners[q].corner) << at;
    }
    EXPECT_EQ(b.cracked, a.cracked) << at;
    ASSERT_EQ(b.forces.size(), a.forces.size()) << at;
    for (size_t q = 0; q < a.forces.size(); ++q) {
      EXPECT_EQ(b.forces[q].joint, a.forces[q].joint) << at;
      EXPECT_NEAR(b.forces[q].normal, a.forces[q].normal, 1e-9 * W) << at;
      EXPECT_NEAR(b.forces[q].shear, a.forces[q].shear, 1e-9 * W) << at;
    }
    ASSERT_EQ(b.reactions.size(), a.reactions.size()) << at;
    for (size_t q = 0; q < a.reactions.size(); ++q) {
      EXPECT_NEAR((b.reactions[q].force - a.reactions[q].force).norm(), 0.0, 1e-9 * W) << at;
      EXPECT_NEAR(b.reactions[q].moment, a.reactions[q].moment, 1e-9 * W * L) << at;
    }
  }
}

Case standard_file(const std::string& name) { return load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

TEST(PrdKeptBasis, StandardScenesRunAsGlpkRunsThem) {
  for (const char* name : {"pointed-arch", "cathedral-settlement", "cathedral-settlement-rotation", "tilting-block"}) {
    expect_same_run(standard_file(name), name);
    EXPECT_EQ(run(standard_file(name), true, true).timing.kept_basis_solves, 0) << name << " (adaptive)";
  }
}

TEST(PrdKeptBasis, AWallRunsAsGlpkRunsIt) {
  BrickWall w;
  w.bond = WallBond::header;
  w.courses = 10;
  w.bricks = 16;
  w.moving = MovingGround::left;
  w.rotation_step = 0.002;  // the ground turns as it settles, so the wall's contacts change
  w.max_steps = 30;
  w.openings = {parse_wall_opening("0.5,0.25,0.5,0.5,arch")};
  expect_same_run(brick_wall(w), "header-bond wall with an arch, left ground settling and turning");
}

}  // namespace
}  // namespace masonry
