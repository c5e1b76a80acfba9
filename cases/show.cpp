// case_svg: the case as the solvers will get it, drawn: blocks with their ids, supports hatched,
// the joints the loader detected, the point loads and the support motion.
#include "cases/show.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "model/interfaces.hpp"
#include "report/escape.hpp"

namespace masonry {

namespace {

// Case text as SVG text: control characters escaped and long ids shortened first.
std::string svg_text(const std::string& s) { return xml_escape(printable(s, 200)); }

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

}  // namespace

std::string case_svg(const Case& c) {
  // Drawing coordinates: x right, y up in the case; SVG's y points down, so y is negated.
  const Bounds box = scene_bounds(c);
  const Vec2 lo = box.lo, hi = box.hi;
  const double L = box.size(), margin = 0.08 * L;
  const double font = 0.025 * L, stroke = 0.002 * L;
  auto pt = [](const Vec2& p) { return num(p.x()) + "," + num(-p.y()); };
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" << num(lo.x() - margin) << " " << num(-hi.y() - margin) << " "
    << num(hi.x() - lo.x() + 2 * margin) << " " << num(hi.y() - lo.y() + 2 * margin) << "\" width=\"1000\">\n";
  o << "<title>" << svg_text(c.name) << " (m; supports hatched, joints red, loads and support motion blue)</title>\n";
  o << "<defs>\n"
    << "<pattern id=\"hatch\" patternUnits=\"userSpaceOnUse\" width=\"" << num(4 * font / 5) << "\" height=\"" << num(4 * font / 5)
    << "\" patternTransform=\"rotate(45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"" << num(4 * font / 5) << "\" stroke=\"#555\" stroke-width=\""
    << num(stroke) << "\"/></pattern>\n"
    << "<marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\">"
    << "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#1f5fbf\"/></marker>\n"
    << "</defs>\n";
  o << "<g id=\"blocks\">\n";
  for (const Block& b : c.blocks) {
    o << "<polygon class=\"block" << (b.support ? " support" : "") << "\" data-id=\"" << svg_text(b.id) << "\" points=\"";
    for (size_t k = 0; k < b.vertices.size(); ++k) o << (k ? " " : "") << pt(b.vertices[k]);
    o << "\" fill=\"" << (b.support ? "url(#hatch)" : "#e8dcc4") << "\" stroke=\"#333\" stroke-width=\"" << num(stroke) << "\"/>\n";
  }
  o << "</g>\n<g id=\"joints\">\n";
  for (const Interface& J : detect_interfaces(c, c.prd.contact_tolerance))
    o << "<line class=\"joint\" x1=\"" << num(J.a.x()) << "\" y1=\"" << num(-J.a.y()) << "\" x2=\"" << num(J.b.x()) << "\" y2=\"" << num(-J.b.y())
      << "\" stroke=\"#c0392b\" stroke-width=\"" << num(2 * stroke) << "\"/>\n";
  o << "</g>\n<g id=\"ids\" font-family=\"sans-serif\" font-size=\"" << num(font) << "\" text-anchor=\"middle\">\n";
  for (const Block& b : c.blocks) {
    const Vec2 m = centroid(b.vertices);
    o << "<text x=\"" << num(m.x()) << "\" y=\"" << num(-m.y() + font / 3) << "\">" << svg_text(b.id) << "</text>\n";
  }
  o << "</g>\n<g id=\"loads\" stroke=\"#1f5fbf\" fill=\"none\" stroke-width=\"" << num(2 * stroke) << "\">\n";
  // Loads: arrows ending at their point, the largest a tenth of the scene long.
  double fmax = 0;
  for (const Load& l : c.loads) fmax = std::max(fmax, l.force.norm());
  for (const Load& l : c.loads) {
    if (!(fmax > 0) || l.force.norm() == 0) continue;
    const Vec2 tail = l.point - 0.1 * L * l.force / fmax;
    o << "<line class=\"load\" x1=\"" << num(tail.x()) << "\" y1=\"" << num(-tail.y()) << "\" x2=\"" << num(l.point.x()) << "\" y2=\""
      << num(-l.point.y()) << "\" marker-end=\"url(#arrow)\"><title>" << num(l.force.x()) << ", " << num(l.force.y()) << " N</title></line>\n";
  }
  o << "</g>\n<g id=\"motion\" stroke=\"#1f5fbf\" fill=\"none\" stroke-width=\"" << num(2 * stroke) << "\">\n";
  // Support motion per unit of d: an arrow for the translation (a tenth of the scene per unit of
  // its direction) and a quarter-circle arrow about `about` for the rotation (its sense).
  for (const SupportMotion& m : c.motion.supports) {
    const Vec2 from = centroid(c.blocks[m.block].vertices);
    if (m.translation.norm() > 0) {
      const Vec2 to = from + 0.1 * L * m.translation.normalized();
      o << "<line class=\"motion\" x1=\"" << num(from.x()) << "\" y1=\"" << num(-from.y()) << "\" x2=\"" << num(to.x()) << "\" y2=\"" << num(-to.y())
        << "\" marker-end=\"url(#arrow)\"/>\n";
    }
    if (m.rotation != 0) {
      const double r = 0.05 * L, s = m.rotation > 0 ? 1.0 : -1.0;
      const Vec2 a = m.about + Vec2(r, 0), b = m.about + Vec2(0, s * r);
      o << "<circle class=\"pivot\" cx=\"" << num(m.about.x()) << "\" cy=\"" << num(-m.about.y()) << "\" r=\"" << num(2 * stroke)
        << "\" fill=\"#1f5fbf\"/>\n";
      // SVG's sweep flag in the flipped frame: counter-clockwise in the case is clockwise on screen.
      o << "<path class=\"motion\" d=\"M" << pt(a) << " A" << num(r) << "," << num(r) << " 0 0," << (s > 0 ? 0 : 1) << " " << pt(b)
        << "\" marker-end=\"url(#arrow)\"/>\n";
    }
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

}  // namespace masonry
