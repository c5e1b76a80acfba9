// `masonry dem CASE --out DIR`: the DEM capacity run, written as it goes.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "app/command.hpp"
#include "app/flags.hpp"
#include "compare/convergence.hpp"
#include "dem/dem.hpp"
#include "dem/variants.hpp"
#include "model/interfaces.hpp"
#include "runs/parallel.hpp"
#include "runs/progress.hpp"
#include "runs/run.hpp"

namespace masonry {

namespace {

struct Opts {
  std::string case_path, out_dir;
  CaseFlags settings;  // the flags that set case options
  bool quiet = false, convergence = false, stiffness_study = false;
  int jobs = 2;
  double spread_limit = 0.02, prd_limit = 0.03;
  std::vector<std::string> only;  // a study: the variants to run; the others are read back
  bool read_back = false;         // a study: read every run back, run none
};

// A study's runs: every variant, or with --only the named ones (none with
// --read-back), the others read back from DIR/<variant>/results.json of an earlier study (a
// finished run, or a refusal).
std::vector<RunResult> study_runs(const Case& c, Study kind, const std::vector<DemVariant>& variants, const Opts& o,
                                  const std::function<void(size_t, const RunResult&)>& on_done) {
  if (o.only.empty() && !o.read_back) return run_variants(c, variants, o.jobs, o.out_dir, on_done);
  std::vector<size_t> rerun;  // indices into variants
  for (const std::string& name : o.only) {
    const auto it = std::find_if(variants.begin(), variants.end(), [&](const DemVariant& v) { return v.name == name; });
    if (it == variants.end()) throw std::invalid_argument("dem --only: no variant '" + name + "' in the " + study_name(kind) + " study");
    rerun.push_back(static_cast<size_t>(it - variants.begin()));
  }
  std::vector<RunResult> runs(variants.size());
  std::vector<DemVariant> to_run;
  for (size_t i = 0; i < variants.size(); ++i) {
    if (std::count(rerun.begin(), rerun.end(), i)) {
      to_run.push_back(variants[i]);
      continue;
    }
    const std::string path = (std::filesystem::path(o.out_dir) / variants[i].name / "results.json").string();
    if (!std::filesystem::exists(path)) throw std::invalid_argument(std::string("dem ") + study_name(kind) + ": " + path + " is missing: run the whole study first");
    runs[i] = load_results(path, c);
    if (runs[i].status == RunStatus::running) throw std::invalid_argument(std::string("dem ") + study_name(kind) + ": " + path + " is a run that did not finish");
  }
  // to_run is in variants' order, and so is rerun once sorted.
  std::sort(rerun.begin(), rerun.end());
  rerun.erase(std::unique(rerun.begin(), rerun.end()), rerun.end());
  const std::vector<RunResult> fresh =
      run_variants(c, to_run, o.jobs, o.out_dir, [&](size_t k, const RunResult& r) { if (on_done) on_done(rerun[k], r); });
  for (size_t k = 0; k < rerun.size(); ++k) runs[rerun[k]] = fresh[k];
  return runs;
}

// A study (convergence or joint stiffness): PRD once for reference, the DEM variants in
// parallel, each written to DIR/<variant>/ as it goes, then DIR/<study>.{json,md} and the verdict.
int run_study(const Case& c, const DemSettings& base, Study kind, const Opts& o) {
  Convergence study;
  study.study = kind;
  study.case_name = c.name;
  study.spread_limit = o.spread_limit;
  study.prd_limit = o.prd_limit;
  study.scene = &c;
  study.prd = run_case(c, Method::prd);
  if (located(study.prd->status)) study.prd_capacity = study.prd->capacity;
  const std::vector<DemVariant> variants = kind == Study::stiffness ? stiffness_variants(base) : convergence_variants(base);
  const std::string name = study_name(kind);
  std::mutex io;
  size_t done = 0;
  const StudyProgress progress("dem " + name, o.only.empty() && !o.read_back ? variants.size() : o.only.size());
  const std::vector<RunResult> runs = study_runs(c, kind, variants, o, [&](size_t i, const RunResult& r) {
    std::lock_guard<std::mutex> lock(io);
    ++done;
    if (o.quiet) return;
    char b[160];
    std::snprintf(b, sizeof b, "%s: %s, capacity %.6g m, %.3g s CPU", variants[i].name.c_str(), status_name(r.status), r.capacity, r.timing.total_s);
    std::cerr << progress.line(done, b) << "\n" << std::flush;
  });
  for (size_t i = 0; i < variants.size(); ++i) {
    study.entries.push_back({variants[i].name, variants[i].what, runs[i], std::nullopt});
    study.entries.back().prd_on_run = prd_on_run(c, runs[i]);
  }
  const std::filesystem::path out(o.out_dir);
  write_file_atomic((out / (name + ".json")).string(), convergence_json(study).dump(1) + "\n");
  write_file_atomic((out / (name + ".md")).string(), convergence_markdown(study));
  const ConvergenceVerdict v = judge(study);
  if (!o.quiet) std::fprintf(stderr, "dem %s: %s (%s)\n", name.c_str(), verdict_name(kind, v), (out / (name + ".md")).c_str());
  return v.ok ? kExitDone : kExitFailed;
}

// Warns before a run whose time step makes each second of model time expensive (very stiff
// joints, tiny blocks): about 80 ns per contact point per cycle on the reference machine
// (README, "Speed"), two contact points per joint, one cycle per time step. Settling under
// gravity alone takes some tenths of a second of model time; a hold may last up to hold_time.
void warn_dem_cost(const Case& c, const DemSettings& s) {
  const DemModel probe(c, s);
  const double points = 2.0 * static_cast<double>(detect_interfaces(c, c.prd.contact_tolerance).size());
  const double per_model_second = 80e-9 * points / probe.dt();
  if (per_model_second < 60) return;
  std::fprintf(stderr,
               "dem: time step %.3g s (kn %.3g Pa/m, %.0f contact points): each second of model time costs about %.3g s of CPU "
               "here, and a hold may last up to %.3g s of model time\n",
               probe.dt(), probe.kn(), points, per_model_second, s.hold_time);
}

}  // namespace

void add_dem_commands(CLI::App& app, Commands& out) {
  auto o = std::make_shared<Opts>();
  CLI::App* sub = app.add_subcommand("dem", "Rigid-block DEM capacity run (explicit, Mohr-Coulomb joints)");
  sub->add_option("case", o->case_path, "Case file (masonry-case/1 JSON)")->required();
  sub->add_option("--out", o->out_dir, "Output directory for results.json and steps.csv")->required();
  using K = CaseFlags::Kind;
  CaseFlags& f = o->settings;
  f.add(sub, "--friction", "dem.friction_angle", K::number, "Friction angle, degrees (default 35)");
  f.add(sub, "--stiffness-reduction", "dem.stiffness_reduction", K::number, "Divide kn and ks by this (default 1; the paper used 10)");
  f.add(sub, "--damping", "dem.damping", K::number, "Local damping coefficient in [0, 1) (default 0.8)");
  f.add(sub, "--timestep-factor", "dem.timestep_factor", K::number, "Time step / critical time step bound, in (0, 1] (default 1)");
  f.add(sub, "--equilibrium-tolerance", "dem.equilibrium_tolerance", K::number, "Largest unbalanced force / block weight at equilibrium (default 1e-4)");
  f.add(sub, "--velocity-tolerance", "dem.velocity_tolerance", K::number, "Largest block speed at equilibrium, m/s (default 1e-5)");
  f.add(sub, "--hold-time", "dem.hold_time", K::number, "Model-time cap of one hold, s: a hold that neither settles nor runs away by then is undecided (default 30)");
  f.add(sub, "--step", "motion.step", K::number, "Increment of the support path parameter d, m");
  f.add(sub, "--max-steps", "motion.max_steps", K::integer, "Number of increments at most");
  f.add(sub, "--kinetic-ratio", "dem.kinetic_ratio", K::number, "Moves keep every block's kinetic energy below this x its weight x support travel over the increment (default 1e-3)");
  f.add(sub, "--move-time", "dem.move_time", K::number, "Constant-speed move over this model time per increment, s, instead of the kinetic-energy servo (default 0: servo)");
  f.add(sub, "--bracket-fraction", "dem.bracket_fraction", K::number, "Bisect a failed increment down to this fraction of the step (default 0.01; 0: no bisection)");
  f.add(sub, "--confirm-collapse", "dem.confirm_collapse", K::flag,
        "Confirm a located collapse by the short move from the bracket's last equilibrium; a failure it does not reproduce "
        "becomes an equilibrium and the run goes on (dem/README.md, stage 4; off by default)");
  f.add(sub, "--ramp-fraction", "dem.ramp_fraction", K::number, "Fraction of the move time spent speeding up (and slowing down), 0..0.5 (default 0.25; 0: abrupt)");
  f.add(sub, "--collapse-drift", "dem.collapse_drift", K::number, "Block travel within an unsettled hold that means collapse, m (default 2% of scene)");
  f.add(sub, "--open-gap", "dem.open_gap", K::number, "Gap growth above which a joint corner is open, m (default prd.contact_tolerance)");
  f.add(sub, "--hold-damping", "dem.hold_damping", K::text,
        "How holds come to rest: local (local damping alone, the default) or kinetic (also stop every free block when the "
        "kinetic energy passes a peak; dem/README.md, \"Holds: local or kinetic damping\")");
  sub->add_flag("--quiet", o->quiet, "No progress lines and no summary: only warnings and why a run failed");
  sub->add_flag("--convergence", o->convergence,
                "Convergence study: the run at these settings and at settings that must not matter (dem/README.md), "
                "DIR/convergence.{json,md}, each run in DIR/<variant>/; exit code 1 when the spread or the default against PRD exceeds its limit");
  sub->add_flag("--stiffness-study", o->stiffness_study,
                "Joint-stiffness study: the run at these settings and with kn, ks x1/10, x1/3, x3, x10, x30 (dem/README.md), "
                "DIR/stiffness.{json,md}, each run in DIR/<variant>/, each run's mechanism against PRD's; a measurement with no "
                "limits: exit code 1 only when a run does not finish")->excludes("--convergence");
  sub->add_option("--jobs", o->jobs, "A study: runs at a time, one thread each (default 2)")->check(CLI::PositiveNumber);
  sub->add_option("--spread-limit", o->spread_limit, "Convergence study: largest (max - min) / default capacity (default 0.02)");
  sub->add_option("--prd-limit", o->prd_limit, "Convergence study: largest |default - PRD| / PRD capacity (default 0.03)");
  sub->add_option("--only", o->only,
                  "A study: run only these variants again and read the others back from DIR/<variant>/results.json "
                  "(of a study run with the same binary and settings: the results do not say which code made them)");
  sub->add_flag("--read-back", o->read_back,
                "A study: run no variant, read them all back from DIR/<variant>/results.json and write the study again");
  out.push_back({sub, [o]() {
                   const Case c = o->settings.apply(load_case(o->case_path));
                   const DemSettings s = DemSettings::from_case(c);
                   if (!o->quiet) warn_dem_cost(c, s);
                   if (o->convergence) return run_study(c, s, Study::convergence, *o);
                   if (o->stiffness_study) return run_study(c, s, Study::stiffness, *o);
                   RunProgress progress("dem", s.step * s.max_steps, 0.0, dem_step_detail, path_unit(c));
                   const RunResult r =
                       run_dem(c, s, {o->out_dir, o->quiet ? std::function<void(const RunResult&)>() : std::ref(progress)});
                   if (!o->quiet)
                     std::fprintf(stderr, "dem: %s, capacity %.6g %s after %d stable steps, %lld cycles, %.3g s (dt %.3g s)\n",
                                  status_name(r.status), r.capacity, path_unit(c).c_str(), r.stable_steps, r.timing.cycles, r.timing.total_s,
                                  r.settings.value("dt", 0.0));
                   if (!located(r.status)) std::fprintf(stderr, "dem: %s\n", r.message.c_str());
                   return exit_code(r.status);
                 }});
}

}  // namespace masonry
