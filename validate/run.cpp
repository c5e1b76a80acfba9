// Running one benchmark: the quantity measured on each method, then judged.
#include <chrono>
#include <cmath>
#include <sstream>

#include "prd/prd.hpp"
#include "runs/run.hpp"
#include "validate/validate.hpp"

namespace masonry {

namespace {

// One measurement: a number, or why there is none.
struct Measured {
  bool ok = false;
  double value = 0.0;
  std::string note;
};

Measured fail(const std::string& why) { return {false, 0.0, why}; }

const RunResult& run_method(const Case& c, Method m, RunCache& cache) {
  const std::string key = std::string(method_name(m)) + "\n" + case_to_json(c);
  auto it = cache.runs.find(key);
  if (it == cache.runs.end())
    it = cache.runs.emplace(key, run_case(c, m)).first;
  return it->second;
}

std::string run_failure(const RunResult& r) {
  return "the " + std::string(r.method) + " run stopped: " + status_name(r.status) + (r.message.empty() ? "" : " (" + r.message + ")");
}

// Whether the structure stands as it is: PRD's one analysis, or the DEM settling under gravity
// (its first hold: equilibrium, or a collapse; undecided is no answer).
Measured stands(Case c, Method m) {
  if (m == Method::prd) return {true, prd_check(c, c.prd.contact_tolerance).stable ? 1.0 : 0.0, ""};
  c.motion.max_steps = 0;
  const RunResult r = run_case(c, Method::dem);
  if (r.status == RunStatus::max_steps) return {true, 1.0, ""};
  if (r.status == RunStatus::collapse) return {true, 0.0, ""};
  return fail(run_failure(r));
}

// Bisection on the searched parameter for where the structure starts (or stops) standing.
Measured threshold(const Catalogue& cat, const Benchmark& b, Method m) {
  const Search& s = *b.search;
  auto at = [&](double v) { return stands(benchmark_case(cat, b, m, v), m); };
  Measured lo = at(s.lo), hi = at(s.hi);
  if (!lo.ok) return fail("at " + b.search->parameter + " = " + std::to_string(s.lo) + ": " + lo.note);
  if (!hi.ok) return fail("at " + b.search->parameter + " = " + std::to_string(s.hi) + ": " + hi.note);
  if (lo.value == hi.value)
    return fail(std::string("the structure ") + (lo.value > 0 ? "stands" : "falls") + " at both ends of the search range");
  double a = s.lo, z = s.hi;
  const double stands_at_lo = lo.value;
  while (z - a > s.resolution) {
    const double mid = 0.5 * (a + z);
    const Measured k = at(mid);
    if (!k.ok) return fail("at " + b.search->parameter + " = " + std::to_string(mid) + ": " + k.note);
    (k.value == stands_at_lo ? a : z) = mid;
  }
  std::ostringstream note;
  note << (stands_at_lo > 0 ? "stands below, falls above: [" : "falls below, stands above: [") << a << ", " << z << "]";
  return {true, 0.5 * (a + z), note.str()};
}

// The record of a run at d (for the DEM, an equilibrium).
const StepRecord* record_at(const RunResult& r, double d) {
  const double eps = 1e-9 * std::max(1.0, std::abs(d));
  for (const StepRecord& s : r.steps)
    if (std::abs(s.d - d) <= eps && is_equilibrium(r, s)) return &s;
  return nullptr;
}

Measured measure(const Catalogue& cat, const Benchmark& b, Method m, RunCache& cache) {
  if (b.quantity == Quantity::threshold) return threshold(cat, b, m);
  Case c = benchmark_case(cat, b, m);
  if (b.quantity == Quantity::stands) return stands(c, m);
  if (b.quantity == Quantity::least_friction_angle) c.prd.sliding_check = true;
  const RunResult& r = run_method(c, m, cache);
  if (r.status == RunStatus::error || r.status == RunStatus::undecided) return fail(run_failure(r));
  switch (b.quantity) {
    case Quantity::capacity:
      if (r.status != RunStatus::collapse)
        return fail("no collapse up to d = " + std::to_string(r.capacity) + " m (stopped: " + status_name(r.status) + ")");
      return {true, r.capacity, ""};
    case Quantity::least_friction_angle: {
      if (!r.sliding || !r.sliding->any) return fail("the sliding check reported nothing");
      return {true, r.sliding->required_friction_angle, "at joint " + r.sliding->joint};
    }
    case Quantity::reaction: {
      const StepRecord* s = record_at(r, b.at_d);
      if (!s) return fail("no recorded equilibrium at d = " + std::to_string(b.at_d) + " m");
      for (const Reaction& x : s->reactions)
        if (x.support == b.support)
          return {true, b.component == "x" ? x.force.x() : b.component == "y" ? x.force.y() : x.moment, ""};
      return fail("no support named '" + b.support + "'");
    }
    case Quantity::reaction_balance: {
      // Quasi-static equilibrium: the supports together carry the dead loads, at every record.
      const Vec2 P = dead_load_resultant(c);
      double worst = 0;
      int n = 0;
      for (const StepRecord& s : r.steps) {
        if (!is_equilibrium(r, s)) continue;  // the failed state closing a DEM run
        Vec2 sum(0, 0);
        for (const Reaction& x : s.reactions) sum += x.force;
        worst = std::max(worst, (sum + P).norm() / P.norm());
        ++n;
      }
      if (n == 0) return fail("no recorded equilibrium");
      return {true, worst, "over " + std::to_string(n) + " recorded equilibria"};
    }
    case Quantity::duality_gap: {
      // LP duality: the primal optimum (power of the loads) equals the dual's on every step.
      const double W = dead_load_resultant(c).norm();
      double worst = 0;
      for (const StepRecord& s : r.steps) {
        if (!s.extra.contains("lp_primal") || !s.extra.contains("lp_dual")) continue;
        const double p = s.extra["lp_primal"].get<double>(), d = s.extra["lp_dual"].get<double>();
        worst = std::max(worst, std::abs(p - d) / (std::abs(p) + W));
      }
      return {true, worst, "over " + std::to_string(r.steps.size()) + " steps"};
    }
    default: break;
  }
  return fail("unhandled quantity");
}

}  // namespace

std::vector<ValidationRow> run_benchmark(const Catalogue& cat, const Benchmark& b, RunCache& cache,
                                         const std::function<void(const ValidationRow&)>& on_row) {
  using clock = std::chrono::steady_clock;
  std::vector<ValidationRow> rows;
  for (const MethodRun& mr : b.methods) {
    const auto t0 = clock::now();
    ValidationRow row;
    row.benchmark = &b;
    row.method = mr.method;
    row.unit = quantity_unit(b.quantity);
    // std::string(...), not a literal: GCC 12 warns falsely on these assignments (PR105651).
    if (b.quantity == Quantity::threshold && b.search->parameter.find("friction_angle") != std::string::npos) row.unit = std::string("deg");
    if (b.quantity == Quantity::threshold && b.search->parameter == "thickness") row.unit = std::string("m");
    if (b.quantity == Quantity::reaction && b.component == "moment") row.unit = std::string("N m");
    const Expected& x = mr.expected ? *mr.expected : b.expected;
    row.expected_from = mr.expected ? mr.source : b.source;
    bool have_expected = true;
    switch (x.kind) {
      case Expected::Kind::value: row.expected = x.value; break;
      case Expected::Kind::per_weight:
        row.expected = x.value * dead_load_resultant(benchmark_case(cat, b, mr.method)).norm();
        break;
      case Expected::Kind::method: {
        const Measured ref = measure(cat, b, x.method, cache);
        row.expected_from = std::string(x.method == Method::prd ? "PRD" : "DEM") + " on the same case";
        if (ref.ok) row.expected = ref.value;
        else {
          have_expected = false;
          row.note = "reference (" + std::string(method_name(x.method)) + "): " + ref.note;
        }
        break;
      }
    }
    if (have_expected) {
      const Measured got = measure(cat, b, mr.method, cache);
      row.measured = got.ok;
      row.obtained = got.value;
      row.note = got.note;
      row.tolerance = mr.tolerance.limit(row.expected);
      row.pass = got.ok && (b.quantity == Quantity::stands ? got.value == row.expected
                                                           : std::abs(row.error()) <= row.tolerance);
    }
    row.seconds = std::chrono::duration<double>(clock::now() - t0).count();
    if (on_row) on_row(row);
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace masonry
