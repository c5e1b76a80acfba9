// PRD: prd_check and the run loop. One GLPK problem per run (lp.cpp), rows and bounds rewritten in
// place each step.
// The LP itself (variables and rows) is described at the top of lp.cpp.
#include <stdexcept>

#include "glpk_hooks.hpp"
#include "internal.hpp"

namespace masonry {

using namespace prd_detail;

PrdSettings PrdSettings::from_case(const Case& c) {
  PrdSettings s;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  s.contact_tolerance = c.prd.contact_tolerance;
  s.adaptive = c.prd.adaptive;
  s.event_tolerance = c.prd.event_tolerance;
  s.max_step = c.prd.max_step;
  s.sliding_check = c.prd.sliding_check;
  return s;
}

PrdCheck prd_check(const Case& c, double contact_tolerance) {
  prd::install_glpk_hooks();
  Model m = build_model(c, contact_tolerance);
  PrdCheck out;
  out.joints = joint_infos(m);
  out.total_weight = total_weight(*m.c);
  const double scale = std::max(scene_size(c), 1e-12) * 1e-3;
  update_lp(m, 0.0, scale);
  // A fresh LP: GLPK's standard basis (every row slack basic) makes the simplex bring each
  // block's columns in one pivot at a time, about two pivots per block, each costing in
  // proportion to the rows, so the analysis grows with the square of the blocks. Bixby's
  // advanced basis starts with most columns basic and halves the pivots (a wall of 4000 blocks:
  // 8000 pivots, 3.4 s, became 4040, 1.9 s); the growth stays quadratic, which is the simplex's.
  if (m.ncols > 0) quiet_adv_basis(m);
  const LpStatus status = m.ncols == 0 ? LpStatus::optimal : solve(m);
  out.state.poses = poses(m);
  if (status == LpStatus::optimal) {
    out.stable = true;
    out.energy_rate = objective(m) * scale;
    read_forces(m, out.state);
    lp_check_fields(m, scale, out.state);
  } else if (status == LpStatus::unbounded) {
    out.stable = false;
    out.state.extra["collapse"] = collapse_mechanism(m, scale);
    out.mechanism.assign(c.blocks.size(), Pose{});
    for (size_t b = 0; b < c.blocks.size(); ++b)
      if (m.col[b] > 0)
        out.mechanism[b] = {col_value(m, m.col[b]), col_value(m, m.col[b] + 1),
                            col_value(m, m.col[b] + 2) / m.radius[b]};
  } else {
    throw std::runtime_error(c.source + ": the analysis LP is infeasible (blocks overlap beyond the tolerance?)");
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
  const auto t_start = Clock::now();
  double io_s = 0;
  RunResult r;
  r.method = "prd";
  r.case_name = c.name;
  // A fixed-step run is the event-driven one with every step accepted: the step never changes
  // and no event is bracketed more finely than one step.
  const double h_ref = s.step;
  const double tol_ev = !s.adaptive ? h_ref : s.event_tolerance > 0 ? s.event_tolerance : 1e-4 * scene_size(c);
  // The longest move. A move's path error (second order, see Path) grows as the square of its
  // length against the scene's, so the default keeps it within the event tolerance:
  // 0.4 sqrt(tolerance x scene size), 1/250 of the scene at the default tolerance.
  const double h_max =
      !s.adaptive ? h_ref
                  : std::max(s.max_step > 0 ? s.max_step : std::min(16 * h_ref, 0.4 * std::sqrt(tol_ev * scene_size(c))), tol_ev);
  const double d_end = s.max_steps * h_ref;
  r.settings = {{"step", s.step}, {"max_steps", s.max_steps}, {"contact_tolerance", s.contact_tolerance}};
  if (s.adaptive) {
    r.settings["adaptive"] = true;
    r.settings["event_tolerance"] = tol_ev;
    r.settings["max_step"] = h_max;
  }
  r.extra["events"] = nlohmann::ordered_json::array();
  Model m = build_model(c, s.contact_tolerance);
  r.joints = joint_infos(m);
  r.total_weight = total_weight(*m.c);
  auto sync_timing = [&] {
    r.timing.lp_s = m.lp_s;
    r.timing.lp_solves = m.lp_solves;
    r.timing.basis_evaluations = m.basis_evaluations;
    r.timing.total_s = seconds_since(t_start) - io_s;
  };
  auto emit = [&] {
    sync_timing();
    if (!on_step) return;
    const auto t0 = Clock::now();
    on_step(r);
    io_s += seconds_since(t0);
  };

  // The record of configuration d_k is completed by the LP solved on it (with the increment to
  // d_{k+1}): its duals are the forces in equilibrium on d_k, and a bounded optimum is what
  // makes d_k stable. An unbounded LP on d_k means d_k admits a collapse mechanism: the
  // capacity is then d_{k-1}, the last configuration with an admissible force state.
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
  Accepted cur;
  SlidingLp sliding;
  std::optional<Accepted> prev, prev2;  // the last accepted configurations, newest first
  StepRecord rec = configuration_record(m, 0, 0.0);
  double h_in = 0;                                          // the move that led to cur
  double seen = std::numeric_limits<double>::infinity();    // d where an event was seen, not yet located
  double h_plan = h_ref;                                    // the step the next LP is solved for
  double arrived_closing = -1;  // the move to cur ended where a corner closed: located within this
  long passing = -1;            // the corner the move to cur was to take past its predicted opening
  std::vector<char> ignored(m.ends.size(), 0);
  // A move stops half a tolerance short of a predicted opening, and the next one goes half a
  // tolerance past it, so that it is bracketed within the tolerance without bisection.
  const auto land = [&](double x) { return x > tol_ev ? x - tol_ev / 2 : std::min(x + tol_ev / 2, tol_ev); };
  // Inside a bracket (an event seen at `seen`, not yet located), the move from d: to land by
  // the estimated crossing while it lies ahead, else to halve the bracket; once the bracket
  // is within the tolerance, to its end.
  double crossing = std::numeric_limits<double>::infinity();
  const auto toward_event = [&](double d) {
    const double left = seen - d;
    if (left <= tol_ev) return left;
    const double x = crossing - d;
    if (x > 0 && x < left) return std::min(land(x), left - tol_ev / 2);
    return left / 2;
  };
  std::vector<double> gap, rate;
  try {
    for (;;) {
      // The LP is solved for the step planned, with open corners held over the event tolerance
      // only: a corner that closes later in the step cuts the move short where it closes (on
      // the exact motion), so the LP's mechanism is the one of this configuration.
      const double h = h_plan, h_open = std::min(h, tol_ev);
      update_lp(m, h, h, h_open);
      const LpStatus st = m.ncols == 0 ? LpStatus::optimal : solve(m);
      if (st == LpStatus::infeasible) {
        r.status = RunStatus::error;
        r.message = "d = " + std::to_string(cur.d) +
                    " m: the LP is infeasible: the prescribed motion cannot be accommodated without penetration";
        break;
      }
      std::vector<size_t> opened, closing;
      if (st == LpStatus::optimal) {
        gaps_and_rates(m, h, h_open, gap, rate);
        const std::vector<char> next = closed_after(m, gap, rate, h, h_open, h_ref);
        for (size_t e = 0; e < m.ends.size(); ++e)
          if (m.ends[e].closed != next[e]) (next[e] ? closing : opened).push_back(e);
      }
      // An event seen at the end of a move longer than the tolerance is located by going back.
      // Unless the move ended where a corner closed, and the previous mechanism held all the
      // way (its basis is still the optimum here, that corner aside): then the closing set
      // the event off, and it is located with the closing.
      bool back = (st == LpStatus::unbounded || !opened.empty()) && prev && h_in > tol_ev * (1 + 1e-9);
      if (back && s.adaptive) {
        const Accepted& p = *prev;
        Accepted here;
        save_basis(m, here);
        here.closed.resize(m.ends.size());
        for (size_t e = 0; e < m.ends.size(); ++e) here.closed[e] = m.ends[e].closed;
        const std::optional<double> x = basis_crossing(m, p, cur.d - p.d, tol_ev);
        set_closed(m, here.closed);
        crossing = x ? p.d + *x : std::numeric_limits<double>::infinity();
        if (x && !std::isfinite(*x) && arrived_closing >= 0) {
          back = false;
          h_in = arrived_closing;
          // basis_crossing left the previous basis in the LP: this configuration's back.
          if (evaluate_basis(m, here, h, h_open) != 0) throw std::runtime_error("GLPK could not restore the step's basis");
        }
      }
      if (back) {
        // Back to the last accepted configuration, and from there to where the previous
        // basis's forces, interpolated between there and here, reach 0 (half way when they
        // do not tell).
        seen = cur.d;
        const Accepted& p = *prev;
        m.cen = p.cen;
        m.angle = p.angle;
        set_closed(m, p.closed);
        h_in = toward_event(p.d);
        const std::vector<char> closed = closed_after(m, p.gap, p.rate, p.h_lp, h_in, h_ref);
        advance(m, Path{p.U, p.dU}, h_in);
        set_closed(m, closed);
        cur.d = p.d + h_in;
        cur.index = p.index + 1;
        rec = configuration_record(m, cur.index, cur.d);
        h_plan = toward_event(cur.d);
        arrived_closing = -1;
        continue;
      }
      if (st == LpStatus::unbounded) {
        r.collapsed = true;
        r.status = RunStatus::collapse;
        r.extra["events"].push_back(event_json(m, "collapse", cur.d, h_in, {}));
        r.extra["collapse"] = collapse_mechanism(m, h);
        r.extra["collapse"]["d"] = cur.d;
        r.extra["collapse"]["poses"] = nlohmann::ordered_json::array();
        for (const Pose& p : rec.poses) r.extra["collapse"]["poses"].push_back({p.x, p.y, p.angle});
        if (!prev) r.message = "unstable as it stands";
        break;
      }

      // cur is accepted. A corner the move was to take past its predicted opening that is still
      // closed has a force that reached 0 without changing the mechanism (a statically
      // indeterminate part's dual forces are one admissible state of many): it is left out of
      // the predictions from here on, and should it open after all, the LP sees it.
      if (passing >= 0 && m.ends[passing].closed && opened.empty() && !ignored[passing]) ignored[passing] = 1;
      passing = -1;
      read_forces(m, rec);
      lp_check_fields(m, h, rec);
      if (s.sliding_check) sliding_check(m, sliding, rec);
      require_finite(rec);
      r.steps.push_back(rec);
      r.capacity = cur.d;
      r.stable_steps = cur.index;
      // An event seen on the way here that did not recur at the same d (the way there
      // differed) is over.
      if (seen - cur.d <= 1e-9 * h_ref) seen = std::numeric_limits<double>::infinity();
      if (!opened.empty()) {
        r.extra["events"].push_back(event_json(m, "open", cur.d, h_in, opened));
        seen = std::numeric_limits<double>::infinity();
      }
      if (s.adaptive ? d_end - cur.d <= 1e-9 * h_ref : cur.index == s.max_steps) {
        r.status = RunStatus::max_steps;
        break;
      }
      emit();

      cur.cen = m.cen;
      cur.angle = m.angle;
      cur.U = column_values(m);
      cur.gap = gap;
      cur.rate = rate;
      cur.h_lp = h;
      cur.closed.resize(m.ends.size());
      for (size_t e = 0; e < m.ends.size(); ++e) cur.closed[e] = m.ends[e].closed;
      cur.fn.resize(m.ends.size());
      for (size_t e = 0; e < m.ends.size(); ++e) cur.fn[e] = corner_force(m, e);
      cur.same = opened.empty() && closing.empty();
      cur.dU.clear();
      save_basis(m, cur);
      double h_take = h;
      Closing shut;  // a closing the move is cut short at
      Move planned;  // the opening the move was planned against
      if (s.adaptive) {
        if (std::isfinite(seen)) {
          h_take = std::min(h, toward_event(cur.d));
        } else if (closing.empty()) {
          // The forces' trend, when the previous configurations had the same mechanism (their
          // chord, with its curvature when there are three), gives a first guess of the move;
          // plan_move checks it on the basis where it would end.
          const auto on_same = [&](const std::optional<Accepted>& a, const Accepted& b) {
            return a && a->same && b.same && a->closed == b.closed && b.d > a->d;
          };
          std::vector<double> slope, curve;
          double x = h;
          Move guess;
          if (on_same(prev, cur)) {
            slope.resize(m.ends.size());
            for (size_t e = 0; e < m.ends.size(); ++e) slope[e] = (cur.fn[e] - prev->fn[e]) / (cur.d - prev->d);
            if (on_same(prev2, *prev)) {
              curve.resize(m.ends.size());
              for (size_t e = 0; e < m.ends.size(); ++e) {
                curve[e] = (slope[e] - (prev->fn[e] - prev2->fn[e]) / (prev->d - prev2->d)) / (cur.d - prev2->d);
                slope[e] += curve[e] * (cur.d - prev->d);  // at cur
              }
            }
            guess = predict_opening(cur, slope, curve, ignored);
            x = std::min(x, land(guess.to_open));
          }
          if (d_end - cur.d > 1e-9 * h_ref) x = std::min(x, d_end - cur.d);
          planned = plan_move(m, cur, h, h_open, x, guess, slope, ignored, 2 * tol_ev, land);
          h_take = planned.h;
        }
        if (d_end - cur.d > 1e-9 * h_ref) h_take = std::min(h_take, d_end - cur.d);
        if (!closing.empty()) {
          h_take = std::min(h_take, h_open);  // the LP holds the closing corner at the end of it
        } else {
          shut = first_closing(m, Path{cur.U, cur.dU}, gap, rate, h_take);
          if (std::isfinite(shut.at)) h_take = shut.at;
        }
        if (planned.to_open <= h_take) passing = planned.corner;
        // The next LP's step: inside a bracket, the next move in it; else as long as allowed,
        // the predictions cutting the move short.
        h_plan = h_max;
        if (std::isfinite(seen) && seen - cur.d - h_take > 1e-9 * h_ref) h_plan = toward_event(cur.d + h_take);
      }
      if (!(h_take > 0)) throw std::logic_error("prd: the step came to a stop at d = " + std::to_string(cur.d) + " m");
      prev2 = std::move(prev);
      prev = cur;
      advance(m, Path{cur.U, cur.dU}, h_take);
      std::vector<char> closed = closed_after(m, gap, rate, h, h_take, h_ref);
      if (std::isfinite(shut.at)) closed[shut.corner] = 1;
      if (!cur.dU.empty())  // off the first-order update, a corner's gap is what it is
        for (size_t e = 0; e < m.ends.size(); ++e) {
          const Interface& jt = m.joints[m.ends[e].joint];
          if (!m.ends[e].closed && (m.pos(jt.j, m.ends[e].X) - m.pos(jt.i, m.ends[e].X)).dot(m.normal(m.ends[e])) <= m.tol)
            closed[e] = 1;
        }
      std::vector<size_t> shut_now;
      for (size_t e = 0; e < m.ends.size(); ++e)
        if (closed[e] && !m.ends[e].closed) shut_now.push_back(e);
      set_closed(m, closed);
      if (!shut_now.empty()) {
        const bool exact = std::isfinite(shut.at) && shut_now.size() == 1;
        r.extra["events"].push_back(event_json(m, "close", cur.d + h_take, exact ? shut.within : h_take, shut_now));
      }
      h_in = h_take;
      arrived_closing = std::isfinite(shut.at) ? shut.within : -1;
      cur.index += 1;
      cur.d = s.adaptive ? prev->d + h_take : cur.index * h_ref;
      rec = configuration_record(m, cur.index, cur.d);
    }
  } catch (const std::exception& e) {
    r.status = RunStatus::error;
    r.message = e.what();
  }
  if (s.sliding_check) {
    r.sliding = sliding_summary(c, r);
    r.sliding->lp_solves = sliding.solves;
  }
  emit();
  return r;
}

}  // namespace masonry
