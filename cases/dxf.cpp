// import_dxf, as named stages: read the drawing (cases/dxf_reader.hpp), turn polylines into polygons in metres
// (units, arcs by chords), name the blocks and give them their layer's properties, snap drafting
// gaps, assemble the case (with the merged fragment) and check it with the case loader.
#include "cases/dxf.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cases/dxf_reader.hpp"
#include "model/fields.hpp"
#include "model/interfaces.hpp"
#include "model/io.hpp"
#include "model/options.hpp"
#include "report/format.hpp"

namespace masonry {

namespace {

using json = nlohmann::json;

bool layer_is(const std::string& layer, const char* prefix) {
  const size_t n = std::strlen(prefix);
  if (layer.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(layer[i])) != prefix[i]) return false;
  return true;
}
bool ignored_layer(const std::string& layer) { return layer_is(layer, "ignore") || layer_is(layer, "defpoints"); }

// Stage 2: metres per drawing unit.
double unit_scale(const std::string& path, const std::string& option, int insunits) {
  static const std::map<std::string, double> names = {{"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"in", 0.0254}, {"ft", 0.3048}};
  if (!option.empty()) {
    auto it = names.find(option);
    if (it == names.end()) throw CaseError(path + ": --units '" + printable(option) + "': one of m, cm, mm, in, ft");
    return it->second;
  }
  switch (insunits) {
    case 1: return 0.0254;
    case 2: return 0.3048;
    case 4: return 0.001;
    case 5: return 0.01;
    case 6: return 1.0;
    case -1:
    case 0: throw CaseError(path + ": the drawing does not say its units ($INSUNITS): give --units m, cm, mm, in or ft");
    default: throw CaseError(path + ": $INSUNITS = " + std::to_string(insunits) + " is not a unit the import knows: give --units");
  }
}

// Beyond these a drawing is a drafting error, not masonry: an arc of more chords, or more
// vertices in all, than any structure needs (each costs memory and time in every check).
constexpr double kMaxChordsPerArc = 1e5;
constexpr size_t kMaxVertices = 10'000'000;

// An edge from p to q with DXF bulge b (tan of a quarter of the included angle, positive
// counter-clockwise), replaced by chords no farther than `tol` from the arc; p included, q not.
// False, with nothing appended, where that takes more than kMaxChordsPerArc chords.
bool append_arc(std::vector<Vec2>& out, const Vec2& p, const Vec2& q, double bulge, double tol) {
  const double chord = (q - p).norm();
  // The arc's height over its chord is |bulge| x half the chord: within the tolerance, one chord.
  if (!(std::abs(bulge) * chord / 2 > tol)) {
    out.push_back(p);
    return true;
  }
  const double theta = 4 * std::atan(bulge);  // included angle, signed
  const double r = chord / (2 * std::sin(std::abs(theta) / 2));
  // Chords of angle a keep within r (1 - cos(a/2)) = 2 r sin^2(a/4) of the arc.
  const double a_max = 4 * std::asin(std::min(1.0, std::sqrt(tol / (2 * r))));
  const double chords = std::ceil(std::abs(theta) / a_max);
  if (!(chords <= kMaxChordsPerArc)) return false;
  const Vec2 mid = 0.5 * (p + q), dir = (q - p) / chord;
  const Vec2 left = perp(dir);
  // The centre lies r cos(theta/2) to the left of p->q for a counter-clockwise arc (to the right
  // beyond a half circle, where the cosine turns negative), mirrored for a clockwise one.
  const Vec2 centre = mid + (theta > 0 ? 1.0 : -1.0) * r * std::cos(std::abs(theta) / 2) * left;
  const int n = std::max(1, static_cast<int>(chords));
  const double a0 = std::atan2(p.y() - centre.y(), p.x() - centre.x());
  out.push_back(p);
  for (int k = 1; k < n; ++k) {
    const double a = a0 + theta * k / n;
    out.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return true;
}

// One block as imported, with where it came from.
struct Piece {
  std::string id, layer, handle;
  bool support = false;
  double density = 0, depth = 1;
  std::vector<Vec2> v;
  Bounds box;
};

// The pieces by the cells of a uniform grid their boxes, grown by `pad`, overlap: the pieces
// near a point without a pass over all of them (a drawing of 10,000 polylines: naming, snapping
// and the near joints would otherwise be quadratic in the blocks).
class PieceGrid {
 public:
  PieceGrid(const std::vector<Piece>& ps, double pad) {
    Bounds all;
    double sizes = 0;
    for (const Piece& k : ps) {
      all.add(k.box.lo);
      all.add(k.box.hi);
      sizes += k.box.size();
    }
    lo_ = all.lo - Vec2(pad, pad);
    const Vec2 ext = all.extent() + Vec2(2 * pad, 2 * pad);
    // About one cell per piece, and no smaller than a typical piece.
    const double n = static_cast<double>(std::max<size_t>(ps.size(), 1));
    h_ = std::max({std::sqrt(ext.x() * ext.y() / n), sizes / n + 2 * pad, 1e-9 * (ext.maxCoeff() + 1)});
    nx_ = cells(ext.x()), ny_ = cells(ext.y());
    cell_.resize(static_cast<size_t>(nx_) * ny_);
    for (size_t i = 0; i < ps.size(); ++i) {
      const auto [x0, y0] = at(ps[i].box.lo - Vec2(pad, pad));
      const auto [x1, y1] = at(ps[i].box.hi + Vec2(pad, pad));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) cell_[static_cast<size_t>(y) * nx_ + x].push_back(static_cast<int>(i));
    }
  }
  // The pieces whose grown boxes may hold p, in drawing order.
  const std::vector<int>& near(const Vec2& p) const {
    const auto [x, y] = at(p);
    return cell_[static_cast<size_t>(y) * nx_ + x];
  }
  // The pieces whose grown boxes may meet box b, in drawing order.
  std::vector<int> near(const Bounds& b) const {
    const auto [x0, y0] = at(b.lo);
    const auto [x1, y1] = at(b.hi);
    std::vector<int> out;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::vector<int>& c = cell_[static_cast<size_t>(y) * nx_ + x];
        out.insert(out.end(), c.begin(), c.end());
      }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  int cells(double e) const { return static_cast<int>(std::clamp(std::floor(e / h_) + 1, 1.0, 4096.0)); }
  std::pair<int, int> at(const Vec2& p) const {
    const auto c = [&](double v, int n) { return static_cast<int>(std::clamp(std::floor(v / h_), 0.0, n - 1.0)); };
    return {c(p.x() - lo_.x(), nx_), c(p.y() - lo_.y(), ny_)};
  }
  double h_ = 1;
  Vec2 lo_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cell_;
};

struct LayerProps {
  std::optional<double> density, depth;
  std::optional<bool> support;
};

json read_json(const std::string& file, const char* what) {
  const std::optional<std::string> text = read_text(file);
  if (!text) throw CaseError(file + ": cannot open " + what);
  return parse_document<CaseError>(*text, file);
}

std::map<std::string, LayerProps> read_layers(const std::string& file) {
  std::map<std::string, LayerProps> out;
  if (file.empty()) return out;
  const json doc = read_json(file, "the layers file");
  if (!doc.is_object() || !doc.contains("layers") || !doc["layers"].is_object())
    throw CaseError(file + ": must be {\"layers\": {\"NAME\": {\"density\": .., \"depth\": .., \"support\": ..}}}");
  for (auto it = doc["layers"].begin(); it != doc["layers"].end(); ++it) {
    const std::string where = file + ": layer '" + printable(it.key()) + "'";
    if (!it->is_object()) throw CaseError(where + ": must be an object");
    LayerProps p;
    for (auto f = it->begin(); f != it->end(); ++f) {
      if (f.key() == "support" && f->is_boolean())
        p.support = f->get<bool>();
      else if ((f.key() == "density" || f.key() == "depth") && f->is_number())
        (f.key() == "density" ? p.density : p.depth) = f->get<double>();
      else
        throw CaseError(where + ": field '" + printable(f.key()) +
                        "': unknown, or not of its type (density, depth: numbers; support: true or false)");
    }
    out[it.key()] = p;
  }
  return out;
}

// At most this many texts outside every block are listed one by one in the notes; the rest are counted.
constexpr int kStrayTextsListed = 5;

// Stage 3: polygons with their ids and properties; what it noticed goes to `notes`.
std::vector<Piece> blocks_of(const std::string& path, const DxfDrawing& d, double scale, const DxfImportOptions& o, std::vector<std::string>& notes) {
  for (const DxfEntity& e : d.curves)
    if (!ignored_layer(e.layer))
      throw CaseError(path + ": " + printable(e.type) + (e.type == "INSERT" ? " (a block reference: explode it in the drawing)" : "") +
                      " on layer '" + printable(e.layer) + "' (handle " + printable(e.handle) +
                      ") cannot be a block: draw blocks as closed polylines (or put it on a layer named IGNORE)");
  const auto layers = read_layers(o.layers_file);
  std::vector<Piece> out;
  std::map<std::string, int> count;
  size_t vertices = 0;
  for (const DxfPolyline& p : d.polylines) {
    if (ignored_layer(p.e.layer)) continue;
    const std::string where = path + ": layer '" + printable(p.e.layer) + "', entity " + printable(p.e.handle);
    const std::string at = path + ":" + std::to_string(p.e.line) + ": " + p.e.name();
    if (p.mesh) throw CaseError(where + ": a polygon mesh, not a block outline");
    if (p.e.off_plane) throw CaseError(at + ": group codes 210/220/230: drawn in another plane than x-y (only 2D drawings import)");
    if (!p.closed) throw CaseError(where + ": an open polyline: a block must be a closed polyline (set its closed flag)");
    if (p.v.size() < 3) throw CaseError(where + ": a closed polyline of fewer than 3 vertices");
    Piece k;
    k.layer = p.e.layer;
    k.handle = p.e.handle;
    for (const DxfVertex& v : p.v)
      if (!(std::max(std::abs(v.x), std::abs(v.y)) * scale <= kMaxCoordinate))
        throw CaseError(path + ":" + std::to_string(v.line) + ": " + p.e.name() +
                        ": group codes 10/20: a vertex beyond 1e5 m from the origin (README, \"Ranges\"; a drawing unit is " + fmt::g(scale, 6) +
                        " m)");
    for (size_t i = 0; i < p.v.size(); ++i) {
      const DxfVertex &a = p.v[i], &b = p.v[(i + 1) % p.v.size()];
      if (!append_arc(k.v, scale * Vec2(a.x, a.y), scale * Vec2(b.x, b.y), a.bulge, o.arc_tolerance))
        throw CaseError(path + ":" + std::to_string(a.line) + ": " + p.e.name() + ": group code 42 = " + fmt::g(a.bulge, 6) +
                        ": the arc needs more than " + std::to_string(static_cast<long>(kMaxChordsPerArc)) + " chords within --arc-tolerance " +
                        fmt::g(o.arc_tolerance, 6) + " m (a drafting error, or give a larger tolerance)");
    }
    // The closing vertex repeated on the first (some programs write it): drop it.
    if (k.v.size() > 3 && (k.v.front() - k.v.back()).norm() <= 1e-12 * (1 + k.v.front().norm())) k.v.pop_back();
    vertices += k.v.size();
    if (vertices > kMaxVertices)
      throw CaseError(at + ": the drawing's blocks have more than " + std::to_string(kMaxVertices) +
                      " vertices with their arcs as chords (give a larger --arc-tolerance)");
    const auto lp = layers.find(p.e.layer);
    const LayerProps props = lp == layers.end() ? LayerProps{} : lp->second;
    k.support = props.support.value_or(layer_is(p.e.layer, "support"));
    k.depth = props.depth.value_or(o.depth);
    if (!k.support) {
      if (!props.density && !o.density)
        throw CaseError(where +
                        ": the layer follows no convention the import knows: not SUPPORT*, not IGNORE*, and no density "
                        "(give --density or the layer's density in --layers)");
      k.density = props.density ? *props.density : *o.density;
    }
    k.id = printable(p.e.layer, 40) + "-" + std::to_string(++count[p.e.layer]);
    k.box = bounds(k.v);
    out.push_back(std::move(k));
  }
  if (out.empty()) throw CaseError(path + ": no closed polyline on a block layer: nothing to import");
  // A TEXT or MTEXT inside a polygon names its block.
  const PieceGrid grid(out, 0.0);
  std::vector<const DxfText*> named_by(out.size(), nullptr);
  int stray = 0;
  for (const DxfText& t : d.texts) {
    if (ignored_layer(t.e.layer) || t.text.empty()) continue;
    if (t.e.off_plane)
      throw CaseError(path + ":" + std::to_string(t.e.line) + ": " + t.e.name() + ": group codes 210/220/230: drawn in another plane than x-y");
    const Vec2 at = scale * Vec2(t.x, t.y);
    bool inside = false;
    for (const int i : grid.near(at)) {
      Piece& k = out[i];
      if (!(k.box.lo.x() <= at.x() && at.x() <= k.box.hi.x() && k.box.lo.y() <= at.y() && at.y() <= k.box.hi.y()) || !point_in_polygon(at, k.v))
        continue;
      if (named_by[i])
        throw CaseError(path + ": layer '" + printable(k.layer) + "', entity " + printable(k.handle) + ": two texts inside the block ('" +
                        printable(named_by[i]->text) + "' and '" + printable(t.text) + "')");
      named_by[i] = &t;
      k.id = t.text;
      inside = true;
    }
    // A text meant as an id but placed beside its block (the block then gets LAYER-n) is a
    // drafting error the user wants to hear about, as a skipped entity is.
    if (!inside && ++stray <= kStrayTextsListed)
      notes.push_back(printable(t.e.type, 40) + " '" + printable(t.text) + "' at (" + fmt::g(t.x, 6) + ", " + fmt::g(t.y, 6) + ") (handle " +
                      (t.e.handle.empty() ? std::string("none") : printable(t.e.handle, 40)) + ", layer '" + printable(t.e.layer, 80) +
                      "') lies in no block: ignored");
  }
  if (stray > kStrayTextsListed) notes.push_back(std::to_string(stray - kStrayTextsListed) + " more texts lie in no block: ignored");
  // An id the case loader would refuse ('/' or ':' make joint names ambiguous) is refused here,
  // naming the entity that holds it: renaming it for the user would leave the drawing, the
  // fragment that names its blocks and the results calling one block by two names.
  for (size_t i = 0; i < out.size(); ++i) {
    const std::string fault = id_fault(out[i].id);
    if (fault.empty()) continue;
    const std::string block = "(the block of layer '" + printable(out[i].layer) + "', entity " + printable(out[i].handle) + ")";
    if (named_by[i])
      throw CaseError(path + ":" + std::to_string(named_by[i]->e.line) + ": " + named_by[i]->e.name() + ": the id '" + printable(out[i].id) +
                      "' it gives " + block + " " + fault + ": rename it in the drawing");
    throw CaseError(path + ": layer '" + printable(out[i].layer) + "', entity " + printable(out[i].handle) + ": the id '" + printable(out[i].id) +
                    "' made from the layer's name " + fault + ": rename the layer, or name the block by a text inside it");
  }
  return out;
}

// Stage 4: drafting gaps. A vertex within `snap` of another block's vertex goes onto it, else
// within `snap` of another block's edge onto the edge.
int snap_pieces(std::vector<Piece>& ps, double snap) {
  if (!(snap > 0)) return 0;
  int moved = 0;
  // Vertices move by at most `snap`, so a piece's vertices stay within its box grown by it.
  const PieceGrid grid(ps, 2 * snap);
  for (size_t i = 0; i < ps.size(); ++i)
    for (Vec2& p : ps[i].v) {
      double best = snap;
      Vec2 target = p;
      bool on_vertex = false;
      for (const int jj : grid.near(p)) {
        const size_t j = static_cast<size_t>(jj);
        if (j == i) continue;
        const auto& q = ps[j].v;
        for (size_t e = 0; e < q.size(); ++e) {
          const double dv = (q[e] - p).norm();
          if (dv <= snap && (!on_vertex || dv < best)) {
            best = dv;
            target = q[e];
            on_vertex = true;
          }
          if (on_vertex) continue;
          const Vec2 &a = q[e], &b = q[(e + 1) % q.size()];
          const double de = distance_to_segment(p, a, b);
          if (de < best) {
            const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            best = de;
            target = a + t * (b - a);
          }
        }
      }
      if (target != p) {
        p = target;
        ++moved;
      }
    }
  return moved;
}

// Vertices that come within `near` of another block without touching it (a gap above the
// contact tolerance) or that poke into it: drafting errors a user wants to hear about.
std::vector<std::string> near_joints(const std::vector<Piece>& ps, double tol, double near) {
  std::vector<std::string> out;
  std::vector<Bounds> box;
  for (const Piece& k : ps) box.push_back(bounds(k.v));
  const PieceGrid grid(ps, near);
  for (size_t i = 0; i < ps.size(); ++i)
    for (const int jj : grid.near(box[i])) {
      const size_t j = static_cast<size_t>(jj);
      if (j <= i) continue;
      if ((box[i].lo - box[j].hi).maxCoeff() > near || (box[j].lo - box[i].hi).maxCoeff() > near) continue;
      // The nearest vertex of either block to the other's outline.
      double gap = INFINITY;
      bool inside = false;
      for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, i}})
        for (const Vec2& p : ps[a].v) {
          const double d = distance_to_boundary(p, ps[b].v);
          if (d < gap) {
            gap = d;
            inside = point_in_polygon(p, ps[b].v);
          }
        }
      if (gap > tol && gap <= near) {
        char b[64];
        std::snprintf(b, sizeof b, "%.3g mm", gap * 1e3);
        out.push_back("blocks '" + printable(ps[i].id) + "' and '" + printable(ps[j].id) +
                      "' almost meet: " + (inside ? "they overlap by " : "a gap of ") + b + " (a drafting error? --snap closes it)");
      }
    }
  return out;
}

// What the import left out, for the notes: LINE entities and other entity types on block layers,
// and whatever stands in paper space.
std::string skipped_note(const DxfDrawing& d) {
  std::map<std::string, int> n;
  int paper = 0;
  for (const DxfEntity& e : d.lines)
    if (!ignored_layer(e.layer)) ++n["LINE"];
  for (const DxfEntity& e : d.skipped) {
    if (e.paper_space)
      ++paper;
    else if (!ignored_layer(e.layer))
      ++n[printable(e.type, 40)];
  }
  std::string s, lower;
  int lowers = 0;
  for (const auto& [type, k] : n) {
    s += (s.empty() ? "" : ", ") + std::to_string(k) + " " + type;
    // The DXF reference writes entity types in upper case, and the reader takes them as written:
    // a 'lwpolyline' is not read as a block, and saying so is the only trace it leaves.
    if (std::any_of(type.begin(), type.end(), [](char ch) { return std::islower(static_cast<unsigned char>(ch)); }))
      lower += (lower.empty() ? "'" : ", '") + type + "'", ++lowers;
  }
  if (!s.empty())
    s += " ignored (blocks are closed polylines" +
         (lower.empty() ? std::string()
                        : "; " + lower + (lowers > 1 ? " are not entity types" : " is not an entity type") + ": DXF writes them in upper case") +
         ")";
  if (paper) s += (s.empty() ? "" : "; ") + std::to_string(paper) + " entities in paper space ignored (the drawing is model space)";
  return s;
}

// An option's value as given: fmt::g writes a non-finite number as "n/a", which is not what the
// user typed ("--density nan" read "--density n/a").
std::string given(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::g(x, 6);
}

// The options' own ranges, before the drawing is read.
void check_options(const std::string& path, const DxfImportOptions& o) {
  const auto length = [&](double x, const char* name, bool zero_ok) {
    if (std::isfinite(x) && (zero_ok ? x >= 0 : x > 0) && x <= kMaxCoordinate) return;
    throw CaseError(path + ": " + name + " " + given(x) + ": must be a length in m, " + (zero_ok ? "0" : "above 0") + " to 1e5");
  };
  length(o.arc_tolerance, "--arc-tolerance", false);
  length(o.snap, "--snap", true);
  length(o.near_joint, "--near-joint", true);
  length(o.depth, "--depth", false);
  // A density given must be one: 0 was taken for "not given" (the layer then "follows no
  // convention"), while -1 was refused.
  if (o.density && !(std::isfinite(*o.density) && *o.density > 0))
    throw CaseError(path + ": --density " + given(*o.density) + ": must be a density in kg/m^3, positive and finite");
}

json merge_fragment(const std::string& file) {
  if (file.empty()) return json::object();
  const json doc = read_json(file, "the fragment to merge");
  if (!doc.is_object()) throw CaseError(file + ": must be a JSON object");
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "name" && it.key() != "description" && it.key() != "gravity" && it.key() != "loads" && it.key() != "motion" &&
        it.key() != "prd" && it.key() != "dem")
      throw CaseError(file + ": field '" + printable(it.key()) + "': a fragment holds name, description, gravity, loads, motion, prd, dem");
  return doc;
}

}  // namespace

DxfImport import_dxf(const std::string& path, const DxfImportOptions& o) {
  check_options(path, o);
  const DxfDrawing d = read_dxf(path);
  const double scale = unit_scale(path, o.units, d.insunits);
  DxfImport out;
  std::vector<std::string> texts;
  std::vector<Piece> pieces = blocks_of(path, d, scale, o, texts);
  const std::string skipped = skipped_note(d);
  if (!skipped.empty()) out.notes.push_back(skipped);
  out.notes.insert(out.notes.end(), texts.begin(), texts.end());
  if (const int moved = snap_pieces(pieces, o.snap)) {
    out.notes.push_back(std::to_string(moved) + " vertices snapped onto a neighbouring block (--snap " + fmt::g(o.snap) + " m)");
    for (Piece& k : pieces) k.box = bounds(k.v);
  }

  // Stage 5: the case, the fragment merged over it, checked by the loader.
  json doc = {{"format", "masonry-case/1"},
              {"name", o.name.empty() ? std::filesystem::path(path).stem().string() : o.name},
              {"description", "imported from " + std::filesystem::path(path).filename().string()}};
  json blocks = json::array();
  for (const Piece& k : pieces) {
    json v = json::array();
    for (const Vec2& p : k.v) v.push_back({p.x(), p.y()});
    json b = {{"id", k.id}, {"vertices", v}, {"depth", k.depth}};
    if (k.support)
      b["support"] = true;
    else
      b["density"] = k.density;
    blocks.push_back(b);
  }
  doc["blocks"] = blocks;
  const json fragment = merge_fragment(o.merge_file);
  // The fragment's contact tolerance decides which gaps are drafting errors: checked against its
  // range first (naming the fragment), or a negative one would call blocks that meet exactly a gap.
  PrdOptions prd;
  try {
    if (fragment.contains("prd")) read_options(fragment["prd"], prd, o.merge_file);
  } catch (const CaseError& e) {
    throw CaseError(std::string(e.what()) + " [merged into " + path + "]");
  }
  const std::vector<std::string> near = near_joints(pieces, prd.contact_tolerance, std::max(o.near_joint, o.snap));
  out.notes.insert(out.notes.end(), near.begin(), near.end());
  json merged = doc;
  for (auto it = fragment.begin(); it != fragment.end(); ++it) merged[it.key()] = it.value();
  // Text the drawing could not give as UTF-8 (a --name, say) is replaced, never a crash.
  const auto text = [](const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); };
  // Say where in the drawing each block the message names comes from, and what the import
  // noticed that may be the cause: a drafting gap, entities it did not read (a 'lwpolyline' left
  // "no free block" with nothing to say why).
  const auto refused = [&](const CaseError& e) {
    std::string msg = e.what();
    std::string where;
    for (const Piece& k : pieces)
      if (msg.find("'" + printable(k.id) + "'") != std::string::npos)
        where += (where.empty() ? "" : "; ") + printable(k.id) + ": layer '" + printable(k.layer) + "', entity " + printable(k.handle);
    if (!where.empty()) msg += " [drawing: " + where + "]";
    if (!near.empty()) msg += " [" + near.front() + "]";
    if (!skipped.empty()) msg += " [" + skipped + "]";
    return CaseError(msg);
  };
  try {
    out.c = parse_case(text(merged), path);
  } catch (const CaseError& e) {
    if (fragment.empty()) throw refused(e);
    // The message names the file that holds what it refuses: the drawing where the drawing alone
    // is refused, else the fragment (a load on a block the drawing lacks, a setting out of range).
    // The drawing alone keeps the fragment's contact tolerance, which decides what touches (a
    // fragment may close a drawing's gap by it), unless the tolerance itself is the fault.
    const auto fails = [&](const json& j, const std::string& source) -> std::optional<CaseError> {
      try {
        parse_case(text(j), source);
      } catch (const CaseError& x) {
        return x;
      }
      return std::nullopt;
    };
    // The drawing too: a fragment's block names are the drawing's ids.
    const auto in_fragment = [&](const CaseError& f) { return refused(CaseError(std::string(f.what()) + " [merged into " + path + "]")); };
    const char* tol_field = option_of(&PrdOptions::contact_tolerance).name;
    json alone = doc;
    if (fragment.contains("prd") && fragment["prd"].contains(tol_field)) alone["prd"] = {{tol_field, prd.contact_tolerance}};
    if (const std::optional<CaseError> d = fails(alone, path)) {
      if (alone.contains("prd") && !fails(doc, path)) throw in_fragment(*fails(alone, o.merge_file));
      throw refused(*d);
    }
    // The drawing stands alone, so the fragment is the fault: the same text again, named by it.
    throw in_fragment(fails(merged, o.merge_file).value_or(e));
  }
  return out;
}

}  // namespace masonry
