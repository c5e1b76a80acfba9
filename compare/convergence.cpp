#include "compare/convergence.hpp"

#include <algorithm>
#include <cmath>

#include "compare/report.hpp"
#include "model/version.hpp"
#include "report/document.hpp"
#include "report/format.hpp"

namespace masonry {

namespace {

using ojson = nlohmann::ordered_json;

std::string pct(double x) { return fmt::pct(x, 2); }

// The unit of d and of the capacities: rad where every moving support only turns.
std::string d_unit(const Convergence& c) { return c.scene ? path_unit(*c.scene) : "m"; }

// A joint counts in the partings when it is open wider than this fraction of the scene: a gap a
// drawing of the mechanism shows, well above the elastic gaps of settling under gravity.
constexpr double kOpenOfScene = 5e-5;

// Where run a's mechanism parts from b's for good (compare.hpp), when the study has the case.
std::optional<Parting> parting(const Convergence& c, const RunResult& a, const RunResult& b) {
  if (!c.scene) return std::nullopt;
  return hinges_part(*c.scene, a, b, kOpenOfScene * scene_size(*c.scene));
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

ojson parting_json(const std::optional<Parting>& p) {
  if (!p) return nullptr;
  return {{"d", p->d},
          {"only_this", p->only_a},
          {"only_other", p->only_b},
          {"at_end", {{"d", p->end_d}, {"only_this", p->end_only_a}, {"only_other", p->end_only_b}}}};
}

// How many of the hinge checks of PRD against a run (compare_runs, five values of d) find the
// same joints, and how many find them within one joint along a ring (compare/README.md,
// "Hinges one joint apart").
struct HingeTally {
  int checks = 0, same = 0, within_one = 0;
};
std::optional<HingeTally> hinge_tally(const Convergence& c, const RunResult& r) {
  if (!c.scene || !c.prd || !located(r.status)) return std::nullopt;
  HingeTally t;
  for (const HingeCheck& h : compare_runs(*c.scene, *c.prd, r).hinges) {
    ++t.checks;
    t.same += h.ok(0);
    t.within_one += h.ok(1);
  }
  return t;
}

// Whether run e has run d's joints: the same kn in the settings it recorded (a run that
// recorded none, as a hand-made study's, counts as the same).
bool same_joints(const ConvergenceEntry& e, const ConvergenceEntry& d) {
  const double a = e.run.settings.value("kn", NAN), b = d.run.settings.value("kn", NAN);
  return !(std::isfinite(a) && std::isfinite(b)) || std::abs(a - b) <= 1e-9 * std::abs(b);
}

}  // namespace

const char* study_name(Study s) { return s == Study::stiffness ? "stiffness" : "convergence"; }

const char* verdict_name(Study s, const ConvergenceVerdict& v) {
  if (s == Study::stiffness) return v.ok ? "complete" : "incomplete";
  return v.ok ? "converged" : v.protocol_converged ? "converged over the protocol" : "NOT shown converged";
}

ConvergenceVerdict judge(const Convergence& c) {
  ConvergenceVerdict v;
  if (c.entries.empty()) {
    v.problems.push_back("no run");
    return v;
  }
  v.complete = true;
  const ConvergenceEntry *lo = nullptr, *hi = nullptr;
  double protocol_lo = INFINITY, protocol_hi = -INFINITY;
  for (const ConvergenceEntry& e : c.entries) {
    if (!located(e.run.status)) {
      v.complete = false;
      v.problems.push_back(e.name + " (" + e.what + ") stopped with " + status_name(e.run.status) +
                           std::string(e.run.message.empty() ? "" : ": " + e.run.message));
      continue;
    }
    if (!lo || e.run.capacity < lo->run.capacity) lo = &e;
    if (!hi || e.run.capacity > hi->run.capacity) hi = &e;
    if (same_joints(e, c.entries.front())) {
      protocol_lo = std::min(protocol_lo, e.run.capacity);
      protocol_hi = std::max(protocol_hi, e.run.capacity);
    }
  }
  const double base = c.entries.front().run.capacity;
  if (v.complete && base > 0) v.spread = (hi->run.capacity - lo->run.capacity) / base;
  if (c.prd_capacity && *c.prd_capacity > 0 && located(c.entries.front().run.status)) v.prd_error = (base - *c.prd_capacity) / *c.prd_capacity;
  if (c.study == Study::stiffness) {
    v.ok = v.complete;
    return v;
  }
  // A stiffness study varies nothing but the joints: it has no protocol spread.
  if (v.complete && base > 0) v.protocol_spread = (protocol_hi - protocol_lo) / base;
  const bool prd_ok = !c.prd_capacity || std::abs(v.prd_error) <= c.prd_limit;
  v.protocol_converged = v.complete && v.protocol_spread <= c.spread_limit;
  if (v.complete && !(v.spread <= c.spread_limit)) {
    // The two ends of the spread, and what PRD says of each one's deformed configuration: a run
    // that PRD on its own geometry follows differs by that geometry (dem/README.md, "What the
    // compliance costs"), not by its protocol.
    const std::string u = " " + d_unit(c);
    const auto end = [&](const ConvergenceEntry& e) {
      std::string s = e.name + " (" + e.what + "): " + fmt::number(e.run.capacity, "%.4f", e.run.capacity) + u;
      if (e.prd_on_run && std::isfinite(e.prd_on_run->kept))
        s += " (PRD on its deformed configuration: " + fmt::number(e.prd_on_run->kept, "%.4f", e.prd_on_run->kept) + u + ", " +
             pct((e.prd_on_run->kept - e.run.capacity) / e.run.capacity) + ")";
      return s;
    };
    v.problems.push_back("the capacities spread by " + fmt::number(100 * v.spread, "%.2f%%", 100 * v.spread) + " of the default's, more than " +
                         fmt::g(100 * c.spread_limit) + "%: from " + end(*lo) + " to " + end(*hi) +
                         "; over the protocol's settings alone (the runs at the default's joint stiffness) by " +
                         fmt::number(100 * v.protocol_spread, "%.2f%%", 100 * v.protocol_spread));
  }
  if (!prd_ok)
    v.problems.push_back("the default's capacity differs from PRD's by " + pct(v.prd_error) + ", more than " + fmt::g(100 * c.prd_limit) + "%");
  v.ok = v.problems.empty();
  return v;
}

ojson convergence_json(const Convergence& c) {
  const ConvergenceVerdict v = judge(c);
  ojson j;
  j["format"] = "masonry-dem-convergence/1";
  j["version"] = version_text();
  j["study"] = study_name(c.study);
  j["units"] = "m for capacities and d, s for times";
  j["case"] = c.case_name;
  j["prd_capacity"] = c.prd_capacity ? ojson(*c.prd_capacity) : ojson(nullptr);
  j["spread_limit"] = c.spread_limit;
  j["prd_limit"] = c.prd_limit;
  j["spread"] = json_number(v.spread);
  j["protocol_spread"] = json_number(v.protocol_spread);
  j["prd_error"] = json_number(v.prd_error);
  j["ok"] = v.ok;
  j["protocol_converged"] = v.protocol_converged;
  j["verdict"] = verdict_name(c.study, v);
  j["problems"] = v.problems;
  ojson runs = ojson::array();
  const double base = c.entries.empty() ? NAN : c.entries.front().run.capacity;
  for (const ConvergenceEntry& e : c.entries) {
    ojson r;
    r["name"] = e.name;
    r["what"] = e.what;
    r["stopped"] = status_name(e.run.status);
    r["capacity"] = located(e.run.status) ? ojson(e.run.capacity) : ojson(nullptr);
    r["against_default"] = located(e.run.status) && base > 0 ? json_number((e.run.capacity - base) / base) : ojson(nullptr);
    r["against_prd"] = located(e.run.status) && c.prd_capacity ? json_number((e.run.capacity - *c.prd_capacity) / *c.prd_capacity) : ojson(nullptr);
    r["bracket_width"] = e.run.collapse_bracket ? json_number(e.run.collapse_bracket->width) : ojson(nullptr);
    r["cpu_s"] = e.run.timing.total_s;
    r["cycles"] = e.run.timing.cycles;
    r["message"] = e.run.message;
    r["kn"] = e.run.settings.contains("kn") ? e.run.settings["kn"] : ojson(nullptr);
    if (const std::optional<HingeTally> h = hinge_tally(c, e.run))
      r["hinges_against_prd"] = {{"checks", h->checks}, {"same_joints", h->same}, {"within_one_joint", h->within_one}};
    if (e.prd_on_run) r["prd_on_run"] = prd_on_run_json(*e.prd_on_run);
    if (c.scene && c.study == Study::stiffness && c.prd)
      r["parts_from_prd"] = parting_json(parting(c, e.run, *c.prd));
    else if (c.scene && &e != &c.entries.front())
      r["parts_from_default"] = parting_json(parting(c, e.run, c.entries.front().run));
    runs.push_back(r);
  }
  j["runs"] = runs;
  if (c.scene && c.prd && !c.entries.empty() && c.study == Study::convergence)
    j["default_parts_from_prd"] = parting_json(parting(c, c.entries.front().run, *c.prd));
  return j;
}

std::string convergence_markdown(const Convergence& c) {
  const ConvergenceVerdict v = judge(c);
  const bool stiffness = c.study == Study::stiffness;
  Document d;
  if (stiffness) {
    d.title = "DEM joint stiffness: " + c.case_name;
    d.paragraph(
        {"The same case with the joints' normal and shear stiffness (kn, ks) scaled together, every other setting at the default. "
         "PRD's blocks are rigid, the limit of stiffening joints, and the elastic gaps and settling shrink as 1/kn: a difference "
         "from PRD that shrinks as the joints stiffen is elastic, not the protocol's. Stiffness belongs to the structure, so "
         "this is a measurement, with no limits. Capacity: the last equilibrium before the collapse, bracketed (dem/README.md)."});
  } else {
    d.title = "DEM convergence: " + c.case_name;
    d.paragraph(
        {"The same case at the default DEM settings and at settings that must not change a quasi-static answer. "
         "Capacity: the last equilibrium before the collapse, bracketed (dem/README.md)."});
  }
  Table t;
  t.head = {
      "run",     "what differs", "stopped", "capacity (" + d_unit(c) + ")", "against default", "against PRD", "bracket (" + milli(d_unit(c)) + ")",
      "CPU (s)", "cycles"};
  t.align = {Align::left, Align::left, Align::left, Align::right, Align::right, Align::right, Align::right, Align::right, Align::right};
  if (stiffness) {
    t.head.insert(t.head.begin() + 2, "kn (Pa/m)");
    t.align.insert(t.align.begin() + 2, Align::right);
  }
  const bool tally = c.scene && c.prd;
  if (tally) {
    t.head.insert(t.head.end() - 2, "hinges as PRD's");
    t.align.insert(t.align.end() - 2, Align::right);
  }
  const double base = c.entries.empty() ? NAN : c.entries.front().run.capacity;
  for (const ConvergenceEntry& e : c.entries) {
    const bool ok = located(e.run.status);
    const double width = e.run.collapse_bracket ? e.run.collapse_bracket->width : NAN;
    t.rows.push_back({e.name, e.what, status_name(e.run.status), ok ? fmt::number(e.run.capacity, "%.4f", e.run.capacity) : "n/a",
                      ok && base > 0 ? pct((e.run.capacity - base) / base) : "n/a",
                      ok && c.prd_capacity ? pct((e.run.capacity - *c.prd_capacity) / *c.prd_capacity) : "n/a", fmt::mm(width, 2),
                      fmt::number(e.run.timing.total_s, "%.1f", e.run.timing.total_s), std::to_string(e.run.timing.cycles)});
    if (stiffness) {
      const double kn = e.run.settings.value("kn", NAN);
      t.rows.back().insert(t.rows.back().begin() + 2, fmt::number(kn, "%.3g", kn));
    }
    if (tally) {
      const std::optional<HingeTally> h = hinge_tally(c, e.run);
      t.rows.back().insert(
          t.rows.back().end() - 2,
          h ? std::to_string(h->same) + " (" + std::to_string(h->within_one) + ") / " + std::to_string(h->checks) : std::string("n/a"));
    }
  }
  d.table(std::move(t));
  if (tally)
    d.paragraph(
        {"Hinges as PRD's: of the five hinge checks of PRD against the run (compare/README.md, \"Hinges\"), how many find the "
         "same joints and, in brackets, the same joints or a neighbour along the ring (\"Hinges one joint apart\")."});
  const auto has = [](const ConvergenceEntry& e) { return e.prd_on_run.has_value(); };
  if (const auto first = std::find_if(c.entries.begin(), c.entries.end(), has); first != c.entries.end()) {
    Text intro{Cell("PRD on each run's deformed configuration", CellStyle::strong), ": "};
    for (Cell& x : prd_on_run_explained(first->prd_on_run->tolerance, milli(d_unit(c)))) intro.push_back(std::move(x));
    d.paragraph(std::move(intro));
    Table g;
    const std::string u = " (" + d_unit(c) + ")";
    g.head = {"run", "from d" + u, "capacity" + u, "PRD, offsets kept" + u, "against the run", "PRD, taken back" + u, "against the run"};
    g.align = {Align::left, Align::right, Align::right, Align::right, Align::right, Align::right, Align::right};
    for (const ConvergenceEntry& e : c.entries) {
      if (!e.prd_on_run) continue;
      const PrdOnRun& p = *e.prd_on_run;
      const double cap = e.run.capacity;
      g.rows.push_back({e.name, fmt::number(p.from_d, "%.4f", p.from_d), fmt::number(cap, "%.4f", cap), fmt::number(p.kept, "%.4f", p.kept),
                        pct((p.kept - cap) / cap), fmt::number(p.taken_back, "%.4f", p.taken_back), pct((p.taken_back - cap) / cap)});
    }
    d.table(std::move(g));
    d.paragraph({"PRD from the case's own geometry, its events located to the same tolerance: " +
                 fmt::number(first->prd_on_run->own, "%.4f", first->prd_on_run->own) + " " + d_unit(c) + "."});
  }
  // "The default" is the case's settings as the command changed them (a stiffness, a hold cap,
  // a number of increments): the settings its run recorded make the study reproducible.
  if (!c.entries.empty() && !c.entries.front().run.settings.empty())
    d.paragraph({"The default's DEM settings (its results.json): ", Cell(c.entries.front().run.settings.dump(), CellStyle::code)});
  d.paragraph(
      {"PRD capacity: " + (c.prd_capacity ? fmt::number(*c.prd_capacity, "%.4f", *c.prd_capacity) + " " + d_unit(c) : std::string("not run")) + "."});
  if (!stiffness)
    d.paragraph({"Spread (largest minus smallest capacity, over the default's): " +
                 (std::isfinite(v.spread) ? fmt::number(100 * v.spread, "%.2f%%", 100 * v.spread) : std::string("n/a")) + " (limit " +
                 fmt::g(100 * c.spread_limit) + "%); over the protocol's settings alone (the runs at the default's joint stiffness): " +
                 (std::isfinite(v.protocol_spread) ? fmt::number(100 * v.protocol_spread, "%.2f%%", 100 * v.protocol_spread) : std::string("n/a")) +
                 "; default against PRD: " + pct(v.prd_error) + " (limit " + fmt::g(100 * c.prd_limit) + "%)."});
  if (c.scene && !c.entries.empty()) {
    d.paragraph({Cell("Where the mechanisms part", CellStyle::strong), " (for good: joints open wider than " +
                                                                           fmt::g(1e3 * kOpenOfScene * scene_size(*c.scene), 3) +
                                                                           " mm differ from there to the end of the common range):"});
    std::vector<Item> items;
    auto line = [&](const std::string& who, const std::string& other, const RunResult& a, const RunResult& b) {
      const std::optional<Parting> p = parting(c, a, b);
      items.push_back(
          {{who + ": " +
            (!p ? "no parting from " + other + " for good (open joints that differ, if any, close again before the end of the common range)"
                : "from d = " + fmt::number(p->d, "%.4f", p->d) + " " + d_unit(c) + ", open only here: " + joined(p->only_a) + "; only in " + other +
                      ": " + joined(p->only_b) + ". At d = " + fmt::number(p->end_d, "%.4f", p->end_d) + " " + d_unit(c) +
                      ", the end of the common range, only here: " + joined(p->end_only_a) + "; only in " + other + ": " + joined(p->end_only_b))},
           {}});
    };
    if (stiffness) {
      // Each stiffness against the rigid limit.
      if (c.prd)
        for (const ConvergenceEntry& e : c.entries) line(e.name, "PRD", e.run, *c.prd);
    } else {
      if (c.prd) line("default", "PRD", c.entries.front().run, *c.prd);
      for (size_t k = 1; k < c.entries.size(); ++k) line(c.entries[k].name, "the default", c.entries[k].run, c.entries.front().run);
    }
    d.list(std::move(items));
  }
  if (stiffness) {
    if (!v.ok) {
      d.paragraph({Cell("Incomplete", CellStyle::strong), ":"});
      std::vector<Item> items;
      for (const std::string& p : v.problems) items.push_back({{p}, {}});
      d.list(std::move(items));
    }
  } else if (v.ok) {
    // A run that ends at its last increment (max_steps) has an answer too, the end of its path,
    // but not a collapse: say which, so a study of the first centimetres does not read as one of
    // capacities.
    bool all_collapsed = true;
    for (const ConvergenceEntry& e : c.entries) all_collapsed = all_collapsed && e.run.status == RunStatus::collapse;
    d.paragraph({Cell("Converged", CellStyle::strong),
                 all_collapsed ? ": every run located its collapse and the capacities agree within the limits."
                               : ": every run located its answer, a collapse or the end of its path (max_steps), and those agree within the "
                                 "limits; a run that ends at the end of its path has not been taken to collapse."});
  } else {
    if (v.protocol_converged)
      d.paragraph({Cell("Converged over the protocol", CellStyle::strong),
                   ": the runs at the default's joints agree within the spread limit, so the DEM answers for the structure it was "
                   "given; what is beyond the limits below is the joints' stiffness or the difference from PRD. Stiffness belongs to "
                   "the structure, and no protocol removes what it changes: where PRD on a run's deformed configuration (above) "
                   "follows the run, the difference is the geometry the joints deform to. Beyond the limits:"});
    else
      d.paragraph({Cell("Not shown converged", CellStyle::strong), ":"});
    std::vector<Item> items;
    for (const std::string& p : v.problems) items.push_back({{p}, {}});
    d.list(std::move(items));
  }
  return markdown(d);
}

}  // namespace masonry
