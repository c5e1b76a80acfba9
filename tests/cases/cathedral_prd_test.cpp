// The cathedral through the PRD solver: stable as it stands, a finite capacity under the
// settlement of the third pier (the paper: 180 cm; any finite value passes here, the numbers are
// in reports/).
#include <gtest/gtest.h>

#include "cases/generators.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

TEST(CathedralPrd, StableAsItStands) {
  const Case c = gothic_cathedral(GothicCathedral{});
  const PrdCheck r = prd_check(c, c.prd.contact_tolerance);
  EXPECT_TRUE(r.stable);
}

TEST(CathedralPrd, FiniteCapacityUnderSettlement) {
  const Case c = standard_case("cathedral-settlement");
  PrdSettings s = PrdSettings::from_case(c);
  // 3 m of settlement is far beyond any plausible capacity (paper: 1.80 m); the run must stop
  // on a collapse before it.
  s.max_steps = 300;
  const RunResult r = prd_run(c, s);
  EXPECT_TRUE(r.collapsed) << r.status << ": " << r.message;
  EXPECT_GT(r.capacity, 0.0);
  EXPECT_LT(r.capacity, s.max_steps * s.step);
}

}  // namespace
}  // namespace masonry
