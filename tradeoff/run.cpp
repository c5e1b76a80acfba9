// Running the plan: every setting through runs/ (at the settings each method reads from the varied
// case), the errors against the method's reference through compare_runs, and the Pareto front.
#include "runs/run.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "compare/compare.hpp"
#include "runs/progress.hpp"
#include "tradeoff/tradeoff.hpp"

namespace masonry {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Whether a run read back had ended: results written while a run is going say "running", and a
// "max_steps" run must also have reached the end of the path (DEM results written before
// 2026-11-22 said "max_steps" while going, and a run stopped from outside left them so).
bool finished(const RunResult& r, const Case& c) {
  if (r.status == RunStatus::collapse || r.status == RunStatus::undecided || r.status == RunStatus::error) return true;
  if (r.status != RunStatus::max_steps || r.steps.empty()) return false;
  const double end = c.motion.step * c.motion.max_steps;
  return r.steps.back().d >= end * (1 - 1e-9);
}

// One run of a planned setting, written to `dir` as it goes (runs/run.hpp); a failure is a run
// stopped by "error" with the message, so one bad setting does not end the measurement.
// `io_cpu_s` receives the CPU time spent writing the results, which is not the solver's.
RunResult run_once(const PlannedRun& p, const std::string& dir, double& io_cpu_s) {
  io_cpu_s = 0;
  RunOutput out;
  out.dir = dir;
  out.write_cpu_s = &io_cpu_s;
  return run_case_in_study(p.c, p.setting.method, out);
}

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The times of one setting's repeats, kept beside its results so that --resume restores them.
struct Times {
  std::vector<double> cpu, wall;
};

nlohmann::ordered_json times_json(const Times& t) {
  nlohmann::ordered_json j;
  j["cpu_s"] = t.cpu;
  j["total_s"] = t.wall;
  return j;
}

void fill(Row& row, const RunResult& r, const Times& t) {
  row.status = r.status;
  row.message = r.message;
  row.cpu = !t.cpu.empty();
  const std::vector<double>& times = row.cpu ? t.cpu : t.wall;
  row.wall_s = median(t.wall);
  row.repeats = int(times.size());
  row.time_s = median(times);
  row.time_min_s = times.empty() ? kNaN : *std::min_element(times.begin(), times.end());
  row.time_max_s = times.empty() ? kNaN : *std::max_element(times.begin(), times.end());
  row.lp_solves = r.timing.lp_solves;
  row.cycles = r.timing.cycles;
  row.steps = int(r.steps.size());
  row.capacity = row.ok() ? r.capacity : kNaN;
}

void set_errors(Row& row, const Case& c, const RunResult* ref, bool ref_ok, const RunResult& r) {
  row.capacity_err = row.thrust_max_err = row.thrust_rms_err = row.thrust_range = kNaN;
  if (!ref || !ref_ok || !row.ok()) return;
  // Thrusts at the coarser run's records: settings step differently, and a run read between two
  // of its records across a jump it did not resolve (the settled thrust falling to the minimum
  // thrust over the first step) would differ from the other by the jump, not by accuracy.
  CompareOptions co;
  co.thrust_grid = ThrustGrid::coarser_run;
  const Comparison k = compare_runs(c, *ref, r, co);
  row.capacity_err = k.capacity_rel_diff;
  row.thrust_max_err = k.thrust_max_diff;
  row.thrust_rms_err = k.thrust_rms_diff;
  row.thrust_range = k.d_max;
  if (!(k.d_max > 0) && ref->capacity > 0) row.thrust_max_err = row.thrust_rms_err = kNaN;
}

}  // namespace

std::vector<Row> run_plan(const Case& base, const std::vector<PlannedRun>& runs, const RunOptions& o, const std::function<void(const Row&)>& on_row) {
  const auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  std::vector<Row> rows;
  const StudyProgress progress("tradeoff", runs.size());
  std::map<Method, RunResult> refs;  // method -> its reference run
  std::map<Method, bool> ref_ok;
  for (const PlannedRun& p : runs) {
    Row row;
    row.method = p.setting.method;
    row.parameter = p.setting.parameter;
    row.label = p.setting.label;
    row.id = p.id;
    row.options = p.setting.options;
    row.reference = p.reference;
    row.baseline = p.baseline;
    RunResult r;
    Times times;
    const std::string name = method_name(row.method);
    const auto reused_dir = o.reference_dir.find(row.method);
    const std::string dir = o.runs_dir.empty() ? "" : (fs::path(o.runs_dir) / p.id).string();
    if (p.reference && reused_dir != o.reference_dir.end()) {
      // A finished run taken as the reference: read back, its own time quoted.
      r = load_results((fs::path(reused_dir->second) / "results.json").string(), base);
      if (known_method(r) != row.method)
        throw std::runtime_error(reused_dir->second + "/results.json: method '" + r.method + "', expected '" + name + "'");
      row.reused = row.given = true;
      row.source = reused_dir->second;
      row.options.clear();
      times.wall.push_back(r.timing.total_s);
      say("tradeoff: " + name + " reference: read back from " + row.source);
    } else {
      const std::string case_text = case_to_json(p.c);
      bool done = false;
      if (o.resume && !dir.empty() && read_text((fs::path(dir) / "case.json").string()) == case_text && fs::exists(fs::path(dir) / "results.json")) {
        try {
          RunResult old = load_results((fs::path(dir) / "results.json").string(), base);
          if (!finished(old, p.c)) say("tradeoff: " + dir + " holds a run that did not finish: running it again");
          if (finished(old, p.c)) {
            r = std::move(old);
            times.wall.push_back(r.timing.total_s);
            // The repeats' times as measured when it ran, if it ran here.
            const std::string tj = read_text((fs::path(dir) / "timing.json").string()).value_or("");
            if (!tj.empty()) {
              const auto j = nlohmann::json::parse(tj, nullptr, false);
              if (j.is_object() && j.contains("cpu_s") && j.contains("total_s") && j["cpu_s"].is_array() && j["total_s"].is_array() &&
                  !j["cpu_s"].empty()) {
                times.cpu = j["cpu_s"].get<std::vector<double>>();
                times.wall = j["total_s"].get<std::vector<double>>();
              }
            }
            row.reused = true;
            done = true;
            say("tradeoff: " + name + " " + row.label + ": finished run reused from " + dir);
          }
        } catch (const std::exception& e) {
          say(std::string("tradeoff: ") + e.what() + " (running it again)");
        }
      }
      if (!done) {
        if (!dir.empty()) {
          fs::create_directories(dir);
          write_file_atomic((fs::path(dir) / "case.json").string(), case_text);
        }
        for (int k = 0; k < std::max(1, p.repeat); ++k) {
          say("tradeoff: " + name + " " + row.label + (p.repeat > 1 ? " (" + std::to_string(k + 1) + " of " + std::to_string(p.repeat) + ")" : "") +
              " ...");
          const double c0 = thread_cpu_s();
          double io = 0;
          r = run_once(p, dir, io);
          times.cpu.push_back(thread_cpu_s() - c0 - io);
          times.wall.push_back(r.timing.total_s);
          if (r.status == RunStatus::error) break;  // a failure is not timed again
        }
        if (!dir.empty()) write_file_atomic((fs::path(dir) / "timing.json").string(), times_json(times).dump() + "\n");
      }
      row.source = dir;
    }
    fill(row, r, times);
    if (p.reference) {
      refs[row.method] = r;
      ref_ok[row.method] = row.ok();
    }
    const auto ref = refs.find(row.method);
    set_errors(row, base, ref == refs.end() ? nullptr : &ref->second, ref_ok[row.method], r);
    say(progress.line(rows.size() + 1, name + " " + row.label + ": " + status_name(row.status) +
                                           std::string(row.message.empty() ? "" : " (" + row.message + ")") + ", capacity " +
                                           (std::isfinite(row.capacity) ? std::to_string(row.capacity) : "n/a") + " m in " +
                                           std::to_string(row.time_s) + " s"));
    rows.push_back(row);
    if (on_row) on_row(rows.back());
  }
  return rows;
}

std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i].time) && std::isfinite(points[i].error)) idx.push_back(i);
  // By time, then error, then index: a point is on the front when its error is below that of
  // every point before it (each of which is at least as fast).
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    if (points[a].time != points[b].time) return points[a].time < points[b].time;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : idx)
    if (points[i].error < best) {
      front.push_back(i);
      best = points[i].error;
    }
  return front;
}

std::vector<Buy> best_buys(const std::vector<ParetoPoint>& points, const std::vector<size_t>& front) {
  std::vector<Buy> out;
  for (size_t k = 0; k + 1 < front.size(); ++k) {
    Buy b;
    b.from = front[k];
    b.to = front[k + 1];
    b.gain = points[b.from].error - points[b.to].error;
    b.cost_s = points[b.to].time - points[b.from].time;
    if (!(b.gain > 0) || !(b.cost_s > 0)) continue;  // cannot happen on a front; kept safe
    b.rate = b.gain / b.cost_s;
    out.push_back(b);
  }
  std::stable_sort(out.begin(), out.end(), [](const Buy& a, const Buy& b) { return a.rate > b.rate; });
  return out;
}

std::vector<ParetoPoint> points_of(const std::vector<Row>& rows, ErrorKind kind) {
  std::vector<ParetoPoint> p;
  for (const Row& r : rows) {
    const double e = kind == ErrorKind::capacity ? std::abs(r.capacity_err) : r.thrust_max_err;
    p.push_back({r.ok() ? r.time_s : kNaN, r.ok() ? e : kNaN});
  }
  return p;
}

}  // namespace masonry
