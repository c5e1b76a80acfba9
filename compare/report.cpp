#include "model/interfaces.hpp"
#include "compare/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "compare/svg.hpp"
#include "model/version.hpp"
#include "report/document.hpp"
#include "report/format.hpp"
#include "report/html.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;

namespace {

const char* kRunColors[] = {"#4a4a4a", "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00"};

using fmt::mm;
// A ratio without an exponent: 0.5, 12.3, 2270.
std::string ratio(double x) { return fmt::number(x, x >= 100 ? "%.0f" : "%.3g", x); }

const StepRecord* record_at(const RunResult& r, double d) { return record_at(stable_records(r), d); }

// The unit d is shown in: mm, or mrad when the supports only turn (path_unit).
std::string d_unit(const Report& r) { return milli(path_unit(*r.c)); }

Panel panel(const ReportRun& rr, const StepRecord* s, double d, const std::string& unit) {
  Panel p{rr.run, s, rr.label, "no record"};
  if (!s) return p;
  p.subtitle = "d = " + mm(s->d, 0) + " " + unit;
  if (d > rr.run->capacity + 1e-9 && rr.run->collapsed) p.subtitle += " (collapsed after " + mm(rr.run->capacity) + " " + unit + ")";
  return p;
}

// How many joints along a ring a hinge may move and still count as the same: the tolerances'
// hinge_shift when they are checked, else 0 (the same joint).
int allowed_shift(const Report& r) { return r.tolerances_checked ? r.tolerances.hinge_shift : 0; }

// Each hinge with how far it has opened since d = 0 (mm), so a reader tells a hinge of the
// mechanism from one just past the threshold.
std::string hinge_list(const std::vector<Hinge>& hs) {
  std::string o;
  for (const Hinge& h : hs) o += (o.empty() ? "" : ", ") + h.label + " (" + fmt::g(h.opening * 1e3, 2) + ")";
  return o.empty() ? "none" : o;
}

std::string changes_text(const RunSummary& s) {
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

Report make_report(const Case& c, const std::vector<ReportRun>& runs, const Tolerances* t, const CompareOptions& o) {
  Report r;
  r.c = &c;
  r.runs = runs;
  r.tolerances_checked = t != nullptr;
  if (t) r.tolerances = *t;
  CompareOptions opts = o;
  if (t) opts.ring_shift = t->hinge_shift;
  for (size_t k = 1; k < runs.size(); ++k) {
    r.comparisons.push_back(compare_runs(c, *runs[0].run, *runs[k].run, opts, runs[0].label, runs[k].label));
    r.violations.push_back(t ? check_tolerances(r.comparisons.back(), *t) : std::vector<std::string>{});
  }
  return r;
}

std::vector<Figure> report_figures(const Report& r) {
  std::vector<Figure> figs;
  const std::string unit = d_unit(r);
  std::vector<Bar> bars;
  for (size_t k = 0; k < r.runs.size(); ++k) bars.push_back({r.runs[k].label, r.runs[k].run->capacity, kRunColors[k % 6]});
  figs.push_back({"figures/capacity.svg", svg_capacity(bars, unit), "Displacement capacity of each run"});
  std::vector<const RunResult*> all;
  for (const ReportRun& rr : r.runs) all.push_back(rr.run);
  const DrawFrame frame = draw_frame(*r.c, all);
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    const Comparison& cmp = r.comparisons[k];
    const ReportRun& A = r.runs[0];
    const ReportRun& B = r.runs[k + 1];
    const std::string n = std::to_string(k + 1);
    if (cmp.thrust_skipped.empty())
      figs.push_back(
          {"figures/thrust-" + n + ".svg", svg_thrust(cmp, *A.run, *B.run), "Thrust curves: " + A.label + " (solid) and " + B.label + " (dashed)"});
    int j = 0;
    for (double d : figure_ds(cmp)) {
      const StepRecord* sa = record_at(*A.run, d);
      const StepRecord* sb = record_at(*B.run, d);
      figs.push_back({"figures/structure-" + n + "-" + std::to_string(++j) + ".svg",
                      svg_structure(*r.c, {panel(A, sa, d, unit), panel(B, sb, d, unit)}, frame), "d = " + mm(d) + " " + unit});
    }
    if (std::abs(cmp.a.capacity - cmp.b.capacity) > 1e-12) {
      const StepRecord* sa = record_at(*A.run, cmp.a.capacity);
      const StepRecord* sb = record_at(*B.run, cmp.b.capacity);
      figs.push_back({"figures/structure-" + n + "-" + std::to_string(++j) + ".svg",
                      svg_structure(*r.c,
                                    {{A.run, sa, A.label, "at its capacity, d = " + mm(cmp.a.capacity) + " " + unit},
                                     {B.run, sb, B.label, "at its capacity, d = " + mm(cmp.b.capacity) + " " + unit}},
                                    frame),
                      "each method at its own capacity"});
    }
  }
  return figs;
}

ojson report_json(const Report& r) {
  ojson j;
  j["format"] = "masonry-comparison/1";
  j["units"] = "SI: m, N, s, rad; thrust as reaction / total weight; d in d_unit";
  j["version"] = version_text();
  j["case"] = r.c->name;
  j["d_unit"] = path_unit(*r.c);
  ojson runs = ojson::array();
  for (const ReportRun& rr : r.runs) {
    runs.push_back({{"label", rr.label},
                    {"method", rr.run->method},
                    {"version", rr.run->version.empty() ? version_text() : rr.run->version},
                    {"dir", rr.dir},
                    {"capacity", json_number(rr.run->capacity)},
                    {"collapsed", rr.run->collapsed},
                    {"stopped", status_name(rr.run->status)},
                    {"message", rr.run->message},
                    {"time_s", json_number(rr.run->timing.total_s)},
                    {"settings", rr.run->settings}});
    if (rr.prd_on_run) runs.back()["prd_on_run"] = prd_on_run_json(*rr.prd_on_run);
    if (rr.rerun) {
      const DampedRerun& x = *rr.rerun;
      const SlideVerdict& v = x.verdict;
      runs.back()["damped_rerun"] = {{"joint", v.slide.joint},
                                     {"slip", json_number(v.slide.slip)},
                                     {"other_slip", json_number(v.slide.other)},
                                     {"travel", json_number(v.slide.travel)},
                                     {"to", json_number(v.slide.to)},
                                     {"friction_angle", json_number(v.friction_angle)},
                                     {"statics_needs", json_number(v.needs)},
                                     {"statics_needs_at", json_number(v.at_d)},
                                     {"statics_joint", v.at_joint},
                                     {"contact_damping", json_number(x.contact_damping)},
                                     {"first_capacity", json_number(x.first_capacity)},
                                     {"first_stopped", status_name(x.first_status)},
                                     {"first_time_s", json_number(x.first_time_s)},
                                     {"rerun_slip", json_number(x.rerun_slip)},
                                     {"removed", x.removed},
                                     {"first_dir", x.first_dir},
                                     {"rerun_dir", x.rerun_dir}};
    }
  }
  j["runs"] = runs;
  ojson cs = ojson::array();
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    ojson c = to_json(r.comparisons[k]);
    if (r.tolerances_checked) {
      ojson lim;
      lim["capacity"] = r.tolerances.capacity ? json_number(*r.tolerances.capacity) : ojson(nullptr);
      lim["capacity_abs"] = r.tolerances.capacity_abs ? json_number(*r.tolerances.capacity_abs) : ojson(nullptr);
      lim["thrust"] = r.tolerances.thrust ? json_number(*r.tolerances.thrust) : ojson(nullptr);
      lim["mechanism"] = r.tolerances.mechanism ? json_number(*r.tolerances.mechanism) : ojson(nullptr);
      lim["collapse_mechanism"] = r.tolerances.collapse_mechanism ? json_number(*r.tolerances.collapse_mechanism) : ojson(nullptr);
      lim["hinges"] = r.tolerances.hinges;
      lim["hinge_shift"] = r.tolerances.hinge_shift;
      c["tolerances"] = {{"limits", lim}, {"pass", r.violations[k].empty()}, {"violations", r.violations[k]}};
    }
    cs.push_back(c);
  }
  j["comparisons"] = cs;
  return j;
}

namespace {

std::string run_labels(const Report& r) {
  std::string labels;
  for (size_t k = 0; k < r.runs.size(); ++k) labels += (k ? (k + 1 == r.runs.size() ? " and " : ", ") : "") + r.runs[k].label;
  return labels;
}

// A joint's slip in mm to the micron (elastic shear is microns, friction slip millimetres); "n/a"
// where its joint came apart.
std::string slip_mm(double m) { return std::isfinite(m) ? fmt::number(m * 1e3, "%.3f", m * 1e3) + " mm" : std::string("n/a"); }

const Figure* find_figure(const std::vector<Figure>& figures, const std::string& file) {
  for (const Figure& f : figures)
    if (f.file == file) return &f;
  return nullptr;
}

// The least mechanism agreement over the intervals of the common range, then the agreement at
// collapse: "0.992 (at collapse 0.651)"; "n/a" where no interval has both runs' joints moving.
std::string least_agreement_text(const Comparison& k) {
  const MotionCheck* least = nullptr;
  const MotionCheck* collapse = nullptr;
  for (const MotionCheck& m : k.motion) {
    if (m.collapse)
      collapse = &m;
    else if (std::isfinite(m.agreement) && (!least || m.agreement < least->agreement))
      least = &m;
  }
  std::string s = least ? fmt::number(least->agreement, "%.3f", least->agreement) : "n/a";
  if (collapse && std::isfinite(collapse->agreement)) s += " (at collapse " + fmt::number(collapse->agreement, "%.3f", collapse->agreement) + ")";
  return s;
}

// The headline: one column per run, the reference first.
Table headline(const Report& r) {
  Table t;
  t.head = {""};
  for (const ReportRun& rr : r.runs) t.head.push_back(rr.label);
  const auto row = [&](const std::string& what, std::vector<Cell> cells) {
    cells.insert(cells.begin(), Cell(what));
    t.rows.push_back(std::move(cells));
  };
  std::vector<Cell> cap, step, time;
  for (const ReportRun& rr : r.runs) {
    const RunStatus st = rr.run->status;
    cap.push_back(fmt::mm(rr.run->capacity) + (st == RunStatus::collapse    ? ""
                                               : st == RunStatus::max_steps ? " (no collapse)"
                                                                            : " (" + std::string(status_name(st)) + ": last equilibrium)"));
    const auto recs = stable_records(*rr.run);
    step.push_back(recs.size() >= 2 ? fmt::mm(record_step(recs), 1) : "n/a");
    time.push_back(fmt::secs(rr.run->timing.total_s));
  }
  std::vector<Cell> rel = {"-"}, tmax = {"-"}, trms = {"-"}, mech = {"-"}, hinges = {"-"}, ratio_ = {"1"};
  for (const Comparison& k : r.comparisons) {
    rel.push_back(fmt::pct(k.capacity_rel_diff));
    tmax.push_back(fmt::g(k.thrust_max_diff));
    trms.push_back(fmt::g(k.thrust_rms_diff));
    mech.push_back(least_agreement_text(k));
    int ok = 0;
    for (const HingeCheck& h : k.hinges) ok += h.ok(allowed_shift(r));
    hinges.push_back(std::to_string(ok) + " / " + std::to_string(k.hinges.size()));
    ratio_.push_back(ratio(k.time_ratio));
  }
  const std::string unit = d_unit(r);
  row("capacity (" + unit + ")", cap);
  row("relative to " + r.runs[0].label, rel);
  row("largest thrust difference (W)", tmax);
  row("rms thrust difference (W)", trms);
  row("mechanism agreement (least)", mech);
  row("hinges match (of checks)", hinges);
  row("step (" + unit + ")", step);
  row("run time (s)", time);
  row("run time / " + r.runs[0].label, ratio_);
  t.align.assign(t.head.size(), Align::right);
  t.align[0] = Align::left;
  return t;
}

}  // namespace

Text prd_on_run_explained(double tolerance, const std::string& unit) {
  return {"PRD started from the DEM's last equilibrium at or before 0.9 of its capacity (", Cell("masonry prd --from", CellStyle::code),
          "), every block where the DEM left it, its events located to " + fmt::mm(tolerance, 2) + " " + unit +
              " (the DEM's collapse bracket). Offsets kept: each touching joint corner's elastic overlap and shear become the "
              "joint's geometry, the blocks rigid from there as the joints had deformed them; taken back: PRD's first step undoes "
              "them, the blocks rigid as cut. Where the kept column meets the DEM's capacity and the taken-back one PRD's from the "
              "case, the two methods agree on the deformed structure and their difference is the geometry the DEM's elastic joints "
              "deform to (",
          Cell("dem/README.md", CellStyle::code), ", \"What the compliance costs\")."};
}

namespace {

// PRD on each DEM run's deformed configuration: what of the capacity difference is the geometry
// the elastic joints deform to.
void deformed_section(Document& d, const Report& r) {
  Table t;
  const std::string unit = d_unit(r);
  t.head = {"run",
            "from d (" + unit + ")",
            "its capacity (" + unit + ")",
            "PRD, offsets kept (" + unit + ")",
            "against the run",
            "PRD, taken back (" + unit + ")",
            "PRD from the case (" + unit + ")"};
  t.align.assign(t.head.size(), Align::right);
  t.align[0] = Align::left;
  double tolerance = 0;
  for (const ReportRun& rr : r.runs) {
    if (!rr.prd_on_run) continue;
    const PrdOnRun& p = *rr.prd_on_run;
    const double cap = rr.run->capacity;
    tolerance = p.tolerance;
    t.rows.push_back({rr.label, fmt::mm(p.from_d, 1), fmt::mm(cap, 1), fmt::mm(p.kept, 1), fmt::pct((p.kept - cap) / cap, 2),
                      fmt::mm(p.taken_back, 1), fmt::mm(p.own, 1)});
  }
  if (t.rows.empty()) return;
  Text intro{Cell("PRD on the DEM's deformed configuration", CellStyle::strong), ": "};
  for (Cell& x : prd_on_run_explained(tolerance, unit)) intro.push_back(std::move(x));
  d.paragraph(std::move(intro));
  d.table(std::move(t));
}

void tolerance_section(Document& d, const Report& r) {
  if (!r.tolerances_checked) return;
  d.heading(2, {"Tolerance checks"});
  std::string capacity = r.tolerances.capacity ? fmt::g(*r.tolerances.capacity * 100) + "%" : std::string();
  if (r.tolerances.capacity_abs) capacity += (capacity.empty() ? "" : " or ") + fmt::mm(*r.tolerances.capacity_abs, 1) + " " + d_unit(r);
  d.paragraph({"Limits: capacity " + (capacity.empty() ? std::string("not checked") : capacity) + ", thrust " +
               (r.tolerances.thrust ? fmt::g(*r.tolerances.thrust) + " W" : std::string("not checked")) + ", mechanism agreement " +
               (r.tolerances.mechanism ? "at least " + fmt::g(*r.tolerances.mechanism) : std::string("not checked")) +
               (r.tolerances.collapse_mechanism ? ", at collapse at least " + fmt::g(*r.tolerances.collapse_mechanism) : std::string()) +
               ", hinges " +
               (!r.tolerances.hinges            ? std::string("not checked")
                : r.tolerances.hinge_shift == 0 ? std::string("must match")
                                                : "must match within " + joints_text(r.tolerances.hinge_shift) + " along a ring") +
               "."});
  std::vector<Item> items;
  for (size_t k = 0; k < r.comparisons.size(); ++k) {
    Item it{{r.comparisons[k].a.label + " against " + r.comparisons[k].b.label + ": ",
             Cell(r.violations[k].empty() ? "PASS" : "FAIL", CellStyle::strong)},
            {}};
    for (const std::string& v : r.violations[k]) it.sub.push_back({v});
    items.push_back(std::move(it));
  }
  d.list(std::move(items));
}

// The page's slider over d: one structure drawing per position, the union of every run's stable
// record d thinned evenly to `frames`.
std::string slider_html(const Report& r, int frames) {
  const Case& c = *r.c;
  std::vector<const RunResult*> all;
  for (const ReportRun& rr : r.runs) all.push_back(rr.run);
  const DrawFrame frame = draw_frame(c, all);
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
  const double pw = r.runs.size() <= 2 ? 470 : 940.0 / r.runs.size();
  std::ostringstream o;
  o << "<h2>The structure step by step</h2>\n<p>Blocks on the deformed geometry (supports hatched), cracked joints bold, hinges as red "
       "rings, joint resultants in blue, the thrust line in red, support reactions in green. Drag the slider (or use the arrow "
       "keys); the black line in the thrust curves below follows it.</p>\n"
    << "<div id=\"controls\"><input type=\"range\" id=\"slider\" min=\"0\" max=\"" << (fd.empty() ? 0 : fd.size() - 1)
    << "\" value=\"0\" step=\"1\" aria-label=\"support displacement step\" data-unit=\"" << d_unit(r)
    << "\"><span id=\"frame-label\"></span></div>\n";
  for (size_t i = 0; i < fd.size(); ++i) {
    std::vector<Panel> panels;
    for (const ReportRun& rr : r.runs) panels.push_back(panel(rr, record_at(*rr.run, fd[i]), fd[i], d_unit(r)));
    char dd[32];
    std::snprintf(dd, sizeof dd, "%.9g", fd[i]);
    std::string id = "f";  // distinct SVG ids per frame
    id += std::to_string(i);
    id += '-';
    o << "<div class=\"frame\" data-d=\"" << dd << "\" data-index=\"" << i << "\"" << (i ? " hidden" : "") << ">\n"
      << svg_structure(c, panels, frame, pw, id, false) << "</div>\n";
  }
  return o.str();
}

// The settled crack pattern each run starts from: the DEM's elastic settling under gravity opens
// small gaps (up to 0.23 mm on the cathedral's tall piers) that are not hinges of the mechanism;
// its later open corners are measured from these gaps (dem/README.md, "Hinges").
std::vector<Item> settled_cracks(const Report& r) {
  std::vector<Item> items;
  for (const ReportRun& rr : r.runs) {
    std::string list;
    if (rr.run && !rr.run->steps.empty() && !is_equilibrium(*rr.run, rr.run->steps.front())) {
      items.push_back({{rr.label + ": none: it did not settle as drawn"}, {}});
      continue;
    }
    if (rr.run && !rr.run->steps.empty()) {
      const std::vector<int> nth = pair_ordinals(rr.run->joints);
      for (int j : rr.run->steps.front().cracked) {
        if (j < 0 || j >= static_cast<int>(rr.run->joints.size())) continue;
        const JointInfo& J = rr.run->joints[j];
        list += (list.empty() ? "" : ", ") + joint_name(*r.c, J.i, J.j, nth[size_t(j)]);
      }
    }
    items.push_back({{rr.label + ": " + (list.empty() ? std::string("none") : list)}, {}});
  }
  return items;
}

// The runs' jumps (compare/README.md, "Jumps"), and where one run's collapse sits at the other's
// jump: the same snap through, which that run read as a collapse while the other went on.
void jumps_paragraph(Document& d, const Comparison& cmp, const std::string& unit) {
  if (cmp.jumps_a.empty() && cmp.jumps_b.empty()) return;
  const auto list = [&](const std::vector<Jump>& v) {
    if (v.empty()) return std::string("none");
    std::string out;
    for (size_t k = 0; k < v.size(); ++k) {
      if (k == 3) {
        out += " and " + std::to_string(v.size() - 3) + " more";
        break;
      }
      out += (k ? "; " : "") + mm(v[k].from, 1) + " to " + mm(v[k].to, 1) + " " + unit + ", " + v[k].block + " " + mm(v[k].drift, 1) + " mm";
    }
    return out;
  };
  std::string text = "Jumps: where a run's structure snapped through between two of its records (a free block moving more than " +
                     fmt::number(kJumpRatio, "%g", kJumpRatio) + " times as far as the supports carried any point, and more than " +
                     fmt::number(kJumpFloor, "%g", kJumpFloor) + " of the scene): " + cmp.a.label + " " + list(cmp.jumps_a) + "; " + cmp.b.label +
                     " " + list(cmp.jumps_b) + ".";
  // A collapse near the other run's jump (within two of its own steps or 2% of d: each method
  // meets a snap where its own path brings it there), which the other went through: it stood
  // on past the jump by more than that (PRD's last sub-step into a located limit is a jump too,
  // and a run collapsing beside it met the same limit, not a snap).
  const auto at_jump = [&](const RunSummary& x, const RunSummary& other, const std::vector<Jump>& v) {
    if (!x.collapsed) return;
    for (const Jump& j : v) {
      const double near = std::max(2 * x.step, 0.02 * std::abs(j.to));
      if (x.capacity < j.from - near || x.capacity > j.to + near || !(other.capacity > j.to + near)) continue;
      text += " " + x.label + " collapsed at " + mm(x.capacity, 1) + " " + unit + ", near " + other.label + "'s jump at " + mm(j.from, 1) + " to " +
              mm(j.to, 1) + " " + unit + ", which " + other.label + " went through: where it is the same snap, " + x.label +
              " took it for a collapse (dem/README.md, \"Protocol\", stage 6, on the DEM's own reading of one).";
      return;
    }
  };
  at_jump(cmp.a, cmp.b, cmp.jumps_b);
  at_jump(cmp.b, cmp.a, cmp.jumps_a);
  d.paragraph({text});
}

// The mechanism checks: per interval of d, how alike the two runs' joint motions are, and where
// they differ most (compare/README.md, "Mechanism agreement").
void mechanism_section(Document& d, const Report& r, const Comparison& cmp) {
  const std::string unit = d_unit(r);
  d.heading(3, {"Mechanism agreement"});
  if (!cmp.mechanism_skipped.empty()) {
    d.paragraph({"Mechanism agreement " + cmp.mechanism_skipped +
                 " (the check moves the joints' corners with the blocks and weights "
                 "each joint by the force it carries)."});
    return;
  }
  d.paragraph(
      {"Whether the two runs move the same way over each interval of d: every joint corner's relative displacement (the "
       "two blocks' copies of the corner, so the supports' imposed motion counts for nothing), weighted by the normal force "
       "the joint carries over W, and the cosine of the two runs' vectors: 1 for the same mechanism at any amplitude, 0 for "
       "motions at other joints or in other directions; n/a where one run's joints do not move (blocks carried rigidly by "
       "their supports)." +
       std::string(cmp.symmetric ? " The scene is symmetric: the mirror image of the second run counts when it agrees better." : "") +
       (cmp.ring_shift > 0 ? " A joint's motion may sit up to " + joints_text(cmp.ring_shift) +
                                 " along a ring from the other run's, as a hinge may (the tolerances' hinge_shift; in brackets "
                                 "the agreement at the same joints where that is lower)."
                           : std::string()) +
       " The last row compares how the runs collapse, from each one's last equilibrium to its collapse state: the DEM's is its "
       "fall when its hold is called a collapse (a block drifted 2% of the scene, its kinetic energy growing, or the cap's rule), PRD's the configuration one step past its capacity moved along its "
       "collapse mechanism alone by up to a step, so large motions past the first one take part. Where the agreement is below 1, the joints that differ most (their share of the "
       "difference) and what each run does there (the second block's turn relative to the first, each corner's opening, the "
       "slip). The hinge table below is the diagnostic of open corners at the interval ends."});
  Table t;
  t.head = {"d (" + unit + ")", "agreement", "differs most at"};
  t.align = {Align::right, Align::right, Align::left};
  for (const MotionCheck& m : cmp.motion) {
    std::string where = m.collapse ? "at collapse: " + cmp.a.label + " from " + fmt::mm(m.a_from) + ", " + cmp.b.label + " from " + fmt::mm(m.b_from)
                                   : fmt::mm(m.from) + " to " + fmt::mm(m.to);
    std::string agree = std::isfinite(m.agreement) ? fmt::number(m.agreement, "%.3f", m.agreement) + (m.mirror ? " (mirror image)" : "")
                        : !m.a_moves && !m.b_moves ? "n/a (no joint moves in either run)"
                                                   : "n/a (no joint moves in " + (!m.a_moves ? cmp.a.label : cmp.b.label) + ")";
    if (std::isfinite(m.agreement) && m.same_joints < m.agreement - 5e-4) agree += " (" + fmt::number(m.same_joints, "%.3f", m.same_joints) + ")";
    std::string most;
    for (const MotionDiff& x : m.differ) {
      if (x.share < 0.05) continue;  // a minor part of the difference
      most += (most.empty() ? "" : "; ") + x.label + " (" + fmt::number(x.share * 100, "%.0f%%", x.share * 100) + "): " + cmp.a.label + " " +
              joint_motion_text(x.a) + "; " + cmp.b.label + " " + joint_motion_text(x.b);
    }
    const std::optional<double>& limit = m.collapse ? r.tolerances.collapse_mechanism : r.tolerances.mechanism;
    const bool low = r.tolerances_checked && limit && m.agreement < *limit;
    // What differs is listed where the agreement reads below 1.000.
    const bool differs = std::isfinite(m.agreement) && m.agreement < 0.9995 && !most.empty();
    t.rows.push_back({where, low ? Cell(agree, CellStyle::strong) : Cell(agree), differs ? Cell(most) : Cell("-")});
  }
  d.table(std::move(t));
  if (cmp.sliding && cmp.sliding->largest_a.joint >= 0) {
    const SlipCheck& s = *cmp.sliding;
    d.paragraph({"Sliding: how far each run's joints slid along themselves from d = 0 to the end of the common range (" + fmt::mm(s.a_to) + " " + unit +
                 " in " + cmp.a.label + ", " + fmt::mm(s.b_to) + " " + unit + " in " + cmp.b.label +
                 "), at the corner of each joint that opened less, the one in contact (blocks turning about a hinge slide nowhere there; a "
                 "joint's elastic shear is microns). Most in " + cmp.a.label + ": " + s.largest_a.label + ", " + slip_mm(s.largest_a.a) + " (" + cmp.b.label +
                 " " + slip_mm(s.largest_a.b) + " there); most in " + cmp.b.label + ": " + s.largest_b.label + ", " + slip_mm(s.largest_b.b) + " (" +
                 cmp.a.label + " " + slip_mm(s.largest_b.a) + " there). Where one method's joints slid and the other's did not, the two "
                 "answer for different mechanisms; a DEM whose joints slid where PRD's mechanism turns about hinges and its friction "
                 "suffices may have joints stiff against the weights (dem/README.md, \"Contact damping\")."});
  }
  jumps_paragraph(d, cmp, unit);
}

// How a run ended, in words: "collapsed at 31 mrad", "stood to the end of its path (400 mm)".
std::string ended_at(RunStatus s, double d, const std::string& unit) {
  const std::string at = fmt::mm(d, 2) + " " + unit;
  switch (s) {
    case RunStatus::collapse: return "collapsed at " + at;
    case RunStatus::max_steps: return "stood to the end of its path (" + at + ")";
    default: return std::string(status_name(s)) + " at " + at;
  }
}

// compare/README.md, "A slide statics does not ask for": why a DEM run was run again with contact
// damping, what the rerun showed, and which of the two this comparison is of.
void damped_rerun_paragraph(Document& d, const Comparison& cmp, const DampedRerun& x, const std::string& unit) {
  const SlideVerdict& v = x.verdict;
  const std::string pct = fmt::number(v.slide.slip / v.slide.travel * 100, "%.1f%%", v.slide.slip / v.slide.travel * 100);
  std::string p = "A slide statics does not ask for: the DEM's first run (" + x.first_dir + ", " + ended_at(x.first_status, x.first_capacity, unit) +
                  ") slid joint " + v.slide.joint + " by " + slip_mm(v.slide.slip) + " up to d = " + fmt::mm(v.slide.to, 2) + " " + unit + ", " + pct +
                  " of the supports' largest travel (" + fmt::mm(v.slide.travel, 1) + " mm), where " + cmp.a.label + "'s joint " +
                  (std::isfinite(v.slide.other) ? "slid " + slip_mm(v.slide.other) : std::string("came apart")) + "; and PRD's sliding check at " +
                  fmt::g(v.friction_angle) + " degrees finds some admissible force state within friction at every step up to there (the most any step needs: " +
                  fmt::g(v.needs) + " degrees, at d = " + fmt::mm(v.at_d, 2) + " " + unit + (v.at_joint.empty() ? "" : ", joint " + v.at_joint) +
                  "). So statics alone does not ask for the slide; the likely cause is the vibration of joints stiff against the weights ratcheting "
                  "them (dem/README.md, \"Contact damping\"), which a rerun with contact damping " + fmt::g(x.contact_damping) + " tests. ";
  if (x.removed)
    p += "With it the DEM's joints slid at most " + slip_mm(x.rerun_slip) + ": the slide was that ratchet, and " + cmp.b.label +
         " here is the rerun (" + x.rerun_dir + "). --no-damped-rerun keeps the first run instead.";
  else
    p += "With it the DEM still slid " + slip_mm(x.rerun_slip) + " (" + x.rerun_dir +
         "): no ratchet, but a slide the DEM's own force state asks for (its elastic joints may need more friction than the least PRD finds), "
         "so " + cmp.b.label + " here is the first run.";
  d.paragraph({p});
}

void comparison_section(Document& d, const Report& r, size_t k, const std::vector<Figure>& figures, bool page) {
  const Comparison& cmp = r.comparisons[k];
  const std::string n = std::to_string(k + 1);
  const std::string unit = d_unit(r);
  d.heading(2, {cmp.a.label + " against " + cmp.b.label});
  if (k + 1 < r.runs.size() && r.runs[k + 1].rerun) damped_rerun_paragraph(d, cmp, *r.runs[k + 1].rerun, unit);
  d.heading(3, {"Thrust curves"});
  std::string p = "Horizontal (H) and vertical (V) reaction of every support over the total weight W = " + fmt::kn(cmp.total_weight) +
                  " kN, against d. Compared on the common range d = 0 to " + fmt::mm(cmp.d_max) + " " + unit + " (" + std::to_string(cmp.d.size()) +
                  " points, every record of either run, linear interpolation between records): largest difference " + fmt::g(cmp.thrust_max_diff) +
                  " W (" + cmp.thrust_max_where + " at d = " + fmt::mm(cmp.thrust_max_d) + " " + unit + "), root-mean-square " +
                  fmt::g(cmp.thrust_rms_diff) + " W.";
  if (cmp.thrust_max_d == 0.0 && cmp.d_max > 0)
    p += " At d = 0 the structure is statically indeterminate: PRD reports one admissible force state among many, the DEM "
         "the one its settling under gravity finds, so a difference there is expected (the paper, Section 4: PRD gives \"just one of "
         "the infinite admissible stress states\" where the structure is statically indeterminate).";
  // A run without reactions (an outside solver's minimal results): said, and no empty table.
  d.paragraph({cmp.thrust_skipped.empty() ? p : "Thrust curves " + cmp.thrust_skipped + "."});
  Table sup;
  sup.head = {"support", "largest difference (W)", "H at d = " + fmt::mm(cmp.d_max) + " " + unit + ", " + cmp.a.label + " / " + cmp.b.label,
              "V at d = " + fmt::mm(cmp.d_max) + " " + unit};
  sup.align = {Align::left, Align::right, Align::right, Align::right};
  for (const SupportCurve& s : cmp.supports) {
    const bool e = !s.h_a.empty();
    sup.rows.push_back({s.support, fmt::g(s.max_diff), e ? fmt::g(s.h_a.back()) + " / " + fmt::g(s.h_b.back()) : "n/a",
                        e ? fmt::g(s.v_a.back()) + " / " + fmt::g(s.v_b.back()) : "n/a"});
  }
  if (!sup.rows.empty()) d.table(std::move(sup));
  if (const Figure* f = find_figure(figures, "figures/thrust-" + n + ".svg"))
    // The page's copy carries the cursor the slider moves.
    d.figure(f->file, f->caption, page ? svg_thrust(cmp, *r.runs[0].run, *r.runs[k + 1].run, true) : std::string());
  d.heading(3, {"Mechanism changes"});
  d.paragraph({"d (" + unit +
               ") where the set of open joint corners changes (a state held for a single record is taken as flicker and not "
               "counted):"});
  d.list({{{cmp.a.label + ": " + changes_text(cmp.a)}, {}}, {{cmp.b.label + ": " + changes_text(cmp.b)}, {}}});
  mechanism_section(d, r, cmp);
  d.heading(3, {"Hinges"});
  if (!cmp.hinges_skipped.empty()) d.paragraph({"Hinges " + cmp.hinges_skipped + " (open corners name joints)."});
  d.paragraph({"A hinge is a joint with exactly one open corner; listed as ", Cell("block/block:corner", CellStyle::code),
               std::string(" (the joint's two blocks and the corner, A or B, it turns about) with, in brackets, how far its open "
                           "corner has opened since d = 0, in mm. ") +
                   (cmp.symmetric ? "The scene is symmetric, so a mirror image counts as a match." : "The scene is not symmetric (in its blocks, or in its loading: support motion, weights, loads).") +
                   (allowed_shift(r) > 0 ? " A hinge within " + joints_text(allowed_shift(r)) +
                                               " of the other run's along a ring, turning about the same side, counts as the same "
                                               "(the tolerances' hinge_shift; compare/README.md, \"Hinges one joint apart\")."
                                         : std::string())});
  d.paragraph(
      {"Joints open at d = 0, before any support motion (the settled crack pattern; a DEM's later hinges are measured from its gaps there):"});
  d.list(settled_cracks(r));
  if (cmp.hinge_gap > 0)
    d.paragraph({"Hinges of the support motion: a corner counts as open when its gap has grown by more than " + fmt::g(cmp.hinge_gap * 1e3) +
                 " mm since d = 0, the widest gap the settling under gravity opened in either run. Compliant joints open gaps that "
                 "wide with no support motion at all, and the motion moves them by as much elsewhere in the structure as it "
                 "redistributes the weight; a hinge of the mechanism opens in proportion to d. Both runs are read by this rule, and "
                 "the drawings mark hinges by it (compare/compare.hpp, settled_gap)."});
  Table h;
  h.head = {"d (" + unit + ")", cmp.a.label, cmp.b.label, "agree"};
  h.align = {Align::right, Align::left, Align::left, Align::left};
  for (const HingeCheck& x : cmp.hinges) {
    const std::string apart = x.shift > 0 ? joints_text(x.shift) + " apart" : std::string();
    h.rows.push_back({fmt::mm(x.d), hinge_list(x.a), hinge_list(x.b),
                      x.match                  ? Cell("yes")
                      : x.mirror               ? Cell("mirror image")
                      : x.ok(allowed_shift(r)) ? Cell("yes, " + apart)
                      : x.shift > 0            ? Cell("no (" + apart + ")", CellStyle::strong)
                                               : Cell("no", CellStyle::strong)});
  }
  if (!h.rows.empty()) d.table(std::move(h));
  // Static drawings at chosen steps: the Markdown's; the page has the slider instead.
  d.heading(3, {"The structure at chosen steps"}).last().medium = Medium::markdown;
  d.paragraph({"Blocks on the deformed geometry (supports hatched), cracked joints bold, hinges as red rings, joint resultants in blue "
               "through their pressure points, the thrust line in red, support reactions in green (force on the structure, labelled in "
               "units of W)."},
              Medium::markdown);
  for (const Figure& f : figures)
    if (f.file.rfind("figures/structure-" + n + "-", 0) == 0) {
      d.paragraph({Cell(f.caption, CellStyle::strong)}, Medium::markdown);
      d.figure(f.file, f.caption, {});
      d.last().medium = Medium::markdown;
    }
}

// Each run, how it ended and why (an undecided or failed run's message).
Table runs_table(const Report& r) {
  Table t;
  t.head = {"run", "results", "stopped", "why"};
  t.align.assign(4, Align::left);
  for (const ReportRun& rr : r.runs)
    t.rows.push_back({rr.label, rr.dir.empty() ? Cell("-") : Cell(rr.dir, CellStyle::link, rr.dir + "/results.json"), status_name(rr.run->status),
                      rr.run->message.empty() ? Cell("-") : Cell(rr.run->message)});
  return t;
}

// The runs' settings, one row per setting and a column per run, so that no cell runs off the page.
Table settings_table(const Report& r) {
  Table t;
  t.head = {"setting"};
  std::vector<std::string> keys;
  for (const ReportRun& rr : r.runs) {
    t.head.push_back(rr.label);
    for (auto it = rr.run->settings.begin(); it != rr.run->settings.end(); ++it)
      if (std::find(keys.begin(), keys.end(), it.key()) == keys.end()) keys.push_back(it.key());
  }
  for (const std::string& key : keys) {
    std::vector<Cell> row{Cell(key, CellStyle::code)};
    for (const ReportRun& rr : r.runs) {
      const auto it = rr.run->settings.find(key);
      if (it == rr.run->settings.end()) {
        row.push_back("-");
      } else if (it->is_number()) {
        row.push_back(fmt::g(it->get<double>(), 6));
      } else if (it->is_string()) {
        row.push_back(it->get<std::string>());
      } else if (it->is_array()) {  // a list of texts (held corners): one per line's worth, comma-separated
        std::string list;
        for (const auto& v : *it) list += (list.empty() ? "" : ", ") + (v.is_string() ? v.get<std::string>() : v.dump());
        row.push_back(list);
      } else {
        row.push_back(it->dump());
      }
    }
    t.rows.push_back(std::move(row));
  }
  t.align.assign(t.head.size(), Align::right);
  t.align[0] = Align::left;
  return t;
}

// The report's content, for both media. `frames` < 0: no slider (the Markdown needs none).
Document report_document(const Report& r, const std::vector<Figure>& figures, int frames) {
  const Case& c = *r.c;
  const bool page = frames >= 0;
  Document d;
  d.title = c.name + ": " + run_labels(r);
  if (!c.description.empty()) d.paragraph({c.description});
  if (!r.command.empty()) {
    d.paragraph({"Made with ", Cell(r.command, CellStyle::code), " (report.html has the same figures and a slider over d)."}, Medium::markdown);
    d.paragraph({"Made with ", Cell(r.command, CellStyle::code), "."}, Medium::html);
  }
  d.table(headline(r));
  tolerance_section(d, r);
  if (!r.notes.empty()) {
    d.heading(2, {"Notes"});
    for (const std::string& p : r.notes) d.paragraph({p});
  }
  d.heading(2, {"Capacities"});
  if (const Figure* f = find_figure(figures, "figures/capacity.svg")) d.figure(f->file, f->caption, f->svg);
  deformed_section(d, r);
  if (page) d.raw_html(slider_html(r, frames));
  for (size_t k = 0; k < r.comparisons.size(); ++k) comparison_section(d, r, k, figures, page);
  d.heading(2, {"Runs"});
  d.table(runs_table(r));
  d.paragraph(
      {"Their settings (", Cell("results.json", CellStyle::code), ", ", Cell("settings", CellStyle::code), "; SI units, friction in degrees):"});
  d.table(settings_table(r));
  d.paragraph({"Numbers: ", Cell("comparison.json", CellStyle::code), "."});
  return d;
}

// The page's two scripts, under one fresh nonce: the first records every error, console error and
// blocked script in #errors (so a headless browser's DOM dump shows them), the second drives the
// slider.
const char* kErrorScript =
    "(function(){\n"
    "  function rec(m){var "
    "e=document.getElementById('errors');if(e){e.textContent+=m+'\\n';e.hidden=false;}else{window.__early=(window.__early||'')+m+'\\n';}}\n"
    "  window.__rec=rec;\n"
    "  window.addEventListener('error',function(e){rec('error: '+(e.message||e.type));},true);\n"
    "  window.addEventListener('unhandledrejection',function(e){rec('unhandled rejection: '+e.reason);});\n"
    "  document.addEventListener('securitypolicyviolation',function(e){rec('blocked: '+e.violatedDirective);});\n"
    "  var ce=console.error;console.error=function(){rec('console.error: '+Array.prototype.join.call(arguments,' '));ce.apply(console,arguments);};\n"
    "})();\n";

const char* kSliderScript =
    "(function(){\n"
    "  if(window.__early)window.__rec(window.__early);\n"
    "  var frames=document.querySelectorAll('.frame'),slider=document.getElementById('slider'),label=document.getElementById('frame-label');\n"
    "  function show(i){\n"
    "    if(!frames.length)return;\n"
    "    i=Math.max(0,Math.min(frames.length-1,Math.round(i)||0));\n"
    "    for(var k=0;k<frames.length;++k)frames[k].hidden=(k!==i);\n"
    "    slider.value=String(i);\n"
    "    var d=parseFloat(frames[i].getAttribute('data-d'));\n"
    "    label.textContent='d = '+(d*1000).toFixed(1)+' '+slider.getAttribute('data-unit')+' (step '+(i+1)+' of '+frames.length+')';\n"
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
    "})();\n";

}  // namespace

std::string report_markdown(const Report& r, const std::vector<Figure>& figures) { return markdown(report_document(r, figures, -1)); }

std::string report_html(const Report& r, const std::vector<Figure>& figures, int frames) {
  const Document d = report_document(r, figures, std::max(frames, 0));
  HtmlPage p;
  p.title = r.c->name + ": comparison";
  p.script_nonce = script_nonce();
  p.head = "<script nonce=\"" + p.script_nonce + "\">\n" + kErrorScript + "</script>\n";
  p.style =
      ".pass{color:#1a7f37;font-weight:bold}.fail{color:#c0392b;font-weight:bold}\n"
      "#controls{position:sticky;top:0;background:#fff;padding:6px 0;border-bottom:1px solid #ddd;z-index:1}\n"
      "#slider{width:70%;vertical-align:middle}#frame-label{font-weight:bold;margin-left:1em}\n#errors{color:#c0392b}\n";
  p.body = "<pre id=\"errors\" hidden></pre>\n" + html_body(d) + "<script nonce=\"" + p.script_nonce + "\">\n" + kSliderScript + "</script>\n";
  return html_page(p);
}

void write_report(const std::string& dir, const Report& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir + "/figures", ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the report directory: " + ec.message());
  const std::vector<Figure> figs = report_figures(r);
  for (const Figure& f : figs) write_file_atomic(dir + "/" + f.file, f.svg);
  write_file_atomic(dir + "/comparison.json", report_json(r).dump(1) + "\n");
  write_file_atomic(dir + "/report.md", report_markdown(r, figs));
  write_file_atomic(dir + "/report.html", report_html(r, figs, r.frames));
}

}  // namespace masonry
