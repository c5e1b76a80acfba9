// `masonry sweep SPEC --out DIR`: a thin front end. Under mpirun the runs are split over the
// ranks; otherwise they go to local threads and MPI is never initialised.
#include <memory>

#include "app/command.hpp"
#include "sweep/sweep.hpp"

namespace masonry {

void add_sweep_commands(CLI::App& app, Commands& out) {
  struct Opts {
    std::string spec;
    SweepOptions o;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* sub = app.add_subcommand(
      "sweep",
      "Run a case over a grid or a Latin hypercube sample of options or generator parameters (sweep file, masonry-sweep/1): DIR/sweep.csv, "
      "sweep.json, sensitivity.json, report.md, report.html");
  sub->add_option("spec", opts->spec, "Sweep file (masonry-sweep/1 JSON; see sweep/README.md)")->required();
  sub->add_option("--out", opts->o.out_dir, "Output directory; a sweep.csv there from the same sweep is resumed")->required();
  sub->add_option("--jobs", opts->o.jobs, "Runs at a time on this machine (default: every core; under mpirun: 1 per rank)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--restart", opts->o.restart, "Discard the rows of an existing DIR/sweep.csv instead of resuming it");
  sub->add_flag("--quiet", opts->o.quiet, "No progress lines");
  sub->add_flag("--keep-runs", opts->o.keep_runs,
                "Keep every run's case.json, results.json and steps.csv in DIR/runs/ID/ (ID: the row's id), for compare --runs");
  out.push_back({sub, [opts]() {
                   SweepOptions o = opts->o;
                   o.command = "masonry sweep " + opts->spec + " --out " + o.out_dir + (o.keep_runs ? " --keep-runs" : "");
                   if (started_by_mpirun()) return run_sweep_mpi(opts->spec, o);
                   const SweepTable t = run_sweep(read_sweep_input(opts->spec), o);
                   for (const auto& r : t)
                     if (r && !located(*r)) return kExitFailed;
                   return kExitDone;
                 }});
}

}  // namespace masonry
