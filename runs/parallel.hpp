// Many runs at once on local cores: one thread per run, at most `jobs` at a time.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dem/variants.hpp"
#include "model/results.hpp"

namespace masonry {

// Calls run(i) for i = 0..n-1 (at most `jobs` at a time, each on its own thread; the caller's
// thread is one of them) and returns the results in order. `run` must be safe to call
// concurrently for different i.
std::vector<RunResult> run_parallel(size_t n, int jobs, const std::function<RunResult(size_t)>& run);

// The DEM's convergence study's runs (dem/variants.hpp), `jobs` at a time, each written to
// DIR/<variant name>/ by run.hpp's rule when `dir` is given. `on_done(i, result)` is called from
// variant i's thread when it ends (calls for different i may overlap).
std::vector<RunResult> run_variants(const Case& c, const std::vector<DemVariant>& variants, int jobs, const std::string& dir = {},
                                    const std::function<void(size_t, const RunResult&)>& on_done = {});

}  // namespace masonry
