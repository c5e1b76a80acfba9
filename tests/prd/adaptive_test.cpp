// Event-driven PRD (`prd --adaptive`): long steps while the mechanism holds, each event located
// to the event tolerance. Expected values come from closed forms (the tipping angle) and from
// fixed-step runs at a quarter of the case's step, never from an adaptive run itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "model/case.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

Case standard(const std::string& name) { return load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

PrdSettings adaptive(const Case& c) {
  PrdSettings s = PrdSettings::from_case(c);
  s.adaptive = true;
  return s;
}

PrdSettings quarter_step(const Case& c) {
  PrdSettings s = PrdSettings::from_case(c);
  s.step /= 4;
  s.max_steps *= 4;
  return s;
}

double event_tolerance(const RunResult& r) { return r.settings["event_tolerance"].get<double>(); }

// A block on a tilting ground (1 rad of tilt per m of d) topples at atan(b/h): the adaptive run
// finds it within the event tolerance, with steps far longer than that tolerance.
TEST(PrdAdaptive, TipsWithinTheEventToleranceOfTheClosedForm) {
  const std::string json = R"({"format": "masonry-case/1", "name": "tilting block",
    "blocks": [
      {"id": "ground", "vertices": [[-2, -0.5], [2, -0.5], [2, 0], [-2, 0]], "support": true},
      {"id": "block", "vertices": [[0, 0], [0.5, 0], [0.5, 1], [0, 1]], "density": 2000}],
    "motion": {"step": 0.01, "max_steps": 200, "supports": [{"block": "ground", "rotation": 1.0, "about": [-2, -0.5]}]},
    "prd": {"adaptive": true, "event_tolerance": 1e-5, "max_step": 0.16}})";
  const Case c = parse_case(json, "tilting-block.json");
  const RunResult r = prd_run(c, PrdSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double critical = std::atan(0.5);
  EXPECT_LE(r.capacity, critical + 1e-9);
  EXPECT_GT(r.capacity, critical - 1e-5);
  // A fixed run at the tolerance would take 46000 LPs; bisection of a 0.16 rad step needs ~15.
  EXPECT_LT(r.timing.lp_solves, 60);
  const std::vector<Event>& ev = r.events.value();
  ASSERT_FALSE(ev.empty());
  EXPECT_EQ(ev.back().kind, EventKind::collapse);
  EXPECT_LE(ev.back().within, 1e-5 * (1 + 1e-6));
  // The collapse event names the corner the toppling opens (the block turns about one end of
  // its only joint, the other lifts), the collapse mechanism's (it was empty).
  ASSERT_TRUE(r.collapse);
  ASSERT_EQ(ev.back().corners.size(), 1u);
  ASSERT_EQ(r.collapse->mechanism.open_corners.size(), 1u);
  EXPECT_EQ(ev.back().corners[0].joint, r.collapse->mechanism.open_corners[0].joint);
  EXPECT_EQ(ev.back().corners[0].corner, r.collapse->mechanism.open_corners[0].corner);
}

// The issue's acceptance test: the capacity agrees with a fixed-step run at a quarter of the
// default step within the event tolerance, and every event is located within it.
void expect_agrees_with_quarter_step(const std::string& name) {
  const Case c = standard(name);
  const RunResult a = prd_run(c, adaptive(c));
  const RunResult q = prd_run(c, quarter_step(c));
  ASSERT_EQ(a.status, RunStatus::collapse) << a.message;
  ASSERT_EQ(q.status, RunStatus::collapse) << q.message;
  const double tol = event_tolerance(a);
  EXPECT_NEAR(a.capacity, q.capacity, tol) << name;
  for (const Event& e : a.events.value()) {
    EXPECT_LE(e.within, tol * (1 + 1e-6)) << name << ": " << event_kind_name(e.kind) << " at " << e.d;
    if (e.kind != EventKind::collapse) {
      EXPECT_FALSE(e.corners.empty()) << event_kind_name(e.kind) << " at " << e.d;
    }
  }
  // Every adaptive record is a configuration in equilibrium the LP accepted: d increases.
  for (size_t k = 1; k < a.steps.size(); ++k) EXPECT_GT(a.steps[k].d, a.steps[k - 1].d);
}

TEST(PrdAdaptive, PointedArchAgreesWithAQuarterStepRun) { expect_agrees_with_quarter_step("pointed-arch"); }
TEST(PrdAdaptive, CathedralAgreesWithAQuarterStepRun) { expect_agrees_with_quarter_step("cathedral-settlement"); }
TEST(PrdAdaptive, CathedralRotationAgreesWithAQuarterStepRun) { expect_agrees_with_quarter_step("cathedral-settlement-rotation"); }

// The arch has three mechanisms (three hinges at the start, the haunch hinge moving once,
// collapse): the adaptive run needs at least three times fewer LPs than the fixed 1 mm run.
TEST(PrdAdaptive, PointedArchNeedsThreeTimesFewerLps) {
  const Case c = standard("pointed-arch");
  const RunResult a = prd_run(c, adaptive(c));
  const RunResult f = prd_run(c, PrdSettings::from_case(c));
  EXPECT_LE(3 * a.timing.lp_solves, f.timing.lp_solves) << a.timing.lp_solves << " vs " << f.timing.lp_solves;
}

// The cathedral changes mechanism 21 times before collapse (a fixed run at a sixteenth of its
// step sees them at 17 distinct d): at least three times fewer LPs than the fixed 1 cm run
// all the same, with the predictions' basis evaluations counted apart.
TEST(PrdAdaptive, CathedralNeedsThreeTimesFewerLps) {
  const Case c = standard("cathedral-settlement");
  const RunResult a = prd_run(c, adaptive(c));
  const RunResult f = prd_run(c, PrdSettings::from_case(c));
  EXPECT_LE(3 * a.timing.lp_solves, f.timing.lp_solves) << a.timing.lp_solves << " vs " << f.timing.lp_solves;
  EXPECT_GT(a.timing.basis_evaluations, 0);
  EXPECT_EQ(f.timing.basis_evaluations, 0);
}

// Long moves follow the mechanism's change along the way, so they stay on the path of short
// ones: halving the longest move leaves the capacity within the event tolerance.
TEST(PrdAdaptive, HalvingTheLongestMoveKeepsTheCapacity) {
  for (const char* name : {"pointed-arch", "cathedral-settlement"}) {
    const Case c = standard(name);
    PrdSettings s = adaptive(c);
    const RunResult a = prd_run(c, s);
    s.max_step = a.settings["max_step"].get<double>() / 2;
    const RunResult b = prd_run(c, s);
    ASSERT_EQ(a.status, RunStatus::collapse) << a.message;
    ASSERT_EQ(b.status, RunStatus::collapse) << b.message;
    EXPECT_NEAR(a.capacity, b.capacity, event_tolerance(a)) << name;
    EXPECT_LT(a.timing.lp_solves, b.timing.lp_solves) << name;
  }
}

// The events of the fixed run at a quarter step, as d where its open set changes, are the
// adaptive run's events: same count, each within the quarter step plus the tolerance.
TEST(PrdAdaptive, PointedArchEventsMatchTheFixedRunsMechanismChanges) {
  const Case c = standard("pointed-arch");
  const RunResult a = prd_run(c, adaptive(c));
  const RunResult q = prd_run(c, quarter_step(c));
  std::vector<double> opens_a, opens_q;
  for (const Event& e : a.events.value())
    if (e.kind == EventKind::open) opens_a.push_back(e.d);
  for (const Event& e : q.events.value())
    if (e.kind == EventKind::open) opens_q.push_back(e.d);
  ASSERT_EQ(opens_a.size(), opens_q.size());
  const double h = quarter_step(c).step, tol = event_tolerance(a);
  for (size_t k = 0; k < opens_a.size(); ++k) EXPECT_NEAR(opens_a[k], opens_q[k], h + tol) << k;
}

TEST(PrdAdaptive, FixedRunsAreUnchangedByTheEventMachinery) {
  // In a fixed run every step is one increment: d_k = k * step exactly, events within a step.
  const Case c = standard("pointed-arch");
  const RunResult f = prd_run(c, PrdSettings::from_case(c));
  for (size_t k = 0; k < f.steps.size(); ++k) EXPECT_DOUBLE_EQ(f.steps[k].d, k * c.motion.step);
  for (const Event& e : f.events.value()) EXPECT_LE(e.within, c.motion.step * (1 + 1e-12));
}

}  // namespace
}  // namespace masonry
