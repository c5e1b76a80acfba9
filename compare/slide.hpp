// A slide one run made and the other did not (compare/README.md, "A slide statics does not ask
// for"): the DEM's net slip along a joint against the supports' travel, what PRD's sliding check
// says statics needs up to there, and the record of the DEM's rerun with contact damping that
// tests whether the slide was its joints' vibration.
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

struct Comparison;

// At the joint run b slid most, b's net slip over the common range (the comparison's sliding
// check) is more than kUnexplainedSlide of the supports' largest travel there
// (path_travel_per_d x b's last record's d), and a's is less. Measured (2026-11-28, the net slips
// of the comparisons): the standard scenes' DEM runs at most 6e-5 of the travel and the structures
// of reports/unseen-structures/ whose friction suffices at most 0.24%, where runs that ratchet on
// joints stiff against the weights slide 1.3% and 1.4% (two pointed arches), 13% (R4 at density
// 2), 38% (the settlement cathedral with joints 30 times stiffer) and 71% (the jack arch scaled by
// 0.05): compare/README.md.
constexpr double kUnexplainedSlide = 0.01;
struct SlideSuspect {
  std::string joint;  // joint_name (case text: escape before display)
  double slip = 0.0;    // m, run b's net slip there
  double other = std::numeric_limits<double>::quiet_NaN();  // m, run a's there (NaN: its joint came apart)
  double travel = 0.0;  // m, the supports' largest travel up to `to`
  double to = 0.0;      // d of run b's last record in the common range
};
// Run b's slide of kUnexplainedSlide; none without a sliding check.
std::optional<SlideSuspect> slide_suspect(const Case& c, const Comparison& k);

// What PRD's sliding check at the DEM's friction angle says of the steps up to the slide's end
// (each step's least friction angle over every admissible force state): within friction at every
// step up to `to` and at the first step at or past it (the onset of sliding could lie anywhere
// between two steps), sliding certain at one of them, or unknown (a step without a check, or a
// check run that stops short).
enum class Statics { within_friction, slides, unknown };
struct SlideVerdict {
  SlideSuspect slide;
  Statics statics = Statics::unknown;
  double friction_angle = 0.0;  // deg, the DEM's
  // within_friction: the most any step needs (deg) and where; slides: the first step that needs
  // more than friction_angle (its d, angle and joint); unknown: why.
  double needs = std::numeric_limits<double>::quiet_NaN();
  double at_d = std::numeric_limits<double>::quiet_NaN();
  std::string at_joint;
  std::string why_unknown;
};

// compare's (and validate's) rerun of a DEM run with contact damping, where statics reads the
// first run's slide within friction.
struct DampedRerun {
  SlideVerdict verdict;
  double contact_damping = 0.0;  // the rerun's zeta
  double first_capacity = 0.0;   // the first run's, d_unit
  RunStatus first_status = RunStatus::collapse;
  double first_time_s = 0.0;
  // m: the damped run's largest net slip at any joint over its own common range with the
  // reference run (NaN: no sliding check).
  double rerun_slip = std::numeric_limits<double>::quiet_NaN();
  // The rerun slid that joint less than kUnexplainedSlide of its travel: the slide was the joints'
  // vibration, and the rerun is the DEM compared. Otherwise damping did not remove it, it was no
  // ratchet, and the first run stays the one compared.
  bool removed = false;
  std::string first_dir, rerun_dir;  // the two runs' results directories, relative to the report
};

}  // namespace masonry
