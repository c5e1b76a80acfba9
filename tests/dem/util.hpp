// Small scenes for the DEM tests, built in code. SI units.
#pragma once

#include <cmath>
#include <functional>

#include "cases/generators.hpp"
#include "dem/dem.hpp"
#include "model/case.hpp"

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

// A block b wide and h high on the slab, which turns about its centroid one degree per
// increment (1 rad per m of d, so d is the tilt in rad): it slides when the tilt reaches phi if
// tan(phi) < b/h, and topples at atan(b/h) otherwise.
inline Case tilt_case(double b, double h, double phi_deg) {
  Case c = slab_case();
  c.blocks.push_back(rect("block", -b / 2, 0, b / 2, h, 2000, false));
  SupportMotion m;
  m.block = 0;
  m.rotation = 1.0;
  m.about = Vec2(0, -0.05);
  c.motion.supports.push_back(m);
  c.motion.step = M_PI / 180;
  c.motion.max_steps = 80;
  c.dem.friction_angle = phi_deg;
  return c;
}

// Its DEM run at the default protocol (the support speed servoed on the kinetic energy).
inline RunResult tilt_run(const Case& c, const std::function<void(const RunResult&)>& on_step = {}) {
  DemSettings s = DemSettings::from_case(c);
  s.collapse_drift = 0.02;  // m; the blocks are 0.2-0.4 m
  return dem_run(c, s, on_step);
}

// The 12-voussoir semicircular arch (R = 1 m, t = 0.15 m) on a support spreading 4 mm per
// increment, joints ten times softer than E / h as the paper ran 3DEC.
inline Case semicircular_arch_case() {
  CircularArch p;
  p.radius = 1.0;
  p.thickness = 0.15;
  p.embrace = M_PI;
  p.voussoirs = 12;
  p.step = 0.004;
  p.max_steps = 200;
  Case c = circular_arch(p);
  c.dem.friction_angle = 35;
  c.dem.stiffness_reduction = 10;
  return c;
}

}  // namespace masonry::test
