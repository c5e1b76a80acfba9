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
#include "model/method.hpp"

namespace masonry {

struct Reaction {
  std::string support;  // block id
  Vec2 force{0, 0};     // N, force the structure receives from the support (sum over its joints)
  double moment = 0.0;  // N m, about the support's `about` point (its centroid if fixed)
};

struct OpenCorner {
  int joint = -1;    // index into RunResult::joints
  int corner = 0;    // 0 = A, 1 = B
  double gap = 0.0;  // m, normal opening at the end of the step
};

struct JointForce {
  int joint = -1;
  double normal = 0.0;  // N, compressive resultant (>= 0)
  double shear = 0.0;   // N, along the joint tangent
  Vec2 point{0, 0};     // m: on the resultant's line of action, nearest its normal forces' centre (on_line_of_action), current configuration
  Vec2 n{0, 0};         // unit normal of the joint (out of block i), current configuration
};

struct Pose {
  double x = 0, y = 0, angle = 0;  // centroid (m) and rotation since the start (rad)
};

// PRD's sliding check of one configuration (PrdSettings::sliding_check), degrees. PRD's
// kinematics forbid sliding, so its forces need not respect a friction limit; this says how much
// friction they need.
struct SlidingCheck {
  double demand_angle = 0.0;  // atan(|T|/N) of the step's dual joint forces, largest over the joints
  int demand_joint = -1;
  double required_angle = 0.0;  // least friction angle for which some admissible force state avoids sliding
  int required_joint = -1;
};

// The sliding check over a whole run (prd's sliding_summary): the most demanding steps.
struct SlidingSummary {
  bool any = false;                    // some step carries the check (else only lp_solves)
  double required_friction_angle = 0;  // deg: largest required_angle over the steps
  double d = 0;                        // m, where
  int step = 0;
  std::string joint;            // "i/j" block ids
  double max_demand_angle = 0;  // deg: largest demand_angle over the steps
  double demand_d = 0;          // m
  std::string demand_joint;
  long long lp_solves = 0;  // the check's feasibility LPs
};

// A joint corner: index into RunResult::joints and the corner (0 = A, 1 = B).
struct CornerRef {
  int joint = -1;
  int corner = 0;
};

// PRD: the optima of the step's LP, the loads' potential energy over the step (J), primal and
// dual; LP duality makes them equal (validate's duality_gap benchmarks).
struct LpOptima {
  double primal = 0.0;  // written as lp_primal
  double dual = 0.0;    // written as lp_dual
};

// PRD with corners held closed (prd.hold_closed): a held corner's force in the step's force state.
struct HeldCorner {
  std::string corner;  // "BLOCK/BLOCK:A", as the results name corners
  double force = 0.0;  // N, negative: a tension
};

// The DEM's hold that ended a record (dem/README.md, "Protocol: every recorded state is an equilibrium or a collapse"): how it ended
// and what it cost. The names are the fields results.json writes in the step.
// What a hold that did not settle travelled over the first and the second half of its last cap
// (dem/README.md, "At the cap: creep or still settling"): m, the largest block displacement.
struct CapTravel {
  double first_half = 0.0, second_half = 0.0;
};
struct DemHold {
  std::string hold_end;           // "equilibrium", "collapse", "creep" or "undecided"
  bool bracket = false;           // a trial of the collapse bracket
  long long cycles = 0;           // of the move and the hold
  long long move_cycles = 0;      // of the move
  double lag = 0.0;               // what the structure travelled during the hold over what it did during the move
  double hold_time = 0.0;         // s, model time of the hold
  double unbalanced_ratio = 0.0;  // of the last cycle: max over free blocks of max(|F|, |M|/r) / W
  double max_speed = 0.0;         // m/s
  double drift = 0.0;             // m, largest block displacement since the hold began
  long long contact_points = 0;
  double max_overlap = 0.0;             // m
  std::optional<CapTravel> cap_travel;  // a hold that ended "creep" or "undecided"
};

struct StepRecord {
  int index = 0;        // 0 = initial configuration
  double d = 0.0;       // path parameter after this step, m
  double energy = 0.0;  // total potential energy of the loads relative to the start, J (NaN: not given)
  std::vector<OpenCorner> open_corners;
  std::vector<int> cracked;         // joints with at least one open corner
  std::vector<Reaction> reactions;  // one per support block
  std::vector<Pose> poses;          // one per block (supports included), in case order
  std::vector<JointForce> forces;   // one per joint carrying force
  // Whether the record is an equilibrium; absent: it is. The DEM writes it for every record
  // (false: the failed state that closes a run).
  std::optional<bool> settled;
  std::optional<DemHold> hold;           // the DEM
  std::optional<LpOptima> lp;            // PRD
  std::vector<HeldCorner> held_corners;  // PRD with corners held closed
  std::optional<SlidingCheck> sliding;   // PRD with the sliding check
};

struct JointInfo {
  int i = -1, j = -1;     // block indices
  Vec2 a{0, 0}, b{0, 0};  // endpoints in the initial configuration
};

struct Timing {
  double total_s = 0.0;  // the run's thread CPU time without I/O (PRD and DEM)
  double lp_s = 0.0;     // PRD: CPU time solving LPs (GLPK, and the kept basis)
  long long lp_solves = 0;
  // PRD: of those, the LPs solved by the previous LP's basis without GLPK (prd/kept_basis.hpp).
  long long kept_basis_solves = 0;
  // PRD: LPs solved by the interior point, a large structure's (prd/interior.hpp); a later LP that
  // its solution still solves counts as kept above.
  long long interior_solves = 0;
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

// A change of mechanism (PRD): a closed corner opens, an open one closes, or the collapse.
enum class EventKind { open, close, collapse };
const char* event_kind_name(EventKind k);
struct Event {
  EventKind kind = EventKind::open;
  double d = 0.0;                  // m
  double within = 0.0;             // m: the event lies in (d - within, d]
  std::vector<CornerRef> corners;  // written as "joints", with the joint's blocks
};

// A collapse mechanism (PRD): the corners it opens and the blocks it moves.
struct Mechanism {
  std::vector<CornerRef> open_corners;
  std::vector<int> moving_blocks;  // block indices (written as ids)
};
// PRD's collapse: the mechanism on the configuration at d, and that configuration.
struct Collapse {
  Mechanism mechanism;
  double d = 0.0;           // m
  std::vector<Pose> poses;  // one per block
  // One per block, or none (results written before it): the configuration moved along the
  // collapse mechanism alone (the supports held, every increment boxed to at most one step), so
  // that the mechanism can be compared where the last step's own motion moves no joint.
  std::vector<Pose> moved_poses;
};

// The DEM's collapse bracket (dem/README.md): the last equilibrium, the failed increment's end,
// and every trial that narrowed it.
struct BracketTrial {
  double d = 0.0;   // m
  std::string end;  // how its hold ended: "equilibrium", "collapse", "creep" or "undecided"
  long long cycles = 0;
  bool confirm = false;  // the confirming hold of DemSettings::confirm_collapse
  bool followed = false;  // the bracket's upper end held on: a creep (the follow stage) or a collapse (the landing stage)
};
struct CollapseBracket {
  double equilibrium = 0.0, failed = 0.0, width = 0.0;  // m
  std::vector<BracketTrial> trials;
};
// A failure the confirming hold did not confirm (DemSettings::confirm_collapse): the run went on.
struct UnconfirmedFailure {
  double d = 0.0, reached_from = 0.0, settled_from = 0.0;  // m
};
// A creep at the collapse bracket's upper end that settled when held on (dem_run's follow
// stage): the structure passed to another branch at d, and the run went on.
struct SettledCreep {
  double d = 0.0;        // m
  int holds = 0;         // holds it was held on for
  double time = 0.0;     // s of model time those holds took
};

// A collapse at the collapse bracket's upper end that came to rest when held on (dem_run's
// landing stage): the structure snapped through, from the equilibrium at `from` to another
// branch at d, and the run went on.
struct SettledSnap {
  double d = 0.0;      // m (rad where the supports only turn), where it landed
  double from = 0.0;   // the last equilibrium before it, same unit
  double drift = 0.0;  // m, the largest block displacement between the two equilibria
  double time = 0.0;   // s of model time of the hold it landed in
};

struct RunResult {
  std::string method;  // method_name(Method), or an outside solver's own name (known_method)
  std::string case_name;
  std::string version;    // the code that made it: masonry's version_text(), or the solver's
  double capacity = 0.0;  // m, the last stable d
  int stable_steps = 0;   // index of the last equilibrium record at or before the capacity
  bool collapsed = false;
  RunStatus status = RunStatus::running;
  std::string message;
  double total_weight = 0.0;  // N, masonry::total_weight(case): what the supports carry vertically
  std::vector<JointInfo> joints;
  std::vector<StepRecord> steps;
  Timing timing;
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();  // the method's settings as run, free-form
  std::optional<SlidingSummary> sliding;                               // PRD with the sliding check
  std::optional<std::vector<Event>> events;                            // PRD
  std::optional<Collapse> collapse;                                    // PRD, a run that collapsed
  std::optional<double> wall_s;                                        // DEM: wall time of the run without I/O, s
  std::optional<CollapseBracket> collapse_bracket;                     // DEM, a located failure
  // DEM: the collapse was located as a limit point (no equilibrium at the bracket's upper end,
  // which creeps without slowing down; no runaway seen). Written only when true.
  bool limit_point = false;
  std::vector<UnconfirmedFailure> unconfirmed_failures;  // DEM (confirm_collapse)
  std::vector<SettledCreep> settled_creeps;              // DEM (the follow stage)
  std::vector<SettledSnap> settled_snaps;                // DEM (the landing stage)
};

// The method that made a run, where it is one of ours (an outside solver's run: nothing), and
// the label people read: "PRD", "DEM", or the outside solver's name.
std::optional<Method> known_method(const RunResult& r);
std::string method_label(const RunResult& r);

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

// Whether a record is an equilibrium: one that does not say otherwise (`settled`), whichever
// method made it: every PRD record (its collapse configuration is not among them), a DEM record
// whose hold settled, not the failed state closing a run.
bool is_equilibrium(const RunResult& r, const StepRecord& s);
// The last equilibrium record at or before d (m), or nullptr where there is none.
const StepRecord* last_equilibrium(const RunResult& r, double d);
// JSON has no NaN or infinity: a non-finite number is written as null, never silently as 0.
// Every JSON writer (results, comparisons, sweeps, trade-offs) writes its numbers through this.
nlohmann::ordered_json json_number(double x);
// {"from_d", "tolerance", "kept", "taken_back", "own"}, m, as comparison and study files write it.
nlohmann::ordered_json prd_on_run_json(const PrdOnRun& p);
// {"open_corners": [{"joint", "corner"}], "moving_blocks": [ids]}, as results.json and
// `masonry check --json` write a mechanism.
nlohmann::ordered_json mechanism_json(const Mechanism& m, const Case& c);

nlohmann::ordered_json to_json(const RunResult& r, const Case& c);
// A CSV field as RFC 4180 writes it: quoted, quotes doubled, where it holds a comma, a quote or a
// line break (an id may hold any of them), so every row of a file has the header's columns.
std::string csv_field(const std::string& s);
// One row per step: step, d, energy, open corners, cracked joints, then Fx and Fy of every support
// (the case's support blocks in its order, as both solvers record them; named from the case so
// that a run with no step, a structure that does not stand as drawn, has the same header).
std::string steps_csv(const RunResult& r, const Case& c);
// Writes DIR/results.json and DIR/steps.csv, each through a temporary file and a rename, so a
// reader (or a later failure) never sees a half-written file. Creates DIR.
void write_results(const std::string& dir, const RunResult& r, const Case& c);

// Reads a results.json (masonry-results/1, schemas/masonry-results.schema.json) written for case
// `c`, by masonry or by an outside solver, into a RunResult. Only format, method, case, capacity,
// stopped and the steps' step and d are required; what a file leaves out stays empty (numbers
// it does not give are NaN: energy, timing.total_s), and total_weight comes from the case. Throws
// std::runtime_error, one line naming the file and the JSON path ("steps[3]: field 'd' ..."), for a field of
// the wrong type, an unknown field, or results that do not fit each other or the case: a
// capacity outside [0, the last d], d decreasing, step indices not consecutive, stable_steps
// other than the last equilibrium's index, an unknown status, a block, support or joint the
// case or the file does not have.
RunResult parse_results(const std::string& text, const Case& c, const std::string& source);
// load_results reads `path`, or `path`.xz where only that is there (read_text_or_xz).
RunResult load_results(const std::string& path, const Case& c);

}  // namespace masonry
