#include <chrono>
#include <cmath>
#include <sstream>

#include "dem.hpp"

namespace masonry {

namespace {

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
HoldOutcome hold(DemModel& m, const Case& c, const DemSettings& s, double collapse_drift) {
  HoldOutcome o;
  const std::vector<DemBlockState> start = snapshot(m, c);
  const long long budget = static_cast<long long>(std::ceil(s.hold_time / m.dt()));
  const long long check = 64;  // cycles between drift checks; the drift is slow against this
  for (long long k = 0; k < budget; ++k) {
    m.cycle();
    ++o.cycles;
    if (!std::isfinite(m.unbalanced_ratio())) throw std::runtime_error("dem: the integration produced a non-finite force");
    if (m.unbalanced_ratio() < s.equilibrium_tolerance && m.max_speed() < s.velocity_tolerance) {
      o.settled = true;
      break;
    }
    if (k % check == 0 && largest_move(m, c, start) > collapse_drift) break;
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
  double io_s = 0;
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
      r.timing.total_s = std::chrono::duration<double>(a - t0).count() - io_s;
      on_step(r);
      io_s += std::chrono::duration<double>(clock::now() - a).count();
    }
  };
  auto fail = [&](const std::string& msg) {
    r.stopped = "error";
    r.message = msg;
  };

  try {
    m.set_support_parameter(0);
    const HoldOutcome h0 = hold(m, c, s, collapse_drift);
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
      r.stopped = "max_steps";
      const long long n_move = std::max<long long>(1, static_cast<long long>(std::ceil(s.move_time / m.dt())));
      for (int k = 1; k <= s.max_steps; ++k) {
        const double d0 = (k - 1) * s.step;
        const long long c0 = m.cycles();
        for (long long i = 1; i <= n_move; ++i) {
          m.set_support_parameter(d0 + s.step * travelled(static_cast<double>(i) / static_cast<double>(n_move), s.ramp_fraction));
          m.cycle();
        }
        m.set_support_parameter(k * s.step);
        const HoldOutcome h = hold(m, c, s, collapse_drift);
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
    }
  } catch (const std::exception& e) {
    fail(e.what());
  }
  r.timing.cycles = m.cycles();
  r.timing.total_s = std::chrono::duration<double>(clock::now() - t0).count() - io_s;
  return r;
}

}  // namespace masonry
