// The piecewise rigid displacement (PRD) solver: a sequence of linear programs on the deformed
// geometry (see shared/docs/prd-method.md). GLPK solves every LP; one problem object lives for
// the whole run and is updated in place.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "case.hpp"
#include "results.hpp"

namespace masonry {

struct PrdSettings {
  double step = 0.001;              // increment of d per step, m
  int max_steps = 1000;
  double contact_tolerance = 1e-5;  // m: a corner with a gap below this is closed
  static PrdSettings from_case(const Case& c);
};

// The single analysis of the structure as it stands (no prescribed motion).
struct PrdCheck {
  bool stable = false;
  double energy_rate = 0.0;  // optimum of the LP (0 when stable with fixed supports)
  // Stable: one admissible force state (joint resultants and support reactions).
  // Unstable: `mechanism` holds the collapse mechanism's open corners and block velocities.
  StepRecord state;
  std::vector<JointInfo> joints;
  std::vector<Pose> mechanism;  // per block: (u_x, u_y, theta) of the normalised mechanism
  double total_weight = 0.0;
};
PrdCheck prd_check(const Case& c, double contact_tolerance);

// The capacity run. `on_step` is called after every finished step (and once at the start, for
// the initial configuration) with the result so far, so the caller can write it as it goes.
RunResult prd_run(const Case& c, const PrdSettings& s,
                  const std::function<void(const RunResult&)>& on_step = {});

}  // namespace masonry
