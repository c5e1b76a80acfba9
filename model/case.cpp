#include "model/case.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "model/fields.hpp"
#include "model/interfaces.hpp"
#include "model/io.hpp"
#include "model/options.hpp"

namespace masonry {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {
// Ranges of the case's quantities (README, "Case files": ranges), wide enough for any masonry
// structure and narrow enough that every derived quantity stays finite in double precision.
// The options' ranges are their rows' (model/options.cpp).
constexpr double kMaxLength = 1e5;   // m: depths
constexpr double kMaxDensity = 1e5;  // kg/m^3 (the densest element, osmium, is 2.3e4)
constexpr double kMaxForce = 1e12;   // N
constexpr double kMaxRate = 1e3;     // m or rad per m of d
}  // namespace

int Case::block_index(const std::string& id) const {
  for (size_t i = 0; i < blocks.size(); ++i)
    if (blocks[i].id == id) return static_cast<int>(i);
  return -1;
}

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % n];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}

double support_travel_per_d(const SupportMotion& m, const Bounds& scene) {
  const Vec2 outside = (scene.lo - m.about).cwiseMax(m.about - scene.hi).cwiseMax(Vec2(0, 0));
  return m.translation.norm() + std::abs(m.rotation) * (scene.size() + outside.norm());
}

double support_travel_per_d(const Case& c) {
  const Bounds scene = scene_bounds(c);
  double v = 0;
  for (const SupportMotion& m : c.motion.supports) v = std::max(v, support_travel_per_d(m, scene));
  return v;
}

double path_travel_per_d(const Case& c) {
  const double v = support_travel_per_d(c);
  return v > 0 ? v : 1.0;
}

double distance_outside(const std::vector<Vec2>& poly, const Vec2& p) {
  bool inside = false;
  double d = INFINITY;
  for (size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2 &a = poly[i], &b = poly[(i + 1) % n];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) inside = !inside;
    const Vec2 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    d = std::min(d, (a + t * ab - p).norm());
  }
  return inside ? 0.0 : d;
}

Vec2 centroid(const std::vector<Vec2>& p) {
  // Relative to the first vertex, so that blocks far from the origin keep their digits.
  const Vec2 o = p.front();
  double a = 0;
  Vec2 c(0, 0);
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double w = u.x() * v.y() - v.x() * u.y();
    a += w;
    c += w * (u + v);
  }
  return o + c / (3.0 * a);
}

double polar_moment(const std::vector<Vec2>& p) {
  const Vec2 o = centroid(p);
  double ixx = 0, a = 0;
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double w = u.x() * v.y() - v.x() * u.y();
    a += w;
    ixx += w * (u.squaredNorm() + u.dot(v) + v.squaredNorm());
  }
  // Orientation-independent: both sums change sign together.
  return std::abs(ixx / 12.0);
}

Bounds bounds(const std::vector<Vec2>& points) {
  Bounds b;
  for (const Vec2& p : points) b.add(p);
  return b;
}

Bounds scene_bounds(const Case& c) {
  Bounds b;
  for (const Block& k : c.blocks)
    for (const Vec2& v : k.vertices) b.add(v);
  return b;
}

double scene_size(const Case& c) { return scene_bounds(c).size(); }

std::string path_unit(const Case& c) {
  bool turns = false;
  for (const SupportMotion& m : c.motion.supports) {
    if (m.translation.x() != 0 || m.translation.y() != 0) return "m";
    turns = turns || m.rotation != 0;
  }
  return turns ? "rad" : "m";
}

double block_mass(const Block& b) { return b.density * std::abs(signed_area(b.vertices)) * b.depth; }

Vec2 dead_load_resultant(const Case& c) {
  Vec2 f(0, 0);
  for (const Block& b : c.blocks)
    if (!b.support) f.y() -= block_mass(b) * c.gravity;
  for (const Load& l : c.loads) f += l.force;
  return f;
}

double total_weight(const Case& c) { return -dead_load_resultant(c).y(); }

std::string printable(const std::string& text, size_t max) {
  std::string out;
  size_t n = std::min(text.size(), max);
  // Cut before a character, never inside one: a UTF-8 continuation byte is 10xxxxxx.
  while (n < text.size() && n > 0 && (static_cast<unsigned char>(text[n]) & 0xc0) == 0x80) --n;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char ch = static_cast<unsigned char>(text[i]);
    if (ch < 0x20 || ch == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", ch);
      out += b;
    } else {
      out += static_cast<char>(ch);
    }
  }
  if (text.size() > max) out += "... (" + std::to_string(text.size()) + " characters)";
  return out;
}

std::string id_fault(const std::string& id) {
  for (const char sep : {'/', ':'})
    if (id.find(sep) != std::string::npos)
      return std::string("holds '") + sep + "', which an id may not (joints are named BLOCK/BLOCK and their corners BLOCK/BLOCK:A)";
  return "";
}

namespace {

// The case format's reader: the shared strict field checks (model/fields.hpp), and what only a
// case has (points, block references).
struct Reader : FieldReader<CaseError, json> {
  Vec2 point(const json& v, const std::string& where, const std::string& field) const {
    if (!v.is_array() || v.size() != 2) fail(where, "field '" + field + "' must be [x, y]");
    return Vec2(number(v[0], where, field), number(v[1], where, field));
  }

  int block_ref(const Case& c, const json& obj, const std::string& where) const {
    auto it = obj.find("block");
    if (it == obj.end() || !it->is_string()) fail(where, "field 'block' must name a block");
    const int b = c.block_index(it->get<std::string>());
    if (b < 0) fail(where, "field 'block': no block '" + printable(it->get<std::string>()) + "'");
    return b;
  }
};

// Tolerances and steps against the scene (the options' SceneRange): below 1e-9 of the scene size a
// length is lost in the round-off of the coordinates; a contact tolerance above a tenth of it makes
// every block touch. A collapse drift below 1e-4 of the scene is not evidence of a collapse: the
// elastic settling under gravity and a hinge snapping to its neighbouring joint move blocks that
// far (the pointed arch's hinge passing near d = 0.094 m: 8.4 mm, 0.4% of it), and 1e-9 of the scene made the settling itself
// a collapse. Derived quantities must be finite before any step.
void check_scales(const Case& c, const Reader& r) {
  const Bounds scene = scene_bounds(c);
  const double L = scene.size();
  if (!(std::isfinite(L) && L > 0)) r.fail("blocks", "the scene has no finite size");
  // The step against the scene: what a support point travels per step, its translation plus
  // its turn times the scene size (so an angular step counts as the arc it turns the scene
  // through, whatever the scene's size), 1e-9 to 1 times the scene size.
  const double per_step = c.motion.step * support_travel_per_d(c);
  if (c.motion.step > 0 && per_step > 0 && !(per_step >= kFinestFraction * L && per_step <= L)) {
    std::ostringstream m;
    m << "field 'step' = " << c.motion.step << " " << path_unit(c) << " moves a support point by " << per_step << " m per step, outside ["
      << kFinestFraction * L << ", " << L << "] m for a scene of " << L << " m (1e-9 to 1 times the scene size)";
    r.fail("motion", m.str());
  }
  check_scene_options(c.motion, L, r.source);
  check_scene_options(c.prd, L, r.source);
  check_scene_options(c.dem, L, r.source);
  // The weight and what the supports travel over the run: finite, so energies and ratios are.
  double W = 0;
  for (const Block& b : c.blocks)
    if (!b.support) W += block_mass(b) * c.gravity;
  if (!std::isfinite(W)) r.fail("blocks", "the total weight is not a finite number");
  const Vec2 P = dead_load_resultant(c);
  if (!(P.norm() > 0)) r.fail("case", "field 'gravity': nothing loads the structure (gravity 0 and no loads)");
  for (const SupportMotion& m : c.motion.supports) {
    const double travel = c.motion.step * c.motion.max_steps * support_travel_per_d(m, scene);
    if (!std::isfinite(travel) || travel > kMaxCoordinate)
      r.fail("motion of block '" + printable(c.blocks[m.block].id) + "'", "the support would travel beyond 1e5 m over max_steps");
  }
}

// Why a free block has no joint: it comes within the contact tolerance of another block only at
// a point or over less than the tolerance (a corner on a face; a block no wider than the
// tolerance standing on its end), or it touches nothing.
std::string no_joint_reason(const Case& c, size_t i, double tol) {
  const std::vector<Vec2>& vi = c.blocks[i].vertices;
  const Bounds bi = bounds(vi);
  for (size_t j = 0; j < c.blocks.size(); ++j) {
    const std::vector<Vec2>& vj = c.blocks[j].vertices;
    const Bounds bj = bounds(vj);
    if (j == i || (bi.lo - bj.hi).maxCoeff() > tol || (bj.lo - bi.hi).maxCoeff() > tol) continue;
    double gap = INFINITY;
    for (const Vec2& p : vi) gap = std::min(gap, distance_to_boundary(p, vj));
    for (const Vec2& p : vj) gap = std::min(gap, distance_to_boundary(p, vi));
    if (gap > tol) continue;
    std::ostringstream m;
    m << "the block meets block '" << printable(c.blocks[j].id) << "' only at a point or over less than the contact tolerance (" << tol
      << " m, prd.contact_tolerance), and a joint is two edges overlapping by more than that (the block is " << bi.extent().x() << " by "
      << bi.extent().y() << " m)";
    return m.str();
  }
  return "the block touches no other block";
}

}  // namespace

Case parse_case(const std::string& text, const std::string& source) {
  const json doc = parse_document<CaseError>(text, source);
  Reader r{source};
  Case c;
  c.source = source;
  read_options(doc, c, source, {"format", "name", "description", "blocks", "loads", "motion", "prd", "dem"});
  if (!doc.contains("format")) r.fail("case", "field 'format' is required (\"masonry-case/1\")");
  const std::string format = r.string(doc, "case", "format", "");
  if (format != "masonry-case/1") r.fail("case", "field 'format': expected \"masonry-case/1\", got \"" + printable(format) + "\"");
  c.name = r.string(doc, "case", "name", source);
  c.description = r.string(doc, "case", "description", "");

  if (!doc.contains("blocks") || !doc["blocks"].is_array() || doc["blocks"].empty()) r.fail("case", "field 'blocks' must be a non-empty array");
  std::set<std::string> ids;
  for (size_t i = 0; i < doc["blocks"].size(); ++i) {
    const json& jb = doc["blocks"][i];
    std::string where = "block #" + std::to_string(i);
    if (jb.is_object() && jb.contains("id") && jb["id"].is_string()) where = "block '" + printable(jb["id"].get<std::string>()) + "'";
    r.only(jb, where, {"id", "vertices", "depth", "density", "support"});
    Block b;
    if (!jb.contains("id") || !jb["id"].is_string() || jb["id"].get<std::string>().empty()) r.fail(where, "field 'id' must be a non-empty string");
    b.id = jb["id"].get<std::string>();
    if (const std::string fault = id_fault(b.id); !fault.empty())
      r.fail("block #" + std::to_string(i) + " '" + printable(b.id) + "'", "field 'id' " + fault);
    if (!ids.insert(b.id).second) r.fail(where, "field 'id': duplicate id");
    if (!jb.contains("vertices") || !jb["vertices"].is_array()) r.fail(where, "field 'vertices' must be an array of [x, y]");
    for (const json& v : jb["vertices"]) {
      b.vertices.push_back(r.point(v, where, "vertices"));
      r.range(b.vertices.back().cwiseAbs().maxCoeff(), 0, kMaxCoordinate, where, "vertices", "m (|x|, |y|)");
    }
    if (jb.contains("support")) {
      if (!jb["support"].is_boolean()) r.fail(where, "field 'support' must be true or false");
      b.support = jb["support"].get<bool>();
    }
    b.depth = r.number(jb, where, "depth", 1.0);
    r.range(b.depth, 0, kMaxLength, where, "depth", "m", true);
    if (!b.support) {
      if (!jb.contains("density")) r.fail(where, "field 'density' is required for a non-support block");
      b.density = r.number(jb["density"], where, "density");
      r.range(b.density, 0, kMaxDensity, where, "density", "kg/m^3", true);
    } else {
      b.density = r.number(jb, where, "density", 0.0);
      r.range(b.density, 0, kMaxDensity, where, "density", "kg/m^3");
    }
    c.blocks.push_back(std::move(b));
  }

  if (doc.contains("loads")) {
    if (!doc["loads"].is_array()) r.fail("loads", "must be an array");
    for (size_t i = 0; i < doc["loads"].size(); ++i) {
      const json& jl = doc["loads"][i];
      const std::string where = "load #" + std::to_string(i);
      r.only(jl, where, {"block", "force", "point"});
      Load l;
      l.block = r.block_ref(c, jl, where);
      if (c.blocks[l.block].support) r.fail(where, "field 'block': '" + printable(c.blocks[l.block].id) + "' is a support; loads go on free blocks");
      if (!jl.contains("force")) r.fail(where, "field 'force' is required");
      l.force = r.point(jl["force"], where, "force");
      r.range(l.force.norm(), 0, kMaxForce, where, "force", "N (magnitude)");
      l.point = jl.contains("point") ? r.point(jl["point"], where, "point") : centroid(c.blocks[l.block].vertices);
      r.range(l.point.cwiseAbs().maxCoeff(), 0, kMaxCoordinate, where, "point", "m (|x|, |y|)");
      // A load acts at a material point of its block: a point off it (a mistyped coordinate
      // carried the block's load on a lever 5 m long and moved a capacity by a third) is refused.
      // On the outline within a millionth of the block's size counts as on it.
      const std::vector<Vec2>& poly = c.blocks[l.block].vertices;
      const double off = distance_outside(poly, l.point);
      if (off > 1e-6 * bounds(poly).size()) {
        std::ostringstream m;
        m << "field 'point' (" << l.point.x() << ", " << l.point.y() << ") m lies " << off << " m outside block '"
          << printable(c.blocks[l.block].id) << "': a load acts at a point of its block";
        r.fail(where, m.str());
      }
      c.loads.push_back(l);
    }
  }

  if (doc.contains("motion")) {
    const json& jm = doc["motion"];
    read_options(jm, c.motion, source, {"supports"});
    if (jm.contains("supports")) {
      if (!jm["supports"].is_array()) r.fail("motion", "field 'supports' must be an array");
      std::set<int> seen;
      for (size_t i = 0; i < jm["supports"].size(); ++i) {
        const json& js = jm["supports"][i];
        std::string where = "motion.supports #" + std::to_string(i);
        r.only(js, where, {"block", "translation", "rotation", "about"});
        SupportMotion s;
        s.block = r.block_ref(c, js, where);
        where = "motion of block '" + printable(c.blocks[s.block].id) + "'";
        if (!c.blocks[s.block].support) r.fail(where, "field 'block': not a support block (add \"support\": true)");
        if (!seen.insert(s.block).second) r.fail(where, "field 'block': motion given twice");
        if (js.contains("translation")) s.translation = r.point(js["translation"], where, "translation");
        r.range(s.translation.norm(), 0, kMaxRate, where, "translation", "m per m of d (magnitude)");
        s.rotation = r.number(js, where, "rotation", 0.0);
        r.range(std::abs(s.rotation), 0, kMaxRate, where, "rotation", "rad per m of d (magnitude)");
        s.about = js.contains("about") ? r.point(js["about"], where, "about") : centroid(c.blocks[s.block].vertices);
        r.range(s.about.cwiseAbs().maxCoeff(), 0, kMaxCoordinate, where, "about", "m (|x|, |y|)");
        c.motion.supports.push_back(s);
      }
    }
  }

  if (doc.contains("prd")) read_options(doc["prd"], c.prd, source);
  if (doc.contains("dem")) read_options(doc["dem"], c.dem, source);

  // Orientation: store counter-clockwise.
  for (Block& b : c.blocks)
    if (b.vertices.size() >= 3 && signed_area(b.vertices) < 0) std::reverse(b.vertices.begin(), b.vertices.end());

  validate_geometry(c);

  bool any_support = false, any_free = false;
  for (const Block& b : c.blocks) {
    any_support = any_support || b.support;
    any_free = any_free || !b.support;
  }
  if (!any_support) r.fail("blocks", "no support block (mark at least one with \"support\": true)");
  if (!any_free) r.fail("blocks", "no free block: every block is a support");
  check_scales(c, r);

  // Every free block must touch something, or it would fall through any method.
  const std::vector<Interface> ifs = detect_interfaces(c, c.prd.contact_tolerance);
  std::vector<char> touched(c.blocks.size(), 0);
  for (const Interface& f : ifs) touched[f.i] = touched[f.j] = 1;
  for (size_t i = 0; i < c.blocks.size(); ++i)
    if (!touched[i] && !c.blocks[i].support)
      r.fail("block '" + printable(c.blocks[i].id) + "'", "field 'vertices': " + no_joint_reason(c, i, c.prd.contact_tolerance));
  return c;
}

Case load_case(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw CaseError(path + ": a directory, not a case file (masonry-case/1 JSON; `compare CASE --runs DIR DIR` takes the case first)");
  const std::optional<std::string> text = read_text(path);
  if (!text) throw CaseError(path + ": cannot open the case file");
  return parse_case(*text, path);
}

std::string case_to_json(const Case& c) {
  ordered_json doc = ordered_json::object();
  doc["format"] = "masonry-case/1";
  doc["name"] = c.name;
  if (!c.description.empty()) doc["description"] = c.description;
  write_options(doc, c);
  ordered_json blocks = ordered_json::array();
  for (const Block& b : c.blocks) {
    ordered_json jb = ordered_json::object();
    jb["id"] = b.id;
    ordered_json vs = ordered_json::array();
    for (const Vec2& v : b.vertices) vs.push_back({v.x(), v.y()});
    jb["vertices"] = vs;
    jb["depth"] = b.depth;
    if (b.support) {
      jb["support"] = true;
    } else {
      jb["density"] = b.density;
    }
    blocks.push_back(jb);
  }
  doc["blocks"] = blocks;
  if (!c.loads.empty()) {
    ordered_json loads = ordered_json::array();
    for (const Load& l : c.loads)
      loads.push_back({{"block", c.blocks[l.block].id}, {"force", {l.force.x(), l.force.y()}}, {"point", {l.point.x(), l.point.y()}}});
    doc["loads"] = loads;
  }
  ordered_json sup = ordered_json::array();
  for (const SupportMotion& s : c.motion.supports)
    sup.push_back({{"block", c.blocks[s.block].id},
                   {"translation", {s.translation.x(), s.translation.y()}},
                   {"rotation", s.rotation},
                   {"about", {s.about.x(), s.about.y()}}});
  ordered_json motion = ordered_json::object(), prd = ordered_json::object(), dem = ordered_json::object();
  write_options(motion, c.motion);
  motion["supports"] = sup;
  write_options(prd, c.prd);
  write_options(dem, c.dem);
  doc["motion"] = motion;
  doc["prd"] = prd;
  doc["dem"] = dem;
  return doc.dump(1, ' ') + "\n";
}

Case with_option(const Case& c, const std::string& key, const nlohmann::json& value) {
  const std::string source = c.source + " [" + printable(key) + "=" + printable(value.dump()) + "]";
  nlohmann::json doc = nlohmann::json::parse(case_to_json(c));
  // Walk the dotted path through objects; the last name may be new (an optional field such as
  // dem.kn), the loader rejects names it does not know.
  nlohmann::json* at = &doc;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    const std::string name = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (name.empty()) throw CaseError(source + ": option: empty name in '" + key + "'");
    if (name == "blocks" || name == "loads" || name == "format")
      throw CaseError(source + ": option: '" + name + "' is not an option (only scalar settings can be varied)");
    if (dot == std::string::npos) {
      if (!at->is_object()) throw CaseError(source + ": option: '" + key + "' does not name a field");
      (*at)[name] = value;
      break;
    }
    if (!at->is_object() || !at->contains(name) || !(*at)[name].is_object())
      throw CaseError(source + ": option: '" + key + "': no section '" + name + "'");
    at = &(*at)[name];
    start = dot + 1;
  }
  return parse_case(doc.dump(), source);
}

const char* hold_damping_name(HoldDamping h) { return kHoldDampingNames[static_cast<size_t>(h)]; }

void check_dem_options(const DemOptions& d, const std::string& source, bool allow_unstable_timestep) {
  check_options(d, source, allow_unstable_timestep);
}

}  // namespace masonry
