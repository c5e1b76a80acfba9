// Whether a DEM run's slide is the statics' or, as a damped rerun then tests, its joints'
// vibration (compare/README.md, "A slide statics does not ask for"): the one decision `masonry
// compare` and `validate`'s PRD-against-DEM rows take before and after running the DEM again with
// contact damping.
#pragma once

#include <optional>

#include "compare/slide.hpp"
#include "model/case.hpp"
#include "model/results.hpp"

namespace masonry {

// Nothing where `dem` (a run of `dem_case`: the case `c` with the DEM's settings) has contact
// damping or stopped by error, `prd` is not a PRD run of `c` that ran, or the DEM slid no joint by
// kUnexplainedSlide (slide_suspect); else the slide with what PRD's sliding check at the DEM's
// friction angle (a PRD run of its own) says of the steps up to its end.
std::optional<SlideVerdict> dem_slide_verdict(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem);
// The slide alone, without the statics' reading (the same gates).
std::optional<SlideSuspect> dem_slide(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem);

// What PRD's sliding check run `check` (of `c`, every step with its sliding record) says of the
// steps up to v.slide.to and the first at or past it, at friction angle phi (deg): v.statics,
// v.friction_angle and the fields each verdict sets (SlideVerdict).
void read_statics(const Case& c, const RunResult& check, double phi, SlideVerdict& v);

// `dem_case` with contact damping kCheckContactDamping: the rerun's case.
Case with_check_damping(const Case& dem_case);

// A rerun for `v` (statics within friction) of the first run `first`, not yet read.
DampedRerun damped_rerun(const SlideVerdict& v, const Case& damped_case, const RunResult& first);
// Reads the damped run `damped` against `prd` into x: its largest unexplained slide, and whether
// the first run's is gone (x.removed).
void read_rerun(const Case& c, const RunResult& prd, const RunResult& damped, DampedRerun& x);

}  // namespace masonry
