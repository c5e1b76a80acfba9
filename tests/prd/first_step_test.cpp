// prd_first_step: the run's first LP, with corners held closed. The expected relations are LP
// theory, not numbers from the code: a constraint the optimum already satisfies leaves the
// optimal value unchanged, and a constraint that cuts the optimum off can only make it worse
// (release less potential energy).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "model/case.hpp"
#include "prd/prd.hpp"

namespace {

using namespace masonry;

const Case& arch() {
  static const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  return c;
}

double opening_of(const FirstStep& f, const std::string& corner) {
  for (const FirstStep::Opening& o : f.opening)
    if (o.corner == corner) return o.opening;
  return 0.0;
}

TEST(PrdFirstStep, AHingeHeldClosedGivesTheMirrorMechanismAndAClosedCornerChangesNothing) {
  const Case& c = arch();
  const double h = 0.001;
  const FirstStep free = prd_first_step(c, c.prd.contact_tolerance, h);
  ASSERT_TRUE(free.bounded);
  ASSERT_FALSE(free.opening.empty());
  EXPECT_LT(free.energy_change, 0);  // spreading supports let the arch down
  // The hinge that opens most, held closed: the structure must find another mechanism.
  const auto widest = std::max_element(free.opening.begin(), free.opening.end(), [](const auto& a, const auto& b) { return a.opening < b.opening; });
  const FirstStep held = prd_first_step(c, c.prd.contact_tolerance, h, {widest->corner});
  ASSERT_TRUE(held.bounded);
  EXPECT_GE(held.energy_change, free.energy_change - 1e-9 * std::abs(free.energy_change));
  EXPECT_LE(opening_of(held, widest->corner), 1e-9 * h) << widest->corner;
  // The arch and its loading are mirror-symmetric (the right support moving out is the mirror
  // image of the left one moving out, up to a rigid horizontal translation that does no work),
  // so mechanisms come in mirror pairs of equal energy (the paper's Remark 3): with one hinge
  // held closed the LP finds the mirror image, which releases the same energy and opens the
  // same amounts at the mirrored joints.
  EXPECT_NEAR(held.energy_change, free.energy_change, 1e-6 * std::abs(free.energy_change));
  auto sizes = [](const FirstStep& f) {
    std::vector<double> v;
    for (const FirstStep::Opening& o : f.opening) v.push_back(o.opening);
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<double> a = sizes(free), b = sizes(held);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-6 * h);
  // A corner that stays closed in the free optimum, held closed: the same optimum value.
  std::string closed;
  for (const std::string& corner : {std::string("v3/v4:A"), std::string("v3/v4:B"), std::string("v4/v5:A"), std::string("v4/v5:B")})
    if (opening_of(free, corner) == 0.0) {
      closed = corner;
      break;
    }
  ASSERT_FALSE(closed.empty());
  const FirstStep same = prd_first_step(c, c.prd.contact_tolerance, h, {closed});
  ASSERT_TRUE(same.bounded);
  EXPECT_NEAR(same.energy_change, free.energy_change, 1e-9 * std::abs(free.energy_change)) << closed;
}

TEST(PrdFirstStep, AnUnknownCornerIsRefusedByName) {
  try {
    prd_first_step(arch(), arch().prd.contact_tolerance, 0.001, {"v6/nosuch:A"});
    ADD_FAILURE() << "an unknown corner was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("v6/nosuch:A"), std::string::npos) << e.what();
  }
}

}  // namespace
