#include <time.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dem.hpp"

namespace masonry {

namespace {

// CPU time of the calling thread, s: a run's own cost even when a sweep runs many in parallel
// threads on fewer cores.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Cycles between the cheap whole-model checks (energy budget, drift): a blow-up multiplies the
// energy many times over within this many cycles, and a collapse drifts slowly against it.
constexpr long long kCheckEvery = 64;

// A state that is no longer finite stops the run before anything is recorded (the sum of the
// kinetic energies carries a NaN or infinity from any block).
void check_finite(const DemModel& m) {
  if (!std::isfinite(m.kinetic_energy()) || !std::isfinite(m.unbalanced_ratio())) {
    std::ostringstream msg;
    msg << "dem: the integration produced a non-finite state at t = " << m.time() << " s (cycle " << m.cycles()
        << "); refusing to record it";
    throw std::runtime_error(msg.str());
  }
}

// Energy balance: kinetic + spring energy + dissipation = work of gravity, the loads and the
// moving supports, so the kinetic energy can never exceed that input. The explicit scheme's own
// error is a fraction of it at any stable step (tests/dem/energy_test.cpp: below half at the
// stability limit); an unstable integration grows the kinetic energy geometrically and crosses
// ten times the input (plus a floor far below any physical energy of the scene) within a few
// checks.
void check_energy(const DemModel& m, double floor) {
  check_finite(m);
  const double input = m.energy_input();
  const double ke = m.kinetic_energy();
  if (ke > 10 * std::max(input, 0.0) + floor) {
    std::ostringstream msg;
    msg << "dem: the integration blew up at t = " << m.time() << " s (cycle " << m.cycles() << "): kinetic energy " << ke
        << " J exceeds the energy put in by gravity, loads and supports (" << input
        << " J); time step too close to the stability limit for these stiffnesses and masses";
    throw std::runtime_error(msg.str());
  }
}

struct HoldOutcome {
  bool settled = false;
  double drift = 0;  // m, largest block displacement since the hold began
  long long cycles = 0;
  double time = 0;
};

double largest_move(const DemModel& m, const Case& c, const std::vector<DemBlockState>& from) {
  double d = 0;
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    if (c.blocks[b].support) continue;
    d = std::max(d, (m.block(static_cast<int>(b)).position - from[b].position).norm());
  }
  return d;
}

std::vector<DemBlockState> snapshot(const DemModel& m, const Case& c) {
  std::vector<DemBlockState> s(c.blocks.size());
  for (size_t b = 0; b < c.blocks.size(); ++b) s[b] = m.block(static_cast<int>(b));
  return s;
}

// Cycles with the supports still until equilibrium, the time budget, or a runaway (a block has
// travelled past the collapse drift: waiting out the budget would only confirm it).
HoldOutcome hold(DemModel& m, const Case& c, const DemSettings& s, double collapse_drift, double energy_floor) {
  HoldOutcome o;
  const std::vector<DemBlockState> start = snapshot(m, c);
  const long long budget = static_cast<long long>(std::ceil(s.hold_time / m.dt()));
  for (long long k = 0; k < budget; ++k) {
    m.cycle();
    ++o.cycles;
    check_finite(m);
    if (m.unbalanced_ratio() < s.equilibrium_tolerance && m.max_speed() < s.velocity_tolerance) {
      o.settled = true;
      break;
    }
    if (k % kCheckEvery == 0) {
      check_energy(m, energy_floor);
      if (largest_move(m, c, start) > collapse_drift) break;
    }
  }
  o.drift = largest_move(m, c, start);
  o.time = o.cycles * m.dt();
  return o;
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

RunResult dem_run(const Case& c, const DemSettings& s, const std::function<void(const RunResult&)>& on_step) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double cpu0 = thread_cpu_s();
  double io_s = 0, io_cpu_s = 0;
  RunResult r;
  r.method = "dem";
  r.case_name = c.name;
  for (const Block& b : c.blocks)
    if (!b.support) r.total_weight += block_mass(b) * c.gravity;
  for (const Load& l : c.loads) r.total_weight -= l.force.y();
  const std::vector<Interface> joints = detect_interfaces(c, c.prd.contact_tolerance);
  for (const Interface& J : joints) r.joints.push_back({J.i, J.j, J.a, J.b});

  DemModel m(c, s);
  const double collapse_drift = s.collapse_drift > 0 ? s.collapse_drift : 0.02 * scene_size(c);
  const double energy_floor = 1e-9 * r.total_weight * scene_size(c);
  r.settings = {{"young_modulus", s.young_modulus},
                {"poisson", s.poisson},
                {"kn", m.kn()},
                {"ks", m.ks()},
                {"stiffness_reduction", s.stiffness_reduction},
                {"friction_angle", s.friction_angle},
                {"damping", s.damping},
                {"timestep_factor", s.timestep_factor},
                {"critical_dt", m.critical_dt()},
                {"dt", m.dt()},
                {"equilibrium_tolerance", s.equilibrium_tolerance},
                {"velocity_tolerance", s.velocity_tolerance},
                {"hold_time", s.hold_time},
                {"move_time", s.move_time},
                {"ramp_fraction", s.ramp_fraction},
                {"collapse_drift", collapse_drift},
                {"open_gap", s.open_gap >= 0 ? s.open_gap : c.prd.contact_tolerance},
                {"step", s.step},
                {"max_steps", s.max_steps}};

  auto emit = [&](int index, const HoldOutcome& h, long long cycles) {
    StepRecord rec = m.record(joints);
    rec.index = index;
    rec.extra["settled"] = h.settled;
    rec.extra["cycles"] = cycles;
    rec.extra["hold_time"] = h.time;
    rec.extra["unbalanced_ratio"] = m.unbalanced_ratio();
    rec.extra["max_speed"] = m.max_speed();
    rec.extra["drift"] = h.drift;
    rec.extra["contact_points"] = m.contact_points();
    rec.extra["max_overlap"] = m.max_overlap();
    r.steps.push_back(std::move(rec));
    r.timing.cycles = m.cycles();
    if (on_step) {
      const auto a = clock::now();
      const double a_cpu = thread_cpu_s();
      r.timing.total_s = a_cpu - cpu0 - io_cpu_s;
      r.extra["wall_s"] = std::chrono::duration<double>(a - t0).count() - io_s;
      on_step(r);
      io_s += std::chrono::duration<double>(clock::now() - a).count();
      io_cpu_s += thread_cpu_s() - a_cpu;
    }
  };
  auto fail = [&](const std::string& msg) {
    r.stopped = "error";
    r.message = msg;
  };

  try {
    m.set_support_parameter(0);
    const HoldOutcome h0 = hold(m, c, s, collapse_drift, energy_floor);
    if (h0.settled) {
      r.stable_steps = 0;
      r.capacity = 0;
    }
    emit(0, h0, h0.cycles);
    if (!h0.settled) {
      r.collapsed = h0.drift > collapse_drift;
      r.stopped = r.collapsed ? "collapse" : "error";
      if (!r.collapsed) r.message = "the initial configuration did not settle within the hold time";
    } else {
      const long long n_move = std::max<long long>(1, static_cast<long long>(std::ceil(s.move_time / m.dt())));
      for (int k = 1; k <= s.max_steps; ++k) {
        const double d0 = (k - 1) * s.step;
        const long long c0 = m.cycles();
        for (long long i = 1; i <= n_move; ++i) {
          m.set_support_parameter(d0 + s.step * travelled(static_cast<double>(i) / static_cast<double>(n_move), s.ramp_fraction));
          m.cycle();
          check_finite(m);
          if (i % kCheckEvery == 0) check_energy(m, energy_floor);
        }
        m.set_support_parameter(k * s.step);
        const HoldOutcome h = hold(m, c, s, collapse_drift, energy_floor);
        if (h.settled) {
          r.capacity = k * s.step;
          ++r.stable_steps;
        }
        emit(k, h, m.cycles() - c0);
        if (!h.settled && h.drift > collapse_drift) {
          r.collapsed = true;
          r.stopped = "collapse";
          break;
        }
      }
      // Only now: the results handed out on the way say "running", so a run stopped from
      // outside does not look finished.
      if (!r.collapsed) r.stopped = "max_steps";
    }
  } catch (const std::exception& e) {
    fail(e.what());
  }
  r.timing.cycles = m.cycles();
  r.timing.total_s = thread_cpu_s() - cpu0 - io_cpu_s;
  r.extra["wall_s"] = std::chrono::duration<double>(clock::now() - t0).count() - io_s;
  return r;
}

}  // namespace masonry
