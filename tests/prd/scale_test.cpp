// Limit analysis has no force scale: multiplying every load by a factor multiplies the forces by
// it and changes no mechanism, so the capacity cannot depend on the density, the gravity or the
// depth (issue 33: a tilting block of density 1e-3 under gravity 1e-6 never toppled, the pointed
// arch moved from 0.278 to 0.293 m). Scaling the geometry by s scales the capacity by s. Expected
// values: the closed form atan(b/h) and the invariances themselves.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "helpers.hpp"
#include "model/case.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

Case standard_file(const std::string& name) { return load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

Case with_weight_scale(Case c, double density, double gravity, double depth = 0) {
  c.gravity = gravity;
  for (Block& b : c.blocks) {
    if (!b.support) b.density = density;
    if (depth > 0) b.depth = depth;
  }
  return c;
}

// The case with every length scaled by s: the blocks, the points the supports turn about, the
// contact tolerance (the step, a length or an angle, is the caller's).
Case with_lengths_scaled(Case c, double s) {
  for (Block& b : c.blocks)
    for (Vec2& v : b.vertices) v *= s;
  for (SupportMotion& m : c.motion.supports) m.about *= s;
  c.prd.contact_tolerance *= s;
  return c;
}

// Every step's open corners, and the forces over the total weight.
void expect_same_run(const RunResult& ref, const RunResult& r, const std::string& what) {
  EXPECT_EQ(r.status, ref.status) << what;
  EXPECT_EQ(r.capacity, ref.capacity) << what;
  ASSERT_EQ(r.steps.size(), ref.steps.size()) << what;
  for (size_t k = 0; k < r.steps.size(); ++k) {
    EXPECT_EQ(testing::open_set(r.steps[k]), testing::open_set(ref.steps[k])) << what << ", step " << k;
    ASSERT_EQ(r.steps[k].reactions.size(), ref.steps[k].reactions.size());
    for (size_t s = 0; s < r.steps[k].reactions.size(); ++s) {
      const Vec2 a = r.steps[k].reactions[s].force / r.total_weight, b = ref.steps[k].reactions[s].force / ref.total_weight;
      EXPECT_NEAR((a - b).norm(), 0.0, 1e-9) << what << ", step " << k;
    }
  }
}

TEST(PrdScale, TiltingBlockTopplesAtAtanBOverHForEveryDensityAndGravity) {
  const Case base = standard_file("tilting-block");  // b = 0.2, h = 0.4, 1 degree per step
  const double topple = std::atan(0.2 / 0.4);
  const RunResult ref = prd_run(base, PrdSettings::from_case(base));
  ASSERT_EQ(ref.status, RunStatus::collapse) << ref.message;
  // The last stable tilt is within one step below atan(b/h).
  EXPECT_LE(ref.capacity, topple);
  EXPECT_GT(ref.capacity, topple - base.motion.step);
  for (double density : {1e-6, 1e-3, 1.0, 1e3, 1e5})
    for (double gravity : {1e-6, 1e-3, 1.0, 1e3}) {
      const Case c = with_weight_scale(base, density, gravity);
      expect_same_run(ref, prd_run(c, PrdSettings::from_case(c)), "density " + std::to_string(density) + ", gravity " + std::to_string(gravity));
    }
}

TEST(PrdScale, PointedArchCapacityIndependentOfTheWeightsScale) {
  Case base = standard_file("pointed-arch");
  base.motion.step = 0.004;  // coarser than the case's 1 mm: the same invariance, 4 times fewer LPs
  const RunResult ref = prd_run(base, PrdSettings::from_case(base));
  ASSERT_EQ(ref.status, RunStatus::collapse) << ref.message;
  for (double density : {1e-6, 1e-2, 1e5})
    for (double gravity : {1e-6, 1e-3, 1e3}) {
      const Case c = with_weight_scale(base, density, gravity);
      expect_same_run(ref, prd_run(c, PrdSettings::from_case(c)), "density " + std::to_string(density) + ", gravity " + std::to_string(gravity));
    }
  for (double depth : {1e-9, 1e-3, 1e3}) {
    const Case c = with_weight_scale(base, 1800.0, 9.81, depth);
    expect_same_run(ref, prd_run(c, PrdSettings::from_case(c)), "depth " + std::to_string(depth));
  }
}

TEST(PrdScale, AdaptiveRunAndSlidingCheckIndependentOfTheWeightsScale) {
  Case base = standard_file("pointed-arch");
  base.prd.adaptive = true;
  base.prd.sliding_check = true;
  const RunResult ref = prd_run(base, PrdSettings::from_case(base));
  ASSERT_EQ(ref.status, RunStatus::collapse) << ref.message;
  ASSERT_TRUE(ref.sliding && ref.sliding->any);
  for (double density : {1e-6, 1e5})
    for (double gravity : {1e-6, 1e3}) {
      const Case c = with_weight_scale(base, density, gravity);
      const RunResult r = prd_run(c, PrdSettings::from_case(c));
      const std::string what = "density " + std::to_string(density) + ", gravity " + std::to_string(gravity);
      EXPECT_NEAR(r.capacity, ref.capacity, 1e-9) << what;
      ASSERT_TRUE(r.sliding && r.sliding->any) << what;
      EXPECT_NEAR(r.sliding->required_friction_angle, ref.sliding->required_friction_angle, 1e-6) << what;
    }
}

TEST(PrdScale, GeometryScaledScalesTheCapacity) {
  const Case base = standard_file("pointed-arch");
  const RunResult ref = prd_run(base, PrdSettings::from_case(base));
  for (double s : {1e-3, 1e2}) {
    Case c = with_lengths_scaled(base, s);
    c.motion.step *= s;  // a translation: d is a length
    const RunResult r = prd_run(c, PrdSettings::from_case(c));
    EXPECT_EQ(r.status, ref.status) << s;
    EXPECT_EQ(r.stable_steps, ref.stable_steps) << s;
    EXPECT_NEAR(r.capacity / s, ref.capacity, 1e-9 * ref.capacity) << s;
  }
}

// Where every moving support only turns, d is an angle: the tilting block scaled by s topples
// at the same tilt, with event-driven steps too. The defaults of the event tolerance and the
// longest step are lengths of the scene (1e-4 of it, 0.4 sqrt(tolerance x size)), taken as the
// turn that moves the scene's points by them; read as angles they grew with the scene, and the
// block scaled by 100 toppled at 0.4524 rad, 2.4% early, in one step of 16 degrees (a user's
// trial, 2026-11-27).
TEST(PrdScale, AnAdaptiveTiltIsTheSameAtAnyScale) {
  Case base = standard_file("tilting-block");
  base.prd.adaptive = true;
  const RunResult ref = prd_run(base, PrdSettings::from_case(base));
  ASSERT_EQ(ref.status, RunStatus::collapse);
  EXPECT_NEAR(ref.capacity, std::atan(0.5), 1e-3 * std::atan(0.5));
  for (double s : {1e-2, 1e2}) {
    const Case c = with_lengths_scaled(base, s);  // a turn: d, an angle, stays
    const RunResult r = prd_run(c, PrdSettings::from_case(c));
    EXPECT_EQ(r.status, ref.status) << s;
    EXPECT_EQ(r.steps.size(), ref.steps.size()) << s;
    EXPECT_NEAR(r.capacity, ref.capacity, 1e-9) << s;
  }
}

}  // namespace
}  // namespace masonry
