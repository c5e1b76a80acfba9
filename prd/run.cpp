// PRD: prd_check and the run loop. One GLPK problem per run (lp.cpp), rows and bounds rewritten in
// place each step.
// The LP itself (variables and rows) is described at the top of lp.cpp.
#include <stdexcept>

#include "model/options.hpp"
#include "prd/glpk_hooks.hpp"
#include "prd/internal.hpp"

namespace masonry {

using namespace prd_detail;

PrdSettings PrdSettings::from_case(const Case& c) {
  PrdSettings s;
  static_cast<PrdOptions&>(s) = c.prd;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  return s;
}

const char* start_offsets_name(StartOffsets o) { return o == StartOffsets::keep ? "keep" : "take-back"; }

PrdCheck prd_check(const Case& c, double contact_tolerance) {
  prd::install_glpk_hooks();
  Model m = build_model(c, contact_tolerance);
  m.first_basis = FirstBasis::advanced;
  PrdCheck out;
  out.joints = joint_infos(m);
  out.total_weight = total_weight(*m.c);
  const double scale = std::max(scene_size(c), 1e-12) * 1e-3;
  update_lp(m, 0.0, scale);
  const LpStatus status = m.ncols == 0 ? LpStatus::optimal : solve(m);
  out.state.poses = poses(m);
  if (status == LpStatus::optimal) {
    out.stable = true;
    out.energy_rate = objective(m) * scale;
    read_forces(m, out.state);
    lp_check_fields(m, scale, out.state);
  } else if (status == LpStatus::unbounded) {
    out.stable = false;
    out.collapse = collapse_mechanism(m, scale);
    out.mechanism.assign(c.blocks.size(), Pose{});
    for (size_t b = 0; b < c.blocks.size(); ++b)
      if (m.col[b] > 0) out.mechanism[b] = {col_value(m, m.col[b]), col_value(m, m.col[b] + 1), col_value(m, m.col[b] + 2) / m.radius[b]};
  } else {
    throw std::runtime_error(c.source + ": the analysis LP is infeasible (blocks overlap beyond the tolerance?)");
  }
  return out;
}

namespace {

// The run loop's state: the LP model, and where the walk along d stands. The record of
// configuration d_k is completed by the LP solved on it (with the increment to d_{k+1}): its
// duals are the forces in equilibrium on d_k, and a bounded optimum is what makes d_k stable.
// An unbounded LP on d_k means d_k admits a collapse mechanism: the capacity is then d_{k-1},
// the last configuration with an admissible force state.
//
// Events (adaptive runs; a fixed run is the same loop with every move one step long).
//  - Opening or collapse: a property of the configuration the LP is solved on: seen on d_k,
//    it happened in (d_{k-1}, d_k]. Moves are planned so that this bracket is within the
//    tolerance: the forces' trend on the current basis (from the previous configurations on
//    it) guesses where one of them reaches 0, the basis evaluated where the move would end
//    corrects the guess (plan_move), and the run stops half a tolerance short of the zero,
//    then steps half a tolerance past. A longer bracket is closed by going back
//    to d_{k-1}, to where its basis's forces, interpolated to d_k, reach 0, or else half way
//    (no LP is needed for the move back), until it is within the tolerance.
//  - Closing: found on the move itself: the move stops where the first open corner's gap
//    reaches the contact tolerance. Only a corner that the LP already holds at its bound
//    (closing within the tolerance) closes at the end of a move.
//  - An opening seen where a move stopped at a closing, while the previous basis still holds
//    there, is the closing's consequence and is located with it.
//  - A corner whose force reached 0 without the mechanism changing (a statically
//    indeterminate part's duals are one admissible force state of many) is left out of the
//    predictions once the run has stepped past its predicted opening.
// Moves follow the mechanism and its rate of change (Path), so that long moves stay on the
// path of ever smaller fixed steps.
struct Walk {
  // For the whole run.
  const PrdSettings& s;
  double h_ref = 0;   // the fixed step, m
  double tol_ev = 0;  // how closely events are located, m (a fixed run: one step)
  double h_max = 0;   // the longest move, m
  double d0 = 0;      // where the loading path starts, m (PrdStart)
  double d_end = 0;   // the end of the loading path, m
  Model m;
  SlidingLp sliding;
  // Where the walk stands.
  Accepted cur;
  std::optional<Accepted> prev, prev2;  // the last accepted configurations, newest first
  StepRecord rec;                       // cur's record, completed when cur is accepted
  double h_in = 0;                      // the move that led to cur
  double h_plan = 0;                    // the step the next LP is solved for
  // Bracketing an event: the d where it was seen, not yet located (nothing: moving along the
  // path, no event pending).
  std::optional<double> seen;
  std::optional<double> crossing;         // where the previous basis's forces were estimated to reach 0, m
  std::optional<double> arrived_closing;  // the move to cur ended where a corner closed: located within this, m
  std::optional<size_t> passing;          // the corner the move to cur was to take past its predicted opening
  std::vector<char> ignored;              // corners left out of the predictions (above)
  std::vector<double> gap, rate;          // cur's corner gaps and their rates, from its LP

  Walk(const Case& c, const PrdSettings& settings) : s(settings), m(build_model(c, settings.contact_tolerance)) {
    // A fixed-step run is the event-driven one with every step accepted: the step never
    // changes and no event is bracketed more finely than one step.
    h_ref = s.step;
    m.kept_basis_allowed = !s.adaptive;
    // The defaults are lengths of the scene; where d is an angle (every moving support only
    // turns) they are the turn that moves the scene's points by that length (its lever, as
    // support_travel_per_d counts it), so that a tilt's events do not depend on the scene's size.
    const double L = scene_size(c), per_d = path_unit(c) == "rad" ? support_travel_per_d(c) : 1.0;
    tol_ev = !s.adaptive ? h_ref : s.event_tolerance > 0 ? s.event_tolerance : 1e-4 * L / per_d;
    // The longest move. A move's path error (second order, see Path) grows as the square of
    // its length against the scene's, so the default keeps it within the event tolerance:
    // 0.4 sqrt(tolerance x scene size), 1/250 of the scene at the default tolerance.
    h_max = !s.adaptive ? h_ref : std::max(s.max_step > 0 ? s.max_step : std::min(16 * h_ref, 0.4 * std::sqrt(tol_ev * per_d * L) / per_d), tol_ev);
    if (s.start) {
      start_from(m, *s.start);
      d0 = s.start->d;
    }
    cur.d = d0;
    d_end = d0 + s.max_steps * h_ref;
    h_plan = h_ref;
    hold_corners(m, s.hold_closed);
    // A held corner never opens, whatever its force does: no event to predict.
    ignored.assign(m.ends.size(), 0);
    for (size_t e = 0; e < m.ends.size(); ++e) ignored[e] = m.ends[e].held;
    rec = configuration_record(m, 0, d0);
  }

  // Whether the loading path goes on beyond d.
  bool before_end(double d) const { return d_end - d > 1e-9 * h_ref; }
  // A move stops half a tolerance short of a predicted opening, and the next one goes half a
  // tolerance past it, so that it is bracketed within the tolerance without bisection.
  double land(double x) const { return x > tol_ev ? x - tol_ev / 2 : std::min(x + tol_ev / 2, tol_ev); }
  // Inside a bracket (an event seen at `seen`, not yet located), the move from d: to land by
  // the estimated crossing while it lies ahead, else to halve the bracket; once the bracket is
  // within the tolerance, to its end.
  double toward_event(double d) const {
    const double left = *seen - d;
    if (left <= tol_ev) return left;
    if (crossing) {
      const double x = *crossing - d;
      if (x > 0 && x < left) return std::min(land(x), left - tol_ev / 2);
    }
    return left / 2;
  }
};

// What the LP solved on the current configuration says.
struct Solved {
  LpStatus status = LpStatus::optimal;
  double h = 0, h_open = 0;             // the step it was solved for; open corners held over h_open
  std::vector<size_t> opened, closing;  // corners whose contact state it changes
};

// The move from an accepted configuration.
struct Step {
  double h = 0;
  Closing shut;  // a closing the move is cut short at
  Move planned;  // the opening the move was planned against
};

// Stage "solve here": the LP for the step planned, with open corners held over the event
// tolerance only: a corner that closes later in the step cuts the move short where it closes
// (on the exact motion), so the LP's mechanism is the one of this configuration.
Solved solve_here(Walk& w) {
  Solved sv;
  sv.h = w.h_plan;
  sv.h_open = std::min(sv.h, w.tol_ev);
  update_lp(w.m, sv.h, sv.h, sv.h_open);
  sv.status = w.m.ncols == 0 ? LpStatus::optimal : solve(w.m);
  if (sv.status == LpStatus::optimal) {
    gaps_and_rates(w.m, sv.h, sv.h_open, w.gap, w.rate);
    const std::vector<char> next = closed_after(w.m, w.gap, w.rate, sv.h, sv.h_open, w.h_ref);
    for (size_t e = 0; e < w.m.ends.size(); ++e)
      if (w.m.ends[e].closed != next[e]) (next[e] ? sv.closing : sv.opened).push_back(e);
  }
  return sv;
}

// Stage "event behind": whether an event (collapse or opening) seen at the end of a move longer
// than the tolerance must be located by going back. Not when the move ended where a corner
// closed and the previous mechanism held all the way (its basis is still the optimum here,
// that corner aside): then the closing set the event off, and it is located with the closing.
// The probe of the previous basis changes the LP; this stage puts back what the walk needs.
bool event_behind(Walk& w, const Solved& sv) {
  bool back = (sv.status == LpStatus::unbounded || !sv.opened.empty()) && w.prev && w.h_in > w.tol_ev * (1 + 1e-9);
  if (!back || !w.s.adaptive) return back;
  const Accepted& p = *w.prev;
  Accepted here;
  save_basis(w.m, here);
  here.closed.resize(w.m.ends.size());
  for (size_t e = 0; e < w.m.ends.size(); ++e) here.closed[e] = w.m.ends[e].closed;
  const std::optional<double> x = basis_crossing(w.m, p, w.cur.d - p.d, w.tol_ev);
  set_closed(w.m, here.closed);
  w.crossing = x ? std::optional<double>(p.d + *x) : std::nullopt;
  if (x && !std::isfinite(*x) && w.arrived_closing) {
    back = false;
    w.h_in = *w.arrived_closing;
    // This configuration's own basis back in the LP, for the stages that read it.
    if (evaluate_basis(w.m, here, sv.h, sv.h_open) != 0) throw std::runtime_error("GLPK could not restore the step's basis");
  }
  return back;
}

// Stage "go back": to the last accepted configuration, and from there to where the previous
// basis's forces, interpolated between there and here, reach 0 (half way when they do not
// tell).
void go_back(Walk& w) {
  w.seen = w.cur.d;
  const Accepted& p = *w.prev;
  w.m.cen = p.cen;
  w.m.angle = p.angle;
  set_closed(w.m, p.closed);
  for (size_t e = 0; e < w.m.ends.size(); ++e) w.m.ends[e].X = p.X[e], w.m.ends[e].Xj = p.Xj[e];
  w.h_in = w.toward_event(p.d);
  const std::vector<char> closed = closed_after(w.m, p.gap, p.rate, p.h_lp, w.h_in, w.h_ref);
  advance(w.m, Path{p.U, p.dU}, w.h_in);
  close_corners(w.m, closed);
  w.cur.d = p.d + w.h_in;
  w.cur.index = p.index + 1;
  w.rec = configuration_record(w.m, w.cur.index, w.cur.d);
  w.h_plan = w.toward_event(w.cur.d);
  w.arrived_closing.reset();
}

// Stage "collapse": the LP on cur is unbounded; its mechanism is the collapse.
void record_collapse(Walk& w, const Solved& sv, RunResult& r) {
  r.collapsed = true;
  r.status = RunStatus::collapse;
  r.collapse = Collapse{};
  r.collapse->mechanism = collapse_mechanism(w.m, sv.h, &r.collapse->moved_poses);
  r.collapse->d = w.cur.d;
  r.collapse->poses = w.rec.poses;
  // The collapse event names the corners its mechanism opens, as an opening event does.
  Event ev = make_event(w.m, EventKind::collapse, w.cur.d, w.h_in, {});
  ev.corners = r.collapse->mechanism.open_corners;
  r.events->push_back(ev);
  if (!w.prev) r.message = "unstable as it stands";
}

// Stage "accept": cur stands; its record gets the LP's forces, and cur keeps what the next
// move and a later going back need.
void accept(Walk& w, const Solved& sv, RunResult& r) {
  Model& m = w.m;
  // A corner the move was to take past its predicted opening that is still closed has a force
  // that reached 0 without changing the mechanism (a statically indeterminate part's dual
  // forces are one admissible state of many): it is left out of the predictions from here on,
  // and should it open after all, the LP sees it.
  if (w.passing && m.ends[*w.passing].closed && sv.opened.empty() && !w.ignored[*w.passing]) w.ignored[*w.passing] = 1;
  w.passing.reset();
  read_forces(m, w.rec);
  record_held(m, w.rec);
  lp_check_fields(m, sv.h, w.rec);
  if (w.s.sliding_check) sliding_check(m, w.sliding, w.rec);
  require_finite(w.rec);
  r.steps.push_back(w.rec);
  r.capacity = w.cur.d;
  r.stable_steps = w.cur.index;
  // An event seen on the way here that did not recur at the same d (the way there differed)
  // is over.
  if (w.seen && *w.seen - w.cur.d <= 1e-9 * w.h_ref) w.seen.reset();
  if (!sv.opened.empty()) {
    r.events->push_back(make_event(m, EventKind::open, w.cur.d, w.h_in, sv.opened));
    w.seen.reset();
  }
  Accepted& cur = w.cur;
  cur.cen = m.cen;
  cur.angle = m.angle;
  cur.U = column_values(m);
  cur.gap = w.gap;
  cur.rate = w.rate;
  cur.h_lp = sv.h;
  cur.closed.resize(m.ends.size());
  cur.X.resize(m.ends.size());
  cur.Xj.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) cur.closed[e] = m.ends[e].closed, cur.X[e] = m.ends[e].X, cur.Xj[e] = m.ends[e].Xj;
  cur.fn.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) cur.fn[e] = corner_force(m, e);
  cur.same = sv.opened.empty() && sv.closing.empty();
  cur.dU.clear();
  save_basis(m, cur);
}

// Whether the run has reached the end of its path at cur.
bool path_done(const Walk& w) { return w.s.adaptive ? !w.before_end(w.cur.d) : w.cur.index == w.s.max_steps; }

// The first guess of an adaptive move with no event pending and no corner closing: the forces'
// trend, when the previous configurations had the same mechanism (their chord, with its
// curvature when there are three), checked by plan_move on the basis where the move would end.
Move plan_on_trend(Walk& w, const Solved& sv) {
  const Model& m = w.m;
  const Accepted& cur = w.cur;
  const auto on_same = [](const std::optional<Accepted>& a, const Accepted& b) {
    return a && a->same && b.same && a->closed == b.closed && b.d > a->d;
  };
  std::vector<double> slope, curve;
  double x = sv.h;
  Move guess;
  if (on_same(w.prev, cur)) {
    const Accepted& prev = *w.prev;
    slope.resize(m.ends.size());
    for (size_t e = 0; e < m.ends.size(); ++e) slope[e] = (cur.fn[e] - prev.fn[e]) / (cur.d - prev.d);
    if (on_same(w.prev2, prev)) {
      const Accepted& prev2 = *w.prev2;
      curve.resize(m.ends.size());
      for (size_t e = 0; e < m.ends.size(); ++e) {
        curve[e] = (slope[e] - (prev.fn[e] - prev2.fn[e]) / (prev.d - prev2.d)) / (cur.d - prev2.d);
        slope[e] += curve[e] * (cur.d - prev.d);  // at cur
      }
    }
    guess = predict_opening(cur, slope, curve, w.ignored);
    x = std::min(x, w.land(guess.to_open));
  }
  if (w.before_end(cur.d)) x = std::min(x, w.d_end - cur.d);
  return plan_move(w.m, w.cur, sv.h, sv.h_open, x, guess, slope, w.ignored, 2 * w.tol_ev, [&w](double y) { return w.land(y); });
}

// Stage "plan": how far to move from cur (a fixed run: one step), and the step the next LP is
// solved for.
Step plan(Walk& w, const Solved& sv) {
  Step st;
  st.h = sv.h;
  if (!w.s.adaptive) return st;
  if (w.seen) {
    st.h = std::min(sv.h, w.toward_event(w.cur.d));
  } else if (sv.closing.empty()) {
    st.planned = plan_on_trend(w, sv);
    st.h = st.planned.h;
  }
  if (w.before_end(w.cur.d)) st.h = std::min(st.h, w.d_end - w.cur.d);
  if (!sv.closing.empty()) {
    st.h = std::min(st.h, sv.h_open);  // the LP holds the closing corner at the end of it
  } else {
    st.shut = first_closing(w.m, Path{w.cur.U, w.cur.dU}, w.gap, w.rate, st.h);
    if (std::isfinite(st.shut.at)) st.h = st.shut.at;
  }
  if (st.planned.to_open <= st.h && st.planned.corner >= 0) w.passing = static_cast<size_t>(st.planned.corner);
  // The next LP's step: inside a bracket, the next move in it; else as long as allowed, the
  // predictions cutting the move short.
  w.h_plan = w.h_max;
  if (w.seen && *w.seen - w.cur.d - st.h > 1e-9 * w.h_ref) w.h_plan = w.toward_event(w.cur.d + st.h);
  return st;
}

// Stage "take": the move along cur's path, and the contact state where it ends.
void take(Walk& w, const Solved& sv, const Step& st, RunResult& r) {
  if (!(st.h > 0)) throw std::logic_error("prd: the step came to a stop at d = " + std::to_string(w.cur.d) + " " + path_unit(*w.m.c));
  Model& m = w.m;
  w.prev2 = std::move(w.prev);
  w.prev = w.cur;
  advance(m, Path{w.cur.U, w.cur.dU}, st.h);
  std::vector<char> closed = closed_after(m, w.gap, w.rate, sv.h, st.h, w.h_ref);
  if (std::isfinite(st.shut.at)) closed[st.shut.corner] = 1;
  // The rates predict the gaps to first order; a corner's gap is what the finite move left,
  // and one within the tolerance is closed by the tolerance's definition (an open corner left
  // a fraction of a micrometre from contact can make the next LP infeasible: a start from a
  // DEM's settled state, with gaps of 1e-6..1e-4 m at many corners, did).
  for (size_t e = 0; e < m.ends.size(); ++e)
    if (!m.ends[e].closed && m.gap(m.ends[e]) <= m.tol) closed[e] = 1;
  std::vector<size_t> shut_now;
  for (size_t e = 0; e < m.ends.size(); ++e)
    if (closed[e] && !m.ends[e].closed) shut_now.push_back(e);
  close_corners(m, closed);
  if (!shut_now.empty()) {
    const bool exact = std::isfinite(st.shut.at) && shut_now.size() == 1;
    r.events->push_back(make_event(m, EventKind::close, w.cur.d + st.h, exact ? st.shut.within : st.h, shut_now));
  }
  w.h_in = st.h;
  w.arrived_closing = std::isfinite(st.shut.at) ? std::optional<double>(st.shut.within) : std::nullopt;
  w.cur.index += 1;
  w.cur.d = w.s.adaptive ? w.prev->d + st.h : w.d0 + w.cur.index * w.h_ref;
  w.rec = configuration_record(m, w.cur.index, w.cur.d);
}

}  // namespace

FirstStep prd_first_step(const Case& c, double contact_tolerance, double h, const std::vector<std::string>& held_closed) {
  prd::install_glpk_hooks();
  if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("prd: the step must be a positive number");
  Model m = build_model(c, contact_tolerance);
  m.first_basis = FirstBasis::advanced;
  const std::vector<int> nth = pair_ordinals(m.joints);
  auto name = [&](size_t e) {
    const Interface& jt = m.joints[m.ends[e].joint];
    return corner_name(c, jt.i, jt.j, m.ends[e].corner, nth[size_t(m.ends[e].joint)]);
  };
  hold_corners(m, held_closed);
  // As the run's first step: the LP for a step h, open corners (none at the start) over h.
  update_lp(m, h, h, h);
  FirstStep out;
  const LpStatus st = m.ncols == 0 ? LpStatus::optimal : solve(m);
  if (st == LpStatus::infeasible)
    throw std::runtime_error(c.source + ": the first step's LP is infeasible (the held corners cannot all stay closed)");
  out.bounded = st == LpStatus::optimal;
  if (!out.bounded) return out;
  // The columns are the increments over the step in units of h: the objective is the loads'
  // potential energy change per unit of h.
  out.energy_change = objective(m) * h;
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const double opening = corner_slack(m, e) * h;
    if (opening > 1e-6 * h) out.opening.push_back({name(e), opening});
  }
  return out;
}

RunResult prd_run(const Case& c, const PrdSettings& s, const std::function<void(const RunResult&)>& on_step) {
  prd::install_glpk_hooks();
  if (!(s.step > 0) || !std::isfinite(s.step)) throw std::invalid_argument("prd: the step must be a positive number");
  if (s.max_steps < 0) throw std::invalid_argument("prd: max_steps must not be negative");
  if (!(s.contact_tolerance > 0)) throw std::invalid_argument("prd: the contact tolerance must be positive");
  if (!std::isfinite(s.event_tolerance) || !std::isfinite(s.max_step))
    throw std::invalid_argument("prd: the event tolerance and the largest step must be finite");
  const auto t_start = cpu_now();
  double io_s = 0;
  RunResult r;
  r.method = method_name(Method::prd);
  r.case_name = c.name;
  Walk w(c, s);
  r.capacity = w.d0;  // a start that is unstable as it stands: no stable configuration beyond it
  // The motion's increment, every option with its value, defaults included (model/options.cpp), the
  // start, the friction angle of the sliding report asked for, and where the steps are
  // event-driven, the tolerance and longest step the run derived.
  set_setting(r.settings, &Motion::step, s.step);
  set_setting(r.settings, &Motion::max_steps, s.max_steps);
  r.settings.update(valued_options<PrdOptions>(s));
  if (s.start) r.settings["start"] = {{"d", s.start->d}, {"offsets", start_offsets_name(s.start->offsets)}, {"from", s.start->source}};
  if (s.friction_angle) r.settings["friction_angle"] = *s.friction_angle;
  if (s.adaptive) {
    set_setting(r.settings, &PrdOptions::event_tolerance, w.tol_ev);
    set_setting(r.settings, &PrdOptions::max_step, w.h_max);
  }
  r.events.emplace();
  r.joints = joint_infos(w.m);
  r.total_weight = total_weight(c);
  auto emit = [&] {
    r.timing.lp_s = w.m.lp_s;
    r.timing.lp_solves = w.m.lp_solves;
    r.timing.kept_basis_solves = w.m.kept_basis_solves;
    r.timing.interior_solves = w.m.interior_solves;
    r.timing.basis_evaluations = w.m.basis_evaluations;
    r.timing.total_s = seconds_since(t_start) - io_s;
    if (!on_step) return;
    const auto t0 = cpu_now();
    on_step(r);
    io_s += seconds_since(t0);
  };
  try {
    for (;;) {
      const Solved sv = solve_here(w);
      if (sv.status == LpStatus::infeasible) {
        r.status = RunStatus::error;
        r.message = "d = " + std::to_string(w.cur.d) + " " + path_unit(c) + ": the LP is infeasible: the prescribed motion cannot be accommodated without a corner penetrating or a closed corner sliding";
        break;
      }
      if (event_behind(w, sv)) {
        go_back(w);
        continue;
      }
      if (sv.status == LpStatus::unbounded) {
        record_collapse(w, sv, r);
        break;
      }
      accept(w, sv, r);
      if (path_done(w)) {
        r.status = RunStatus::max_steps;
        break;
      }
      emit();
      take(w, sv, plan(w, sv), r);
    }
  } catch (const std::exception& e) {
    r.status = RunStatus::error;
    r.message = e.what();
  }
  if (s.sliding_check) {
    r.sliding = sliding_summary(c, r);
    r.sliding->lp_solves = w.sliding.solves;
  }
  emit();
  return r;
}

}  // namespace masonry
