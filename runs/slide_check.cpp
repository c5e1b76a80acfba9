#include "runs/slide_check.hpp"

#include "dem/dem.hpp"
#include "model/options.hpp"
#include "prd/prd.hpp"
#include "runs/run.hpp"

namespace masonry {

std::optional<SlideVerdict> dem_slide_verdict(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem) {
  if (dem_case.dem.contact_damping > 0 || known_method(prd) != Method::prd || known_method(dem) != Method::dem) return std::nullopt;
  const std::optional<SlideSuspect> s = slide_suspect(c, compare_runs(c, prd, dem));
  if (!s) return std::nullopt;
  const double phi = dem_case.dem.friction_angle;
  PrdSettings ps = PrdSettings::from_case(c);
  ps.sliding_check = true;
  ps.friction_angle = phi;
  SlideVerdict v{*s};
  if (const std::optional<SlidingExceedance> e = first_sliding(c, run_prd(c, ps), phi, true)) v.statics_slides_at = e->d;
  return v;
}

Case with_check_damping(const Case& dem_case) { return with_option(dem_case, option_key(&DemOptions::contact_damping), kCheckContactDamping); }

}  // namespace masonry
