#include "runs/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace masonry {

namespace {
double since(std::chrono::steady_clock::time_point t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); }
}  // namespace

std::string time_left(double elapsed_s, double fraction_done, bool at_most) {
  char b[96];
  if (fraction_done > 0 && std::isfinite(fraction_done)) {
    const double left = elapsed_s * std::max(0.0, 1 - fraction_done) / fraction_done;
    std::snprintf(b, sizeof b, ", %.0f s, %s %.0f s more", elapsed_s, at_most ? "at most" : "about", left);
  } else {
    std::snprintf(b, sizeof b, ", %.0f s", elapsed_s);
  }
  return b;
}

RunProgress::RunProgress(std::string who, double d_end, double every_s, std::function<std::string(const StepRecord&)> detail, std::string unit)
    : who_(std::move(who)),
      d_end_(d_end),
      every_s_(every_s),
      detail_(std::move(detail)),
      unit_(std::move(unit)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void RunProgress::operator()(const RunResult& r) {
  // From the first step on the path (the start's record, or a DEM's settling, tells no pace).
  if (r.steps.empty() || !(r.steps.back().d > r.steps.front().d) || (printed_ && since(last_) < every_s_)) return;
  last_ = std::chrono::steady_clock::now();
  printed_ = true;
  const StepRecord& s = r.steps.back();
  const double d0 = r.steps.front().d;
  const double fraction = d_end_ > d0 ? (s.d - d0) / (d_end_ - d0) : NAN;
  char b[160];
  std::snprintf(b, sizeof b, "%s: step %d, d = %.6g %s of at most %.6g %s", who_.c_str(), s.index, s.d, unit_.c_str(), d_end_, unit_.c_str());
  const std::string detail = detail_ ? detail_(s) : std::string();
  std::cerr << b << (detail.empty() ? "" : " (" + detail + ")") << time_left(since(start_), fraction, true) << "\n" << std::flush;
}

std::string dem_step_detail(const StepRecord& s) {
  char b[128];
  if (!s.hold) return "";
  std::snprintf(b, sizeof b, "%s, %lld cycles, unbalanced %.2e", s.hold->hold_end.c_str(), s.hold->cycles, s.hold->unbalanced_ratio);
  return b;
}

StudyProgress::StudyProgress(std::string who, size_t runs) : who_(std::move(who)), runs_(runs), start_(std::chrono::steady_clock::now()) {}

std::string StudyProgress::line(size_t k, const std::string& what) const {
  return who_ + ": [" + std::to_string(k) + "/" + std::to_string(runs_) + "] " + what +
         time_left(since(start_), runs_ ? static_cast<double>(k) / static_cast<double>(runs_) : NAN, false);
}

}  // namespace masonry
