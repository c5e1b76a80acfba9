// The PRD sliding check. Expected values from statics: a block on a plane inclined at alpha
// needs exactly tan(alpha) of friction in any admissible state; on a tilting plane that angle
// is the tilt, up to toppling at atan(b/h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "model/case.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

constexpr double kDeg = 180.0 / M_PI;

// A block b x h standing on a ground block; both are rotated by alpha about the origin. With
// `split`, the ground is two blocks meeting under the middle of the block: two joints on one
// line, so how the shear is shared between them is statically indeterminate.
Case inclined(double alpha, double b, double h, bool split, bool tilting) {
  Eigen::Matrix2d R;
  R << std::cos(alpha), -std::sin(alpha), std::sin(alpha), std::cos(alpha);
  auto poly = [&](std::vector<Vec2> v) {
    nlohmann::json a = nlohmann::json::array();
    for (Vec2& p : v) {
      p = R * p;
      a.push_back({p.x(), p.y()});
    }
    return a;
  };
  nlohmann::json blocks = nlohmann::json::array();
  if (split) {
    blocks.push_back({{"id", "ground-l"}, {"vertices", poly({{-2, -0.5}, {0.1, -0.5}, {0.1, 0}, {-2, 0}})}, {"support", true}});
    blocks.push_back({{"id", "ground-r"}, {"vertices", poly({{0.1, -0.5}, {2, -0.5}, {2, 0}, {0.1, 0}})}, {"support", true}});
  } else {
    blocks.push_back({{"id", "ground"}, {"vertices", poly({{-2, -0.5}, {2, -0.5}, {2, 0}, {-2, 0}})}, {"support", true}});
  }
  blocks.push_back(
      {{"id", "block"}, {"vertices", poly({{-b / 2 + 0.1, 0}, {b / 2 + 0.1, 0}, {b / 2 + 0.1, h}, {-b / 2 + 0.1, h}})}, {"density", 2000.0}});
  nlohmann::json motion = {{"step", 0.5 / kDeg}, {"max_steps", tilting ? 200 : 0}, {"supports", nlohmann::json::array()}};
  if (tilting)
    for (const auto& g : blocks)
      if (g.contains("support")) motion["supports"].push_back({{"block", g["id"]}, {"rotation", 1.0}, {"about", {0.0, 0.0}}});
  nlohmann::json doc = {
      {"format", "masonry-case/1"}, {"name", "inclined block"}, {"blocks", blocks}, {"motion", motion}, {"prd", {{"sliding_check", true}}}};
  return parse_case(doc.dump(), "inclined-block.json");
}

TEST(PrdSliding, BlockOnAnInclinedPlaneNeedsTheInclination) {
  for (double alpha_deg : {0.0, 10.0, 20.0, 30.0}) {
    const Case c = inclined(alpha_deg / kDeg, 0.6, 0.4, false, false);
    const RunResult r = prd_run(c, PrdSettings::from_case(c));
    ASSERT_EQ(r.steps.size(), 1u) << r.message;
    ASSERT_TRUE(r.steps[0].sliding && r.sliding && r.sliding->any);
    EXPECT_NEAR(r.steps[0].sliding->demand_angle, alpha_deg, 1e-6) << alpha_deg;
    EXPECT_NEAR(r.steps[0].sliding->required_angle, alpha_deg, 0.02) << alpha_deg;
    EXPECT_NEAR(r.sliding->required_friction_angle, alpha_deg, 0.02);
  }
}

// Two joints on one line: the dual may share the shear unevenly (its demand can exceed alpha),
// but some admissible state shares it in proportion to the normal forces, needing alpha.
TEST(PrdSliding, IndeterminateShearNeedsOnlyTheInclination) {
  const double alpha_deg = 20;
  const Case c = inclined(alpha_deg / kDeg, 0.6, 0.4, true, false);
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_EQ(r.steps.size(), 1u) << r.message;
  ASSERT_TRUE(r.steps[0].sliding);
  EXPECT_GE(r.steps[0].sliding->demand_angle, alpha_deg - 1e-6);
  EXPECT_NEAR(r.steps[0].sliding->required_angle, alpha_deg, 0.02);
}

// On a tilting plane the need grows with the tilt until the block topples at atan(b/h): the
// run's required angle is that tilt, and the first step needing more than 15 degrees is at
// 15 degrees of tilt.
TEST(PrdSliding, TiltingPlaneNeedsTheTiltUntilToppling) {
  const double b = 0.4, h = 0.8;
  const Case c = inclined(0.0, b, h, false, true);
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double step_deg = 0.5, topple_deg = std::atan(b / h) * kDeg;
  for (const StepRecord& s : r.steps) {
    ASSERT_TRUE(s.sliding) << s.d;
    EXPECT_NEAR(s.sliding->required_angle, s.d * kDeg, 0.02) << s.d;
  }
  ASSERT_TRUE(r.sliding && r.sliding->any);
  const double req = r.sliding->required_friction_angle;
  EXPECT_LE(req, topple_deg + 0.02);
  EXPECT_GT(req, topple_deg - step_deg - 0.02);
  const auto e = first_sliding(c, r, 15.0, true);
  ASSERT_TRUE(e.has_value());
  EXPECT_GT(e->d * kDeg, 15.0 - 0.02);  // at exactly 15 degrees round-off decides
  EXPECT_LE(e->d * kDeg, 15.0 + step_deg + 1e-9);
  EXPECT_EQ(e->blocks, "ground/block");
  EXPECT_FALSE(first_sliding(c, r, 45.0, false).has_value());
}

// LP duality in the small: the best admissible state never needs more than the dual's.
TEST(PrdSliding, RequiredNeverExceedsTheDualsDemand) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  PrdSettings s = PrdSettings::from_case(c);
  s.sliding_check = true;
  const RunResult r = prd_run(c, s);
  ASSERT_EQ(r.status, RunStatus::collapse);
  for (const StepRecord& st : r.steps) {
    ASSERT_TRUE(st.sliding) << st.d;
    EXPECT_LE(st.sliding->required_angle, st.sliding->demand_angle + 1e-9);
  }
}

}  // namespace
}  // namespace masonry
