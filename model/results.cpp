#include "model/results.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "model/version.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;

ojson json_number(double x) { return std::isfinite(x) ? ojson(x) : ojson(nullptr); }

ojson prd_on_run_json(const PrdOnRun& p) {
  return {{"from_d", p.from_d},
          {"tolerance", p.tolerance},
          {"kept", json_number(p.kept)},
          {"taken_back", json_number(p.taken_back)},
          {"own", json_number(p.own)}};
}

namespace {
ojson vec(const Vec2& v) { return ojson::array({json_number(v.x()), json_number(v.y())}); }
}  // namespace

const char* status_name(RunStatus s) {
  switch (s) {
    case RunStatus::running: return "running";
    case RunStatus::collapse: return "collapse";
    case RunStatus::max_steps: return "max_steps";
    case RunStatus::undecided: return "undecided";
    case RunStatus::error: return "error";
  }
  return "?";
}

std::optional<RunStatus> parse_status(const std::string& name) {
  for (RunStatus s : {RunStatus::running, RunStatus::collapse, RunStatus::max_steps, RunStatus::undecided, RunStatus::error})
    if (name == status_name(s)) return s;
  return std::nullopt;
}

bool located(RunStatus s) { return s == RunStatus::collapse || s == RunStatus::max_steps; }

const char* event_kind_name(EventKind k) {
  switch (k) {
    case EventKind::open: return "open";
    case EventKind::close: return "close";
    case EventKind::collapse: return "collapse";
  }
  return "?";
}

bool is_equilibrium(const RunResult&, const StepRecord& s) { return s.settled.value_or(true); }

const StepRecord* last_equilibrium(const RunResult& r, double d) {
  const double eps = 1e-9 * std::max(1.0, std::abs(d));
  const StepRecord* out = nullptr;
  for (const StepRecord& s : r.steps)
    if (s.d <= d + eps && is_equilibrium(r, s) && (!out || s.d >= out->d)) out = &s;
  return out;
}

std::ostream& operator<<(std::ostream& o, RunStatus s) { return o << status_name(s); }

namespace {
const char* corner_letter(int corner) { return corner == 0 ? "A" : "B"; }

ojson corner_json(const CornerRef& x) { return {{"joint", x.joint}, {"corner", corner_letter(x.corner)}}; }

ojson poses_json(const std::vector<Pose>& poses) {
  ojson po = ojson::array();
  for (const Pose& p : poses) po.push_back(ojson::array({json_number(p.x), json_number(p.y), json_number(p.angle)}));
  return po;
}

// The fields of the DEM's hold, in the step, in the order the DEM has always written them.
void write_hold(const DemHold& h, ojson& js) {
  js["hold_end"] = h.hold_end;
  if (h.bracket) js["bracket"] = true;
  js["cycles"] = h.cycles;
  js["move_cycles"] = h.move_cycles;
  js["lag"] = json_number(h.lag);
  js["hold_time"] = json_number(h.hold_time);
  js["unbalanced_ratio"] = json_number(h.unbalanced_ratio);
  js["max_speed"] = json_number(h.max_speed);
  js["drift"] = json_number(h.drift);
  js["contact_points"] = h.contact_points;
  js["max_overlap"] = json_number(h.max_overlap);
  if (h.cap_travel)
    js["cap_travel"] = {{"first_half", json_number(h.cap_travel->first_half)}, {"second_half", json_number(h.cap_travel->second_half)}};
}

ojson event_json(const Event& e, const RunResult& r, const Case& c) {
  ojson ev = {{"kind", event_kind_name(e.kind)}, {"d", json_number(e.d)}, {"within", json_number(e.within)}};
  ev["joints"] = ojson::array();
  for (const CornerRef& x : e.corners) {
    ojson jx = corner_json(x);
    const JointInfo& f = r.joints.at(x.joint);
    jx["blocks"] = {c.blocks[f.i].id, c.blocks[f.j].id};
    ev["joints"].push_back(jx);
  }
  return ev;
}

ojson bracket_json(const CollapseBracket& b) {
  ojson trials = ojson::array();
  for (const BracketTrial& t : b.trials) {
    ojson x = {{"d", json_number(t.d)}, {"end", t.end}, {"cycles", t.cycles}};
    if (t.confirm) x["confirm"] = true;
    if (t.followed) x["followed"] = true;
    trials.push_back(x);
  }
  return {{"equilibrium", json_number(b.equilibrium)}, {"failed", json_number(b.failed)}, {"width", json_number(b.width)}, {"trials", trials}};
}
}  // namespace

ojson mechanism_json(const Mechanism& m, const Case& c) {
  ojson out;
  out["open_corners"] = ojson::array();
  for (const CornerRef& x : m.open_corners) out["open_corners"].push_back(corner_json(x));
  out["moving_blocks"] = ojson::array();
  for (int b : m.moving_blocks) out["moving_blocks"].push_back(c.blocks.at(b).id);
  return out;
}

std::optional<Method> known_method(const RunResult& r) { return parse_method(r.method); }

std::string method_label(const RunResult& r) {
  const std::optional<Method> m = known_method(r);
  return m ? method_label(*m) : r.method;
}

ojson to_json(const RunResult& r, const Case& c) {
  ojson j;
  j["format"] = "masonry-results/1";
  j["units"] = "SI: m, N, J, s, rad";
  j["version"] = r.version.empty() ? version_text() : r.version;
  j["method"] = r.method;
  j["case"] = r.case_name;
  // A run still going is written as its records stand: a solver hands its results out as it
  // records a step, and may count that step only after (a DEM run killed there had written
  // capacity 0.028 m beside its equilibrium record at 0.029 m).
  double capacity = r.capacity;
  int stable_steps = r.stable_steps;
  if (r.status == RunStatus::running)
    for (const StepRecord& s : r.steps)
      if (is_equilibrium(r, s) && s.d > capacity) {
        capacity = s.d;
        stable_steps = s.index;  // stable_steps is the last equilibrium record's index
      }
  j["capacity"] = json_number(capacity);
  j["stable_steps"] = stable_steps;
  j["collapsed"] = r.collapsed;
  j["stopped"] = status_name(r.status);
  if (!r.message.empty()) j["message"] = r.message;
  j["total_weight"] = json_number(r.total_weight);
  j["settings"] = r.settings;
  ojson t;
  t["total_s"] = json_number(r.timing.total_s);
  if (known_method(r) == Method::prd) {
    t["lp_s"] = json_number(r.timing.lp_s);
    t["lp_solves"] = r.timing.lp_solves;
    t["kept_basis_solves"] = r.timing.kept_basis_solves;
    t["interior_solves"] = r.timing.interior_solves;
    t["basis_evaluations"] = r.timing.basis_evaluations;
  } else {
    t["cycles"] = r.timing.cycles;
  }
  j["timing"] = t;
  ojson blocks = ojson::array();
  for (const Block& b : c.blocks) blocks.push_back({{"id", b.id}, {"support", b.support}});
  j["blocks"] = blocks;
  ojson joints = ojson::array();
  for (size_t k = 0; k < r.joints.size(); ++k) {
    const JointInfo& f = r.joints[k];
    joints.push_back({{"id", k}, {"blocks", {c.blocks[f.i].id, c.blocks[f.j].id}}, {"a", vec(f.a)}, {"b", vec(f.b)}});
  }
  j["joints"] = joints;
  ojson steps = ojson::array();
  for (const StepRecord& s : r.steps) {
    ojson js;
    js["step"] = s.index;
    js["d"] = json_number(s.d);
    js["energy"] = json_number(s.energy);
    ojson oc = ojson::array();
    for (const OpenCorner& o : s.open_corners) oc.push_back({{"joint", o.joint}, {"corner", corner_letter(o.corner)}, {"gap", json_number(o.gap)}});
    js["open_corners"] = oc;
    js["cracked"] = s.cracked;
    ojson re = ojson::array();
    for (const Reaction& x : s.reactions) re.push_back({{"support", x.support}, {"force", vec(x.force)}, {"moment", json_number(x.moment)}});
    js["reactions"] = re;
    js["poses"] = poses_json(s.poses);
    ojson fo = ojson::array();
    for (const JointForce& f : s.forces)
      fo.push_back(
          {{"joint", f.joint}, {"normal", json_number(f.normal)}, {"shear", json_number(f.shear)}, {"point", vec(f.point)}, {"n", vec(f.n)}});
    js["forces"] = fo;
    if (s.settled) js["settled"] = *s.settled;
    if (s.hold) write_hold(*s.hold, js);
    if (s.lp) {
      js["lp_primal"] = json_number(s.lp->primal);
      js["lp_dual"] = json_number(s.lp->dual);
    }
    if (!s.held_corners.empty()) {
      ojson held = ojson::array();
      for (const HeldCorner& h : s.held_corners) held.push_back({{"corner", h.corner}, {"force", json_number(h.force)}});
      js["held_corners"] = held;
    }
    if (s.sliding)
      js["sliding"] = {{"demand_angle", json_number(s.sliding->demand_angle)},
                       {"demand_joint", s.sliding->demand_joint},
                       {"required_angle", json_number(s.sliding->required_angle)},
                       {"required_joint", s.sliding->required_joint}};
    steps.push_back(js);
  }
  j["steps"] = steps;
  if (r.events) {
    ojson ev = ojson::array();
    for (const Event& e : *r.events) ev.push_back(event_json(e, r, c));
    j["events"] = ev;
  }
  if (r.collapse) {
    ojson x = mechanism_json(r.collapse->mechanism, c);
    x["d"] = json_number(r.collapse->d);
    x["poses"] = poses_json(r.collapse->poses);
    if (!r.collapse->moved_poses.empty()) x["moved_poses"] = poses_json(r.collapse->moved_poses);
    j["collapse"] = x;
  }
  if (r.wall_s) j["wall_s"] = json_number(*r.wall_s);
  if (r.collapse_bracket) j["collapse_bracket"] = bracket_json(*r.collapse_bracket);
  if (r.limit_point) j["limit_point"] = true;
  if (!r.unconfirmed_failures.empty()) {
    ojson u = ojson::array();
    for (const UnconfirmedFailure& f : r.unconfirmed_failures)
      u.push_back({{"d", json_number(f.d)}, {"reached_from", json_number(f.reached_from)}, {"settled_from", json_number(f.settled_from)}});
    j["unconfirmed_failures"] = u;
  }
  if (!r.settled_creeps.empty()) {
    ojson u = ojson::array();
    for (const SettledCreep& f : r.settled_creeps) u.push_back({{"d", json_number(f.d)}, {"holds", f.holds}, {"time", json_number(f.time)}});
    j["settled_creeps"] = u;
  }
  if (!r.settled_snaps.empty()) {
    ojson u = ojson::array();
    for (const SettledSnap& f : r.settled_snaps)
      u.push_back({{"d", json_number(f.d)}, {"from", json_number(f.from)}, {"drift", json_number(f.drift)}, {"time", json_number(f.time)}});
    j["settled_snaps"] = u;
  }
  if (r.sliding) {
    const SlidingSummary& x = *r.sliding;
    ojson o = ojson::object();
    if (x.any) {
      o["required_friction_angle"] = json_number(x.required_friction_angle);
      o["d"] = json_number(x.d);
      o["step"] = x.step;
      o["joint"] = x.joint;
      o["max_demand_angle"] = json_number(x.max_demand_angle);
      o["demand_d"] = json_number(x.demand_d);
      o["demand_joint"] = x.demand_joint;
    }
    o["lp_solves"] = x.lp_solves;
    j["sliding"] = o;
  }
  return j;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

std::string steps_csv(const RunResult& r, const Case& c) {
  std::ostringstream o;
  o.precision(12);
  o << "step,d_" << path_unit(c) << ",energy_J,open_corners,cracked_joints";  // d_rad where the supports only turn
  for (const Block& b : c.blocks)
    if (b.support) o << "," << csv_field("Fx_" + b.id + "_N") << "," << csv_field("Fy_" + b.id + "_N");
  o << "\n";
  for (const StepRecord& s : r.steps) {
    o << s.index << "," << s.d << "," << s.energy << "," << s.open_corners.size() << "," << s.cracked.size();
    // Each support's columns by its id: a file read back may list its reactions in another order,
    // or give none (an outside solver's), and every row keeps the header's columns.
    for (const Block& b : c.blocks) {
      if (!b.support) continue;
      const auto x = std::find_if(s.reactions.begin(), s.reactions.end(), [&](const Reaction& y) { return y.support == b.id; });
      if (x == s.reactions.end())
        o << ",,";
      else
        o << "," << x->force.x() << "," << x->force.y();
    }
    o << "\n";
  }
  return o.str();
}

void write_results(const std::string& dir, const RunResult& r, const Case& c) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the output directory: " + ec.message());
  write_file_atomic(dir + "/results.json", to_json(r, c).dump(1) + "\n");
  write_file_atomic(dir + "/steps.csv", steps_csv(r, c));
}

void require_finite(const StepRecord& s) {
  auto check = [&](double x, const char* what) {
    if (std::isfinite(x)) return;
    std::ostringstream m;
    m << "the state at step " << s.index << " (d = " << s.d << ") is not finite: " << what
      << " (the case's numbers are outside what double precision carries)";
    throw std::runtime_error(m.str());
  };
  check(s.d, "d");
  check(s.energy, "energy");
  for (const Pose& p : s.poses) check(p.x + p.y + p.angle, "a block's pose");
  for (const Reaction& x : s.reactions) check(x.force.x() + x.force.y() + x.moment, "a support reaction");
  for (const JointForce& f : s.forces) check(f.normal + f.shear + f.point.x() + f.point.y(), "a joint force");
  for (const OpenCorner& o : s.open_corners) check(o.gap, "a corner gap");
}

}  // namespace masonry
