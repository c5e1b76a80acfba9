// PRD against DEM (or any two runs of one case): capacities, thrust curves, hinges, mechanism
// changes and run times, in numbers (compare_runs, to_json), against limits for CI
// (check_tolerances) and as reports people read (report.hpp). Reads RunResults only: it never
// calls a solver, and solvers never call it.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// Limits for CI. Absent limits are not checked.
struct Tolerances {
  std::optional<double> capacity;  // largest |cap_b - cap_a| / |cap_a|
  std::optional<double> thrust;    // largest |reaction component difference| / total weight
  bool hinges = false;             // hinge locations must match (or mirror-match) at every check
  // How many joints along a ring a hinge may sit from the other run's (0: the same joint). Where
  // the thrust line runs along a ring's edge over several voussoirs, which of their joints
  // opens is not decided by the mechanics: PRD itself moves such hinges by a joint when its step
  // is halved (compare/README.md, "Hinges one joint apart").
  int hinge_shift = 0;
  // Largest |cap_b - cap_a|, m. With `capacity` too, the capacities may differ by the larger of
  // the two limits (as a catalogue's tolerance): an absolute limit judges a reference capacity
  // near 0, or one step of an incremental run.
  std::optional<double> capacity_abs = std::nullopt;
  // The least mechanism agreement (0 to 1) over the checked intervals of d (MotionCheck): the two
  // runs' joints must move the same way, by their relative motion weighted by the forces they
  // carry (compare/README.md, "Mechanism agreement").
  std::optional<double> mechanism = std::nullopt;
  // The least agreement of the mechanisms the runs collapse by (the MotionCheck from each run's
  // last equilibrium to its collapse state). Apart from `mechanism`: a DEM's collapse state is its
  // fall when a block has drifted 2% of the scene (on the cathedral 0.9 m), PRD's the
  // configuration one step past its capacity, neither of them the collapse's first motion.
  std::optional<double> collapse_mechanism = std::nullopt;
};
// The largest hinge_shift looked for (HingeCheck::shift is -1 beyond it).
inline constexpr int kMaxHingeShift = 3;
// Parses {"capacity": 0.05, "capacity_abs": 0.002, "thrust": 0.10, "mechanism": 0.9, "collapse_mechanism": 0.5,
// "hinges": true, "hinge_shift": 1}; unknown keys and
// wrong types throw std::runtime_error naming the file and the key.
Tolerances parse_tolerances(const std::string& text, const std::string& source);
Tolerances load_tolerances(const std::string& path);

// A hinge: a joint with exactly one open corner; it turns about the closed one.
struct Hinge {
  int joint = -1;        // index into the run's joints
  int i = -1, j = -1;    // the joint's blocks
  int corner = 0;        // the closed corner: 0 = A, 1 = B
  std::string label;     // "v3/v4:A", corner_name (block ids: case text, escape before display)
  Vec2 point{0, 0};      // the closed corner, initial configuration
  double opening = 0.0;  // m, the open corner's gap beyond its gap in the run's first record
  // Fewest joints along a ring to a hinge of the other run turning about the same side (0: the
  // same joint), -1 when none is within kMaxHingeShift. Set by compare_runs (not mirrored).
  int apart = -1;
};

struct HingeCheck {
  double d = 0.0;               // requested d, m
  double d_a = 0.0, d_b = 0.0;  // the records used (the last record at or before d)
  std::vector<Hinge> a, b;
  bool match = false;   // same hinges
  bool mirror = false;  // b's hinges are the mirror image of a's (symmetric scenes only)
  // Fewest joints along a ring that some hinge must move for the two sets to agree, directly or
  // as mirror images: 0 when they match or mirror-match, -1 when more than kMaxHingeShift.
  int shift = -1;
  bool ok(int allowed_shift = 0) const { return shift >= 0 && shift <= allowed_shift; }
};

// How one joint moved over an interval in one run: the relative rotation of its two blocks, how
// far each corner opened (negative: closed), and the slip along the joint.
struct JointMotion {
  double rotation = 0.0;              // rad: the higher-indexed block's turn relative to the other's
  double open_a = 0.0, open_b = 0.0;  // m: corner A's and B's separation along the joint's normal
  double slip = 0.0;                  // m: the corners' mean relative displacement along the joint
};
// A joint where two runs' motions differ, with what each run does there.
struct MotionDiff {
  int joint = -1;       // index into run a's joints
  std::string label;    // "blockA/blockB" (case text: escape before display)
  double share = 0.0;   // its part of the squared difference of the two unit motions (0 to 1)
  double weight = 0.0;  // the normal force it carries, over W (both runs, both ends, averaged)
  JointMotion a, b;     // b mirrored when the agreement is the mirror image's
};
// Whether two runs move the same way over one checked interval of d. Each run's motion is the
// vector of every joint corner's relative displacement increment (the two blocks' copies of the
// corner, in the lower-indexed block's frame, so the rigid motion the supports impose on a pair
// counts for nothing), each joint's entries weighted by the normal force it carries over W
// (averaged over both runs at both ends): a work scale, so a joint that carries the structure
// counts and an unloaded one hardly. The agreement is the cosine of the two vectors, 0 below 0:
// 1 for the same mechanism at any amplitude, 0 for motions at other joints or in other
// directions (compare/README.md, "Mechanism agreement").
struct MotionCheck {
  double from = 0.0, to = 0.0;                                // m: the interval of the common range; `to` NaN for the collapse
  bool collapse = false;                                      // each run from its last equilibrium to its collapse state
  double a_from = 0.0, a_to = 0.0, b_from = 0.0, b_to = 0.0;  // m: d of the records used
  bool a_moves = false, b_moves = false;                      // some joint corner moves beyond round-off (1e-9 of the scene)
  // 0 to 1; NaN unless both runs' joints move. With CompareOptions::ring_shift n > 0, the better
  // of the two runs' motions with either's moved along rings by up to n joints to meet the other's
  // (a hinge one voussoir or course along is the same mechanism, "Hinges one joint apart").
  double agreement = std::numeric_limits<double>::quiet_NaN();
  double same_joints = std::numeric_limits<double>::quiet_NaN();  // the agreement with every motion where it is
  bool mirror = false;                                            // the agreement of b's mirror image (a symmetric scene), higher than the direct one
  std::vector<MotionDiff> differ;                                 // the joints that differ most, largest share first (up to 3)
};
// A run's collapse state: the DEM's failed hold past its capacity, PRD's configuration one step
// past it (where its last mechanism took the blocks); nothing for a run that did not collapse.
std::optional<StepRecord> collapse_state(const RunResult& r);
// The mechanism checks of two runs of case c: one per interval between consecutive d of `ds`
// (from 0), each run read at its last record at or before each end, and, when both collapsed,
// one from each run's last equilibrium to its collapse state. On a symmetric scene the mirror
// image of b counts when it agrees better; along rings, motions `shift` joints apart count as the
// same joint's (MotionCheck::agreement).
std::vector<MotionCheck> mechanism_checks(const Case& c, const RunResult& a, const RunResult& b, const std::vector<double>& ds, int shift = 0);

// How far each run's joints slid along themselves over the common range (compare/README.md,
// "Sliding"): at each joint (run a's), the relative displacement along the joint of the corner
// that opened less, between the run's first record and its last at or before `to`. That corner
// is the one in contact (a hinge's pivot, which a rotation about it does not move along the
// joint): a rigid-block mechanism without sliding gives none, a joint's elastic shear microns,
// friction slip as far as the joint slid.
struct JointSlip {
  int joint = -1;                                  // index into run a's joints, -1 when none
  std::string label;                               // joint_name, "blockA/blockB" (case text: escape before display)
  double a = std::numeric_limits<double>::quiet_NaN();  // m, |net slip| in run a (NaN: the joint came apart)
  double b = std::numeric_limits<double>::quiet_NaN();  // m, in run b
};
struct SlipCheck {
  double to = 0.0;         // m: each run read from its first record to its last at or before this d
  double a_to = 0.0, b_to = 0.0;  // m: those last records' d
  JointSlip largest_a;     // the joint run a slid most at, with run b's slip there
  JointSlip largest_b;     // the joint run b slid most at, with run a's
};
// A joint whose corner in contact opened by more than min_gap came apart, and is left out.
SlipCheck slip_check(const Case& c, const RunResult& a, const RunResult& b, double to, double min_gap);

// Where a run's structure jumped between two consecutive stable records (compare/README.md,
// "Jumps"; compare/jumps.cpp): a free block moved more than kJumpRatio times as far as the
// supports carried any point (path_travel_per_d x the change of d), and more than kJumpFloor of
// the scene: a snap through to another equilibrium that the run followed. A mechanism carries a
// block a few times the supports' travel at most (up to 3.3 times over the PRD steps of the
// standard scenes and the zoo); the pointed arch's hinge passing near d = 0.1 m moves one 9.5 times.
constexpr double kJumpRatio = 5.0;
constexpr double kJumpFloor = 1e-3;
struct Jump {
  double from = 0.0, to = 0.0;  // d of the two records (m, or rad where the supports only turn)
  double drift = 0.0;           // m, the largest free block displacement between them
  std::string block;            // the block that moved most (case text: escape before display)
};
std::vector<Jump> jumps(const Case& c, const RunResult& r);

// Horizontal (H = Fx / W) and vertical (V = Fy / W) reaction of one support against d, for both
// runs, on the common d grid.
struct SupportCurve {
  std::string support;  // block id
  std::vector<double> h_a, v_a, h_b, v_b;
  double max_diff = 0.0;  // largest |difference| of either component
};

struct RunSummary {
  std::string label;      // "PRD", "DEM phi=35", ...
  std::string method;     // "prd" or "dem"
  double capacity = 0.0;  // m
  bool collapsed = false;
  RunStatus status = RunStatus::running;
  double step = 0.0;            // m, the run's increment (from the records)
  double time_s = 0.0;          // run time without I/O
  std::vector<double> changes;  // d (m) where the mechanism changes
};

struct Comparison {
  std::string case_name;
  double total_weight = 0.0;  // N (of run a)
  RunSummary a, b;
  double capacity_rel_diff = 0.0;  // (cap_b - cap_a) / cap_a; NaN if cap_a == 0 and cap_b != 0
  double d_max = 0.0;              // common range [0, d_max], d_max = min of the capacities
  std::vector<double> d;           // the d the thrust curves are compared at (CompareOptions::thrust_grid)
  std::vector<SupportCurve> supports;
  double thrust_max_diff = 0.0;  // largest over supports and components, / W
  double thrust_max_d = 0.0;     // m, where it occurs
  std::string thrust_max_where;  // "H of left" (support id: case text)
  double thrust_rms_diff = 0.0;  // root-mean-square over supports, components and grid points
  bool symmetric = false;        // the block geometry is its own mirror image about x = xc
  double hinge_gap = 0.0;        // m, opening beyond the settled gap a hinge needs (settled_gap)
  std::vector<HingeCheck> hinges;
  std::vector<MotionCheck> motion;  // mechanism agreement per checked interval
  std::optional<SlipCheck> sliding;  // how far the joints slid over the common range (with the mechanism checks)
  std::vector<Jump> jumps_a, jumps_b;  // each run's snaps through, over its own stable records
  int ring_shift = 0;               // the CompareOptions::ring_shift it was measured with
  std::string d_unit = "m";         // the path parameter's SI unit (path_unit): "m" or "rad"
  double time_ratio = 0.0;          // time_b / time_a (NaN when time_a is 0)
  // What a run's results do not give is not compared (a results file need give only its
  // capacity and steps): the reason, or empty when compared. Thrust curves need every run's
  // reactions, hinges its joints and open corners, the mechanism agreement its joints, poses
  // and forces at every record.
  std::string thrust_skipped, hinges_skipped, mechanism_skipped;
};

// Where two runs' thrust curves are compared.
enum class ThrustGrid {
  every_record,  // every record of either run, each run interpolated between its own (the comparison's)
  // Only at the records of the run with fewer records in the common range, the other run
  // interpolated there: neither is read between two of its records across a jump it did not
  // resolve (the trade-off's, whose settings step differently: a DEM arch's settled thrust falls
  // to the minimum thrust over the first step, so a run read half way through that step against
  // one recorded there differs by the jump, not by accuracy).
  coarser_run,
};

struct CompareOptions {
  ThrustGrid thrust_grid = ThrustGrid::every_record;
  // How many joints along a ring a mechanism's motion may sit from the other run's and count as
  // the same joint's (Tolerances::hinge_shift; make_report passes the tolerances').
  int ring_shift = 0;
  // Fractions of the common range at which hinge locations are compared.
  std::vector<double> hinge_fractions{0.1, 0.25, 0.5, 0.75, 1.0};
  // A mechanism state (set of open corners) held for fewer consecutive records than this is
  // flicker: it is merged into the state before it, so the change list shows what a reader
  // would call a change of mechanism. 1 keeps every change.
  int min_state_records = 2;
};

// Both runs must come from `c` (same blocks, in order). Labels default to the method names.
Comparison compare_runs(const Case& c, const RunResult& a, const RunResult& b, const CompareOptions& o = {}, const std::string& label_a = "",
                        const std::string& label_b = "");

// The stable records of a run: those with d <= capacity (the collapse record is left out).
std::vector<const StepRecord*> stable_records(const RunResult& r);
// The last of `recs` at or before d (records in order of d; the first when d is before them all).
const StepRecord* record_at(const std::vector<const StepRecord*>& recs, double d);
// The step between the first two records (m), 0 with fewer than two.
double record_step(const std::vector<const StepRecord*>& recs);
// The widest gap of a run's settled state (its first record, d = 0), m; 0 without one. A DEM's
// joints are compliant: settling under gravity shortens tall piers unequally and opens gaps up
// to this wide with no support motion at all. The motion redistributes the same weight over the
// same joints, so elastic gap changes anywhere in the structure are of this size too (on the
// cathedral: 0.23 mm settled, left-side joints that PRD's mechanism leaves at rest grow by up to
// 0.1 mm), while a hinge of the mechanism opens in proportion to d. An opening beyond the settled
// gap smaller than this is not told apart from elastic redistribution. PRD's rigid blocks settle
// with no gap: 0.
double settled_gap(const RunResult& r);
// A joint corner a hinge may move to, `steps` joints along its ring from where it is.
struct RingSpot {
  int joint = -1, corner = 0, steps = 0;
};
// Where a hinge may move along a ring: the joint corners reachable from `joint`'s `corner` (the
// one it turns about) in at most `shift` steps, nearest first, the start itself first. A step
// crosses a ring block (a free block with exactly two joints, a voussoir or a course) to its
// other joint and keeps to the same side of the ring (the corner on the same side of the line
// joining the two joints' midpoints). Blocks where rings branch (a pier carrying a flyer) and
// supports are not crossed.
std::vector<RingSpot> ring_neighbours(const Case& c, const RunResult& r, int joint, int corner, int shift);
// The unit reports show d in: "mm" for "m", "mrad" for "rad" (d x 1000 either way).
std::string milli(const std::string& unit);
// "turns 12.1 mrad, opens 36.1 mm at A and 0.02 mm at B, slides 0.1 mm".
std::string joint_motion_text(const JointMotion& m);
// "from d = 93 to 232 mm", or "at collapse (PRD from d = 930, DEM from d = 913.7 mm)".
std::string interval_text(const MotionCheck& m, const std::string& d_unit, const std::string& label_a, const std::string& label_b);
// "1 joint", "2 joints": a shift along a ring as messages and reports write it.
std::string joints_text(int n);
// Hinges of one record (joint with exactly one open corner), sorted by joint. With min_opening >
// 0 a corner counts as open only when its gap exceeds its gap in the run's first record (the
// settled state) by more than min_opening: the hinges the support motion opens.
std::vector<Hinge> hinges_of(const Case& c, const RunResult& r, const StepRecord& s, double min_opening = 0.0);

// Where two runs' mechanisms part for good: the first record of `a` in the common range from
// which on the joints open wider than `min_gap` differ from b's (at b's last record at or
// before the same d) at every record up to the end of the common range. An early difference
// that closes again (a hinge that opens one increment later in one run) is not a parting, and
// neither is one at the last record alone (the approach to collapse at slightly different d).
// The settled state (step 0) is not compared: a mechanism is what the support motion opens.
struct Parting {
  double d = 0.0;                           // m
  std::vector<std::string> only_a, only_b;  // "blocks:corner (gap mm)", block ids unescaped
  // The same at the last record compared (the end of the common range): the mechanisms as they
  // stand at collapse, where the first difference may be a joint that later closes.
  double end_d = 0.0;
  std::vector<std::string> end_only_a, end_only_b;
};
std::optional<Parting> hinges_part(const Case& c, const RunResult& a, const RunResult& b, double min_gap);
// d (m) where the set of open corners changes (see CompareOptions::min_state_records).
std::vector<double> mechanism_changes(const RunResult& r, int min_state_records = 2);
// Block index -> index of its mirror image about the vertical line through the scene's centre,
// or empty when some block has no mirror image (matched by vertices and support flag), or when
// the loading is not its own mirror image: the supports' motion up to a translation of the whole
// scene (one support spreading is; one settling, or a slab tilting, is not), the blocks' weights
// and the point loads.
std::vector<int> mirror_blocks(const Case& c);

// comparison.json content for one comparison (NaN and infinities written as null).
nlohmann::ordered_json to_json(const Comparison& k);
// Violated limits, one readable line each; empty when every limit holds.
std::vector<std::string> check_tolerances(const Comparison& k, const Tolerances& t);

}  // namespace masonry
