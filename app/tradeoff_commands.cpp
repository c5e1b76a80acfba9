// `masonry tradeoff CASE --out DIR`: a thin front end over the plan, run_plan and the reports.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/command.hpp"
#include "tradeoff/tradeoff.hpp"

namespace masonry {

namespace {

struct TradeoffOpts {
  std::string case_path, out_dir, plan_path, runs_dir, reference_prd, reference_dem;
  std::vector<std::string> methods{"prd", "dem"};
  std::vector<std::string> sets, varies;
  std::optional<int> repeat;
  double target_capacity = 0.01, target_thrust = 0.01;
  bool quick = false, resume = false, dry_run = false, quiet = false;
};

std::string num_text(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

// The command line that reproduces the measurement, for the report's header.
std::string command_line(const TradeoffOpts& o) {
  std::string s = "masonry tradeoff " + o.case_path + " --out " + o.out_dir;
  std::string m;
  for (const std::string& x : o.methods) m += (m.empty() ? "" : ",") + x;
  s += " --methods " + m;
  if (!o.plan_path.empty()) s += " --plan " + o.plan_path;
  if (o.quick) s += " --quick";
  if (o.repeat) s += " --repeat " + std::to_string(*o.repeat);
  for (const std::string& x : o.sets) s += " --set " + x;
  for (const std::string& x : o.varies) s += " --vary " + x;
  if (!o.reference_prd.empty()) s += " --reference-prd " + o.reference_prd;
  if (!o.reference_dem.empty()) s += " --reference-dem " + o.reference_dem;
  if (o.target_capacity != 0.01) s += " --target-capacity " + num_text(o.target_capacity);
  if (o.target_thrust != 0.01) s += " --target-thrust " + num_text(o.target_thrust);
  return s;
}

// --vary [METHOD:]KEY=V1,V2,...: the values of KEY for METHOD (or for every method that reads
// the key), replacing the plan's list.
void apply_vary(Plan& plan, const std::string& text, const std::vector<Method>& methods) {
  std::string rest = text, only;
  const size_t colon = text.find(':');
  const size_t eq = text.find('=');
  if (colon != std::string::npos && (eq == std::string::npos || colon < eq)) {
    only = text.substr(0, colon);
    rest = text.substr(colon + 1);
    if (!parse_method(only)) throw std::runtime_error("--vary " + text + ": unknown method '" + only + "' (prd, dem)");
  }
  const size_t e = rest.find('=');
  if (e == std::string::npos || e == 0 || e + 1 == rest.size()) throw std::runtime_error("--vary " + text + ": expected [METHOD:]KEY=V1,V2,...");
  const std::string key = rest.substr(0, e);
  std::vector<nlohmann::json> values;
  std::stringstream list(rest.substr(e + 1));
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.empty()) throw std::runtime_error("--vary " + text + ": empty value");
    values.push_back(parse_assignment(key + "=" + item, "--vary " + text).value);
  }
  bool used = false;
  for (const Method method : methods) {
    const std::string m = method_name(method);
    if (!only.empty() && m != only) continue;
    if (key.rfind(m + ".", 0) != 0 && key.rfind("motion.", 0) != 0) continue;
    // Through the plan parser, so a --vary value gets the checks a plan file gets.
    nlohmann::ordered_json j = plan_to_json(plan);
    if (!j.contains(m)) j[m] = {{"vary", nlohmann::ordered_json::object()}};
    j[m]["vary"][key] = nlohmann::ordered_json::parse(nlohmann::json(values).dump());
    plan = parse_plan(j.dump(), "--vary " + text);
    used = true;
  }
  if (!used) throw std::runtime_error("--vary " + text + ": no selected method reads '" + key + "'");
}

int run_tradeoff_command(const TradeoffOpts& o) {
  namespace fs = std::filesystem;
  Case base = load_case(o.case_path);
  Tradeoff t;
  for (const std::string& s : o.sets) {
    const CaseOption opt = parse_assignment(s, "--set");
    base = with_option(base, opt.key, opt.value);
    t.base.push_back(opt);
  }
  std::vector<Method> methods;
  for (const std::string& m : o.methods) {
    const std::optional<Method> method = parse_method(m);
    if (!method) throw std::runtime_error("--methods: unknown method '" + m + "' (prd, dem)");
    methods.push_back(*method);
  }
  Plan plan = o.plan_path.empty() ? default_plan(o.quick) : load_plan(o.plan_path);
  const std::string plan_source = o.plan_path.empty() ? (o.quick ? "(built-in quick plan)" : "(built-in plan)") : o.plan_path;
  for (const std::string& v : o.varies) apply_vary(plan, v, methods);
  if (o.repeat)
    for (auto& [name, m] : plan.methods) m.repeat = *o.repeat;
  RunOptions ro;
  ro.runs_dir = o.runs_dir.empty() ? (fs::path(o.out_dir) / "runs").string() : o.runs_dir;
  ro.resume = o.resume;
  std::vector<Method> reused;
  for (const auto& [method, dir] : {std::pair<Method, std::string>{Method::prd, o.reference_prd}, {Method::dem, o.reference_dem}}) {
    if (dir.empty()) continue;
    const std::string m = method_name(method);
    if (std::find(methods.begin(), methods.end(), method) == methods.end())
      throw std::runtime_error("--reference-" + m + " given, but " + m + " is not among --methods");
    // Fail before any long run when the reference cannot be read (results.json, or the .xz the
    // runs kept under reports/ are).
    if (!fs::exists(fs::path(dir) / "results.json") && !fs::exists(fs::path(dir) / "results.json.xz"))
      throw std::runtime_error(dir + "/results.json: no such file (--reference-" + m + ")");
    ro.reference_dir[method] = dir;
    reused.push_back(method);
  }
  const std::vector<PlannedRun> runs = expand_plan(base, plan, methods, plan_source, reused);
  if (!o.quiet || o.dry_run) {
    std::cerr << "tradeoff: " << runs.size() << " settings on " << base.name << ":\n";
    for (const PlannedRun& p : runs)
      std::cerr << "  " << method_name(p.setting.method) << "  " << p.setting.label << (p.repeat > 1 ? "  x" + std::to_string(p.repeat) : "") << "  ("
                << p.id << ")\n";
  }
  if (o.dry_run) {
    // Each run's case file, so a setting can be run (or resumed) by hand.
    for (const PlannedRun& p : runs) {
      fs::create_directories(fs::path(ro.runs_dir) / p.id);
      write_file_atomic((fs::path(ro.runs_dir) / p.id / "case.json").string(), case_to_json(p.c));
    }
    std::cerr << "tradeoff: dry run: case files in " << ro.runs_dir << "/<id>/case.json, nothing run\n";
    return 0;
  }
  t.case_name = base.name;
  t.d_unit = path_unit(base);
  t.command = command_line(o);
  t.plan = plan;
  t.methods = methods;
  t.target_capacity = o.target_capacity;
  t.target_thrust = o.target_thrust;
  fs::create_directories(o.out_dir);
  // Row by row as runs finish, so a long measurement that is stopped keeps its finished rows.
  const std::string csv_path = (fs::path(o.out_dir) / "tradeoff.csv").string();
  {
    std::ofstream csv(csv_path, std::ios::binary | std::ios::trunc);
    if (!csv) throw std::runtime_error(csv_path + ": cannot write");
    csv << csv_header();
  }
  if (!o.quiet) ro.progress = [](const std::string& s) { std::cerr << s << "\n" << std::flush; };
  t.rows = run_plan(base, runs, ro, [&](const Row& r) {
    std::ofstream csv(csv_path, std::ios::binary | std::ios::app);
    csv << csv_row(r) << std::flush;
  });
  write_tradeoff(o.out_dir, t);
  if (!o.quiet) {
    for (const std::string& s : summary_lines(t)) std::cerr << "tradeoff: " << s << "\n";
    std::cerr << "tradeoff: report in " << o.out_dir << "/report.html and " << o.out_dir << "/report.md\n";
  }
  bool ref_failed = false;
  for (const Row& r : t.rows) ref_failed = ref_failed || (r.reference && !r.ok());
  if (ref_failed) std::cerr << "tradeoff: a reference run did not finish: its method's errors are n/a\n";
  return ref_failed ? kExitFailed : kExitDone;
}

}  // namespace

void add_tradeoff_commands(CLI::App& app, Commands& out) {
  auto o = std::make_shared<TradeoffOpts>();
  CLI::App* sub = app.add_subcommand("tradeoff", "Run time against accuracy of the PRD and DEM settings: runs, Pareto front, report");
  sub->add_option("case", o->case_path, "Case file (masonry-case/1 JSON)")->required();
  sub->add_option("--out", o->out_dir, "Output directory: tradeoff.csv, tradeoff.json, report.md, report.html, figures/, runs/")->required();
  sub->add_option("--methods", o->methods, "Methods to measure, comma separated (default prd,dem)")->delimiter(',');
  sub->add_option("--plan", o->plan_path, "Plan file (masonry-tradeoff-plan/1, tradeoff/README.md) instead of the built-in plan");
  sub->add_flag("--quick", o->quick, "The reduced built-in plan (a few settings per method)");
  sub->add_option("--repeat", o->repeat, "Runs per setting, for every method (the time quoted is their median)")->check(CLI::Range(1, 1000));
  sub->add_option("--set", o->sets, "KEY=VALUE: change the case before everything (the baseline), e.g. dem.stiffness_reduction=10");
  sub->add_option("--vary", o->varies, "[METHOD:]KEY=V1,V2,...: the values of one option (numbers, true/false or x<factor> of the case's own)");
  sub->add_option("--reference-prd", o->reference_prd, "A finished PRD run (directory with results.json) to use as the PRD reference");
  sub->add_option("--reference-dem", o->reference_dem, "A finished DEM run (directory with results.json) to use as the DEM reference");
  sub->add_option("--runs-dir", o->runs_dir, "Where each run's case.json, results.json and steps.csv go (default OUT/runs)");
  sub->add_flag("--resume", o->resume, "Reuse a finished run in the runs directory whose case.json is the setting's");
  sub->add_flag("--dry-run", o->dry_run, "List the settings and write their case files; run nothing");
  sub->add_option("--target-capacity", o->target_capacity, "Capacity error counted as good enough in the summary (default 0.01)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--target-thrust", o->target_thrust, "Thrust error (/ W) counted as good enough in the summary (default 0.01)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--quiet", o->quiet, "No progress lines and no summary: only warnings and why the exit code is not 0");
  out.push_back({sub, [o]() { return run_tradeoff_command(*o); }});
}

}  // namespace masonry
