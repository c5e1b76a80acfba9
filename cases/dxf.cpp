// import_dxf, as named stages: read the drawing (dxflib), turn polylines into polygons in metres
// (units, arcs by chords), name the blocks and give them their layer's properties, snap drafting
// gaps, assemble the case (with the merged fragment) and check it with the case loader.
#include "cases/dxf.hpp"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

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

#include "model/interfaces.hpp"

namespace masonry {

namespace {

using json = nlohmann::json;

// What the drawing holds, as read.
struct RawVertex {
  double x = 0, y = 0, bulge = 0;
};
struct RawPolyline {
  std::string layer, handle;
  bool closed = false, mesh = false;
  std::vector<RawVertex> v;
};
struct RawText {
  std::string layer, handle, text;
  double x = 0, y = 0;
};
struct RawDrawing {
  int insunits = -1;  // $INSUNITS, -1: absent
  std::vector<RawPolyline> polylines;
  std::vector<RawText> texts;
  std::vector<std::string> refused;  // entities that cannot be blocks: "CIRCLE on layer L (handle H)"
  int ignored_lines = 0;
};

std::string hex_handle(int h) {
  if (h < 0) return "?";
  char b[24];
  std::snprintf(b, sizeof b, "%X", h);
  return b;
}

bool layer_is(const std::string& layer, const char* prefix) {
  const size_t n = std::strlen(prefix);
  if (layer.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(layer[i])) != prefix[i]) return false;
  return true;
}
bool ignored_layer(const std::string& layer) { return layer_is(layer, "ignore") || layer_is(layer, "defpoints"); }

// Stage 1: dxflib's callbacks into RawDrawing. A polyline's vertices arrive after it (LWPOLYLINE
// at once, POLYLINE as VERTEX entities up to SEQEND); the next entity closes it.
struct Reader : DL_CreationAdapter {
  RawDrawing d;
  bool open = false;
  void close() { open = false; }
  std::string where() { return "layer '" + printable(attributes.getLayer()) + "' (handle " + hex_handle(attributes.getHandle()) + ")"; }
  void addPolyline(const DL_PolylineData& p) override {
    close();
    RawPolyline r;
    r.layer = attributes.getLayer();
    r.handle = hex_handle(attributes.getHandle());
    r.closed = (p.flags & 1) != 0;
    r.mesh = (p.flags & (16 | 64)) != 0;
    d.polylines.push_back(r);
    open = true;
  }
  void addVertex(const DL_VertexData& v) override {
    if (open) d.polylines.back().v.push_back({v.x, v.y, v.bulge});
  }
  void endSequence() override { close(); }
  void addText(const DL_TextData& t) override {
    close();
    d.texts.push_back({attributes.getLayer(), hex_handle(attributes.getHandle()), t.text, t.ipx, t.ipy});
  }
  void addMText(const DL_MTextData& t) override {
    close();
    d.texts.push_back({attributes.getLayer(), hex_handle(attributes.getHandle()), t.text, t.ipx, t.ipy});
  }
  void refuse(const char* kind) {
    close();
    if (!ignored_layer(attributes.getLayer())) d.refused.push_back(std::string(kind) + " on " + where());
  }
  void addCircle(const DL_CircleData&) override { refuse("CIRCLE"); }
  void addArc(const DL_ArcData&) override { refuse("ARC"); }
  void addEllipse(const DL_EllipseData&) override { refuse("ELLIPSE"); }
  void addSpline(const DL_SplineData&) override { refuse("SPLINE"); }
  void addInsert(const DL_InsertData&) override { refuse("INSERT (a block reference: explode it in the drawing)"); }
  void addLine(const DL_LineData&) override {
    close();
    if (!ignored_layer(attributes.getLayer())) ++d.ignored_lines;
  }
  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") d.insunits = value;
  }
};

RawDrawing read_drawing(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError(path + ": cannot open the drawing");
  std::string head(64, '\0');
  in.read(head.data(), 64);
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.empty()) throw CaseError(path + ": the drawing is empty");
  if (head.rfind("AutoCAD Binary DXF", 0) == 0) throw CaseError(path + ": a binary DXF: save the drawing as ASCII DXF");
  for (char ch : head)
    if (ch == '\0' || (static_cast<unsigned char>(ch) < 0x20 && ch != '\n' && ch != '\r' && ch != '\t'))
      throw CaseError(path + ": not a DXF drawing (binary content in its first bytes)");
  Reader r;
  DL_Dxf dxf;
  try {
    if (!dxf.in(path, &r)) throw CaseError(path + ": cannot read the drawing");
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {
    throw CaseError(path + ": not a readable DXF drawing (" + printable(e.what()) + ")");
  }
  return r.d;
}

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

// An edge from p to q with DXF bulge b (tan of a quarter of the included angle, positive
// counter-clockwise), replaced by chords no farther than `tol` from the arc; p included, q not.
void append_arc(std::vector<Vec2>& out, const Vec2& p, const Vec2& q, double bulge, double tol) {
  out.push_back(p);
  if (std::abs(bulge) < 1e-12) return;
  const double theta = 4 * std::atan(bulge);  // included angle, signed
  const double chord = (q - p).norm();
  const double r = chord / (2 * std::sin(std::abs(theta) / 2));
  const Vec2 mid = 0.5 * (p + q), dir = (q - p) / chord;
  const Vec2 left(-dir.y(), dir.x());
  // The centre lies to the left of p->q for a counter-clockwise arc shorter than a half circle.
  const double off = r * std::cos(std::abs(theta) / 2);
  const Vec2 centre = mid + (theta > 0 ? 1.0 : -1.0) * (std::abs(theta) < M_PI ? 1.0 : -1.0) * off * left;
  // Chords of angle a keep within r (1 - cos(a/2)) of the arc.
  const double a_max = tol < r ? 2 * std::acos(1 - tol / r) : M_PI / 2;
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(theta) / a_max)));
  const double a0 = std::atan2(p.y() - centre.y(), p.x() - centre.x());
  for (int k = 1; k < n; ++k) {
    const double a = a0 + theta * k / n;
    out.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
  }
}

// One block as imported, with where it came from.
struct Piece {
  std::string id, layer, handle;
  bool support = false;
  double density = 0, depth = 1;
  std::vector<Vec2> v;
};

struct LayerProps {
  std::optional<double> density, depth;
  std::optional<bool> support;
};

json read_json(const std::string& file, const char* what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CaseError(file + ": cannot open " + what);
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw CaseError(file + ": malformed JSON: " + printable(e.what()));
  }
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
      if (f.key() == "support" && f->is_boolean()) p.support = f->get<bool>();
      else if ((f.key() == "density" || f.key() == "depth") && f->is_number())
        (f.key() == "density" ? p.density : p.depth) = f->get<double>();
      else throw CaseError(where + ": field '" + printable(f.key()) + "': unknown, or not of its type (density, depth: numbers; support: true or false)");
    }
    out[it.key()] = p;
  }
  return out;
}

// Stage 3: polygons with their ids and properties.
std::vector<Piece> blocks_of(const std::string& path, const RawDrawing& d, double scale, const DxfImportOptions& o) {
  if (!d.refused.empty())
    throw CaseError(path + ": " + d.refused.front() + " cannot be a block: draw blocks as closed polylines (or put it on a layer named IGNORE)");
  const auto layers = read_layers(o.layers_file);
  std::vector<Piece> out;
  std::map<std::string, int> count;
  for (const RawPolyline& p : d.polylines) {
    if (ignored_layer(p.layer)) continue;
    const std::string where = path + ": layer '" + printable(p.layer) + "', entity " + p.handle;
    if (p.mesh) throw CaseError(where + ": a polygon mesh, not a block outline");
    if (!p.closed) throw CaseError(where + ": an open polyline: a block must be a closed polyline (set its closed flag)");
    if (p.v.size() < 3) throw CaseError(where + ": a closed polyline of fewer than 3 vertices");
    Piece k;
    k.layer = p.layer;
    k.handle = p.handle;
    for (size_t i = 0; i < p.v.size(); ++i) {
      const RawVertex &a = p.v[i], &b = p.v[(i + 1) % p.v.size()];
      append_arc(k.v, scale * Vec2(a.x, a.y), scale * Vec2(b.x, b.y), a.bulge, o.arc_tolerance);
    }
    // The closing vertex repeated on the first (some programs write it): drop it.
    if (k.v.size() > 3 && (k.v.front() - k.v.back()).norm() <= 1e-12 * (1 + k.v.front().norm())) k.v.pop_back();
    const auto lp = layers.find(p.layer);
    const LayerProps props = lp == layers.end() ? LayerProps{} : lp->second;
    k.support = props.support.value_or(layer_is(p.layer, "support"));
    k.depth = props.depth.value_or(o.depth);
    if (!k.support) {
      if (!props.density && !(o.density > 0))
        throw CaseError(where + ": the layer follows no convention the import knows: not SUPPORT*, not IGNORE*, and no density "
                                "(give --density or the layer's density in --layers)");
      k.density = props.density.value_or(o.density);
    }
    k.id = printable(p.layer, 40) + "-" + std::to_string(++count[p.layer]);
    out.push_back(std::move(k));
  }
  if (out.empty()) throw CaseError(path + ": no closed polyline on a block layer: nothing to import");
  // A TEXT or MTEXT inside a polygon names its block.
  std::map<std::string, std::string> named_by;
  for (const RawText& t : d.texts) {
    if (ignored_layer(t.layer) || t.text.empty()) continue;
    const Vec2 at = scale * Vec2(t.x, t.y);
    for (Piece& k : out) {
      if (!point_in_polygon(at, k.v)) continue;
      if (named_by.count(k.handle))
        throw CaseError(path + ": layer '" + printable(k.layer) + "', entity " + k.handle + ": two texts inside the block ('" +
                        printable(named_by[k.handle]) + "' and '" + printable(t.text) + "')");
      named_by[k.handle] = t.text;
      k.id = t.text;
    }
  }
  return out;
}

// Stage 4: drafting gaps. A vertex within `snap` of another block's vertex goes onto it, else
// within `snap` of another block's edge onto the edge.
int snap_pieces(std::vector<Piece>& ps, double snap) {
  if (!(snap > 0)) return 0;
  int moved = 0;
  for (size_t i = 0; i < ps.size(); ++i)
    for (Vec2& p : ps[i].v) {
      double best = snap;
      Vec2 target = p;
      bool on_vertex = false;
      for (size_t j = 0; j < ps.size(); ++j) {
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
  for (size_t i = 0; i < ps.size(); ++i)
    for (size_t j = i + 1; j < ps.size(); ++j) {
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
        out.push_back("blocks '" + printable(ps[i].id) + "' and '" + printable(ps[j].id) + "' almost meet: " +
                      (inside ? "they overlap by " : "a gap of ") + b + " (a drafting error? --snap closes it)");
      }
    }
  return out;
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
  const RawDrawing d = read_drawing(path);
  const double scale = unit_scale(path, o.units, d.insunits);
  std::vector<Piece> pieces = blocks_of(path, d, scale, o);
  DxfImport out;
  if (d.ignored_lines > 0)
    out.notes.push_back(std::to_string(d.ignored_lines) + " LINE entities ignored (blocks are closed polylines)");
  if (const int moved = snap_pieces(pieces, o.snap))
    out.notes.push_back(std::to_string(moved) + " vertices snapped onto a neighbouring block (--snap " + std::to_string(o.snap) + " m)");

  // Stage 5: the case, the fragment merged over it, checked by the loader.
  json doc = {{"format", "masonry-case/1"},
              {"name", o.name.empty() ? std::filesystem::path(path).stem().string() : o.name},
              {"description", "imported from " + std::filesystem::path(path).filename().string()}};
  json blocks = json::array();
  for (const Piece& k : pieces) {
    json v = json::array();
    for (const Vec2& p : k.v) v.push_back({p.x(), p.y()});
    json b = {{"id", k.id}, {"vertices", v}, {"depth", k.depth}};
    if (k.support) b["support"] = true;
    else b["density"] = k.density;
    blocks.push_back(b);
  }
  doc["blocks"] = blocks;
  const json fragment = merge_fragment(o.merge_file);
  for (auto it = fragment.begin(); it != fragment.end(); ++it) doc[it.key()] = it.value();
  const double tol = doc.contains("prd") && doc["prd"].contains("contact_tolerance") && doc["prd"]["contact_tolerance"].is_number()
                         ? doc["prd"]["contact_tolerance"].get<double>()
                         : PrdOptions{}.contact_tolerance;
  const std::vector<std::string> near = near_joints(pieces, tol, std::max(o.near_joint, o.snap));
  out.notes.insert(out.notes.end(), near.begin(), near.end());
  try {
    out.c = parse_case(doc.dump(), path);
  } catch (const CaseError& e) {
    // Say where in the drawing each block the message names comes from.
    std::string msg = e.what();
    std::string where;
    for (const Piece& k : pieces)
      if (msg.find("'" + printable(k.id) + "'") != std::string::npos)
        where += (where.empty() ? "" : "; ") + printable(k.id) + ": layer '" + printable(k.layer) + "', entity " + k.handle;
    if (!where.empty()) msg += " [drawing: " + where + "]";
    if (!near.empty()) msg += " [" + near.front() + "]";
    throw CaseError(msg);
  }
  return out;
}

}  // namespace masonry
