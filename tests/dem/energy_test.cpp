// With damping off and no slip limit (phi = 90 degrees) a block dropped a few millimetres onto a
// support bounces forever: kinetic + gravity + spring energy stays at its initial value. A time
// step above the stability limit is refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dem/dem.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

constexpr double kDrop = 0.003;  // m

Case drop_case(double timestep_factor) {
  Case c = test::slab_case();
  c.blocks.push_back(test::rect("block", -0.2, kDrop, 0.2, kDrop + 0.2, 2000, false));
  c.dem.friction_angle = 90;
  c.dem.damping = 0;
  c.dem.timestep_factor = timestep_factor;
  return c;
}

struct Trace {
  double max_error = 0;  // |E(t) - E(0)| / (m g drop), largest
  int impacts = 0;
  double lowest = INFINITY, highest_after_first = -INFINITY;  // block bottom, m
};

Trace bounce(double factor, double seconds) {
  const Case c = drop_case(factor);
  DemModel m(c, DemSettings::from_case(c));
  const double mg = 2000 * 0.4 * 0.2 * c.gravity;
  Trace t;
  bool in_contact = false;
  const long long n = static_cast<long long>(seconds / m.dt());
  for (long long k = 0; k < n; ++k) {
    m.cycle();
    const double e = m.kinetic_energy() + m.gravity_energy() + m.spring_energy();
    t.max_error = std::max(t.max_error, std::abs(e) / (mg * kDrop));
    const bool touching = m.contact_points() > 0;
    if (touching && !in_contact) ++t.impacts;
    in_contact = touching;
    const double bottom = m.block(1).position.y() - 0.1;
    t.lowest = std::min(t.lowest, bottom);
    if (t.impacts > 0 && !touching) t.highest_after_first = std::max(t.highest_after_first, bottom);
  }
  return t;
}

TEST(DemEnergy, DroppedBlockConservesEnergyAtTheReportedStep) {
  const Trace t = bounce(0.2, 2.0);
  std::printf("factor 0.2: energy error %.3g of m g drop over %d impacts\n", t.max_error, t.impacts);
  // Flight time between impacts is 2 sqrt(2 drop / g) = 0.05 s: about 40 bounces in 2 s.
  EXPECT_GE(t.impacts, 30);
  EXPECT_LT(t.max_error, 5e-3);  // stated tolerance: 0.5% of m g drop
  // The block keeps bouncing back to its release height (within the same 0.5%).
  EXPECT_NEAR(t.highest_after_first, kDrop, 5e-3 * kDrop);
  // Spring compression at impact: m g drop = 1/2 K x^2 - m g x with K = 2 points * kn * area/2.
  EXPECT_LT(t.lowest, 0);
}

TEST(DemEnergy, StableUpToTheCriticalStepBound) {
  // The bound on the critical step is conservative: at factor 1 nothing blows up.
  // The error is larger (the step is coarse against the contact period) but bounded: an unstable
  // integration would grow without limit over 40 impacts.
  const Trace t = bounce(1.0, 2.0);
  std::printf("factor 1: energy error %.3g of m g drop over %d impacts\n", t.max_error, t.impacts);
  EXPECT_GE(t.impacts, 30);
  EXPECT_LT(t.max_error, 0.5);
  EXPECT_NEAR(t.highest_after_first, kDrop, 0.5 * kDrop);
}

TEST(DemEnergy, UnstableTimeStepIsRefused) {
  const Case c = drop_case(1.5);
  try {
    DemModel m(c, DemSettings::from_case(c));
    FAIL() << "a time-step factor of 1.5 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("stability limit"), std::string::npos) << e.what();
  }
  // dem_run refuses it the same way, before any cycle.
  EXPECT_THROW(dem_run(c, DemSettings::from_case(c)), std::runtime_error);
}

// A capacity run without damping and with local holds: nothing takes energy out of a hold, so
// none can settle (dem/README.md, "Refusals and the blow-up guard"); it ran until the blow-up
// guard stopped it, blaming the time step even at a tenth of its bound. It is refused before
// the first cycle, in one line naming the field and what to set instead.
TEST(DemEnergy, AnUndampedRunWithLocalHoldsIsRefused) {
  Case c = test::tilt_case(0.2, 0.4, 35);
  c.dem.damping = 0;
  c.dem.timestep_factor = 0.1;
  try {
    dem_run(c, DemSettings::from_case(c));
    FAIL() << "ran undamped with local holds";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("dem: field 'damping' = 0 with dem.hold_damping local"), std::string::npos) << msg;
    EXPECT_NE(msg.find("dem.hold_damping kinetic"), std::string::npos) << msg;
  }
}

// Kinetic holds stop the blocks at each peak of the kinetic energy, so they settle without
// damping: the block topples at atan(b/h), as with damping (tilt_test.cpp's bound: at most a
// degree below, the bracket and the joints' elastic lean).
TEST(DemEnergy, AnUndampedRunWithKineticHoldsTopplesAtAtanBOverH) {
  const double b = 0.2, h = 0.4;
  Case c = test::tilt_case(b, h, 45);
  c.dem.damping = 0;
  c.dem.hold_damping = HoldDamping::kinetic;
  const RunResult r = test::tilt_run(c);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double topple = std::atan(b / h);
  EXPECT_LE(r.capacity, topple);
  EXPECT_GT(r.capacity, topple - M_PI / 180);
}

// Lightly damped (1e-4; 0.01 settles), the gain of each contact's opening and closing between
// cycles outgrows what the damping takes out at the full time step, and the guard stops the run.
// The step is within its stability bound, so the message names the damping, not the step.
TEST(DemEnergy, ALightlyDampedRunThatGainsEnergySaysDampingNotTimeStep) {
  Case c = test::tilt_case(0.2, 0.4, 35);
  c.dem.damping = 1e-4;
  c.motion.max_steps = 3;
  const RunResult r = dem_run(c, DemSettings::from_case(c));
  ASSERT_EQ(r.status, RunStatus::error) << r.message;
  EXPECT_NE(r.message.find("blew up"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("dem.damping 0.0001 is too light"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("the time step is within its stability bound"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("times the bound"), std::string::npos) << r.message;
}

}  // namespace
