// The DEM's convergence study: the same case at the default settings and at settings that must
// not change a quasi-static answer (loading twice as slow, half the increment, another damping,
// half the time step, joints three times stiffer and softer, more friction), run in parallel
// threads. Reading the spread is compare/convergence.hpp's business.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dem/dem.hpp"

namespace masonry {

struct DemVariant {
  std::string name;  // file-name safe: the run's directory
  std::string what;  // what differs from the default, for tables
  DemSettings settings;
};

// The default first, then one variation per setting that must not matter.
std::vector<DemVariant> convergence_variants(const DemSettings& base);

// Runs every variant (at most `jobs` at a time, each on its own thread) and returns the results
// in the variants' order. `on_step(i, partial)` is called from variant i's thread after each of
// its records (for writing results as they go); `on_done(i, result)` once it ends. Both may run
// concurrently for different i.
std::vector<RunResult> run_variants(const Case& c, const std::vector<DemVariant>& variants, int jobs,
                                    const std::function<void(size_t, const RunResult&)>& on_step = {},
                                    const std::function<void(size_t, const RunResult&)>& on_done = {});

}  // namespace masonry
