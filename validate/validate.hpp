// `masonry validate`: every benchmark of a catalogue run on the methods it names, one row per
// benchmark and method, judged against the expected value and its tolerance.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/results.hpp"
#include "validate/catalogue.hpp"

namespace masonry {

// An outside solver judged by the catalogue (`masonry validate --solver`, README "Gate your own
// solver in CI"): a shell command that reads a masonry-case/1 file and writes a
// masonry-results/1 file.
struct OutsideSolver {
  std::string command;          // run by /bin/sh -c, "{case}" and "{out}" replaced by paths
  std::string name = "solver";  // the table's method column
  Method as = Method::prd;      // judged by this method's expected value and tolerance
  double timeout_s = 600;       // per run; a run past it is killed (its process group) and is an error
  std::string workdir;          // an existing directory: each run's case.json, out/ and solver.log go under it
  bool kept = false;            // workdir is the user's (--solver-keep) and stays: a failure names its run's files
};

// Runs the solver on case `c` in a directory of its own under workdir (named after `label`):
// writes case.json, makes an empty out/, runs the command (stdout and stderr to solver.log) and
// reads out/results.json through the results reader. Throws std::runtime_error, one line, when
// the command exits non-zero, times out or writes no results, or the reader refuses them (naming
// the file and the JSON path).
RunResult run_outside(const OutsideSolver& s, const Case& c, const std::string& label);

// Thrown by run_outside when the command is sent SIGINT, SIGTERM or SIGHUP while the solver runs:
// the solver (in a process group of its own, which a terminal's Ctrl-C does not reach) has been
// killed. Not a std::exception, so no row catches it: the command removes its temporary
// directory and ends by the same signal.
struct SolverInterrupted {
  int signal = 0;
};

struct ValidationRow {
  const Benchmark* benchmark = nullptr;
  Method method = Method::prd;
  std::string method_label;   // the table's method column: the method's name, or the outside solver's
  bool applicable = true;     // false: the quantity is none a results file gives, or no tolerance for the method (note says)
  bool solver_error = false;  // an outside solver failed (exit status, no file, a file the reader refuses)
  std::string unit;           // of expected, obtained, error and tolerance
  double expected = 0.0;
  double obtained = 0.0;
  double tolerance = 0.0;  // the limit on |obtained - expected|
  bool measured = false;   // false: no number came out (a run error, an undecided DEM hold)
  bool pass = false;
  // A DEM judged by its rerun with contact damping, its first run having slid where statics does
  // not ask for it (compare/README.md, "A slide statics does not ask for"): said in the table.
  bool damped_rerun = false;
  double seconds = 0.0;       // wall time of the row's runs (the reference method's included)
  std::string expected_from;  // the benchmark's source, or "PRD on the same case"
  std::string note;           // why no number came out, or what the number is (a bracket)
  double error() const { return obtained - expected; }
};

// Runs of one validation, by method and case: benchmarks that measure different quantities of
// the same run (a capacity, the reactions) share it.
struct RunCache {
  std::map<std::string, RunResult> runs;
  std::map<std::string, std::string> outside_errors;  // an outside solver's run that failed, by case: its reason
  int outside_runs = 0;                               // numbers the outside solver's run directories
};

// Runs one benchmark on each of its methods; `on_row` sees each row as it is finished. With an
// outside solver: one row, the solver judged as the method solver->as (not applicable when the
// benchmark has no tolerance for that method, or measures what a results file cannot give).
std::vector<ValidationRow> run_benchmark(const Catalogue& cat, const Benchmark& b, RunCache& cache,
                                         const std::function<void(const ValidationRow&)>& on_row = {}, const OutsideSolver* solver = nullptr);
// Whether a row counts against the exit code: it failed or errored (a not-applicable row does not).
inline bool failed(const ValidationRow& r) { return r.applicable && !r.pass; }

// Reports: a fixed-width table for the terminal, and JSON and Markdown documents.
std::string validation_table(const std::vector<ValidationRow>& rows);
// For each failing row: what was expected, from where, and what came out.
std::string validation_failures(const std::vector<ValidationRow>& rows);
// For each row that does not apply: why ("n/a NAME (METHOD): the results give no reactions").
std::string validation_not_applicable(const std::vector<ValidationRow>& rows);
nlohmann::ordered_json validation_json(const Catalogue& cat, const std::vector<ValidationRow>& rows);
std::string validation_markdown(const Catalogue& cat, const std::vector<ValidationRow>& rows, const std::string& command);

}  // namespace masonry
