// DEM speed, measured as benchmarks (never as timed tests): the cost of one integration cycle on
// the standard scenes, per cycle and per contact point. Run:
//   taskset -c 0 ./build/bench/masonry_bench --benchmark_filter=dem --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
// and quote the medians. `s_per_point_cycle` is CPU time per manifold point per cycle (shown with
// an SI prefix: 50n = 50 ns). The full capacity runs are timed by bench/dem-capacity.sh.
#include <benchmark/benchmark.h>

#include <string>

#include "dem/dem.hpp"
#include "model/case.hpp"

namespace {

masonry::Case standard(const std::string& name) { return masonry::load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/" + name + ".json"); }

// Cycles of the model under gravity, after `warmup` cycles so the joints are loaded and every
// contact pair has its manifold (the first cycles are not typical: nothing touches yet). The
// model keeps settling while it is timed, as in the holds of a capacity run.
void cycles(benchmark::State& state, const std::string& name, double stiffness_reduction, long long warmup) {
  const masonry::Case c = standard(name);
  masonry::DemSettings s = masonry::DemSettings::from_case(c);
  s.stiffness_reduction = stiffness_reduction;
  masonry::DemModel m(c, s);
  m.set_support_parameter(0);
  m.cycle(warmup);
  const long long per_iteration = state.range(0);
  for (auto _ : state) {
    m.cycle(per_iteration);
    benchmark::DoNotOptimize(m.unbalanced_ratio());
  }
  const double points = m.contact_points();
  state.counters["points"] = points;
  state.counters["blocks"] = static_cast<double>(c.blocks.size());
  state.counters["s_per_cycle"] =
      benchmark::Counter(static_cast<double>(per_iteration), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["s_per_point_cycle"] =
      benchmark::Counter(static_cast<double>(per_iteration) * points, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The pointed arch at the paper's settings (stiffness / 10), the cathedral at the case's.
BENCHMARK_CAPTURE(cycles, dem_pointed_arch, std::string("pointed-arch"), 10.0, 20000)->Arg(20000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(cycles, dem_cathedral_settlement, std::string("cathedral-settlement"), 1.0, 5000)->Arg(2000)->Unit(benchmark::kMillisecond);

}  // namespace
