// A PRD run with joint corners held closed over the whole run (prd.hold_closed, `masonry prd
// --hold`). Expected values from statics and LP theory: a tilting block glued at its lifting
// corner carries the closed-form corner force W (b cos t - h sin t) / (2 b), a tension past the
// toppling angle atan(b/h); holding a corner the free run never opens keeps its path (LP theory);
// a name no
// corner has is refused naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "common.hpp"
#include "model/case.hpp"
#include "model/interfaces.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

const std::string kBlock = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";
const std::string kArch = std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json";

double held_force(const StepRecord& s, const std::string& corner) {
  for (const HeldCorner& h : s.held_corners)
    if (h.corner == corner) return h.force;
  return NAN;
}

TEST(PrdHold, ATiltingBlockHeldAtItsLiftingCornerCarriesTheClosedFormForce) {
  // The slab turns counter-clockwise by d rad: the block would topple to the left about its
  // left corner (B) at atan(b/h); its right corner A is the one that lifts.
  const Case free_case = load_case(kBlock);
  const RunResult free = prd_run(free_case, PrdSettings::from_case(free_case));
  ASSERT_EQ(free.status, RunStatus::collapse);
  const Case c = with_option(free_case, "prd.hold_closed", std::vector<std::string>{"ground/block:A"});
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  // Glued at A, the block has no mechanism left: it rides the slab to the end of the path.
  EXPECT_EQ(r.status, RunStatus::max_steps) << r.message;
  ASSERT_EQ(r.steps.size(), size_t(c.motion.max_steps) + 1);
  const double b = 0.2, h = 0.4, W = b * h * 1.0 * 2000 * 9.81;
  bool tension = false;
  for (const StepRecord& s : r.steps) {
    const double t = s.d;  // 1 rad of tilt per m of d
    EXPECT_NEAR(held_force(s, "ground/block:A"), W * (b * std::cos(t) - h * std::sin(t)) / (2 * b), 1e-6 * W) << "d = " << s.d;
    tension = tension || held_force(s, "ground/block:A") < 0;
    for (const OpenCorner& o : s.open_corners) EXPECT_FALSE(o.joint == 0 && o.corner == 0) << "the held corner opened at d = " << s.d;
  }
  EXPECT_TRUE(tension);  // past atan(b/h) = 0.4636 rad the hold pulls
  EXPECT_EQ(r.settings["hold_closed"], nlohmann::json::array({"ground/block:A"}));
}

TEST(PrdHold, HoldingACornerTheFreeRunNeverOpensChangesNothing) {
  const Case free_case = load_case(kArch);
  const RunResult free = prd_run(free_case, PrdSettings::from_case(free_case));
  std::set<std::pair<int, int>> opened;
  for (const StepRecord& s : free.steps)
    for (const OpenCorner& o : s.open_corners) opened.insert({o.joint, o.corner});
  for (const CornerRef& o : free.collapse.value().mechanism.open_corners) opened.insert({o.joint, o.corner});
  // The first corner of the arch that opens neither on the way nor in the collapse mechanism.
  std::string never;
  for (size_t j = 0; j < free.joints.size() && never.empty(); ++j)
    for (int k = 0; k < 2 && never.empty(); ++k)
      if (!opened.count({int(j), k})) never = corner_name(free_case, free.joints[j].i, free.joints[j].j, k);
  ASSERT_FALSE(never.empty());
  const Case c = with_option(free_case, "prd.hold_closed", std::vector<std::string>{never});
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  EXPECT_EQ(r.status, free.status);
  // The same path: the same open corners at every step on the way; the capacity within one step
  // (the hold closes the corner exactly where the free run leaves a gap under the contact
  // tolerance, a difference of second order that can move the last step).
  const double step = c.motion.step;
  EXPECT_NEAR(r.capacity, free.capacity, step * 1.001) << "held " << never;
  for (size_t k = 0; k < std::min(r.steps.size(), free.steps.size()) && free.steps[k].d < free.capacity - 2 * step; ++k) {
    std::set<std::pair<int, int>> a, b;
    for (const OpenCorner& o : r.steps[k].open_corners) a.insert({o.joint, o.corner});
    for (const OpenCorner& o : free.steps[k].open_corners) b.insert({o.joint, o.corner});
    EXPECT_EQ(a, b) << "d = " << free.steps[k].d;
  }
}

TEST(PrdHold, ACornerNoJointHasIsRefusedNamingTheField) {
  const test::Scratch scratch("prd-hold");
  const std::string cmd =
      std::string(MASONRY_EXE) + " prd " + kArch + " --hold v3/nowhere:A --out " + scratch.path.string() + " 2> " + (scratch.path / "err").string();
  EXPECT_EQ(test::run(cmd), 2);
  const std::string err = test::read(scratch.path / "err");
  EXPECT_NE(err.find("hold_closed"), std::string::npos) << err;
  EXPECT_NE(err.find("v3/nowhere:A"), std::string::npos) << err;
  // Not a corner name at all: the case loader refuses it.
  EXPECT_THROW(with_option(load_case(kArch), "prd.hold_closed", std::vector<std::string>{"v3"}), CaseError);
  // One '/', one ':', then a letter, or A or B and a joint's number past the letters (the 14th on).
  for (const char* bad : {"a/b/c:A", "a:x/b:A", "a/b:c:A", "a/b:A0", "a/b:B13", "a/b:a", "a/b:"})
    EXPECT_THROW(with_option(load_case(kArch), "prd.hold_closed", std::vector<std::string>{bad}), CaseError) << bad;
  for (const char* good : {"v3/v4:A", "v3/v4:C", "v3/v4:Z", "v3/v4:A14", "v3/v4:B140"})
    EXPECT_NO_THROW(with_option(load_case(kArch), "prd.hold_closed", std::vector<std::string>{good})) << good;
}

// Two blocks that meet at more than one joint (a post seated in a notch: its two sides and the
// floor) name each joint's corners apart, so a hold holds the one corner it names.
TEST(PrdHold, AHoldInANotchHoldsTheCornerItNames) {
  const Case seated = parse_case(R"({"format": "masonry-case/1", "name": "notch", "gravity": 9.81, "blocks": [
    {"id": "base", "support": true, "vertices": [[-1, -0.5], [1, -0.5], [1, 0.5], [0.25, 0.5], [0.25, 0], [-0.25, 0], [-0.25, 0.5], [-1, 0.5]]},
    {"id": "post", "density": 2000, "vertices": [[-0.25, 0], [0.25, 0], [0.25, 1], [-0.25, 1]]}],
    "motion": {"step": 0.01, "max_steps": 3, "supports": [{"block": "base", "rotation": 1, "about": [0, -0.5]}]}})",
                                 "notch.json");
  // The joints in their order (detect_interfaces: by blocks, the normal's direction, then along
  // the tangent): the right wall (A, B), the floor (C, D), the left wall (E, F).
  const RunResult free = prd_run(seated, PrdSettings::from_case(seated));
  ASSERT_EQ(free.joints.size(), 3u);
  EXPECT_EQ(free.joints[0].a, Vec2(0.25, 0.5));
  EXPECT_EQ(free.joints[1].a, Vec2(0.25, 0.0));  // the floor: C is its right corner
  EXPECT_EQ(free.joints[1].b, Vec2(-0.25, 0.0));
  EXPECT_EQ(free.joints[2].b, Vec2(-0.25, 0.5));
  for (const std::string corner : {"base/post:A", "base/post:C", "base/post:F"}) {
    const Case c = with_option(seated, "prd.hold_closed", std::vector<std::string>{corner});
    const RunResult r = prd_run(c, PrdSettings::from_case(c));
    ASSERT_FALSE(r.steps.empty()) << r.message;
    for (const StepRecord& s : r.steps) {
      ASSERT_EQ(s.held_corners.size(), 1u) << corner << " at d = " << s.d;
      EXPECT_EQ(s.held_corners[0].corner, corner);
    }
  }
}

}  // namespace
}  // namespace masonry
