// Inside the sweep library: what its files share, the local runner (run.cpp) and the MPI runner
// (mpi.cpp) above all.
#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "runs/progress.hpp"
#include "sweep/sweep.hpp"

namespace masonry::sweep_detail {

// The row of run i, or nullptr where the table has none (table.cpp).
const SweepRow* row_at(const SweepTable& t, int i);
// Whether an option is the DEM's ("dem.*"): PRD ignores it (spec.cpp).
bool is_dem_option(const std::string& key);
// FNV-1a, 64 bits: run ids, the plan's hash, the design's column streams (spec.cpp).
uint64_t fnv1a(const std::string& s);

// The plan, the rows an earlier invocation finished, and the runs still to do. Preparing rewrites
// DIR/sweep.csv with those rows only (sorted, without a torn last line), ready for appending.
struct Prepared {
  SweepPlan plan;
  SweepTable table;
  std::vector<int> todo;  // run indices, increasing
  std::string csv_path;
};
Prepared prepare(const SweepInput& in, const SweepOptions& o);

// Appends each finished row to sweep.csv at once (one line, flushed), keeps it in the table and
// prints the progress line; at the end writes the sorted table and the report.
class Recorder {
 public:
  Recorder(Prepared& pr, const SweepOptions& o, int workers, const std::string& where);
  void operator()(const SweepRow& r);
  // Returns the exit code: 0, or 1 when a run failed.
  int finish();

 private:
  Prepared& pr_;
  const SweepOptions& o_;
  std::ofstream file_;
  size_t done_ = 0;
  StudyProgress progress_;
};

// Runs `todo`: PRD runs on the calling thread, then DEM runs on `jobs` threads (with `keep`, each
// row carries its run's files). `done` is called
// on the calling thread for every finished row (so it may use MPI); `idle`, if given, every few
// milliseconds while the threads work.
void execute_runs(const SweepPlan& p, const std::vector<int>& todo, int jobs, bool keep, const std::function<void(const SweepRow&)>& done,
                  const std::function<void()>& idle);

}  // namespace masonry::sweep_detail
