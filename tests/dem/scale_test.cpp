// Settings that must not matter to the DEM's answer: the scale of the weights (density, gravity)
// and where the scene lies. A rigid block topples at atan(b/h) whatever it weighs and wherever it
// stands; the joints' elasticity only moves that by their overlap over the block's width.
// Joints too soft to carry a block's weight on its joints are refused, not computed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dem/dem.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

constexpr double kDeg = M_PI / 180;

// The 0.2 x 0.4 m block of the tilt tests toppling on its slab (friction 45 degrees, so it does
// not slide first), at the given density and gravity.
RunResult topple_run(double density, double gravity, const Vec2& shift = Vec2(0, 0)) {
  Case c = test::tilt_case(0.2, 0.4, 45);
  c.blocks[1].density = density;
  c.gravity = gravity;
  for (Block& b : c.blocks)
    for (Vec2& v : b.vertices) v += shift;
  c.motion.supports[0].about += shift;
  c.motion.max_steps = 40;
  return test::tilt_run(c);
}

// How early the soft joints of the test scenes may let the block tip, rad: the toe's elastic
// overlap turns the block by overlap / b before the heel lifts. At the tipping point the toe
// carries the whole weight on its half of the joint (2 W / (kn A)); the bound doubles that for
// the tilt's own share. At 2000 kg/m^3 and 9.81 m/s^2 it is 0.09 degrees (the runs tip 0.07
// degrees early: DemBracket.ACollapseDuringAMoveIsACollapse); lighter, proportionally less.
double elastic_allowance(double density, double gravity) {
  const double W = density * 0.2 * 0.4 * gravity;
  return 4 * W / (1e8 * 0.2) / 0.2;
}

// Density 2000 down to 0.2 kg/m^3 (the joints 1e4 times stiffer against the weight) and gravity
// 9.81 down to 1e-4 m/s^2: the same toppling, each within its bracket (1% of the one-degree step)
// and the equilibrium tolerance's resolution of the tipping point. Before the DEM scaled its
// inertia to the structure's gravity and capped the servo's acceleration (dem/README.md,
// "Scale"), both light variants "toppled" at one degree: the supports braked at 90 times gravity
// and threw the block off the slab.
TEST(DemScale, TheWeightsScaleDoesNotMoveTheToppling) {
  const double resolution = 1e-4 * std::sqrt((0.04 + 0.16) / 12) / (0.5 * std::hypot(0.2, 0.4));
  for (const auto& [density, gravity] : {std::pair{2000.0, 9.81}, {0.2, 9.81}, {2000.0, 1e-4}}) {
    const RunResult r = topple_run(density, gravity);
    SCOPED_TRACE("density " + std::to_string(density) + " gravity " + std::to_string(gravity));
    ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
    const double tol = 0.01 * kDeg + 2 * resolution;
    EXPECT_LE(r.capacity, std::atan(0.5) + tol);
    EXPECT_GE(r.capacity, std::atan(0.5) - elastic_allowance(density, gravity) - tol);
    EXPECT_NEAR(r.settings["mass_scale"].get<double>(), gravity / kReferenceGravity, 1e-12);
  }
}

// The scene moved to (9e4, 9e4) m, near the coordinate range's end: the same capacity as at the
// origin, to its bracket, and the poses reported where the blocks are.
TEST(DemScale, APositionFarFromTheOriginChangesNothing) {
  const Vec2 far(9e4, 9e4);
  const RunResult here = topple_run(2000, 9.81), there = topple_run(2000, 9.81, far);
  ASSERT_EQ(there.status, RunStatus::collapse) << there.message;
  EXPECT_NEAR(there.capacity, here.capacity, 0.01 * kDeg);
  const Pose &p = there.steps[1].poses[1], &q = here.steps[1].poses[1];
  EXPECT_NEAR(p.x - far.x(), q.x, 1e-6);
  EXPECT_NEAR(p.y - far.y(), q.y, 1e-6);
}

// The 12-voussoir semicircular arch of the DEM tests far from the origin: a creep of 1e-6 m/s at
// its time step moves a block by about 1e-11 m a cycle, under the resolution of a double at
// 7e4 m, so in world coordinates its slow phases stalled (the paper's arch moved there found its
// "limit" at a third of its capacity). The same capacity, to the bracket.
TEST(DemScale, AnArchFarFromTheOriginHasItsCapacity) {
  Case c = test::semicircular_arch_case();
  const RunResult here = dem_run(c, DemSettings::from_case(c));
  const Vec2 far(7e4, 7e4);
  for (Block& b : c.blocks)
    for (Vec2& v : b.vertices) v += far;
  for (SupportMotion& m : c.motion.supports) m.about += far;
  const RunResult there = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(here.status, RunStatus::collapse) << here.message;
  ASSERT_EQ(there.status, RunStatus::collapse) << there.message;
  EXPECT_NEAR(there.capacity, here.capacity, 2 * c.dem.bracket_fraction * c.motion.step);
}

// A block 1e5 m deep on a 1 m deep slab carries its weight on 1 m of depth: at the tilt tests'
// kn its joint would overlap by 7.8 m. Refused before the first cycle, naming the block and the
// field, instead of computing the block sinking through the slab (a "collapse" at d = 0).
TEST(DemScale, JointsTooSoftForTheWeightAreRefused) {
  Case c = test::tilt_case(0.2, 0.4, 45);
  c.blocks[1].depth = 1e5;
  try {
    DemModel m(c, DemSettings::from_case(c));
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("block 'block'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'depth'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  c.blocks[1].depth = 1.0;
  EXPECT_NO_THROW(DemModel(c, DemSettings::from_case(c)));
}

// Joints too soft at matched depths are the stiffness's fault, not the depth's: the tilting block
// at --stiffness-reduction 1e6 was told "field 'depth' ... match the depths" (they matched) and
// not which of its settings made kn 100 Pa/m. The refusal names the option that set the
// stiffness. Expected: the case file's kn 1e8 Pa/m over 1e6, the block's weight
// (0.2 x 0.4 m x 2000 kg/m^3 x 9.81) over kn times its 0.2 m x 1 m base.
TEST(DemScale, JointsTooSoftAtMatchedDepthsNameTheStiffnessOption) {
  const Case file = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  const Case c = with_option(file, "dem.stiffness_reduction", 1e6);
  ASSERT_EQ(c.dem.kn, 1e8);
  try {
    DemModel m(c, DemSettings::from_case(c));
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("block 'block': field 'dem.stiffness_reduction' = 1e+06: its joints would overlap by at least 78.48 m"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("kn 100 Pa/m"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("'depth'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // Without a reduction, the case's own dem.kn is named.
  try {
    DemModel m(with_option(file, "dem.kn", 100.0), DemSettings::from_case(with_option(file, "dem.kn", 100.0)));
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'block': field 'dem.kn' = 100:"), std::string::npos) << e.what();
  }
}

}  // namespace
