// The capacity's sensitivity to a sweep's options (DIR/sensitivity.json): elasticities, the
// one-at-a-time lines, the sampled capacities' percentiles and the share of each collapse
// mechanism.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>

#include "model/version.hpp"
#include "sweep/runner.hpp"

namespace masonry {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

namespace {

constexpr int kPercentiles[] = {5, 50, 95};

using sweep_detail::row_at;
const SweepRow* located_row(const SweepTable& t, int i) {
  const SweepRow* r = row_at(t, i);
  return r && located(*r) ? r : nullptr;
}

// The q-th percentile of sorted values: linear interpolation between the order statistics at
// (n - 1) q / 100 (Hyndman & Fan's type 7, numpy's default).
double percentile(const std::vector<double>& sorted, double q) {
  const double h = double(sorted.size() - 1) * q / 100;
  const size_t lo = static_cast<size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  return sorted[lo] + (h - double(lo)) * (sorted[lo + 1] - sorted[lo]);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return percentile(v, 50);
}

// Ranks 1..n, ties given their mean rank.
std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    for (size_t k = i; k <= j; ++k) r[order[k]] = (double(i) + double(j)) / 2 + 1;
    i = j + 1;
  }
  return r;
}

// Spearman's rank correlation; nothing when either variable is constant.
std::optional<double> spearman(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 3) return std::nullopt;
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double mx = (double(x.size()) + 1) / 2;
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mx) * (ry[i] - mx);
    sxx += (rx[i] - mx) * (rx[i] - mx);
    syy += (ry[i] - mx) * (ry[i] - mx);
  }
  if (!(sxx > 0) || !(syy > 0)) return std::nullopt;
  return sxy / std::sqrt(sxx * syy);
}

double number_of(const json& v) { return v.is_number() ? v.get<double>() : NAN; }

// Whether every value key k takes among `runs` is a positive number (ln x is defined).
bool all_positive(const SweepPlan& p, const std::vector<int>& runs, size_t k) {
  for (int i : runs)
    if (!(number_of(p.runs[i].values[k]) > 0)) return false;
  return true;
}

// A sampled sweep: ln(capacity) regressed on every sampled option at once (ln x where the range
// is positive, x otherwise), over the samples with a positive capacity; the coefficients are the
// elasticities with the other options held fixed, averaged over the design.
void regress_samples(const SweepPlan& p, const SweepTable& t, const std::vector<int>& samples, MethodSensitivity& m) {
  const size_t nk = p.keys.size();
  std::vector<bool> log(nk);
  std::vector<int> use;
  for (int i : samples)
    if (const SweepRow* r = located_row(t, i); r && r->capacity > 0) use.push_back(i);
  for (size_t k = 0; k < nk; ++k) log[k] = p.sample->ranges[k].lo > 0;
  std::vector<size_t> cols;  // the keys that enter (PRD: not the DEM options it ignores)
  for (size_t k = 0; k < nk; ++k)
    if (!m.parameters[k].ignored) cols.push_back(k);
  const size_t nc = cols.size() + 1;
  for (size_t c = 0; c < cols.size(); ++c) {
    ParameterSensitivity& ps = m.parameters[cols[c]];
    ps.log = log[cols[c]];
    ps.n = static_cast<int>(use.size());
    ps.estimate = std::string("least squares of ln(capacity) on ") + (ps.log ? "ln(x)" : "x") +
                  " of every sampled option together, over the samples with a positive capacity" +
                  (ps.log ? "" : " (the range reaches x <= 0: d ln(capacity) / dx)");
  }
  if (use.size() < nc + 2) return;  // no residual degrees of freedom to speak of
  Eigen::MatrixXd X(use.size(), nc);
  Eigen::VectorXd y(use.size());
  for (size_t i = 0; i < use.size(); ++i) {
    const SweepRun& run = p.runs[use[i]];
    X(i, 0) = 1;
    for (size_t c = 0; c < cols.size(); ++c) {
      const double x = number_of(run.values[cols[c]]);
      X(i, c + 1) = log[cols[c]] ? std::log(x) : x;
    }
    y(i) = std::log(t[use[i]]->capacity);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  if (qr.rank() < static_cast<Eigen::Index>(nc)) return;  // an option constant over the samples
  const Eigen::VectorXd b = qr.solve(y);
  const Eigen::VectorXd res = y - X * b;
  const double ssr = res.squaredNorm(), sst = (y.array() - y.mean()).matrix().squaredNorm();
  const double s2 = ssr / double(use.size() - nc);
  const Eigen::MatrixXd cov = s2 * (X.transpose() * X).inverse();
  for (size_t c = 0; c < cols.size(); ++c) {
    m.parameters[cols[c]].elasticity = b(c + 1);
    m.parameters[cols[c]].standard_error = std::sqrt(std::max(0.0, cov(c + 1, c + 1)));
  }
  if (sst > 0) m.r2 = 1 - ssr / sst;
}

// A grid: the slope of ln(capacity) against ln(x) along every line of the grid in key k (the
// other options fixed), each line with its own intercept, over the runs with a positive capacity.
void grid_elasticity(const SweepPlan& p, const SweepTable& t, const std::vector<int>& runs, size_t k, ParameterSensitivity& ps) {
  std::map<std::string, std::vector<std::pair<double, double>>> lines;
  std::vector<int> numeric;
  for (int i : runs)
    if (p.runs[i].values[k].is_number()) numeric.push_back(i);
  if (numeric.size() != runs.size()) return;  // strings or switches: no slope
  // ln(x) where every x that enters the fit is positive: the runs located with a positive
  // capacity, not every run (a failed run at thickness -0.05 turned the thickness's elasticity
  // from 5.98 to a slope against x of 38.5 while the four runs fitted were the same).
  // (Of those, the ones on a grid line with another: a line of one point has no slope.)
  const auto others_of = [&](int i) {
    json others = json::array();
    for (size_t j = 0; j < p.keys.size(); ++j) others.push_back(j == k ? json(nullptr) : p.runs[i].values[j]);
    return others.dump();
  };
  std::map<std::string, std::vector<int>> on_line;
  for (int i : runs)
    if (const SweepRow* r = located_row(t, i); r && r->capacity > 0) on_line[others_of(i)].push_back(i);
  std::vector<int> fitted;
  for (const auto& [key, line] : on_line)
    if (line.size() >= 2) fitted.insert(fitted.end(), line.begin(), line.end());
  ps.log = all_positive(p, fitted, k);
  ps.estimate = std::string("least-squares slope of ln(capacity) against ") + (ps.log ? "ln(x)" : "x") +
                " along the grid's lines (the other options fixed, each line its own intercept), over the runs with a positive capacity";
  for (int i : runs) {
    const SweepRow* r = located_row(t, i);
    if (!r || !(r->capacity > 0)) continue;
    const double x = number_of(p.runs[i].values[k]);
    lines[others_of(i)].emplace_back(ps.log ? std::log(x) : x, std::log(r->capacity));
  }
  double sxx = 0, sxy = 0;
  int n = 0, groups = 0;
  for (const auto& [key, pts] : lines) {
    if (pts.size() < 2) continue;
    double mx = 0, my = 0;
    for (const auto& [x, y] : pts) mx += x, my += y;
    mx /= double(pts.size()), my /= double(pts.size());
    for (const auto& [x, y] : pts) sxx += (x - mx) * (x - mx), sxy += (x - mx) * (y - my);
    n += static_cast<int>(pts.size());
    ++groups;
  }
  ps.n = n;
  if (!(sxx > 0)) return;
  const double slope = sxy / sxx;
  double ssr = 0;
  for (const auto& [key, pts] : lines) {
    if (pts.size() < 2) continue;
    double mx = 0, my = 0;
    for (const auto& [x, y] : pts) mx += x, my += y;
    mx /= double(pts.size()), my /= double(pts.size());
    for (const auto& [x, y] : pts) ssr += std::pow(y - my - slope * (x - mx), 2);
  }
  ps.elasticity = slope;
  if (n - groups - 1 > 0) ps.standard_error = std::sqrt(ssr / double(n - groups - 1) / sxx);
}

// The values key k takes in `runs`, in their first order (the grid's axis order).
std::vector<json> axis_values(const SweepPlan& p, const std::vector<int>& runs, size_t k) {
  std::vector<json> out;
  for (int i : runs)
    if (std::find(out.begin(), out.end(), p.runs[i].values[k]) == out.end()) out.push_back(p.runs[i].values[k]);
  return out;
}

// The one-at-a-time line of key k: x and the located capacities along it, by increasing x.
void one_at_a_time(const SweepPlan& p, const SweepTable& t, const std::vector<int>& runs, size_t k, ParameterSensitivity& ps) {
  std::vector<int> line;
  int centre = -1;
  if (p.sample) {
    for (int i : runs) {
      const SweepRun& r = p.runs[i];
      if (r.point == SweepPoint::base) centre = i;
      if (r.point == SweepPoint::base || (r.point == SweepPoint::one_at_a_time && r.line == int(k))) line.push_back(i);
    }
  } else {
    // A grid: the line through the middle value of every other option.
    std::vector<json> middle(p.keys.size());
    for (size_t j = 0; j < p.keys.size(); ++j) {
      const std::vector<json> v = axis_values(p, runs, j);
      middle[j] = v[(v.size() - 1) / 2];
    }
    for (int i : runs) {
      bool on = true;
      for (size_t j = 0; j < p.keys.size() && on; ++j) on = j == k || p.runs[i].values[j] == middle[j];
      if (!on) continue;
      line.push_back(i);
      if (p.runs[i].values[k] == middle[k]) centre = i;
    }
  }
  std::vector<std::pair<double, double>> pts;
  for (int i : line)
    if (const SweepRow* r = located_row(t, i); r && p.runs[i].values[k].is_number()) pts.emplace_back(number_of(p.runs[i].values[k]), r->capacity);
  std::sort(pts.begin(), pts.end());
  for (const auto& [x, c] : pts) ps.values.push_back(x), ps.capacities.push_back(c);
  if (centre >= 0 && p.runs[centre].values[k].is_number()) {
    ps.base_value = number_of(p.runs[centre].values[k]);
    if (const SweepRow* r = located_row(t, centre)) ps.base_capacity = r->capacity;
  }
}

MethodSensitivity method_sensitivity(const SweepPlan& p, const SweepTable& t, Method method) {
  MethodSensitivity m;
  m.method = method;
  std::vector<int> runs, counted;
  for (const SweepRun& r : p.runs)
    if (r.method == method) {
      runs.push_back(r.index);
      if (!p.sample || r.point == SweepPoint::sample) counted.push_back(r.index);
    }
  m.counted = static_cast<int>(counted.size());
  std::vector<double> caps;
  std::map<std::string, std::vector<double>> by_hinges;
  for (int i : counted)
    if (const SweepRow* r = located_row(t, i)) {
      caps.push_back(r->capacity);
      m.zero += r->capacity == 0;
      by_hinges[r->hinges].push_back(r->capacity);
    }
  m.located = static_cast<int>(caps.size());
  if (!caps.empty()) {
    std::vector<double> sorted = caps;
    std::sort(sorted.begin(), sorted.end());
    m.min = sorted.front();
    m.max = sorted.back();
    if (p.sample)
      for (int q : kPercentiles) {
        const double v = percentile(sorted, q);
        m.percentiles.emplace_back(q, v);
        NearestSample best;
        for (int i : counted)
          if (const SweepRow* r = located_row(t, i); r && (best.run < 0 || std::abs(r->capacity - v) < std::abs(best.capacity - v)))
            best = {i, p.runs[i].sample, r->capacity};
        m.nearest.push_back(best);
      }
  }
  // Grouped by the members as lists (ids may hold spaces, so no joined string is a key).
  std::map<std::vector<std::string>, std::vector<double>> member_sets;
  for (const auto& [hinges, c] : by_hinges) {
    std::vector<double>& g = member_sets[members_of(hinges)];
    g.insert(g.end(), c.begin(), c.end());
  }
  std::map<std::string, std::vector<double>> by_member;
  for (const auto& [members, c] : member_sets) {
    for (const std::string& one : members) {
      std::vector<double>& h = by_member[one];
      h.insert(h.end(), c.begin(), c.end());
    }
  }
  const auto name = [](const auto& key) {
    if constexpr (std::is_same_v<std::decay_t<decltype(key)>, std::string>)
      return key;
    else
      return join_members(key);
  };
  const auto shares = [&](const auto& groups) {
    std::vector<MechanismShare> out;
    for (const auto& [key, c] : groups) out.push_back({name(key), static_cast<int>(c.size()), double(c.size()) / double(m.located), median(c)});
    std::stable_sort(out.begin(), out.end(), [](const MechanismShare& a, const MechanismShare& b) { return a.count > b.count; });
    return out;
  };
  m.mechanisms = shares(by_hinges);
  m.members = shares(member_sets);
  m.member_frequency = shares(by_member);
  for (size_t k = 0; k < p.keys.size(); ++k) {
    ParameterSensitivity ps;
    ps.key = p.keys[k];
    ps.ignored = method == Method::prd && sweep_detail::is_dem_option(ps.key);
    if (!ps.ignored) one_at_a_time(p, t, runs, k, ps);
    m.parameters.push_back(std::move(ps));
  }
  if (p.sample) {
    regress_samples(p, t, counted, m);
    for (size_t k = 0; k < p.keys.size(); ++k) {
      if (m.parameters[k].ignored) continue;
      std::vector<double> x, c;
      for (int i : counted)
        if (const SweepRow* r = located_row(t, i)) x.push_back(number_of(p.runs[i].values[k])), c.push_back(r->capacity);
      m.parameters[k].spearman = spearman(x, c);
    }
  } else {
    for (size_t k = 0; k < p.keys.size(); ++k)
      if (!m.parameters[k].ignored) grid_elasticity(p, t, runs, k, m.parameters[k]);
  }
  return m;
}

ojson optional_number(const std::optional<double>& x) { return x ? json_number(*x) : ojson(nullptr); }

// {"groups": [...], "left_out": {"groups", "rows"}}: the 50 most frequent groups; a long tail of
// sets met once (the cathedral's hinge sets) is only counted, each row's set being in sweep.csv.
ojson groups_json(const std::vector<MechanismShare>& groups, const char* name) {
  constexpr size_t kListed = 50;
  ojson list = ojson::array();
  int rows = 0;
  for (size_t i = 0; i < groups.size(); ++i) {
    const MechanismShare& x = groups[i];
    if (i >= kListed) {
      rows += x.count;
      continue;
    }
    list.push_back({{name, x.hinges}, {"count", x.count}, {"share", json_number(x.share)}, {"median_capacity", json_number(x.median_capacity)}});
  }
  return {{"groups", list}, {"left_out", {{"groups", groups.size() > kListed ? groups.size() - kListed : 0}, {"rows", rows}}}};
}

}  // namespace

SweepSensitivity sensitivity(const SweepPlan& p, const SweepTable& t) {
  SweepSensitivity s;
  s.sampled = p.sample.has_value();
  for (Method m : p.methods) s.methods.push_back(method_sensitivity(p, t, m));
  for (const SweepRun& r : p.runs) {
    if (r.method != Method::dem) continue;
    const SweepRow* dem = located_row(t, r.index);
    const SweepRow* prd = located_row(t, r.prd);
    if (dem && prd) s.pairs.push_back({r.index, r.prd, r.sample, prd->capacity, dem->capacity});
  }
  return s;
}

ojson sensitivity_json(const SweepPlan& p, const SweepSensitivity& s) {
  ojson j;
  j["format"] = "masonry-sensitivity/1";
  j["version"] = version_text();  // as sweep.json has: the code that made it
  j["units"] =
      "SI: capacity in " + path_unit(p.base) + " (the last stable d); elasticities d ln(capacity) / d ln(x), dimensionless (d ln(capacity) / dx, 1/unit of x, where log is "
      "false)";
  j["name"] = p.name;
  j["spec"] = p.source;
  j["plan"] = p.hash;
  j["keys"] = p.keys;
  if (p.sample) {
    ojson ranges = ojson::object();
    for (const SweepRange& g : p.sample->ranges) ranges[g.key] = {g.lo, g.hi};
    j["design"] = {{"kind", "latin-hypercube"}, {"count", p.sample->count},          {"seed", p.sample->seed},
                   {"ranges", ranges},          {"one_at_a_time", p.sample->levels}, {"only", p.sample->only}};
  } else {
    j["design"] = {{"kind", "grid"}};
  }
  ojson base = ojson::object();
  for (size_t k = 0; k < p.keys.size(); ++k) base[p.keys[k]] = ojson::parse(p.base_values[k].dump());
  j["base"] = base;
  j["prd_ignores"] = p.prd_ignores;
  const std::string note = prd_ignores_note(p);
  j["note"] = note.empty() ? ojson(nullptr) : ojson(note);
  ojson methods = ojson::object();
  for (const MethodSensitivity& m : s.methods) {
    ojson o;
    o["counted"] = m.counted;
    o["located"] = m.located;
    o["zero_capacity"] = m.zero;
    o["min"] = m.located ? json_number(m.min) : ojson(nullptr);
    o["max"] = m.located ? json_number(m.max) : ojson(nullptr);
    if (s.sampled) {
      ojson pc = ojson::object(), near = ojson::object();
      for (size_t q = 0; q < m.percentiles.size(); ++q) {
        const std::string name = std::to_string(m.percentiles[q].first);
        pc[name] = json_number(m.percentiles[q].second);
        near[name] = {{"sample", m.nearest[q].sample}, {"run", m.nearest[q].run}, {"capacity", json_number(m.nearest[q].capacity)}};
      }
      o["percentiles"] = pc;
      o["nearest"] = near;
      o["r2"] = optional_number(m.r2);
    }
    o["mechanisms"] = groups_json(m.mechanisms, "hinges");
    o["mechanisms_by_member"] = groups_json(m.members, "members");
    o["hinge_members"] = groups_json(m.member_frequency, "member");
    ojson params = ojson::object();
    for (const ParameterSensitivity& ps : m.parameters) {
      ojson q;
      if (ps.ignored) {
        q["ignored"] = true;
        params[ps.key] = q;
        continue;
      }
      q["elasticity"] = optional_number(ps.elasticity);
      q["standard_error"] = optional_number(ps.standard_error);
      q["log"] = ps.log;
      q["n"] = ps.n;
      q["estimate"] = ps.estimate;
      if (s.sampled) q["spearman"] = optional_number(ps.spearman);
      ojson line;
      line["values"] = ojson::array();
      line["capacities"] = ojson::array();
      for (size_t i = 0; i < ps.values.size(); ++i) {
        line["values"].push_back(json_number(ps.values[i]));
        line["capacities"].push_back(json_number(ps.capacities[i]));
      }
      line["base_value"] = optional_number(ps.base_value);
      line["base_capacity"] = optional_number(ps.base_capacity);
      q["one_at_a_time"] = line;
      params[ps.key] = q;
    }
    o["parameters"] = params;
    methods[method_name(m.method)] = o;
  }
  j["methods"] = methods;
  ojson pairs = ojson::array();
  for (const PrdDemPair& x : s.pairs)
    pairs.push_back({{"dem_run", x.dem},
                     {"prd_run", x.prd},
                     {"sample", x.sample >= 0 ? ojson(x.sample) : ojson(nullptr)},
                     {"prd", json_number(x.prd_capacity)},
                     {"dem", json_number(x.dem_capacity)},
                     {"diff", x.prd_capacity > 0 ? json_number((x.dem_capacity - x.prd_capacity) / x.prd_capacity) : ojson(nullptr)}});
  j["prd_dem"] = pairs;
  return j;
}

}  // namespace masonry
