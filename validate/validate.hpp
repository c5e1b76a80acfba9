// `masonry validate`: every benchmark of a catalogue run on the methods it names, one row per
// benchmark and method, judged against the expected value and its tolerance.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "validate/catalogue.hpp"
#include "model/results.hpp"

namespace masonry {

struct ValidationRow {
  const Benchmark* benchmark = nullptr;
  Method method = Method::prd;
  std::string unit;             // of expected, obtained, error and tolerance
  double expected = 0.0;
  double obtained = 0.0;
  double tolerance = 0.0;       // the limit on |obtained - expected|
  bool measured = false;        // false: no number came out (a run error, an undecided DEM hold)
  bool pass = false;
  double seconds = 0.0;         // wall time of the row's runs (the reference method's included)
  std::string expected_from;    // the benchmark's source, or "PRD on the same case"
  std::string note;             // why no number came out, or what the number is (a bracket)
  double error() const { return obtained - expected; }
};

// Runs of one validation, by method and case: benchmarks that measure different quantities of
// the same run (a capacity, the reactions) share it.
struct RunCache {
  std::map<std::string, RunResult> runs;
};

// Runs one benchmark on each of its methods; `on_row` sees each row as it is finished.
std::vector<ValidationRow> run_benchmark(const Catalogue& cat, const Benchmark& b, RunCache& cache,
                                         const std::function<void(const ValidationRow&)>& on_row = {});

// Reports: a fixed-width table for the terminal, and JSON and Markdown documents.
std::string validation_table(const std::vector<ValidationRow>& rows);
// For each failing row: what was expected, from where, and what came out.
std::string validation_failures(const std::vector<ValidationRow>& rows);
nlohmann::ordered_json validation_json(const Catalogue& cat, const std::vector<ValidationRow>& rows);
std::string validation_markdown(const Catalogue& cat, const std::vector<ValidationRow>& rows, const std::string& command);

}  // namespace masonry
