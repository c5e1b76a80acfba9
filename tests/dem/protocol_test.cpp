// The quasi-static protocol (dem/README.md, "Protocol"): holds end on equilibrium, on evidence
// of collapse, or undecided at the cap (a creeping structure is never called a collapse); the
// collapse is bracketed from the last equilibrium, so the capacity does not move with the
// increment; hinges are measured from the settled state; a restored state replays exactly; and
// a small arch gives one capacity across the settings that must not matter.
#include "dem/protocol.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common.hpp"
#include "compare/convergence.hpp"
#include "dem/dem.hpp"
#include "dem/variants.hpp"
#include "prd/prd.hpp"
#include "runs/parallel.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

constexpr double kDeg = M_PI / 180;

Vec2 turned(const Vec2& p, double a) { return Vec2(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y()); }

// A block resting on a fixed slab inclined by `slope` (rad), with soft joints.
Case incline_case(double slope, double phi_deg) {
  Case c = test::slab_case();
  Block& g = c.blocks[0];
  for (Vec2& v : g.vertices) v = turned(v, slope);
  Block b = test::rect("block", -0.1, 0.0, 0.1, 0.1, 2000, false);
  for (Vec2& v : b.vertices) v = turned(v, slope);
  c.blocks.push_back(b);
  c.dem.friction_angle = phi_deg;
  return c;
}

dem::Limits limits(double drift, double ke_collapse) {
  dem::Limits l;
  l.collapse_drift = drift;
  l.energy_floor = 1e-9;
  l.ke_collapse = ke_collapse;
  return l;
}

// A block sliding down a slope steeper than its friction angle has no equilibrium: the hold
// ends as a collapse (energy growing), long before the cap.
TEST(DemHold, RunawayIsCollapse) {
  const Case c = incline_case(20 * kDeg, 10);
  DemSettings s = DemSettings::from_case(c);
  DemModel m(c, s);
  const dem::HoldOutcome h = dem::hold(m, c, s, limits(0.05, 1e-6));
  EXPECT_EQ(h.end, dem::HoldEnd::collapse);
  EXPECT_LT(h.time, 0.5 * s.hold_time);
}

// With damping 0.9999 a block on soft joints creeps down onto its 4 mm of elastic overlap, taking
// many of its natural periods: the hold waits (the kinetic energy stays far below what a runaway
// reaches, the threshold dem_run sets for a 1 cm increment) and ends in equilibrium; with a cap
// too short for the creep, it is undecided, never a collapse. Local damping takes its share of
// the unbalanced force every cycle, so how long the creep lasts in model time goes with the
// cycles per second: the time step is pinned at the factor these durations were set with.
TEST(DemHold, CreepTowardsEquilibriumIsNotCollapse) {
  Case c = incline_case(0.0, 35);
  c.dem.kn = 1e6;
  c.dem.ks = 4e5;
  c.dem.damping = 0.9999;
  c.dem.timestep_factor = 0.8;
  DemSettings s = DemSettings::from_case(c);
  const double W = 2000 * 0.2 * 0.1 * c.gravity, mass = W / c.gravity;
  const double overlap = W / (1e6 * 0.2);                          // W / (kn A)
  const double period = 2 * M_PI * std::sqrt(mass / (1e6 * 0.2));  // of the block on its bed
  const double ke_collapse = 10 * s.kinetic_ratio * W * 0.01;
  {
    DemModel m(c, s);
    const dem::HoldOutcome h = dem::hold(m, c, s, limits(0.05, ke_collapse));
    EXPECT_EQ(h.end, dem::HoldEnd::equilibrium) << dem::hold_end_name(h.end) << " after " << h.time << " s";
    EXPECT_GT(h.time, 10 * period);  // it did creep
    EXPECT_NEAR(h.drift, overlap, 0.01 * overlap);
  }
  {
    s.hold_time = 2 * period;
    DemModel m(c, s);
    const dem::HoldOutcome h = dem::hold(m, c, s, limits(0.05, ke_collapse));
    EXPECT_EQ(h.end, dem::HoldEnd::undecided) << dem::hold_end_name(h.end);
  }
}

// A collapse slower than the cap is a collapse: a block on a slope one degree steeper than its
// friction angle, heavily damped, slides at 0.04 m/s^2 (a fifth of g (sin 36 - cos 36 tan 35));
// with a cap of 1 s it goes 2 cm, less than the collapse drift (5 cm), and the kinetic-energy
// rule is off, but it goes farther in the second half of the cap, or of a window of it (the
// early looks), than in the first: collapse, not undecided, within the cap. (The creeping block
// above never goes a tenth of the collapse drift.)
TEST(DemHold, ACollapseSlowerThanTheCapIsACollapse) {
  const Case c = incline_case(36 * kDeg, 35);
  DemSettings s = DemSettings::from_case(c);
  s.hold_time = 1.0;
  DemModel m(c, s);
  const dem::HoldOutcome h = dem::hold(m, c, s, limits(0.05, INFINITY));
  EXPECT_EQ(h.end, dem::HoldEnd::collapse) << dem::hold_end_name(h.end) << ", drift " << h.drift << " m";
  EXPECT_LT(h.drift, 0.05);
  EXPECT_LE(h.time, s.hold_time + 1e-3);
}

// The cap's rule read early: the same slide with a cap of 8 s and a collapse drift of 0.5 m
// (its tenth, 5 cm, is passed at t = sqrt(0.05 / 0.02) = 1.6 s on x = a t^2 / 2, a = 0.04 m/s^2)
// is called a collapse at the first window of j/16 of the cap (j >= 2) that ends past 1.6 s and
// shows the second half's travel at least the first's: at 2 s, not at the cap.
TEST(DemHold, AFailureSpeedingUpIsCalledBeforeTheCap) {
  const Case c = incline_case(36 * kDeg, 35);
  DemSettings s = DemSettings::from_case(c);
  s.hold_time = 8.0;
  DemModel m(c, s);
  const dem::HoldOutcome h = dem::hold(m, c, s, limits(0.5, INFINITY));
  EXPECT_EQ(h.end, dem::HoldEnd::collapse) << dem::hold_end_name(h.end) << ", drift " << h.drift << " m";
  EXPECT_NEAR(h.time, 2.0, 0.01);
  EXPECT_GT(h.drift, 0.05);
  EXPECT_LT(h.drift, 0.5);
}

// A run whose first settling cannot finish within the cap (and its three extensions) says so:
// undecided, no capacity. (The time step pinned as above.)
TEST(DemHold, UndecidedInitialStateIsNoCapacity) {
  Case c = incline_case(0.0, 35);
  c.dem.kn = 1e6;
  c.dem.ks = 4e5;
  c.dem.damping = 0.9999;
  c.dem.timestep_factor = 0.8;
  c.dem.hold_time = 0.2;
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  EXPECT_EQ(r.status, RunStatus::undecided);
  EXPECT_EQ(r.stable_steps, 0);
  EXPECT_NE(r.message.find("neither settled nor ran away"), std::string::npos) << r.message;
}

// How far past the tipping point of a b x h block (rad of tilt) the equilibrium criterion can
// still call it settled: an unbalanced moment of 1e-4 W r (r the radius of gyration) is a tilt of
// 1e-4 r / (half the diagonal) past it.
double tipping_resolution(double b, double h) { return 1e-4 * std::sqrt((b * b + h * h) / 12) / (0.5 * std::hypot(b, h)); }

// Toppling at atan(b/h) is located within the bracket whatever the increment: 1 and 3 degrees
// both give it within their bracket (1% of the increment) plus twice the equilibrium
// tolerance's resolution of the tipping point (tipping_resolution).
TEST(DemBracket, CapacityDoesNotMoveWithTheIncrement) {
  const double b = 0.2, h = 0.4;
  const double topple = std::atan(b / h);
  const double resolution = tipping_resolution(b, h);
  double caps[2];
  int k = 0;
  for (const double step_deg : {1.0, 3.0}) {
    Case c = test::tilt_case(b, h, 45);
    // Stiff joints: the toe's elastic overlap turns the block by overlap / b before the heel
    // lifts, 0.05 degrees at the test scenes' 1e8 Pa/m (tipping that much early), 0.0005 here.
    c.dem.kn = 1e10;
    c.dem.ks = 4e9;
    c.motion.step = step_deg * kDeg;
    c.motion.max_steps = static_cast<int>(40 / step_deg);
    const RunResult r = test::tilt_run(c);
    ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
    std::printf("step %g deg: capacity %.4f deg, bracket %s\n", step_deg, r.capacity / kDeg,
                r.collapse_bracket ? std::to_string(r.collapse_bracket->width).c_str() : "none");
    ASSERT_TRUE(r.collapse_bracket);
    const double width = r.collapse_bracket->width;
    EXPECT_LE(width, c.dem.bracket_fraction * c.motion.step * (1 + 1e-9));
    EXPECT_NEAR(r.capacity, topple, c.dem.bracket_fraction * c.motion.step + 2 * resolution) << "step " << step_deg;
    // The record closes on the failed state just past the capacity, the equilibria before it.
    EXPECT_FALSE(r.steps.back().settled.value_or(true));
    for (size_t i = 1; i + 1 < r.steps.size(); ++i) EXPECT_GT(r.steps[i].d, r.steps[i - 1].d);
    caps[k++] = r.capacity;
  }
  EXPECT_NEAR(caps[0], caps[1], 0.03 * kDeg + 2 * resolution);
}

// A failure that only a long move produces is not the capacity. Supports that tilt the slab by 5
// degrees in 5 ms and stop dead (the constant-speed protocol without ramps) throw the block into
// rocking that tips it over at a few degrees of tilt, far below atan(b/h). Every bisection trial
// below settles, so the failure sits on the increment grid; the short move that confirms it
// from the last equilibrium settles too, and the run goes on, to topple at atan(b/h) (no
// friction limit: phi = 90).
TEST(DemBracket, AFailureThatAShortMoveDoesNotReproduceIsNotTheCapacity) {
  const double b = 0.2, h = 0.4;
  const double topple = std::atan(b / h);
  const double resolution = tipping_resolution(b, h);
  Case c = test::tilt_case(b, h, 90);
  c.dem.kn = 1e10;
  c.dem.ks = 4e9;
  c.dem.move_time = 0.005;
  c.dem.ramp_fraction = 0;
  c.motion.step = 5 * kDeg;
  c.motion.max_steps = 8;
  DemSettings s = DemSettings::from_case(c);
  s.collapse_drift = 0.02;
  s.confirm_collapse = true;
  const RunResult r = dem_run(c, s);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const auto& u = r.unconfirmed_failures;
  ASSERT_FALSE(u.empty());
  // The first failure, from the settled block at 0, at a tilt far below toppling (where the
  // run would have ended before this stage).
  EXPECT_LT(u[0].d, 0.5 * topple);
  EXPECT_NEAR(r.capacity, topple, c.dem.bracket_fraction * c.motion.step + 2 * resolution);
  EXPECT_FALSE(r.steps.back().settled.value_or(true));
  // Without the stage the run ends at that first failure.
  s.confirm_collapse = false;
  const RunResult plain = dem_run(c, s);
  EXPECT_LT(plain.capacity, 0.5 * topple);
}

// At the defaults too: a slender block (b/h = 0.02) on a slab tilting 1 degree per increment.
// The first whole increment's move, from rest at 0, throws it over at 1 degree, while it stands
// to atan(b/h) = 1.146 degrees when tilted gently: every bisection trial below 1 degree settles,
// and without stage 4 the bracket closes on that move's failure, 13% early. With it (the
// default), the short move from the bracket's last equilibrium does not reproduce the failure,
// and the run topples the block at atan(b/h), within the bracket and the equilibrium
// tolerance's resolution of the tipping point.
TEST(DemBracket, ASlenderBlockTopplesAtItsLimitAtTheDefaults) {
  const double b = 0.02, h = 1.0;
  const double topple = std::atan(b / h);
  Case c = test::tilt_case(b, h, 35);
  c.dem.kn.reset();  // the default joints, E / h_block: the slab's 1e8 Pa/m would let the block
  c.dem.ks.reset();  // lean over elastically (rocking stiffness kn b^3 / 12 below W h / 2)
  c.motion.max_steps = 3;
  const DemSettings s = DemSettings::from_case(c);
  ASSERT_TRUE(s.confirm_collapse);
  const RunResult r = dem_run(c, s);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_FALSE(r.unconfirmed_failures.empty());
  EXPECT_NEAR(r.capacity, topple, c.dem.bracket_fraction * c.motion.step + 2 * tipping_resolution(b, h));
  DemSettings plain = s;
  plain.confirm_collapse = false;
  EXPECT_LT(dem_run(c, plain).capacity, 0.95 * topple);
}

// A limit point is a located collapse. A wide block (b/h = 2) on a tilting slab slides when the
// tilt reaches its friction angle, 20.1 degrees, and no sooner (closed form: tan theta =
// tan phi). The slab turns 0.2 degrees per increment, holds are capped at 0.5 s and the
// collapse drift is 0.2 m, so past the limit no trial shows a runaway within its cap: each
// slides slowly on (0.1 degree past, the force along the slope is 0.2% of the weight, and local
// damping 0.8 leaves a fifth of it), nearer the limit ever more slowly. The bracket still closes
// on 20.1 degrees, and its upper end, which creeps without slowing down, locates the limit: the
// run is a collapse, at the friction angle, and says it ended on a limit point.
TEST(DemBracket, ALimitPointIsALocatedCollapse) {
  Case c = test::tilt_case(0.4, 0.2, 20.1);
  c.motion.step = 0.2 * kDeg;
  c.motion.max_steps = 150;
  c.dem.hold_time = 0.5;
  DemSettings s = DemSettings::from_case(c);
  s.collapse_drift = 0.2;  // m: half the block's width; the slide's drift is then far from it
  const RunResult r = dem_run(c, s);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_TRUE(r.limit_point) << r.message;
  EXPECT_NE(r.message.find("limit point"), std::string::npos) << r.message;
  ASSERT_TRUE(r.collapse_bracket);
  for (const BracketTrial& t : r.collapse_bracket->trials) EXPECT_NE(t.end, "collapse") << t.d;
  // Within the bracket, plus the equilibrium tolerance's reach of the friction limit (an
  // unbalanced force of 1e-4 W along the slope is a tilt of 1e-4 / cos^2 20.1 = 1.1e-4 rad).
  EXPECT_NEAR(r.capacity, 20.1 * kDeg, c.dem.bracket_fraction * c.motion.step + 2 * 1.1e-4);
}

// A limit point of one branch is not the capacity where the structure can pass to another. A
// segmental arch (R 1.5 m, t 0.2 m, 120 degrees, 7 voussoirs, a 3 kN load on the second
// voussoir; tests/dem/passing-hinge-arch.json, trial t3's R4 at its density 2000) on a spreading
// support forms three hinges at once; near d = 0.05 m the one between the loaded side's first two
// voussoirs closes while one at the other springing opens (a hinge passing to another joint), a
// finite motion through a mechanism that starts from rest. With holds capped at 1 s it took
// longer than a cap, every bracket trial past it crept, and the run ended on a "limit point" at
// 0.054 m. Held on while it speeds up (dem_run's follow stage), the creep settles on the other
// branch and the run goes on to the arch's collapse: where the default cap (30 s, which outlasts
// the passing) puts it, and PRD (rigid blocks, another method) within 3%.
TEST(DemBracket, AHingePassingToAnotherJointIsNotALimitPoint) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/tests/dem/passing-hinge-arch.json");
  const RunResult full = dem_run(c, DemSettings::from_case(c));
  Case capped = c;
  capped.dem.hold_time = 1;
  const RunResult r = dem_run(capped, DemSettings::from_case(capped));
  ASSERT_EQ(full.status, RunStatus::collapse) << full.message;
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double prd = prd_run(c, PrdSettings::from_case(c)).capacity;
  EXPECT_NEAR(r.capacity, full.capacity, 2 * c.dem.bracket_fraction * c.motion.step + 0.005 * full.capacity);
  EXPECT_NEAR(r.capacity, prd, 0.03 * prd);
}

// A snap through is not a collapse (dem_run's landing stage). Near d = 0.1 m a hinge of the
// pointed arch passes to another joint, a finite motion to another equilibrium: PRD moves a
// block some 9.5 mm in one 1 mm step there, and goes on to 0.28 m. With collapse_drift at 5 mm (a
// quarter of a percent of the scene, where the default is 2%) the DEM's hold at the snap drifts
// past that limit, and the run called a collapse at 0.0975 m. Held on once more, it lands: the
// run goes on to the end of its path, the snap recorded, as long as PRD's jump.
TEST(DemBracket, ASnapLongerThanTheDriftLimitLandsAndTheRunGoesOn) {
  Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  c.motion.max_steps = 110;
  c.dem.collapse_drift = 0.005;
  // PRD's jump: the step whose largest block motion is the largest of the path.
  const RunResult prd = prd_run(c, PrdSettings::from_case(c));
  ASSERT_EQ(prd.status, RunStatus::max_steps) << prd.message;
  double jump = 0, jump_d = 0;
  for (size_t k = 1; k < prd.steps.size(); ++k)
    for (size_t b = 0; b < prd.steps[k].poses.size(); ++b) {
      const Pose &p = prd.steps[k].poses[b], &q = prd.steps[k - 1].poses[b];
      const double move = std::hypot(p.x - q.x, p.y - q.y);
      if (move > jump) jump = move, jump_d = prd.steps[k].d;
    }
  ASSERT_GT(jump, c.dem.collapse_drift);  // the snap is longer than the drift limit: the case tests the stage
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::max_steps) << r.message;
  ASSERT_EQ(r.settled_snaps.size(), 1u);
  const SettledSnap& s = r.settled_snaps[0];
  EXPECT_GT(s.drift, c.dem.collapse_drift);
  EXPECT_NEAR(s.drift, jump, 0.2 * jump);
  EXPECT_NEAR(s.d, jump_d, 0.01);  // the same hinge's passing, within ten steps of PRD's
  EXPECT_LT(s.from, s.d);
  EXPECT_GE(s.from, s.d - c.motion.step);
}

// A fall is not a snap: a part that comes to rest on a face it was not cut against has fallen.
// The toppling block with a post 5 cm beside its downhill face (a second support turning with the
// slab): past atan(b/h) it falls against the post, its centroid 28 mm from where it stood (over
// the 20 mm drift limit, under twice it), and held on it would rest there; the landing stage takes
// no rest that touches outside the case's joints, so the run collapses at atan(b/h), as PRD does
// (the post is no joint of it).
TEST(DemBracket, ABlockFallenAgainstAPostIsACollapseNotALanding) {
  const double b = 0.2, h = 0.4, gap = 0.05;
  Case c = test::tilt_case(b, h, 35);
  c.blocks.insert(c.blocks.begin() + 1, test::rect("post", -b / 2 - gap - 0.05, 0.0, -b / 2 - gap, 0.5, 0.0, true));
  SupportMotion post = c.motion.supports[0];
  post.block = 1;
  c.motion.supports.push_back(post);
  c.motion.max_steps = 40;
  const RunResult r = test::tilt_run(c);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_TRUE(r.settled_snaps.empty());
  // It did come to rest, against the post: the run says so (the landing's trial reads a collapse).
  EXPECT_NE(r.message.find("came to rest when held on, but against post/block"), std::string::npos) << r.message;
  ASSERT_TRUE(r.collapse_bracket);
  EXPECT_TRUE(r.collapse_bracket->trials.back().followed);
  EXPECT_EQ(r.collapse_bracket->trials.back().end, "collapse");
  const double topple = std::atan(b / h);
  EXPECT_LE(r.capacity, topple + 2 * tipping_resolution(b, h));
  EXPECT_GT(r.capacity, topple - 0.1 * kDeg);
  EXPECT_NEAR(prd_run(c, PrdSettings::from_case(c)).capacity, topple, c.motion.step);
}

// A collapse that happens during a move is a collapse. With damping 0.6 and a quarter of the
// default kinetic ratio, the support tilts so slowly that the block topples and lands on its side
// within one move; the hold then found the fallen block at rest and counted it as an equilibrium,
// so the block "stood" until it slid at the friction angle, 35 degrees. A block carried farther
// than collapse_drift plus the support's own travel ends the move as a collapse, at atan(b/h).
TEST(DemBracket, ACollapseDuringAMoveIsACollapse) {
  const double b = 0.2, h = 0.4;
  const double topple = std::atan(b / h);
  const double resolution = tipping_resolution(b, h);
  Case c = test::tilt_case(b, h, 35);
  c.dem.damping = 0.6;
  c.dem.kinetic_ratio = 2.5e-4;
  c.motion.max_steps = 40;
  const RunResult r = test::tilt_run(c);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  // The soft joints of the test scenes let the toe's elastic overlap tip the block early, by
  // overlap / b: 0.07 degrees here (DemBracket.CapacityDoesNotMoveWithTheIncrement).
  EXPECT_LE(r.capacity, topple + 2 * resolution);
  EXPECT_GT(r.capacity, topple - 0.1 * kDeg);
}

// The loading rate follows the blocks that move, not the weight of the whole scene. A block 100
// times heavier than the tilting one, at rest on a fixed slab of its own below the tilting slab
// (inside the scene's bounds, so the support travel per d is the same), changes nothing of the
// tilting block's loading: the first move takes the same cycles and the block topples at the
// same tilt. A servo on the whole scene's kinetic energy over its whole weight let the light
// block move 100 times more energetically beside the heavy one (its first move took 24% fewer
// cycles); on the cathedral that chose the aisle arch's hinge (dem/README.md, "The loading
// rate"). The ratio is a tenth of the default, so that the servo's target binds on this small
// block's moves.
TEST(DemLoading, AHeavyBlockAtRestElsewhereDoesNotSpeedUpTheMove) {
  const double b = 0.2, h = 0.4;
  Case alone = test::tilt_case(b, h, 45);
  alone.dem.kinetic_ratio = 1e-4;
  Case beside = alone;
  beside.blocks.push_back(test::rect("low-slab", -0.6, -0.8, 0.6, -0.7, 0.0, true));
  const double density = 100 * (b * h * 2000) / (1.2 * 0.2);
  beside.blocks.push_back(test::rect("heavy", -0.6, -0.7, 0.6, -0.5, density, false));
  ASSERT_DOUBLE_EQ(scene_size(beside), scene_size(alone));
  const RunResult r0 = test::tilt_run(alone);
  const RunResult r1 = test::tilt_run(beside);
  ASSERT_EQ(r0.status, RunStatus::collapse) << r0.message;
  ASSERT_EQ(r1.status, RunStatus::collapse) << r1.message;
  const double m0 = static_cast<double>(r0.steps.at(1).hold.value().move_cycles);
  const double m1 = static_cast<double>(r1.steps.at(1).hold.value().move_cycles);
  EXPECT_NEAR(m1, m0, 0.02 * m0) << "first move: " << m0 << " cycles alone, " << m1 << " beside the heavy block";
  EXPECT_NEAR(r1.capacity, r0.capacity, alone.dem.bracket_fraction * alone.motion.step + 2 * tipping_resolution(b, h));
}

// The time step is a numerical setting: at half the default time-step factor the supports move
// as they do at the default in model time (the servo's rates are kept per unit of model time),
// so the first move takes the same model time and twice the cycles, and the block topples at
// the same tilt. With the rates per cycle, the move took the same cycles, half the model time.
TEST(DemLoading, TheTimeStepDoesNotChangeTheLoading) {
  const double b = 0.2, h = 0.4;
  Case full = test::tilt_case(b, h, 45);
  Case half = full;
  half.dem.timestep_factor = full.dem.timestep_factor / 2;
  const RunResult r0 = test::tilt_run(full);
  const RunResult r1 = test::tilt_run(half);
  ASSERT_EQ(r0.status, RunStatus::collapse) << r0.message;
  ASSERT_EQ(r1.status, RunStatus::collapse) << r1.message;
  const auto move_time = [](const RunResult& r) {
    return static_cast<double>(r.steps.at(1).hold.value().move_cycles) * r.settings.at("dt").get<double>();
  };
  EXPECT_NEAR(move_time(r1), move_time(r0), 0.05 * move_time(r0));
  // Both topple at atan(b/h), less the soft joints' early tipping (overlap / b, 0.07 degrees:
  // DemBracket.ACollapseDuringAMoveIsACollapse).
  for (const RunResult* r : {&r0, &r1}) {
    EXPECT_LE(r->capacity, std::atan(b / h) + 2 * tipping_resolution(b, h));
    EXPECT_GT(r->capacity, std::atan(b / h) - 0.1 * kDeg);
  }
}

// The bracket goes back to a saved equilibrium: a restored model replays the same cycles bit for
// bit.
TEST(DemModelState, RestoreReplaysExactly) {
  const Case c = test::tilt_case(0.2, 0.4, 35);
  DemModel m(c, DemSettings::from_case(c));
  m.set_support_parameter(0.01);
  m.cycle(500);
  const DemSnapshot snap = m.save();
  m.cycle(700);
  const DemBlockState a = m.block(1);
  m.set_support_parameter(0.3);  // somewhere else entirely
  m.cycle(300);
  m.restore(snap);
  m.cycle(700);
  const DemBlockState b = m.block(1);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.angle, b.angle);
  EXPECT_EQ(a.velocity, b.velocity);
}

// Two blocks side by side on the slab, the right one loaded at its far edge: its bed joint
// compresses unevenly, it turns by about 0.01 rad, and the top of the vertical joint between the
// two opens by some 2 mm, elastically. That gap is the settled state, shown at d = 0; moving the
// slab sideways, which carries both blocks rigidly, opens no hinge.
TEST(DemHinges, SettledGapsAreNotHinges) {
  Case c = test::slab_case();
  c.blocks.push_back(test::rect("left", -0.2, 0.0, 0.0, 0.2, 2000, false));
  c.blocks.push_back(test::rect("right", 0.0, 0.0, 0.2, 0.2, 2000, false));
  c.dem.kn = 1e7;
  c.dem.ks = 4e6;
  const double W = 2000 * 0.2 * 0.2 * c.gravity;
  Load l;
  l.block = 2;
  l.force = Vec2(0, -3 * W);
  l.point = Vec2(0.2, 0.2);
  c.loads.push_back(l);
  SupportMotion sm;
  sm.block = 0;
  sm.translation = Vec2(1, 0);
  sm.about = Vec2(0, -0.05);
  c.motion.supports.push_back(sm);
  c.motion.step = 0.001;
  c.motion.max_steps = 2;
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::max_steps) << r.message;
  ASSERT_EQ(r.steps.size(), 3u);
  // Settled: the top corner of the vertical joint stands open (and nothing else).
  ASSERT_EQ(r.steps[0].open_corners.size(), 1u);
  const OpenCorner& o = r.steps[0].open_corners[0];
  EXPECT_EQ(r.joints[o.joint].i + r.joints[o.joint].j, 3);  // blocks 1 and 2
  EXPECT_GT(o.gap, 100 * c.prd.contact_tolerance);
  for (size_t k = 1; k < r.steps.size(); ++k) EXPECT_TRUE(r.steps[k].open_corners.empty()) << "d = " << r.steps[k].d;
}

// The 12-voussoir semicircular arch on a spreading support: one capacity across every setting
// that must not matter (within 2%), and within 3% of PRD's.
TEST(DemConvergence, SmallArchAgreesAcrossSettings) {
  const Case c = test::semicircular_arch_case();
  const std::vector<DemVariant> variants = convergence_variants(DemSettings::from_case(c));
  ASSERT_GE(variants.size(), 7u);
  const std::vector<RunResult> runs = run_variants(c, variants, 2);
  Convergence study;
  study.case_name = c.name;
  study.prd_capacity = prd_run(c, PrdSettings::from_case(c)).capacity;
  for (size_t i = 0; i < variants.size(); ++i) {
    std::printf("%-15s %-10s %.5f m, %.2f s\n", variants[i].name.c_str(), status_name(runs[i].status), runs[i].capacity, runs[i].timing.total_s);
    study.entries.push_back({variants[i].name, variants[i].what, runs[i], std::nullopt});
  }
  const ConvergenceVerdict v = judge(study);
  for (const std::string& problem : v.problems) ADD_FAILURE() << problem;
  EXPECT_TRUE(v.ok);
  EXPECT_LE(v.spread, 0.02);
}

// `masonry dem --convergence`: the files, the verdict in the exit code.
TEST(DemConvergence, CommandWritesTheStudy) {
  test::Scratch d("dem-convergence");
  const std::string cmd = std::string(MASONRY_EXE) + " dem " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --convergence --jobs 2 --out " +
                          (d.path / "out").string() + " --quiet 2>/dev/null";
  EXPECT_EQ(test::run(cmd), 0);
  const nlohmann::json j = nlohmann::json::parse(test::read(d.path / "out" / "convergence.json"));
  EXPECT_TRUE(j["ok"].get<bool>()) << j.dump(1);
  EXPECT_GE(j["runs"].size(), 7u);
  EXPECT_TRUE(std::filesystem::exists(d.path / "out" / "default" / "results.json"));
  EXPECT_NE(test::read(d.path / "out" / "convergence.md").find("**Converged**"), std::string::npos);
  // An impossible limit fails the gate.
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " dem " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --convergence --prd-limit 1e-9 --out " +
                      (d.path / "out2").string() + " --quiet 2>/dev/null"),
            1);
  // --only runs the named variant again and reads the others back: the study is the same, and a
  // read-back run keeps its file untouched (the deterministic DEM gives the rerun's capacity
  // again).
  const auto stamp = std::filesystem::last_write_time(d.path / "out" / "default" / "results.json");
  const std::string base =
      std::string(MASONRY_EXE) + " dem " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --convergence --quiet --out " + (d.path / "out").string();
  EXPECT_EQ(test::run(base + " --only damping 2>/dev/null"), 0);
  EXPECT_EQ(std::filesystem::last_write_time(d.path / "out" / "default" / "results.json"), stamp);
  const nlohmann::json again = nlohmann::json::parse(test::read(d.path / "out" / "convergence.json"));
  ASSERT_EQ(again["runs"].size(), j["runs"].size());
  for (size_t i = 0; i < j["runs"].size(); ++i) EXPECT_EQ(again["runs"][i]["capacity"], j["runs"][i]["capacity"]) << i;
  // --read-back runs nothing and writes the same study.
  EXPECT_EQ(test::run(base + " --read-back 2>/dev/null"), 0);
  EXPECT_EQ(std::filesystem::last_write_time(d.path / "out" / "default" / "results.json"), stamp);
  const nlohmann::json read = nlohmann::json::parse(test::read(d.path / "out" / "convergence.json"));
  for (size_t i = 0; i < j["runs"].size(); ++i)
    for (const char* key : {"name", "stopped", "capacity", "cycles"}) EXPECT_EQ(read["runs"][i][key], again["runs"][i][key]) << i << " " << key;
  // An unknown variant, or one never run, is refused with the name and the file.
  const std::string bad = d.path.string() + "/bad.txt";
  EXPECT_EQ(test::run(base + " --only dampin 2>" + bad), 2);
  EXPECT_NE(test::read(bad).find("no variant 'dampin'"), std::string::npos) << test::read(bad);
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " dem " + MASONRY_SOURCE_DIR +
                      "/cases/tilting-block.json --convergence --quiet --only damping --out " + (d.path / "empty").string() + " 2>" + bad),
            2);
  EXPECT_NE(test::read(bad).find("default/results.json is missing"), std::string::npos) << test::read(bad);
}

// `masonry dem --stiffness-study` on the tilting block (b = 0.2 m, h = 0.4 m): the joints scaled
// by the factors the study names, and the toppling tilt rising to the rigid block's closed form
// atan(b/h) as the joints stiffen. A soft joint lets the block sink into its toe as it leans, which
// moves its weight outwards and topples it earlier; PRD's rigid block is the limit.
TEST(DemStiffnessStudy, TheTopplingTiltTendsToTheRigidBlocksAsTheJointsStiffen) {
  test::Scratch d("dem-stiffness");
  const std::string out = (d.path / "out").string();
  ASSERT_EQ(test::run(std::string(MASONRY_EXE) + " dem " + MASONRY_SOURCE_DIR +
                      "/cases/tilting-block.json --stiffness-study --jobs 2 --quiet --out " + out + " 2>/dev/null"),
            0);
  const nlohmann::json j = nlohmann::json::parse(test::read(d.path / "out" / "stiffness.json"));
  EXPECT_EQ(j["study"], "stiffness");
  EXPECT_TRUE(j["ok"].get<bool>()) << j.dump(1);
  const std::map<std::string, double> factor{{"default", 1.0},    {"softer-x10", 0.1},   {"softer-x3", 1.0 / 3},
                                             {"stiffer-x3", 3.0}, {"stiffer-x10", 10.0}, {"stiffer-x30", 30.0}};
  ASSERT_EQ(j["runs"].size(), factor.size());
  ASSERT_EQ(j["runs"][0]["name"], "default");
  const double kn0 = j["runs"][0]["kn"].get<double>();
  std::vector<std::pair<double, double>> by_kn;  // (kn, capacity)
  double width = 0;
  for (const auto& r : j["runs"]) {
    const std::string name = r["name"];
    ASSERT_TRUE(factor.count(name)) << name;
    ASSERT_EQ(r["stopped"], "collapse") << name;
    EXPECT_NEAR(r["kn"].get<double>() / kn0, factor.at(name), 1e-12 * factor.at(name)) << name;
    EXPECT_TRUE(r["parts_from_prd"].is_null()) << name << ": the block topples as PRD's does: " << r["parts_from_prd"].dump();
    by_kn.emplace_back(r["kn"].get<double>(), r["capacity"].get<double>());
    width = std::max(width, r["bracket_width"].get<double>());
  }
  std::sort(by_kn.begin(), by_kn.end());
  const double rigid = std::atan(0.2 / 0.4);
  // PRD on each run's deformed configuration: rigid as cut, it topples at atan(b/h); with the
  // joint's elastic offsets kept, near where the run did (the soft joint's lean is the difference).
  for (const auto& r : j["runs"]) {
    ASSERT_TRUE(r.contains("prd_on_run")) << r["name"];
    const auto& p = r["prd_on_run"];
    const double tol = p["tolerance"].get<double>(), cap = r["capacity"].get<double>();
    EXPECT_NEAR(p["taken_back"].get<double>(), rigid, 2 * tol) << r["name"];
    EXPECT_LT(std::abs(p["kept"].get<double>() - cap), 0.25 * std::abs(rigid - cap) + 2 * tol) << r["name"] << ": " << p.dump();
  }
  for (size_t k = 0; k < by_kn.size(); ++k) {
    EXPECT_LE(by_kn[k].second, rigid + width) << "kn " << by_kn[k].first;
    if (k > 0) {
      EXPECT_GE(by_kn[k].second, by_kn[k - 1].second - width) << "kn " << by_kn[k].first;
    }
  }
  EXPECT_NEAR(by_kn.back().second, rigid, 2 * width);
  EXPECT_GT(rigid - by_kn.front().second, 5 * width) << "the softest joints topple visibly earlier";
  const std::string md = test::read(d.path / "out" / "stiffness.md");
  EXPECT_NE(md.find("DEM joint stiffness"), std::string::npos);
  EXPECT_EQ(md.find("Converged"), std::string::npos);
}

}  // namespace
