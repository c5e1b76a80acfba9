#include "report/svg.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/escape.hpp"
#include "report/format.hpp"

namespace masonry {

using fmt::px;

std::string svg_open(double width, double height, const std::string& attrs) {
  std::string o = "<svg xmlns=\"http://www.w3.org/2000/svg\" ";
  if (!attrs.empty()) o += attrs + " ";
  o += "width=\"" + px(width) + "\" height=\"" + px(height) + "\" viewBox=\"0 0 " + px(width) + " " + px(height) +
       "\" font-family=\"Helvetica, Arial, sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  return o;
}

const char* series_color(size_t i) {
  static const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#7f7f7f"};
  return kPalette[i % 8];
}

double nice_step(double range, int n) {
  if (!(range > 0) || n < 1) return 1.0;
  const double raw = range / n, p = std::pow(10.0, std::floor(std::log10(raw))), q = raw / p;
  return (q < 1.5 ? 1 : q < 3 ? 2 : q < 7 ? 5 : 10) * p;
}

Ticks linear_ticks(double lo, double hi, int n, int digits, double label_scale) {
  Ticks t;
  if (!(hi >= lo) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
  t.step = nice_step(hi - lo, n);
  const double eps = t.step * 1e-6;
  // Multiples by index, not by adding the step, so round-off does not gather along the axis.
  for (long k = std::lround(std::ceil((lo - eps) / t.step)); k * t.step <= hi + eps; ++k) {
    const double v = k * t.step;
    const double shown = std::abs(v) < eps ? 0.0 : v;
    t.at.push_back(shown);
    t.label.push_back(fmt::g(shown * label_scale, digits));
  }
  return t;
}

Ticks decade_ticks(int d0, int d1) {
  Ticks t;
  t.step = 1;
  for (int d = d0; d <= d1; ++d) {
    const double v = std::pow(10.0, d);
    t.at.push_back(d);
    t.label.push_back(d >= 0 ? fmt::number(v, "%.0f", v) : d >= -3 ? fmt::number(v, "%.*f", -d, v) : "1e" + std::to_string(d));
  }
  return t;
}

double Plot::X(double x) const {
  const double v = xlog ? std::log10(std::max(x, 1e-300)) : x;
  return left + (std::max(v, x0) - x0) / (x1 - x0) * width;
}

double Plot::Y(double y) const {
  if (ylog && !(y > 0)) return top + height + band * 0.6;
  const double v = ylog ? std::max(std::log10(y), y0) : y;
  return top + (y1 - v) / (y1 - y0) * height;
}

std::string svg_axes(const Plot& p, const Ticks& x, const Ticks& y, const std::string& x_title, const std::string& y_title) {
  // Grid positions from tick values in axis units (log10 values on a log axis).
  const auto gx = [&](double v) { return p.left + (v - p.x0) / (p.x1 - p.x0) * p.width; };
  const auto gy = [&](double v) { return p.top + (p.y1 - v) / (p.y1 - p.y0) * p.height; };
  const double bottom = p.top + p.height + p.band;
  std::ostringstream o;
  o << "<g font-size=\"11\" fill=\"#333\">\n";
  for (size_t k = 0; k < y.at.size(); ++k) {
    const bool zero = !p.ylog && y.at[k] == 0.0;
    o << "<line x1=\"" << px(p.left) << "\" x2=\"" << px(p.left + p.width) << "\" y1=\"" << px(gy(y.at[k])) << "\" y2=\"" << px(gy(y.at[k]))
      << "\" stroke=\"" << (zero ? "#999" : "#e6e6e6") << "\"/><text x=\"" << px(p.left - 6) << "\" y=\"" << px(gy(y.at[k]) + 4)
      << "\" text-anchor=\"end\">" << xml_escape(y.label[k]) << "</text>\n";
  }
  for (size_t k = 0; k < x.at.size(); ++k)
    o << "<line x1=\"" << px(gx(x.at[k])) << "\" x2=\"" << px(gx(x.at[k])) << "\" y1=\"" << px(p.top) << "\" y2=\"" << px(bottom)
      << "\" stroke=\"#e6e6e6\"/><text x=\"" << px(gx(x.at[k])) << "\" y=\"" << px(bottom + 14) << "\" text-anchor=\"middle\">"
      << xml_escape(x.label[k]) << "</text>\n";
  o << "<rect x=\"" << px(p.left) << "\" y=\"" << px(p.top) << "\" width=\"" << px(p.width) << "\" height=\"" << px(p.height + p.band)
    << "\" fill=\"none\" stroke=\"#333\"/>\n";
  if (p.band > 0)
    o << "<line x1=\"" << px(p.left) << "\" x2=\"" << px(p.left + p.width) << "\" y1=\"" << px(p.top + p.height) << "\" y2=\"" << px(p.top + p.height)
      << "\" stroke=\"#333\" stroke-dasharray=\"3,3\"/><text x=\"" << px(p.left - 6) << "\" y=\"" << px(p.top + p.height + p.band * 0.6 + 4)
      << "\" text-anchor=\"end\">0</text>\n";
  if (!x_title.empty())
    o << "<text x=\"" << px(p.left + p.width / 2) << "\" y=\"" << px(bottom + 32) << "\" text-anchor=\"middle\" font-size=\"12\">"
      << xml_escape(x_title) << "</text>\n";
  if (!y_title.empty())
    o << "<text transform=\"translate(" << px(p.left - 50) << "," << px(p.top + p.height / 2)
      << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">" << xml_escape(y_title) << "</text>\n";
  o << "</g>\n";
  return o.str();
}

}  // namespace masonry
