// The results.json reader: the inverse of results.cpp's writer, strict about what does not fit
// the case (every front end and study that reads finished runs back goes through it).
#include <limits>
#include <set>
#include <stdexcept>

#include "model/io.hpp"
#include "model/results.hpp"

namespace masonry {

namespace {

using ojson = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

RunResult parse_results(const std::string& text, const Case& c, const std::string& source) {
  ojson j;
  try {
    j = ojson::parse(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(source + ": not JSON: " + e.what());
  }
  const auto fail = [&](const std::string& what) { return std::runtime_error(source + ": " + what); };
  const auto dbl = [&](const ojson& v, const std::string& field) -> double {
    if (v.is_null()) return kNaN;
    if (!v.is_number()) throw fail(field + ": expected a number");
    return v.get<double>();
  };
  const auto vec = [&](const ojson& v, const std::string& field) -> Vec2 {
    if (!v.is_array() || v.size() != 2) throw fail(field + ": expected [x, y]");
    return Vec2(dbl(v[0], field), dbl(v[1], field));
  };
  const auto block = [&](const ojson& v, const std::string& field) -> int {
    if (!v.is_string()) throw fail(field + ": expected a block id");
    const int b = c.block_index(v.get<std::string>());
    if (b < 0) throw fail(field + ": block \"" + v.get<std::string>() + "\" is not in case \"" + c.name + "\"");
    return b;
  };
  try {
    if (j.value("format", "") != "masonry-results/1") throw fail("format: expected \"masonry-results/1\"");
    RunResult r;
    r.method = j.at("method").get<std::string>();
    r.case_name = j.at("case").get<std::string>();
    r.capacity = dbl(j.at("capacity"), "capacity");
    r.stable_steps = j.value("stable_steps", 0);
    r.collapsed = j.value("collapsed", false);
    const std::string stopped = j.value("stopped", "");
    const std::optional<RunStatus> status = parse_status(stopped);
    if (!status) throw fail("stopped: \"" + stopped + "\" is not a run status (running, collapse, max_steps, undecided, error)");
    r.status = *status;
    r.message = j.value("message", "");
    r.total_weight = dbl(j.at("total_weight"), "total_weight");
    if (j.contains("settings")) r.settings = j["settings"];
    if (j.contains("timing")) {
      const ojson& t = j["timing"];
      r.timing.total_s = t.contains("total_s") ? dbl(t["total_s"], "timing.total_s") : 0.0;
      r.timing.lp_s = t.contains("lp_s") ? dbl(t["lp_s"], "timing.lp_s") : 0.0;
      r.timing.lp_solves = t.value("lp_solves", 0LL);
      r.timing.basis_evaluations = t.value("basis_evaluations", 0LL);
      r.timing.cycles = t.value("cycles", 0LL);
    }
    const ojson& blocks = j.at("blocks");
    if (blocks.size() != c.blocks.size()) throw fail("blocks: " + std::to_string(blocks.size()) + " blocks, the case has " + std::to_string(c.blocks.size()));
    for (size_t b = 0; b < blocks.size(); ++b)
      if (blocks[b].at("id").get<std::string>() != c.blocks[b].id)
        throw fail("blocks[" + std::to_string(b) + "].id: not the case's block \"" + c.blocks[b].id + "\"");
    for (const ojson& jj : j.at("joints")) {
      JointInfo ji;
      ji.i = block(jj.at("blocks").at(0), "joints[].blocks");
      ji.j = block(jj.at("blocks").at(1), "joints[].blocks");
      ji.a = vec(jj.at("a"), "joints[].a");
      ji.b = vec(jj.at("b"), "joints[].b");
      r.joints.push_back(ji);
    }
    const int nj = int(r.joints.size());
    static const std::set<std::string> known{"step",  "d",     "energy", "open_corners", "cracked",
                                             "reactions", "poses", "forces", "sliding"};
    for (const ojson& js : j.at("steps")) {
      StepRecord s;
      s.index = js.at("step").get<int>();
      s.d = dbl(js.at("d"), "steps[].d");
      s.energy = dbl(js.value("energy", ojson(nullptr)), "steps[].energy");
      for (const ojson& o : js.at("open_corners")) {
        OpenCorner oc;
        oc.joint = o.at("joint").get<int>();
        if (oc.joint < 0 || oc.joint >= nj) throw fail("steps[" + std::to_string(s.index) + "].open_corners: joint out of range");
        oc.corner = o.at("corner").get<std::string>() == "B" ? 1 : 0;
        oc.gap = dbl(o.value("gap", ojson(nullptr)), "open_corners[].gap");
        s.open_corners.push_back(oc);
      }
      s.cracked = js.value("cracked", std::vector<int>{});
      for (const ojson& x : js.at("reactions")) {
        Reaction re;
        re.support = x.at("support").get<std::string>();
        re.force = vec(x.at("force"), "reactions[].force");
        re.moment = dbl(x.value("moment", ojson(nullptr)), "reactions[].moment");
        s.reactions.push_back(re);
      }
      for (const ojson& p : js.at("poses")) {
        if (!p.is_array() || p.size() != 3) throw fail("steps[].poses: expected [x, y, angle]");
        s.poses.push_back({dbl(p[0], "poses"), dbl(p[1], "poses"), dbl(p[2], "poses")});
      }
      if (!s.poses.empty() && s.poses.size() != c.blocks.size())
        throw fail("steps[" + std::to_string(s.index) + "].poses: one per block expected");
      for (const ojson& f : js.at("forces")) {
        JointForce jf;
        jf.joint = f.at("joint").get<int>();
        if (jf.joint < 0 || jf.joint >= nj) throw fail("steps[" + std::to_string(s.index) + "].forces: joint out of range");
        jf.normal = dbl(f.at("normal"), "forces[].normal");
        jf.shear = dbl(f.value("shear", ojson(0.0)), "forces[].shear");
        jf.point = vec(f.at("point"), "forces[].point");
        jf.n = vec(f.at("n"), "forces[].n");
        s.forces.push_back(jf);
      }
      if (js.contains("sliding")) {
        const ojson& x = js["sliding"];
        s.sliding = SlidingCheck{dbl(x.at("demand_angle"), "steps[].sliding.demand_angle"), x.at("demand_joint").get<int>(),
                                 dbl(x.at("required_angle"), "steps[].sliding.required_angle"), x.at("required_joint").get<int>()};
      }
      for (auto it = js.begin(); it != js.end(); ++it)
        if (!known.count(it.key())) s.extra[it.key()] = it.value();
      r.steps.push_back(std::move(s));
    }
    // What a solver added beside the common fields (the DEM's collapse_bracket, wall_s, ...)
    // comes back as it was written, as the steps' own extras do.
    static const std::set<std::string> common{"format", "units",  "method", "case",     "capacity", "stable_steps", "collapsed", "stopped",
                                              "message", "total_weight", "settings", "timing", "blocks", "joints", "steps", "sliding"};
    for (auto it = j.begin(); it != j.end(); ++it)
      if (!common.count(it.key())) r.extra[it.key()] = it.value();
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("malformed results: ") + e.what());
  }
}

RunResult load_results(const std::string& path, const Case& c) {
  std::optional<std::string> text = read_text_or_xz(path);  // the runs under reports/ are results.json.xz
  if (!text) throw std::runtime_error(path + ": cannot read");
  return parse_results(*text, c, path);
}

}  // namespace masonry
