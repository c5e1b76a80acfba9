#include "compare/svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include "model/energy.hpp"
#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/svg.hpp"

namespace masonry {

namespace {

// Colours of the drawing's elements; supports take report/svg.hpp's series colours.
const char* kForce = "#1f4fbf";
const char* kThrustLine = "#c0392b";
const char* kReaction = "#1a7f37";
const char* kHinge = "#d62728";

using fmt::px;

// Current position of a material point of block b (initial coordinates) at a record.
struct Placer {
  const Case& c;
  const StepRecord& s;
  std::vector<Vec2> c0;  // initial centroids
  Placer(const Case& cc, const StepRecord& ss) : c(cc), s(ss) {
    for (const Block& b : c.blocks) c0.push_back(centroid(b.vertices));
  }
  Vec2 at(int b, const Vec2& p) const { return b < 0 || b >= int(s.poses.size()) ? p : placed(c0[b], s.poses[b], p); }
};

// World -> pixel mapping of one panel.
struct Map {
  double ox, oy, s, x0, y1;
  double X(double x) const { return ox + (x - x0) * s; }
  double Y(double y) const { return oy + (y1 - y) * s; }
  std::string P(const Vec2& p) const { return px(X(p.x())) + "," + px(Y(p.y())); }
};

// Path data in tenths of a pixel, each point after the first relative to the one before ("M187.5,
// 503.7l-25.4,0 0,10.5z"): the slider repeats every drawing 24 to 60 times in one page, where
// absolute coordinates with a fixed decimal made a cathedral's report.html 3.8 MB.
class PathData {
 public:
  explicit PathData(const Map& m) : m_(m) {}
  // A subpath through `pts` (a single point: a dot), closed with `close`.
  void polyline(const std::vector<Vec2>& pts, bool close) {
    if (pts.empty()) return;
    long x0 = 0, y0 = 0;
    for (size_t k = 0; k < pts.size(); ++k) {
      const long x = tenths(m_.X(pts[k].x())), y = tenths(m_.Y(pts[k].y()));
      // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) about "M" + std::string.
      d_.append(1, k == 0 ? 'M' : k == 1 ? 'l' : ' ').append(text(k == 0 ? x : x - x0)).append(1, ',').append(text(k == 0 ? y : y - y0));
      x0 = x;
      y0 = y;
    }
    if (close) d_ += 'z';
    if (pts.size() == 1) d_ += "h0";  // a dot: a zero-length segment drawn with round caps
  }
  const std::string& str() const { return d_; }
  bool empty() const { return d_.empty(); }

 private:
  static long tenths(double v) { return std::isfinite(v) ? std::lround(v * 10) : 0; }
  static std::string text(long t) {  // tenths as a decimal number: 1875 -> "187.5", 1870 -> "187", -5 -> "-0.5"
    std::string out = t < 0 ? "-" : "";
    const long a = std::labs(t);
    out += std::to_string(a / 10);
    if (a % 10) out.append(1, '.').append(std::to_string(a % 10));
    return out;
  }
  const Map& m_;
  std::string d_;
};

std::string arrow_defs(const std::string& id) {
  std::string s = "<defs><marker id=\"";
  s += id;
  s += "arr\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" markerHeight=\"6\" "
       "orient=\"auto-start-reverse\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"";
  s += kReaction;
  s += "\"/></marker><marker id=\"";
  s += id;
  s += "mot\" viewBox=\"0 0 10 10\" refX=\"8\" refY=\"5\" markerWidth=\"5\" markerHeight=\"5\" orient=\"auto\">"
       "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#555\"/></marker></defs>\n";
  return s;
}

// Reaction of a support and where to draw it: the normal-weighted centre of its joints'
// pressure points (where the structure actually bears on it).
bool reaction_point(const RunResult& r, const StepRecord& s, int support, Vec2& p) {
  double w = 0;
  Vec2 acc(0, 0);
  for (const JointForce& f : s.forces) {
    if (f.joint < 0 || f.joint >= int(r.joints.size())) continue;
    const JointInfo& j = r.joints[f.joint];
    if (j.i != support && j.j != support) continue;
    if (!std::isfinite(f.normal) || f.normal <= 0) continue;
    acc += f.normal * f.point;
    w += f.normal;
  }
  if (w <= 0) return false;
  p = acc / w;
  return true;
}

void draw_panel(std::ostringstream& o, const Case& c, const Panel& pn, const DrawFrame& f, const Map& m, double width, const std::string& id,
                bool titles) {
  o << "<text x=\"" << px(m.ox + width / 2) << "\" y=\"" << px(m.oy - 24) << "\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">"
    << xml_escape(pn.title) << "</text>\n<text x=\"" << px(m.ox + width / 2) << "\" y=\"" << px(m.oy - 7)
    << "\" text-anchor=\"middle\" font-size=\"13\">" << xml_escape(pn.subtitle) << "</text>\n";
  if (!pn.run || !pn.record || pn.record->poses.size() != c.blocks.size()) return;
  const RunResult& r = *pn.run;
  const StepRecord& s = *pn.record;
  const Placer pl(c, s);
  // Blocks: free blocks share one fill, supports the hatching; with `titles` each is a path of
  // its own with its id as a tooltip, else each group is one path. Segments and dots below go into
  // one path each (a scene of 300 joints drawn at 24 slider positions in two panels: separate
  // <line> and <circle> elements made a cathedral's report.html 3.8 MB).
  for (int support = 0; support < 2; ++support) {
    o << "<g stroke=\"#6b6b6b\" stroke-width=\"0.7\" stroke-linejoin=\"round\" fill=\""
      << (support ? "url(#" + id + "hatch)" : std::string("#eadfca")) << "\">\n";
    PathData group(m);
    for (size_t b = 0; b < c.blocks.size(); ++b) {
      const Block& B = c.blocks[b];
      if (B.support != bool(support)) continue;
      std::vector<Vec2> pts;
      for (const Vec2& v : B.vertices) pts.push_back(pl.at(int(b), v));
      if (!titles) {
        group.polyline(pts, true);
        continue;
      }
      PathData one(m);
      one.polyline(pts, true);
      o << "<path d=\"" << one.str() << "\"><title>" << xml_escape(B.id) << "</title></path>\n";
    }
    if (!group.empty()) o << "<path d=\"" << group.str() << "\"/>\n";
    o << "</g>\n";
  }
  // Cracked joints: both faces bold, so an opening shows as a wedge between two black lines.
  std::vector<int> open_count(r.joints.size(), 0);
  for (const OpenCorner& oc : s.open_corners)
    if (oc.joint >= 0 && oc.joint < int(open_count.size())) ++open_count[oc.joint];
  PathData cracks(m);
  for (size_t j = 0; j < r.joints.size(); ++j) {
    if (!open_count[j]) continue;
    const JointInfo& J = r.joints[j];
    for (int side : {J.i, J.j}) cracks.polyline({pl.at(side, J.a), pl.at(side, J.b)}, false);
  }
  if (!cracks.empty()) o << "<path stroke=\"#111\" stroke-width=\"3\" stroke-linecap=\"round\" fill=\"none\" d=\"" << cracks.str() << "\"/>\n";
  // Joint resultants: a segment through the pressure point along the force, length ~ F / W, and
  // the pressure point as a dot (a zero-length segment with round caps). Smaller dots when
  // joints are many, or a pier becomes a string of beads.
  const char* dot = r.joints.size() > 60 ? "2.6" : "4.4";
  PathData segments(m), dots(m);
  for (const JointForce& jf : s.forces) {
    if (!std::isfinite(jf.normal) || jf.normal <= 0) continue;
    const Vec2 t(-jf.n.y(), jf.n.x());
    const Vec2 F = jf.normal * jf.n + jf.shear * t;
    const Vec2 h = 0.5 * F / f.weight * f.force_len;
    segments.polyline({jf.point - h, jf.point + h}, false);
    dots.polyline({jf.point}, false);
  }
  if (!segments.empty())
    o << "<path stroke=\"" << kForce << "\" stroke-width=\"1.6\" fill=\"none\" d=\"" << segments.str() << "\"/>\n<path stroke=\"" << kForce
      << "\" stroke-width=\"" << dot << "\" stroke-linecap=\"round\" fill=\"none\" d=\"" << dots.str() << "\"/>\n";
  // Thrust line: through the pressure points, joined across every free block that carries force
  // on exactly two joints (an arch ring, a pier shaft); branching blocks show their resultants only.
  std::map<int, std::vector<Vec2>> per_block;
  for (const JointForce& jf : s.forces) {
    if (jf.joint < 0 || jf.joint >= int(r.joints.size()) || !(jf.normal > 0)) continue;
    const JointInfo& J = r.joints[jf.joint];
    for (int b : {J.i, J.j})
      if (b >= 0 && b < int(c.blocks.size()) && !c.blocks[b].support) per_block[b].push_back(jf.point);
  }
  PathData thrust(m);
  for (const auto& [b, pts] : per_block)
    if (pts.size() == 2) thrust.polyline(pts, false);
  if (!thrust.empty()) o << "<path stroke=\"" << kThrustLine << "\" stroke-width=\"2\" fill=\"none\" d=\"" << thrust.str() << "\"/>\n";
  // Hinges: the closed corner of a joint with one open corner.
  o << "<g fill=\"#fff\" stroke=\"" << kHinge << "\" stroke-width=\"2.2\">\n";
  for (const Hinge& h : hinges_of(c, r, s, f.hinge_gap)) {
    const Vec2 p = pl.at(h.i, h.point);
    o << "<circle cx=\"" << px(m.X(p.x())) << "\" cy=\"" << px(m.Y(p.y())) << "\" r=\"5\"><title>hinge " << xml_escape(h.label)
      << "</title></circle>\n";
  }
  o << "</g>\n";
  // Support reactions: an arrow ending where the structure bears on the support, labelled.
  for (const Reaction& re : s.reactions) {
    const int b = c.block_index(re.support);
    Vec2 p;
    if (b < 0 || !reaction_point(r, s, b, p)) continue;
    const Vec2 tail = p - re.force / f.weight * f.force_len;
    o << "<line x1=\"" << px(m.X(tail.x())) << "\" y1=\"" << px(m.Y(tail.y())) << "\" x2=\"" << px(m.X(p.x())) << "\" y2=\"" << px(m.Y(p.y()))
      << "\" stroke=\"" << kReaction << "\" stroke-width=\"2.6\" marker-end=\"url(#" << id << "arr)\"/>\n";
    // Label under the arrow's tail, kept inside the panel; two short lines so that the labels
    // of neighbouring supports do not run into each other.
    const double lx = std::clamp(m.X(tail.x()), m.ox + 35, m.ox + width - 35);
    const double ly = m.Y(tail.y());
    o << "<text x=\"" << px(lx) << "\" y=\"" << px(ly + 13) << "\" font-size=\"11\" fill=\"" << kReaction << "\" text-anchor=\"middle\">H "
      << fmt::g(re.force.x() / f.weight) << " W</text><text x=\"" << px(lx) << "\" y=\"" << px(ly + 26) << "\" font-size=\"11\" fill=\"" << kReaction
      << "\" text-anchor=\"middle\">V " << fmt::g(re.force.y() / f.weight) << " W</text>\n";
  }
  // The imposed motion: a grey arrow beside each moving support (off to its side, clear of the
  // structure above it), along its translation, and an arc for a rotation (counter-clockwise
  // positive), so the reader sees which support moves and how.
  for (const SupportMotion& sm : c.motion.supports) {
    if (sm.block < 0 || sm.block >= int(c.blocks.size())) continue;
    const Block& B = c.blocks[sm.block];
    const Vec2 cen = pl.at(sm.block, centroid(B.vertices));
    const double tn = sm.translation.norm();
    const Vec2 u = tn > 0 ? Vec2(sm.translation / tn) : Vec2(1, 0);
    const Vec2 perp(u.y(), -u.x());  // to the right of the motion: below a rightward push, left of a settlement
    double reach = 0;                // half extent of the support along perp, m
    for (const Vec2& v : B.vertices) reach = std::max(reach, (pl.at(sm.block, v) - cen).dot(perp));
    const Vec2 mid = cen + perp * (reach + 16 / m.s);
    const double X = m.X(mid.x()), Y = m.Y(mid.y()), L = 30;  // px
    o << "<g stroke=\"#555\" stroke-width=\"2.4\" fill=\"none\"><title>imposed support motion</title>";
    if (tn > 0)
      o << "<line x1=\"" << px(X - u.x() * L / 2) << "\" y1=\"" << px(Y + u.y() * L / 2) << "\" x2=\"" << px(X + u.x() * L / 2) << "\" y2=\""
        << px(Y - u.y() * L / 2) << "\" marker-end=\"url(#" << id << "mot)\"/>";
    if (sm.rotation != 0) {
      const double rr = 10, cx = X + perp.x() * 18, cy = Y - perp.y() * 18;
      const bool ccw = sm.rotation > 0;
      o << "<path d=\"M" << px(cx + rr) << "," << px(cy) << " A" << rr << "," << rr << " 0 1," << (ccw ? 0 : 1) << " " << px(cx) << ","
        << px(ccw ? cy - rr : cy + rr) << "\" marker-end=\"url(#" << id << "mot)\"/>";
    }
    o << "</g>\n";
  }
  // Status line under the drawing.
  const size_t nh = hinges_of(c, r, s, f.hinge_gap).size();
  o << "<text x=\"" << px(m.ox + width / 2) << "\" y=\"" << px(m.Y(f.lo.y()) + 16) << "\" text-anchor=\"middle\" font-size=\"12\" fill=\"#333\">"
    << s.cracked.size() << " cracked joint" << (s.cracked.size() == 1 ? "" : "s") << ", " << nh << " hinge" << (nh == 1 ? "" : "s") << "</text>\n";
}

}  // namespace

DrawFrame draw_frame(const Case& c, const std::vector<const RunResult*>& runs) {
  DrawFrame f;
  Bounds box;
  for (const RunResult* r : runs)
    for (const StepRecord* s : stable_records(*r)) {
      if (s->poses.size() != c.blocks.size()) continue;
      const Placer pl(c, *s);
      for (size_t b = 0; b < c.blocks.size(); ++b)
        for (const Vec2& v : c.blocks[b].vertices)
          if (const Vec2 p = pl.at(int(b), v); p.allFinite()) box.add(p);
      f.weight = r->total_weight > 0 ? r->total_weight : f.weight;
    }
  if (box.empty()) box = scene_bounds(c);
  for (const RunResult* r : runs) f.hinge_gap = std::max(f.hinge_gap, settled_gap(*r));
  const double size = box.size();
  // Forces drawn at 0.35 scene sizes per total weight: an arch's thrust (0.2-0.5 W) reads as a
  // clear segment without covering the blocks.
  f.force_len = 0.35 * size;
  // The window also holds every reaction arrow (tail at p - R / W * force_len) and its label.
  for (const RunResult* r : runs)
    for (const StepRecord* s : stable_records(*r))
      for (const Reaction& re : s->reactions) {
        const int b = c.block_index(re.support);
        Vec2 p;
        if (b < 0 || !reaction_point(*r, *s, b, p)) continue;
        const Vec2 tail = p - re.force / f.weight * f.force_len;
        if (!tail.allFinite()) continue;
        box.add(tail - Vec2(0.02 * size, 0.09 * size));
        box.add(tail);
      }
  const double pad = 0.03 * size;
  f.lo = box.lo - Vec2(pad, pad);
  f.hi = box.hi + Vec2(pad, pad);
  return f;
}

std::string svg_structure(const Case& c, const std::vector<Panel>& panels, const DrawFrame& f, double panel_width, const std::string& id,
                          bool titles) {
  const double gap = 20, top = 46, legend_h = 64;
  const double s = panel_width / std::max(1e-12, f.hi.x() - f.lo.x());
  const double ph = (f.hi.y() - f.lo.y()) * s;
  const double W = panels.size() * panel_width + (panels.size() + 1) * gap;
  const double H = top + ph + 24 + legend_h;
  std::ostringstream o;
  o << svg_open(W, H) << arrow_defs(id) << "<defs><pattern id=\"" << id
    << "hatch\" width=\"6\" height=\"6\" patternUnits=\"userSpaceOnUse\" patternTransform=\"rotate(45)\">"
       "<rect width=\"6\" height=\"6\" fill=\"#cfcfcf\"/><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"6\" stroke=\"#8a8a8a\" "
       "stroke-width=\"1.5\"/></pattern></defs>\n";
  for (size_t k = 0; k < panels.size(); ++k) {
    const Map m{gap + k * (panel_width + gap), top, s, f.lo.x(), f.hi.y()};
    o << "<g class=\"panel\">\n";
    draw_panel(o, c, panels[k], f, m, panel_width, id, titles);
    o << "</g>\n";
  }
  // Legend, with a force scale bar of 0.1 W.
  const double ly = top + ph + 34;
  double x = gap;
  const auto item = [&](const std::string& glyph, const std::string& text, double w) {
    o << "<g transform=\"translate(" << px(x) << "," << px(ly) << ")\">" << glyph << "<text x=\"30\" y=\"4\" font-size=\"12\">" << text
      << "</text></g>\n";
    x += w;
  };
  item("<line x1=\"0\" y1=\"0\" x2=\"24\" y2=\"0\" stroke=\"#111\" stroke-width=\"3\"/>", "cracked joint", 120);
  item(std::string("<circle cx=\"12\" cy=\"0\" r=\"5\" fill=\"#fff\" stroke=\"") + kHinge + "\" stroke-width=\"2.2\"/>", "hinge", 80);
  item(std::string("<line x1=\"0\" y1=\"0\" x2=\"24\" y2=\"0\" stroke=\"") + kThrustLine + "\" stroke-width=\"2\"/>", "thrust line", 110);
  item(std::string("<line x1=\"0\" y1=\"0\" x2=\"24\" y2=\"0\" stroke=\"") + kForce +
           "\" stroke-width=\"1.6\"/><circle cx=\"12\" cy=\"0\" r=\"2.2\" fill=\"" + kForce + "\"/>",
       "joint resultant", 130);
  item(std::string("<line x1=\"0\" y1=\"0\" x2=\"22\" y2=\"0\" stroke=\"") + kReaction + "\" stroke-width=\"2.6\" marker-end=\"url(#" + id +
           "arr)\"/>",
       "support reaction (W = total weight)", 250);
  item(std::string("<line x1=\"0\" y1=\"0\" x2=\"22\" y2=\"0\" stroke=\"#555\" stroke-width=\"2.4\" marker-end=\"url(#") + id + "mot)\"/>",
       "imposed motion", 130);
  const double bar = 0.1 * f.force_len * s;
  o << "<g transform=\"translate(" << px(gap) << "," << px(ly + 22) << ")\"><line x1=\"0\" y1=\"0\" x2=\"" << px(bar) << "\" y2=\"0\" stroke=\""
    << kForce << "\" stroke-width=\"1.6\"/><line x1=\"0\" y1=\"-4\" x2=\"0\" y2=\"4\" stroke=\"" << kForce << "\"/><line x1=\"" << px(bar)
    << "\" y1=\"-4\" x2=\"" << px(bar) << "\" y2=\"4\" stroke=\"" << kForce << "\"/><text x=\"" << px(bar + 8)
    << "\" y=\"4\" font-size=\"12\">force scale: 0.1 W = " << fmt::kn(0.1 * f.weight) << " kN; hatched: supports</text></g>\n";
  o << "</svg>\n";
  return o.str();
}

std::string svg_thrust(const Comparison& k, const RunResult& a, const RunResult& b, bool cursor) {
  const double W = 800, ph = 250, left = 70, right = 190, top = 40, between = 60;
  const double H = top + 2 * ph + between + 50;
  const double pw = W - left - right;
  const double W_n = k.total_weight > 0 ? k.total_weight : 1.0;
  const auto ra = stable_records(a), rb = stable_records(b);
  double dmax = 0;
  for (const auto* recs : {&ra, &rb})
    if (!recs->empty()) dmax = std::max(dmax, recs->back()->d);
  if (!(dmax > 0)) dmax = 1e-3;
  const double sx = pw / dmax;  // px per m
  std::vector<std::string> supports;
  for (const SupportCurve& sc : k.supports) supports.push_back(sc.support);
  std::ostringstream o;
  o << svg_open(W, H, "class=\"thrust\" data-x0=\"" + px(left) + "\" data-sx=\"" + fmt::g(sx, 10) + "\"");
  o << "<text x=\"" << px(left) << "\" y=\"20\" font-size=\"15\" font-weight=\"bold\">Support reactions over total weight W = " << fmt::kn(W_n)
    << " kN</text>\n";
  for (int comp = 0; comp < 2; ++comp) {
    const double oy = top + comp * (ph + between);
    // Value range over both runs, all supports, with zero included.
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const auto* recs : {&ra, &rb})
      for (const StepRecord* s : *recs)
        for (const Reaction& x : s->reactions) {
          const double v = (comp == 0 ? x.force.x() : x.force.y()) / W_n;
          if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
        }
    if (lo > hi) lo = hi = 0;
    // A span of at least 0.05 W, so round-off does not look like a trend.
    if (hi - lo < 0.05) {
      const double mid = 0.5 * (hi + lo);
      lo = mid - 0.025;
      hi = mid + 0.025;
    }
    const double padv = 0.06 * (hi - lo);
    lo -= padv;
    hi += padv;
    const Plot plot{left, oy, pw, ph, 0, dmax, lo, hi};
    const auto X = [&](double d) { return plot.X(d); };
    const auto Y = [&](double v) { return plot.Y(v); };
    o << svg_axes(plot, linear_ticks(0, dmax, 8, 4, 1000), linear_ticks(lo, hi, 6, 3),
                  (k.d_unit == "rad" ? "support rotation d (" : "support displacement d (") + milli(k.d_unit) + ")",
                  comp == 0 ? "horizontal reaction H / W" : "vertical reaction V / W");
    // Mechanism changes: ticks at the top (a) and the bottom (b) of the panel, and the capacities.
    const auto marks = [&](const RunSummary& rs, bool at_top, const char* dash) {
      for (double d : rs.changes)
        o << "<path d=\"M" << px(X(d)) << "," << px(at_top ? oy : oy + ph) << " l-4," << (at_top ? "-8" : "8") << " h8 z\" fill=\"#555\"><title>"
          << xml_escape(rs.label) << ": mechanism changes at d = " << fmt::g(d * 1000, 4) << " " << milli(k.d_unit) << "</title></path>\n";
      o << "<line x1=\"" << px(X(rs.capacity)) << "\" x2=\"" << px(X(rs.capacity)) << "\" y1=\"" << px(oy) << "\" y2=\"" << px(oy + ph)
        << "\" stroke=\"#555\" stroke-width=\"1\" stroke-dasharray=\"" << dash << "\"/>\n";
    };
    marks(k.a, true, "2,3");
    marks(k.b, false, "7,4");
    // Curves: one colour per support; a solid, b dashed.
    for (size_t si = 0; si < supports.size(); ++si) {
      const char* col = series_color(si);
      for (int run = 0; run < 2; ++run) {
        const auto& recs = run == 0 ? ra : rb;
        std::string pts;
        for (const StepRecord* s : recs)
          for (const Reaction& x : s->reactions)
            if (x.support == supports[si]) {
              const double v = (comp == 0 ? x.force.x() : x.force.y()) / W_n;
              if (std::isfinite(v)) pts += px(X(s->d)) + "," + px(Y(v)) + " ";
            }
        o << "<polyline fill=\"none\" stroke=\"" << col << "\" stroke-width=\"" << (run == 0 ? "2.2" : "2") << "\""
          << (run == 1 ? " stroke-dasharray=\"7,4\"" : "") << " points=\"" << pts << "\"/>\n";
      }
    }
    if (cursor)
      o << "<line class=\"cursor\" x1=\"" << px(left) << "\" x2=\"" << px(left) << "\" y1=\"" << px(oy) << "\" y2=\"" << px(oy + ph)
        << "\" stroke=\"#000\" stroke-width=\"1.5\" opacity=\"0.6\"/>\n";
  }
  // Legend on the right.
  double ly = top + 10;
  const double lx = left + pw + 16;
  o << "<g font-size=\"12\">\n";
  for (int run = 0; run < 2; ++run) {
    const RunSummary& rs = run == 0 ? k.a : k.b;
    o << "<line x1=\"" << px(lx) << "\" x2=\"" << px(lx + 30) << "\" y1=\"" << px(ly) << "\" y2=\"" << px(ly)
      << "\" stroke=\"#333\" stroke-width=\"2\"" << (run == 1 ? " stroke-dasharray=\"7,4\"" : "") << "/><text x=\"" << px(lx + 36) << "\" y=\""
      << px(ly + 4) << "\">" << xml_escape(rs.label) << "</text>\n";
    ly += 20;
  }
  ly += 6;
  for (size_t si = 0; si < supports.size(); ++si) {
    o << "<rect x=\"" << px(lx) << "\" y=\"" << px(ly - 6) << "\" width=\"30\" height=\"10\" fill=\"" << series_color(si) << "\"/><text x=\""
      << px(lx + 36) << "\" y=\"" << px(ly + 4) << "\">" << xml_escape(supports[si]) << "</text>\n";
    ly += 18;
  }
  ly += 10;
  o << "<text x=\"" << px(lx) << "\" y=\"" << px(ly + 4) << "\">mechanism changes:</text>\n";
  ly += 18;
  o << "<path d=\"M" << px(lx + 15) << "," << px(ly + 4) << " l-4,-8 h8 z\" fill=\"#555\"/><text x=\"" << px(lx + 30) << "\" y=\"" << px(ly + 4)
    << "\">" << xml_escape(k.a.label) << " (top)</text>\n";
  ly += 18;
  o << "<path d=\"M" << px(lx + 15) << "," << px(ly - 4) << " l-4,8 h8 z\" fill=\"#555\"/><text x=\"" << px(lx + 30) << "\" y=\"" << px(ly + 4)
    << "\">" << xml_escape(k.b.label) << " (bottom)</text>\n";
  ly += 22;
  o << "<line x1=\"" << px(lx) << "\" x2=\"" << px(lx + 30) << "\" y1=\"" << px(ly) << "\" y2=\"" << px(ly)
    << "\" stroke=\"#555\" stroke-dasharray=\"2,3\"/><text x=\"" << px(lx + 36) << "\" y=\"" << px(ly + 4) << "\">capacities</text>\n";
  o << "</g>\n</svg>\n";
  return o.str();
}

std::string svg_capacity(const std::vector<Bar>& bars, const std::string& unit) {
  const double left = 150, bw = 480, bh = 26, gap = 12, top = 34;
  const double H = top + bars.size() * (bh + gap) + 30, W = left + bw + 110;
  double vmax = 0;
  for (const Bar& b : bars)
    if (std::isfinite(b.value)) vmax = std::max(vmax, b.value);
  if (!(vmax > 0)) vmax = 1e-3;
  std::ostringstream o;
  o << svg_open(W, H) << "<text x=\"" << px(left)
    << "\" y=\"20\" font-size=\"15\" font-weight=\"bold\">Displacement capacity (last stable d)</text>\n";
  for (size_t k = 0; k < bars.size(); ++k) {
    const double y = top + k * (bh + gap);
    const double w = std::isfinite(bars[k].value) ? bars[k].value / vmax * bw : 0;
    o << "<text x=\"" << px(left - 8) << "\" y=\"" << px(y + bh / 2 + 5) << "\" text-anchor=\"end\" font-size=\"13\">" << xml_escape(bars[k].label)
      << "</text><rect x=\"" << px(left) << "\" y=\"" << px(y) << "\" width=\"" << px(w) << "\" height=\"" << px(bh) << "\" fill=\""
      << xml_escape(bars[k].color) << "\"/><text x=\"" << px(left + w + 6) << "\" y=\"" << px(y + bh / 2 + 5) << "\" font-size=\"13\">"
      << (std::isfinite(bars[k].value) ? fmt::mm(bars[k].value) + " " + xml_escape(unit) : "n/a") << "</text>\n";
  }
  o << "<line x1=\"" << px(left) << "\" x2=\"" << px(left) << "\" y1=\"" << px(top - 4) << "\" y2=\"" << px(H - 26)
    << "\" stroke=\"#333\"/>\n</svg>\n";
  return o.str();
}

}  // namespace masonry
