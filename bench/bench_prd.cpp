// PRD speed, measured as benchmarks (never as timed tests). Run:
//   ./build/bench/masonry_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and quote the medians; these machines are shared and noisy.
#include <benchmark/benchmark.h>

#include <string>

#include "model/case.hpp"
#include "prd/prd.hpp"

namespace {

masonry::Case standard(const std::string& name) {
  return masonry::load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json");
}

void capacity_run(benchmark::State& state, const std::string& name, bool adaptive) {
  const masonry::Case c = standard(name);
  masonry::PrdSettings s = masonry::PrdSettings::from_case(c);
  s.adaptive = adaptive;
  double lp_share = 0;
  for (auto _ : state) {
    const masonry::RunResult r = masonry::prd_run(c, s);
    benchmark::DoNotOptimize(r.capacity);
    state.counters["capacity_m"] = r.capacity;
    state.counters["lp_solves"] = static_cast<double>(r.timing.lp_solves);
    state.counters["basis_evals"] = static_cast<double>(r.timing.basis_evaluations);
    lp_share = r.timing.lp_s / r.timing.total_s;
  }
  state.counters["glpk_share"] = lp_share;
}

void single_analysis(benchmark::State& state, const std::string& name) {
  const masonry::Case c = standard(name);
  for (auto _ : state) benchmark::DoNotOptimize(masonry::prd_check(c, c.prd.contact_tolerance).stable);
}

BENCHMARK_CAPTURE(single_analysis, pointed_arch, std::string("pointed-arch"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, pointed_arch, std::string("pointed-arch"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(single_analysis, cathedral, std::string("cathedral-settlement"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement, std::string("cathedral-settlement"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_rotation, std::string("cathedral-settlement-rotation"), false)
    ->Unit(benchmark::kMillisecond);
// Event-driven runs (--adaptive): the same capacities, events located to 1e-4 of the scene.
BENCHMARK_CAPTURE(capacity_run, pointed_arch_adaptive, std::string("pointed-arch"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_adaptive, std::string("cathedral-settlement"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_rotation_adaptive, std::string("cathedral-settlement-rotation"), true)
    ->Unit(benchmark::kMillisecond);

}  // namespace
