// Stability at the extremes: joint stiffnesses from 1e6 to 1e13 Pa/m, friction angles from 5 to
// 90 degrees, a mass ratio of 1e4 between neighbouring blocks, time-step factors at and beyond
// the stability bound. Every run ends in a result that statics confirms or in a one-line refusal:
// never NaN, never a hang (every hold has a cycle budget), never a blow-up recorded as a result.
// Hold budgets are a fixed number of the slowest natural periods, so the cycle counts (and the
// run time of this suite) do not grow with the stiffness.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dem/dem.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

constexpr double kDeg = M_PI / 180;
constexpr double kWidth = 0.4, kHeight = 0.2, kJointArea = kWidth * 1.0;  // m, m, m^2 (depth 1 m)

// Blocks of the given densities stacked from the slab up (block k spans y in [0.2 k, 0.2 (k+1)]).
Case stack(const std::vector<double>& densities, double kn) {
  Case c = test::slab_case();
  for (size_t k = 0; k < densities.size(); ++k) {
    std::string id = "b";
    id += std::to_string(k);
    c.blocks.push_back(test::rect(id, -kWidth / 2, kHeight * k, kWidth / 2, kHeight * (k + 1), densities[k], false));
  }
  c.dem.kn = kn;
  c.dem.ks = 0.4 * kn;
  return c;
}

// Enough model time for `periods` of the slowest vertical oscillation (heaviest block on one
// joint's normal spring): the settling time of a damped oscillator in periods does not depend on
// the stiffness.
double periods_of(const Case& c, double periods) {
  double m_max = 0;
  for (const Block& b : c.blocks)
    if (!b.support) m_max = std::max(m_max, block_mass(b));
  return periods * 2 * M_PI * std::sqrt(m_max / (*c.dem.kn * kJointArea));
}

// Every number of a run's results is finite (the JSON writer would turn a NaN into null).
void expect_all_finite(const nlohmann::ordered_json& j, const std::string& where = "") {
  if (j.is_number()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
  } else if (j.is_structured()) {
    for (auto it = j.begin(); it != j.end(); ++it) expect_all_finite(*it, where + "/" + (j.is_object() ? it.key() : "[]"));
  }
}

// The settled step 0 of a stack: reactions carry the weight (and any horizontal load), each
// joint's closure is the weight above it over kn A.
void expect_statics(const Case& c, const RunResult& r, double rel) {
  ASSERT_FALSE(r.steps.empty()) << r.message;
  const StepRecord& st = r.steps[0];
  ASSERT_TRUE(st.settled.value_or(false)) << "unbalanced " << (st.hold ? st.hold->unbalanced_ratio : -1.0) << ", " << r.message;
  double W = 0, Fx = 0;
  for (const Load& l : c.loads) Fx += l.force.x();
  for (const Block& b : c.blocks) W += block_mass(b) * c.gravity;
  ASSERT_EQ(st.reactions.size(), 1u);
  EXPECT_NEAR(st.reactions[0].force.y(), W, rel * W);
  EXPECT_NEAR(st.reactions[0].force.x(), -Fx, rel * W + 1e-9 * W);
  // Joint k closes by the weight above it over kn A; the drops add up from the slab.
  const size_t n = c.blocks.size() - 1;
  double drop = 0;
  for (size_t k = 0; k < n; ++k) {
    double above = 0;
    for (size_t i = k; i < n; ++i) above += block_mass(c.blocks[1 + i]) * c.gravity;
    drop += above / (*c.dem.kn * kJointArea);
    const Pose& p = st.poses[1 + k];
    EXPECT_NEAR(kHeight * k + kHeight / 2 - p.y, drop, rel * drop) << "block " << k << ", kn " << *c.dem.kn;
  }
}

TEST(DemExtremes, StiffnessFrom1e6To1e13PaPerM) {
  for (const double kn : {1e6, 1e8, 1e10, 1e13}) {
    Case c = stack({2000, 2000, 2000}, kn);
    c.dem.hold_time = periods_of(c, 40);
    // At 1e6 Pa/m the top block settles by 2.4 cm, as much as the default collapse drift (2% of
    // the 1.2 m scene): a soft scene needs a larger one, or its settling reads as a collapse.
    c.dem.collapse_drift = 0.1;
    const RunResult r = dem_run(c, DemSettings::from_case(c));
    SCOPED_TRACE("kn " + std::to_string(kn));
    EXPECT_EQ(r.status, RunStatus::max_steps) << r.message;
    expect_statics(c, r, 2e-3);
    // The overlap at 1e13 Pa/m is 1e-9 m, three orders above the resolution of the positions.
    expect_all_finite(to_json(r, c));
  }
}

// A block on a slab that tilts one degree per increment (test::tilt_case): it slides when the
// tilt reaches phi if tan(phi) < b/h, and topples at atan(b/h) otherwise; phi = 90 degrees is no
// slip limit at all.
RunResult tilt(double b, double h, double phi_deg) { return test::tilt_run(test::tilt_case(b, h, phi_deg)); }

TEST(DemExtremes, FrictionFrom5To90Degrees) {
  struct Row {
    double b, h, phi, expected;  // expected limit tilt, degrees
    bool slides;
  };
  const double topple = std::atan(2.0) / kDeg;  // b/h = 2: 63.43 degrees
  for (const Row& row : {Row{0.4, 0.2, 5.5, 5.5, true}, Row{0.4, 0.2, 60.5, 60.5, true}, Row{0.4, 0.2, 90, topple, false}}) {
    SCOPED_TRACE("phi " + std::to_string(row.phi));
    const RunResult r = tilt(row.b, row.h, row.phi);
    ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
    const double cap = r.capacity / kDeg;
    // The equilibrium criterion admits an unbalanced force or moment of equilibrium_tolerance x W,
    // so a state a hair beyond the limit tilt may count as settled: by tol cos(phi) rad for
    // sliding (the slope force W (sin t - cos t tan phi) grows at W / cos phi per radian), and by
    // tol r / L for toppling (the moment about the centroid, W L sin t, over r W; L from the
    // centroid to the corner, r the radius of gyration).
    const double tol = DemSettings::from_case(test::tilt_case(row.b, row.h, row.phi)).equilibrium_tolerance;
    const double L = 0.5 * std::hypot(row.b, row.h), rg = std::sqrt((row.b * row.b + row.h * row.h) / 12);
    const double admitted = (row.slides ? tol * std::cos(row.phi * kDeg) : tol * rg / L) / kDeg;
    EXPECT_LE(cap, row.expected + admitted);
    EXPECT_GT(cap, row.expected - 1.0);
    const StepRecord& last = r.steps.back();
    if (row.slides) {
      EXPECT_NEAR(last.poses[1].angle, last.d, 0.02);  // still flat on the slab
    } else {
      EXPECT_GT(std::abs(last.poses[1].angle - last.d), 0.05);  // turned over its corner
    }
  }
}

TEST(DemExtremes, MassRatio1e4BetweenNeighbours) {
  // Heavy on light and light on heavy, at the default factor and at the bound itself: the bound
  // takes the lightest block, so the heavy one needs many cycles per period but nothing blows up.
  for (const bool heavy_on_top : {true, false})
    for (const double factor : {0.2, 1.0}) {
      Case c = heavy_on_top ? stack({0.2, 2000}, 1e8) : stack({2000, 0.2}, 1e8);
      c.dem.timestep_factor = factor;
      c.dem.hold_time = periods_of(c, 40);
      SCOPED_TRACE(std::string(heavy_on_top ? "heavy on light" : "light on heavy") + ", factor " + std::to_string(factor));
      const RunResult r = dem_run(c, DemSettings::from_case(c));
      EXPECT_EQ(r.status, RunStatus::max_steps) << r.message;
      expect_statics(c, r, 2e-3);
      expect_all_finite(to_json(r, c));
    }
}

TEST(DemExtremes, TimeStepFactorsAtAndBeyondTheBound) {
  // At the bound: the stack settles to its statics.
  Case c = stack({2000, 2000, 2000}, 1e8);
  c.dem.timestep_factor = 1.0;
  c.dem.hold_time = periods_of(c, 40);
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  expect_statics(c, r, 2e-3);
  // Beyond it (and outside (0, 1] at all): refused before any cycle, in one line.
  for (const double factor : {1.0 + 1e-12, 1.5, 100.0, 0.0, -0.2, std::nan(""), HUGE_VAL}) {
    c.dem.timestep_factor = factor;
    SCOPED_TRACE("factor " + std::to_string(factor));
    try {
      DemModel m(c, DemSettings::from_case(c));
      ADD_FAILURE() << "accepted";
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("outside (0, 1]"), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
}

TEST(DemExtremes, NonsenseSettingsAreRefused) {
  const Case c = stack({2000}, 1e8);
  auto refused = [&](const DemSettings& s, const std::string& what) {
    try {
      dem_run(c, s);
      ADD_FAILURE() << what << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(c.source + ": ", 0), 0u) << e.what();  // names the file
    }
  };
  DemSettings s = DemSettings::from_case(c);
  s.kn = -1e8;
  refused(s, "field 'kn' = -1e+08 is outside (0,");
  s = DemSettings::from_case(c);
  s.hold_time = INFINITY;
  refused(s, "field 'hold_time'");
  s = DemSettings::from_case(c);
  s.friction_angle = 91;
  refused(s, "field 'friction_angle' = 91");
  s = DemSettings::from_case(c);
  s.young_modulus = NAN;
  refused(s, "field 'young_modulus'");
}

TEST(DemExtremes, BlowUpStopsTheRunInsteadOfBeingRecorded) {
  // Far beyond the bound (only possible through the test switch) the integration diverges; the
  // run's energy guard stops it with an error, and nothing non-finite reaches the results.
  for (const double factor : {3.0, 30.0}) {
    Case c = stack({2000, 2000, 2000}, 1e8);
    c.dem.timestep_factor = factor;
    c.dem.hold_time = 2.0;
    DemSettings s = DemSettings::from_case(c);
    s.allow_unstable_timestep = true;
    const RunResult r = dem_run(c, s);
    SCOPED_TRACE("factor " + std::to_string(factor));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_TRUE(r.message.find("blew up") != std::string::npos || r.message.find("non-finite") != std::string::npos) << r.message;
    EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
    EXPECT_TRUE(r.steps.empty());  // step 0 never finished
    expect_all_finite(to_json(r, c));
  }
}

TEST(DemExtremes, EveryCornerEndsInAResultOrARefusal) {
  // The corners of the ranges together: stiffness, friction, mass ratio (a neighbour 1e4 times
  // lighter, above or below), factor at the bound or beyond. A horizontal dead load of 5% of the
  // top block's weight stays below the friction limit even at 5 degrees (tan 5 = 0.087), so each
  // accepted run must settle to statics; each factor beyond the bound must be refused.
  for (const double kn : {1e6, 1e13})
    for (const double phi : {5.0, 90.0})
      for (const bool heavy_on_top : {true, false})
        for (const double factor : {1.0, 1.5}) {
          Case c = heavy_on_top ? stack({0.2, 2000}, kn) : stack({2000, 0.2}, kn);
          c.dem.friction_angle = phi;
          c.dem.timestep_factor = factor;
          c.dem.hold_time = periods_of(c, 40);
          const Block& top = c.blocks.back();
          Load l;
          l.block = static_cast<int>(c.blocks.size()) - 1;
          l.force = Vec2(0.05 * block_mass(top) * c.gravity, 0);
          l.point = centroid(top.vertices);
          c.loads.push_back(l);
          SCOPED_TRACE("kn " + std::to_string(kn) + " phi " + std::to_string(phi) + (heavy_on_top ? " heavy on light" : " light on heavy") +
                       " factor " + std::to_string(factor));
          if (factor > 1) {
            EXPECT_THROW(dem_run(c, DemSettings::from_case(c)), std::runtime_error);
            continue;
          }
          const RunResult r = dem_run(c, DemSettings::from_case(c));
          expect_all_finite(to_json(r, c));
          // Round-off floor of the equilibrium check: a joint's force is kn A times an overlap
          // resolved to one ulp of the block heights, against the lightest block's weight. At
          // 1e13 Pa/m with a 0.016 kg block that is ~1e-3, above the 1e-4 tolerance: equilibrium
          // cannot be recognised in double precision, and the run must say so, not go on: the
          // hold neither settles nor runs away, so the run is undecided, without a capacity.
          const double floor = kn * kJointArea * std::nextafter(0.4, 1.0) - kn * kJointArea * 0.4;
          const double w_light = block_mass(c.blocks[heavy_on_top ? 1 : 2]) * c.gravity;
          if (floor / w_light > 0.5 * c.dem.equilibrium_tolerance) {
            EXPECT_EQ(r.status, RunStatus::undecided);
            EXPECT_NE(r.message.find("neither settled nor ran away"), std::string::npos) << r.message;
            EXPECT_EQ(r.stable_steps, 0);
            continue;
          }
          EXPECT_EQ(r.status, RunStatus::max_steps) << r.message;
          // The load adds its own (small) closure gradient across the joint, not its mean: the
          // centroid drops check stays within the same tolerance.
          expect_statics(c, r, 5e-3);
        }
}

}  // namespace
