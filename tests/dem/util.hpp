// Small scenes for the DEM tests, built in code. SI units.
#pragma once

#include <cmath>

#include "case.hpp"

namespace masonry::test {

inline Block rect(const std::string& id, double x0, double y0, double x1, double y1, double density, bool support) {
  Block b;
  b.id = id;
  b.vertices = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
  b.density = density;
  b.support = support;
  return b;
}

// A fixed slab (top face at y = 0, centroid at (0, -0.05)) with soft joints so the tests run fast.
inline Case slab_case() {
  Case c;
  c.name = "test";
  c.source = "test";
  c.blocks.push_back(rect("ground", -0.6, -0.1, 0.6, 0.0, 0.0, true));
  c.dem.kn = 1e8;
  c.dem.ks = 4e7;
  c.motion.max_steps = 0;
  return c;
}

}  // namespace masonry::test
