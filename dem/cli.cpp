// `masonry dem CASE --out DIR`: the DEM capacity run, written as it goes.
#include <cstdio>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "dem.hpp"

namespace masonry {

void add_dem_commands(CLI::App& app, Commands& out) {
  struct Opts {
    std::string case_path, out_dir;
    std::optional<double> friction, reduction, damping, factor, eq_tol, vel_tol, hold, step, move_time, ramp, drift, open_gap;
    std::optional<int> max_steps;
    bool quiet = false;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* sub = app.add_subcommand("dem", "Rigid-block DEM capacity run (explicit, Mohr-Coulomb joints)");
  sub->add_option("case", o->case_path, "Case file (masonry-case/1 JSON)")->required();
  sub->add_option("--out", o->out_dir, "Output directory for results.json and steps.csv")->required();
  sub->add_option("--friction", o->friction, "Friction angle, degrees (case: dem.friction_angle, default 35)");
  sub->add_option("--stiffness-reduction", o->reduction, "Divide kn and ks by this (case default 1; the paper used 10)");
  sub->add_option("--damping", o->damping, "Local damping coefficient in [0, 1) (default 0.8)");
  sub->add_option("--timestep-factor", o->factor, "Time step / critical time step bound, in (0, 1] (default 0.2)");
  sub->add_option("--equilibrium-tolerance", o->eq_tol, "Largest unbalanced force / block weight at equilibrium (default 1e-4)");
  sub->add_option("--velocity-tolerance", o->vel_tol, "Largest block speed at equilibrium, m/s (default 1e-5)");
  sub->add_option("--hold-time", o->hold, "Model-time budget of each hold, s (default 3)");
  sub->add_option("--step", o->step, "Increment of the support path parameter d, m (case: motion.step)");
  sub->add_option("--max-steps", o->max_steps, "Number of increments at most (case: motion.max_steps)");
  sub->add_option("--move-time", o->move_time, "Model time to travel one increment, s (default: the case's dem.move_time)");
  sub->add_option("--ramp-fraction", o->ramp, "Fraction of the move time spent speeding up (and slowing down), 0..0.5 (default 0.25; 0: abrupt)");
  sub->add_option("--collapse-drift", o->drift, "Block travel within an unsettled hold that means collapse, m (default 2% of scene)");
  sub->add_option("--open-gap", o->open_gap, "Gap above which a joint corner is open, m (default prd.contact_tolerance)");
  sub->add_flag("--quiet", o->quiet, "No progress lines");
  out.push_back({sub, [o]() {
                   const Case c = load_case(o->case_path);
                   DemSettings s = DemSettings::from_case(c);
                   if (o->friction) s.friction_angle = *o->friction;
                   if (o->reduction) s.stiffness_reduction = *o->reduction;
                   if (o->damping) s.damping = *o->damping;
                   if (o->factor) s.timestep_factor = *o->factor;
                   if (o->eq_tol) s.equilibrium_tolerance = *o->eq_tol;
                   if (o->vel_tol) s.velocity_tolerance = *o->vel_tol;
                   if (o->hold) s.hold_time = *o->hold;
                   if (o->step) s.step = *o->step;
                   if (o->max_steps) s.max_steps = *o->max_steps;
                   if (o->move_time) s.move_time = *o->move_time;
                   if (o->ramp) s.ramp_fraction = *o->ramp;
                   if (o->drift) s.collapse_drift = *o->drift;
                   if (o->open_gap) s.open_gap = *o->open_gap;
                   const RunResult r = dem_run(c, s, [&](const RunResult& part) {
                     write_results(o->out_dir, part, c);
                     if (o->quiet || part.steps.empty()) return;
                     const StepRecord& st = part.steps.back();
                     std::fprintf(stderr, "dem: step %d d=%.6g m  cycles %lld (total %lld)  unbalanced %.2e  %s\n", st.index, st.d,
                                  st.extra.value("cycles", 0LL), part.timing.cycles, st.extra.value("unbalanced_ratio", 0.0),
                                  st.extra.value("settled", false) ? "settled" : "NOT settled");
                   });
                   write_results(o->out_dir, r, c);
                   if (!o->quiet)
                     std::fprintf(stderr, "dem: %s, capacity %.6g m after %d stable steps, %lld cycles, %.3g s (dt %.3g s)\n",
                                  r.stopped.c_str(), r.capacity, r.stable_steps, r.timing.cycles, r.timing.total_s,
                                  r.settings.value("dt", 0.0));
                   if (r.stopped == "error") throw std::runtime_error(r.message);
                   return 0;
                 }});
}

}  // namespace masonry
