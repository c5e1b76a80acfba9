// The spread of a DEM convergence study (dem/convergence.hpp): the capacity at each setting that
// must not matter against the default's, the spread across them, and the default against PRD.
// Reads RunResults only; writes convergence.json and convergence.md.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "compare/compare.hpp"
#include "model/results.hpp"

namespace masonry {

// What a study's runs vary: settings that must not matter (a check: spread and PRD limits), or the
// joints' stiffness (a measurement: each run against PRD, no limits; dem/variants.hpp).
enum class Study { convergence, stiffness };
const char* study_name(Study s);  // "convergence", "stiffness": the study's file names

struct ConvergenceEntry {
  std::string name, what;  // the variant
  RunResult run;
  std::optional<PrdOnRun> prd_on_run;
};

struct Convergence {
  Study study = Study::convergence;
  std::string case_name;
  std::vector<ConvergenceEntry> entries;  // the default first
  std::optional<double> prd_capacity;     // m
  // With the case and PRD's run, the report also says where each run's mechanism parts from
  // the default's, and the default's from PRD's (hinges_part, joints open wider than
  // 5e-5 x the scene size: 2 mm on the cathedrals, 0.1 mm on the pointed arch).
  const Case* scene = nullptr;
  std::optional<RunResult> prd;
  double spread_limit = 0.02;  // (max - min) / default capacity
  double prd_limit = 0.03;     // |default - PRD| / PRD
};

// A stiffness study has no limits: ok when it is complete.
struct ConvergenceVerdict {
  bool complete = false;  // every run ended in a located collapse or max_steps
  double spread = NAN;    // (max - min) / default over the runs, NaN when a run failed
  // The same over the runs at the default's joint stiffness (kn), the protocol's settings alone.
  // The joints' stiffness belongs to the structure: a run at another kn may differ by the
  // geometry its joints deform to (PRD on its configuration says), which no protocol removes.
  double protocol_spread = NAN;
  double prd_error = NAN;  // (default - PRD) / PRD
  bool ok = false;         // complete, spread and PRD error within their limits
  // Complete and the protocol spread within the limit: the DEM answers for the structure it was
  // given, whatever the joints' stiffness and PRD's capacity then show.
  bool protocol_converged = false;
  std::vector<std::string> problems;  // one sentence each, empty when ok
};

ConvergenceVerdict judge(const Convergence& c);
// One word for the verdict, the same in the command's line and the study's files: "converged"
// (every limit met), "converged over the protocol" (the protocol spread within its limit, the
// joints' stiffness or PRD beyond one), "NOT shown converged"; a stiffness study "complete" or
// "incomplete".
const char* verdict_name(Study s, const ConvergenceVerdict& v);
nlohmann::ordered_json convergence_json(const Convergence& c);
std::string convergence_markdown(const Convergence& c);

}  // namespace masonry
