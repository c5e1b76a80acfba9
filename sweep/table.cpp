// The sweep table: rows, sweep.csv written and read back, and the summary the report draws.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "model/options.hpp"
#include "sweep/runner.hpp"

namespace masonry {

using nlohmann::json;

namespace {

const char* const kTail[] = {"capacity", "stopped", "time_s", "diff_prd", "required_friction_angle", "hinges", "message"};

// A sampled sweep's table has a `sample` column after `method`: the run's point in the design.
size_t head_columns(const SweepPlan& p) { return p.sample ? 4 : 3; }

// Numbers in their shortest exact form (nlohmann's): a resumed table reads back the very doubles
// it wrote, so a row computed from them (diff_prd) is the same whether or not the sweep stopped.
std::string num(double x) { return std::isfinite(x) ? json(x).dump() : ""; }

std::string csv_join(const std::vector<std::string>& cells) {
  std::string s;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (i) s += ',';
    s += csv_field(cells[i]);
  }
  s += '\n';
  return s;
}

// One CSV line (RFC 4180 quoting, no embedded newlines: messages are one line).
std::vector<std::string> csv_split(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        f.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      f.emplace_back();
    } else {
      f.back() += ch;
    }
  }
  return f;
}

bool parse_number(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(x);
}

// m: the end of a run's loading path, step x max_steps with the run's own values where it varies them.
double path_end(const SweepPlan& p, const SweepRun& run) {
  double step = p.base.motion.step, steps = p.base.motion.max_steps;
  for (size_t k = 0; k < p.keys.size(); ++k) {
    if (!run.values[k].is_number()) continue;
    if (p.keys[k] == option_key(&Motion::step)) step = run.values[k].get<double>();
    if (p.keys[k] == option_key(&Motion::max_steps)) steps = run.values[k].get<double>();
  }
  return step * steps * (1 + 1e-9);
}

}  // namespace

namespace sweep_detail {
const SweepRow* row_at(const SweepTable& t, int i) { return i >= 0 && i < int(t.size()) && t[i] ? &*t[i] : nullptr; }
}  // namespace sweep_detail
using sweep_detail::row_at;

json row_to_json(const SweepRow& r) {
  json j = {
      {"run", r.index},     {"id", r.id},          {"method", method_name(r.method)}, {"stopped", status_name(r.status)}, {"capacity", r.capacity},
      {"time_s", r.time_s}, {"message", r.message}};
  if (r.required_friction_angle) j["required_friction_angle"] = *r.required_friction_angle;
  if (!r.hinges.empty()) j["hinges"] = r.hinges;
  if (r.files) j["files"] = {{"case", r.files->case_json}, {"results", r.files->results_json}, {"steps", r.files->steps_csv}};
  return j;
}

SweepRow row_from_json(const json& j) {
  SweepRow r;
  r.index = j.at("run").get<int>();
  r.id = j.at("id").get<std::string>();
  const std::string method = j.at("method").get<std::string>();
  const std::optional<Method> m = parse_method(method);
  if (!m) throw std::runtime_error("sweep row: unknown \"method\" '" + method + "'");
  r.method = *m;
  const std::string status = j.at("stopped").get<std::string>();
  const std::optional<RunStatus> st = parse_status(status);
  if (!st || *st == RunStatus::running) throw std::runtime_error("sweep row: unknown \"stopped\" '" + status + "'");
  r.status = *st;
  r.capacity = j.at("capacity").get<double>();
  r.time_s = j.at("time_s").get<double>();
  r.message = j.at("message").get<std::string>();
  if (j.contains("required_friction_angle")) r.required_friction_angle = j["required_friction_angle"].get<double>();
  if (j.contains("hinges")) r.hinges = j["hinges"].get<std::string>();
  if (j.contains("files"))
    r.files = SweepRow::Files{j["files"].at("case").get<std::string>(), j["files"].at("results").get<std::string>(),
                              j["files"].at("steps").get<std::string>()};
  return r;
}

bool located(const SweepRow& r) { return located(r.status); }

std::optional<double> diff_prd(const SweepRow& dem, const SweepRow* prd) {
  if (!prd || !located(dem) || !located(*prd) || prd->capacity == 0) return std::nullopt;
  const double d = (dem.capacity - prd->capacity) / prd->capacity;
  if (!std::isfinite(d)) return std::nullopt;
  return d;
}

std::string sweep_csv_header(const SweepPlan& p) {
  std::vector<std::string> cells = {"run", "id", "method"};
  if (p.sample) cells.push_back("sample");
  cells.insert(cells.end(), p.keys.begin(), p.keys.end());
  cells.insert(cells.end(), std::begin(kTail), std::end(kTail));
  return csv_join(cells);
}

std::string sweep_csv_line(const SweepPlan& p, const SweepRow& r, const SweepTable& t) {
  const SweepRun& run = p.runs.at(r.index);
  std::vector<std::string> cells = {std::to_string(r.index), r.id, method_name(r.method)};
  if (p.sample) cells.push_back(point_text(run));
  for (const json& v : run.values) cells.push_back(v.is_null() ? std::string() : value_text(v));
  const std::optional<double> diff = r.method == Method::dem ? diff_prd(r, row_at(t, run.prd)) : std::nullopt;
  cells.push_back(r.status == RunStatus::error ? std::string() : num(r.capacity));
  cells.push_back(status_name(r.status));
  cells.push_back(num(r.time_s));
  cells.push_back(diff ? num(*diff) : std::string());
  cells.push_back(r.required_friction_angle ? num(*r.required_friction_angle) : std::string());
  cells.push_back(r.hinges);
  std::string message = r.message;  // one line, as every message is meant to be
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  cells.push_back(message);
  return csv_join(cells);
}

std::string sweep_csv(const SweepPlan& p, const SweepTable& t) {
  std::string s = sweep_csv_header(p);
  for (const auto& r : t)
    if (r) s += sweep_csv_line(p, *r, t);
  return s;
}

SweepTable read_sweep_csv(const SweepPlan& p, const std::string& text, const std::string& source) {
  SweepTable t(p.runs.size());
  std::map<std::string, int> by_id;
  for (const SweepRun& r : p.runs) by_id[r.id] = r.index;
  const std::string header = sweep_csv_header(p);
  size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    const size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) break;  // torn last line: the process stopped while writing it
    const std::string line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (line_no == 1) {
      if (line + "\n" != header)
        throw SweepError(source + ": written by another sweep (its columns are \"" + line + "\"): use --restart to discard it, or another --out");
      continue;
    }
    const std::vector<std::string> f = csv_split(line);
    const size_t nk = p.keys.size(), h = head_columns(p), tail = h + nk;
    if (f.size() != tail + std::size(kTail)) continue;
    auto it = by_id.find(f[1]);
    if (it == by_id.end())
      throw SweepError(
          source + ":" + std::to_string(line_no) + ": run id " + f[1] +
          " is not a run of this sweep (the sweep file or the case changed since): use --restart to discard the table, or another --out");
    const SweepRun& run = p.runs[it->second];
    // A line whose fields do not all read back is incomplete: its run is done again.
    bool ok = f[2] == method_name(run.method) && (h == 3 || f[3] == point_text(run));
    for (size_t k = 0; k < nk && ok; ++k) ok = f[h + k] == (run.values[k].is_null() ? "" : value_text(run.values[k]));
    SweepRow r;
    r.index = run.index;
    r.id = run.id;
    r.method = run.method;
    const std::optional<RunStatus> status = parse_status(f[tail + 1]);
    ok = ok && status && *status != RunStatus::running;
    if (status) r.status = *status;
    r.hinges = f[tail + 5];
    r.message = f[tail + 6];
    // A number no run can give (a capacity beyond its path or below 0, a negative time, an angle
    // beyond 90 degrees) is a row someone or something else wrote: its run is done again.
    ok = ok && parse_number(f[tail + 2], r.time_s) && r.time_s >= 0;
    if (r.status != RunStatus::error) ok = ok && parse_number(f[tail], r.capacity) && r.capacity >= 0 && r.capacity <= path_end(p, run);
    double angle = 0;
    if (!f[tail + 4].empty()) {
      ok = ok && parse_number(f[tail + 4], angle) && angle >= 0 && angle <= 90;
      r.required_friction_angle = angle;
    }
    if (ok && !t[r.index]) t[r.index] = r;
  }
  return t;
}

SweepSummary summarize(const SweepPlan& p, const SweepTable& t) {
  SweepSummary s;
  for (const auto& r : t) {
    s.finished += r.has_value();
    s.errors += r && !located(*r);
  }
  // A sampled sweep has no curves: its samples vary every key at once (the sensitivity section
  // draws them).
  if (p.sample) return s;
  // The curves are the DEM runs, or the PRD runs in a sweep without DEM; x is the friction angle
  // when it varies, else the first option whose values in those runs are all numbers.
  bool has_dem = false;
  for (const SweepRun& r : p.runs) has_dem = has_dem || r.method == Method::dem;
  const Method method = has_dem ? Method::dem : Method::prd;
  int xk = -1;
  for (size_t k = 0; k < p.keys.size() && xk < 0; ++k)
    if (p.keys[k] == option_key(&DemOptions::friction_angle) && has_dem) xk = int(k);
  for (size_t k = 0; k < p.keys.size() && xk < 0; ++k) {
    bool numeric = true;
    for (const SweepRun& r : p.runs) numeric = numeric && (r.method != method || r.values[k].is_number());
    if (numeric) xk = int(k);
  }
  if (xk < 0) return s;
  s.x = p.keys[xk];
  std::map<std::string, int> curve_of;
  for (const SweepRun& r : p.runs) {
    if (r.method != method) continue;
    json others = json::array();
    for (size_t k = 0; k < p.keys.size(); ++k) others.push_back(int(k) == xk ? json(nullptr) : r.values[k]);
    auto [it, fresh] = curve_of.emplace(others.dump(), int(s.curves.size()));
    if (fresh) {
      SweepCurve c;
      for (size_t k = 0; k < p.keys.size(); ++k)
        if (int(k) != xk && !r.values[k].is_null()) c.fixed.emplace_back(p.keys[k], r.values[k]);
      s.curves.push_back(std::move(c));
    }
    const SweepRow* row = row_at(t, r.index);
    if (row && located(*row)) s.curves[it->second].runs.push_back(r.index);
  }
  for (SweepCurve& c : s.curves) {
    std::stable_sort(c.runs.begin(), c.runs.end(),
                     [&](int a, int b) { return p.runs[a].values[xk].get<double>() < p.runs[b].values[xk].get<double>(); });
    if (s.x != option_key(&DemOptions::friction_angle)) continue;
    // Largest friction angle at which DEM and PRD differ by more than the tolerance.
    std::vector<std::pair<double, bool>> differ;  // (angle, |diff| > tolerance)
    for (int i : c.runs)
      if (const auto d = diff_prd(*t[i], row_at(t, p.runs[i].prd)))
        differ.emplace_back(p.runs[i].values[xk].get<double>(), std::abs(*d) > p.tolerance);
    for (const auto& [x, out] : differ)
      if (out) c.boundary = x;
    if (c.boundary)
      for (const auto& [x, out] : differ) c.boundary_clean = c.boundary_clean && (out == (x <= *c.boundary));
  }
  return s;
}

}  // namespace masonry
