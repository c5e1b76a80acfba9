// Running one case by one method. One rule for writing results as the run goes: with a
// directory, results.json and steps.csv are rewritten after recorded steps (never spending more
// than about a fifth of the run's time on it: a long run with large files is written less often,
// a short one after every step) and always at the end, so a run stopped from outside, or one
// that fails later, keeps every finished step.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "dem/dem.hpp"
#include "model/case.hpp"
#include "model/method.hpp"
#include "model/results.hpp"
#include "prd/prd.hpp"

namespace masonry {

struct RunOutput {
  std::string dir;                                // results.json and steps.csv; empty: nowhere
  std::function<void(const RunResult&)> on_step;  // after each recorded step (progress lines)
  double* write_cpu_s = nullptr;                  // when given, receives the thread CPU time spent writing (not the solver's)
};

// At the case's own settings (PrdSettings::from_case, DemSettings::from_case). Input the solver
// refuses (settings, geometry it cannot model) throws, as loading a case does: nothing ran; so
// does a case whose supports do not move (CaseError: no loading path) unless it asks for no step.
RunResult run_case(const Case& c, Method m, const RunOutput& out = {});
// At explicit settings (a study's variant of the case's own).
RunResult run_prd(const Case& c, const PrdSettings& s, const RunOutput& out = {});
RunResult run_dem(const Case& c, const DemSettings& s, const RunOutput& out = {});

// For studies that go on past one bad run (sweep, tradeoff): what run_case throws becomes a run
// stopped by "error" with the message, written to the directory like any other.
RunResult run_case_in_study(const Case& c, Method m, const RunOutput& out = {});

// PRD on a DEM run's deformed configuration (model/results.hpp, PrdOnRun): from its last
// equilibrium at or before 0.9 of its capacity, near enough to the collapse to carry most of
// the deformation and far enough for PRD to have a path; events located to the run's collapse
// bracket (bracket_fraction x step). Nothing for a run that is not a DEM's or has no answer.
std::optional<PrdOnRun> prd_on_run(const Case& c, const RunResult& run);

}  // namespace masonry
