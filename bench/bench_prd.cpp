// PRD speed, measured as benchmarks (never as timed tests). Run (PRD only, without the
// 10,000-block wall, which takes minutes):
//   taskset -c 0 ./build/bench/masonry_bench --benchmark_filter='-dem|prd_wall/100' --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true
// and quote the medians; these machines are shared and noisy. `total_s` is the run's own
// timing.total_s (its thread CPU time), `lp_s` its time solving LPs (GLPK's and the kept basis's;
// `kept_basis_solves` of them without GLPK, prd/kept_basis.hpp), `first_lp_s` that of its first
// LP. The walls (prd_wall/N: N courses of N bricks in running bond, the right half of the ground
// settling 1 mm a step, 20 steps; 497, 2,049 and 10,052 blocks) are one run per repetition.
#include <benchmark/benchmark.h>

#include <string>

#include "cases/generators.hpp"
#include "model/case.hpp"
#include "prd/prd.hpp"

namespace {

masonry::Case standard(const std::string& name) { return masonry::load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

// False (and the benchmark marked skipped: a run that ended in an error is no timing of the run
// asked for) where the run failed; the caller then leaves its loop, as Google Benchmark asks.
bool count_run(benchmark::State& state, const masonry::RunResult& r, double first_lp_s) {
  if (r.status == masonry::RunStatus::error) {
    state.SkipWithError(r.message.c_str());
    return false;
  }
  state.counters["capacity_m"] = r.capacity;
  state.counters["lp_solves"] = static_cast<double>(r.timing.lp_solves);
  state.counters["kept_basis_solves"] = static_cast<double>(r.timing.kept_basis_solves);
  state.counters["total_s"] = r.timing.total_s;
  state.counters["lp_s"] = r.timing.lp_s;
  state.counters["first_lp_s"] = first_lp_s;
  return true;
}

void capacity_run(benchmark::State& state, const std::string& name, bool adaptive) {
  const masonry::Case c = standard(name);
  masonry::PrdSettings s = masonry::PrdSettings::from_case(c);
  s.adaptive = adaptive;
  double lp_share = 0;
  for (auto _ : state) {
    const masonry::RunResult r = masonry::prd_run(c, s);
    benchmark::DoNotOptimize(r.capacity);
    if (!count_run(state, r, -1)) break;
    state.counters["basis_evals"] = static_cast<double>(r.timing.basis_evaluations);
    lp_share = r.timing.lp_s / r.timing.total_s;
  }
  state.counters["lp_share"] = lp_share;
}

// A running-bond wall of n courses of n bricks (cases/README.md, "Brick wall"), 20 steps of 1 mm.
void prd_wall(benchmark::State& state) {
  masonry::BrickWall p;
  p.courses = p.bricks = static_cast<int>(state.range(0));
  p.max_steps = 20;
  const masonry::Case c = masonry::brick_wall(p);
  const masonry::PrdSettings s = masonry::PrdSettings::from_case(c);
  for (auto _ : state) {
    double first_lp_s = -1;
    const masonry::RunResult r = masonry::prd_run(c, s, [&](const masonry::RunResult& at) {
      if (first_lp_s < 0) first_lp_s = at.timing.lp_s;
    });
    benchmark::DoNotOptimize(r.capacity);
    if (!count_run(state, r, first_lp_s)) break;
  }
  state.counters["blocks"] = static_cast<double>(c.blocks.size());
}
BENCHMARK(prd_wall)->Arg(22)->Arg(45)->Arg(100)->Iterations(1)->Unit(benchmark::kSecond);

void single_analysis(benchmark::State& state, const std::string& name) {
  const masonry::Case c = standard(name);
  for (auto _ : state) benchmark::DoNotOptimize(masonry::prd_check(c, c.prd.contact_tolerance).stable);
}

BENCHMARK_CAPTURE(single_analysis, pointed_arch, std::string("pointed-arch"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, pointed_arch, std::string("pointed-arch"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(single_analysis, cathedral, std::string("cathedral-settlement"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement, std::string("cathedral-settlement"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_rotation, std::string("cathedral-settlement-rotation"), false)->Unit(benchmark::kMillisecond);
// Event-driven runs (--adaptive): the same capacities, events located to 1e-4 of the scene.
BENCHMARK_CAPTURE(capacity_run, pointed_arch_adaptive, std::string("pointed-arch"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_adaptive, std::string("cathedral-settlement"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(capacity_run, cathedral_settlement_rotation_adaptive, std::string("cathedral-settlement-rotation"), true)
    ->Unit(benchmark::kMillisecond);

}  // namespace
