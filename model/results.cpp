#include "model/results.hpp"

#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace masonry {

using ojson = nlohmann::ordered_json;

ojson json_number(double x) { return std::isfinite(x) ? ojson(x) : ojson(nullptr); }

ojson prd_on_run_json(const PrdOnRun& p) {
  return {{"from_d", p.from_d}, {"tolerance", p.tolerance}, {"kept", json_number(p.kept)}, {"taken_back", json_number(p.taken_back)},
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

bool is_equilibrium(const RunResult& r, const StepRecord& s) { return r.method != "dem" || s.extra.value("settled", false); }

const StepRecord* last_equilibrium(const RunResult& r, double d) {
  const double eps = 1e-9 * std::max(1.0, std::abs(d));
  const StepRecord* out = nullptr;
  for (const StepRecord& s : r.steps)
    if (s.d <= d + eps && is_equilibrium(r, s) && (!out || s.d >= out->d)) out = &s;
  return out;
}

std::ostream& operator<<(std::ostream& o, RunStatus s) { return o << status_name(s); }

ojson to_json(const RunResult& r, const Case& c) {
  ojson j;
  j["format"] = "masonry-results/1";
  j["units"] = "SI: m, N, J, s, rad";
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
        ++stable_steps;
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
  if (r.method == "prd") {
    t["lp_s"] = json_number(r.timing.lp_s);
    t["lp_solves"] = r.timing.lp_solves;
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
    joints.push_back({{"id", k},
                      {"blocks", {c.blocks[f.i].id, c.blocks[f.j].id}},
                      {"a", vec(f.a)},
                      {"b", vec(f.b)}});
  }
  j["joints"] = joints;
  ojson steps = ojson::array();
  for (const StepRecord& s : r.steps) {
    ojson js;
    js["step"] = s.index;
    js["d"] = json_number(s.d);
    js["energy"] = json_number(s.energy);
    ojson oc = ojson::array();
    for (const OpenCorner& o : s.open_corners) oc.push_back({{"joint", o.joint}, {"corner", o.corner == 0 ? "A" : "B"}, {"gap", json_number(o.gap)}});
    js["open_corners"] = oc;
    js["cracked"] = s.cracked;
    ojson re = ojson::array();
    for (const Reaction& x : s.reactions) re.push_back({{"support", x.support}, {"force", vec(x.force)}, {"moment", json_number(x.moment)}});
    js["reactions"] = re;
    ojson po = ojson::array();
    for (const Pose& p : s.poses) po.push_back(ojson::array({json_number(p.x), json_number(p.y), json_number(p.angle)}));
    js["poses"] = po;
    ojson fo = ojson::array();
    for (const JointForce& f : s.forces)
      fo.push_back({{"joint", f.joint}, {"normal", json_number(f.normal)}, {"shear", json_number(f.shear)}, {"point", vec(f.point)}, {"n", vec(f.n)}});
    js["forces"] = fo;
    for (auto it = s.extra.begin(); it != s.extra.end(); ++it) js[it.key()] = it.value();
    if (s.sliding)
      js["sliding"] = {{"demand_angle", json_number(s.sliding->demand_angle)},
                       {"demand_joint", s.sliding->demand_joint},
                       {"required_angle", json_number(s.sliding->required_angle)},
                       {"required_joint", s.sliding->required_joint}};
    steps.push_back(js);
  }
  j["steps"] = steps;
  for (auto it = r.extra.begin(); it != r.extra.end(); ++it) j[it.key()] = it.value();
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

std::string steps_csv(const RunResult& r) {
  std::ostringstream o;
  o.precision(12);
  o << "step,d_m,energy_J,open_corners,cracked_joints";
  if (!r.steps.empty())
    for (const Reaction& x : r.steps.front().reactions)
      o << "," << csv_field("Fx_" + x.support + "_N") << "," << csv_field("Fy_" + x.support + "_N");
  o << "\n";
  for (const StepRecord& s : r.steps) {
    o << s.index << "," << s.d << "," << s.energy << "," << s.open_corners.size() << "," << s.cracked.size();
    for (const Reaction& x : s.reactions) o << "," << x.force.x() << "," << x.force.y();
    o << "\n";
  }
  return o.str();
}

void write_results(const std::string& dir, const RunResult& r, const Case& c) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the output directory: " + ec.message());
  write_file_atomic(dir + "/results.json", to_json(r, c).dump(1) + "\n");
  write_file_atomic(dir + "/steps.csv", steps_csv(r));
}

void require_finite(const StepRecord& s) {
  auto check = [&](double x, const char* what) {
    if (std::isfinite(x)) return;
    std::ostringstream m;
    m << "the state at step " << s.index << " (d = " << s.d << " m) is not finite: " << what
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
