// The speed/accuracy trade of the solvers' settings: a plan of settings per method (one factor
// at a time from the case's own settings, a few combined ones, and a most accurate reference),
// the runs, their errors against the reference (capacity and thrust curves, through
// compare_runs), the Pareto front of run time against error, and the reports. The format of the
// plan file and every choice are in tradeoff/README.md.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// ---- The plan ----------------------------------------------------------------------------

// One case option ("motion.step", "dem.hold_time", ...; see with_option) and its value. In a
// plan a value may be relative, a string "x<factor>": the case's own value times the factor.
struct CaseOption {
  std::string key;
  nlohmann::json value;
};

// A setting to measure: case options applied to the baseline (the case as given, with --set).
struct Setting {
  Method method = Method::prd;
  std::string parameter;  // what it varies: a case option key, "baseline", "reference", "combined"
  std::string label;      // shown in tables and figures ("motion.step=0.002", "fast")
  std::vector<CaseOption> options;
};

struct MethodPlan {
  int repeat = 1;                                                         // runs per setting; the time quoted is their median
  bool baseline = true;                                                   // run the case's own settings (off when a reused reference is the baseline)
  std::vector<CaseOption> reference;                                      // the most accurate setting
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> vary;  // key -> values, in order
  std::vector<Setting> combined;                                          // label and options
};

struct Plan {
  std::map<Method, MethodPlan> methods;
};

// Parses a plan file (masonry-tradeoff-plan/1, README). Throws std::runtime_error with one line
// naming `source` and the field.
Plan parse_plan(const std::string& text, const std::string& source);
Plan load_plan(const std::string& path);
// The built-in plans (also in README): full, or reduced for --quick.
Plan default_plan(bool quick);
// The plan as JSON (the format parse_plan reads).
nlohmann::ordered_json plan_to_json(const Plan& p);

// A setting resolved against a case: relative values turned into numbers, the case with the
// options applied and validated (so a bad value fails before any run).
struct PlannedRun {
  Setting setting;  // options with absolute values
  std::string id;   // run directory name: method and options, file-name safe
  bool reference = false;
  bool baseline = false;
  int repeat = 1;
  Case c;
};

// Settings of `methods` in run order per method: reference, baseline, the one-factor variations
// (values equal to the baseline's skipped), then the combined settings. A setting whose options
// come to the same case as an earlier one is left out. Changing motion.step without
// motion.max_steps keeps the path length: max_steps becomes ceil(baseline travel / step).
// Throws std::runtime_error (one line naming the plan source and the option) for a value the
// case refuses or a relative value of an option the case has no number for.
// `reused_references`: methods whose reference is a finished run read back (--reference-*): its
// planned settings are not compared with the others'.
std::vector<PlannedRun> expand_plan(const Case& base, const Plan& plan, const std::vector<Method>& methods, const std::string& plan_source,
                                    const std::vector<Method>& reused_references = {});

// The case's current value of a dotted option (null when absent).
nlohmann::json case_option(const Case& c, const std::string& key);
// Parses "KEY=VALUE" (VALUE as JSON if it parses, else a string); throws naming `what`.
CaseOption parse_assignment(const std::string& text, const std::string& what);

// ---- Results ---------------------------------------------------------------------------------

// One measured setting.
struct Row {
  Method method = Method::prd;
  std::string parameter, label, id;
  std::vector<CaseOption> options;
  bool reference = false, baseline = false;
  std::string source;   // where the run is (its directory), or the reused run's directory
  bool reused = false;  // read back (--reference-*, --resume) instead of run here
  bool given = false;   // the reference is a finished run given with --reference-* (options unknown)
  RunStatus status = RunStatus::running;
  bool ok() const { return located(status); }  // its capacity is an answer: a collapse or max_steps
  std::string message;                         // why a run failed
  int repeats = 0;
  // The time of a setting: the median over the repeats of the CPU time of the solver call,
  // measured here on the calling thread (the solvers are single-threaded), which a busy machine
  // does not inflate; for a run read back (--reference-*, --resume of a run without timing.json)
  // the run's own timing.total_s. `cpu` says which.
  double time_s = 0.0;
  double time_min_s = 0.0, time_max_s = 0.0;
  bool cpu = false;
  double wall_s = 0.0;  // median of the runs' own timing.total_s (wall time without I/O)
  long long lp_solves = 0, cycles = 0;
  int steps = 0;          // records of the run
  double capacity = 0.0;  // m
  // Against the method's reference (NaN when either run failed): relative capacity difference
  // (signed), largest and rms thrust-curve difference over the total weight.
  double capacity_err = 0.0;
  double thrust_max_err = 0.0, thrust_rms_err = 0.0;
  // m: the common range of d the thrust curves were compared over, [0, min of the capacities].
  // When it is empty (one run's capacity is 0) and the reference's is not, there is nothing to
  // compare beyond the initial state and the thrust errors are NaN.
  double thrust_range = 0.0;
};

// Indices of the Pareto-optimal points (minimising both time and error), in order of increasing
// time (and so strictly decreasing error). Points with a non-finite coordinate are left out; of
// identical points the first is kept.
struct ParetoPoint {
  double time = 0.0;
  double error = 0.0;
};
std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points);

// A step along a Pareto front, from a faster point to the next slower one: error reduction
// bought per extra second.
struct Buy {
  size_t from = 0, to = 0;  // indices into the points
  double gain = 0.0;        // error(from) - error(to) > 0
  double cost_s = 0.0;      // time(to) - time(from) > 0
  double rate = 0.0;        // gain / cost_s
};
// The steps of a front (as returned by pareto_front), best rate first.
std::vector<Buy> best_buys(const std::vector<ParetoPoint>& points, const std::vector<size_t>& front);

enum class ErrorKind { capacity, thrust };
// |capacity_err| or thrust_max_err of each row against run time (NaN for failed rows).
std::vector<ParetoPoint> points_of(const std::vector<Row>& rows, ErrorKind kind);

struct Tradeoff {
  std::string case_name;
  std::string d_unit = "m";      // the path parameter's SI unit (path_unit): "m" or "rad"
  std::string command;           // how it was made (shown verbatim, escaped)
  std::vector<CaseOption> base;  // --set options: the baseline's difference from the case file
  Plan plan;
  std::vector<Method> methods;
  std::vector<Row> rows;          // in run order; per method the reference first
  double target_capacity = 0.01;  // "good enough" thresholds for the summary
  double target_thrust = 0.01;    // W
};

// ---- Running ---------------------------------------------------------------------------------

struct RunOptions {
  std::string runs_dir;                              // each run's results.json goes to runs_dir/<id>/ ("": not kept)
  std::map<Method, std::string> reference_dir;       // method -> finished run directory used as its reference
  bool resume = false;                               // reuse runs_dir/<id>/ when it holds a finished run of the same setting
  std::function<void(const std::string&)> progress;  // one line per event (may be empty)
};

// Runs every planned setting (the reference of each method first, so each row's errors are
// known when it finishes) and calls `on_row` after each. A run that fails is recorded with its
// message and the rest go on. Throws only for a reference directory that cannot be read.
std::vector<Row> run_plan(const Case& base, const std::vector<PlannedRun>& runs, const RunOptions& o,
                          const std::function<void(const Row&)>& on_row = {});

// ---- Reports ---------------------------------------------------------------------------------

std::string csv_header();
std::string csv_row(const Row& r);
nlohmann::ordered_json tradeoff_json(const Tradeoff& t);
// Sentences computed from the data: per method and error, the Pareto front and the settings
// that buy most accuracy per second, and the fastest setting within the targets.
std::vector<std::string> summary_lines(const Tradeoff& t);
// Time (log scale) against capacity error and against thrust error for one method's rows, the
// Pareto-optimal points ringed and joined.
std::string svg_pareto(const Tradeoff& t, Method method);
std::string tradeoff_markdown(const Tradeoff& t);
std::string tradeoff_html(const Tradeoff& t);
// DIR/tradeoff.json, DIR/tradeoff.csv (whole, rewritten), DIR/report.md, DIR/report.html,
// DIR/figures/pareto-<method>.svg.
void write_tradeoff(const std::string& dir, const Tradeoff& t);

}  // namespace masonry
