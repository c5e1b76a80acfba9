// The piecewise rigid displacement (PRD) solver: a sequence of linear programs on the deformed
// geometry (see shared/docs/prd-method.md). GLPK solves the LPs (one problem object lives for the
// whole run and is updated in place), but for those a previous LP's basis or solution still
// solves and those of large structures (below).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// A run started from a configuration another run recorded (either method's results.json):
// every block, supports included, where the record's poses put it, and d going on from the
// record's d. The joints are the case's own, found on its geometry; a corner whose gap exceeds
// the contact tolerance starts open. A closed corner's offset (a DEM's elastic overlap and
// elastic shear) is either kept as the joint's geometry, so the blocks go on rigid as the
// elastic joints had deformed them, or taken back over the first step, so they go on rigid as
// cut. Why: PRD on the DEM's deformed configuration says what of a capacity difference is the
// geometry the elastic joints deform to (dem/README.md, "Joint stiffness").
enum class StartOffsets { keep, take_back };
struct PrdStart {
  double d = 0.0;           // m: the record's d; the run's records and capacity count from it
  std::vector<Pose> poses;  // one per block, in case order (centroid and rotation since the start)
  StartOffsets offsets = StartOffsets::keep;
  std::string source;  // where the configuration comes from, for the results' settings
};
const char* start_offsets_name(StartOffsets o);  // "keep", "take-back": the CLI's words

// From this many free blocks up a fixed-step run solves an LP that the previous LP's basis or
// solution does not by an interior point, GLPK where that fails (prd/README.md, "The interior
// point"): GLPK's simplex pays for such an LP in minutes, and fails on it from its advanced basis.
constexpr int kInteriorPointBlocks = 5000;

// PRD's settings (model/case.hpp's PrdOptions, declared once there) and the motion's increment,
// as one run takes them.
struct PrdSettings : PrdOptions {
  double step = 0.001;            // increment of d per step, m
  int max_steps = 1000;           // the run ends after max_steps steps (at d = max_steps * step from the start)
  std::optional<PrdStart> start;  // absent: from the case's own geometry at d = 0
  // deg: the friction angle `masonry prd --friction-angle` judges the sliding check against (the
  // first step and joint needing more, on stderr). The run does not use it; its results' settings
  // record it, so a results file says which angle its sliding report was made for. Absent: none.
  std::optional<double> friction_angle;
  static PrdSettings from_case(const Case& c);
};

// The single analysis of the structure as it stands (no prescribed motion).
struct PrdCheck {
  bool stable = false;
  double energy_rate = 0.0;  // optimum of the LP (0 when stable with fixed supports)
  // Stable: one admissible force state (joint resultants and support reactions).
  // Unstable: `collapse` holds the collapse mechanism's open corners and moving blocks,
  // `mechanism` its block velocities.
  StepRecord state;
  Mechanism collapse;
  std::vector<JointInfo> joints;
  std::vector<Pose> mechanism;  // per block: (u_x, u_y, theta) of the normalised mechanism
  double total_weight = 0.0;
};
PrdCheck prd_check(const Case& c, double contact_tolerance);

// The run's first LP: the mechanism the prescribed support motion over one step h drives from
// the initial configuration, with the corners named in `held_closed` ("BLOCK/BLOCK:A" or ":B",
// further joints between the same blocks ":C", ":D" and on; the joint's blocks in the order the
// results name them) kept closed. Comparing the potential
// energy it releases with and without a hinge held closed measures how near the next-best
// mechanism is (dem/README.md, "The branch X"). Throws std::runtime_error naming an unknown corner.
struct FirstStep {
  bool bounded = false;        // false: the structure collapses at d = 0 (the LP is unbounded)
  double energy_change = 0.0;  // J: potential energy of the loads over the step (negative: released)
  struct Opening {
    std::string corner;    // "BLOCK/BLOCK:A"
    double opening = 0.0;  // m, over the step
  };
  std::vector<Opening> opening;  // the corners the step opens by more than 1e-6 of h
};
FirstStep prd_first_step(const Case& c, double contact_tolerance, double h, const std::vector<std::string>& held_closed = {});

// The capacity run. `on_step` is called after every finished step (and once at the start, for
// the initial configuration) with the result so far, so the caller can write it as it goes.
RunResult prd_run(const Case& c, const PrdSettings& s, const std::function<void(const RunResult&)>& on_step = {});

// The sliding check's answer for a whole run, from its records' StepRecord::sliding:
//   required_friction_angle (deg): the largest over the steps of the smallest friction angle
//     for which the step admits a force state without sliding: below it PRD's no-sliding
//     assumption fails somewhere before collapse; with d (m), step and joint ("i/j") where
//     that happens;
//   max_demand_angle (deg), demand_d, demand_joint: the same for the dual force state alone.
// `any` is false when no step carries the check.
SlidingSummary sliding_summary(const Case& c, const RunResult& r);

// The first step where the friction demand (required = false: of the dual forces; true: of
// the best admissible state) exceeds angle_deg.
struct SlidingExceedance {
  int step = 0;
  double d = 0.0;      // m
  double angle = 0.0;  // deg
  int joint = -1;
  std::string blocks;  // "i/j" block ids
};
std::optional<SlidingExceedance> first_sliding(const Case& c, const RunResult& r, double angle_deg, bool required);

}  // namespace masonry
