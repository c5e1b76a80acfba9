// SVG pieces shared by every figure (no plotting dependency): the document's opening, and axes
// (grid, tick labels, frame, titles) over a plot area with linear or decade scales.
#pragma once

#include <string>
#include <vector>

namespace masonry {

// The opening of a standalone SVG: size, viewBox, font, white background. `attrs` are added to
// the <svg> element as they are (e.g. class="thrust" data-x0="70").
std::string svg_open(double width, double height, const std::string& attrs = "");

// The colour of the i-th series of a figure (supports, curves, parameters): the Okabe-Ito
// palette, safe for colour-blind readers, without its black (kept for references), then grey.
const char* series_color(size_t i);

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about n ticks over `range`.
double nice_step(double range, int n);

struct Ticks {
  std::vector<double> at;          // data values (log10 values on a decade axis)
  std::vector<std::string> label;  // plain text
  double step = 0;                 // the spacing of `at` (0 when fewer than two)
};
// The multiples of a nice step within [lo, hi] (about n of them), labelled value x label_scale
// with `digits` significant digits; a tick at round-off from zero reads 0.
Ticks linear_ticks(double lo, double hi, int n, int digits = 4, double label_scale = 1);
// Whole decades d0..d1 (log10 values), labelled 0.001, 1, 1000 and, below 0.001, 1e-5.
Ticks decade_ticks(int d0, int d1);

// A plot area in px and the data range it shows. On a log axis the range is in log10 units and
// X/Y take the value itself; values at or below the range's low end sit on it, and on a log y
// axis a value <= 0 sits in `band`, a strip below the scale (for exact zeros).
struct Plot {
  double left = 0, top = 0, width = 1, height = 1;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool xlog = false, ylog = false;
  double band = 0;  // px below the y scale inside the frame
  double X(double x) const;
  double Y(double y) const;
};

// Grid lines at the ticks (the y = 0 line darker), tick labels, the frame and the axis titles
// (plain text, escaped here). With a band, its top edge is dashed and labelled 0.
std::string svg_axes(const Plot& p, const Ticks& x, const Ticks& y, const std::string& x_title, const std::string& y_title);

}  // namespace masonry
