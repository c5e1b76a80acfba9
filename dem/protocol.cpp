#include "dem/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace masonry::dem {

namespace {

// Cycles between the cheap whole-model checks (energy budget, drift): a blow-up multiplies the
// energy many times over within this many cycles, and a collapse drifts slowly against it.
constexpr long long kCheckEvery = 64;
// The kinetic-energy trend of a hold is read over windows that double in length (1024 cycles,
// then 2048, 4096, ...): a runaway's energy grows from each window to the next, however slowly
// it started, while a structure settling towards equilibrium, however slowly, loses energy
// through damping over any span longer than its transient, and the doubling windows outgrow
// every transient. Three rises in a row, above the threshold, make a collapse.
constexpr long long kFirstWindow = 1024;
constexpr int kRisingWindows = 3;
// The hold's verdict at its cap (hold()). A motion that still covers at least half the ground
// over the cap's second half that it covered over the first, while its unbalanced force does
// not fall, is not dying out on the time scale of the cap (an exponential decay would need a
// time constant above 0.72 cap): creep. One that is dying out gets up to three more caps (4.2 of
// the slowest such time constants: its motion falls below 2% of what it was), so a slow
// settling is not mistaken for a failure.
constexpr double kCreepRatio = 0.5;
constexpr int kExtensions = 3;
// The cap's collapse rule is also read over shorter windows from the cap's start, j/16 of the cap
// long (j = 2..15), so a failure that is already speeding up far from its start does not wait
// for the cap (near the cathedral's capacity a failing trial ran 30 s of model time, 400,000
// cycles, to be called at the cap). The positions at each window's middle are kept every 1/32 of
// the cap over its first half.
constexpr int kLookSegments = 32;
constexpr int kFirstLook = 2;

// The servo's rates and the hold's first window are set in cycles at the default time-step
// factor and kept in model time at any other: the time step is a numerical setting, so halving it
// must not make the supports speed up and brake twice as fast in model time (which loads the
// structure more abruptly), nor make the hold's windows half as long. Returns how many default
// cycles one cycle is: exactly 1 at the default. Contact damping shortens the step too (by
// contact_damping_step_factor), a numerical consequence, so its factor counts the same way.
double default_cycles_per_cycle(const DemSettings& s) {
  return s.timestep_factor * contact_damping_step_factor(s.contact_damping) / DemOptions{}.timestep_factor;
}

// A state that is no longer finite stops the run before anything is recorded (the sum of the
// kinetic energies carries a NaN or infinity from any block, and from any free block's force or
// torque, which its new velocity takes in: so the unbalanced force, over the same blocks, is
// finite whenever the kinetic energy is).
void check_finite(const DemModel& m) {
  if (!std::isfinite(m.kinetic_energy())) {
    std::ostringstream msg;
    msg << "dem: the integration produced a non-finite state at t = " << m.time() << " s (cycle " << m.cycles() << "); refusing to record it";
    throw std::runtime_error(msg.str());
  }
}

// Energy balance: kinetic + spring energy + dissipation = work of gravity, the loads and the
// moving supports, so the kinetic energy can never exceed that input. The explicit scheme's own
// error is a fraction of it at any stable step (tests/dem/energy_test.cpp: below half at the
// stability limit); an unstable integration grows the kinetic energy geometrically and crosses
// ten times the input (plus a floor far below any physical energy of the scene) within a few
// checks.
//
// The time step is a bound on the stability limit (model.cpp, set_time_step), so within it (a
// factor up to 1, all a case may set) the step is not what gains energy: the contacts are. A
// contact that opens or closes between two cycles gets a force for the part of the step it was
// not touching (or loses it for the part it was), a small gain per event, which local damping
// takes out at a fraction of the motion per oscillation; a damping too light for it (1e-4 on the
// tilting block at the full step, where 0.01 settles) lets the gains pile up until they pass the
// input. The message names what to change accordingly; only a factor above 1 (a test's switch)
// names the step.
void check_energy(const DemModel& m, double floor, const DemSettings& s) {
  check_finite(m);
  const double input = m.energy_input();
  const double ke = m.kinetic_energy();
  if (ke > 10 * std::max(input, 0.0) + floor) {
    std::ostringstream msg;
    msg << "dem: the integration blew up at t = " << m.time() << " s (cycle " << m.cycles() << "): kinetic energy " << ke
        << " J exceeds the energy put in by gravity, loads and supports (" << input << " J); ";
    if (s.timestep_factor > 1)
      msg << "the time step is " << s.timestep_factor << " times the bound on its stability limit";
    else
      msg << "the time step is within its stability bound (dem.timestep_factor " << s.timestep_factor
          << "), so the energy came from the contacts' opening and closing between cycles, which dem.damping " << s.damping
          << " is too light to take out: raise dem.damping (default 0.8)";
    throw std::runtime_error(msg.str());
  }
}

// Fraction of the increment travelled after a fraction u of the move time: constant speed with
// half-cosine ramps of length r at both ends.
double travelled(double u, double r) {
  if (r <= 0) return u;
  const double vp = 1 / (1 - r);  // plateau speed, increments per move time
  auto up = [&](double x) { return vp * (x / 2 - r / (2 * M_PI) * std::sin(M_PI * x / r)); };
  if (u <= r) return up(u);
  if (u >= 1 - r) return 1 - up(1 - u);
  return vp * (r / 2 + (u - r));
}

}  // namespace

std::vector<Vec2> positions(const DemModel& m, const Case& c) {
  std::vector<Vec2> p(c.blocks.size());
  for (size_t b = 0; b < c.blocks.size(); ++b) p[b] = m.block(static_cast<int>(b)).position;
  return p;
}

double largest_move(const DemModel& m, const Case& c, const std::vector<Vec2>& from) {
  double d = 0;
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    if (c.blocks[b].support) continue;
    d = std::max(d, (m.block(static_cast<int>(b)).position - from[b]).norm());
  }
  return d;
}

double largest_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b, const Case& c) {
  double d = 0;
  for (size_t k = 0; k < c.blocks.size(); ++k)
    if (!c.blocks[k].support) d = std::max(d, (a[k] - b[k]).norm());
  return d;
}

const char* hold_end_name(HoldEnd e) {
  switch (e) {
    case HoldEnd::equilibrium: return "equilibrium";
    case HoldEnd::collapse: return "collapse";
    case HoldEnd::creep: return "creep";
    case HoldEnd::undecided: return "undecided";
  }
  return "?";
}

namespace {
// The cap's collapse rule (hold()), at the cap and over the early windows from the cap's start:
// the structure has drifted a tenth of the collapse drift and travels at least as far over the
// window's second half as over its first. (Not also "pushed at least as hard", as a creep must
// be: a block sliding down a slope at constant friction speeds up while its unbalanced force,
// read each cycle, falls by 1-2%.)
bool speeding_up_far_out(const DemModel& m, const Case& c, const std::vector<Vec2>& start, const std::vector<Vec2>& window_start,
                         const std::vector<Vec2>& window_mid, const Limits& lim) {
  return largest_move(m, c, start) > 0.1 * lim.collapse_drift && largest_move(m, c, window_mid) >= largest_distance(window_start, window_mid, c);
}
}  // namespace

HoldOutcome hold(DemModel& m, const Case& c, const DemSettings& s, const Limits& lim, long long watch, const std::vector<Vec2>* drift_from) {
  HoldOutcome o;
  const std::vector<Vec2> start = positions(m, c);
  const std::vector<Vec2>& origin = drift_from ? *drift_from : start;
  const long long budget = static_cast<long long>(std::ceil(s.hold_time / m.dt()));
  double window_peak = 0, last_peak = INFINITY;
  long long window_end = std::max(1LL, std::llround(static_cast<double>(kFirstWindow) / default_cycles_per_cycle(s)));
  int rising = 0;
  // The current cap: its end, and the positions half way through it.
  long long cap_end = budget;
  int extensions = 0;
  std::vector<Vec2> cap_start = start, mid;
  double unbalanced[2] = {0, 0};  // sums of the unbalanced-force ratio over the cap's two halves
  // The early looks (kLookSegments): positions at each 1/32 of the cap up to its half (the
  // first, looks[0], is cap_start).
  const long long segment = budget / kLookSegments;
  std::vector<std::vector<Vec2>> looks(kLookSegments / 2 + 1);
  // Kinetic damping: stop every free block when the kinetic energy passes a peak, so the hold
  // relaxes towards the nearest equilibrium without momentum (HoldDamping).
  const bool kinetic = s.hold_damping == HoldDamping::kinetic;
  double prev_ke = 0;
  for (long long k = 0; k < cap_end; ++k) {
    if (k == cap_end - budget + budget / 2) mid = positions(m, c);
    const long long in_cap = k - (cap_end - budget);  // cycles since this cap began
    if (segment > 0 && in_cap % segment == 0 && in_cap / segment <= kLookSegments / 2) looks[in_cap / segment] = positions(m, c);
    m.cycle();
    ++o.cycles;
    if (kinetic) {
      const double ke = m.kinetic_energy();
      if (ke < prev_ke) {
        m.stop_free_blocks();
        prev_ke = 0;
      } else {
        prev_ke = ke;
      }
    }
    check_finite(m);
    unbalanced[k >= cap_end - budget + budget / 2] += m.unbalanced_ratio();
    const bool at_rest = m.unbalanced_ratio() < s.equilibrium_tolerance && m.max_speed() < s.velocity_tolerance;
    if (at_rest && k + 1 >= std::min(watch, budget)) {
      o.end = HoldEnd::equilibrium;
      break;
    }
    if (k % kCheckEvery == 0) {
      check_energy(m, lim.energy_floor, s);
      if (largest_move(m, c, origin) > lim.collapse_drift) {
        o.end = HoldEnd::collapse;
        break;
      }
    }
    window_peak = std::max(window_peak, m.kinetic_energy());
    if (k + 1 == window_end) {
      rising = window_peak > lim.ke_collapse && window_peak > last_peak ? rising + 1 : 0;
      last_peak = window_peak;
      window_peak = 0;
      window_end *= 2;
      if (rising >= kRisingWindows) {
        o.end = HoldEnd::collapse;
        break;
      }
    }
    if (segment > 0 && (in_cap + 1) % (2 * segment) == 0) {
      const long long j = (in_cap + 1) / (2 * segment);  // the window is 2j segments long, its middle at segment j
      check_energy(m, lim.energy_floor, s);              // a diverging integration also drifts: it is an error, never a collapse
      if (lim.read_early && j >= kFirstLook && j < kLookSegments / 2 && speeding_up_far_out(m, c, start, cap_start, looks[size_t(j)], lim)) {
        o.end = HoldEnd::collapse;
        break;
      }
    }
    if (k + 1 < cap_end) continue;
    // At the cap: how the motion goes on. A structure settling towards an equilibrium travels
    // less over the cap's second half than over its first (an exponential decay with time
    // constant tau gives the ratio exp(-cap / (2 tau))), or, where it settles too slowly for the
    // cap to show that, it is pushed less and less as it approaches the equilibrium: its
    // unbalanced force falls (a block sinking onto soft joints under damping 0.9999 travels
    // faster in the second half of a cap of two periods, while its unbalanced force falls by 2%).
    // A mechanism past its limit point keeps its pace or speeds up, and nothing takes up its
    // unbalanced force.
    o.first_half = largest_distance(cap_start, mid, c);
    o.second_half = largest_move(m, c, mid);
    const bool pushed_as_hard = unbalanced[1] >= unbalanced[0];  // the halves have equal lengths, to a cycle
    const bool creeping = o.second_half > lim.creep_floor && o.second_half >= kCreepRatio * o.first_half && pushed_as_hard;
    unbalanced[0] = unbalanced[1] = 0;
    if (lim.read_early && speeding_up_far_out(m, c, start, cap_start, mid, lim)) {
      // Collapsing more slowly than the cap (on the settlement cathedral, a block 0.47 m from its
      // start still moving at 0.13 m/s after 30 s).
      o.end = HoldEnd::collapse;
    } else if (creeping) {
      o.end = HoldEnd::creep;
    } else if (extensions < kExtensions) {
      // Still dying out: one more cap, from here.
      ++extensions;
      cap_end += budget;
      cap_start = positions(m, c);
      continue;
    }
    break;
  }
  o.drift = largest_move(m, c, start);
  o.time = static_cast<double>(o.cycles) * m.dt();
  return o;
}

MoveOutcome move(DemModel& m, const Case& c, const DemSettings& s, double d0, double d1, double ke_height, double start_speed, const Limits& lim) {
  MoveOutcome o;
  const double dt = m.dt();
  const std::vector<Vec2> start = positions(m, c);
  // The periodic checks: the energy balance, and whether the structure collapsed on the way.
  auto collapsed = [&](long long cycle) {
    if (cycle % kCheckEvery != 0) return false;
    check_energy(m, lim.energy_floor, s);
    return o.collapsed = largest_move(m, c, start) > lim.move_drift;
  };
  if (s.move_time > 0) {
    const long long n = std::max<long long>(1, static_cast<long long>(std::ceil(s.move_time / dt)));
    for (long long i = 1; i <= n; ++i) {
      m.set_support_parameter(d0 + (d1 - d0) * travelled(static_cast<double>(i) / static_cast<double>(n), s.ramp_fraction));
      m.cycle();
      ++o.cycles;
      check_finite(m);
      if (collapsed(i)) break;
    }
    o.speed = (d1 - d0) / s.move_time;
    return o;
  }
  // The servo: the speed follows the structure's kinetic energy, so a stiff, light structure is
  // loaded fast and a tall, slow one slowly, each in the quasi-static regime the target sets. It
  // reads every block's kinetic energy over that block's own weight, not the whole structure's
  // over the whole weight: a light aisle arch carried by a moving pier of a cathedral otherwise
  // moves fast relative to its weight while most of the structure stands still, and the move's
  // transient, not the structure, chooses its hinge (dem/README.md, "The loading rate"). The
  // floor bounds the move's length by the hold cap. The supports also brake at the servo's own
  // rate towards the end, so they stop without a shock: a block near its friction limit on a
  // support that stops at once slips (the tilting block slid 1.5 degrees early).
  //
  // The rates are relative (0.2% up, 2% down per cycle), so the supports' acceleration grows with
  // the speed and as the time step shrinks, and a structure on an accelerating support feels it
  // as a tilt: the servo's acceleration is also capped at lim.move_accel, a hundredth of gravity
  // (dem_run's kMoveAccel has the measurements).
  const double floor = (d1 - d0) / s.hold_time;
  const double per = default_cycles_per_cycle(s);
  const double kUp = std::pow(1.002, per), kDown = std::pow(0.98, per);
  const double dv = lim.move_accel * dt;  // the largest change of the speed per cycle
  double v = std::max(start_speed, floor), d = d0;
  while (d < d1) {
    d = std::min(d1, d + v * dt);
    m.set_support_parameter(d);
    m.cycle();
    ++o.cycles;
    check_finite(m);
    if (collapsed(o.cycles)) break;
    // Braking from v at kDown per cycle travels v dt / (1 - kDown); by dv per cycle, about
    // v (v + dv) dt / (2 dv).
    const bool brake = d1 - d < std::max(v * dt / (1 - kDown), v * (v + dv) * dt / (2 * dv));
    v = !brake && m.max_kinetic_per_weight() < ke_height ? std::min(v * kUp, v + dv) : std::max(floor, std::max(v * kDown, v - dv));
  }
  o.speed = v;
  return o;
}

}  // namespace masonry::dem
