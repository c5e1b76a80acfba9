// PRD solver tests. Every expected value comes from outside the solver: closed forms
// (toppling at atan(b/h), Milankovitch's minimum thickness), equilibrium recomputed from the
// reported forces, LP duality, and invariances (step, tolerance, scale, density).
#include "prd/prd.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cases/generators.hpp"
#include "helpers.hpp"

namespace masonry {
namespace {

using testing::equilibrium_residual;
using testing::hinge_count;
using testing::mechanism_sequence;

Case tilting_block(double b, double h, double step, bool with_load = false) {
  std::string json = R"({
    "format": "masonry-case/1", "name": "tilting block", "gravity": 9.81,
    "blocks": [
      {"id": "ground", "vertices": [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.0], [-2.0, 0.0]], "support": true},
      {"id": "block", "vertices": [[0.0, 0.0], [B, 0.0], [B, H], [0.0, H]], "density": 2000.0}
    ],)";
  if (with_load) json += R"( "loads": [{"block": "block", "force": [0.0, -500.0], "point": [BHALF, H]}],)";
  json += R"( "motion": {"step": STEP, "max_steps": 5000,
      "supports": [{"block": "ground", "rotation": 1.0, "about": [-2.0, -0.5]}]}
  })";
  auto sub = [&](const std::string& key, double v) {
    for (size_t p; (p = json.find(key)) != std::string::npos;) json.replace(p, key.size(), std::to_string(v));
  };
  sub("BHALF", b / 2);
  sub("STEP", step);
  sub("B", b);
  sub("H", h);
  return parse_case(json, "tilting-block.json");
}

TEST(PrdTopple, BlockOnTiltingSupportToppleAtAtanBOverH) {
  const double step = 0.001;  // rad of tilt per step (rotation 1 rad per m of d)
  Case c = tilting_block(0.5, 1.0, step);
  RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_TRUE(r.collapsed) << r.message;
  const double critical = std::atan(0.5 / 1.0);
  // The capacity is the last stable tilt: within one step below the closed form.
  EXPECT_LE(r.capacity, critical);
  EXPECT_GT(r.capacity, critical - step);
}

TEST(PrdTopple, PointLoadOnTopMovesTheTippingAngle) {
  // Weight W at h/2 and a 500 N dead load at h, both over the middle of the base: the block
  // tips when their common line of action passes the lower corner: tan(a) = (b/2) / h_eff.
  const double b = 0.5, h = 1.0, step = 0.0005;
  Case c = tilting_block(b, h, step, true);
  const double W = 2000.0 * 9.81 * b * h, P = 500.0;
  const double h_eff = (W * h / 2 + P * h) / (W + P);
  const double critical = std::atan((b / 2) / h_eff);
  RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_TRUE(r.collapsed);
  EXPECT_LE(r.capacity, critical);
  EXPECT_GT(r.capacity, critical - step);
}

TEST(PrdTopple, SquatBlockTopplesLaterThanSlenderOne) {
  // Same closed form for another aspect ratio: b/h = 0.8.
  const double step = 0.001;
  Case c = tilting_block(0.8, 1.0, step);
  RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_TRUE(r.collapsed);
  const double critical = std::atan(0.8);
  EXPECT_LE(r.capacity, critical);
  EXPECT_GT(r.capacity, critical - step);
}

Case semicircle(double t_over_r, int n = 20) {
  CircularArch a;
  a.radius = 1.0;
  a.thickness = t_over_r;
  a.voussoirs = n;
  a.spreading = false;
  return circular_arch(a);
}

TEST(PrdMilankovitch, SemicircularArchStableAt0110UnstableAt0105) {
  EXPECT_TRUE(prd_check(semicircle(0.110), 1e-5).stable);
  EXPECT_FALSE(prd_check(semicircle(0.105), 1e-5).stable);
}

TEST(PrdMilankovitch, BisectionFindsMinimumThickness) {
  double lo = 0.09, hi = 0.13;  // unstable, stable
  ASSERT_FALSE(prd_check(semicircle(lo), 1e-5).stable);
  ASSERT_TRUE(prd_check(semicircle(hi), 1e-5).stable);
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    (prd_check(semicircle(mid), 1e-5).stable ? hi : lo) = mid;
  }
  // Milankovitch (1907): t/R = 0.1075 for the semicircular arch with radial joints.
  EXPECT_NEAR(0.5 * (lo + hi), 0.1075, 0.001);
}

TEST(PrdMilankovitch, UnstableArchReportsACollapseMechanism) {
  const PrdCheck k = prd_check(semicircle(0.09), 1e-5);
  ASSERT_FALSE(k.stable);
  // A four-hinge mechanism at least (a three-hinge arch is statically determinate).
  EXPECT_GE(k.collapse.open_corners.size(), 4u);
}

// Forces: equilibrium of every free block, compression only, reactions = weight, duality.
void check_forces(const Case& c, const RunResult& r, const StepRecord& s, bool fixed_supports) {
  const auto res = equilibrium_residual(c, r, s);
  EXPECT_LT(res.force, 1e-8 * r.total_weight) << "step " << s.index;
  EXPECT_LT(res.moment, 1e-8 * r.total_weight * scene_size(c)) << "step " << s.index;
  for (const JointForce& f : s.forces) EXPECT_GE(f.normal, -1e-9 * r.total_weight) << "joint " << f.joint;
  if (fixed_supports) {
    Vec2 sum(0, 0);
    for (const Reaction& x : s.reactions) sum += x.force;
    EXPECT_NEAR(sum.y(), r.total_weight, 1e-8 * r.total_weight);
    EXPECT_NEAR(sum.x(), 0.0, 1e-8 * r.total_weight);
  }
  ASSERT_TRUE(s.lp);
  const double primal = s.lp->primal, dual = s.lp->dual;
  EXPECT_NEAR(primal, dual, 1e-7 * (std::abs(primal) + r.total_weight * 1e-3));
}

TEST(PrdForces, ArchAsItStandsIsInEquilibrium) {
  Case c = semicircle(0.15);
  c.motion.max_steps = 0;  // only the configuration as it stands
  RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_EQ(r.steps.size(), 1u);
  check_forces(c, r, r.steps[0], true);
  double W = 0;
  for (const Block& b : c.blocks) W += b.support ? 0 : block_mass(b) * c.gravity;
  EXPECT_NEAR(r.total_weight, W, 1e-9 * W);
}

TEST(PrdForces, SpreadingArchStaysInEquilibriumAtEveryStep) {
  CircularArch a;
  a.thickness = 0.15;
  a.voussoirs = 16;
  a.step = 0.002;
  Case c = circular_arch(a);
  RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_TRUE(r.collapsed);
  ASSERT_GT(r.steps.size(), 10u);
  for (const StepRecord& s : r.steps) check_forces(c, r, s, false);
  // With a moving support the reactions still carry the whole weight vertically and balance
  // horizontally (nothing else touches the structure).
  for (const StepRecord& s : r.steps) {
    Vec2 sum(0, 0);
    for (const Reaction& x : s.reactions) sum += x.force;
    EXPECT_NEAR(sum.y(), r.total_weight, 1e-8 * r.total_weight);
    EXPECT_NEAR(sum.x(), 0.0, 1e-8 * r.total_weight);
  }
}

TEST(PrdForces, CheckOfAPointLoadedBlockCarriesTheLoad) {
  Case c = tilting_block(0.5, 1.0, 0.001, true);
  const PrdCheck k = prd_check(c, 1e-5);
  ASSERT_TRUE(k.stable);
  const double W = 2000.0 * 9.81 * 0.5;
  ASSERT_EQ(k.state.reactions.size(), 1u);
  EXPECT_NEAR(k.state.reactions[0].force.y(), W + 500.0, 1e-8 * W);
  EXPECT_NEAR(k.total_weight, W + 500.0, 1e-9 * W);
}

RunResult spreading_arch(double step, double tol, double scale = 1.0, double density = 1800.0) {
  CircularArch a;
  a.radius = 1.0 * scale;
  a.thickness = 0.15 * scale;
  a.voussoirs = 20;
  a.step = step * scale;
  a.density = density;
  a.max_steps = 5000;
  Case c = circular_arch(a);
  c.prd.contact_tolerance = tol * scale;
  return prd_run(c, PrdSettings::from_case(c));
}

TEST(PrdSpreadingArch, ThreeHingesAtTheFirstStepAndFiniteCapacity) {
  RunResult r = spreading_arch(0.001, 1e-5);
  ASSERT_TRUE(r.collapsed) << r.status << " " << r.message;
  EXPECT_EQ(r.status, RunStatus::collapse);
  ASSERT_GE(r.steps.size(), 2u);
  EXPECT_EQ(hinge_count(r.steps[1]), 3);
  EXPECT_EQ(r.steps[1].open_corners.size(), 3u);
  EXPECT_GT(r.capacity, 0.01);
  EXPECT_LT(r.capacity, 1.0);
  // The potential energy falls as the arch follows its support down.
  EXPECT_LT(r.steps.back().energy, 0.0);
}

void expect_same_run(const RunResult& ref, const RunResult& other, const char* what) {
  EXPECT_NEAR(other.capacity, ref.capacity, 0.02 * ref.capacity) << what;
  const auto a = mechanism_sequence(ref), b = mechanism_sequence(other);
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].open, b[k].open) << what << ", mechanism " << k;
    EXPECT_NEAR(a[k].d, b[k].d, 0.02 * ref.capacity + 2 * ref.settings["step"].get<double>()) << what;
  }
}

TEST(PrdSpreadingArch, StableUnderStepAndToleranceChanges) {
  const RunResult ref = spreading_arch(0.001, 1e-5);
  ASSERT_TRUE(ref.collapsed);
  expect_same_run(ref, spreading_arch(0.0005, 1e-5), "step halved");
  expect_same_run(ref, spreading_arch(0.001, 1e-4), "tolerance x10");
  expect_same_run(ref, spreading_arch(0.001, 1e-6), "tolerance /10");
}

TEST(PrdInvariance, GeometryScaledByTenScalesTheCapacity) {
  const RunResult a = spreading_arch(0.001, 1e-5);
  const RunResult b = spreading_arch(0.001, 1e-5, 10.0);
  ASSERT_TRUE(a.collapsed && b.collapsed);
  EXPECT_NEAR(b.capacity, 10 * a.capacity, 10 * 0.001 + 1e-9);
  EXPECT_EQ(mechanism_sequence(a).size(), mechanism_sequence(b).size());
}

TEST(PrdInvariance, DensityChangesNothingButTheForces) {
  const RunResult a = spreading_arch(0.002, 1e-5, 1.0, 1800.0);
  const RunResult b = spreading_arch(0.002, 1e-5, 1.0, 2500.0);
  EXPECT_EQ(a.capacity, b.capacity);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(testing::open_set(a.steps[k]), testing::open_set(b.steps[k]));
    for (size_t s = 0; s < a.steps[k].reactions.size(); ++s)
      EXPECT_NEAR(b.steps[k].reactions[s].force.x() / b.total_weight, a.steps[k].reactions[s].force.x() / a.total_weight, 1e-9);
  }
}

TEST(PrdDeterminism, SameCaseSameResult) {
  const RunResult a = spreading_arch(0.002, 1e-5), b = spreading_arch(0.002, 1e-5);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  EXPECT_EQ(a.capacity, b.capacity);
  for (size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(testing::open_set(a.steps[k]), testing::open_set(b.steps[k]));
    for (size_t p = 0; p < a.steps[k].poses.size(); ++p) EXPECT_EQ(a.steps[k].poses[p].x, b.steps[k].poses[p].x);
  }
}

TEST(PrdRun, CallbackSeesEveryFinishedStep) {
  Case c = tilting_block(0.5, 1.0, 0.01);
  std::vector<size_t> seen;
  RunResult r = prd_run(c, PrdSettings::from_case(c), [&](const RunResult& x) { seen.push_back(x.steps.size()); });
  ASSERT_FALSE(seen.empty());
  // Each call holds one more finished step than the one before, and the last holds them all.
  for (size_t k = 1; k + 1 < seen.size(); ++k) EXPECT_EQ(seen[k], seen[k - 1] + 1);
  EXPECT_EQ(seen.back(), r.steps.size());
  EXPECT_EQ(r.stable_steps + 1, static_cast<int>(r.steps.size()));
}

TEST(PrdRun, MaxStepsStopsAStableRun) {
  Case c = tilting_block(0.5, 1.0, 0.001);
  PrdSettings s = PrdSettings::from_case(c);
  s.max_steps = 10;
  RunResult r = prd_run(c, s);
  EXPECT_FALSE(r.collapsed);
  EXPECT_EQ(r.status, RunStatus::max_steps);
  EXPECT_EQ(r.stable_steps, 10);
  EXPECT_NEAR(r.capacity, 0.010, 1e-12);
  EXPECT_EQ(r.timing.lp_solves, 11);
}

}  // namespace
}  // namespace masonry
