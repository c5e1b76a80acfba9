// Parameter sweeps: one case run by PRD and/or DEM over a full-factorial grid of case options
// (sweep/README.md). A sweep file (masonry-sweep/1) names the case, the methods and the options
// to vary; the plan lists the runs; the table (DIR/sweep.csv) gets one row per finished run, so
// an interrupted sweep resumes; the report sets the DEM capacity against the friction angle
// beside the PRD capacity. Runs go to local threads, or to MPI ranks under mpirun.
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

struct SweepSpec {
  std::string source;       // the sweep file, for messages
  std::string name;         // title (default: the case's name)
  std::string description;
  std::string case_ref;     // as written: a path (ending in .json) or a standard case name
  std::vector<std::string> methods;  // "prd", "dem" (at least one)
  std::vector<SweepAxis> vary;       // at least one
  std::vector<std::pair<std::string, nlohmann::json>> set;  // options fixed for every run
  double tolerance = 0.05;  // |diff_prd| above this is a disagreement (report only)
};

// Parses a masonry-sweep/1 document; `source` names the file in messages. Throws SweepError.
SweepSpec parse_sweep(const std::string& text, const std::string& source);

// What every MPI rank needs to rebuild the same plan: the texts, not the paths (rank 0 reads
// the files and broadcasts them, so other machines need none of them).
struct SweepInput {
  std::string spec_text, spec_source;
  std::string case_text, case_source;  // a standard case: its case_to_json, source = its name
};
// Reads the sweep file and the case it names (relative to the sweep file's directory).
SweepInput read_sweep_input(const std::string& spec_path);

struct SweepRun {
  int index = 0;
  std::string method;                  // "prd" or "dem"
  std::vector<nlohmann::json> values;  // per plan key; null where the option does not apply
  std::string id;                      // 16 hex digits: the case, the method and the values
  int prd = -1;                        // DEM run: the PRD run with the same non-DEM values
};

struct SweepPlan {
  std::string source;  // the sweep file
  std::string name, description;
  Case base;           // the case with the spec's "set" applied
  std::vector<std::string> methods;
  std::vector<std::string> keys;  // varied options, in the spec's order
  std::vector<SweepRun> runs;     // PRD runs first, then DEM; each in factorial order
  std::string hash;               // 16 hex digits over the base case and the runs
  double tolerance = 0.05;
};

// The full factorial over spec.vary (last key fastest). DEM options ("dem.*") do not change a
// PRD run, so PRD runs are one per distinct combination of the other options. Throws SweepError
// for a key that is not a case option ("set" values are checked here; a refused "vary" value is
// a failed run, unless every value of the key is refused).
SweepPlan plan_sweep(const SweepSpec& spec, const Case& c);
SweepPlan plan_sweep(const SweepInput& in);
// The case of one run: the base case with the run's values applied. Throws CaseError.
Case case_of_run(const SweepPlan& p, const SweepRun& r);
// "dem.friction_angle=20, motion.step=0.001" (only the values that apply).
std::string run_label(const SweepPlan& p, const SweepRun& r);
// A value as shown in the table: strings bare, numbers in their shortest exact form.
std::string value_text(const nlohmann::json& v);

// One finished run.
struct SweepRow {
  int index = -1;
  std::string id;
  std::string method;
  // collapse, max_steps, undecided (a DEM hold that neither settled nor ran away: the capacity
  // is the last equilibrium, not a located collapse) or error; never running.
  RunStatus status = RunStatus::error;
  double capacity = 0;  // m, the last stable d; not shown for an error
  double time_s = 0;    // run time without I/O
  std::string message;  // one line
  // PRD: the sliding check's required_friction_angle of the run (deg), when the solver gives it.
  std::optional<double> required_friction_angle;
};
// Whether the row's capacity is a located answer (collapse or the end of the path): only those
// are compared, drawn and counted as done; an undecided or failed row is listed with its reason.
bool located(const SweepRow& r);
nlohmann::json row_to_json(const SweepRow& r);
SweepRow row_from_json(const nlohmann::json& j);

// Runs one planned run; never throws: a failure is a row with stopped "error" and the message.
SweepRow execute_run(const SweepPlan& p, const SweepRun& r);

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

// DIR/sweep.json (masonry-sweep-results/1): the table and the summary, for CI.
nlohmann::ordered_json sweep_json(const SweepPlan& p, const SweepTable& t, const SweepSummary& s);
// SVG: capacity against x, DEM points per curve, PRD capacity as a horizontal line, the PRD
// sliding prediction and the disagreement boundary as vertical lines.
std::string svg_sweep(const SweepPlan& p, const SweepTable& t, const SweepSummary& s);
std::string sweep_markdown(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command);
std::string sweep_html(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command);
// Writes DIR/sweep.csv (sorted), DIR/sweep.json, DIR/report.md, DIR/report.html and
// DIR/figures/capacity.svg, each atomically.
void write_sweep_outputs(const std::string& dir, const SweepPlan& p, const SweepTable& t, const std::string& command);

struct SweepOptions {
  std::string out_dir;
  int jobs = 0;          // threads; 0: the hardware's (under MPI: 1 per rank)
  bool restart = false;  // discard an existing sweep.csv instead of resuming it
  bool quiet = false;    // no progress lines
  std::string command;   // shown in the report
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
