// SVG figures of a comparison, written directly (no plotting dependency): the structure on its
// deformed geometry, thrust curves, capacity bars. Every text that comes from a case (names,
// ids) goes through xml_escape.
#pragma once

#include <string>
#include <vector>

#include "compare/compare.hpp"

namespace masonry {

// World window and force scale shared by every structure drawing of one comparison, so frames
// do not jump and forces are comparable between methods and steps.
struct DrawFrame {
  Vec2 lo{0, 0}, hi{1, 1};  // world window, m
  double force_len = 1.0;   // m of drawing per unit of F / W
  double weight = 1.0;      // N, total weight (forces are drawn relative to it)
  double hinge_gap = 0.0;   // m, the opening a hinge needs beyond its settled gap (settled_gap)
};
// The window covering every stable record of the runs, with room for the reaction arrows; the
// hinge rule of the runs' comparisons (the widest settled gap of any of them).
DrawFrame draw_frame(const Case& c, const std::vector<const RunResult*>& runs);

// One panel per (run, record) side by side, titles above, a legend below. A null record draws
// an empty panel with the title only.
struct Panel {
  const RunResult* run = nullptr;
  const StepRecord* record = nullptr;
  std::string title;     // plain text (escaped here), bold
  std::string subtitle;  // second line, e.g. "d = 150 mm"
};
// `id` prefixes the SVG's internal ids (pattern, marker): several drawings in one HTML page need
// distinct ids, since a definition inside a hidden drawing does not render for the others.
// `titles`: every block a path of its own with its id as a tooltip (the figures); without, the
// blocks are one path per fill (the page's slider, which repeats the drawing at every position).
std::string svg_structure(const Case& c, const std::vector<Panel>& panels, const DrawFrame& f, double panel_width = 470, const std::string& id = "s",
                          bool titles = true);

// H/W and V/W of every support against d (mm), both runs over their own stable range, mechanism
// changes marked, capacities marked. With `cursor`, the SVG carries a vertical cursor line per
// panel (class "cursor") and data-x0 / data-sx (px at d = 0, px per m) for a script to move it.
std::string svg_thrust(const Comparison& k, const RunResult& a, const RunResult& b, bool cursor = false);

// Horizontal bars: capacity of each run, value printed at the bar's end in `unit` ("mm": d x 1000
// with its unit, milli(path_unit)).
struct Bar {
  std::string label;
  double value = 0.0;  // m
  std::string color;
};
std::string svg_capacity(const std::vector<Bar>& bars, const std::string& unit);

}  // namespace masonry
