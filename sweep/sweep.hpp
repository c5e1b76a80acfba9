// Parameter sweeps: one case run by PRD and/or DEM over a full-factorial grid of case options or
// of a generator's parameters, or over a Latin hypercube sample of them (sweep/README.md). A
// sweep file (masonry-sweep/1) names the case (a file, a standard case or a generator call), the
// methods and the options to vary or sample; the plan lists the runs; the table (DIR/sweep.csv)
// gets one row per finished run, so an interrupted sweep resumes; the report sets the DEM
// capacity against the friction angle beside the PRD capacity, and the sensitivity of the
// capacity to each option (sensitivity.json). Runs go to local threads, or to MPI ranks.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// Bad sweep input or an output directory that belongs to another sweep: one line naming the
// file and the field.
struct SweepError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One varied option: a dotted case option (with_option) and its values, in the file's order.
struct SweepAxis {
  std::string key;
  std::vector<nlohmann::json> values;  // numbers, strings or booleans
};

// A sampled option: values drawn from [lo, hi].
struct SweepRange {
  std::string key;
  double lo = 0, hi = 0;
};

// A sampled sweep (the file's "sample"): a Latin hypercube of `count` points over the ranges
// (sweep/design.cpp), drawn from `seed`; besides the samples, the base point (every option at
// the case's own value) and, per range, `levels` evenly spaced values from lo to hi with the
// other options at the base point (the one-at-a-time lines the tornado chart draws).
struct SweepSample {
  int count = 0;
  unsigned long long seed = 0;
  std::vector<SweepRange> ranges;  // the file's order
  int levels = 3;                  // one-at-a-time values per range; 0: no base point, no lines
  std::vector<int> only;           // sample numbers to run (0-based, increasing); empty: all
};

// The options of a sweep over a generator's parameters are "generator.NAME".
inline constexpr const char* kGeneratorPrefix = "generator.";

struct SweepSpec {
  std::string source;  // the sweep file, for messages
  std::string name;    // title (default: the case's name)
  std::string description;
  std::string case_ref;                                  // as written: a path (ending in .json) or a standard case name; "" for a generator
  std::string generator;                                 // a generator call {"generator": NAME, "parameters": {...}}: its name
  nlohmann::json parameters = nlohmann::json::object();  // and its parameters
  std::vector<Method> methods;                           // at least one
  std::vector<SweepAxis> vary;                           // a grid: at least one (none with `sample`)
  std::optional<SweepSample> sample;
  std::vector<std::pair<std::string, nlohmann::json>> set;  // options fixed for every run
  double tolerance = 0.05;                                  // |diff_prd| above this is a disagreement (report only)
};

// A Latin hypercube of n points in [0, 1)^k, points[i][j] (sweep/design.cpp): each column j holds
// one point in each of the n strata [s/n, (s+1)/n), at a uniform position within its stratum,
// the columns' strata paired by independent random permutations. Column j is drawn from a
// stream of its own, seeded by `seed` and names[j], so it does not depend on the other columns or
// their order. Portable: std::mt19937_64, whose output the C++ standard fixes, with our own
// conversions (the standard's distributions are not portable), so a seed gives the same points
// on any compiler.
std::vector<std::vector<double>> latin_hypercube(int n, const std::vector<std::string>& names, unsigned long long seed);

// Parses a masonry-sweep/1 document; `source` names the file in messages. Throws SweepError.
SweepSpec parse_sweep(const std::string& text, const std::string& source);

// What every MPI rank needs to rebuild the same plan: the texts, not the paths (rank 0 reads
// the files and broadcasts them, so other machines need none of them).
struct SweepInput {
  std::string spec_text, spec_source;
  // A standard case: its case_to_json, source = its name; a generator call: empty (the spec has it).
  std::string case_text, case_source;
};
// Reads the sweep file and the case it names (relative to the sweep file's directory).
SweepInput read_sweep_input(const std::string& spec_path);

// Where a run lies in the design: a grid point, or in a sampled sweep the base point, a point of
// a one-at-a-time line, or a sample.
enum class SweepPoint { grid, base, one_at_a_time, sample };

struct SweepRun {
  int index = 0;
  Method method = Method::prd;
  std::vector<nlohmann::json> values;  // per plan key; null where the option does not apply
  std::string id;                      // 16 hex digits: the case, the method, the values (and the sample)
  int prd = -1;                        // DEM run: the PRD run with the same non-DEM values
  SweepPoint point = SweepPoint::grid;
  int sample = -1;  // SweepPoint::sample: its number in the design
  int line = -1;    // SweepPoint::one_at_a_time: the key (index) it varies
};

struct SweepPlan {
  std::string source;  // the sweep file
  std::string name, description;
  Case base;                                                    // the case with the spec's "set" applied
  std::string generator;                                        // a generator call: its name ("" otherwise)
  nlohmann::json parameters;                                    // and its parameters with the "set" ones (generator.NAME)
  std::vector<std::pair<std::string, nlohmann::json>> options;  // "set"'s case options, applied after the generator
  std::vector<Method> methods;
  std::vector<std::string> keys;            // varied or sampled options, in the spec's order
  std::vector<nlohmann::json> base_values;  // per key: its value in the base case (null: none)
  std::optional<SweepSample> sample;        // a sampled sweep
  // A PRD-only sweep: the keys PRD ignores (DEM options), which give it no other run.
  std::vector<std::string> prd_ignores;
  // PRD runs carry the sliding check (the friction angle report's prediction) unless "set" says
  // prd.sliding_check: it costs 25 times the run itself on the cathedral.
  bool sliding_check = true;
  std::vector<SweepRun> runs;  // PRD runs first, then DEM; each in factorial order
  std::string hash;            // 16 hex digits over the base case and the runs
  double tolerance = 0.05;
};

// The full factorial over spec.vary (last key fastest), or the sampled design (the base point,
// the one-at-a-time lines, the samples). DEM options ("dem.*") do not change a PRD run, so PRD
// runs are one per distinct combination of the other options. Throws SweepError for a key that
// is not a case option or generator parameter ("set" values are checked here; a refused "vary"
// value is a failed run, unless every value of the key is refused).
SweepPlan plan_sweep(const SweepSpec& spec, const Case& c);
SweepPlan plan_sweep(const SweepInput& in);
// The case of one run: the base case with the run's values applied (a generator's parameters
// generate the case again, then "set"'s options and the run's other options apply). Throws
// CaseError.
Case case_of_run(const SweepPlan& p, const SweepRun& r);
// "base", "one-at-a-time", or the sample number: the `sample` column of a sampled sweep.
std::string point_text(const SweepRun& r);
// The one line a PRD-only sweep over options PRD ignores prints and its report shows; "" when
// it varies none.
std::string prd_ignores_note(const SweepPlan& p);
// "dem.friction_angle=20, motion.step=0.001" (only the values that apply).
std::string run_label(const SweepPlan& p, const SweepRun& r);
// A value as shown in the table: strings bare, numbers in their shortest exact form.
std::string value_text(const nlohmann::json& v);

// One finished run.
struct SweepRow {
  int index = -1;
  std::string id;
  Method method = Method::prd;
  // collapse, max_steps, undecided (a DEM hold that neither settled nor ran away: the capacity
  // is the last equilibrium, not a located collapse) or error; never running.
  RunStatus status = RunStatus::error;
  double capacity = 0;  // m, the last stable d; not shown for an error
  double time_s = 0;    // run time without I/O
  std::string message;  // one line
  // PRD: the sliding check's required_friction_angle of the run (deg), when the solver gives it.
  std::optional<double> required_friction_angle;
  // The hinges at collapse, "v3/v4:A v9/v10:B" (joints by block ids, the corner each turns about;
  // sweep/mechanism.cpp); "" when there are none or the run failed.
  std::string hinges;
  // With --keep-runs: the run's files, written by the process that records the row to
  // DIR/runs/ID/ (never in sweep.csv).
  struct Files {
    std::string case_json, results_json, steps_csv;
  };
  std::optional<Files> files;
};
// Whether the row's capacity is a located answer (collapse or the end of the path): only those
// are compared, drawn and counted as done; an undecided or failed row is listed with its reason.
bool located(const SweepRow& r);
nlohmann::json row_to_json(const SweepRow& r);
SweepRow row_from_json(const nlohmann::json& j);

// Runs one planned run; never throws: a failure is a row with stopped "error" and the message.
// With `keep`, the row carries the run's files.
SweepRow execute_run(const SweepPlan& p, const SweepRun& r, bool keep = false);
// The hinges at collapse of a finished run of case c (sweep/mechanism.cpp): PRD's collapse
// mechanism where it located one, else the hinges of the last equilibrium (a DEM's measured
// beyond its settled gaps, as compare/ does), and for a DEM with none there that collapsed,
// those of the state its failed hold was called a collapse in.
std::string hinges_at_collapse(const Case& c, const RunResult& r);
// The labels of hinges_at_collapse's string, one per hinge (ids may hold spaces, never ':').
std::vector<std::string> hinge_labels(const std::string& hinges);
// The members a set of hinges lies in, {"R-pier/R-aisle", "nave"}: each hinge's two block ids
// without their trailing number (a voussoir's or a course's), one name where both are the same
// member, each member or pair once, sorted. Coarser than the hinges themselves: geometry that
// moves a hinge by a voussoir, or renumbers the courses, keeps its members.
std::vector<std::string> members_of(const std::string& hinges);
// Members for a table: "R-pier/R-aisle, nave".
std::string join_members(const std::vector<std::string>& members);

// (cap_dem - cap_prd) / cap_prd of a DEM row against its PRD row; nullopt when either is
// missing or failed, or the PRD capacity is 0.
std::optional<double> diff_prd(const SweepRow& dem, const SweepRow* prd);

// sweep.csv: the header, and one line per row (rows[i] is the row of run i or absent).
using SweepTable = std::vector<std::optional<SweepRow>>;
std::string sweep_csv_header(const SweepPlan& p);
std::string sweep_csv_line(const SweepPlan& p, const SweepRow& r, const SweepTable& t);
std::string sweep_csv(const SweepPlan& p, const SweepTable& t);
// Reads a sweep.csv back: complete rows only (a torn last line, or a line with missing fields,
// is left out so the run is done again). Throws SweepError when the file belongs to another
// sweep: other columns, or a row whose id is not a run of this plan.
SweepTable read_sweep_csv(const SweepPlan& p, const std::string& text, const std::string& source);

// The report's numbers: capacity against one varied option x (dem.friction_angle when varied,
// else the first numeric key), one curve per combination of the other options.
struct SweepCurve {
  std::vector<std::pair<std::string, nlohmann::json>> fixed;  // the other options' values
  // Its runs with a result, by increasing x: DEM runs (PRD runs in a sweep without DEM); each
  // DEM run's PRD reference is p.runs[i].prd.
  std::vector<int> runs;
  // x = dem.friction_angle only: the largest friction angle at which |diff_prd| > tolerance,
  // and whether every DEM run at or below it disagrees and every one above agrees.
  std::optional<double> boundary;
  bool boundary_clean = true;
};
struct SweepSummary {
  std::string x;  // "" when no key is numeric
  std::vector<SweepCurve> curves;
  int finished = 0, errors = 0;
};
SweepSummary summarize(const SweepPlan& p, const SweepTable& t);

// The sensitivity of the capacity to the varied or sampled options (sweep/sensitivity.cpp,
// DIR/sensitivity.json), per method. Only located rows count.
struct ParameterSensitivity {
  std::string key;
  // d ln(capacity) / d ln(x) (`log`), or d ln(capacity) / d x where the key takes values <= 0;
  // how it was estimated in `estimate`; from the n runs with a positive capacity.
  std::optional<double> elasticity, standard_error;
  bool log = true;
  int n = 0;
  std::string estimate;
  std::optional<double> spearman;  // sampled: rank correlation of x and the capacity, all samples
  // The one-at-a-time line: x and the capacity along it, the other options at the base point
  // (a sampled sweep) or at their middle values (a grid), and the capacity there.
  std::vector<double> values, capacities;
  std::optional<double> base_value, base_capacity;
  bool ignored = false;  // a DEM option in the PRD's rows: PRD ignores it
};
struct MechanismShare {
  std::string hinges;  // SweepRow::hinges; "" for none (a run that ends standing)
  int count = 0;
  double share = 0;            // of the counted rows
  double median_capacity = 0;  // m
};
struct NearestSample {
  int run = -1, sample = -1;
  double capacity = 0;
};
struct MethodSensitivity {
  Method method = Method::prd;
  int counted = 0;            // the rows it is computed from: the samples (sampled), every run (grid)
  int located = 0, zero = 0;  // of them: with a located capacity; of those, capacity 0
  // Sampled: the 5th, 50th and 95th percentiles of the samples' capacities (linear
  // interpolation between order statistics), and the sample nearest each.
  std::vector<std::pair<int, double>> percentiles;
  std::vector<NearestSample> nearest;
  double min = 0, max = 0;
  std::optional<double> r2;                // sampled: the log-log regression's coefficient of determination
  std::vector<MechanismShare> mechanisms;  // most frequent first
  std::vector<MechanismShare> members;     // the same grouped by members_of (its `hinges`: the members)
  // Each member (or pair) of members_of alone: the rows whose hinges at collapse include it.
  std::vector<MechanismShare> member_frequency;
  std::vector<ParameterSensitivity> parameters;  // per plan key
};
// A DEM row beside the PRD row of the same values.
struct PrdDemPair {
  int dem = -1, prd = -1;  // runs
  int sample = -1;
  double prd_capacity = 0, dem_capacity = 0;
};
struct SweepSensitivity {
  bool sampled = false;
  std::vector<MethodSensitivity> methods;  // in the plan's order of methods
  std::vector<PrdDemPair> pairs;
};
SweepSensitivity sensitivity(const SweepPlan& p, const SweepTable& t);
// DIR/sensitivity.json (masonry-sensitivity/1).
nlohmann::ordered_json sensitivity_json(const SweepPlan& p, const SweepSensitivity& s);
// Figures: the one-at-a-time ranges as a tornado chart (one per method), the samples'
// capacities as a histogram, PRD against DEM per point; "" when there is nothing to draw.
std::string svg_tornado(const SweepPlan& p, const MethodSensitivity& m);
std::string svg_histogram(const SweepPlan& p, const SweepTable& t, const MethodSensitivity& m);
std::string svg_prd_dem(const SweepPlan& p, const SweepSensitivity& s);

// DIR/sweep.json (masonry-sweep-results/1): the table and the summary, for CI.
nlohmann::ordered_json sweep_json(const SweepPlan& p, const SweepTable& t, const SweepSummary& s);
// SVG: capacity against x, DEM points per curve, PRD capacity as a horizontal line, the PRD
// sliding prediction and the disagreement boundary as vertical lines.
std::string svg_sweep(const SweepPlan& p, const SweepTable& t, const SweepSummary& s);
std::string sweep_markdown(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command);
std::string sweep_html(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command);
// Writes DIR/sweep.csv (sorted), DIR/sweep.json, DIR/sensitivity.json, DIR/report.md,
// DIR/report.html and the figures (capacity.svg, tornado.svg, histogram.svg, prd-dem.svg, each
// where it has something to draw), each atomically.
void write_sweep_outputs(const std::string& dir, const SweepPlan& p, const SweepTable& t, const std::string& command);

struct SweepOptions {
  std::string out_dir;
  int jobs = 0;            // threads; 0: the hardware's (under MPI: 1 per rank)
  bool restart = false;    // discard an existing sweep.csv instead of resuming it
  bool quiet = false;      // no progress lines
  bool keep_runs = false;  // every run's case.json, results.json and steps.csv in DIR/runs/ID/
  std::string command;     // shown in the report
};

// Runs the sweep on this machine: resumes DIR/sweep.csv, runs the missing runs (PRD on the
// calling thread, DEM on `jobs` threads), appends each row as it finishes, then writes the
// sorted table and the report. Returns the table. Throws SweepError for bad input.
SweepTable run_sweep(const SweepInput& in, const SweepOptions& o);

// True when this process was started by mpirun (Open MPI's or a PMIx launcher's environment).
bool started_by_mpirun();
// The same under MPI: rank 0 reads the files and the existing table, every rank runs the
// missing runs whose position in the to-do list is its rank modulo the size, rank 0 gathers
// the rows and writes everything. Returns the exit code (rank 0: as run_sweep's caller would).
int run_sweep_mpi(const std::string& spec_path, const SweepOptions& o);

}  // namespace masonry
