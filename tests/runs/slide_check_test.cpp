// runs/slide_check.hpp's read_statics: what PRD's sliding check says of a DEM's slide up to its
// end (compare/README.md, "A slide statics does not ask for"), on a check run made up here: each
// step's least friction angle over every admissible force state, given, and the verdict read from
// it against the DEM's friction angle by the rule's own words (within friction at every step up to
// the slide's end and at the first step at or past it; sliding certain at one of them; unknown
// where a step has no check or the run stops short).
#include "runs/slide_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace masonry {
namespace {

const Case& arch() {
  static const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  return c;
}

// A PRD run with steps at d = 0, 0.1, ..., each needing `angles[k]` degrees (NaN: no check at that
// step), the most demanding joint v1/v2 (blocks 2 and 3 of the arch).
RunResult check_run(const std::vector<double>& angles) {
  RunResult r;
  r.method = "prd";
  r.joints.push_back(JointInfo{});
  r.joints[0].i = 2;
  r.joints[0].j = 3;
  for (size_t k = 0; k < angles.size(); ++k) {
    StepRecord s;
    s.index = int(k);
    s.d = 0.1 * double(k);
    if (!std::isnan(angles[k])) s.sliding = SlidingCheck{angles[k], 0, angles[k], 0};
    r.steps.push_back(s);
  }
  r.capacity = r.steps.back().d;
  return r;
}

SlideVerdict slide_to(double to) {
  SlideVerdict v;
  v.slide.to = to;
  return v;
}

TEST(SlideStatics, WithinFrictionUpToTheSlidesEndAndTheNextStepIsNotAsked) {
  SlideVerdict v = slide_to(0.25);
  read_statics(arch(), check_run({10, 20, 24, 28, 40}), 30, v);
  EXPECT_EQ(v.statics, Statics::within_friction);
  EXPECT_EQ(v.needs, 28.0);  // the most over d = 0 to 0.3, the first step past 0.25
  EXPECT_NEAR(v.at_d, 0.3, 1e-12);
  EXPECT_EQ(v.at_joint, "v1/v2");
  EXPECT_EQ(v.friction_angle, 30.0);
}

TEST(SlideStatics, SlidingCertainBeforeTheEndOrAtTheNextStepIsAsked) {
  SlideVerdict v = slide_to(0.25);
  read_statics(arch(), check_run({10, 31, 24, 28, 40}), 30, v);
  EXPECT_EQ(v.statics, Statics::slides);
  EXPECT_NEAR(v.at_d, 0.1, 1e-12);
  EXPECT_EQ(v.needs, 31.0);
  // Certain only at the first step past the end: the onset may lie before it.
  v = slide_to(0.25);
  read_statics(arch(), check_run({10, 20, 24, 31, 40}), 30, v);
  EXPECT_EQ(v.statics, Statics::slides);
  EXPECT_NEAR(v.at_d, 0.3, 1e-12);
  // At the end itself: the step at d = 0.2 is the first at or past it.
  v = slide_to(0.2);
  read_statics(arch(), check_run({10, 20, 31, 40}), 30, v);
  EXPECT_EQ(v.statics, Statics::slides);
}

TEST(SlideStatics, AStepWithoutACheckOrARunThatStopsShortIsUnknown) {
  SlideVerdict v = slide_to(0.25);
  read_statics(arch(), check_run({10, NAN, 24, 28}), 30, v);
  EXPECT_EQ(v.statics, Statics::unknown);
  EXPECT_NE(v.why_unknown.find("step 1"), std::string::npos) << v.why_unknown;
  v = slide_to(0.45);
  read_statics(arch(), check_run({10, 20, 24, 28}), 30, v);
  EXPECT_EQ(v.statics, Statics::unknown);
  EXPECT_NE(v.why_unknown.find("stops"), std::string::npos) << v.why_unknown;
}

}  // namespace
}  // namespace masonry
