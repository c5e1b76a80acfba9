// Reports of a trade-off measurement: tradeoff.csv, tradeoff.json, report.md, report.html and
// the Pareto figures. Reads Rows only: nothing here runs a solver.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "model/version.hpp"
#include "report/document.hpp"
#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/svg.hpp"
#include "tradeoff/tradeoff.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ojson to_ordered(const nlohmann::json& v) { return ojson::parse(v.dump()); }

std::string value_text(const nlohmann::json& v) {
  if (v.is_number()) return fmt::number(v.get<double>(), "%.12g", v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}
std::string options_text(const std::vector<CaseOption>& o) {
  std::string s;
  for (const CaseOption& x : o) s += (s.empty() ? "" : ", ") + x.key + "=" + value_text(x.value);
  return s;
}

using fmt::px;
using fmt::secs;

// Errors (spanning decades, so in significant digits): an exact zero (a setting that gives the reference's result) reads "0".
std::string pct(double x) {
  if (x == 0) return "0%";
  return fmt::number(x, std::abs(x) < 1e-4 ? "%.1e%%" : "%.3g%%", x * 100);
}
std::string pct_signed(double x) {
  if (x == 0) return "0%";
  return fmt::number(x, std::abs(x) < 1e-4 ? "%+.1e%%" : "%+.3g%%", x * 100);
}
std::string weight(double x) {
  if (x == 0) return "0 W";
  return fmt::number(x, std::abs(x) < 1e-3 ? "%.1e W" : "%.4f W", x);
}
// d x 1000, in mm or mrad (Tradeoff::d_unit).
std::string mm(double m) { return fmt::mm(m, 1); }

std::string role(const Row& r) { return r.reference ? "reference" : r.baseline ? "baseline" : r.parameter == "combined" ? "combined" : "vary"; }

// A point's error as the reader sees it.
std::string err_text(ErrorKind k, double e) { return k == ErrorKind::capacity ? pct(e) : weight(e); }
const char* kind_name(ErrorKind k) { return k == ErrorKind::capacity ? "capacity error" : "thrust error"; }

std::vector<size_t> rows_of(const Tradeoff& t, Method method) {
  std::vector<size_t> out;
  for (size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i].method == method) out.push_back(i);
  return out;
}

std::vector<Row> method_rows(const Tradeoff& t, Method method) {
  std::vector<Row> out;
  for (size_t i : rows_of(t, method)) out.push_back(t.rows[i]);
  return out;
}

// The front and the buys of one method and error measure, as indices into method_rows().
struct Front {
  std::vector<ParetoPoint> points;
  std::vector<size_t> front;
  std::vector<Buy> buys;
};
Front front_of(const std::vector<Row>& rows, ErrorKind k) {
  Front f;
  f.points = points_of(rows, k);
  f.front = pareto_front(f.points);
  f.buys = best_buys(f.points, f.front);
  return f;
}

// Colours per parameter, in order of first appearance; black and grey mark the reference and baseline.
std::map<std::string, std::string> parameter_colors(const std::vector<Row>& rows) {
  std::map<std::string, std::string> c;
  int n = 0;
  c["reference"] = "#000000";
  c["baseline"] = "#9e9e9e";
  for (const Row& r : rows)
    if (!c.count(r.parameter)) c[r.parameter] = series_color(n++);
  return c;
}

Table method_table(const Tradeoff& t, Method method) {
  const std::vector<Row> rows = method_rows(t, method);
  const Front fc = front_of(rows, ErrorKind::capacity), ft = front_of(rows, ErrorKind::thrust);
  const auto on = [](const Front& f, size_t i) { return std::find(f.front.begin(), f.front.end(), i) != f.front.end(); };
  Table tb;
  const std::string unit = std::string(1, 'm').append(t.d_unit);  // d x 1000: mm, or mrad for a turning support
  tb.head = {"setting",
             "options",
             "stopped",
             "capacity (" + unit + ")",
             "capacity error",
             "thrust error max / rms (W)",
             "over d (" + unit + ")",
             "time (s)",
             "wall (s)",
             method == Method::prd ? "LP solves" : "cycles",
             "Pareto"};
  // Names, options and status left; numbers right, even where a cell adds a unit or a range.
  tb.align.assign(tb.head.size(), Align::right);
  for (int k = 0; k < 3; ++k) tb.align[k] = Align::left;
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::string setting = r.label;
    if (r.reused) setting += r.given ? " (read back)" : " (reused)";
    std::string opts = r.given ? r.source : options_text(r.options);
    if (opts.empty()) opts = "(the case's own)";
    std::string stopped = status_name(r.status) + std::string(r.message.empty() ? "" : ": " + r.message);
    std::string time = secs(r.time_s) + (r.cpu ? "" : " (wall)");
    if (r.repeats > 1) time += " (" + secs(r.time_min_s) + "-" + secs(r.time_max_s) + ", " + std::to_string(r.repeats) + " runs)";
    std::string front;
    if (on(fc, i)) front += "capacity";
    if (on(ft, i)) front += std::string(front.empty() ? "" : ", ") + "thrust";
    tb.rows.push_back({setting, opts, stopped, mm(r.capacity), pct_signed(r.capacity_err),
                       std::isfinite(r.thrust_max_err) ? weight(r.thrust_max_err) + " / " + weight(r.thrust_rms_err) : "n/a", mm(r.thrust_range),
                       time, secs(r.wall_s), std::to_string(method == Method::prd ? r.lp_solves : r.cycles), front.empty() ? "-" : front});
  }
  return tb;
}

std::string reference_text(const Tradeoff& t, Method method) {
  for (const Row& r : t.rows)
    if (r.method == method && r.reference) {
      if (r.given) return "the finished run in " + r.source;
      return r.options.empty() ? "the case's own settings" : options_text(r.options);
    }
  return "none";
}

}  // namespace

std::string csv_header() {
  return "method,setting,parameter,role,options,stopped,capacity_m,capacity_err,thrust_max_err_W,thrust_rms_err_W,thrust_range_m,time_s,time_min_s,"
         "time_max_s,time_kind,wall_s,repeats,lp_solves,cycles,reused,source,message\n";
}

std::string csv_row(const Row& r) {
  // Quoted fields for text that may hold commas; doubled quotes inside; one line always.
  const auto q = [](std::string s) {
    for (char& ch : s)
      if (ch == '\n' || ch == '\r') ch = ' ';
    std::string o = "\"";
    for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return o + "\"";
  };
  const auto g = [](double x) { return fmt::number(x, "%.10g", x); };
  std::string opts;
  for (const CaseOption& o : r.options) opts += (opts.empty() ? "" : ";") + o.key + "=" + value_text(o.value);
  std::ostringstream o;
  o << method_name(r.method) << "," << q(r.label) << "," << q(r.parameter) << "," << role(r) << "," << q(opts) << "," << status_name(r.status) << ","
    << g(r.capacity) << "," << g(r.capacity_err) << "," << g(r.thrust_max_err) << "," << g(r.thrust_rms_err) << "," << g(r.thrust_range) << ","
    << g(r.time_s) << "," << g(r.time_min_s) << "," << g(r.time_max_s) << "," << (r.cpu ? "cpu" : "wall") << "," << g(r.wall_s) << "," << r.repeats
    << "," << r.lp_solves << "," << r.cycles << "," << (r.reused ? "yes" : "no") << "," << q(r.source) << "," << q(r.message) << "\n";
  return o.str();
}

std::vector<std::string> summary_lines(const Tradeoff& t) {
  std::vector<std::string> out;
  for (const Method method : t.methods) {
    const std::vector<Row> rows = method_rows(t, method);
    if (rows.empty()) continue;
    const std::string M = method_label(method);
    double ref_time = kNaN;
    for (const Row& r : rows)
      if (r.reference) ref_time = r.time_s;
    for (ErrorKind k : {ErrorKind::capacity, ErrorKind::thrust}) {
      const Front f = front_of(rows, k);
      if (f.front.empty()) {
        out.push_back(M + ", " + kind_name(k) + ": no finished run to compare.");
        continue;
      }
      std::string s = M + ", " + kind_name(k) + ": the Pareto front, fastest first, is ";
      for (size_t n = 0; n < f.front.size(); ++n) {
        const size_t i = f.front[n];
        s += (n ? (n + 1 == f.front.size() ? " and " : ", ") : "") + rows[i].label + " (" + secs(f.points[i].time) + " s, " +
             err_text(k, f.points[i].error) + ")";
      }
      s += ".";
      if (f.buys.empty()) {
        s += " One setting is both fastest and most accurate: nothing to buy.";
      } else {
        s += " Most accuracy per second: ";
        for (size_t n = 0; n < f.buys.size() && n < 3; ++n) {
          const Buy& b = f.buys[n];
          s += std::string(n ? "; then " : "") + "from " + rows[b.from].label + " to " + rows[b.to].label + " the error falls from " +
               err_text(k, f.points[b.from].error) + " to " + err_text(k, f.points[b.to].error) + " for " + fmt::duration(b.cost_s) + " more";
        }
        s += ".";
      }
      out.push_back(s);
    }
    // The fastest finished setting within both targets.
    const Row* best = nullptr;
    for (const Row& r : rows)
      if (r.ok() && std::isfinite(r.time_s) && std::abs(r.capacity_err) <= t.target_capacity && r.thrust_max_err <= t.target_thrust &&
          (!best || r.time_s < best->time_s))
        best = &r;
    const std::string target = pct(t.target_capacity) + " in capacity and " + weight(t.target_thrust) + " in thrust";
    if (best) {
      std::string s = M + ": the fastest setting within " + target + " of the reference is " + best->label + " (" + secs(best->time_s) + " s";
      if (!best->reference && std::isfinite(ref_time) && best->time_s > 0)
        s += ", " + fmt::number(ref_time / best->time_s, "%.3g", ref_time / best->time_s) + " times faster than the reference's " + secs(ref_time) +
             " s";
      out.push_back(s + ").");
    } else {
      out.push_back(M + ": no setting is within " + target + " of the reference.");
    }
    int failed = 0;
    for (const Row& r : rows) failed += r.ok() ? 0 : 1;
    if (failed) out.push_back(M + ": " + std::to_string(failed) + " setting" + (failed == 1 ? "" : "s") + " did not finish (see the table).");
  }
  return out;
}

ojson tradeoff_json(const Tradeoff& t) {
  ojson j;
  j["format"] = "masonry-tradeoff/1";
  j["version"] = version_text();
  j["case"] = t.case_name;
  j["d_unit"] = t.d_unit;
  j["command"] = t.command;
  j["base"] = ojson::object();
  for (const CaseOption& o : t.base) j["base"][o.key] = to_ordered(o.value);
  j["methods"] = ojson::array();
  for (Method m : t.methods) j["methods"].push_back(method_name(m));
  j["plan"] = plan_to_json(t.plan);
  j["targets"] = {{"capacity", json_number(t.target_capacity)}, {"thrust", json_number(t.target_thrust)}};
  j["rows"] = ojson::array();
  for (const Row& r : t.rows) {
    ojson x;
    x["method"] = method_name(r.method);
    x["setting"] = r.label;
    x["parameter"] = r.parameter;
    x["role"] = role(r);
    x["id"] = r.id;
    x["options"] = ojson::object();
    for (const CaseOption& o : r.options) x["options"][o.key] = to_ordered(o.value);
    x["stopped"] = status_name(r.status);
    if (!r.message.empty()) x["message"] = r.message;
    x["capacity"] = json_number(r.capacity);
    x["capacity_err"] = json_number(r.capacity_err);
    x["thrust_max_err"] = json_number(r.thrust_max_err);
    x["thrust_rms_err"] = json_number(r.thrust_rms_err);
    x["thrust_range"] = json_number(r.thrust_range);
    x["time_s"] = json_number(r.time_s);
    x["time_min_s"] = json_number(r.time_min_s);
    x["time_max_s"] = json_number(r.time_max_s);
    x["time_kind"] = r.cpu ? "cpu" : "wall";
    x["wall_s"] = json_number(r.wall_s);
    x["repeats"] = r.repeats;
    x["lp_solves"] = r.lp_solves;
    x["cycles"] = r.cycles;
    x["records"] = r.steps;
    x["reused"] = r.reused;
    x["source"] = r.source;
    j["rows"].push_back(x);
  }
  j["pareto"] = ojson::object();
  for (const Method method : t.methods) {
    const std::vector<Row> rows = method_rows(t, method);
    ojson m;
    for (ErrorKind k : {ErrorKind::capacity, ErrorKind::thrust}) {
      const Front f = front_of(rows, k);
      ojson e;
      e["front"] = ojson::array();
      for (size_t i : f.front) e["front"].push_back(rows[i].label);
      e["best_buys"] = ojson::array();
      for (const Buy& b : f.buys)
        e["best_buys"].push_back({{"from", rows[b.from].label},
                                  {"to", rows[b.to].label},
                                  {"error_reduction", json_number(b.gain)},
                                  {"extra_s", json_number(b.cost_s)},
                                  {"per_s", json_number(b.rate)}});
      m[k == ErrorKind::capacity ? "capacity" : "thrust"] = e;
    }
    j["pareto"][method_name(method)] = m;
  }
  j["summary"] = summary_lines(t);
  return j;
}

std::string svg_pareto(const Tradeoff& t, Method method) {
  const std::vector<Row> rows = method_rows(t, method);
  const auto colors = parameter_colors(rows);
  const double left = 70, pw = 360, ph = 280, gap = 120, top = 62, zero_band = 26;
  const double W = left + 2 * pw + gap + 30;
  // Legend: one entry per parameter, below the panels.
  std::vector<std::string> params;
  for (const Row& r : rows)
    if (std::find(params.begin(), params.end(), r.parameter) == params.end()) params.push_back(r.parameter);
  const int per_line = 3;
  const double legend_top = top + ph + zero_band + 50;
  const double H = legend_top + 20 * ((params.size() + per_line - 1) / per_line) + 20;
  // Time axis, shared by both panels: whole decades around the finished runs.
  double tlo = std::numeric_limits<double>::infinity(), thi = -tlo;
  for (const Row& r : rows)
    if (r.ok() && std::isfinite(r.time_s) && r.time_s > 0) tlo = std::min(tlo, r.time_s), thi = std::max(thi, r.time_s);
  if (!(tlo <= thi)) tlo = thi = 1;
  double d0 = std::floor(std::log10(tlo)), d1 = std::ceil(std::log10(thi));
  if (d1 <= d0) d1 = d0 + 1;
  std::ostringstream o;
  o << svg_open(W, H);
  o << "<text x=\"" << px(left) << "\" y=\"20\" font-size=\"15\" font-weight=\"bold\">" << xml_escape(method_label(method)) << " settings on "
    << xml_escape(t.case_name) << ": run time against error (reference: error 0)</text>\n";
  for (int panel = 0; panel < 2; ++panel) {
    const ErrorKind k = panel == 0 ? ErrorKind::capacity : ErrorKind::thrust;
    const Front f = front_of(rows, k);
    const double ox = left + panel * (pw + gap);
    // Error axis: log scale over the positive errors (capacity in %), zeros on a band below.
    const double scale = k == ErrorKind::capacity ? 100.0 : 1.0;
    double elo = std::numeric_limits<double>::infinity(), ehi = -elo;
    for (const ParetoPoint& p : f.points)
      if (std::isfinite(p.error) && p.error > 0) elo = std::min(elo, p.error * scale), ehi = std::max(ehi, p.error * scale);
    const bool any_pos = elo <= ehi;
    double e0 = any_pos ? std::floor(std::log10(elo)) : -3, e1 = any_pos ? std::ceil(std::log10(ehi)) : 0;
    if (e1 <= e0) e1 = e0 + 1;
    // Five decades at most: smaller errors (round-off against the reference) sit on the bottom
    // line of the scale, their values in the tooltips and the table.
    e0 = std::max(e0, e1 - 5);
    const Plot plot{ox, top, pw, ph, d0, d1, e0, e1, true, true, zero_band};
    const auto X = [&](double s) { return plot.X(s); };
    const auto Y = [&](double e) { return plot.Y(e * scale); };
    o << "<text x=\"" << px(ox) << "\" y=\"" << px(top - 12) << "\" font-size=\"13\" font-weight=\"bold\">"
      << (k == ErrorKind::capacity ? "|capacity error| (%)" : "thrust error, largest (W = total weight)") << "</text>\n"
      << svg_axes(plot, decade_ticks(int(d0), int(d1)), decade_ticks(int(e0), int(e1)), "run time (s, log scale)", "");
    // The front: joined in order of time, each point ringed and named.
    std::string pts;
    for (size_t i : f.front) pts += px(X(f.points[i].time)) + "," + px(Y(f.points[i].error)) + " ";
    o << "<polyline fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.8\" points=\"" << pts << "\"/>\n";
    for (size_t i = 0; i < rows.size(); ++i) {
      const ParetoPoint& p = f.points[i];
      if (!std::isfinite(p.time) || !std::isfinite(p.error) || !(p.time > 0)) continue;
      const bool front = std::find(f.front.begin(), f.front.end(), i) != f.front.end();
      const double x = X(p.time), y = Y(p.error);
      o << "<g><title>" << xml_escape(rows[i].label) << ": " << secs(p.time) << " s, " << err_text(k, p.error) << "</title>";
      if (rows[i].reference)
        o << "<path d=\"M" << px(x) << "," << px(y - 7) << " L" << px(x + 6) << "," << px(y + 5) << " L" << px(x - 6) << "," << px(y + 5)
          << " z\" fill=\"#000\"/>";
      else
        o << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y) << "\" r=\"5\" fill=\"" << colors.at(rows[i].parameter) << "\" stroke=\"#fff\"/>";
      if (front) o << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y) << "\" r=\"9\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.6\"/>";
      o << "</g>\n";
      // Names of the front's points, turned to the left of the point near the right edge.
      if (front) {
        const double room = panel == 0 ? ox + pw + gap - 8 : ox + pw + 25;
        const bool flip = x + 11 + 5.6 * rows[i].label.size() > room;
        o << "<text x=\"" << px(flip ? x - 11 : x + 11) << "\" y=\"" << px(y - 8) << "\" font-size=\"10\" fill=\"#333\""
          << (flip ? " text-anchor=\"end\"" : "") << ">" << xml_escape(rows[i].label) << "</text>\n";
      }
    }
  }
  // Legend.
  o << "<g font-size=\"12\">\n";
  for (size_t n = 0; n < params.size(); ++n) {
    const double x = left + (n % per_line) * 260, y = legend_top + 20 * (n / per_line);
    if (params[n] == "reference")
      o << "<path d=\"M" << px(x + 6) << "," << px(y - 7) << " l6,12 h-12 z\" fill=\"#000\"/>";
    else
      o << "<circle cx=\"" << px(x + 6) << "\" cy=\"" << px(y - 1) << "\" r=\"5\" fill=\"" << colors.at(params[n]) << "\"/>";
    o << "<text x=\"" << px(x + 18) << "\" y=\"" << px(y + 3) << "\">" << xml_escape(params[n]) << "</text>\n";
  }
  const double y = legend_top + 20 * ((params.size() + per_line - 1) / per_line) + 8;
  o << "<circle cx=\"" << px(left + 6) << "\" cy=\"" << px(y - 1) << "\" r=\"8\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.6\"/>"
    << "<text x=\"" << px(left + 18) << "\" y=\"" << px(y + 3)
    << "\">Pareto-optimal (no other setting is both faster and more accurate), joined by the red line</text>\n";
  o << "</g>\n</svg>\n";
  return o.str();
}

namespace {

std::string intro_text(const Tradeoff& t) {
  std::string s = "Each setting changes the case's own settings (the baseline";
  if (!t.base.empty()) s += ", here with " + options_text(t.base);
  s += ") one option at a time, or a few together (combined). Errors are against each method's reference, its most accurate setting: ";
  std::string refs;
  for (Method m : t.methods) refs += (refs.empty() ? "" : "; ") + std::string(method_label(m)) + ": " + reference_text(t, m);
  return s + refs + ".";
}

const char* kDefinitions =
    "Capacity error: (capacity - reference capacity) / reference capacity, the capacity being the last stable d. "
    "Thrust error: the largest (and the rms) difference of any support reaction component, over the total weight W, "
    "between the run and the reference on their common range of d, [0, the smaller capacity] (compare/README.md), "
    "compared at the records of whichever of the two has fewer there, the other interpolated between its own records: "
    "so neither is read half way through a step it did not resolve, where the thrust can jump (an arch's settled thrust, one "
    "admissible state of a statically indeterminate structure, falls to the minimum thrust over the first step); "
    "n/a when that range is empty. "
    "Time: the CPU time of the solver call (thread CPU time, without file writing), the median when a setting was run several times; "
    "a busy machine does not inflate it as it does the wall time, but it still depends on the machine; the errors do not. "
    "Runs read back from a directory carry only their own wall time (timing.total_s, marked wall). "
    "A setting is Pareto-optimal when no other is both at least as fast and at least as accurate; "
    "along the front, each step to a slower setting buys an error reduction, and the steps are ranked by error reduction per extra second.";

}  // namespace

namespace {

// The report for both media: the Markdown links the Pareto figures, the page inlines them.
Document tradeoff_document(const Tradeoff& t) {
  Document d;
  d.title = "Speed against accuracy: " + t.case_name;
  if (!t.command.empty()) d.paragraph({"Made with: ", Cell(t.command, CellStyle::code)});
  d.paragraph({intro_text(t)});
  d.heading(2, {"Which settings buy most accuracy per second"});
  std::vector<Item> items;
  for (const std::string& s : summary_lines(t)) items.push_back({{s}, {}});
  d.list(std::move(items));
  for (Method m : t.methods) {
    if (rows_of(t, m).empty()) continue;
    d.heading(2, {method_label(m)});
    d.figure("figures/pareto-" + std::string(method_name(m)) + ".svg", method_label(m) + std::string(": run time against error"), svg_pareto(t, m));
    d.table(method_table(t, m));
  }
  d.heading(2, {"Definitions"});
  d.paragraph({kDefinitions});
  d.paragraph({"The numbers: ", Cell("tradeoff.json", CellStyle::code), ", ", Cell("tradeoff.csv", CellStyle::code), "."});
  return d;
}

}  // namespace

std::string tradeoff_markdown(const Tradeoff& t) { return markdown(tradeoff_document(t)); }

std::string tradeoff_html(const Tradeoff& t) {
  const Document d = tradeoff_document(t);
  // No script at all: the policy forbids every script and every fetch.
  HtmlPage page;
  page.title = t.case_name + ": speed against accuracy";
  page.body = html_body(d);
  page.max_width_px = 1100;
  return html_page(page);
}

void write_tradeoff(const std::string& dir, const Tradeoff& t) {
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(dir) / "figures");
  std::string csv = csv_header();
  for (const Row& r : t.rows) csv += csv_row(r);
  write_file_atomic((fs::path(dir) / "tradeoff.csv").string(), csv);
  write_file_atomic((fs::path(dir) / "tradeoff.json").string(), tradeoff_json(t).dump(1) + "\n");
  for (Method m : t.methods)
    if (!rows_of(t, m).empty())
      write_file_atomic((fs::path(dir) / "figures" / ("pareto-" + std::string(method_name(m)) + ".svg")).string(), svg_pareto(t, m));
  write_file_atomic((fs::path(dir) / "report.md").string(), tradeoff_markdown(t));
  write_file_atomic((fs::path(dir) / "report.html").string(), tradeoff_html(t));
}

}  // namespace masonry
