// Running one benchmark: the quantity measured on each method, then judged.
#include "runs/run.hpp"
#include "runs/slide_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "cases/parameters.hpp"
#include "model/options.hpp"
#include "prd/prd.hpp"
#include "report/format.hpp"
#include "validate/validate.hpp"

namespace masonry {

namespace {

// One measurement: a number, or why there is none (a failure; an outside solver's error; a
// quantity that does not apply).
struct Measured {
  bool ok = false;
  double value = 0.0;
  std::string note;
  bool error = false;
  bool applicable = true;
  bool damped_rerun = false;  // a DEM judged by its rerun with contact damping (measure_dem_against_prd)
};

Measured fail(const std::string& why) { return {false, 0.0, why}; }
Measured solver_error(const std::string& why) { return {false, 0.0, why, true}; }
Measured not_applicable(const std::string& why) { return {false, 0.0, why, false, false}; }

const RunResult& run_method(const Case& c, Method m, RunCache& cache) {
  const std::string key = std::string(method_name(m)) + "\n" + case_to_json(c);
  auto it = cache.runs.find(key);
  if (it == cache.runs.end()) it = cache.runs.emplace(key, run_case(c, m)).first;
  return it->second;
}

// `who` names the run: the method's name, or an outside solver's --solver-name.
std::string run_failure(const RunResult& r, const std::string& who) {
  return "the " + who + " run stopped: " + status_name(r.status) + (r.message.empty() ? "" : " (" + r.message + ")");
}

// Whether the structure stands as it is: PRD's one analysis, or the DEM settling under gravity
// (its first hold: equilibrium, or a collapse; undecided is no answer).
Measured stands(Case c, Method m) {
  if (m == Method::prd) return {true, prd_check(c, c.prd.contact_tolerance).stable ? 1.0 : 0.0, ""};
  c.motion.max_steps = 0;
  const RunResult r = run_case(c, Method::dem);
  if (r.status == RunStatus::max_steps) return {true, 1.0, ""};
  if (r.status == RunStatus::collapse) return {true, 0.0, ""};
  return fail(run_failure(r, method_name(m)));
}

// Bisection on the searched parameter for where the structure starts (or stops) standing;
// `at` says whether it stands at a value.
Measured bisect(const Benchmark& b, const std::function<Measured(double)>& at) {
  const Search& s = *b.search;
  const auto failed_at = [&](double v, Measured k) {
    k.note = "at " + s.parameter + " = " + std::to_string(v) + ": " + k.note;
    return k;
  };
  Measured lo = at(s.lo);
  if (!lo.ok) return failed_at(s.lo, lo);
  Measured hi = at(s.hi);
  if (!hi.ok) return failed_at(s.hi, hi);
  if (lo.value == hi.value) return fail(std::string("the structure ") + (lo.value > 0 ? "stands" : "falls") + " at both ends of the search range");
  double a = s.lo, z = s.hi;
  const double stands_at_lo = lo.value;
  while (z - a > s.resolution) {
    const double mid = 0.5 * (a + z);
    const Measured k = at(mid);
    if (!k.ok) return failed_at(mid, k);
    (k.value == stands_at_lo ? a : z) = mid;
  }
  std::ostringstream note;
  note << (stands_at_lo > 0 ? "stands below, falls above: [" : "falls below, stands above: [") << a << ", " << z << "]";
  return {true, 0.5 * (a + z), note.str()};
}

// The record of a run at d (an equilibrium: for the DEM, a hold that settled).
const StepRecord* record_at(const RunResult& r, double d) {
  const double eps = 1e-9 * std::max(1.0, std::abs(d));
  for (const StepRecord& s : r.steps)
    if (std::abs(s.d - d) <= eps && is_equilibrium(r, s)) return &s;
  return nullptr;
}

bool any_reactions(const RunResult& r) {
  for (const StepRecord& s : r.steps)
    if (!s.reactions.empty()) return true;
  return false;
}

// The quantities one capacity run gives: from masonry's own runs, and from an outside solver's.
Measured from_run(const Benchmark& b, const Case& c, const RunResult& r) {
  switch (b.quantity) {
    case Quantity::capacity:
      if (r.status != RunStatus::collapse)
        return fail("no collapse up to d = " + std::to_string(r.capacity) + " " + path_unit(c) + " (stopped: " + status_name(r.status) + ")");
      return {true, r.capacity, ""};
    case Quantity::least_friction_angle: {
      if (!r.sliding || !r.sliding->any) return fail("the sliding check reported nothing");
      return {true, r.sliding->required_friction_angle, "at joint " + r.sliding->joint};
    }
    case Quantity::reaction: {
      if (!any_reactions(r)) return not_applicable("the results give no reactions");
      const StepRecord* s = record_at(r, b.at_d);
      if (!s) return fail("no recorded equilibrium at d = " + std::to_string(b.at_d) + " " + path_unit(c));
      for (const Reaction& x : s->reactions)
        if (x.support == b.support) return {true, b.component == "x" ? x.force.x() : b.component == "y" ? x.force.y() : x.moment, ""};
      return fail("no reaction of support '" + b.support + "' at d = " + std::to_string(s->d) + " " + path_unit(c));
    }
    case Quantity::reaction_balance: {
      if (!any_reactions(r)) return not_applicable("the results give no reactions");
      // Quasi-static equilibrium: the supports together carry the dead loads, at every record.
      const Vec2 P = dead_load_resultant(c);
      double worst = 0;
      int n = 0;
      for (const StepRecord& s : r.steps) {
        if (!is_equilibrium(r, s)) continue;  // the failed state closing a DEM run
        Vec2 sum(0, 0);
        for (const Reaction& x : s.reactions) sum += x.force;
        // A null force (JSON has no NaN) is no measurement: std::max would skip it and pass.
        if (!std::isfinite(sum.x()) || !std::isfinite(sum.y()))
          return fail("step " + std::to_string(s.index) + " gives a reaction that is not a number (null in its results)");
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
        if (!s.lp) continue;
        const double gap = std::abs(s.lp->primal - s.lp->dual) / (std::abs(s.lp->primal) + W);
        if (!std::isfinite(gap)) return fail("step " + std::to_string(s.index) + " gives an LP optimum that is not a number (null in its results)");
        worst = std::max(worst, gap);
      }
      return {true, worst, "over " + std::to_string(r.steps.size()) + " steps"};
    }
    default: break;
  }
  return fail("unhandled quantity");
}

Measured measure(const Catalogue& cat, const Benchmark& b, Method m, RunCache& cache) {
  if (b.quantity == Quantity::threshold) return bisect(b, [&](double v) { return stands(benchmark_case(cat, b, m, v), m); });
  Case c = benchmark_case(cat, b, m);
  if (b.quantity == Quantity::stands) return stands(c, m);
  if (b.quantity == Quantity::least_friction_angle) c.prd.sliding_check = true;
  const RunResult& r = run_method(c, m, cache);
  if (r.status == RunStatus::error || r.status == RunStatus::undecided) return fail(run_failure(r, method_name(m)));
  return from_run(b, c, r);
}

// A DEM capacity judged against PRD's on the same case, as `masonry compare` takes it
// (compare/README.md, "A slide statics does not ask for"; runs/slide_check.hpp): where the DEM's
// first run slid a joint PRD's did not, statics reads within friction up to there, and a rerun
// with contact damping removes the slide, the rerun's capacity, the row marked so.
Measured measure_dem_against_prd(const Catalogue& cat, const Benchmark& b, RunCache& cache) {
  const Case c = benchmark_case(cat, b, Method::dem);
  const RunResult& first = run_method(c, Method::dem, cache);
  const Case cp = benchmark_case(cat, b, Method::prd);
  const std::optional<SlideVerdict> v = dem_slide_verdict(cp, c, run_method(cp, Method::prd, cache), first);
  const auto judged = [&](const Case& at, const RunResult& r) {
    if (r.status == RunStatus::error || r.status == RunStatus::undecided) return fail(run_failure(r, method_name(Method::dem)));
    return from_run(b, at, r);
  };
  if (!v || v->statics != Statics::within_friction) return judged(c, first);
  const Case damped = with_check_damping(c);
  DampedRerun x = damped_rerun(*v, damped, first);
  const RunResult& r = run_method(damped, Method::dem, cache);
  read_rerun(cp, run_method(cp, Method::prd, cache), r, x);
  const std::string unit = path_unit(c);
  std::ostringstream why;
  why << "the first run slid " << printable(v->slide.joint) << " by " << fmt::mm(v->slide.slip, 2) << " mm ("
      << fmt::g(100 * v->slide.slip / v->slide.travel, 2) << "% of the supports' travel) where some admissible force state stays within "
      << fmt::g(v->friction_angle) << " deg of friction, and ended " << status_name(first.status) << " at " << fmt::g(first.capacity, 5) << " " << unit;
  if (!x.removed) {
    Measured m = judged(c, first);
    m.note += (m.note.empty() ? "" : "; ") + why.str() + "; with contact damping " + fmt::g(x.contact_damping) + " it still slid " + fmt::mm(x.rerun_slip, 2) +
              " mm: no ratchet, the first run judged";
    return m;
  }
  Measured m = judged(damped, r);
  m.damped_rerun = true;
  m.note += (m.note.empty() ? "" : "; ") + std::string("judged by a rerun with contact damping ") + fmt::g(x.contact_damping) + ": " + why.str();
  return m;
}

// ---- An outside solver: its runs, one per case, cached as masonry's own are.

const RunResult* outside_run(const OutsideSolver& s, const Case& c, const Benchmark& b, RunCache& cache, std::string& why) {
  const std::string key = "outside\n" + case_to_json(c);
  if (auto it = cache.runs.find(key); it != cache.runs.end()) return &it->second;
  if (auto it = cache.outside_errors.find(key); it != cache.outside_errors.end()) {
    why = it->second;
    return nullptr;
  }
  try {
    RunResult r = run_outside(s, c, b.name + "-" + std::to_string(++cache.outside_runs));
    return &cache.runs.emplace(key, std::move(r)).first->second;
  } catch (const std::exception& e) {
    why = cache.outside_errors[key] = e.what();
    return nullptr;
  }
}

// A run that stopped by error is the solver's error; undecided is no answer (a failed row).
std::optional<Measured> outside_failure(const RunResult& r, const OutsideSolver& s) {
  if (r.status == RunStatus::error) return solver_error(run_failure(r, s.name));
  if (r.status == RunStatus::undecided || r.status == RunStatus::running) return fail(run_failure(r, s.name));
  return std::nullopt;
}

// The structure as it stands: the solver run with motion.max_steps = 0 (README, "Gate your own
// solver in CI"): stopped max_steps, it stands; collapse, it falls.
Measured outside_stands(const OutsideSolver& s, Case c, const Benchmark& b, RunCache& cache) {
  c.motion.max_steps = 0;
  std::string why;
  const RunResult* r = outside_run(s, c, b, cache, why);
  if (!r) return solver_error(why);
  if (const auto f = outside_failure(*r, s)) return *f;
  return {true, r->status == RunStatus::max_steps ? 1.0 : 0.0, ""};
}

Measured measure_outside(const Catalogue& cat, const Benchmark& b, const OutsideSolver& s, RunCache& cache) {
  switch (b.quantity) {
    case Quantity::least_friction_angle:
      return not_applicable("PRD's sliding check (the least friction angle of its force states) is not in a results file");
    case Quantity::duality_gap: return not_applicable("an LP duality gap is not in a results file");
    case Quantity::threshold: return bisect(b, [&](double v) { return outside_stands(s, benchmark_case(cat, b, s.as, v), b, cache); });
    case Quantity::stands: return outside_stands(s, benchmark_case(cat, b, s.as), b, cache);
    default: break;
  }
  const Case c = benchmark_case(cat, b, s.as);
  std::string why;
  const RunResult* r = outside_run(s, c, b, cache, why);
  if (!r) return solver_error(why);
  if (const auto f = outside_failure(*r, s)) return *f;
  return from_run(b, c, *r);
}

// A threshold is in its parameter's own unit, from the one table that defines the parameter: a
// case option's (model/options.cpp, as `masonry options` shows it; motion.step is d's, m or
// rad), a generator parameter's (cases/parameters.cpp, the catalogue's name with '_' read as '-'
// as Python's generate() reads it); "" for a ratio or a count.
std::string threshold_unit(const Catalogue& cat, const Benchmark& b, Method m) {
  const std::string& key = b.search->parameter;
  if (key == option_key(&Motion::step)) return path_unit(benchmark_case(cat, b, m));
  for (const OptionInfo& o : option_infos())
    if (o.key == key) return o.unit;
  std::string name = key;
  std::replace(name.begin(), name.end(), '_', '-');
  if (const CaseGenerator* g = find_case_generator(b.case_source.generator))
    if (const int k = parameter_index(*g, name); k >= 0) return g->parameters[size_t(k)].unit;
  return "";
}

std::string methods_of(const Benchmark& b) {
  std::string out;
  for (const MethodRun& m : b.methods) out += (out.empty() ? "" : " and ") + std::string(method_name(m.method));
  return out;
}

}  // namespace

std::vector<ValidationRow> run_benchmark(const Catalogue& cat, const Benchmark& b, RunCache& cache,
                                         const std::function<void(const ValidationRow&)>& on_row, const OutsideSolver* solver) {
  using clock = std::chrono::steady_clock;
  std::vector<ValidationRow> rows;
  const auto finish = [&](ValidationRow row, clock::time_point t0) {
    row.seconds = std::chrono::duration<double>(clock::now() - t0).count();
    if (on_row) on_row(row);
    rows.push_back(std::move(row));
  };
  const auto unit_of = [&](Method m) -> std::string {
    // std::string(...), not a literal: GCC 12 warns falsely on these assignments (PR105651).
    if (b.quantity == Quantity::threshold) return threshold_unit(cat, b, m);
    if (b.quantity == Quantity::reaction && b.component == "moment") return std::string("N m");
    // A capacity is in d's unit: rad where every moving support only turns (a tilting slab).
    if (b.quantity == Quantity::capacity) return path_unit(benchmark_case(cat, b, m));
    return quantity_unit(b.quantity);
  };
  bool judged = false;
  for (const MethodRun& mr : b.methods) {
    if (solver && mr.method != solver->as) continue;
    judged = true;
    const auto t0 = clock::now();
    ValidationRow row;
    row.benchmark = &b;
    row.method = mr.method;
    row.method_label = solver ? solver->name : method_name(mr.method);
    row.unit = unit_of(mr.method);
    const Expected& x = mr.expected ? *mr.expected : b.expected;
    row.expected_from = mr.expected ? mr.source : b.source;
    bool have_expected = true;
    switch (x.kind) {
      case Expected::Kind::value: row.expected = x.value; break;
      case Expected::Kind::per_weight: row.expected = x.value * dead_load_resultant(benchmark_case(cat, b, mr.method)).norm(); break;
      case Expected::Kind::method: {
        const Measured ref = measure(cat, b, x.method, cache);
        row.expected_from = std::string(method_label(x.method)) + " on the same case";
        if (ref.ok)
          row.expected = ref.value;
        else {
          have_expected = false;
          row.note = "reference (" + std::string(method_name(x.method)) + "): " + ref.note;
        }
        break;
      }
    }
    if (have_expected) {
      const bool dem_against_prd = mr.method == Method::dem && x.kind == Expected::Kind::method && x.method == Method::prd && b.quantity == Quantity::capacity;
      Measured got = solver            ? measure_outside(cat, b, *solver, cache)
                     : dem_against_prd ? measure_dem_against_prd(cat, b, cache)
                                       : measure(cat, b, mr.method, cache);
      // A results file may give null where a number is asked for (JSON has no NaN): no number,
      // and the row says so (it failed with an empty note, "n/a" in the table).
      if (got.ok && !std::isfinite(got.value)) got = fail("the run gives no finite number for it (null in its results)");
      row.measured = got.ok;
      row.obtained = got.value;
      row.note = got.note;
      row.solver_error = got.error;
      row.applicable = got.applicable;
      row.damped_rerun = got.damped_rerun;
      row.tolerance = mr.tolerance.limit(row.expected);
      row.pass = got.ok && (b.quantity == Quantity::stands ? got.value == row.expected : std::abs(row.error()) <= row.tolerance);
    }
    finish(std::move(row), t0);
  }
  if (solver && !judged) {
    ValidationRow row;
    row.benchmark = &b;
    row.method = solver->as;
    row.method_label = solver->name;
    row.unit = unit_of(solver->as);
    row.applicable = false;
    row.expected_from = b.source;
    row.note = "the catalogue judges only " + methods_of(b) + " here (no " + method_name(solver->as) + " tolerance)";
    finish(std::move(row), clock::now());
  }
  return rows;
}

}  // namespace masonry
