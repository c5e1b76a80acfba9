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
  // The study's own flags as given (a count each), for the note that they act only with it.
  std::vector<const CLI::Option*> study_flags, convergence_flags;
};

// The study's flags given to a run they do not act on, one line each, in idle_options' words:
// `dem CASE --jobs 3` ran one run and said nothing of the 3.
std::vector<std::string> idle_study_flags(const Opts& o) {
  std::vector<std::string> out;
  if (!o.convergence && !o.stiffness_study)
    for (const CLI::Option* f : o.study_flags)
      if (f->count() > 0) out.push_back(f->get_name() + " has no effect without a study (--convergence or --stiffness-study): this is one run");
  if (!o.convergence)
    for (const CLI::Option* f : o.convergence_flags)
      if (f->count() > 0) out.push_back(f->get_name() + " has no effect without --convergence: only the convergence study has limits");
  return out;
}

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
    if (!std::filesystem::exists(path))
      throw std::invalid_argument(std::string("dem ") + study_name(kind) + ": " + path + " is missing: run the whole study first");
    runs[i] = load_results(path, c);
    if (runs[i].status == RunStatus::running)
      throw std::invalid_argument(std::string("dem ") + study_name(kind) + ": " + path + " is a run that did not finish");
  }
  // to_run is in variants' order, and so is rerun once sorted.
  std::sort(rerun.begin(), rerun.end());
  rerun.erase(std::unique(rerun.begin(), rerun.end()), rerun.end());
  const std::vector<RunResult> fresh = run_variants(c, to_run, o.jobs, o.out_dir, [&](size_t k, const RunResult& r) {
    if (on_done) on_done(rerun[k], r);
  });
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
    std::snprintf(b, sizeof b, "%s: %s, capacity %.6g %s, %.3g s CPU", variants[i].name.c_str(), status_name(r.status), r.capacity,
                  path_unit(c).c_str(), r.timing.total_s);
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
  o->settings.add(sub, OptionCommand::dem);
  sub->add_flag("--quiet", o->quiet, "No progress lines and no summary: only warnings and why a run failed");
  sub->add_flag("--convergence", o->convergence,
                "Convergence study: the run at these settings and at settings that must not matter (dem/README.md), "
                "DIR/convergence.{json,md}, each run in DIR/<variant>/; exit code 1 when the spread or the default against PRD exceeds its limit");
  sub->add_flag("--stiffness-study", o->stiffness_study,
                "Joint-stiffness study: the run at these settings and with kn, ks x1/10, x1/3, x3, x10, x30 (dem/README.md), "
                "DIR/stiffness.{json,md}, each run in DIR/<variant>/, each run's mechanism against PRD's; a measurement with no "
                "limits: exit code 1 only when a run does not finish")
      ->excludes("--convergence");
  o->study_flags.push_back(sub->add_option("--jobs", o->jobs, "A study: runs at a time, one thread each (default 2)")->check(CLI::PositiveNumber));
  o->convergence_flags.push_back(
      sub->add_option("--spread-limit", o->spread_limit, "Convergence study: largest (max - min) / default capacity (default 0.02)"));
  o->convergence_flags.push_back(
      sub->add_option("--prd-limit", o->prd_limit, "Convergence study: largest |default - PRD| / PRD capacity (default 0.03)"));
  o->study_flags.push_back(sub->add_option("--only", o->only,
                                           "A study: run only these variants again and read the others back from DIR/<variant>/results.json "
                                           "(of a study run with the same binary and settings: the results do not say which code made them)"));
  o->study_flags.push_back(sub->add_flag("--read-back", o->read_back,
                                         "A study: run no variant, read them all back from DIR/<variant>/results.json and write the study again"));
  out.push_back({sub, [o]() {
                   const Case c = o->settings.apply(load_case(o->case_path));
                   const DemSettings s = DemSettings::from_case(c);
                   if (!o->quiet) warn_dem_cost(c, s);
                   for (const std::string& line : idle_options(c.dem)) std::cerr << "dem: note: " << line << "\n";
                   for (const std::string& line : idle_study_flags(*o)) std::cerr << "dem: note: " << line << "\n";
                   if (o->convergence) return run_study(c, s, Study::convergence, *o);
                   if (o->stiffness_study) return run_study(c, s, Study::stiffness, *o);
                   RunProgress progress("dem", s.step * s.max_steps, 0.0, dem_step_detail, path_unit(c));
                   const RunResult r = run_dem(c, s, {o->out_dir, o->quiet ? std::function<void(const RunResult&)>() : std::ref(progress)});
                   if (!o->quiet)
                     std::fprintf(stderr, "dem: %s, capacity %.6g %s after %d stable steps, %lld cycles, %.3g s (dt %.3g s)\n", status_name(r.status),
                                  r.capacity, path_unit(c).c_str(), r.stable_steps, r.timing.cycles, r.timing.total_s, r.settings.value("dt", 0.0));
                   if (!located(r.status)) std::fprintf(stderr, "dem: %s\n", r.message.c_str());
                   return exit_code(r.status);
                 }});
}

}  // namespace masonry
