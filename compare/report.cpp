#include "compare/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

#include "compare/format.hpp"
#include "compare/svg.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;

namespace {

const char* kRunColors[] = {"#4a4a4a", "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00"};

std::string mm(double m, int decimals = 0) { return fmt::number(m, "%.*f", decimals, m * 1000); }
std::string pct(double x) { return fmt::number(x, "%+.1f%%", x * 100); }
std::string secs(double s) { return fmt::number(s, s < 10 ? "%.2f" : "%.0f", s); }
ojson num(double x) { return std::isfinite(x) ? ojson(x) : ojson(nullptr); }
// A ratio without an exponent: 0.5, 12.3, 2270.
std::string ratio(double x) { return fmt::number(x, x >= 100 ? "%.0f" : "%.3g", x); }

const StepRecord* record_at(const RunResult& r, double d) {
  const auto recs = stable_records(r);
  const StepRecord* best = recs.empty() ? nullptr : recs.front();
  for (const StepRecord* s : recs)
    if (s->d <= d + 1e-9 * std::max(1.0, std::abs(d))) best = s;
  return best;
}

Panel panel(const ReportRun& rr, const StepRecord* s, double d) {
  Panel p{rr.run, s, rr.label, "no record"};
  if (!s) return p;
  p.subtitle = "d = " + mm(s->d, 0) + " mm";
  if (d > rr.run->capacity + 1e-9 && rr.run->collapsed) p.subtitle += " (collapsed after " + mm(rr.run->capacity) + " mm)";
  return p;
}

std::string hinge_list(const std::vector<Hinge>& hs) {
  std::string o;
  for (const Hinge& h : hs) o += (o.empty() ? "" : ", ") + h.label;
  return o.empty() ? "none" : o;
}

std::string changes_mm(const RunSummary& s) {
  std::string o;
  for (double d : s.changes) o += (o.empty() ? "" : ", ") + mm(d);
  return o.empty() ? "none" : o;
}

// The d values of the structure figures of comparison k: early, half way, the end of the
// common range; then each method at its own capacity.
std::vector<double> figure_ds(const Comparison& k) {
  std::vector<double> ds;
  const double step = std::max(k.a.step, k.b.step);
  if (k.d_max > 0) {
    ds.push_back(std::min(k.d_max, std::max(step, 0.02 * k.d_max)));
    ds.push_back(0.5 * k.d_max);
    ds.push_back(k.d_max);
  } else {
    ds.push_back(0.0);
  }
  return ds;
}

}  // namespace

std::string md_escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\n': case '\r': o += ' '; break;
      case '\\': case '`': case '*': case '_': case '[': case ']': case '(': case ')': case '#': case '|': case '!':
      case '~':
        o += '\\';
        o += ch;
        break;
      default: o += ch;
    }
  }
  return o;
}

Report make_report(const Case& c, const std::vector<ReportRun>& runs, const Tolerances* t, const CompareOptions& o) {
  Report r;
  r.c = &c;
  r.runs = runs;
  r.tolerances_checked = t != nullptr;
  if (t) r.tolerances = *t;
  for (size_t k = 1; k < runs.size(); ++k) {
    r.comparisons.push_back(compare_runs(c, *runs[0].run, *runs[k].run, o, runs[0].label, runs[k].label));
    r.violations.push_back(t ? check_tolerances(r.comparisons.back(), *t) : std::vector<std::string>{});
  }
  return r;
}

std::vector<Figure> report_figures(const Report& r) {
  std::vector<Figure> figs;
  std::vector<Bar> bars;
  for (size_t k = 0; k < r.runs.size(); ++k) bars.push_back({r.runs[k].label, r.runs[k].run->capacity, kRunColors[k % 6]});
  figs.push_back({"figures/capacity.svg", svg_capacity(bars), "Displacement capacity of each run"});
  std::vector<const RunResult*> all;
  for (const ReportRun& rr : r.runs) all.push_back(rr.run);
  const DrawFrame frame = draw_frame(*r.c, all);
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    const Comparison& cmp = r.comparisons[k];
    const ReportRun& A = r.runs[0];
    const ReportRun& B = r.runs[k + 1];
    const std::string n = std::to_string(k + 1);
    figs.push_back({"figures/thrust-" + n + ".svg", svg_thrust(cmp, *A.run, *B.run),
                    "Thrust curves: " + A.label + " (solid) and " + B.label + " (dashed)"});
    int j = 0;
    for (double d : figure_ds(cmp)) {
      const StepRecord* sa = record_at(*A.run, d);
      const StepRecord* sb = record_at(*B.run, d);
      figs.push_back({"figures/structure-" + n + "-" + std::to_string(++j) + ".svg",
                      svg_structure(*r.c, {panel(A, sa, d), panel(B, sb, d)}, frame),
                      "d = " + mm(d) + " mm"});
    }
    if (std::abs(cmp.a.capacity - cmp.b.capacity) > 1e-12) {
      const StepRecord* sa = record_at(*A.run, cmp.a.capacity);
      const StepRecord* sb = record_at(*B.run, cmp.b.capacity);
      figs.push_back({"figures/structure-" + n + "-" + std::to_string(++j) + ".svg",
                      svg_structure(*r.c, {{A.run, sa, A.label, "at its capacity, d = " + mm(cmp.a.capacity) + " mm"},
                                           {B.run, sb, B.label, "at its capacity, d = " + mm(cmp.b.capacity) + " mm"}},
                                    frame),
                      "each method at its own capacity"});
    }
  }
  return figs;
}

ojson report_json(const Report& r) {
  ojson j;
  j["format"] = "masonry-comparison/1";
  j["units"] = "SI: m, N, s; thrust as reaction / total weight";
  j["case"] = r.c->name;
  ojson runs = ojson::array();
  for (const ReportRun& rr : r.runs)
    runs.push_back({{"label", rr.label},
                    {"method", rr.run->method},
                    {"dir", rr.dir},
                    {"capacity", num(rr.run->capacity)},
                    {"collapsed", rr.run->collapsed},
                    {"stopped", status_name(rr.run->status)},
                    {"time_s", num(rr.run->timing.total_s)},
                    {"settings", rr.run->settings}});
  j["runs"] = runs;
  ojson cs = ojson::array();
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    ojson c = to_json(r.comparisons[k]);
    if (r.tolerances_checked) {
      ojson lim;
      lim["capacity"] = r.tolerances.capacity ? num(*r.tolerances.capacity) : ojson(nullptr);
      lim["thrust"] = r.tolerances.thrust ? num(*r.tolerances.thrust) : ojson(nullptr);
      lim["hinges"] = r.tolerances.hinges;
      c["tolerances"] = {{"limits", lim}, {"pass", r.violations[k].empty()}, {"violations", r.violations[k]}};
    }
    cs.push_back(c);
  }
  j["comparisons"] = cs;
  return j;
}

std::string report_markdown(const Report& r, const std::vector<Figure>& figures) {
  const Case& c = *r.c;
  std::ostringstream o;
  std::string labels;
  for (size_t k = 0; k < r.runs.size(); ++k) labels += (k ? (k + 1 == r.runs.size() ? " and " : ", ") : "") + r.runs[k].label;
  o << "# " << md_escape(c.name) << ": " << md_escape(labels) << "\n\n";
  if (!c.description.empty()) o << md_escape(c.description) << "\n\n";
  std::string cmd = r.command;  // a code span cannot escape a backtick
  std::replace(cmd.begin(), cmd.end(), '`', '\'');
  if (!cmd.empty()) o << "Made with `" << cmd << "`" << " (`report.html` has the same figures and a slider over d).\n\n";
  // Headline table.
  o << "| | ";
  for (const ReportRun& rr : r.runs) o << md_escape(rr.label) << " | ";
  o << "\n|---|";
  for (size_t k = 0; k < r.runs.size(); ++k) o << "---:|";
  o << "\n| capacity (mm) | ";
  for (const ReportRun& rr : r.runs) o << mm(rr.run->capacity) << (rr.run->collapsed ? "" : " (no collapse)") << " | ";
  o << "\n| relative to " << md_escape(r.runs[0].label) << " | - | ";
  for (const Comparison& k : r.comparisons) o << pct(k.capacity_rel_diff) << " | ";
  o << "\n| largest thrust difference (W) | - | ";
  for (const Comparison& k : r.comparisons) o << fmt::g(k.thrust_max_diff) << " | ";
  o << "\n| rms thrust difference (W) | - | ";
  for (const Comparison& k : r.comparisons) o << fmt::g(k.thrust_rms_diff) << " | ";
  o << "\n| hinges match (of checks) | - | ";
  for (const Comparison& k : r.comparisons) {
    int ok = 0;
    for (const HingeCheck& h : k.hinges) ok += h.ok();
    o << ok << " / " << k.hinges.size() << " | ";
  }
  o << "\n| step (mm) | ";
  for (const ReportRun& rr : r.runs) {
    const auto recs = stable_records(*rr.run);
    o << (recs.size() >= 2 ? mm(recs[1]->d - recs[0]->d, 1) : "n/a") << " | ";
  }
  o << "\n| run time (s) | ";
  for (const ReportRun& rr : r.runs) o << secs(rr.run->timing.total_s) << " | ";
  o << "\n| run time / " << md_escape(r.runs[0].label) << " | 1 | ";
  for (const Comparison& k : r.comparisons) o << ratio(k.time_ratio) << " | ";
  o << "\n\n";
  if (r.tolerances_checked) {
    o << "## Tolerance checks\n\nLimits: capacity "
      << (r.tolerances.capacity ? fmt::g(*r.tolerances.capacity * 100) + "%" : std::string("not checked")) << ", thrust "
      << (r.tolerances.thrust ? fmt::g(*r.tolerances.thrust) + " W" : std::string("not checked")) << ", hinges "
      << (r.tolerances.hinges ? "must match" : "not checked") << ".\n\n";
    for (size_t k = 0; k < r.comparisons.size(); ++k) {
      o << "- " << md_escape(r.comparisons[k].a.label) << " against " << md_escape(r.comparisons[k].b.label) << ": "
        << (r.violations[k].empty() ? "**PASS**" : "**FAIL**") << "\n";
      for (const std::string& v : r.violations[k]) o << "  - " << md_escape(v) << "\n";
    }
    o << "\n";
  }
  const auto fig = [&](const std::string& file) {
    for (const Figure& f : figures)
      if (f.file == file) o << "![" << md_escape(f.caption) << "](" << f.file << ")\n\n";
  };
  o << "## Capacities\n\n";
  fig("figures/capacity.svg");
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    const Comparison& cmp = r.comparisons[k];
    const std::string n = std::to_string(k + 1);
    o << "## " << md_escape(cmp.a.label) << " against " << md_escape(cmp.b.label) << "\n\n";
    o << "### Thrust curves\n\nHorizontal (H) and vertical (V) reaction of every support over the total weight W = "
      << fmt::kn(cmp.total_weight) << " kN, against d. Compared on the common range d = 0 to " << mm(cmp.d_max)
      << " mm (" << cmp.d.size() << " points, every record of either run, linear interpolation between records): largest difference "
      << fmt::g(cmp.thrust_max_diff) << " W (" << md_escape(cmp.thrust_max_where) << " at d = " << mm(cmp.thrust_max_d) << " mm), root-mean-square "
      << fmt::g(cmp.thrust_rms_diff) << " W.";
    if (cmp.thrust_max_d == 0.0 && cmp.d_max > 0)
      o << " At d = 0 the structure is statically indeterminate: PRD reports one admissible force state among many, the DEM "
           "the one its settling under gravity finds, so a difference there is expected (the paper, Section 4: PRD gives \"just one of the infinite admissible stress states\" where the structure is statically indeterminate).";
    o << "\n\n";
    o << "| support | largest difference (W) | H at d = " << mm(cmp.d_max) << " mm, " << md_escape(cmp.a.label) << " / "
      << md_escape(cmp.b.label) << " | V at d = " << mm(cmp.d_max) << " mm |\n|---|---:|---:|---:|\n";
    for (const SupportCurve& s : cmp.supports) {
      const bool e = !s.h_a.empty();
      o << "| " << md_escape(s.support) << " | " << fmt::g(s.max_diff) << " | " << (e ? fmt::g(s.h_a.back()) + " / " + fmt::g(s.h_b.back()) : "n/a")
        << " | " << (e ? fmt::g(s.v_a.back()) + " / " + fmt::g(s.v_b.back()) : "n/a") << " |\n";
    }
    o << "\n";
    fig("figures/thrust-" + n + ".svg");
    o << "### Mechanism changes\n\nd (mm) where the set of open joint corners changes (a state held for a single record is "
         "taken as flicker and not counted):\n\n";
    o << "- " << md_escape(cmp.a.label) << ": " << changes_mm(cmp.a) << "\n- " << md_escape(cmp.b.label) << ": " << changes_mm(cmp.b)
      << "\n\n";
    o << "### Hinges\n\nA hinge is a joint with exactly one open corner; listed as `block/block:corner` (the joint's two blocks and the corner, A or B, it turns about). "
      << (cmp.symmetric ? "The scene is symmetric, so a mirror image counts as a match." : "The scene is not symmetric.") << "\n\n";
    // The crack pattern each run starts from: the DEM's elastic settling under gravity opens
    // small gaps (tens of microns on tall piers) that are not hinges of the mechanism; its
    // later open corners are measured from these gaps (dem/README.md, "Hinges").
    o << "Joints open at d = 0, before any support motion (the settled crack pattern; a DEM's later hinges are measured from "
         "its gaps there):\n\n";
    for (const ReportRun& rr : r.runs) {
      std::string list;
      if (rr.run && !rr.run->steps.empty())
        for (int j : rr.run->steps.front().cracked) {
          if (j < 0 || j >= static_cast<int>(rr.run->joints.size())) continue;
          const JointInfo& J = rr.run->joints[j];
          list += (list.empty() ? "" : ", ") + c.blocks[J.i].id + "/" + c.blocks[J.j].id;
        }
      o << "- " << md_escape(rr.label) << ": " << (list.empty() ? std::string("none") : md_escape(list)) << "\n";
    }
    o << "\n";
    o << "| d (mm) | " << md_escape(cmp.a.label) << " | " << md_escape(cmp.b.label) << " | agree |\n|---:|---|---|---|\n";
    for (const HingeCheck& h : cmp.hinges)
      o << "| " << mm(h.d) << " | " << md_escape(hinge_list(h.a)) << " | " << md_escape(hinge_list(h.b)) << " | "
        << (h.match ? "yes" : h.mirror ? "mirror image" : "**no**") << " |\n";
    o << "\n### The structure at chosen steps\n\nBlocks on the deformed geometry (supports hatched), cracked joints bold, "
         "hinges as red rings, joint resultants in blue through their pressure points, the thrust line in red, support "
         "reactions in green (force on the structure, labelled in units of W).\n\n";
    for (const Figure& f : figures)
      if (f.file.rfind("figures/structure-" + n + "-", 0) == 0) {
        o << "**" << md_escape(f.caption) << "**\n\n";
        fig(f.file);
      }
  }
  o << "## Runs\n\n| run | results | stopped | settings |\n|---|---|---|---|\n";
  for (const ReportRun& rr : r.runs) {
    o << "| " << md_escape(rr.label) << " | ";
    if (rr.dir.empty())
      o << "-";
    else
      o << "[" << md_escape(rr.dir) << "](" << rr.dir << "/results.json)";
    std::string settings = rr.run->settings.dump();  // numbers and keys of ours: shown as code
    std::replace(settings.begin(), settings.end(), '`', '\'');
    std::replace(settings.begin(), settings.end(), '|', '/');
    o << " | " << status_name(rr.run->status) << " | `" << settings << "` |\n";
  }
  o << "\nNumbers: `comparison.json`.\n";
  return o.str();
}

std::string report_html(const Report& r, int frames) {
  const Case& c = *r.c;
  std::vector<const RunResult*> all;
  for (const ReportRun& rr : r.runs) all.push_back(rr.run);
  const DrawFrame frame = draw_frame(c, all);
  // Slider positions: the union of every run's stable record d, thinned evenly to `frames`.
  std::vector<double> ds;
  for (const RunResult* run : all)
    for (const StepRecord* s : stable_records(*run)) ds.push_back(s->d);
  std::sort(ds.begin(), ds.end());
  ds.erase(std::unique(ds.begin(), ds.end(), [](double x, double y) { return std::abs(x - y) < 1e-12; }), ds.end());
  if (frames <= 0) frames = c.blocks.size() > 60 ? 24 : 60;  // keeps a large scene's file to a few MB
  std::vector<double> fd;
  if (int(ds.size()) <= frames) {
    fd = ds;
  } else {
    for (int i = 0; i < frames; ++i) fd.push_back(ds[size_t(std::llround(double(i) * (ds.size() - 1) / (frames - 1)))]);
  }
  // A fresh nonce per report: only our own two scripts run, whatever text a case carries.
  std::random_device rd;
  char nonce[40];
  std::snprintf(nonce, sizeof nonce, "%08x%08x%08x", rd(), rd(), rd());
  const double pw = r.runs.size() <= 2 ? 470 : 940.0 / r.runs.size();
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; script-src 'nonce-" << nonce
    << "'\">\n<title>" << xml_escape(c.name) << ": comparison</title>\n"
    << "<script nonce=\"" << nonce << "\">\n"
    << "// Every error, console error and blocked script lands in #errors, so a headless browser's DOM dump shows them.\n"
       "(function(){\n"
       "  function rec(m){var e=document.getElementById('errors');if(e){e.textContent+=m+'\\n';e.hidden=false;}else{window.__early=(window.__early||'')+m+'\\n';}}\n"
       "  window.__rec=rec;\n"
       "  window.addEventListener('error',function(e){rec('error: '+(e.message||e.type));},true);\n"
       "  window.addEventListener('unhandledrejection',function(e){rec('unhandled rejection: '+e.reason);});\n"
       "  document.addEventListener('securitypolicyviolation',function(e){rec('blocked: '+e.violatedDirective);});\n"
       "  var ce=console.error;console.error=function(){rec('console.error: '+Array.prototype.join.call(arguments,' '));ce.apply(console,arguments);};\n"
       "})();\n</script>\n"
    << "<style>\nbody{font-family:Helvetica,Arial,sans-serif;max-width:1040px;margin:1em auto;padding:0 1em;color:#222}\n"
       "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
       "th:first-child,td:first-child{text-align:left}\n.pass{color:#1a7f37;font-weight:bold}.fail{color:#c0392b;font-weight:bold}\n"
       "#controls{position:sticky;top:0;background:#fff;padding:6px 0;border-bottom:1px solid #ddd;z-index:1}\n"
       "#slider{width:70%;vertical-align:middle}#frame-label{font-weight:bold;margin-left:1em}\n"
       "#errors{color:#c0392b}svg{max-width:100%;height:auto}\n</style>\n</head>\n<body>\n"
    << "<pre id=\"errors\" hidden></pre>\n";
  std::string labels;
  for (size_t k = 0; k < r.runs.size(); ++k) labels += (k ? (k + 1 == r.runs.size() ? " and " : ", ") : "") + r.runs[k].label;
  o << "<h1>" << xml_escape(c.name) << ": " << xml_escape(labels) << "</h1>\n";
  if (!c.description.empty()) o << "<p>" << xml_escape(c.description) << "</p>\n";
  if (!r.command.empty()) o << "<p>Made with <code>" << xml_escape(r.command) << "</code></p>\n";
  // Headline table.
  o << "<table><tr><th></th>";
  for (const ReportRun& rr : r.runs) o << "<th>" << xml_escape(rr.label) << "</th>";
  o << "</tr>\n<tr><td>capacity (mm)</td>";
  for (const ReportRun& rr : r.runs) o << "<td>" << mm(rr.run->capacity) << (rr.run->collapsed ? "" : " (no collapse)") << "</td>";
  o << "</tr>\n<tr><td>relative to " << xml_escape(r.runs[0].label) << "</td><td>-</td>";
  for (const Comparison& k : r.comparisons) o << "<td>" << pct(k.capacity_rel_diff) << "</td>";
  o << "</tr>\n<tr><td>largest / rms thrust difference (W)</td><td>-</td>";
  for (const Comparison& k : r.comparisons) o << "<td>" << fmt::g(k.thrust_max_diff) << " / " << fmt::g(k.thrust_rms_diff) << "</td>";
  o << "</tr>\n<tr><td>hinges agree (of checks)</td><td>-</td>";
  for (const Comparison& k : r.comparisons) {
    int ok = 0;
    for (const HingeCheck& h : k.hinges) ok += h.ok();
    o << "<td>" << ok << " / " << k.hinges.size() << "</td>";
  }
  o << "</tr>\n<tr><td>run time (s)</td>";
  for (const ReportRun& rr : r.runs) o << "<td>" << secs(rr.run->timing.total_s) << "</td>";
  o << "</tr>\n</table>\n";
  if (r.tolerances_checked) {
    o << "<h2>Tolerance checks</h2>\n<ul>\n";
    for (size_t k = 0; k < r.comparisons.size(); ++k) {
      o << "<li>" << xml_escape(r.comparisons[k].a.label) << " against " << xml_escape(r.comparisons[k].b.label) << ": "
        << (r.violations[k].empty() ? "<span class=\"pass\">PASS</span>" : "<span class=\"fail\">FAIL</span>");
      if (!r.violations[k].empty()) {
        o << "<ul>";
        for (const std::string& v : r.violations[k]) o << "<li>" << xml_escape(v) << "</li>";
        o << "</ul>";
      }
      o << "</li>\n";
    }
    o << "</ul>\n";
  }
  // Slider and frames.
  o << "<h2>The structure step by step</h2>\n<p>Blocks on the deformed geometry (supports hatched), cracked joints bold, hinges as red "
       "rings, joint resultants in blue, the thrust line in red, support reactions in green. Drag the slider (or use the arrow "
       "keys); the black line in the thrust curves below follows it.</p>\n"
    << "<div id=\"controls\"><input type=\"range\" id=\"slider\" min=\"0\" max=\"" << (fd.empty() ? 0 : fd.size() - 1)
    << "\" value=\"0\" step=\"1\" aria-label=\"support displacement step\"><span id=\"frame-label\"></span></div>\n";
  for (size_t i = 0; i < fd.size(); ++i) {
    std::vector<Panel> panels;
    for (const ReportRun& rr : r.runs) {
      const StepRecord* s = record_at(*rr.run, fd[i]);
      panels.push_back(panel(rr, s, fd[i]));
    }
    char dd[32];
    std::snprintf(dd, sizeof dd, "%.9g", fd[i]);
    std::string id = "f";  // distinct SVG ids per frame
    id += std::to_string(i);
    id += '-';
    o << "<div class=\"frame\" data-d=\"" << dd << "\" data-index=\"" << i << "\"" << (i ? " hidden" : "") << ">\n"
      << svg_structure(c, panels, frame, pw, id) << "</div>\n";
  }
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    const Comparison& cmp = r.comparisons[k];
    o << "<h2>" << xml_escape(cmp.a.label) << " against " << xml_escape(cmp.b.label) << "</h2>\n";
    o << "<p>Common range d = 0 to " << mm(cmp.d_max) << " mm; largest thrust difference " << fmt::g(cmp.thrust_max_diff) << " W ("
      << xml_escape(cmp.thrust_max_where) << " at d = " << mm(cmp.thrust_max_d) << " mm), rms "
      << fmt::g(cmp.thrust_rms_diff) << " W. Mechanism changes (mm): " << xml_escape(cmp.a.label) << " " << changes_mm(cmp.a) << "; "
      << xml_escape(cmp.b.label) << " " << changes_mm(cmp.b) << ".</p>\n";
    o << svg_thrust(cmp, *r.runs[0].run, *r.runs[k + 1].run, true);
    o << "<table><tr><th>d (mm)</th><th>" << xml_escape(cmp.a.label) << " hinges</th><th>" << xml_escape(cmp.b.label)
      << " hinges</th><th>agree</th></tr>\n";
    for (const HingeCheck& h : cmp.hinges)
      o << "<tr><td>" << mm(h.d) << "</td><td>" << xml_escape(hinge_list(h.a)) << "</td><td>" << xml_escape(hinge_list(h.b)) << "</td><td>"
        << (h.match ? "yes" : h.mirror ? "mirror image" : "<strong>no</strong>") << "</td></tr>\n";
    o << "</table>\n";
  }
  std::vector<Bar> bars;
  for (size_t k = 0; k < r.runs.size(); ++k) bars.push_back({r.runs[k].label, r.runs[k].run->capacity, kRunColors[k % 6]});
  o << "<h2>Capacities</h2>\n" << svg_capacity(bars);
  o << "<script nonce=\"" << nonce << "\">\n"
    << "(function(){\n"
       "  if(window.__early)window.__rec(window.__early);\n"
       "  var frames=document.querySelectorAll('.frame'),slider=document.getElementById('slider'),label=document.getElementById('frame-label');\n"
       "  function show(i){\n"
       "    if(!frames.length)return;\n"
       "    i=Math.max(0,Math.min(frames.length-1,Math.round(i)||0));\n"
       "    for(var k=0;k<frames.length;++k)frames[k].hidden=(k!==i);\n"
       "    slider.value=String(i);\n"
       "    var d=parseFloat(frames[i].getAttribute('data-d'));\n"
       "    label.textContent='d = '+(d*1000).toFixed(1)+' mm (step '+(i+1)+' of '+frames.length+')';\n"
       "    document.body.setAttribute('data-frame',String(i));\n"
       "    var plots=document.querySelectorAll('svg.thrust');\n"
       "    for(var p=0;p<plots.length;++p){\n"
       "      var x=parseFloat(plots[p].getAttribute('data-x0'))+d*parseFloat(plots[p].getAttribute('data-sx'));\n"
       "      var cs=plots[p].querySelectorAll('.cursor');\n"
       "      for(var q=0;q<cs.length;++q){cs[q].setAttribute('x1',x);cs[q].setAttribute('x2',x);}\n"
       "    }\n"
       "  }\n"
       "  slider.addEventListener('input',function(){show(+slider.value);});\n"
       "  // Test hook and shareable links: report.html#step=N moves the slider to position N the way a\n"
       "  // reader does (its value, then an input event), so a test exercises the slider's own handler.\n"
       "  function fromHash(){var m=/step=(\\d+)/.exec(location.hash);if(m){slider.value=m[1];slider.dispatchEvent(new Event('input'));}}\n"
       "  window.addEventListener('hashchange',fromHash);\n"
       "  show(0);fromHash();\n"
       "  document.body.setAttribute('data-ready','1');\n"
       "})();\n</script>\n</body>\n</html>\n";
  return o.str();
}

void write_report(const std::string& dir, const Report& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir + "/figures", ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the report directory: " + ec.message());
  const std::vector<Figure> figs = report_figures(r);
  for (const Figure& f : figs) write_file_atomic(dir + "/" + f.file, f.svg);
  write_file_atomic(dir + "/comparison.json", report_json(r).dump(1) + "\n");
  write_file_atomic(dir + "/report.md", report_markdown(r, figs));
  write_file_atomic(dir + "/report.html", report_html(r, r.frames));
}

}  // namespace masonry
