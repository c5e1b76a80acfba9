// compare/README.md, "A slide statics does not ask for": slide_suspect reads a comparison's
// sliding check against the supports' travel. The pointed arch's support spreads by d along a unit
// translation, so the travel up to d is d (closed form), and a DEM joint's net slip counts against
// kUnexplainedSlide of it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "compare/compare.hpp"
#include "compare/slide.hpp"
#include "model/case.hpp"

namespace masonry {
namespace {

Comparison with_slips(double to, double slip_a, double slip_b) {
  Comparison k;
  SlipCheck s;
  s.to = s.a_to = s.b_to = to;
  s.largest_b = {3, "v3/v4", slip_a, slip_b};
  s.largest_a = s.largest_b;
  k.sliding = s;
  return k;
}

const Case& arch() {
  static const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  return c;
}

TEST(Slide, ADemJointSlidFarOnAPathWherePrdsDidNotIsSuspect) {
  const double to = 0.25;  // m of spreading: the supports' travel, the translation being a unit vector
  const auto s = slide_suspect(arch(), with_slips(to, 1e-6, 2 * kUnexplainedSlide * to));
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->joint, "v3/v4");
  EXPECT_NEAR(s->travel, to, 1e-12);
  EXPECT_NEAR(s->slip, 2 * kUnexplainedSlide * to, 1e-15);
  EXPECT_NEAR(s->other, 1e-6, 1e-18);
  EXPECT_EQ(s->to, to);
  // PRD's joint came apart there (NaN): the DEM slid where PRD opened, still a slide PRD has not.
  EXPECT_TRUE(slide_suspect(arch(), with_slips(to, std::numeric_limits<double>::quiet_NaN(), 0.1 * to)).has_value());
}

TEST(Slide, ElasticShearAndASlideBothRunsMadeAreNot) {
  const double to = 0.25;
  // Below the limit: a joint's elastic shear (microns), or half the limit.
  EXPECT_FALSE(slide_suspect(arch(), with_slips(to, 0.0, 5e-6)).has_value());
  EXPECT_FALSE(slide_suspect(arch(), with_slips(to, 0.0, 0.5 * kUnexplainedSlide * to)).has_value());
  // Both runs slid the joint: they agree on a sliding mechanism.
  EXPECT_FALSE(slide_suspect(arch(), with_slips(to, 0.04 * to, 0.05 * to)).has_value());
  // Nothing travelled yet, or no sliding check.
  EXPECT_FALSE(slide_suspect(arch(), with_slips(0.0, 0.0, 1e-3)).has_value());
  EXPECT_FALSE(slide_suspect(arch(), Comparison{}).has_value());
}

}  // namespace
}  // namespace masonry
