// `masonry compare` and `masonry demo`: thin front ends that run PRD and DEM on one case (or read
// finished runs back), then hand the RunResults to the comparison and its reports.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "app/flags.hpp"
#include "cases/generators.hpp"
#include "compare/compare.hpp"
#include "compare/report.hpp"
#include "dem/dem.hpp"
#include "model/io.hpp"
#include "report/format.hpp"
#include "runs/progress.hpp"
#include "runs/run.hpp"
#include "runs/slide_check.hpp"

namespace masonry {

namespace {

struct CompareOpts {
  std::string case_path, out_dir, tolerances, notes;
  std::vector<double> frictions;
  std::vector<std::string> runs;   // existing result directories instead of running
  CaseFlags settings;              // the flags that set case options, for both methods
  std::optional<double> dem_step;  // motion.step of the DEM runs only
  int frames = 0;
  bool quiet = false;
  bool no_damped_rerun = false;  // keep a DEM run that slid where statics does not ask for it
};

std::string num_text(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

// The command line that reproduces the run, for the report's header.
std::string command_line(const CompareOpts& o, const std::string& case_shown) {
  std::string s = "masonry compare " + case_shown + " --out " + o.out_dir;
  for (double f : o.frictions) s += " --friction " + num_text(f);
  s += o.settings.command_line();
  if (o.dem_step) s += " --dem-step " + num_text(*o.dem_step);
  if (!o.tolerances.empty()) s += " --tolerances " + o.tolerances;
  if (!o.notes.empty()) s += " --notes " + o.notes;
  if (o.no_damped_rerun) s += " --no-damped-rerun";
  if (!o.runs.empty()) {
    s += " --runs";
    for (const std::string& r : o.runs) s += " " + r;
  }
  return s;
}

std::string dem_label(double phi) { return "DEM phi=" + num_text(phi); }

// The author's notes for the report: plain text, paragraphs separated by blank lines (the lines
// of a paragraph are joined with spaces).
std::vector<std::string> read_notes(const std::string& path) {
  const std::optional<std::string> text = read_text(path);
  if (!text) throw std::runtime_error(path + ": cannot read the notes file (--notes)");
  std::vector<std::string> paragraphs;
  std::string para;
  std::istringstream in(*text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) {
      if (!para.empty()) paragraphs.push_back(std::move(para));
      para.clear();
    } else {
      para += (para.empty() ? "" : " ") + line;
    }
  }
  if (!para.empty()) paragraphs.push_back(std::move(para));
  return paragraphs;
}

void progress(bool quiet, const std::string& line) {
  if (!quiet) std::cerr << line << std::flush;
}

// "PRD", or "PRD held A, B" when corners were held closed: a reader sees at once that the run
// followed a constrained path.
std::string prd_label(const nlohmann::json& held) {
  std::string label = "PRD";
  if (!held.is_array()) return label;
  for (size_t k = 0; k < held.size(); ++k)
    if (held[k].is_string()) label += (k ? ", " : " held ") + held[k].get<std::string>();
  return label;
}

// Where a DEM run's damped rerun keeps the run it did not compare: SUB + one of these.
constexpr const char* kUndamped = "-undamped";
constexpr const char* kDamped = "-damped";

// compare/README.md, "A slide statics does not ask for": where the DEM run slid a joint PRD's
// did not and PRD's sliding check reads the statics within the DEM's friction up to there
// (runs/slide_check.hpp), the DEM runs again with contact damping into SUB-damped. Where that
// removes the slide, the rerun is the DEM compared (moved to SUB, the first run to SUB-undamped);
// where it does not, the slide was no ratchet and the first run stays.
std::optional<DampedRerun> rerun_if_unexplained_slide(const Case& c, const Case& dc, const RunResult& prd, RunResult& dem, const CompareOpts& o,
                                                      const std::string& sub) {
  if (o.no_damped_rerun) {
    // Said even with --quiet: the first run is kept on the user's word, not unread.
    if (const std::optional<SlideSuspect> s = dem_slide(c, dc, prd, dem))
      std::cerr << "compare: note: the DEM slid joint " << printable(s->joint) << " by " << fmt::mm(s->slip, 2) << " mm ("
                << fmt::g(100 * s->slip / s->travel, 2) << "% of the supports' travel) where PRD's did not; --no-damped-rerun: neither read against "
                << "statics nor run again with contact damping (compare/README.md, \"A slide statics does not ask for\")\n";
    return std::nullopt;
  }
  const std::optional<SlideVerdict> v = dem_slide_verdict(c, dc, prd, dem);
  if (!v) return std::nullopt;
  const std::string unit = path_unit(c), joint = printable(v->slide.joint),
                    slid = "compare: the DEM slid joint " + joint + " by " + fmt::mm(v->slide.slip, 2) + " mm (" + fmt::g(100 * v->slide.slip / v->slide.travel, 2) +
                           "% of the supports' travel, " + sub + ")";
  if (v->statics == Statics::slides) {
    progress(o.quiet, slid + ", as statics asks: every admissible force state needs more than " + num_text(v->friction_angle) + " deg of friction at d = " +
                          num_text(v->at_d) + " " + unit + " (joint " + printable(v->at_joint) + "): no damped rerun\n");
    return std::nullopt;
  }
  if (v->statics == Statics::unknown) {
    progress(o.quiet, slid + ", and statics cannot say whether it asks for that (" + v->why_unknown + "): no damped rerun\n");
    return std::nullopt;
  }
  const Case damped = with_check_damping(dc);
  DampedRerun x = damped_rerun(*v, damped, dem);
  const std::string first = sub + kUndamped, second = sub + kDamped;
  progress(o.quiet, slid + " where some admissible force state stays within " + num_text(v->friction_angle) +
                        " deg of friction (it needs at most " + fmt::g(v->needs) + " deg): the DEM again, with contact damping " + num_text(x.contact_damping) +
                        " ...\n");
  RunProgress dem_progress("compare: dem (damped)", damped.motion.step * damped.motion.max_steps, 0.0, dem_step_detail, unit);
  RunResult rerun = run_case(damped, Method::dem, {o.out_dir + "/" + second, o.quiet ? std::function<void(const RunResult&)>() : std::ref(dem_progress)});
  read_rerun(c, prd, rerun, x);
  if (x.removed) {
    std::filesystem::rename(o.out_dir + "/" + sub, o.out_dir + "/" + first);
    std::filesystem::rename(o.out_dir + "/" + second, o.out_dir + "/" + sub);
    dem = std::move(rerun);
    x.first_dir = first;
    x.rerun_dir = sub;
    progress(o.quiet, "compare: with contact damping the DEM's joints slide at most " + fmt::g(x.rerun_slip * 1e3, 2) + " mm: it is the DEM compared (the first run in " + first +
                          ")\n");
  } else {
    x.first_dir = sub;
    x.rerun_dir = second;
    progress(o.quiet, "compare: with contact damping the DEM still slides (" + fmt::mm(x.rerun_slip, 2) + " mm): no ratchet, the first run stays the DEM compared (the damped one in " +
                          second + ")\n");
  }
  return x;
}

int run_compare(const Case& c, const CompareOpts& o, const std::string& case_shown) {
  std::vector<Case> dem_cases;  // one per friction angle, where compare runs the DEM
  std::optional<Tolerances> tol;
  if (!o.tolerances.empty()) tol = load_tolerances(o.tolerances);  // fail before any long run
  std::vector<RunResult> results;
  std::vector<ReportRun> runs;
  if (!o.runs.empty()) {
    if (o.runs.size() < 2) throw std::runtime_error("--runs needs at least two result directories");
    for (const std::string& d : o.runs) {
      results.push_back(load_results(d + "/results.json", c));
      const RunResult& r = results.back();
      std::string label = method_label(r);
      if (known_method(r) == Method::dem && r.settings.contains("friction_angle") && r.settings["friction_angle"].is_number())
        label = dem_label(r.settings["friction_angle"].get<double>());
      if (known_method(r) == Method::prd && r.settings.contains("hold_closed")) label = prd_label(r.settings["hold_closed"]);
      // Links in the report are relative to it.
      std::error_code ec;
      std::string rel = std::filesystem::relative(d, o.out_dir, ec).generic_string();
      if (ec || rel.empty()) rel = std::filesystem::absolute(d).generic_string();
      runs.push_back({label, nullptr, rel});
    }
    // Two runs of one method: tell them apart by their directory names.
    bool twins = false;
    for (size_t k = 0; k < runs.size(); ++k)
      for (size_t m = k + 1; m < runs.size(); ++m) twins = twins || runs[k].label == runs[m].label;
    if (twins)
      for (size_t q = 0; q < runs.size(); ++q) runs[q].label += " " + std::filesystem::path(o.runs[q]).filename().string();
  } else {
    results.reserve(1 + std::max<size_t>(1, o.frictions.size()));
    std::vector<double> phis = o.frictions;
    if (phis.empty()) phis.push_back(c.dem.friction_angle);
    const Case dem_case = o.dem_step ? with_option(c, option_key(&Motion::step), *o.dem_step) : c;
    for (double phi : phis) dem_cases.push_back(with_option(dem_case, option_key(&DemOptions::friction_angle), phi));
    // The DEM's refusals before PRD runs (a large case's PRD can take minutes).
    for (const Case& dc : dem_cases) dem_check(dc, DemSettings::from_case(dc));
    progress(o.quiet, "compare: PRD on " + c.name + " ...\n");
    RunProgress prd_progress("compare: prd", c.motion.step * c.motion.max_steps, 1.0, {}, path_unit(c));
    results.push_back(run_case(c, Method::prd, {o.out_dir + "/prd", o.quiet ? std::function<void(const RunResult&)>() : std::ref(prd_progress)}));
    progress(o.quiet, "compare: PRD capacity " + num_text(results.back().capacity) + " " + path_unit(c) + ", " + num_text(results.back().timing.total_s) + " s\n");
    runs.push_back({prd_label(results.back().settings.value("hold_closed", nlohmann::json::array())), nullptr, "prd"});
    for (size_t k = 0; k < phis.size(); ++k) {
      const double phi = phis[k];
      const Case& dc = dem_cases[k];
      const std::string sub = phis.size() == 1 ? "dem" : "dem-phi" + num_text(phi);
      const std::string dir = o.out_dir + "/" + sub;
      progress(o.quiet, "compare: DEM (friction " + num_text(phi) + " deg) on " + c.name + " ...\n");
      // What an earlier comparison in this directory left of a damped rerun is not this one's.
      for (const char* tail : {kUndamped, kDamped}) std::filesystem::remove_all(dir + tail);
      RunProgress dem_progress("compare: dem", dc.motion.step * dc.motion.max_steps, 0.0, dem_step_detail, path_unit(c));
      results.push_back(run_case(dc, Method::dem, {dir, o.quiet ? std::function<void(const RunResult&)>() : std::ref(dem_progress)}));
      progress(o.quiet, "compare: DEM capacity " + num_text(results.back().capacity) + " " + path_unit(c) + ", " + num_text(results.back().timing.total_s) + " s\n");
      runs.push_back({dem_label(phi), nullptr, sub});
    }
  }
  const auto report = [&]() {
    for (size_t k = 0; k < runs.size(); ++k) {
      runs[k].run = &results[k];
      runs[k].prd_on_run = prd_on_run(c, results[k]);
    }
    Report rep = make_report(c, runs, tol ? &*tol : nullptr);
    rep.command = command_line(o, case_shown);
    rep.frames = o.frames;
    if (!o.notes.empty()) rep.notes = read_notes(o.notes);
    write_report(o.out_dir, rep);
    return rep;
  };
  Report rep = report();
  // The comparison of the first runs is written before any damped rerun, which can take longer
  // than they did: a rerun stopped or failed leaves it, and one that finishes rewrites it.
  if (o.runs.empty()) {
    bool again = false;
    for (size_t k = 1; k < runs.size(); ++k) {
      const Case& dc = dem_cases[k - 1];
      runs[k].rerun = rerun_if_unexplained_slide(c, dc, results.front(), results[k], o, runs[k].dir);
      if (!runs[k].rerun) continue;
      again = true;
      if (runs[k].rerun->removed)
        progress(o.quiet, "compare: DEM with contact damping: capacity " + num_text(results[k].capacity) + " " + path_unit(c) + ", " +
                              num_text(results[k].timing.total_s) + " s\n");
    }
    if (again) rep = report();
  }
  bool failed = false, errored = false;
  for (const RunResult& r : results) errored = errored || !located(r.status);
  for (size_t k = 0; k < rep.comparisons.size(); ++k) {
    const Comparison& cmp = rep.comparisons[k];
    // fmt: "n/a", never "nan", for what a run's results do not give (an outside solver's timing).
    const char* unit = cmp.d_unit.c_str();
    if (!o.quiet)
      std::fprintf(stderr, "compare: %s: %s %.4g %s, %s %.4g %s (%s), thrust difference max %s W rms %s W, times %s s / %s s\n", c.name.c_str(),
                   cmp.a.label.c_str(), cmp.a.capacity, unit, cmp.b.label.c_str(), cmp.b.capacity, unit, fmt::pct(cmp.capacity_rel_diff).c_str(),
                   fmt::g(cmp.thrust_max_diff).c_str(), fmt::g(cmp.thrust_rms_diff).c_str(), fmt::g(cmp.a.time_s).c_str(),
                   fmt::g(cmp.b.time_s).c_str());
    for (const std::string& v : rep.violations[k]) std::cerr << "compare: limit exceeded: " << v << "\n";
    failed = failed || !rep.violations[k].empty();
  }
  if (!o.quiet) std::cerr << "compare: report in " << o.out_dir << "/report.html and " << o.out_dir << "/report.md\n";
  if (errored) std::cerr << "compare: a run ended without a located answer (an error, or undecided: see its results.json)\n";
  return failed || errored ? kExitFailed : kExitDone;
}

void add_common_options(CLI::App* sub, CompareOpts& o) {
  o.settings.add(sub, OptionCommand::compare);
  sub->add_option("--dem-step", o.dem_step, "DEM increment of d only, m (default: --step)")->check(CLI::PositiveNumber);
  sub->add_option("--frames", o.frames, "Slider positions in report.html (default 60, 24 for scenes over 60 blocks)")->check(CLI::NonNegativeNumber);
  sub->add_option("--tolerances", o.tolerances,
                  "JSON limits {\"capacity\": 0.05, \"thrust\": 0.10, \"hinges\": true, \"hinge_shift\": 1}: exit code 1 when one is exceeded");
  sub->add_option("--notes", o.notes,
                  "Plain-text file of the author's notes on the result (paragraphs separated by blank lines), shown after the "
                  "tolerance checks, e.g. the mechanical reason a check fails");
  sub->add_flag("--quiet", o.quiet, "No progress lines and no summary: only warnings and why the exit code is not 0");
  sub->add_flag("--no-damped-rerun", o.no_damped_rerun,
                "Keep a DEM run that slid a joint where PRD's did not and statics does not ask for it, instead of running it again with "
                "contact damping (compare/README.md)");
}

}  // namespace

void add_compare_commands(CLI::App& app, Commands& out) {
  {
    auto o = std::make_shared<CompareOpts>();
    CLI::App* sub = app.add_subcommand("compare", "Run PRD and DEM on one case and write comparison.json, report.md and report.html");
    sub->add_option("case", o->case_path, "Case file (masonry-case/1 JSON)")->required();
    sub->add_option("--out", o->out_dir, "Output directory: prd/, dem/, comparison.json, report.md, report.html, figures/")->required();
    sub->add_option("--friction", o->frictions,
                    "DEM friction angle(s), degrees: one DEM run per value, each compared with the PRD run (default: the case's)");
    sub->add_option("--runs", o->runs,
                    "Compare finished runs instead of running: result directories (each with results.json), the first is the reference");
    add_common_options(sub, *o);
    out.push_back({sub, [o]() {
                     const Case c = o->settings.apply(load_case(o->case_path));
                     for (const std::string& line : idle_options(c.prd)) std::cerr << "compare: note: " << line << "\n";
                     for (const std::string& line : idle_options(c.dem)) std::cerr << "compare: note: " << line << "\n";
                     return run_compare(c, *o, o->case_path);
                   }});
  }
  {
    auto o = std::make_shared<CompareOpts>();
    o->out_dir = "out/demo";
    CLI::App* sub = app.add_subcommand(
        "demo", "The main job: PRD against DEM on the paper's pointed arch (built-in), under a minute; prints where the report is");
    sub->add_option("--out", o->out_dir, "Output directory (default out/demo)");
    sub->add_flag("--quiet", o->quiet, "No progress lines and no summary: only warnings, why the exit code is not 0 and where the report is");
    out.push_back({sub, [o]() {
                     // The standard case as the paper ran it: 1 mm increments, friction 35 deg and
                     // the joint stiffnesses divided by 10 (its Section 3.3), which is what brings
                     // the DEM under a minute (about 40 s here; undivided it takes a few times longer).
                     const Case c = with_option(standard_case("pointed-arch"), option_key(&DemOptions::stiffness_reduction), 10.0);
                     o->frictions = {35.0};
                     const int rc = run_compare(c, *o, "(built-in pointed-arch, dem.stiffness_reduction 10)");
                     std::cout << "Report: " << o->out_dir << "/report.html (open it in a browser) and " << o->out_dir << "/report.md\n";
                     return rc;
                   }});
  }
}

}  // namespace masonry
