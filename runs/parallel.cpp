#include "runs/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <thread>

#include "runs/run.hpp"

namespace masonry {

std::vector<RunResult> run_parallel(size_t n, int jobs, const std::function<RunResult(size_t)>& run) {
  std::vector<RunResult> out(n);
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t i = next++; i < n; i = next++) out[i] = run(i);
  };
  const int threads = std::max(1, std::min<int>(jobs, static_cast<int>(n)));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return out;
}

std::vector<RunResult> run_variants(const Case& c, const std::vector<DemVariant>& variants, int jobs, const std::string& dir,
                                    const std::function<void(size_t, const RunResult&)>& on_done) {
  return run_parallel(variants.size(), jobs, [&](size_t i) {
    RunOutput out;
    if (!dir.empty()) out.dir = (std::filesystem::path(dir) / variants[i].name).string();
    RunResult r = run_dem(c, variants[i].settings, out);
    if (on_done) on_done(i, r);
    return r;
  });
}

}  // namespace masonry
