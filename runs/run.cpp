#include "runs/run.hpp"

#include <chrono>

#include "model/io.hpp"

namespace masonry {

namespace {

// The one writing rule (run.hpp): after a step only when the last write cost less than a
// quarter of the time since, so writing takes at most about a fifth of the run; at the end always.
class ResultsWriter {
 public:
  ResultsWriter(const Case& c, const RunOutput& out) : c_(c), out_(out) {}
  void step(const RunResult& r) {
    if (!out_.dir.empty()) {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - last_).count() >= 4 * last_cost_) {
        write(r);
        last_ = std::chrono::steady_clock::now();
        last_cost_ = std::chrono::duration<double>(last_ - now).count();
      }
    }
    if (out_.on_step) out_.on_step(r);
  }
  RunResult last(RunResult r) const {
    if (!out_.dir.empty()) write(r);
    return r;
  }

 private:
  void write(const RunResult& r) const {
    const double c0 = out_.write_cpu_s ? thread_cpu_s() : 0;
    write_results(out_.dir, r, c_);
    if (out_.write_cpu_s) *out_.write_cpu_s += thread_cpu_s() - c0;
  }

  const Case& c_;
  const RunOutput& out_;
  std::chrono::steady_clock::time_point last_{};
  double last_cost_ = 0;
};

// A capacity run follows a loading path: some support must move, or the run would walk to
// max_steps and report its end as a capacity (a run of no steps only settles the structure).
void require_motion(const Case& c, int max_steps) {
  if (max_steps == 0) return;
  for (const SupportMotion& m : c.motion.supports)
    if (m.translation.norm() > 0 || m.rotation != 0) return;
  throw CaseError(c.source + ": motion: no support moves (" +
                  (c.motion.supports.empty() ? "motion.supports lists none" : "every support's translation and rotation is 0") +
                  "): a capacity run has no loading path; `masonry check` says whether the structure stands as it is");
}

}  // namespace

RunResult run_prd(const Case& c, const PrdSettings& s, const RunOutput& out) {
  require_motion(c, s.max_steps);
  ResultsWriter w(c, out);
  return w.last(prd_run(c, s, [&](const RunResult& r) { w.step(r); }));
}

RunResult run_dem(const Case& c, const DemSettings& s, const RunOutput& out) {
  require_motion(c, s.max_steps);
  ResultsWriter w(c, out);
  return w.last(dem_run(c, s, [&](const RunResult& r) { w.step(r); }));
}

RunResult run_case(const Case& c, Method m, const RunOutput& out) {
  return m == Method::prd ? run_prd(c, PrdSettings::from_case(c), out) : run_dem(c, DemSettings::from_case(c), out);
}

RunResult run_case_in_study(const Case& c, Method m, const RunOutput& out) {
  try {
    return run_case(c, m, out);
  } catch (const std::exception& e) {
    RunResult r;
    r.method = method_name(m);
    r.case_name = c.name;
    r.total_weight = total_weight(c);
    r.status = RunStatus::error;
    r.message = e.what();
    if (!out.dir.empty()) write_results(out.dir, r, c);
    return r;
  }
}

std::optional<PrdOnRun> prd_on_run(const Case& c, const RunResult& run) {
  if (known_method(run) != Method::dem || !(located(run.status) || run.status == RunStatus::undecided)) return std::nullopt;
  const StepRecord* rec = last_equilibrium(run, 0.9 * run.capacity);
  if (!rec) return std::nullopt;
  const auto number = [&](const char* key, double fallback) {
    return run.settings.contains(key) && run.settings[key].is_number() ? run.settings[key].get<double>() : fallback;
  };
  PrdOnRun out;
  out.from_d = rec->d;
  out.tolerance = number("bracket_fraction", c.dem.bracket_fraction) * number("step", c.motion.step);
  PrdSettings s = PrdSettings::from_case(c);
  s.adaptive = true;
  s.event_tolerance = out.tolerance;
  const auto capacity = [&](const PrdSettings& t) {
    const RunResult r = prd_run(c, t);
    return located(r.status) ? r.capacity : NAN;
  };
  out.own = capacity(s);
  for (StartOffsets o : {StartOffsets::keep, StartOffsets::take_back}) {
    s.start = PrdStart{rec->d, rec->poses, o, "the DEM run's record " + std::to_string(rec->index)};
    (o == StartOffsets::keep ? out.kept : out.taken_back) = capacity(s);
  }
  return out;
}

}  // namespace masonry
