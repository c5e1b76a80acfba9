// One progress line for every command that prints progress (README, "Commands"): where the work
// stands, the time it has taken and the time left at its pace so far, on stderr, one line each:
//
//   prd: step 120, d = 0.12 m of at most 1 m, 5 s, at most 37 s more
//   dem: step 12, d = 0.012 m of at most 1 m (equilibrium, 40210 cycles, unbalanced 2.1e-05), 97 s, at most 110 s more
//   sweep: [3/10] run 2 prd (friction 30): collapse, capacity 0.45 m, 12 s, about 28 s more
//
// A run's time left is "at most": the rest of its loading path at the pace so far (a collapse
// ends it sooner). A study's is "about": its runs still to go at the mean time of those done.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "model/results.hpp"

namespace masonry {

// ", 97 s, at most 110 s more" (or "about"), from the time so far and the fraction of the work done.
std::string time_left(double elapsed_s, double fraction_done, bool at_most);

// A capacity run's progress (RunOutput::on_step): after a recorded step beyond the start, at most
// one line every `every_s` seconds. `d_end` is where the loading path ends (step x max_steps past its start);
// `detail` adds the method's own words about the step (the DEM's hold); `unit` is d's (path_unit:
// "m", or "rad" where the supports only turn).
class RunProgress {
 public:
  RunProgress(std::string who, double d_end, double every_s = 1.0, std::function<std::string(const StepRecord&)> detail = {}, std::string unit = "m");
  void operator()(const RunResult& r);

 private:
  std::string who_;
  double d_end_, every_s_;
  std::function<std::string(const StepRecord&)> detail_;
  std::string unit_;
  std::chrono::steady_clock::time_point start_, last_;
  bool printed_ = false;
};

// The DEM's words about a recorded step in its progress line: how the hold ended, its cycles and
// how far from equilibrium.
std::string dem_step_detail(const StepRecord& s);

// A study's progress: one line per finished run, "who: [k/n] what, T s, about L s more".
class StudyProgress {
 public:
  StudyProgress(std::string who, size_t runs);
  // The line for the k-th finished run (1-based), without a newline.
  std::string line(size_t k, const std::string& what) const;

 private:
  std::string who_;
  size_t runs_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace masonry
