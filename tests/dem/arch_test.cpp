// A circular arch on a spreading support: DEM capacity against the PRD solver on the same case,
// and the same three hinges (or their mirror image).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "cases/generators.hpp"
#include "dem/dem.hpp"
#include "prd/prd.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

// Block pairs of the hinged joints (a joint with exactly one open corner) at the step whose d is
// the capacity.
std::set<std::pair<int, int>> hinges(const RunResult& r) {
  std::set<std::pair<int, int>> h;
  std::map<int, int> open;
  const StepRecord* at = nullptr;
  for (const StepRecord& s : r.steps)
    if (std::abs(s.d - r.capacity) < 1e-9) at = &s;
  if (!at) return h;
  for (const OpenCorner& o : at->open_corners) ++open[o.joint];
  for (auto [j, n] : open)
    if (n == 1) h.insert({r.joints[j].i, r.joints[j].j});
  return h;
}

std::set<std::pair<int, int>> mirror(const std::set<std::pair<int, int>>& h, int nblocks) {
  std::set<std::pair<int, int>> m;
  for (auto [i, j] : h) m.insert({nblocks - 1 - j, nblocks - 1 - i});
  return m;
}

std::string show(const std::set<std::pair<int, int>>& h) {
  std::string s;
  for (auto [i, j] : h) {
    s += '(';
    s += std::to_string(i);
    s += ',';
    s += std::to_string(j);
    s += ')';
  }
  return s;
}

TEST(DemArch, CapacityAndHingesMatchPrd) {
  const Case c = test::semicircular_arch_case();
  const DemSettings s = DemSettings::from_case(c);
  const RunResult dem = dem_run(c, s);
  std::printf("DEM: %s capacity %.4f m, %d stable steps, %lld cycles, %.2f s, dt %.3g s\n", status_name(dem.status), dem.capacity, dem.stable_steps,
              dem.timing.cycles, dem.timing.total_s, dem.settings.value("dt", 0.0));
  ASSERT_EQ(dem.status, RunStatus::collapse) << dem.message;
  ASSERT_GT(dem.capacity, 0);
  const auto hd = hinges(dem);
  std::printf("DEM hinges at d = %.4f m: %s\n", dem.capacity, show(hd).c_str());
  EXPECT_EQ(hd.size(), 3u);

  const RunResult prd = prd_run(c, PrdSettings::from_case(c));
  ASSERT_NE(prd.status, RunStatus::error) << prd.message;
  std::printf("PRD: %s capacity %.4f m\n", status_name(prd.status), prd.capacity);
  EXPECT_NEAR(dem.capacity, prd.capacity, 0.06 * prd.capacity);
  const auto hp = hinges(prd);
  std::printf("PRD hinges at d = %.4f m: %s\n", prd.capacity, show(hp).c_str());
  // Rigid-block kinematics: with the same hinges, the hinge openings at the same d agree (they
  // do not if the springing joint slips under the support's start-up shock).
  const double d_mid = 15 * c.motion.step;
  for (const RunResult* r : {&dem, &prd}) ASSERT_GT(r->steps.size(), 16u);
  ASSERT_NEAR(dem.steps[15].d, d_mid, 1e-12);
  ASSERT_NEAR(prd.steps[15].d, d_mid, 1e-12);
  for (const OpenCorner& op : prd.steps[15].open_corners) {
    if (hd != hp) break;  // mirrored hinges open mirrored corners
    double gap = 0;
    for (const OpenCorner& od : dem.steps[15].open_corners)
      if (od.joint == op.joint && od.corner == op.corner) gap = od.gap;
    EXPECT_NEAR(gap, op.gap, 0.05 * op.gap) << "joint " << op.joint << " corner " << op.corner;
  }
  const int nb = static_cast<int>(c.blocks.size());
  EXPECT_TRUE(hd == hp || mirror(hd, nb) == hp) << "DEM " << show(hd) << " PRD " << show(hp);
}

}  // namespace
