// dem_run: the capacity run, as a sequence of named stages (dem/README.md, "Protocol"):
// settle the initial configuration, then per increment move and hold; once an increment fails,
// go back to the last equilibrium and bracket the collapse.
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dem.hpp"
#include "io.hpp"
#include "protocol.hpp"

namespace masonry {

namespace {

using dem::HoldEnd;
using dem::HoldOutcome;

// How far a support point travels per unit of d, m/m: its translation plus its rotation over the
// scene. The work the supports do on the structure over an increment is of the order of the
// weight times this times the increment.
double support_travel_per_d(const Case& c) {
  double v = 0;
  for (const SupportMotion& sm : c.motion.supports) v = std::max(v, sm.translation.norm() + std::abs(sm.rotation) * scene_size(c));
  return v > 0 ? v : 1.0;
}

// One attempt to reach d1 from an equilibrium at d0: move, then hold.
struct Attempt {
  HoldOutcome hold;
  long long cycles = 0;       // move and hold
  long long move_cycles = 0;
  double move_drift = 0;      // m, largest block displacement during the move
  // What the structure still travelled during the hold over what it travelled during the move
  // (a diagnostic, per step. On the cathedral with rotation it is 1.3-2 at the default loading
  // and at half its speed, and stayed above 0.25 with supports 32 times slower, so it measures
  // slow settling of parts other than those the move carries, not a lag behind the loading).
  double lag() const { return move_drift > 0 ? hold.drift / move_drift : 0.0; }
};


}  // namespace

RunResult dem_run(const Case& c, const DemSettings& s, const std::function<void(const RunResult&)>& on_step) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double cpu0 = thread_cpu_s();
  double io_s = 0, io_cpu_s = 0;
  RunResult r;
  r.method = "dem";
  r.case_name = c.name;
  r.total_weight = total_weight(c);
  const std::vector<Interface> joints = detect_interfaces(c, c.prd.contact_tolerance);
  for (const Interface& J : joints) r.joints.push_back({J.i, J.j, J.a, J.b});

  DemModel m(c, s);
  dem::Limits lim;
  // A block that travels 2% of the scene during a hold, with the supports at rest, has left its
  // equilibrium for good. Smaller drifts are not evidence: a hinge that jumps to another joint
  // snaps the pointed arch by 4 mm (0.2% of its size) to a new equilibrium near d = 0.09 m.
  lim.collapse_drift = s.collapse_drift > 0 ? s.collapse_drift : 0.02 * scene_size(c);
  lim.energy_floor = 1e-9 * r.total_weight * scene_size(c);
  // The kinetic energy a move may carry per metre of d: the target of the speed servo.
  const double ke_per_d = s.kinetic_ratio * r.total_weight * support_travel_per_d(c);
  const double bracket = s.bracket_fraction * s.step;
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
                {"kinetic_ratio", s.kinetic_ratio},
                {"move_time", s.move_time},
                {"ramp_fraction", s.ramp_fraction},
                {"collapse_drift", lim.collapse_drift},
                {"bracket_fraction", s.bracket_fraction},
                {"open_gap", s.open_gap >= 0 ? s.open_gap : c.prd.contact_tolerance},
                {"step", s.step},
                {"max_steps", s.max_steps}};

  // Corner gaps of the settled initial configuration: hinges are measured from them.
  std::vector<double> settled_gaps;
  auto emit = [&](int index, const HoldOutcome& h, long long cycles, long long move_cycles, bool bracketing, double lag) {
    StepRecord rec = m.record(joints, settled_gaps);
    rec.index = index;
    rec.extra["settled"] = h.end == HoldEnd::equilibrium;
    rec.extra["hold_end"] = dem::hold_end_name(h.end);
    if (bracketing) rec.extra["bracket"] = true;
    rec.extra["cycles"] = cycles;
    rec.extra["move_cycles"] = move_cycles;
    rec.extra["lag"] = lag;
    rec.extra["hold_time"] = h.time;
    rec.extra["unbalanced_ratio"] = m.unbalanced_ratio();
    rec.extra["max_speed"] = m.max_speed();
    rec.extra["drift"] = h.drift;
    rec.extra["contact_points"] = m.contact_points();
    rec.extra["max_overlap"] = m.max_overlap();
    require_finite(rec);
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

  // The support speed at the end of the last move: the next move starts at a quarter of it, so
  // the servo need not find the structure's pace again from the floor every increment.
  double speed = 0;
  auto attempt = [&](double d0, double d1, long long watch = 0) {
    Attempt a;
    const long long c0 = m.cycles();
    const double ke_target = ke_per_d * (d1 - d0);
    lim.ke_collapse = 10 * ke_target;
    lim.move_drift = lim.collapse_drift + support_travel_per_d(c) * (d1 - d0);
    const std::vector<Vec2> before = dem::positions(m, c);
    const dem::MoveOutcome mv = dem::move(m, c, s, d0, d1, ke_target, speed / 4, lim);
    speed = mv.speed;
    a.move_cycles = mv.cycles;
    a.move_drift = dem::largest_move(m, c, before);
    if (mv.collapsed) {
      a.hold.end = HoldEnd::collapse;  // no hold: the structure fell during the move
    } else {
      m.set_support_parameter(d1);
      a.hold = dem::hold(m, c, s, lim, watch);
    }
    a.cycles = m.cycles() - c0;
    return a;
  };

  try {
    // Stage 1: the initial configuration settles under gravity. Only a drift ends it as a
    // collapse: the kinetic energy of the first settling is no sign of one.
    m.set_support_parameter(0);
    lim.ke_collapse = INFINITY;
    const HoldOutcome h0 = dem::hold(m, c, s, lim);
    if (h0.end == HoldEnd::equilibrium) r.capacity = 0;
    emit(0, h0, h0.cycles, 0, false, 0.0);  // absolute gaps: the settled crack pattern
    if (h0.end != HoldEnd::equilibrium) {
      r.collapsed = h0.end == HoldEnd::collapse;
      r.status = r.collapsed ? RunStatus::collapse : RunStatus::undecided;
      if (!r.collapsed)
        r.message = "the initial configuration neither settled nor ran away within the hold cap (" + std::to_string(s.hold_time) +
                    " s): no capacity";
    } else {
      settled_gaps = m.corner_gaps(joints);
      DemSnapshot last_eq = m.save();
      double d_eq = 0;
      int index = 1;
      // Increments follow the grid k x step until a failure that was not confirmed moves the
      // last equilibrium off it; from there they are step long, up to max_steps x step.
      int k = 1;
      bool on_grid = true;
      const double d_end = s.max_steps * s.step;
      nlohmann::ordered_json unconfirmed = nlohmann::ordered_json::array();
      while (true) {
        // Stage 2: increments, each a move and a hold, from the last equilibrium.
        Attempt failed;
        double d_fail = 0;
        bool failure = false;
        while (on_grid ? k <= s.max_steps : d_eq + s.step <= d_end * (1 + 1e-12)) {
          const double d1 = on_grid ? k * s.step : d_eq + s.step;
          ++k;
          const Attempt a = attempt(d_eq, d1);
          if (a.hold.end != HoldEnd::equilibrium) {
            failed = a;
            d_fail = d1;
            failure = true;
            break;
          }
          emit(index++, a.hold, a.cycles, a.move_cycles, false, a.lag());
          r.capacity = d_eq = d1;
          ++r.stable_steps;
          last_eq = m.save();
        }
        if (!failure) {
          // Only now: the results handed out on the way say "running", so a run stopped from
          // outside does not look finished.
          r.status = RunStatus::max_steps;
          break;
        }
        // Stage 3: the collapse bracket. Back to the last equilibrium, halve the failed
        // increment until the bracket is narrower than bracket_fraction x step. A trial that
        // does not settle (collapse or undecided) moves the upper end; one that settles is a
        // recorded equilibrium and moves the lower end.
        nlohmann::ordered_json trials = nlohmann::ordered_json::array();
        trials.push_back({{"d", d_fail}, {"end", dem::hold_end_name(failed.hold.end)}, {"cycles", failed.cycles}});
        DemSnapshot failed_state = m.save();
        double failed_from = d_eq;  // the equilibrium the failed attempt at d_fail started from
        while (bracket > 0 && d_fail - d_eq > bracket) {
          m.restore(last_eq);
          speed = 0;
          const double mid = 0.5 * (d_eq + d_fail);
          const Attempt a = attempt(d_eq, mid);
          trials.push_back({{"d", mid}, {"end", dem::hold_end_name(a.hold.end)}, {"cycles", a.cycles}});
          if (a.hold.end == HoldEnd::equilibrium) {
            emit(index++, a.hold, a.cycles, a.move_cycles, true, a.lag());
            r.capacity = d_eq = mid;
            ++r.stable_steps;
            last_eq = m.save();
          } else {
            failed = a;
            d_fail = mid;
            failed_from = d_eq;
            failed_state = m.save();
          }
        }
        // Stage 4: confirm the collapse. The failure at d_fail was reached by a move from
        // failed_from; if the bracket's lower end has moved up since, the collapse must also
        // follow from the last equilibrium by a move shorter than the bracket. Where it does
        // not, the longer move's own dynamics tipped the structure over (every trial below
        // d_fail settling is the sign: the failure sits on the increment grid), so d_fail is
        // an equilibrium, not the capacity, and the increments go on from there.
        if (s.confirm_collapse && bracket > 0 && failed_from < d_eq) {
          m.restore(last_eq);
          speed = 0;
          // The confirming hold does not end at the first equilibrium: past an unstable one
          // the structure starts from rest, so the hold watches four times as long as the
          // failure took to show itself (at most the cap) before it calls the state settled.
          // (A perturbation 100 times smaller, a move under 1% of the step, takes ln 100 = 4.6
          // more growth times to reach the same size.)
          const Attempt a = attempt(d_eq, d_fail, 4 * failed.hold.cycles);
          trials.push_back({{"d", d_fail}, {"end", dem::hold_end_name(a.hold.end)}, {"cycles", a.cycles}, {"confirm", true}});
          if (a.hold.end == HoldEnd::equilibrium) {
            unconfirmed.push_back({{"d", d_fail}, {"reached_from", failed_from}, {"settled_from", d_eq}});
            emit(index++, a.hold, a.cycles, a.move_cycles, true, a.lag());
            r.capacity = d_eq = d_fail;
            ++r.stable_steps;
            last_eq = m.save();
            on_grid = false;
            continue;
          }
          failed = a;
          failed_state = m.save();
        }
        // The failed state nearest the capacity closes the record.
        m.restore(failed_state);
        emit(index++, failed.hold, failed.cycles, failed.move_cycles, bracket > 0, failed.lag());
        r.extra["collapse_bracket"] = {{"equilibrium", d_eq}, {"failed", d_fail}, {"width", d_fail - d_eq}, {"trials", trials}};
        // A collapse shown anywhere beyond the capacity makes the run a collapse; the bracket's
        // upper end may still be a hold that had not decided when the cap came.
        bool any_collapse = false;
        for (const auto& t : trials) any_collapse = any_collapse || t["end"] == "collapse";
        r.collapsed = any_collapse;
        r.status = r.collapsed ? RunStatus::collapse : RunStatus::undecided;
        if (!r.collapsed) {
          std::ostringstream msg;
          msg << "the hold at d = " << d_fail << " m neither settled nor ran away within the hold cap (" << s.hold_time
              << " s): the capacity " << d_eq << " m is the last equilibrium, not a located collapse";
          r.message = msg.str();
        }
        break;
      }
      if (!unconfirmed.empty()) r.extra["unconfirmed_failures"] = unconfirmed;
    }
  } catch (const std::exception& e) {
    r.status = RunStatus::error;
    r.message = e.what();
  }
  r.timing.cycles = m.cycles();
  r.timing.total_s = thread_cpu_s() - cpu0 - io_cpu_s;
  r.extra["wall_s"] = std::chrono::duration<double>(clock::now() - t0).count() - io_s;
  return r;
}

}  // namespace masonry
