// The sensitivity section's figures: a tornado chart of the one-at-a-time ranges, a histogram of
// the sampled capacities, PRD against DEM per point. Inline SVG, no script.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/svg.hpp"
#include "sweep/sweep.hpp"

namespace masonry {

namespace {

using fmt::px;

// An option's value in a label: 4 significant digits.
std::string v4(double x) { return fmt::g(x, 4); }

std::string title(double x, double y, const std::string& text) {
  return "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" font-size=\"15\" font-weight=\"bold\">" + xml_escape(text) + "</text>\n";
}

std::string vline(const Plot& p, double x, const char* colour, const char* dash, const std::string& tip) {
  return "<line x1=\"" + px(p.X(x)) + "\" x2=\"" + px(p.X(x)) + "\" y1=\"" + px(p.top) + "\" y2=\"" + px(p.top + p.height) + "\" stroke=\"" + colour +
         "\" stroke-width=\"1.6\"" + (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : std::string()) + "><title>" + xml_escape(tip) +
         "</title></line>\n";
}

}  // namespace

std::string svg_tornado(const SweepPlan& p, const MethodSensitivity& m) {
  struct Bar {
    const ParameterSensitivity* ps;
    double lo, hi, x_lo, x_hi;
  };
  std::vector<Bar> bars;
  std::optional<double> base;
  for (const ParameterSensitivity& ps : m.parameters) {
    if (ps.ignored || ps.capacities.size() < 2) continue;
    const auto [a, b] = std::minmax_element(ps.capacities.begin(), ps.capacities.end());
    bars.push_back({&ps, *a, *b, ps.values[a - ps.capacities.begin()], ps.values[b - ps.capacities.begin()]});
    if (ps.base_capacity) base = ps.base_capacity;
  }
  if (bars.empty()) return "";
  // The widest range on top.
  std::stable_sort(bars.begin(), bars.end(), [](const Bar& a, const Bar& b) { return a.hi - a.lo > b.hi - b.lo; });
  const double row = 30, left = 230, right = 60, top = 48, W = 860;
  const double ph = row * double(bars.size()), H = top + ph + 56;
  double xmax = 0;
  for (const Bar& b : bars) xmax = std::max(xmax, b.hi);
  if (base) xmax = std::max(xmax, *base);
  if (!(xmax > 0)) xmax = 1e-3;
  xmax *= 1.08;
  const Plot plot{left, top, W - left - right, ph, 0, xmax, 0, 1};
  std::ostringstream o;
  o << svg_open(W, H) << title(left, 22, std::string(method_label(m.method)) + ": capacity over each option's range, one at a time") << "<text x=\""
    << px(left) << "\" y=\"38\" font-size=\"11\" fill=\"#555\">"
    << xml_escape(p.sample ? "the other options at the base point (vertical line: its capacity); bar ends labelled with x"
                           : "the other options at their middle values (vertical line: the capacity there); bar ends labelled with x")
    << "</text>\n"
    << svg_axes(plot, linear_ticks(0, xmax, 8, 4), Ticks{}, "capacity: last stable d (" + path_unit(p.base) + ")", "");
  for (size_t i = 0; i < bars.size(); ++i) {
    const Bar& b = bars[i];
    const double y = top + row * double(i) + 6, h = row - 12;
    const double x0 = plot.X(b.lo), x1 = std::max(plot.X(b.hi), x0 + 2);
    o << "<text x=\"" << px(left - 8) << "\" y=\"" << px(y + h / 2 + 4) << "\" font-size=\"12\" text-anchor=\"end\">" << xml_escape(b.ps->key)
      << "</text>\n"
      << "<rect x=\"" << px(x0) << "\" y=\"" << px(y) << "\" width=\"" << px(x1 - x0) << "\" height=\"" << px(h) << "\" fill=\"" << series_color(0)
      << "\" fill-opacity=\"0.75\"><title>" << xml_escape(b.ps->key) << ": " << fmt::g(b.lo, 4) << " " << path_unit(p.base) << " at " << v4(b.x_lo)
      << ", " << fmt::g(b.hi, 4) << " " << path_unit(p.base) << " at " << v4(b.x_hi)
      << "</title></rect>\n"
      // The low end's x outside the bar, or inside it where the bar starts at the axis.
      << (x0 - left > 40 ? "<text x=\"" + px(x0 - 3) + "\" y=\"" + px(y + h / 2 + 4) + "\" font-size=\"10\" text-anchor=\"end\" fill=\"#333\">"
                         : "<text x=\"" + px(x0 + 3) + "\" y=\"" + px(y + h / 2 + 4) + "\" font-size=\"10\" fill=\"#fff\">")
      << v4(b.x_lo) << "</text>\n"
      << "<text x=\"" << px(x1 + 3) << "\" y=\"" << px(y + h / 2 + 4) << "\" font-size=\"10\" fill=\"#333\">" << v4(b.x_hi) << "</text>\n";
  }
  if (base) o << vline(plot, *base, "#000", "4,3", "base point: " + fmt::g(*base, 4) + " " + path_unit(p.base));
  o << "</svg>\n";
  return o.str();
}

std::string svg_histogram(const SweepPlan& p, const SweepTable& t, const MethodSensitivity& m) {
  if (!p.sample || m.located < 2) return "";
  std::vector<double> caps;
  for (const SweepRun& r : p.runs)
    if (r.method == m.method && r.point == SweepPoint::sample && r.index < int(t.size()) && t[r.index] && located(*t[r.index]))
      caps.push_back(t[r.index]->capacity);
  const double lo = m.min, hi = m.max > m.min ? m.max : m.min + 1e-3;
  // About sqrt(n) bins, at most 40.
  const int nb = std::clamp(static_cast<int>(std::ceil(std::sqrt(double(caps.size())))), 5, 40);
  const double w = (hi - lo) / nb;
  std::vector<int> count(nb, 0);
  for (double c : caps) count[std::min(nb - 1, static_cast<int>((c - lo) / w))]++;
  const int cmax = *std::max_element(count.begin(), count.end());
  const double W = 860, left = 70, right = 40, top = 44, ph = 300, H = top + ph + 56;
  const double ymax = cmax * 1.12 + 0.5;
  const Plot plot{left, top, W - left - right, ph, lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo), 0, ymax};
  std::ostringstream o;
  o << svg_open(W, H) << title(left, 22, std::string(method_label(m.method)) + ": the " + std::to_string(caps.size()) + " sampled capacities")
    << svg_axes(plot, linear_ticks(plot.x0, plot.x1, 8, 4), linear_ticks(0, ymax, 6, 4), "capacity: last stable d (" + path_unit(p.base) + ")",
                "samples");
  for (int b = 0; b < nb; ++b) {
    if (!count[b]) continue;
    const double x0 = plot.X(lo + b * w), x1 = plot.X(lo + (b + 1) * w);
    o << "<rect x=\"" << px(x0) << "\" y=\"" << px(plot.Y(count[b])) << "\" width=\"" << px(std::max(1.0, x1 - x0 - 1)) << "\" height=\""
      << px(plot.Y(0) - plot.Y(count[b])) << "\" fill=\"" << series_color(0) << "\" fill-opacity=\"0.8\"><title>" << fmt::g(lo + b * w, 4) << " to "
      << fmt::g(lo + (b + 1) * w, 4) << " " << path_unit(p.base) << ": " << count[b] << "</title></rect>\n";
  }
  for (size_t i = 0; i < m.percentiles.size(); ++i) {
    const auto& [q, v] = m.percentiles[i];
    // Labels one line apart: percentiles may lie close together.
    o << vline(plot, v, "#000", q == 50 ? "" : "5,3", std::to_string(q) + "th percentile: " + fmt::g(v, 4) + " " + path_unit(p.base)) << "<text x=\""
      << px(plot.X(v) + 3) << "\" y=\"" << px(top + 12 + 14 * double(i)) << "\" font-size=\"11\">" << q << "th: " << fmt::g(v, 3) << " "
      << path_unit(p.base) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

std::string svg_prd_dem(const SweepPlan& p, const SweepSensitivity& s) {
  if (s.pairs.empty()) return "";
  double vmax = 0;
  for (const PrdDemPair& x : s.pairs) vmax = std::max({vmax, x.prd_capacity, x.dem_capacity});
  if (!(vmax > 0)) vmax = 1e-3;
  vmax *= 1.1;
  const double W = 600, left = 74, top = 44, side = 440, H = top + side + 56;
  const Plot plot{left, top, side, side, 0, vmax, 0, vmax};
  std::ostringstream o;
  o << svg_open(W, H) << title(left, 22, "DEM against PRD, point by point")
    << svg_axes(plot, linear_ticks(0, vmax, 6, 4), linear_ticks(0, vmax, 6, 4), "PRD capacity (" + path_unit(p.base) + ")",
                "DEM capacity (" + path_unit(p.base) + ")");
  const auto diag = [&](double f, const char* dash, const std::string& tip) {
    o << "<line x1=\"" << px(plot.X(0)) << "\" y1=\"" << px(plot.Y(0)) << "\" x2=\"" << px(plot.X(vmax / std::max(f, 1.0))) << "\" y2=\""
      << px(plot.Y(vmax * std::min(f, 1.0))) << "\" stroke=\"#666\" stroke-width=\"1.2\""
      << (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") << "><title>" << xml_escape(tip) << "</title></line>\n";
  };
  diag(1, "", "DEM = PRD");
  diag(1 + p.tolerance, "4,3", "DEM = PRD x (1 + tolerance)");
  diag(1 - p.tolerance, "4,3", "DEM = PRD x (1 - tolerance)");
  o << "<g fill=\"" << series_color(1) << "\">\n";
  for (const PrdDemPair& x : s.pairs) {
    const std::string label = x.sample >= 0 ? "sample " + std::to_string(x.sample) : "run " + std::to_string(x.dem);
    o << "<circle cx=\"" << px(plot.X(x.prd_capacity)) << "\" cy=\"" << px(plot.Y(x.dem_capacity)) << "\" r=\"4\"><title>" << xml_escape(label)
      << ": PRD " << fmt::g(x.prd_capacity, 4) << " " << path_unit(p.base) << ", DEM " << fmt::g(x.dem_capacity, 4) << " " << path_unit(p.base)
      << "</title></circle>\n";
    if (s.pairs.size() <= 12)
      o << "<text x=\"" << px(plot.X(x.prd_capacity) + 6) << "\" y=\"" << px(plot.Y(x.dem_capacity) - 6) << "\" font-size=\"10\" fill=\"#333\">"
        << xml_escape(label) << "</text>\n";
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

}  // namespace masonry
