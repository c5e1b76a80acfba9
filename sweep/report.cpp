// The sweep's report, in the compare style: sweep.json for CI, report.md and report.html (no
// script: a figure and tables), figures/capacity.svg.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

#include "model/options.hpp"
#include "model/version.hpp"
#include "report/document.hpp"
#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/svg.hpp"
#include "sweep/runner.hpp"

namespace masonry {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

namespace {

using fmt::pct;
using fmt::px;
using fmt::secs;

using sweep_detail::row_at;
double x_of(const SweepPlan& p, const SweepSummary& s, int run) {
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (p.keys[k] == s.x) return p.runs[run].values[k].get<double>();
  return NAN;
}
bool friction_x(const SweepSummary& s) { return s.x == option_key(&DemOptions::friction_angle); }

// The PRD run every point of a curve refers to, when it is one run (x is a DEM option).
const SweepRow* curve_prd(const SweepPlan& p, const SweepTable& t, const SweepCurve& c) {
  int prd = -1;
  for (int i : c.runs) {
    if (p.runs[i].method != Method::dem || p.runs[i].prd < 0 || (prd >= 0 && p.runs[i].prd != prd)) return nullptr;
    prd = p.runs[i].prd;
  }
  const SweepRow* r = row_at(t, prd);
  return r && located(*r) ? r : nullptr;
}

// An option's value for people: numbers to 6 digits (sweep.csv keeps every digit).
std::string shown(const json& v) { return v.is_number() ? fmt::g(v.get<double>(), 6) : value_text(v); }

std::string curve_label(const SweepCurve& c, bool dem) {
  std::string s;
  for (const auto& [key, value] : c.fixed) s += (s.empty() ? "" : ", ") + key + " = " + shown(value);
  return s.empty() ? (dem ? "DEM" : "PRD") : s;
}

std::string x_title(const SweepSummary& s) { return friction_x(s) ? "friction angle (deg)" : s.x; }

const char* point_name(SweepPoint k) {
  switch (k) {
    case SweepPoint::grid: return "grid";
    case SweepPoint::base: return "base";
    case SweepPoint::one_at_a_time: return "one-at-a-time";
    case SweepPoint::sample: return "sample";
  }
  return "grid";
}

bool any_dem(const SweepPlan& p) {
  for (const SweepRun& r : p.runs)
    if (r.method == Method::dem) return true;
  return false;
}

// The report's text, shared by the Markdown and the HTML writers.
struct Content {
  std::string title, lead;
  std::vector<std::string> findings;  // one sentence each
  Table boundaries, runs;
  bool has_figure = false;
};

Content content(const SweepPlan& p, const SweepTable& t, const SweepSummary& s) {
  Content c;
  c.title = "Sweep: " + p.name;
  int prd = 0;
  for (const SweepRun& r : p.runs) prd += r.method == Method::prd;
  c.lead = "Case " + p.base.name + " (sweep file " + p.source + ", plan " + p.hash + "): " + std::to_string(p.runs.size()) + " runs (" +
           std::to_string(prd) + " PRD, " + std::to_string(p.runs.size() - prd) + " DEM), " + std::to_string(s.finished) + " finished, " +
           std::to_string(s.errors) + " without a located capacity (failed, or a DEM hold undecided). Capacity: the last stable d (" +
           path_unit(p.base) + "); difference: (DEM - PRD) / PRD; tolerance " + fmt::g(p.tolerance * 100) + "%.";
  c.has_figure = !s.x.empty() && !s.curves.empty();
  const bool dem = any_dem(p);
  if (friction_x(s) && dem) {
    c.boundaries.head = {"curve", "PRD capacity (" + path_unit(p.base) + ")", "PRD: sliding below (deg)",
                         "DEM and PRD differ by more than " + fmt::g(p.tolerance * 100) + "% up to (deg)"};
    for (const SweepCurve& cv : s.curves) {
      const SweepRow* pr = curve_prd(p, t, cv);
      std::string b = cv.boundary ? fmt::g(*cv.boundary, 6) : "nowhere";
      if (cv.boundary && !cv.boundary_clean) b += " (not a clean boundary: agreement below it, or disagreement above)";
      c.boundaries.rows.push_back({curve_label(cv, dem), pr ? fmt::g(pr->capacity, 4) : "-",
                                   pr && pr->required_friction_angle ? fmt::g(*pr->required_friction_angle, 4) : "-", b});
      if (cv.boundary)
        c.findings.push_back(curve_label(cv, dem) + ": the DEM capacity differs from the PRD's by more than " + fmt::g(p.tolerance * 100) +
                             "% at friction angles up to " + fmt::g(*cv.boundary, 6) + " deg" +
                             (pr && pr->required_friction_angle
                                  ? "; the PRD's sliding check predicts sliding below " + fmt::g(*pr->required_friction_angle, 4) + " deg."
                                  : "."));
    }
  }
  c.runs.head = {"run", "method"};
  if (p.sample) c.runs.head.push_back("sample");
  for (const std::string& k : p.keys) c.runs.head.push_back(k);
  c.runs.head.push_back("capacity (" + path_unit(p.base) + ")");
  for (const char* h : {"stopped", "difference from PRD", "PRD: sliding below (deg)", "time (s)", "message"}) c.runs.head.push_back(h);
  for (const SweepRun& run : p.runs) {
    std::vector<std::string> r = {std::to_string(run.index), method_name(run.method)};
    if (p.sample) r.push_back(point_text(run));
    for (const json& v : run.values) r.push_back(v.is_null() ? "-" : shown(v));
    const SweepRow* row = row_at(t, run.index);
    if (!row) {
      for (const char* x : {"-", "not run", "-", "-", "-", ""}) r.push_back(x);
    } else {
      const auto d = run.method == Method::dem ? diff_prd(*row, row_at(t, run.prd)) : std::nullopt;
      r.push_back(row->status == RunStatus::error ? "-" : fmt::g(row->capacity, 6));
      r.push_back(status_name(row->status));
      r.push_back(d ? pct(*d) : "-");
      r.push_back(row->required_friction_angle ? fmt::g(*row->required_friction_angle, 4) : "-");
      r.push_back(secs(row->time_s));
      r.push_back(row->message);
    }
    c.runs.rows.emplace_back(r.begin(), r.end());
  }
  return c;
}

}  // namespace

ojson sweep_json(const SweepPlan& p, const SweepTable& t, const SweepSummary& s) {
  ojson j;
  j["format"] = "masonry-sweep-results/1";
  j["version"] = version_text();
  j["units"] = "SI: capacity in " + path_unit(p.base) + " (the last stable d), time in s; friction angles in degrees";
  j["name"] = p.name;
  j["spec"] = p.source;
  j["case"] = p.base.name;
  j["plan"] = p.hash;
  j["methods"] = ojson::array();
  for (Method m : p.methods) j["methods"].push_back(method_name(m));
  j["keys"] = p.keys;
  j["tolerance"] = p.tolerance;
  j["complete"] = s.finished == static_cast<int>(p.runs.size());
  j["failed"] = s.errors;
  ojson runs = ojson::array();
  for (const SweepRun& run : p.runs) {
    const SweepRow* row = row_at(t, run.index);
    if (!row) continue;
    ojson params = ojson::object();
    for (size_t k = 0; k < p.keys.size(); ++k)
      if (!run.values[k].is_null()) params[p.keys[k]] = ojson::parse(run.values[k].dump());
    const auto d = run.method == Method::dem ? diff_prd(*row, row_at(t, run.prd)) : std::nullopt;
    runs.push_back({{"run", run.index},
                    {"id", run.id},
                    {"method", method_name(run.method)},
                    {"point", point_name(run.point)},
                    {"sample", run.sample >= 0 ? ojson(run.sample) : ojson(nullptr)},
                    {"parameters", params},
                    {"stopped", status_name(row->status)},
                    {"capacity", row->status == RunStatus::error ? ojson(nullptr) : json_number(row->capacity)},
                    {"time_s", json_number(row->time_s)},
                    {"prd_run", run.prd >= 0 ? ojson(run.prd) : ojson(nullptr)},
                    {"diff_prd", d ? json_number(*d) : ojson(nullptr)},
                    {"required_friction_angle", row->required_friction_angle ? json_number(*row->required_friction_angle) : ojson(nullptr)},
                    {"hinges", row->hinges},
                    {"message", row->message}});
  }
  j["runs"] = runs;
  j["x"] = s.x.empty() ? ojson(nullptr) : ojson(s.x);
  ojson curves = ojson::array();
  for (const SweepCurve& c : s.curves) {
    ojson fixed = ojson::object();
    for (const auto& [key, value] : c.fixed) fixed[key] = ojson::parse(value.dump());
    const SweepRow* pr = curve_prd(p, t, c);
    curves.push_back({{"parameters", fixed},
                      {"runs", c.runs},
                      {"prd_capacity", pr ? json_number(pr->capacity) : ojson(nullptr)},
                      {"prd_required_friction_angle", pr && pr->required_friction_angle ? json_number(*pr->required_friction_angle) : ojson(nullptr)},
                      {"boundary", c.boundary ? json_number(*c.boundary) : ojson(nullptr)},
                      {"boundary_clean", c.boundary_clean}});
  }
  j["curves"] = curves;
  return j;
}

std::string svg_sweep(const SweepPlan& p, const SweepTable& t, const SweepSummary& s) {
  const double W = 860, left = 74, right = 270, top = 44, ph = 360, H = top + ph + 56;
  const double pw = W - left - right;
  const bool dem = any_dem(p), fx = friction_x(s);
  // Ranges: every point, every PRD capacity, every vertical marker.
  double xlo = std::numeric_limits<double>::max(), xhi = -xlo, ymax = 0;
  const auto cover_x = [&](double x) { xlo = std::min(xlo, x), xhi = std::max(xhi, x); };
  for (const SweepCurve& c : s.curves) {
    for (int i : c.runs) {
      cover_x(x_of(p, s, i));
      ymax = std::max(ymax, t[i]->capacity);
      if (const SweepRow* pr = dem ? row_at(t, p.runs[i].prd) : nullptr; pr && located(*pr)) ymax = std::max(ymax, pr->capacity);
    }
    if (const SweepRow* pr = curve_prd(p, t, c); fx && pr && pr->required_friction_angle) cover_x(*pr->required_friction_angle);
  }
  if (xlo > xhi) xlo = 0, xhi = 1;
  if (xhi - xlo < 1e-12) xlo -= 1, xhi += 1;
  const double padx = 0.04 * (xhi - xlo);
  xlo -= padx;
  xhi += padx;
  if (!(ymax > 0)) ymax = 1e-3;
  ymax *= 1.1;
  const Plot plot{left, top, pw, ph, xlo, xhi, 0, ymax};
  const auto X = [&](double x) { return plot.X(x); };
  const auto Y = [&](double y) { return plot.Y(y); };
  std::ostringstream o;
  o << svg_open(W, H) << "<text x=\"" << px(left) << "\" y=\"22\" font-size=\"15\" font-weight=\"bold\">Capacity against the "
    << xml_escape(x_title(s)) << "</text>\n"
    << svg_axes(plot, linear_ticks(xlo, xhi, 8, 6), linear_ticks(0, ymax, 6, 4), x_title(s), "capacity: last stable d (" + path_unit(p.base) + ")");
  for (size_t ci = 0; ci < s.curves.size(); ++ci) {
    const SweepCurve& c = s.curves[ci];
    const char* col = series_color(ci);
    // The PRD reference: one horizontal line when every point has the same PRD run.
    if (dem) {
      const SweepRow* pr = curve_prd(p, t, c);
      std::string pts;
      if (pr) {
        pts = px(X(xlo)) + "," + px(Y(pr->capacity)) + " " + px(X(xhi)) + "," + px(Y(pr->capacity));
      } else {
        for (int i : c.runs)
          if (const SweepRow* q = row_at(t, p.runs[i].prd); q && located(*q)) pts += px(X(x_of(p, s, i))) + "," + px(Y(q->capacity)) + " ";
      }
      if (!pts.empty())
        o << "<polyline fill=\"none\" stroke=\"" << col << "\" stroke-width=\"1.8\" stroke-dasharray=\"8,5\" points=\"" << pts
          << "\"><title>PRD capacity</title></polyline>\n";
      if (fx && pr && pr->required_friction_angle)
        o << "<line x1=\"" << px(X(*pr->required_friction_angle)) << "\" x2=\"" << px(X(*pr->required_friction_angle)) << "\" y1=\"" << px(top)
          << "\" y2=\"" << px(top + ph) << "\" stroke=\"" << col << "\" stroke-width=\"1.6\" stroke-dasharray=\"2,3\"><title>PRD: sliding below "
          << fmt::g(*pr->required_friction_angle, 4) << " deg</title></line>\n";
      if (c.boundary)
        o << "<line x1=\"" << px(X(*c.boundary)) << "\" x2=\"" << px(X(*c.boundary)) << "\" y1=\"" << px(top) << "\" y2=\"" << px(top + ph)
          << "\" stroke=\"" << col << "\" stroke-width=\"1.4\" stroke-dasharray=\"10,3,2,3\"><title>DEM and PRD differ by more than "
          << fmt::g(p.tolerance * 100) << "% up to " << fmt::g(*c.boundary, 6) << "</title></line>\n";
    }
    std::string pts;
    for (int i : c.runs) pts += px(X(x_of(p, s, i))) + "," + px(Y(t[i]->capacity)) + " ";
    o << "<polyline fill=\"none\" stroke=\"" << col << "\" stroke-width=\"2\" points=\"" << pts << "\"/>\n<g fill=\"" << col << "\">\n";
    for (int i : c.runs)
      o << "<circle cx=\"" << px(X(x_of(p, s, i))) << "\" cy=\"" << px(Y(t[i]->capacity)) << "\" r=\"3.5\"><title>run " << i << ": "
        << xml_escape(run_label(p, p.runs[i])) << ": " << fmt::g(t[i]->capacity, 6) << " " << path_unit(p.base) << ", " << status_name(t[i]->status)
        << "</title></circle>\n";
    o << "</g>\n";
  }
  // Legend on the right: the curves, then the line styles.
  double ly = top + 8;
  const double lx = left + pw + 16;
  o << "<g font-size=\"12\">\n";
  for (size_t ci = 0; ci < s.curves.size(); ++ci, ly += 18)
    o << "<rect x=\"" << px(lx) << "\" y=\"" << px(ly - 6) << "\" width=\"28\" height=\"10\" fill=\"" << series_color(ci) << "\"/><text x=\""
      << px(lx + 34) << "\" y=\"" << px(ly + 4) << "\">" << xml_escape(curve_label(s.curves[ci], dem)) << "</text>\n";
  ly += 8;
  const auto style = [&](const char* dash, const std::string& text) {
    o << "<line x1=\"" << px(lx) << "\" x2=\"" << px(lx + 28) << "\" y1=\"" << px(ly) << "\" y2=\"" << px(ly)
      << "\" stroke=\"#333\" stroke-width=\"1.8\"" << (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : std::string()) << "/><text x=\""
      << px(lx + 34) << "\" y=\"" << px(ly + 4) << "\">" << xml_escape(text) << "</text>\n";
    ly += 18;
  };
  bool predicted = false, bounded = false;
  for (const SweepCurve& c : s.curves) {
    const SweepRow* pr = curve_prd(p, t, c);
    predicted = predicted || (pr && pr->required_friction_angle);
    bounded = bounded || c.boundary;
  }
  style("", dem ? "DEM capacity (points: runs)" : "PRD capacity (points: runs)");
  if (dem) style("8,5", "PRD capacity");
  if (dem && fx && predicted) style("2,3", "PRD: sliding predicted below");
  if (dem && fx && bounded) style("10,3,2,3", "differ by > " + fmt::g(p.tolerance * 100) + "% up to here");
  o << "</g>\n</svg>\n";
  return o.str();
}

namespace {

// How the capacity runs along a one-at-a-time line.
std::string trend(const std::vector<double>& c) {
  if (c.size() < 2) return "-";
  bool up = false, down = false;
  for (size_t i = 1; i < c.size(); ++i) up = up || c[i] > c[i - 1], down = down || c[i] < c[i - 1];
  return up && down ? "not monotonic" : up ? "rises" : down ? "falls" : "flat";
}

std::string design_text(const SweepPlan& p) {
  if (!p.sample) return "The grid's runs. One-at-a-time lines: each option's values with every other option at its middle value.";
  const SweepSample& s = *p.sample;
  std::string text = "A Latin hypercube of " + std::to_string(s.count) + " samples (seed " + std::to_string(s.seed) + ") over " +
                     std::to_string(s.ranges.size()) + " option" + (s.ranges.size() > 1 ? "s" : "") +
                     ": each range cut into as many equal strata as samples, one sample in each stratum at a uniform position within it, "
                     "the options' strata paired at random; values rounded to 6 significant digits (whole numbers for an integer parameter).";
  if (!s.only.empty()) text += " This sweep runs " + std::to_string(s.only.size()) + " of the samples (field 'only').";
  if (s.levels > 0)
    text += " Besides the samples: the base point (every option at the case's own value) and " + std::to_string(s.levels) +
            " evenly spaced values of each range with the other options at the base point (one at a time).";
  return text;
}

// The most frequent groups (`max_rows` rows at most, the rest summed up).
Table mechanism_table(const std::vector<MechanismShare>& groups, const std::string& what, const std::string& d_unit, bool sampled, int located,
                      size_t max_rows = 12) {
  Table t;
  t.head = {what, sampled ? "samples" : "runs", "share", "median capacity (" + d_unit + ")"};
  int rest = 0, rest_groups = 0;
  for (size_t i = 0; i < groups.size(); ++i) {
    const MechanismShare& x = groups[i];
    if (i >= max_rows) {
      rest += x.count, ++rest_groups;
      continue;
    }
    t.rows.push_back({x.hinges.empty() ? Cell("none") : Cell(x.hinges, CellStyle::code), std::to_string(x.count),
                      fmt::number(100 * x.share, "%.1f%%", 100 * x.share), fmt::g(x.median_capacity, 4)});
  }
  if (rest) {
    const double share = 100.0 * rest / std::max(1, located);
    t.rows.push_back({std::to_string(rest_groups) + " others", std::to_string(rest), fmt::number(share, "%.1f%%", share), "-"});
  }
  return t;
}

void sensitivity_section(Document& d, const SweepPlan& p, const SweepTable& t, const SweepSensitivity& sens) {
  d.heading(2, {"Sensitivity of the capacity"});
  d.paragraph({design_text(p) + " The numbers are also in ", Cell("sensitivity.json", CellStyle::code), "."});
  for (const MethodSensitivity& m : sens.methods) {
    const std::string M = method_label(m.method);
    d.heading(3, {M});
    if (sens.sampled) {
      Table pc;
      const std::string u = " (" + path_unit(p.base) + ")";
      pc.head = {"samples", "located", "capacity 0", "5th percentile" + u, "median" + u, "95th percentile" + u, "least" + u, "largest" + u};
      std::vector<Cell> row = {std::to_string(m.counted), std::to_string(m.located), std::to_string(m.zero)};
      for (size_t q = 0; q < 3; ++q) row.push_back(q < m.percentiles.size() ? fmt::g(m.percentiles[q].second, 4) : "-");
      row.push_back(m.located ? fmt::g(m.min, 4) : "-");
      row.push_back(m.located ? fmt::g(m.max, 4) : "-");
      pc.rows.push_back(row);
      d.table(pc);
      std::string near;
      for (size_t q = 0; q < m.nearest.size(); ++q)
        near += (near.empty() ? "" : "; ") + std::to_string(m.percentiles[q].first) + "th: sample " + std::to_string(m.nearest[q].sample) + " (" +
                fmt::g(m.nearest[q].capacity, 4) + " " + path_unit(p.base) + ")";
      if (!near.empty())
        d.paragraph({"Percentiles: linear interpolation between the sorted capacities (numpy's default). The samples nearest them: " + near + "."});
    }
    Table el;
    el.head = {"option",
               "elasticity",
               "standard error",
               "runs",
               sens.sampled ? "Spearman" : "",
               "one at a time: capacity (" + path_unit(p.base) + ")",
               "along the line",
               "capacity 0 at"};
    if (!sens.sampled) el.head.erase(el.head.begin() + 4);
    std::string how;
    for (const ParameterSensitivity& ps : m.parameters) {
      std::vector<Cell> row = {Cell(ps.key, CellStyle::code)};
      if (ps.ignored) {
        for (const char* x : {"ignored", "-", "-"}) row.push_back(x);
        if (sens.sampled) row.push_back("-");
        for (const char* x : {"-", "-", "-"}) row.push_back(x);
        el.rows.push_back(row);
        continue;
      }
      if (how.empty()) how = ps.estimate;
      row.push_back(ps.elasticity ? fmt::g(*ps.elasticity, 3) + (ps.log ? "" : " per unit") : "-");
      row.push_back(ps.standard_error ? fmt::g(*ps.standard_error, 2) : "-");
      row.push_back(std::to_string(ps.n));
      if (sens.sampled) row.push_back(ps.spearman ? fmt::number(*ps.spearman, "%+.2f", *ps.spearman) : "-");
      if (ps.capacities.empty()) {
        row.push_back("-");
      } else {
        const auto [a, b] = std::minmax_element(ps.capacities.begin(), ps.capacities.end());
        row.push_back(fmt::g(*a, 3) + " to " + fmt::g(*b, 3) + " (x = " + fmt::g(ps.values[a - ps.capacities.begin()], 4) + ", " +
                      fmt::g(ps.values[b - ps.capacities.begin()], 4) + ")");
      }
      row.push_back(trend(ps.capacities));
      std::string zeros;
      for (size_t i = 0; i < ps.values.size(); ++i)
        if (ps.capacities[i] == 0) zeros += (zeros.empty() ? "" : ", ") + fmt::g(ps.values[i], 4);
      row.push_back(zeros.empty() ? "-" : zeros);
      el.rows.push_back(row);
    }
    d.table(el);
    if (!how.empty())
      d.paragraph({"Elasticity: d ln(capacity) / d ln(x) (d ln(capacity) / dx, per unit of x, for an option whose fitted values reach 0 or below), " + how + (m.r2 ? " (R² = " + fmt::g(*m.r2, 3) + ")" : "") +
                   "; runs with capacity 0 have no logarithm and are left out of it" +
                   (sens.sampled ? " (the Spearman rank correlation of x and the capacity, over every located sample, keeps them)" : "") +
                   ". One at a time: the least and largest capacity along the option's line, and the x where they occur."});
    if (const std::string svg = svg_tornado(p, m); !svg.empty())
      d.figure("figures/tornado-" + std::string(method_name(m.method)) + ".svg", M + ": one-at-a-time ranges", svg);
    if (const std::string svg = svg_histogram(p, t, m); !svg.empty())
      d.figure("figures/histogram-" + std::string(method_name(m.method)) + ".svg", M + ": the sampled capacities", svg);
    if (!m.mechanisms.empty()) {
      d.paragraph({"Collapse mechanisms: the " + std::string(sens.sampled ? "samples" : "runs") +
                   " grouped by their hinges at collapse (PRD: the corners its collapse mechanism opens, a hinge named by the corner it turns "
                   "about; DEM: the hinges of its last equilibrium beyond its settled gaps, or where it has none, of the state its failed hold was "
                   "called a collapse in), then by the members those hinges lie in (block ids "
                   "without their voussoir or course number), which geometry that moves a hinge by a voussoir keeps."});
      // Hinge sets that group nothing (each its own, as on the cathedral, whose courses and
      // voussoirs renumber with the geometry) are left to sweep.csv's `hinges` column.
      if (2 * m.mechanisms.size() <= size_t(m.located) || m.mechanisms.size() <= 12)
        d.table(mechanism_table(m.mechanisms, "hinges at collapse", path_unit(p.base), sens.sampled, m.located));
      else
        d.paragraph({std::to_string(m.mechanisms.size()) + " different sets of hinges over " + std::to_string(m.located) + " rows (each row's in ",
                     Cell("sweep.csv", CellStyle::code), "'s column ", Cell("hinges", CellStyle::code), "): grouped by members only."});
      if (m.members.size() < m.mechanisms.size())
        d.table(mechanism_table(m.members, "members with hinges", path_unit(p.base), sens.sampled, m.located));
      if (m.members.size() > 1) {
        d.paragraph({"Each member (or pair of members joined by a hinge) alone: the share of the " + std::string(sens.sampled ? "samples" : "runs") +
                     " whose hinges at collapse include it, and their median capacity."});
        d.table(mechanism_table(m.member_frequency, "member with a hinge", path_unit(p.base), sens.sampled, m.located, m.member_frequency.size()));
      }
    }
  }
  if (const std::string svg = svg_prd_dem(p, sens); !svg.empty()) {
    d.heading(3, {"PRD against DEM"});
    d.figure("figures/prd-dem.svg", "DEM against PRD per point", svg);
    Table pd;
    pd.head = {"sample", "run (DEM)", "PRD (" + path_unit(p.base) + ")", "DEM (" + path_unit(p.base) + ")", "difference"};
    for (const PrdDemPair& x : sens.pairs)
      pd.rows.push_back({x.sample >= 0 ? std::to_string(x.sample) : "-", std::to_string(x.dem), fmt::g(x.prd_capacity, 4), fmt::g(x.dem_capacity, 4),
                         x.prd_capacity > 0 ? pct((x.dem_capacity - x.prd_capacity) / x.prd_capacity) : "-"});
    d.table(pd);
  }
}

// The report for both media: the Markdown links figures/capacity.svg, the page inlines it.
Document sweep_document(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command) {
  const Content c = content(p, t, s);
  Document d;
  d.title = c.title;
  if (!p.description.empty()) d.paragraph({p.description});
  if (!command.empty())
    d.paragraph({"Made with ", Cell(command, CellStyle::code), "; the table is ", Cell("sweep.csv", CellStyle::code), ", the numbers also in ",
                 Cell("sweep.json", CellStyle::code), "."});
  d.paragraph({c.lead});
  if (const std::string note = prd_ignores_note(p); !note.empty()) d.paragraph({Cell(note, CellStyle::strong)});
  if (c.has_figure) {
    d.heading(2, {"Capacity against the " + x_title(s)});
    d.figure("figures/capacity.svg", "capacity against " + s.x, svg_sweep(p, t, s));
  }
  if (!c.boundaries.head.empty()) {
    d.heading(2, {"Where DEM and PRD part"});
    std::vector<Item> items;
    for (const std::string& f : c.findings) items.push_back({{f}, {}});
    if (!items.empty()) d.list(std::move(items));
    d.table(c.boundaries);
  }
  sensitivity_section(d, p, t, sensitivity(p, t));
  d.heading(2, {"Runs"});
  d.table(c.runs);
  return d;
}

}  // namespace

std::string sweep_markdown(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command) {
  return markdown(sweep_document(p, t, s, command));
}

std::string sweep_html(const SweepPlan& p, const SweepTable& t, const SweepSummary& s, const std::string& command) {
  const Document d = sweep_document(p, t, s, command);
  HtmlPage page;  // no script: a figure and tables
  page.title = d.title;
  page.body = html_body(d);
  return html_page(page);
}

void write_sweep_outputs(const std::string& dir, const SweepPlan& p, const SweepTable& t, const std::string& command) {
  std::error_code ec;
  std::filesystem::create_directories(dir + "/figures", ec);
  if (ec) throw SweepError(dir + ": cannot create the report directory: " + ec.message());
  const SweepSummary s = summarize(p, t);
  write_file_atomic(dir + "/sweep.csv", sweep_csv(p, t));
  write_file_atomic(dir + "/sweep.json", sweep_json(p, t, s).dump(1) + "\n");
  const SweepSensitivity sens = sensitivity(p, t);
  write_file_atomic(dir + "/sensitivity.json", sensitivity_json(p, sens).dump(1) + "\n");
  if (!s.x.empty() && !s.curves.empty()) write_file_atomic(dir + "/figures/capacity.svg", svg_sweep(p, t, s));
  for (const MethodSensitivity& m : sens.methods) {
    if (const std::string svg = svg_tornado(p, m); !svg.empty()) write_file_atomic(dir + "/figures/tornado-" + method_name(m.method) + ".svg", svg);
    if (const std::string svg = svg_histogram(p, t, m); !svg.empty())
      write_file_atomic(dir + "/figures/histogram-" + method_name(m.method) + ".svg", svg);
  }
  if (const std::string svg = svg_prd_dem(p, sens); !svg.empty()) write_file_atomic(dir + "/figures/prd-dem.svg", svg);
  write_file_atomic(dir + "/report.md", sweep_markdown(p, t, s, command));
  write_file_atomic(dir + "/report.html", sweep_html(p, t, s, command));
}

}  // namespace masonry
