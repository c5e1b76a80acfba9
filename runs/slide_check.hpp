// Whether a DEM run's slide is the statics' or its joints' vibration (compare/README.md, "A slide
// statics does not ask for"): the one decision `masonry compare` and `validate`'s PRD-against-DEM
// rows take before running the DEM again with contact damping.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "compare/compare.hpp"
#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

struct SlideVerdict {
  SlideSuspect slide;  // the DEM run's slide PRD's run did not make (slide_suspect)
  // d of PRD's first step where every admissible force state needs more friction than the DEM
  // has (its sliding check, first_sliding), NaN at none.
  double statics_slides_at = std::numeric_limits<double>::quiet_NaN();
  // The weights ask for the slide: sliding is certain before the DEM's slide ends.
  bool statics_asks() const { return std::isfinite(statics_slides_at) && statics_slides_at <= slide.to; }
};

// Nothing where `dem` (a run of `dem_case`, the case `c` with the DEM's settings) already has
// contact damping, `prd` is not a PRD run of `c`, or the DEM slid no joint by kUnexplainedSlide;
// else the slide with PRD's sliding check at the DEM's friction angle (a PRD run of its own).
std::optional<SlideVerdict> dem_slide_verdict(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem);

// `dem_case` with contact damping kCheckContactDamping: the rerun's case.
Case with_check_damping(const Case& dem_case);

}  // namespace masonry
