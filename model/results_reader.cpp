// The results.json reader (masonry-results/1, schemas/masonry-results.schema.json): the inverse of
// results.cpp's writer, and the one gate for results an outside solver writes. Declared fields
// only, each of its type; then the checks that the results fit each other and the case. Every
// front end and study that reads finished runs back goes through it.
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "model/fields.hpp"
#include "model/io.hpp"
#include "model/results.hpp"

namespace masonry {

namespace {

using ojson = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A number as messages show it: 6 significant digits, never 300 of them.
std::string num(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

std::string item(const std::string& where, size_t k) { return where + "[" + std::to_string(k) + "]"; }
std::string member(const std::string& where, const std::string& key) { return where == "results" ? key : where + "." + key; }

// Messages: "FILE: WHERE: field 'X' ...", WHERE the JSON path of the object holding the field
// ("steps[3].open_corners[0]"; "results" for the top level).
struct Reader : FieldReader<std::runtime_error, ojson> {
  const Case& c;
  int joints = 0;  // the file's joints, which open corners, forces and events refer to

  Reader(const std::string& src, const Case& c_) : FieldReader{src}, c(c_) {}

  const ojson& need(const ojson& o, const std::string& where, const char* field) const {
    auto it = o.find(field);
    if (it == o.end()) fail(where, std::string("field '") + field + "' is required");
    return *it;
  }
  // A number, or null for one the writer could not give (JSON has no NaN): NaN.
  double maybe(const ojson& v, const std::string& where, const std::string& field) const { return v.is_null() ? kNaN : number(v, where, field); }
  double maybe(const ojson& o, const std::string& where, const char* field, double dflt) const {
    auto it = o.find(field);
    return it == o.end() ? dflt : maybe(*it, where, field);
  }
  long long integer(const ojson& v, const std::string& where, const std::string& field) const {
    if (!v.is_number_integer()) fail(where, "field '" + field + "' must be a whole number");
    return v.get<long long>();
  }
  long long integer(const ojson& o, const std::string& where, const char* field, long long dflt) const {
    auto it = o.find(field);
    return it == o.end() ? dflt : integer(*it, where, field);
  }
  const ojson& array(const ojson& o, const std::string& where, const char* field) const {
    static const ojson empty = ojson::array();
    auto it = o.find(field);
    if (it == o.end()) return empty;
    if (!it->is_array()) fail(where, std::string("field '") + field + "' must be an array");
    return *it;
  }
  std::string text(const ojson& v, const std::string& where, const std::string& field) const {
    if (!v.is_string()) fail(where, "field '" + field + "' must be a string");
    return v.get<std::string>();
  }
  Vec2 vec(const ojson& o, const std::string& where, const char* field) const {
    const ojson& v = need(o, where, field);
    if (!v.is_array() || v.size() != 2) fail(where, std::string("field '") + field + "' must be [x, y]");
    return Vec2(maybe(v[0], where, field), maybe(v[1], where, field));
  }
  std::vector<Pose> poses(const ojson& arr, const std::string& where, const char* field) const {
    std::vector<Pose> out;
    for (size_t k = 0; k < arr.size(); ++k) {
      const ojson& p = arr[k];
      if (!p.is_array() || p.size() != 3) fail(where, std::string("field '") + field + "': item " + std::to_string(k) + " must be [x, y, angle]");
      out.push_back({maybe(p[0], where, field), maybe(p[1], where, field), maybe(p[2], where, field)});
    }
    if (!out.empty() && out.size() != c.blocks.size())
      fail(where, std::string("field '") + field + "' has " + std::to_string(out.size()) + " poses, one per block of the case (" +
                      std::to_string(c.blocks.size()) + ") expected");
    return out;
  }
  int block(const ojson& v, const std::string& where, const std::string& field) const {
    const std::string id = text(v, where, field);
    const int b = c.block_index(id);
    if (b < 0) fail(where, "field '" + field + "': block \"" + printable(id) + "\" is not in case \"" + printable(c.name) + "\"");
    return b;
  }
  int joint(const ojson& o, const std::string& where) const {
    const long long j = integer(need(o, where, "joint"), where, "joint");
    if (j < 0 || j >= joints)
      fail(where, "field 'joint' = " + std::to_string(j) + " is not one of the file's " + std::to_string(joints) + " joints (field 'joints')");
    return static_cast<int>(j);
  }
  int corner(const ojson& o, const std::string& where) const {
    const std::string s = text(need(o, where, "corner"), where, "corner");
    if (s != "A" && s != "B") fail(where, "field 'corner' must be \"A\" or \"B\"");
    return s == "B" ? 1 : 0;
  }
  std::string hold_end(const ojson& v, const std::string& where, const std::string& field) const {
    const std::string s = text(v, where, field);
    if (s != "equilibrium" && s != "collapse" && s != "creep" && s != "undecided")
      fail(where, "field '" + field + "' must be equilibrium, collapse, creep or undecided");
    return s;
  }
};

void read_blocks(const Reader& in, const ojson& blocks) {
  const std::string w = "blocks";
  if (blocks.size() != in.c.blocks.size()) in.fail(w, std::to_string(blocks.size()) + " blocks, the case has " + std::to_string(in.c.blocks.size()));
  for (size_t b = 0; b < blocks.size(); ++b) {
    const std::string wb = item(w, b);
    in.only(blocks[b], wb, {"id", "support"});
    if (in.text(in.need(blocks[b], wb, "id"), wb, "id") != in.c.blocks[b].id)
      in.fail(wb, "field 'id': not the case's block \"" + printable(in.c.blocks[b].id) + "\" (blocks in the case's order)");
    if (in.boolean(blocks[b], wb, "support", in.c.blocks[b].support) != in.c.blocks[b].support)
      in.fail(wb, "field 'support' differs from the case's block \"" + printable(in.c.blocks[b].id) + "\"");
  }
}

std::vector<JointInfo> read_joints(const Reader& in, const ojson& joints) {
  std::vector<JointInfo> out;
  for (size_t k = 0; k < joints.size(); ++k) {
    const std::string w = item("joints", k);
    const ojson& jj = joints[k];
    in.only(jj, w, {"id", "blocks", "a", "b"});
    if (jj.contains("id") && in.integer(jj["id"], w, "id") != static_cast<long long>(k))
      in.fail(w, "field 'id' must be the joint's position, " + std::to_string(k));
    const ojson& b = in.need(jj, w, "blocks");
    if (!b.is_array() || b.size() != 2) in.fail(w, "field 'blocks' must be [block id, block id]");
    JointInfo ji;
    ji.i = in.block(b[0], w, "blocks");
    ji.j = in.block(b[1], w, "blocks");
    if (ji.i == ji.j) in.fail(w, "field 'blocks' names one block twice");
    ji.a = in.vec(jj, w, "a");
    ji.b = in.vec(jj, w, "b");
    out.push_back(ji);
  }
  return out;
}

StepRecord read_step(const Reader& in, const ojson& js, const std::string& w) {
  in.only(js, w, {"step",      "d",        "energy",         "open_corners", "cracked",     "reactions", "poses",     "forces",
                  "settled",   "hold_end", "bracket",        "cycles",       "move_cycles", "lag",       "hold_time", "unbalanced_ratio",
                  "max_speed", "drift",    "contact_points", "max_overlap",  "cap_travel",  "lp_primal", "lp_dual",   "held_corners",
                  "sliding"});
  StepRecord s;
  const long long index = in.integer(in.need(js, w, "step"), w, "step");
  if (index < 0 || index > std::numeric_limits<int>::max()) in.fail(w, "field 'step' must be a step index, 0 or more");
  s.index = static_cast<int>(index);
  s.d = in.number(in.need(js, w, "d"), w, "d");
  s.energy = in.maybe(js, w, "energy", kNaN);
  const ojson& oc = in.array(js, w, "open_corners");
  for (size_t k = 0; k < oc.size(); ++k) {
    const std::string wk = item(member(w, "open_corners"), k);
    in.only(oc[k], wk, {"joint", "corner", "gap"});
    s.open_corners.push_back({in.joint(oc[k], wk), in.corner(oc[k], wk), in.maybe(oc[k], wk, "gap", kNaN)});
  }
  const ojson& cracked = in.array(js, w, "cracked");
  for (size_t k = 0; k < cracked.size(); ++k) {
    const long long j = in.integer(cracked[k], w, "cracked");
    if (j < 0 || j >= in.joints)
      in.fail(w, "field 'cracked': joint " + std::to_string(j) + " is not one of the file's " + std::to_string(in.joints) + " joints");
    s.cracked.push_back(static_cast<int>(j));
  }
  const ojson& re = in.array(js, w, "reactions");
  for (size_t k = 0; k < re.size(); ++k) {
    const std::string wk = item(member(w, "reactions"), k);
    in.only(re[k], wk, {"support", "force", "moment"});
    Reaction x;
    const int b = in.block(in.need(re[k], wk, "support"), wk, "support");
    if (!in.c.blocks[b].support) in.fail(wk, "field 'support': block \"" + printable(in.c.blocks[b].id) + "\" is not a support of the case");
    x.support = in.c.blocks[b].id;
    x.force = in.vec(re[k], wk, "force");
    x.moment = in.maybe(re[k], wk, "moment", kNaN);
    s.reactions.push_back(x);
  }
  s.poses = in.poses(in.array(js, w, "poses"), w, "poses");
  const ojson& fo = in.array(js, w, "forces");
  for (size_t k = 0; k < fo.size(); ++k) {
    const std::string wk = item(member(w, "forces"), k);
    in.only(fo[k], wk, {"joint", "normal", "shear", "point", "n"});
    JointForce f;
    f.joint = in.joint(fo[k], wk);
    f.normal = in.maybe(in.need(fo[k], wk, "normal"), wk, "normal");
    f.shear = in.maybe(fo[k], wk, "shear", 0.0);
    f.point = in.vec(fo[k], wk, "point");
    f.n = in.vec(fo[k], wk, "n");
    s.forces.push_back(f);
  }
  if (js.contains("settled")) s.settled = in.boolean(js, w, "settled", true);
  if (js.contains("hold_end")) {
    DemHold& h = s.hold.emplace();
    h.hold_end = in.hold_end(js["hold_end"], w, "hold_end");
    h.bracket = in.boolean(js, w, "bracket", false);
    h.cycles = in.integer(js, w, "cycles", 0);
    h.move_cycles = in.integer(js, w, "move_cycles", 0);
    h.lag = in.maybe(js, w, "lag", kNaN);
    h.hold_time = in.maybe(js, w, "hold_time", kNaN);
    h.unbalanced_ratio = in.maybe(js, w, "unbalanced_ratio", kNaN);
    h.max_speed = in.maybe(js, w, "max_speed", kNaN);
    h.drift = in.maybe(js, w, "drift", kNaN);
    h.contact_points = in.integer(js, w, "contact_points", 0);
    h.max_overlap = in.maybe(js, w, "max_overlap", kNaN);
    if (js.contains("cap_travel")) {
      const std::string wc = member(w, "cap_travel");
      const ojson& x = js["cap_travel"];
      in.only(x, wc, {"first_half", "second_half"});
      h.cap_travel = CapTravel{in.maybe(in.need(x, wc, "first_half"), wc, "first_half"), in.maybe(in.need(x, wc, "second_half"), wc, "second_half")};
    }
  } else {
    for (const char* k : {"bracket", "cycles", "move_cycles", "lag", "hold_time", "unbalanced_ratio", "max_speed", "drift", "contact_points",
                          "max_overlap", "cap_travel"})
      if (js.contains(k)) in.fail(w, std::string("field '") + k + "' is one of the DEM hold's fields, which go with 'hold_end'");
  }
  if (js.contains("lp_primal") != js.contains("lp_dual")) in.fail(w, "fields 'lp_primal' and 'lp_dual' go together");
  if (js.contains("lp_primal")) s.lp = LpOptima{in.maybe(js["lp_primal"], w, "lp_primal"), in.maybe(js["lp_dual"], w, "lp_dual")};
  const ojson& held = in.array(js, w, "held_corners");
  for (size_t k = 0; k < held.size(); ++k) {
    const std::string wk = item(member(w, "held_corners"), k);
    in.only(held[k], wk, {"corner", "force"});
    s.held_corners.push_back({in.text(in.need(held[k], wk, "corner"), wk, "corner"), in.maybe(in.need(held[k], wk, "force"), wk, "force")});
  }
  if (js.contains("sliding")) {
    const std::string wk = member(w, "sliding");
    const ojson& x = js["sliding"];
    in.only(x, wk, {"demand_angle", "demand_joint", "required_angle", "required_joint"});
    s.sliding = SlidingCheck{in.maybe(in.need(x, wk, "demand_angle"), wk, "demand_angle"),
                             static_cast<int>(in.integer(in.need(x, wk, "demand_joint"), wk, "demand_joint")),
                             in.maybe(in.need(x, wk, "required_angle"), wk, "required_angle"),
                             static_cast<int>(in.integer(in.need(x, wk, "required_joint"), wk, "required_joint"))};
  }
  return s;
}

Timing read_timing(const Reader& in, const ojson& t) {
  const std::string w = "timing";
  in.only(t, w, {"total_s", "lp_s", "lp_solves", "kept_basis_solves", "interior_solves", "basis_evaluations", "cycles"});
  Timing out;
  out.total_s = in.maybe(t, w, "total_s", kNaN);
  out.lp_s = in.maybe(t, w, "lp_s", 0.0);
  out.lp_solves = in.integer(t, w, "lp_solves", 0);
  out.kept_basis_solves = in.integer(t, w, "kept_basis_solves", 0);
  out.interior_solves = in.integer(t, w, "interior_solves", 0);
  out.basis_evaluations = in.integer(t, w, "basis_evaluations", 0);
  out.cycles = in.integer(t, w, "cycles", 0);
  return out;
}

std::vector<CornerRef> read_corners(const Reader& in, const ojson& arr, const std::string& where, const RunResult* r) {
  std::vector<CornerRef> out;
  for (size_t k = 0; k < arr.size(); ++k) {
    const std::string wk = item(where, k);
    in.only(arr[k], wk, {"joint", "corner", "blocks"});
    const CornerRef x{in.joint(arr[k], wk), in.corner(arr[k], wk)};
    if (r && arr[k].contains("blocks")) {
      const ojson& b = arr[k]["blocks"];
      const JointInfo& f = r->joints[x.joint];
      if (!b.is_array() || b.size() != 2 || in.block(b[0], wk, "blocks") != f.i || in.block(b[1], wk, "blocks") != f.j)
        in.fail(wk, "field 'blocks' must be the blocks of joint " + std::to_string(x.joint) + " (field 'joints')");
    }
    out.push_back(x);
  }
  return out;
}

void read_prd_fields(const Reader& in, const ojson& j, RunResult& r) {
  if (j.contains("events")) {
    r.events.emplace();
    const ojson& ev = in.array(j, "results", "events");
    for (size_t k = 0; k < ev.size(); ++k) {
      const std::string w = item("events", k);
      in.only(ev[k], w, {"kind", "d", "within", "joints"});
      Event e;
      const std::string kind = in.text(in.need(ev[k], w, "kind"), w, "kind");
      if (kind == "open")
        e.kind = EventKind::open;
      else if (kind == "close")
        e.kind = EventKind::close;
      else if (kind == "collapse")
        e.kind = EventKind::collapse;
      else
        in.fail(w, "field 'kind' must be open, close or collapse");
      e.d = in.maybe(in.need(ev[k], w, "d"), w, "d");
      e.within = in.maybe(ev[k], w, "within", kNaN);
      e.corners = read_corners(in, in.array(ev[k], w, "joints"), member(w, "joints"), &r);
      r.events->push_back(std::move(e));
    }
  }
  if (j.contains("collapse")) {
    const std::string w = "collapse";
    const ojson& x = j["collapse"];
    in.only(x, w, {"open_corners", "moving_blocks", "d", "poses", "moved_poses"});
    Collapse col;
    col.mechanism.open_corners = read_corners(in, in.array(x, w, "open_corners"), member(w, "open_corners"), nullptr);
    for (const ojson& b : in.array(x, w, "moving_blocks")) col.mechanism.moving_blocks.push_back(in.block(b, w, "moving_blocks"));
    col.d = in.maybe(x, w, "d", kNaN);
    col.poses = in.poses(in.array(x, w, "poses"), w, "poses");
    if (x.contains("moved_poses")) col.moved_poses = in.poses(in.array(x, w, "moved_poses"), w, "moved_poses");
    r.collapse = std::move(col);
  }
}

void read_dem_fields(const Reader& in, const ojson& j, RunResult& r) {
  if (j.contains("wall_s")) r.wall_s = in.maybe(j["wall_s"], "results", "wall_s");
  if (j.contains("collapse_bracket")) {
    const std::string w = "collapse_bracket";
    const ojson& x = j["collapse_bracket"];
    in.only(x, w, {"equilibrium", "failed", "width", "trials"});
    CollapseBracket b;
    b.equilibrium = in.maybe(in.need(x, w, "equilibrium"), w, "equilibrium");
    b.failed = in.maybe(in.need(x, w, "failed"), w, "failed");
    b.width = in.maybe(in.need(x, w, "width"), w, "width");
    const ojson& trials = in.array(x, w, "trials");
    for (size_t k = 0; k < trials.size(); ++k) {
      const std::string wk = item(member(w, "trials"), k);
      in.only(trials[k], wk, {"d", "end", "cycles", "confirm", "followed"});
      b.trials.push_back({in.maybe(in.need(trials[k], wk, "d"), wk, "d"), in.hold_end(in.need(trials[k], wk, "end"), wk, "end"),
                          in.integer(trials[k], wk, "cycles", 0), in.boolean(trials[k], wk, "confirm", false),
                          in.boolean(trials[k], wk, "followed", false)});
    }
    r.collapse_bracket = std::move(b);
  }
  r.limit_point = in.boolean(j, "results", "limit_point", false);
  const ojson& un = in.array(j, "results", "unconfirmed_failures");
  for (size_t k = 0; k < un.size(); ++k) {
    const std::string w = item("unconfirmed_failures", k);
    in.only(un[k], w, {"d", "reached_from", "settled_from"});
    r.unconfirmed_failures.push_back({in.maybe(in.need(un[k], w, "d"), w, "d"), in.maybe(in.need(un[k], w, "reached_from"), w, "reached_from"),
                                      in.maybe(in.need(un[k], w, "settled_from"), w, "settled_from")});
  }
  const ojson& sc = in.array(j, "results", "settled_creeps");
  for (size_t k = 0; k < sc.size(); ++k) {
    const std::string w = item("settled_creeps", k);
    in.only(sc[k], w, {"d", "holds", "time"});
    r.settled_creeps.push_back({in.maybe(in.need(sc[k], w, "d"), w, "d"), static_cast<int>(in.integer(sc[k], w, "holds", 0)),
                                in.maybe(in.need(sc[k], w, "time"), w, "time")});
  }
  const ojson& sn = in.array(j, "results", "settled_snaps");
  for (size_t k = 0; k < sn.size(); ++k) {
    const std::string w = item("settled_snaps", k);
    in.only(sn[k], w, {"d", "from", "drift", "time"});
    r.settled_snaps.push_back({in.maybe(in.need(sn[k], w, "d"), w, "d"), in.maybe(in.need(sn[k], w, "from"), w, "from"),
                               in.maybe(in.need(sn[k], w, "drift"), w, "drift"), in.maybe(in.need(sn[k], w, "time"), w, "time")});
  }
}

std::optional<SlidingSummary> read_sliding(const Reader& in, const ojson& x) {
  const std::string w = "sliding";
  in.only(x, w, {"required_friction_angle", "d", "step", "joint", "max_demand_angle", "demand_d", "demand_joint", "lp_solves"});
  SlidingSummary s;
  s.any = x.contains("required_friction_angle");
  s.lp_solves = in.integer(x, w, "lp_solves", 0);
  if (!s.any) return s;
  s.required_friction_angle = in.maybe(x["required_friction_angle"], w, "required_friction_angle");
  s.d = in.maybe(x, w, "d", kNaN);
  s.step = static_cast<int>(in.integer(x, w, "step", 0));
  s.joint = in.string(x, w, "joint", "");
  s.max_demand_angle = in.maybe(x, w, "max_demand_angle", kNaN);
  s.demand_d = in.maybe(x, w, "demand_d", kNaN);
  s.demand_joint = in.string(x, w, "demand_joint", "");
  return s;
}

// The checks that need the whole file: the steps run forward from step 0, the capacity and
// stable_steps are those of the equilibria among them, and the status agrees with `collapsed`.
void check_consistency(const Reader& in, const RunResult& r, bool has_stable_steps, bool has_collapsed) {
  const std::string u = path_unit(in.c);  // d's unit: rad where every moving support only turns
  for (size_t k = 1; k < r.steps.size(); ++k) {
    const StepRecord &a = r.steps[k - 1], &b = r.steps[k];
    if (b.index != a.index + 1)
      in.fail(item("steps", k),
              "field 'step' = " + std::to_string(b.index) + " after " + std::to_string(a.index) + ": step indices must be consecutive");
    if (b.d < a.d) in.fail(item("steps", k), "field 'd' = " + num(b.d) + " " + u + " is less than the step before (" + num(a.d) + " " + u + "): d never decreases");
  }
  if (!r.steps.empty() && r.steps.front().index != 0)
    in.fail(item("steps", 0), "field 'step' = " + std::to_string(r.steps.front().index) + ": the first record is step 0, the configuration the run starts from");
  // The capacity is a d where the structure stands: from 0 to the last equilibrium recorded (a
  // file of no steps, or of none settled, passed the gate with any capacity). A run with none
  // (a structure that does not stand as drawn) stands nowhere past its start: d = 0, or where
  // PRD was started on another configuration (settings.start.d, `prd --from`; an outside
  // solver's free-form settings do not move the bound).
  const StepRecord* eq = nullptr;
  for (const StepRecord& s : r.steps)
    if (is_equilibrium(r, s)) eq = &s;
  if (eq) {
    const double eps = 1e-9 * std::max(1.0, std::abs(eq->d));
    if (r.capacity < 0 || r.capacity > eq->d + eps)
      in.fail("results", "field 'capacity' = " + num(r.capacity) + " " + u + " is outside [0, the last equilibrium's d = " + num(eq->d) + " " + u +
                             " (step " + std::to_string(eq->index) + ")]: the capacity is a d where the structure stands");
  } else {
    const ojson* start = r.method == "prd" && r.settings.is_object() && r.settings.contains("start") ? &r.settings["start"] : nullptr;
    const double d0 = start && start->is_object() && start->contains("d") && (*start)["d"].is_number() ? (*start)["d"].get<double>() : 0.0;
    if (std::abs(r.capacity - d0) > 1e-9 * std::max(1.0, std::abs(d0)))
      in.fail("results", "field 'capacity' = " + num(r.capacity) + " " + u + ", but no step is an equilibrium: a run that never stands has the capacity of its start, d = " +
                             num(d0) + " " + u);
  }
  if (has_stable_steps) {
    const StepRecord* at = last_equilibrium(r, r.capacity);
    const int expected = at ? at->index : 0;
    if (r.stable_steps != expected)
      in.fail("results", "field 'stable_steps' = " + std::to_string(r.stable_steps) +
                             ", but the last equilibrium at or before the capacity is step " + std::to_string(expected));
  }
  if (has_collapsed && r.collapsed != (r.status == RunStatus::collapse))
    in.fail("results",
            std::string("field 'collapsed' = ") + (r.collapsed ? "true" : "false") + " contradicts 'stopped' = \"" + status_name(r.status) + "\"");
}

}  // namespace

RunResult parse_results(const std::string& text, const Case& c, const std::string& source) {
  // A key given twice is refused, as in a case file: nlohmann keeps the last one silently, and a
  // solver's {"capacity": 0.53, "capacity": 0} went to the gate as 0.
  const ojson j = parse_document<std::runtime_error, ojson>(text, source);
  Reader in(source, c);
  const std::string w = "results";
  in.only(j, w, {"format",       "units",
                 "version",      "method",
                 "case",         "capacity",
                 "stable_steps", "collapsed",
                 "stopped",      "message",
                 "total_weight", "settings",
                 "timing",       "blocks",
                 "joints",       "steps",
                 "events",       "collapse",
                 "wall_s",       "collapse_bracket",
                 "limit_point",  "unconfirmed_failures",
                 "settled_creeps", "settled_snaps", "sliding"});
  const std::string format = in.text(in.need(j, w, "format"), w, "format");
  if (format != "masonry-results/1") in.fail(w, "field 'format' must be \"masonry-results/1\", not \"" + printable(format) + "\"");
  RunResult r;
  r.method = in.text(in.need(j, w, "method"), w, "method");
  if (r.method.empty()) in.fail(w, "field 'method' must name the method (prd, dem, or a solver's own name)");
  r.case_name = in.text(in.need(j, w, "case"), w, "case");
  r.version = in.string(j, w, "version", "");
  in.string(j, w, "units", "");
  r.capacity = in.number(in.need(j, w, "capacity"), w, "capacity");
  const std::string stopped = in.text(in.need(j, w, "stopped"), w, "stopped");
  const std::optional<RunStatus> status = parse_status(stopped);
  if (!status) in.fail(w, "field 'stopped' = \"" + printable(stopped) + "\" is not a run status (running, collapse, max_steps, undecided, error)");
  r.status = *status;
  r.collapsed = in.boolean(j, w, "collapsed", r.status == RunStatus::collapse);
  const long long stable = in.integer(j, w, "stable_steps", 0);
  if (stable < 0 || stable > std::numeric_limits<int>::max()) in.fail(w, "field 'stable_steps' must be a step index, 0 or more");
  r.stable_steps = static_cast<int>(stable);
  r.message = in.string(j, w, "message", "");
  // null (a writer's missing number) is as absent: the case's weight.
  const bool weight_given = j.contains("total_weight") && !j["total_weight"].is_null();
  const std::optional<double> stated_weight = weight_given ? std::optional<double>(in.number(j["total_weight"], w, "total_weight")) : std::nullopt;
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) in.fail(w, "field 'settings' must be a JSON object");
    r.settings = j["settings"];
  }
  if (j.contains("timing"))
    r.timing = read_timing(in, j["timing"]);
  else
    r.timing.total_s = kNaN;
  if (j.contains("blocks")) read_blocks(in, in.array(j, w, "blocks"));
  // Thrusts are compared over the weight, so a weight the file states is checked against the
  // case's (after the blocks, which name another case more plainly): a file of 1e6 N (the
  // case's blocks weigh 2943 N) let reactions of the wrong sign pass a thrust limit, and 1e-300
  // gave differences of 1e288 W.
  r.total_weight = total_weight(c);
  if (stated_weight && !(std::abs(*stated_weight - r.total_weight) <= 1e-6 * std::abs(r.total_weight)))
    in.fail(w, "field 'total_weight' = " + num(*stated_weight) + " N, but the case's dead loads weigh " + num(r.total_weight) +
                   " N: a run of another case (or other densities, gravity or loads)");
  r.joints = read_joints(in, in.array(j, w, "joints"));
  in.joints = static_cast<int>(r.joints.size());
  const ojson& steps = in.need(j, w, "steps");
  if (!steps.is_array()) in.fail(w, "field 'steps' must be an array");
  for (size_t k = 0; k < steps.size(); ++k) r.steps.push_back(read_step(in, steps[k], item("steps", k)));
  read_prd_fields(in, j, r);
  read_dem_fields(in, j, r);
  if (j.contains("sliding")) r.sliding = read_sliding(in, j["sliding"]);
  check_consistency(in, r, j.contains("stable_steps"), j.contains("collapsed"));
  if (!j.contains("stable_steps")) {
    const StepRecord* at = last_equilibrium(r, r.capacity);
    r.stable_steps = at ? at->index : 0;
  }
  return r;
}

RunResult load_results(const std::string& path, const Case& c) {
  std::optional<std::string> text = read_text_or_xz(path);  // the runs under reports/ are results.json.xz
  if (!text) throw std::runtime_error(path + ": cannot read");
  return parse_results(*text, c, path);
}

}  // namespace masonry
