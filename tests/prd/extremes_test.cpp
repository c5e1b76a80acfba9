// PRD where the numerics get hard: steps over four decades of the scene size, tolerances over five, geometry
// scaled by 0.01 and 100, blocks with aspect ratios of 100. Expected values are invariances
// (the capacity in units of the scene, within one step) and closed forms (atan(b/h)).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "cases/generators.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

RunResult arch(double scale, double step_over_size, double tol_over_size = 1e-5) {
  CircularArch a;
  a.radius = scale;
  a.thickness = 0.15 * scale;
  a.voussoirs = 20;
  a.step = step_over_size * 2 * scale;  // the span is the scene size
  a.max_steps = 1000000;
  Case c = circular_arch(a);
  c.prd.contact_tolerance = tol_over_size * scale;
  return prd_run(c, PrdSettings::from_case(c));
}

TEST(PrdExtremes, StepsFromOneHundredThousandthToOneTwentiethOfTheScene) {
  const RunResult fine = arch(1.0, 1e-5);
  ASSERT_EQ(fine.status, RunStatus::collapse) << fine.message;
  for (double s : {1e-4, 1e-3, 1e-2, 5e-2}) {
    const RunResult r = arch(1.0, s);
    EXPECT_EQ(r.status, RunStatus::collapse) << s << ": " << r.message;
    // A coarser step can only stop earlier, by less than one of its steps.
    EXPECT_LE(r.capacity, fine.capacity + 1e-12) << s;
    EXPECT_GT(r.capacity, fine.capacity - 2 * s) << s;  // one step is 2 s (span 2)
  }
  // And the finest step agrees with the next one to a tenth of the coarser step.
  const RunResult next = arch(1.0, 1e-4);
  EXPECT_NEAR(next.capacity, fine.capacity, 2e-4 + 1e-12);
}

TEST(PrdExtremes, SceneScaledByOneHundredthAndOneHundred) {
  const RunResult unit = arch(1.0, 1e-3);
  for (double scale : {0.01, 100.0}) {
    const RunResult r = arch(scale, 1e-3);
    EXPECT_EQ(r.status, RunStatus::collapse) << scale;
    EXPECT_EQ(r.stable_steps, unit.stable_steps) << scale;
    EXPECT_NEAR(r.capacity / scale, unit.capacity, 1e-9) << scale;
  }
}

TEST(PrdExtremes, ToleranceOverFiveDecades) {
  const RunResult ref = arch(1.0, 5e-4);
  for (double tol : {1e-7, 1e-6, 1e-4, 1e-3}) {
    const RunResult r = arch(1.0, 5e-4, tol);
    EXPECT_EQ(r.status, RunStatus::collapse) << tol;
    EXPECT_NEAR(r.capacity, ref.capacity, 0.02 * ref.capacity) << tol;
  }
}

TEST(PrdExtremes, ArchesWithinOnePercentOfTheirMinimumThickness) {
  // Bracket the minimum thickness of the 20-voussoir semicircle, then check 1% either side.
  auto stable = [](double t) {
    CircularArch a;
    a.thickness = t;
    a.spreading = false;
    return prd_check(circular_arch(a), 1e-6).stable;
  };
  double lo = 0.09, hi = 0.13;
  while (hi - lo > 1e-6) (stable(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  EXPECT_TRUE(stable(1.01 * hi));
  EXPECT_FALSE(stable(0.99 * lo));
  // A spreading arch 1% above its minimum thickness has a small but finite capacity.
  CircularArch a;
  a.thickness = 1.01 * hi;
  a.step = 1e-5;
  a.max_steps = 100000;
  const RunResult r = prd_run(circular_arch(a), PrdSettings::from_case(circular_arch(a)));
  EXPECT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_GT(r.capacity, 0.0);
  EXPECT_LT(r.capacity, 0.05);
}

TEST(PrdExtremes, BlocksWithAspectRatioOfOneHundred) {
  struct Shape {
    double b, h, step;
  };
  for (const Shape& s : {Shape{0.01, 1.0, 1e-5}, Shape{1.0, 0.01, 1e-3}, Shape{0.1, 10.0, 1e-5}}) {
    char json[1024];
    std::snprintf(json, sizeof json,
                  R"({"format": "masonry-case/1", "blocks": [{"id": "g", "vertices": [[-20, -1], [20, -1], [20, 0], [-20, 0]], "support": true},
                     {"id": "b", "vertices": [[0, 0], [%.17g, 0], [%.17g, %.17g], [0, %.17g]], "density": 2000}],
                     "motion": {"step": %.17g, "max_steps": 2000000,
                                "supports": [{"block": "g", "rotation": 1.0, "about": [-20, -1]}]}})",
                  s.b, s.b, s.h, s.h, s.step);
    const Case c = parse_case(json, "slender.json");
    const RunResult r = prd_run(c, PrdSettings::from_case(c));
    EXPECT_EQ(r.status, RunStatus::collapse) << s.b << "x" << s.h;
    EXPECT_LE(r.capacity, std::atan(s.b / s.h)) << s.b << "x" << s.h;
    EXPECT_GT(r.capacity, std::atan(s.b / s.h) - s.step) << s.b << "x" << s.h;
  }
}

// The event-driven run at the same extremes: scaled geometry gives the scaled capacity (its
// tolerance and longest move scale with the scene), event tolerances over three decades agree
// with the finest fixed run within each tolerance, and a block of aspect ratio 100 tips
// within the tolerance of atan(b/h).
TEST(PrdExtremes, AdaptiveRunsScaleKeepTheirToleranceAndTip) {
  auto adaptive_arch = [](double scale, double event_over_size) {
    CircularArch a;
    a.radius = scale;
    a.thickness = 0.15 * scale;
    a.voussoirs = 20;
    a.step = 1e-3 * 2 * scale;
    a.max_steps = 1000000;
    Case c = circular_arch(a);
    c.prd.contact_tolerance = 1e-5 * scale;
    c.prd.adaptive = true;
    c.prd.event_tolerance = event_over_size * 2 * scale;
    return prd_run(c, PrdSettings::from_case(c));
  };
  const RunResult unit = adaptive_arch(1.0, 1e-4);
  ASSERT_EQ(unit.status, RunStatus::collapse) << unit.message;
  for (double scale : {0.01, 100.0}) {
    const RunResult r = adaptive_arch(scale, 1e-4);
    EXPECT_EQ(r.status, RunStatus::collapse) << scale;
    EXPECT_NEAR(r.capacity / scale, unit.capacity, 1e-6 * unit.capacity) << scale;
  }
  const RunResult fine = arch(1.0, 1e-5);
  for (double tol : {1e-5, 1e-4, 1e-3}) {
    const RunResult r = adaptive_arch(1.0, tol);
    EXPECT_EQ(r.status, RunStatus::collapse) << tol << ": " << r.message;
    // Within the tolerance and the fine run's own step (2e-5).
    EXPECT_NEAR(r.capacity, fine.capacity, 2 * tol + 2e-5) << tol;
  }

  const Case c =
      parse_case(R"({"format": "masonry-case/1", "blocks": [{"id": "g", "vertices": [[-20, -1], [20, -1], [20, 0], [-20, 0]], "support": true},
      {"id": "b", "vertices": [[0, 0], [0.01, 0], [0.01, 1], [0, 1]], "density": 2000}],
      "motion": {"step": 1e-3, "max_steps": 1000, "supports": [{"block": "g", "rotation": 1.0, "about": [-20, -1]}]},
      "prd": {"adaptive": true, "event_tolerance": 1e-6}})",
                 "slender.json");
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  EXPECT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_LE(r.capacity, std::atan(0.01) + 1e-12);
  EXPECT_GT(r.capacity, std::atan(0.01) - 1e-6);
  EXPECT_LT(r.timing.lp_solves, 40);
}

// A case no loader would pass (coordinates of 1e119 m), built in code: GLPK cannot scale its LP
// and fails an internal assertion. That is the run's error, one line naming GLPK, and nothing
// else's: the process goes on, a run beside it on another thread finishes, and GLPK solves
// again on the thread that failed (prd/README.md, "GLPK's internal errors are the run's error").
Case huge_case() {
  Case c;
  c.source = c.name = "huge";
  Block g, b;
  g.id = "ground";
  g.support = true;
  g.vertices = {Vec2(-6e119, -1e119), Vec2(6e119, -1e119), Vec2(6e119, 0), Vec2(-6e119, 0)};
  b.id = "block";
  b.density = 2000;
  b.vertices = {Vec2(-1e119, 0), Vec2(1e119, 0), Vec2(1e119, 4e119), Vec2(-1e119, 4e119)};
  c.blocks = {g, b};
  SupportMotion m;
  m.block = 0;
  m.rotation = 1.0;
  m.about = Vec2(0, -5e118);
  c.motion.supports = {m};
  c.motion.step = 0.0174533;
  c.motion.max_steps = 60;
  return c;
}

TEST(PrdExtremes, GlpkInternalErrorIsTheRunsErrorAndNothingElses) {
  // The tilting block of the standard cases: it topples at atan(b/h), b/h = 0.2 / 0.4.
  const Case tilt = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  RunResult beside;
  std::thread other([&] { beside = prd_run(tilt, PrdSettings::from_case(tilt)); });
  const Case c = huge_case();
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  other.join();
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("the LP solver (GLPK) stopped on an internal error"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
  EXPECT_EQ(beside.status, RunStatus::collapse) << beside.message;
  EXPECT_LE(beside.capacity, std::atan(0.5));
  EXPECT_GT(beside.capacity, std::atan(0.5) - tilt.motion.step);
  const RunResult again = prd_run(tilt, PrdSettings::from_case(tilt));
  EXPECT_EQ(again.status, RunStatus::collapse) << again.message;
  EXPECT_EQ(again.capacity, beside.capacity);
}

}  // namespace
}  // namespace masonry
