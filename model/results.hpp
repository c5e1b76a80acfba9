// Results of a capacity run, in the shape both methods write (results.json and steps.csv).
// Solvers fill these structs; only the writers below touch files.
#pragma once

#include <cmath>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/io.hpp"

namespace masonry {

struct Reaction {
  std::string support;  // block id
  Vec2 force{0, 0};     // N, force the structure receives from the support (sum over its joints)
  double moment = 0.0;  // N m, about the support's `about` point (its centroid if fixed)
};

struct OpenCorner {
  int joint = -1;     // index into RunResult::joints
  int corner = 0;     // 0 = A, 1 = B
  double gap = 0.0;   // m, normal opening at the end of the step
};

struct JointForce {
  int joint = -1;
  double normal = 0.0;      // N, compressive resultant (>= 0)
  double shear = 0.0;       // N, along the joint tangent
  Vec2 point{0, 0};         // application point of the resultant, current configuration
  Vec2 n{0, 0};             // unit normal of the joint (out of block i), current configuration
};

struct Pose {
  double x = 0, y = 0, angle = 0;  // centroid (m) and rotation since the start (rad)
};

// PRD's sliding check of one configuration (PrdSettings::sliding_check), degrees. PRD's
// kinematics forbid sliding, so its forces need not respect a friction limit; this says how much
// friction they need.
struct SlidingCheck {
  double demand_angle = 0.0;    // atan(|T|/N) of the step's dual joint forces, largest over the joints
  int demand_joint = -1;
  double required_angle = 0.0;  // least friction angle for which some admissible force state avoids sliding
  int required_joint = -1;
};

// The sliding check over a whole run (prd's sliding_summary): the most demanding steps.
struct SlidingSummary {
  bool any = false;                     // some step carries the check (else only lp_solves)
  double required_friction_angle = 0;   // deg: largest required_angle over the steps
  double d = 0;                         // m, where
  int step = 0;
  std::string joint;                    // "i/j" block ids
  double max_demand_angle = 0;          // deg: largest demand_angle over the steps
  double demand_d = 0;                  // m
  std::string demand_joint;
  long long lp_solves = 0;              // the check's feasibility LPs
};

struct StepRecord {
  int index = 0;     // 0 = initial configuration
  double d = 0.0;    // path parameter after this step, m
  double energy = 0.0;  // total potential energy of the loads relative to the start, J
  std::vector<OpenCorner> open_corners;
  std::vector<int> cracked;          // joints with at least one open corner
  std::vector<Reaction> reactions;   // one per support block
  std::vector<Pose> poses;           // one per block (supports included), in case order
  std::vector<JointForce> forces;    // one per joint carrying force
  std::optional<SlidingCheck> sliding;  // PRD with the sliding check
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();  // method-specific fields
};

struct JointInfo {
  int i = -1, j = -1;  // block indices
  Vec2 a{0, 0}, b{0, 0};  // endpoints in the initial configuration
};

struct Timing {
  double total_s = 0.0;  // PRD: wall time of the run without I/O; DEM: the run's thread CPU time
  double lp_s = 0.0;     // PRD: time in GLPK
  long long lp_solves = 0;
  // PRD (event-driven): evaluations of an LP's final basis at another configuration (where a
  // planned move would end) without simplex iterations, one factorisation each; their time is
  // in lp_s.
  long long basis_evaluations = 0;
  long long cycles = 0;  // DEM: integration cycles
};

// How a run ended; results.json writes its name as "stopped".
enum class RunStatus {
  running,    // the results handed out while the run goes on (a run stopped from outside stays so)
  collapse,   // the structure collapsed: the capacity is the last equilibrium before it
  max_steps,  // the loading path ended with the structure standing: the capacity is its end
  // DEM: a hold neither settled nor ran away within its cap; the capacity is the last
  // equilibrium, not a located collapse
  undecided,
  error,  // the run failed; `message` says why
};
const char* status_name(RunStatus s);
// The status named `name`, or nothing for a name that is none of them.
std::optional<RunStatus> parse_status(const std::string& name);
// Whether a run that ended so located its capacity (a collapse, or the end of the path): only
// such capacities are compared, drawn and timed as answers.
bool located(RunStatus s);
std::ostream& operator<<(std::ostream& o, RunStatus s);  // its name (test messages, logs)

struct RunResult {
  std::string method;           // "prd" or "dem"
  std::string case_name;
  double capacity = 0.0;        // m, the last stable d
  int stable_steps = 0;
  bool collapsed = false;
  RunStatus status = RunStatus::running;
  std::string message;
  double total_weight = 0.0;    // N, masonry::total_weight(case): what the supports carry vertically
  std::vector<JointInfo> joints;
  std::vector<StepRecord> steps;
  Timing timing;
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();
  std::optional<SlidingSummary> sliding;  // PRD with the sliding check
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();  // method-specific, top level
};

// Throws std::runtime_error naming the step and the quantity when a record holds a number that
// is not finite: a run whose state turned non-finite stops with an error, never a result.
void require_finite(const StepRecord& s);

// PRD started from a DEM run's configuration (prd/prd.hpp, PrdStart; runs/run.hpp, prd_on_run)
// with each touching joint corner's elastic offset kept as the joint's geometry, and with it
// taken back, beside PRD from the case's own geometry, all located to the same tolerance: how
// much of the DEM's difference from PRD is the geometry its elastic joints deform to.
struct PrdOnRun {
  double from_d = 0.0;      // m: the run's equilibrium record PRD starts from
  double tolerance = 0.0;   // m: how closely PRD locates its events (the DEM's collapse bracket)
  double kept = NAN;        // m: PRD's capacity with the offsets kept (NaN: not located)
  double taken_back = NAN;  // m: with them taken back
  double own = NAN;         // m: PRD from the case's own geometry
};

// Whether a record is an equilibrium: every PRD record (its collapse configuration is not
// among them); a DEM record whose hold settled, not the failed state closing a run.
bool is_equilibrium(const RunResult& r, const StepRecord& s);
// The last equilibrium record at or before d (m), or nullptr where there is none.
const StepRecord* last_equilibrium(const RunResult& r, double d);
// JSON has no NaN or infinity: a non-finite number is written as null, never silently as 0.
// Every JSON writer (results, comparisons, sweeps, trade-offs) writes its numbers through this.
nlohmann::ordered_json json_number(double x);
// {"from_d", "tolerance", "kept", "taken_back", "own"}, m, as comparison and study files write it.
nlohmann::ordered_json prd_on_run_json(const PrdOnRun& p);

nlohmann::ordered_json to_json(const RunResult& r, const Case& c);
// One row per step: step, d, energy, open corners, cracked joints, then Fx and Fy of every support.
std::string steps_csv(const RunResult& r);
// Writes DIR/results.json and DIR/steps.csv, each through a temporary file and a rename, so a
// reader (or a later failure) never sees a half-written file. Creates DIR.
void write_results(const std::string& dir, const RunResult& r, const Case& c);

// Reads a results.json (masonry-results/1) written for case `c` back into a RunResult; throws
// std::runtime_error naming the file and field for anything that does not fit the case.
RunResult parse_results(const std::string& text, const Case& c, const std::string& source);
// load_results reads `path`, or `path`.xz where only that is there (read_text_or_xz).
RunResult load_results(const std::string& path, const Case& c);

}  // namespace masonry
