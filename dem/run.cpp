// dem_run: the capacity run, as a sequence of named stages (dem/README.md, "Protocol"):
// settle the initial configuration, then per increment move and hold; once an increment fails,
// go back to the last equilibrium and bracket the collapse.
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "dem/dem.hpp"
#include "dem/protocol.hpp"
#include "model/io.hpp"
#include "model/options.hpp"

namespace masonry {

namespace {

using dem::HoldEnd;
using dem::HoldOutcome;

// The servo's largest acceleration of a point carried by the supports, over gravity (dem::move):
// a hundredth of gravity at the farthest point of the scene a support could carry (its
// translation plus its rotation over the scene size, per unit of d). A structure on an
// accelerating support feels it as a tilt of a / g, so near a toppling limit its capacity moves
// by that much, and the servo's relative rates (0.2% up, 2% down per cycle, chattering about the
// kinetic-energy target) accelerated the supports at v x 0.02 / dt: up to 1.5 g at the top of a
// stack of four blocks on a turning slab (the stack rocked off one corner in the first move,
// its top block walked 7.7-9 mm downhill by 0.24 rad, and it toppled 0.005 rad, 2%, before
// atan(b/H)), 0.34 g on the pointed arch, 1.6 g at the cathedral's settling pier, 90 g with joints
// stiff against the weights (the tilting block thrown off its slab at 1 degree). With the cap:
// the stack within 0.2% of atan(b/H), its top block 1 mm off; the pointed arch's capacity the
// same to 1e-15 m in 13% fewer cycles (its holds start calmer). A move of the paper's 1 mm then
// takes at least 2 sqrt(step / (0.01 g)) = 0.2 s, about what the kinetic-energy target already
// made it take.
constexpr double kMoveAccel = 0.01;

// The most holds the follow stage holds a creeping upper end on (follow()), each a cap long (up
// to four where its motion seems to die out: dem::hold's extensions): it bounds the cost of a
// limit point, not its verdict. The stiff segmental arch's hinge needed some 2.5 caps of the
// default 30 s from rest to pass to another joint (74 s).
constexpr int kFollowHolds = 8;

// The most landings (land()) one run makes: each is a snap through of at least collapse_drift
// from where its hold began, so a run that keeps landing is carried far from its geometry by a
// string of them (a stick-slip ratchet would read so): past this many the next collapse stands.
// A bound on the cost, not the verdict; no case here lands more than once.
constexpr int kMaxLandings = 4;

// One attempt to reach d1 from an equilibrium at d0: move, then hold.
struct Attempt {
  HoldOutcome hold;
  long long cycles = 0;  // move and hold
  long long move_cycles = 0;
  double move_drift = 0;  // m, largest block displacement during the move
  bool fell_in_move = false;  // the move itself stopped as a collapse: no hold was made
  // What the structure still travelled during the hold over what it travelled during the move
  // (a diagnostic, per step. On the cathedral with rotation it is 1.3-2 at the default loading
  // and at half its speed, and stayed above 0.25 with supports 32 times slower, so it measures
  // slow settling of parts other than those the move carries, not a lag behind the loading).
  double lag() const { return move_drift > 0 ? hold.drift / move_drift : 0.0; }
};

// The run: the model and its limits, where the loading stands, and the results as they grow.
struct Run {
  const Case& c;
  const DemSettings& s;
  const std::function<void(const RunResult&)>& on_step;
  RunResult& r;
  std::vector<Interface> joints;
  DemModel m;
  dem::Limits lim;
  // The servo's target, m per m of d: the kinetic energy a block may carry during a move, over its
  // own weight (kinetic_ratio x support travel).
  double ke_height_per_d = 0;
  double bracket = 0;  // m: the collapse bracket's width
  // Corner gaps of the settled initial configuration: hinges are measured from them.
  std::vector<double> settled_gaps;
  // The support speed at the end of the last move: the next move starts at a quarter of it, so
  // the servo need not find the structure's pace again from the floor every increment.
  double speed = 0;
  DemSnapshot last_eq;  // the last equilibrium, at d_eq
  double d_eq = 0;
  int landings = 0;  // land()'s, so far
  int index = 0;  // of the next record (0: the settled initial configuration)
  // Increments follow the grid k x step until a failure that was not confirmed moves the last
  // equilibrium off it; from there they are step long, up to max_steps x step.
  int k = 1;
  bool on_grid = true;
  std::vector<UnconfirmedFailure> unconfirmed;
  // The run's clocks, without the time spent handing out results.
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double cpu0 = thread_cpu_s();
  double io_s = 0, io_cpu_s = 0;

  Run(const Case& c_, const DemSettings& s_, const std::function<void(const RunResult&)>& f, RunResult& r_)
      : c(c_), s(s_), on_step(f), r(r_), joints(detect_interfaces(c_, c_.prd.contact_tolerance)), m(c_, s_) {}
};

// The failure that ends a stretch of increments, and the bracket around it.
struct Failure {
  Attempt attempt;
  double d = 0;       // where it failed
  double from = 0;    // the equilibrium the failed attempt started from
  DemSnapshot state;  // the failed state
  std::vector<BracketTrial> trials;
  int followed = 0;  // holds the follow stage held the failed state on
  std::string fallen_against;  // the landing came to rest against these blocks, which share no joint ("a/b")
};

// Every option as the case set it (model/options.cpp), then what the run derived from them where
// the case leaves a default, and the motion's increment.
void record_settings(Run& u) {
  const DemSettings& s = u.s;
  u.r.settings = valued_options<DemOptions>(s);
  set_setting(u.r.settings, &DemOptions::kn, u.m.kn());
  set_setting(u.r.settings, &DemOptions::ks, u.m.ks());
  set_setting(u.r.settings, &DemOptions::collapse_drift, u.lim.collapse_drift);
  set_setting(u.r.settings, &DemOptions::open_gap, s.open_gap.value_or(u.c.prd.contact_tolerance));
  u.r.settings["critical_dt"] = u.m.critical_dt();
  u.r.settings["dt"] = u.m.dt();
  u.r.settings["mass_scale"] = u.m.mass_scale();
  set_setting(u.r.settings, &Motion::step, s.step);
  set_setting(u.r.settings, &Motion::max_steps, s.max_steps);
}

// The run's own CPU and wall time so far, without handing out results.
void sync_timing(Run& u) {
  u.r.timing.cycles = u.m.cycles();
  u.r.timing.total_s = thread_cpu_s() - u.cpu0 - u.io_cpu_s;
  u.r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - u.t0).count() - u.io_s;
}

// Records the current state (after a hold) and hands the results out.
void emit(Run& u, const HoldOutcome& h, long long cycles, long long move_cycles, bool bracketing, double lag) {
  StepRecord rec = u.m.record(u.joints, u.settled_gaps);
  rec.index = u.index++;
  rec.settled = h.end == HoldEnd::equilibrium;
  DemHold& x = rec.hold.emplace();
  x.hold_end = dem::hold_end_name(h.end);
  x.bracket = bracketing;
  x.cycles = cycles;
  x.move_cycles = move_cycles;
  x.lag = lag;
  x.hold_time = h.time;
  x.unbalanced_ratio = u.m.unbalanced_ratio();
  x.max_speed = u.m.max_speed();
  x.drift = h.drift;
  x.contact_points = u.m.contact_points();
  x.max_overlap = u.m.max_overlap();
  if (h.end == HoldEnd::creep || h.end == HoldEnd::undecided) x.cap_travel = CapTravel{h.first_half, h.second_half};
  require_finite(rec);
  u.r.steps.push_back(std::move(rec));
  u.r.timing.cycles = u.m.cycles();
  if (!u.on_step) return;
  const auto a = std::chrono::steady_clock::now();
  const double a_cpu = thread_cpu_s();
  sync_timing(u);
  u.on_step(u.r);
  u.io_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
  u.io_cpu_s += thread_cpu_s() - a_cpu;
}

void emit(Run& u, const Attempt& a, bool bracketing) { emit(u, a.hold, a.cycles, a.move_cycles, bracketing, a.lag()); }

// An equilibrium reached at d: recorded, and the state to go back to.
void settled_at(Run& u, const Attempt& a, double d, bool bracketing) {
  emit(u, a, bracketing);
  u.r.capacity = u.d_eq = d;
  ++u.r.stable_steps;
  u.last_eq = u.m.save();
}

// One attempt to reach d1 from an equilibrium at d0: move, then hold (watching at least `watch`
// cycles, see dem::hold).
Attempt attempt(Run& u, double d0, double d1, long long watch = 0) {
  Attempt a;
  const long long c0 = u.m.cycles();
  // The hold's runaway scale, J: the same target for the whole structure's kinetic energy.
  u.lim.ke_collapse = 10 * (u.ke_height_per_d * u.r.total_weight) * (d1 - d0);
  u.lim.move_drift = u.lim.collapse_drift + path_travel_per_d(u.c) * (d1 - d0);
  const std::vector<Vec2> before = dem::positions(u.m, u.c);
  const dem::MoveOutcome mv = dem::move(u.m, u.c, u.s, d0, d1, u.ke_height_per_d * (d1 - d0), u.speed / 4, u.lim);
  u.speed = mv.speed;
  a.move_cycles = mv.cycles;
  a.move_drift = dem::largest_move(u.m, u.c, before);
  if (mv.collapsed) {
    a.fell_in_move = true;
    a.hold.end = HoldEnd::collapse;  // no hold: the structure fell during the move
  } else {
    u.m.set_support_parameter(d1);
    a.hold = dem::hold(u.m, u.c, u.s, u.lim, watch);
  }
  a.cycles = u.m.cycles() - c0;
  return a;
}

// Stage 1: the initial configuration settles under gravity. Only a drift ends it as a collapse:
// the kinetic energy of the first settling is no sign of one. Whether it settled.
bool settle(Run& u) {
  u.m.set_support_parameter(0);
  u.lim.ke_collapse = INFINITY;
  const HoldOutcome h0 = dem::hold(u.m, u.c, u.s, u.lim);
  if (h0.end == HoldEnd::equilibrium) u.r.capacity = 0;
  emit(u, h0, h0.cycles, 0, false, 0.0);  // absolute gaps: the settled crack pattern
  if (h0.end != HoldEnd::equilibrium) {
    // A creep at d = 0 is not taken for a collapse: with no equilibrium below it to bracket
    // against, nothing locates a limit point.
    u.r.collapsed = h0.end == HoldEnd::collapse;
    u.r.status = u.r.collapsed ? RunStatus::collapse : RunStatus::undecided;
    std::ostringstream msg;
    if (h0.end == HoldEnd::creep)
      msg << "the initial configuration neither settled nor ran away within the hold cap (" << u.s.hold_time
          << " s): it creeps without slowing down (" << h0.second_half << " m over the last half cap after " << h0.first_half << " m): no capacity";
    else if (!u.r.collapsed)
      msg << "the initial configuration neither settled nor ran away within the hold cap (" << u.s.hold_time
          << " s) and three more, its motion still dying out: no capacity; a longer dem.hold_time may settle it";
    else
      msg << "the initial configuration does not stand: it collapsed while settling under gravity at d = 0, before any support "
             "motion: no capacity";
    u.r.message = msg.str();
    return false;
  }
  u.settled_gaps = u.m.corner_gaps(u.joints);
  u.last_eq = u.m.save();
  u.d_eq = 0;
  return true;
}

// Stage 2: increments, each a move and a hold, from the last equilibrium, until one fails
// (returned) or the path ends (nothing).
std::optional<Failure> increments(Run& u) {
  // Off the grid (after an unconfirmed failure or a landing) the last increment is what is left
  // to the path's end, so a run that stands reaches d_end as PRD's does.
  const double d_end = u.s.max_steps * u.s.step;
  while (u.on_grid ? u.k <= u.s.max_steps : d_end - u.d_eq > 1e-9 * u.s.step) {
    const double d1 = u.on_grid ? u.k * u.s.step : std::min(u.d_eq + u.s.step, d_end);
    ++u.k;
    const Attempt a = attempt(u, u.d_eq, d1);
    if (a.hold.end != HoldEnd::equilibrium) {
      Failure f;
      f.attempt = a;
      f.d = d1;
      f.from = u.d_eq;
      f.trials.push_back({d1, dem::hold_end_name(a.hold.end), a.cycles});
      f.state = u.m.save();
      return f;
    }
    settled_at(u, a, d1, false);
  }
  return std::nullopt;
}

// Stage 3: the collapse bracket. Back to the last equilibrium, halve the failed increment until
// the bracket is narrower than bracket_fraction x step. A trial that does not settle (collapse
// or undecided) moves the upper end; one that settles is a recorded equilibrium and moves the
// lower end.
void bracket(Run& u, Failure& f) {
  while (u.bracket > 0 && f.d - u.d_eq > u.bracket) {
    u.m.restore(u.last_eq);
    u.speed = 0;
    const double mid = 0.5 * (u.d_eq + f.d);
    const Attempt a = attempt(u, u.d_eq, mid);
    f.trials.push_back({mid, dem::hold_end_name(a.hold.end), a.cycles});
    if (a.hold.end == HoldEnd::equilibrium) {
      settled_at(u, a, mid, true);
    } else {
      f.attempt = a;
      f.d = mid;
      f.from = u.d_eq;
      f.state = u.m.save();
    }
  }
}

// Stage 4 (DemSettings::confirm_collapse): confirm the collapse. The failure at f.d was reached
// by a move from f.from; if the bracket's lower end has moved up since, the collapse must also
// follow from the last equilibrium by a move shorter than the bracket. Where it does not, the
// longer move's own dynamics tipped the structure over (every trial below f.d settling is the
// sign: the failure sits on the increment grid), so f.d is an equilibrium, not the capacity,
// and the increments go on from there. Whether it was confirmed.
bool confirm(Run& u, Failure& f) {
  if (!u.s.confirm_collapse || u.bracket <= 0 || f.from >= u.d_eq) return true;
  u.m.restore(u.last_eq);
  u.speed = 0;
  // The confirming hold does not end at the first equilibrium: past an unstable one the
  // structure starts from rest, so the hold watches four times as long as the failure took to
  // show itself (at most the cap) before it calls the state settled. (A perturbation 100 times
  // smaller, a move under 1% of the step, takes ln 100 = 4.6 more growth times to reach the
  // same size.)
  const Attempt a = attempt(u, u.d_eq, f.d, 4 * f.attempt.hold.cycles);
  f.trials.push_back({f.d, dem::hold_end_name(a.hold.end), a.cycles, true});
  if (a.hold.end == HoldEnd::equilibrium) {
    u.unconfirmed.push_back({f.d, f.from, u.d_eq});
    settled_at(u, a, f.d, true);
    u.on_grid = false;
    return false;
  }
  f.attempt = a;
  f.from = u.d_eq;  // the failed attempt now starts there
  f.state = u.m.save();
  return true;
}

// The failed state, the supports at its d, held on from where it stands (stages 5 and 6): only a
// drift of collapse_drift from there calls a collapse, not the kinetic energy's rise over the
// hold's windows, nor the reading of a slow collapse from a tenth of that drift, since a hinge
// passing to another joint gains energy and moves that far, speeding up, before it lands (as the
// settling at d = 0, which only a drift ends). Returns where it stood.
std::vector<Vec2> from_failed_state(Run& u, const Failure& f) {
  u.m.restore(f.state);
  u.m.set_support_parameter(f.d);
  u.lim.ke_collapse = INFINITY;
  return dem::positions(u.m, u.c);
}
HoldOutcome hold_on(Run& u, const std::vector<Vec2>& here, long long watch) {
  u.lim.read_early = false;
  const HoldOutcome h = dem::hold(u.m, u.c, u.s, u.lim, watch, &here);
  u.lim.read_early = true;
  return h;
}

// A failure held on that settled: another branch. The record counts the whole attempt's cycles;
// its hold is the one that settled; the increments go on from there, off the grid.
void settled_on_another_branch(Run& u, Failure& f, const HoldOutcome& h, long long cycles) {
  f.attempt.hold = h;
  f.attempt.cycles += cycles;
  settled_at(u, f.attempt, f.d, true);
  u.on_grid = false;
}

// Stage 5: the creep at the bracket's upper end held on. A bracket that closes on an upper end
// that creeps, and speeds up, has found a limit point of the branch the structure was on; that is
// its capacity only where no other equilibrium lies within reach. A hinge that passes from one
// joint to another (the old one closing as the new one opens) takes the structure through a
// mechanism over a finite motion to another branch, and starts from rest at the limit, so it can
// take longer than the cap: on a segmental arch whose joints are stiff against its weights
// (density 2 kg/m^3) the hinge passing from joint 1 to joint 7 took 74 s from rest to settle, and
// the run ended on a "limit point" at 0.106 m where the structure stands and goes on to 0.32 m
// (dem/README.md, "Protocol", stage 5). So the creeping state is held on, a hold at a time, while
// it speeds up: it ends in an equilibrium (another branch: recorded, and the increments go on from
// there, off the grid), in a collapse (located), or, once it no longer speeds up or after
// kFollowHolds holds, the bracket's verdict stands. Whether the run goes on.
bool follow(Run& u, Failure& f) {
  if (f.attempt.hold.end != HoldEnd::creep) return false;
  const std::vector<Vec2> here = from_failed_state(u, f);
  HoldOutcome h = f.attempt.hold;
  long long cycles = 0;
  double time = 0;
  while (f.followed < kFollowHolds && h.end == HoldEnd::creep && h.second_half > h.first_half) {
    const long long c0 = u.m.cycles();
    h = hold_on(u, here, 0);
    ++f.followed;
    cycles += u.m.cycles() - c0;
    time += h.time;
    f.trials.push_back({f.d, dem::hold_end_name(h.end), u.m.cycles() - c0, false, true});
  }
  if (h.end == HoldEnd::equilibrium) {
    u.r.settled_creeps.push_back({f.d, f.followed, time});
    settled_on_another_branch(u, f, h, cycles);
    return true;
  }
  if (h.end == HoldEnd::collapse) {
    f.attempt.hold = h;
    f.attempt.cycles += cycles;
    f.state = u.m.save();
  }
  // Otherwise (still creeping, or slowing down without settling) the bracket's verdict stands,
  // with the state it found: the followed holds are in its trials.
  return false;
}

// Stage 6: a collapse at the bracket's upper end held on once more, from where it stands. A drift
// of collapse_drift within a hold calls a collapse, but a structure can also snap through: a hinge
// passing to another joint carries it over a finite motion, speeding up, to an equilibrium on
// another branch. When that motion is longer than collapse_drift, the drift alone reads a landing
// as a fall: the pointed arch of eccentricity 0.3 whose support settles outwards snaps at 0.369 m,
// its blocks moving 46 mm in one 1 mm step of PRD (2.2% of the scene), and the DEM called that a
// collapse at 0.373 m where PRD goes on to 0.585 m (and the DEM too, at 0.584 m, with a drift
// limit of 0.4 m). So a collapse is a drift of collapse_drift that does not come to rest within
// another collapse_drift: the failed state is held on, and only a drift of collapse_drift from
// there calls the collapse (from_failed_state: a snap gains energy and speeds up before it
// lands, as the follow stage's hinges do). Where it settles without
// pressing on a face it was not cut against, the structure stands on the other branch: recorded
// (settled_snaps), and the increments go on from there, off the grid. Otherwise the collapse
// stands, with the state the bracket found. A failure during the move is not held on: its
// supports stopped short of f.d. Whether the run goes on.
bool land(Run& u, Failure& f) {
  if (f.attempt.hold.end != HoldEnd::collapse || f.attempt.fell_in_move || u.landings >= kMaxLandings) return false;
  // The last equilibrium's positions (how far a snap carries the blocks) and its contacts off the
  // case's joints (a landing may keep these, not add to them), read from its snapshot.
  u.m.restore(u.last_eq);
  const std::vector<Vec2> eq_positions = dem::positions(u.m, u.c);
  const std::vector<std::pair<int, int>> eq_off_joints = u.m.off_joint_contacts(u.joints);
  const std::vector<Vec2> here = from_failed_state(u, f);
  const long long c0 = u.m.cycles();
  // As the confirming hold: a rest is taken only after four times as long as the failure took
  // to show itself (at most the cap), since the motion may pass through rest at an unstable state.
  const HoldOutcome h = hold_on(u, here, 4 * f.attempt.hold.cycles);
  const long long cycles = u.m.cycles() - c0;
  // A snap passes along the structure's own joints (a hinge closes, another opens), as PRD's
  // step does, which keeps contact only at the joints it started from; a part that comes to rest
  // on a face it was not cut against, touching a block it was not touching at the last
  // equilibrium, has fallen there: a collapse.
  if (h.end == HoldEnd::equilibrium) {
    for (const auto& p : u.m.off_joint_contacts(u.joints))
      if (!std::binary_search(eq_off_joints.begin(), eq_off_joints.end(), p)) {
        f.fallen_against = printable(u.c.blocks[size_t(p.first)].id) + "/" + printable(u.c.blocks[size_t(p.second)].id);
        break;
      }
  }
  const bool landed = h.end == HoldEnd::equilibrium && f.fallen_against.empty();
  const HoldEnd shown = landed || h.end != HoldEnd::equilibrium ? h.end : HoldEnd::collapse;  // a rest against such a face is a fall
  f.trials.push_back({f.d, dem::hold_end_name(shown), cycles, false, true});
  if (!landed) return false;
  ++u.landings;
  u.r.settled_snaps.push_back({f.d, u.d_eq, dem::largest_distance(eq_positions, dem::positions(u.m, u.c), u.c), h.time});
  settled_on_another_branch(u, f, h, cycles);
  return true;
}

// The end of a located failure: the failed state nearest the capacity closes the record.
void close(Run& u, const Failure& f) {
  u.m.restore(f.state);
  emit(u, f.attempt, u.bracket > 0);
  u.r.collapse_bracket = CollapseBracket{u.d_eq, f.d, f.d - u.d_eq, f.trials};
  // A collapse shown anywhere beyond the capacity makes the run a collapse. So does a limit point
  // located within the bracket: the last equilibrium lies within the bracket's width of a state
  // that creeps without slowing down (dem::HoldEnd::creep), which is how a structure just past
  // its limit point moves, since the growth of its collapse mode tends to zero there (the
  // pointed arch's limit, say, is reached with no runaway to see). A located collapse needs no
  // runaway, only that no equilibrium was found at the bracket's upper end.
  bool any_collapse = false;
  for (const auto& t : f.trials) any_collapse = any_collapse || t.end == "collapse";
  const double width = f.d - u.d_eq;
  const bool limit_point = f.attempt.hold.end == HoldEnd::creep && width <= (u.bracket > 0 ? u.bracket : u.s.step) * (1 + 1e-9);
  u.r.collapsed = any_collapse || limit_point;
  u.r.status = u.r.collapsed ? RunStatus::collapse : RunStatus::undecided;
  std::ostringstream msg;
  const std::string unit = path_unit(u.c);  // d's: rad where the supports only turn
  if (!any_collapse && limit_point) {
    msg << "limit point: no equilibrium at d = " << f.d << " " << unit << ", which creeps without slowing down (" << f.attempt.hold.second_half
        << " m over the last half cap after " << f.attempt.hold.first_half << " m";
    if (f.followed > 0) msg << "; held on " << f.followed << " more hold" << (f.followed > 1 ? "s" : "") << " without settling";
    msg << "), " << width << " " << unit << " past the last equilibrium";
    u.r.limit_point = true;
  } else if (u.r.collapsed && !f.fallen_against.empty()) {
    msg << "the collapse at d = " << f.d << " " << unit << " came to rest when held on, but against " << f.fallen_against
        << ", blocks that share no joint and did not touch at the last equilibrium: a fall, not a snap through (dem/README.md, "
           "\"Protocol\", stage 6)";
  } else if (u.r.collapsed && u.landings >= kMaxLandings && f.attempt.hold.end == HoldEnd::collapse && !f.attempt.fell_in_move) {
    msg << "the run landed " << u.landings << " snaps through already, the most it holds on (dem/README.md, \"Protocol\", stage 6): "
        << "the collapse at d = " << f.d << " " << unit << " was not held on";
  } else if (!u.r.collapsed) {
    // The bracket stops narrowing at its tolerance, or where a trial could not be decided.
    const double tolerance = u.bracket > 0 ? u.bracket : u.s.step;
    msg << "the hold at d = " << f.d << " " << unit << " neither settled nor ran away within the hold cap (" << u.s.hold_time << " s"
        << (f.attempt.hold.end == HoldEnd::creep ? "): it creeps without slowing down" : ") and three more: its motion still dying out")
        << "; the collapse bracket [" << u.d_eq << ", " << f.d << "] " << unit
        << (width > tolerance * (1 + 1e-9) ? " is wider than its tolerance" : "'s upper end stayed undecided") << ": the capacity " << u.d_eq
        << " " << unit << " is the last equilibrium, not a located collapse";
  }
  u.r.message = msg.str();
}

}  // namespace

namespace {
// Every recorded state is a hold that settled, and a hold with local damping settles by that
// damping alone: at 0 nothing takes energy out of it (a block on its elastic joints rocks for
// ever, and each contact's opening and closing between cycles adds a little energy that then
// stays), so no hold can settle and the run could only end undecided or in the blow-up guard.
// Kinetic holds stop the blocks at each peak of the kinetic energy, and do settle.
void check_hold_damping(const Case& c, const DemSettings& s) {
  if (s.damping == 0 && s.hold_damping == HoldDamping::local)
    throw CaseError(c.source + ": dem: field '" + option_of(&DemOptions::damping).name + "' = 0 with " + option_key(&DemOptions::hold_damping) +
                    " local: nothing takes energy out of a hold, so none can settle (an undamped block rocks on its elastic joints for ever, "
                    "and the contacts' opening and closing between cycles add energy); set it above 0 (default 0.8) or " +
                    option_key(&DemOptions::hold_damping) + " kinetic");
}
}  // namespace

void dem_check(const Case& c, const DemSettings& s) {
  check_hold_damping(c, s);
  const DemModel m(c, s);  // the model's own refusals: settings, time step, joints too soft
}

RunResult dem_run(const Case& c, const DemSettings& s, const std::function<void(const RunResult&)>& on_step) {
  check_hold_damping(c, s);
  RunResult r;
  r.method = method_name(Method::dem);
  r.case_name = c.name;
  r.total_weight = total_weight(c);
  Run u(c, s, on_step, r);
  for (const Interface& J : u.joints) r.joints.push_back({J.i, J.j, J.a, J.b});
  // A block that travels 2% of the scene during a hold, with the supports at rest, and does not
  // come to rest within as much again (land()), has left its equilibrium for good. Smaller drifts
  // are not evidence: a hinge that jumps to another joint snaps the pointed arch by 8.4 mm (0.4%
  // of its size) to a new equilibrium near d = 0.094 m.
  u.lim.collapse_drift = s.collapse_drift > 0 ? s.collapse_drift : 0.02 * scene_size(c);
  u.lim.energy_floor = 1e-9 * r.total_weight * scene_size(c);
  u.lim.creep_floor = std::max(0.01 * c.prd.contact_tolerance, 1e-9 * scene_size(c));
  u.ke_height_per_d = s.kinetic_ratio * path_travel_per_d(c);
  u.lim.move_accel = kMoveAccel * kReferenceGravity / path_travel_per_d(c);
  u.bracket = s.bracket_fraction * s.step;
  record_settings(u);
  try {
    if (settle(u)) {
      for (;;) {
        std::optional<Failure> f = increments(u);
        if (!f) {
          // Only now: the results handed out on the way say "running", so a run stopped from
          // outside does not look finished.
          r.status = RunStatus::max_steps;
          break;
        }
        bracket(u, *f);
        if (!confirm(u, *f)) continue;
        if (follow(u, *f)) continue;
        if (land(u, *f)) continue;
        close(u, *f);
        break;
      }
      r.unconfirmed_failures = u.unconfirmed;
    }
  } catch (const std::exception& e) {
    r.status = RunStatus::error;
    r.message = e.what();
  }
  sync_timing(u);
  return r;
}

}  // namespace masonry
