#include "runs/slide_check.hpp"

#include <algorithm>
#include <cmath>

#include "compare/compare.hpp"
#include "dem/dem.hpp"
#include "model/interfaces.hpp"
#include "model/options.hpp"
#include "prd/prd.hpp"
#include "runs/run.hpp"

namespace masonry {

void read_statics(const Case& c, const RunResult& check, double phi, SlideVerdict& v) {
  v.friction_angle = phi;
  const double to = v.slide.to, eps = 1e-9 * std::max(1.0, std::abs(to));
  const std::vector<int> nth = pair_ordinals(check.joints);
  const auto name = [&](int j) { return j >= 0 && size_t(j) < check.joints.size() ? joint_name(c, check.joints[j].i, check.joints[j].j, nth[j]) : std::string(); };
  double most = 0;
  std::string most_joint;
  bool past = false;
  for (const StepRecord& s : check.steps) {
    if (!is_equilibrium(check, s)) break;
    if (!s.sliding) {
      v.why_unknown = "PRD's sliding check has no force state at step " + std::to_string(s.index);
      return;
    }
    const double need = s.sliding->required_angle;
    if (need > phi) {
      v.statics = Statics::slides;
      v.needs = need;
      v.at_d = s.d;
      v.at_joint = name(s.sliding->required_joint);
      return;
    }
    if (need >= most) most = need, most_joint = name(s.sliding->required_joint), v.at_d = s.d;
    if (s.d >= to - eps) {
      past = true;
      break;
    }
  }
  if (!past) {
    v.why_unknown = "PRD's sliding check stops at d = " + std::to_string(check.capacity) + ", before the slide's end";
    v.at_d = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  v.statics = Statics::within_friction;
  v.needs = most;
  v.at_joint = most_joint;
}

std::optional<SlideSuspect> dem_slide(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem) {
  if (dem_case.dem.contact_damping > 0 || known_method(prd) != Method::prd || known_method(dem) != Method::dem) return std::nullopt;
  if (prd.status == RunStatus::error || dem.status == RunStatus::error) return std::nullopt;
  return slide_suspect(c, compare_runs(c, prd, dem));
}

std::optional<SlideVerdict> dem_slide_verdict(const Case& c, const Case& dem_case, const RunResult& prd, const RunResult& dem) {
  const std::optional<SlideSuspect> s = dem_slide(c, dem_case, prd, dem);
  if (!s) return std::nullopt;
  PrdSettings ps = PrdSettings::from_case(c);
  ps.sliding_check = true;
  SlideVerdict v;
  v.slide = *s;
  read_statics(c, run_prd(c, ps), dem_case.dem.friction_angle, v);
  return v;
}

Case with_check_damping(const Case& dem_case) { return with_option(dem_case, option_key(&DemOptions::contact_damping), kCheckContactDamping); }

DampedRerun damped_rerun(const SlideVerdict& v, const Case& damped_case, const RunResult& first) {
  DampedRerun x;
  x.verdict = v;
  x.contact_damping = damped_case.dem.contact_damping;
  x.first_capacity = first.capacity;
  x.first_status = first.status;
  x.first_time_s = first.timing.total_s;
  return x;
}

void read_rerun(const Case& c, const RunResult& prd, const RunResult& damped, DampedRerun& x) {
  const Comparison k = compare_runs(c, prd, damped);
  if (k.sliding && k.sliding->largest_b.joint >= 0) x.rerun_slip = k.sliding->largest_b.b;
  x.removed = damped.status != RunStatus::error && !slide_suspect(c, k);
}

}  // namespace masonry
