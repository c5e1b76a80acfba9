// A contact point's shear history belongs to the physical contact, not to the manifold's feature
// id. At an open hinge the two faces meet at an angle theta; when one face reaches past the
// touching corner by e, the separating-axis search prefers the other block's face as soon as
// theta e exceeds Box2D's bias (0.1 b2_linearSlop = 0.5 mm), so the reference face, and with it
// the id, flips with the hinge's angle while the contact stays where it was. Dropping the shear
// at each flip is a slip that no friction law allows (dem/README.md, "Shear history follows the
// contact, not the id").
#include <box2d/b2_common.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dem/contact.hpp"
#include "dem/dem.hpp"
#include "model/case.hpp"
#include "model/interfaces.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

std::vector<Vec2> normals_of(const std::vector<Vec2>& v) {
  std::vector<Vec2> n;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 e = v[(i + 1) % v.size()] - v[i];
    n.push_back(Vec2(e.y(), -e.x()).normalized());
  }
  return n;
}

// A pier top 1 m wide (top face y = 0 from x = 0 to 1) and a block 2 m wide resting on its left
// corner, its right end lifted by theta x 1 m (the hinge's gap) and reaching 1 m past the corner
// on the left, its corner 10 um into the pier.
dem::Manifold hinge(double theta) {
  const std::vector<Vec2> pier = {Vec2(0, -1), Vec2(1, -1), Vec2(1, 0), Vec2(0, 0)};
  std::vector<Vec2> block;
  const double c = std::cos(theta), s = std::sin(theta), overlap = 1e-5;
  for (const Vec2& p : {Vec2(-1, 0), Vec2(1, 0), Vec2(1, 1), Vec2(-1, 1)})
    block.push_back(Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y() - overlap));
  const std::vector<Vec2> np = normals_of(pier), nb = normals_of(block);
  dem::Manifold m;
  dem::collide(pier.data(), np.data(), 4, block.data(), nb.data(), 4, m);
  return m;
}

TEST(DemShearHistory, TheReferenceFaceFlipsAtAnOpenHingeWhileTheContactStays) {
  // theta e below and above the bias: e = 1 m, so theta = 0.4e-3 and 0.6e-3 rad.
  const double bias = 0.1 * b2_linearSlop;
  ASSERT_NEAR(bias, 5e-4, 1e-9);  // b2_linearSlop is a float
  const dem::Manifold below = hinge(0.8 * bias), above = hinge(1.2 * bias);
  ASSERT_EQ(below.count, 1);  // the hinge is open at x = 1 (gap 0.4 and 0.6 mm)
  ASSERT_EQ(above.count, 1);
  // The reference face passes from the pier to the block: the flip is part of the point's
  // feature id, so the id changes...
  EXPECT_FALSE(below.flip);
  EXPECT_TRUE(above.flip);
  // ...for the same contact: both points sit at the pier's corner, far within a quarter of the
  // 1 m joint (the rule that carries the shear over, dem/model.cpp).
  EXPECT_LT(below.points[0].point.norm(), 1e-4);
  EXPECT_LT(above.points[0].point.norm(), 1e-4);
  EXPECT_NEAR(below.points[0].separation, above.points[0].separation, 1e-6);
}

// The settlement cathedral, whose nave springs from the settling pier with such a hinge
// (nave-41/R-pier-30: the pier's top face reaches a metre past the voussoir's corner). When
// every flip there dropped 3.2e5 N of shear (|T|/N 0.23, far below tan 35 degrees), the
// springing slid in steps of some 11 um every 40 ms, the holds took 14-20 s, and the nave left
// PRD's mechanism for the DEM's "X" (nave-24/25 opening right of the crown) by d = 0.03 m. With
// the contact's history kept, the DEM opens PRD's springing hinge. Expected values come from PRD
// on the same case.
TEST(DemShearHistory, TheSettlingCathedralOpensPrdsSpringingHingeNotAnotherMechanism) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/cathedral-settlement.json");
  const int steps = 3;  // d = 0.03 m
  PrdSettings ps = PrdSettings::from_case(c);
  ps.max_steps = steps;
  const RunResult prd = prd_run(c, ps);
  DemSettings ds = DemSettings::from_case(c);
  ds.max_steps = steps;
  const RunResult dem = dem_run(c, ds);
  ASSERT_EQ(dem.status, RunStatus::max_steps) << dem.message;
  ASSERT_EQ(static_cast<int>(dem.steps.size()), steps + 1);
  ASSERT_EQ(static_cast<int>(prd.steps.size()), steps + 1);

  const auto gap = [&](const RunResult& r, const std::string& corner) {
    for (const OpenCorner& o : r.steps.back().open_corners) {
      const JointInfo& J = r.joints[o.joint];
      if (corner_name(c, J.i, J.j, o.corner) == corner) return o.gap;
    }
    return 0.0;
  };
  const std::string springing = "nave-41/R-pier-30:A", x_hinge = "nave-24/nave-25:A";
  const double prd_springing = gap(prd, springing);
  ASSERT_GT(prd_springing, 1e-3) << "PRD's springing hinge at d = 0.03 m";
  ASSERT_EQ(gap(prd, x_hinge), 0.0);
  // The DEM's hinge opens as PRD's does, within half of its opening (the elastic joints open it
  // later: the first millimetres of settlement go into their compliance).
  EXPECT_GT(gap(dem, springing), 0.5 * prd_springing);
  // And X's hinge stays shut: below the widest gap the settling left (0.23 mm; compare/README.md,
  // "Hinges of the support motion"), where it opened 2.7 mm before.
  EXPECT_LT(gap(dem, x_hinge), 0.23e-3);
}

}  // namespace
}  // namespace masonry
