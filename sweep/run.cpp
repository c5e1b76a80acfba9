// Running a sweep on this machine: one run, the thread pool, resuming the table.
#include "runs/run.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "model/options.hpp"
#include "sweep/runner.hpp"

namespace masonry {

SweepRow execute_run(const SweepPlan& p, const SweepRun& run, bool keep) {
  SweepRow row;
  row.index = run.index;
  row.id = run.id;
  row.method = run.method;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const Method m = run.method;
    const Case own = case_of_run(p, run);
    // PRD runs carry the sliding check, so the report can set its prediction beside the DEM
    // (unless the sweep file's "set" turns it off).
    const Case c = m == Method::prd && p.sliding_check ? with_option(own, option_key(&PrdOptions::sliding_check), true) : own;
    const RunResult r = run_case_in_study(c, m);
    row.hinges = hinges_at_collapse(c, r);
    // The case as the run's row names it (without the PRD's sliding check, a setting): what
    // `masonry compare CASE --runs` is given for any two runs of the same point.
    if (keep) row.files = SweepRow::Files{case_to_json(own), to_json(r, c).dump(1) + "\n", steps_csv(r, c)};
    row.capacity = r.capacity;
    row.time_s = r.timing.total_s;
    row.message = r.message;
    row.status = r.status;
    if (r.status == RunStatus::running || r.status == RunStatus::error) {
      row.status = RunStatus::error;
      if (row.message.empty()) row.message = std::string("the run ended as '") + status_name(r.status) + "'";
    }
    // The PRD's sliding check (prd/): the friction angle below which its run would slide.
    if (r.sliding && r.sliding->any && std::isfinite(r.sliding->required_friction_angle))
      row.required_friction_angle = r.sliding->required_friction_angle;
  } catch (const std::exception& e) {
    row.status = RunStatus::error;
    row.message = e.what();
    row.capacity = 0;
    row.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  for (char& ch : row.message)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return row;
}

namespace sweep_detail {

Prepared prepare(const SweepInput& in, const SweepOptions& o) {
  Prepared pr;
  pr.plan = plan_sweep(in);
  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  if (ec) throw SweepError(o.out_dir + ": cannot create the output directory: " + ec.message());
  pr.csv_path = o.out_dir + "/sweep.csv";
  pr.table.assign(pr.plan.runs.size(), std::nullopt);
  if (!o.restart && std::filesystem::exists(pr.csv_path)) {
    std::ifstream f(pr.csv_path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    pr.table = read_sweep_csv(pr.plan, ss.str(), pr.csv_path);
  }
  write_file_atomic(pr.csv_path, sweep_csv(pr.plan, pr.table));
  for (size_t i = 0; i < pr.table.size(); ++i)
    if (!pr.table[i]) pr.todo.push_back(static_cast<int>(i));
  return pr;
}

Recorder::Recorder(Prepared& pr, const SweepOptions& o, int workers, const std::string& where)
    : pr_(pr), o_(o), file_(pr.csv_path, std::ios::binary | std::ios::app), progress_("sweep", pr.todo.size()) {
  if (!file_) throw SweepError(pr.csv_path + ": cannot append");
  if (o_.quiet) return;
  int prd = 0;
  for (const SweepRun& r : pr.plan.runs) prd += r.method == Method::prd;
  std::fprintf(stderr, "sweep: %s: %zu runs (%d PRD, %zu DEM); %zu in %s already, %zu to run on %d %s\n", pr.plan.name.c_str(), pr.plan.runs.size(),
               prd, pr.plan.runs.size() - prd, pr.plan.runs.size() - pr.todo.size(), pr.csv_path.c_str(), pr.todo.size(), workers, where.c_str());
  if (const std::string note = prd_ignores_note(pr.plan); !note.empty()) std::fprintf(stderr, "sweep: %s\n", note.c_str());
}

void Recorder::operator()(const SweepRow& r) {
  if (r.files) {
    // The files write_results writes, from their texts (a row from another MPI rank carries them).
    const std::string dir = o_.out_dir + "/runs/" + r.id;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw SweepError(dir + ": cannot create the run's directory: " + ec.message());
    write_file_atomic(dir + "/results.json", r.files->results_json);
    write_file_atomic(dir + "/steps.csv", r.files->steps_csv);
    write_file_atomic(dir + "/case.json", r.files->case_json);
  }
  pr_.table.at(r.index) = r;
  pr_.table.at(r.index)->files.reset();  // written: not kept in memory
  file_ << sweep_csv_line(pr_.plan, r, pr_.table) << std::flush;
  if (!file_) throw SweepError(pr_.csv_path + ": write failed");
  ++done_;
  if (o_.quiet) return;
  const SweepRun& run = pr_.plan.runs[r.index];
  const std::string label = run_label(pr_.plan, run);
  char b[96];
  if (r.status == RunStatus::error)
    std::snprintf(b, sizeof b, "error after %.3g s", r.time_s);
  else
    std::snprintf(b, sizeof b, "%s, capacity %.6g %s in %.3g s", status_name(r.status), r.capacity, path_unit(pr_.plan.base).c_str(), r.time_s);
  std::cerr << progress_.line(done_, "run " + std::to_string(r.index) + " " + method_name(r.method) + " (" + label + "): " + b +
                                         (r.status == RunStatus::error ? ": " + r.message : std::string()))
            << "\n"
            << std::flush;
}

int Recorder::finish() {
  file_.close();
  write_sweep_outputs(o_.out_dir, pr_.plan, pr_.table, o_.command);
  const SweepSummary s = summarize(pr_.plan, pr_.table);
  if (!o_.quiet) {
    std::fprintf(stderr, "sweep: %d rows, %d failed; table %s, report %s/report.html and %s/report.md\n", s.finished, s.errors, pr_.csv_path.c_str(),
                 o_.out_dir.c_str(), o_.out_dir.c_str());
    for (const SweepCurve& c : s.curves)
      if (c.boundary)
        std::fprintf(stderr, "sweep: DEM and PRD differ by more than %g%% up to a friction angle of %g deg\n", pr_.plan.tolerance * 100, *c.boundary);
  }
  return s.errors > 0 ? 1 : 0;
}

void execute_runs(const SweepPlan& p, const std::vector<int>& todo, int jobs, bool keep, const std::function<void(const SweepRow&)>& done,
                  const std::function<void()>& idle) {
  std::vector<int> dem;
  // GLPK keeps one environment per thread (thread-local in Debian's build), and a pool thread's
  // would be left behind when the thread ends: PRD runs, a few LPs each, stay on this thread.
  for (int i : todo) {
    if (p.runs[i].method != Method::prd) {
      dem.push_back(i);
      continue;
    }
    done(execute_run(p, p.runs[i], keep));
    if (idle) idle();
  }
  if (dem.empty()) return;
  std::mutex m;
  std::condition_variable cv;
  std::deque<SweepRow> ready;
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t k; (k = next++) < dem.size();) {
      SweepRow r = execute_run(p, p.runs[dem[k]], keep);
      std::lock_guard<std::mutex> lock(m);
      ready.push_back(std::move(r));
      cv.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, std::min<int>(jobs, static_cast<int>(dem.size()))); ++t) pool.emplace_back(work);
  try {
    for (size_t received = 0; received < dem.size();) {
      std::deque<SweepRow> got;
      {
        std::unique_lock<std::mutex> lock(m);
        if (idle)
          cv.wait_for(lock, std::chrono::milliseconds(10), [&] { return !ready.empty(); });
        else
          cv.wait(lock, [&] { return !ready.empty(); });
        got.swap(ready);
      }
      for (const SweepRow& r : got) {
        done(r);
        ++received;
      }
      if (idle) idle();
    }
  } catch (...) {
    next = dem.size();  // no new runs; the running ones finish, then the error goes on
    for (std::thread& t : pool) t.join();
    throw;
  }
  for (std::thread& t : pool) t.join();
}

}  // namespace sweep_detail

SweepTable run_sweep(const SweepInput& in, const SweepOptions& o) {
  sweep_detail::Prepared pr = sweep_detail::prepare(in, o);
  const int jobs = o.jobs > 0 ? o.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  sweep_detail::Recorder record(pr, o, jobs, jobs == 1 ? "thread" : "threads");
  sweep_detail::execute_runs(pr.plan, pr.todo, jobs, o.keep_runs, std::ref(record), {});
  record.finish();
  return pr.table;
}

}  // namespace masonry
