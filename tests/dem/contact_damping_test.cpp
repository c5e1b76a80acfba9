// Contact damping (dem.contact_damping, dem/README.md "Contact damping"): viscous damping of the
// joints' relative motion. It must stop the joints of a structure whose joints are stiff against
// its weights from ratcheting on the vibrations that local damping leaves alone, leave the statics
// as they are, and keep the integration within its stability limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dem/dem.hpp"
#include "dem/variants.hpp"
#include "model/interfaces.hpp"
#include "model/io.hpp"
#include "util.hpp"

namespace {

using namespace masonry;

// Where a point of the initial configuration on block b is in record `to`, moved rigidly with the
// block from record `from` (poses: centroid and rotation since the start).
Vec2 carried(const Vec2& p, const Pose& from, const Pose& to) {
  const double a = to.angle - from.angle, c = std::cos(a), s = std::sin(a);
  const Vec2 r = p - Vec2(from.x, from.y);
  return Vec2(to.x + c * r.x() - s * r.y(), to.y + s * r.x() + c * r.y());
}

// The largest slip of any joint between two records: the relative tangential displacement of the
// two blocks at the joint's corner that stays closed (the one whose normal gap changed least), so
// a hinge turning about that corner counts as no slip.
double largest_slip(const Case& c, const RunResult& r, size_t from, size_t to) {
  double worst = 0;
  for (const Interface& J : detect_interfaces(c, c.prd.contact_tolerance)) {
    const Pose &ai = r.steps[from].poses[size_t(J.i)], &aj = r.steps[from].poses[size_t(J.j)];
    const Pose &bi = r.steps[to].poses[size_t(J.i)], &bj = r.steps[to].poses[size_t(J.j)];
    const double turn = bi.angle - ai.angle;
    const Vec2 t0 = (J.b - J.a).normalized();
    const Vec2 t(std::cos(turn) * t0.x() - std::sin(turn) * t0.y(), std::sin(turn) * t0.x() + std::cos(turn) * t0.y());
    const Vec2 n(-t.y(), t.x());
    double best_gap = INFINITY, slip = 0;
    for (const Vec2& corner : {J.a, J.b}) {
      // The corner as each block carries it from `from` to `to`: their relative motion.
      const Vec2 rel = (carried(corner, aj, bj) - corner) - (carried(corner, ai, bi) - corner);
      if (std::abs(rel.dot(n)) < best_gap) best_gap = std::abs(rel.dot(n)), slip = std::abs(rel.dot(t));
    }
    worst = std::max(worst, slip);
  }
  return worst;
}

// The segmental arch of tests/dem/passing-hinge-arch.json with its weights and its load a
// thousandth of the file's (density 2 kg/m^3, a 3 N load; trial t3's R4): the same structure to
// a rigid-block method, with joints a thousand times stiffer against the weights. Up to 3 cm of
// spreading its joints hinge and none slides (PRD's mechanism; the DEM at density 2000 moves
// them by microns). Without contact damping the joints vibrate on the blocks' steady motion
// during the moves, which local damping, opposing each block's own velocity, does not take out;
// each vibration takes the light joints past friction, and the slips add up: 1.9 mm at the
// crown's joint by 3 cm, 43 mm by the run's end, which then ends at 0.3216 m against PRD's
// 0.336. With it, each joint moves within its elastic shear range, tan(phi) kn / ks times the
// largest overlap (the spring stretch at which friction stops it).
TEST(DemContactDamping, TheJointsOfALightArchDoNotRatchet) {
  Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/tests/dem/passing-hinge-arch.json");
  for (Block& b : c.blocks) b.density *= 1e-3;
  for (Load& l : c.loads) l.force *= 1e-3;
  c.motion.max_steps = 3;
  DemSettings s = DemSettings::from_case(c);
  s.contact_damping = 0.3;
  const RunResult r = dem_run(c, s);
  ASSERT_EQ(r.status, RunStatus::max_steps) << r.message;
  ASSERT_EQ(r.steps.size(), 4u);
  double overlap = 0;
  for (const StepRecord& x : r.steps) overlap = std::max(overlap, x.hold->max_overlap);
  const double elastic = std::tan(c.dem.friction_angle * M_PI / 180) * 2 * (1 + c.dem.poisson) * overlap;
  EXPECT_LT(largest_slip(c, r, 0, 3), 10 * elastic) << "overlap " << overlap;
}

// An arch thinner than its least thickness falls, drawn with non-convex voussoirs too (trial t3's
// R3: each intrados two chords, a reflex vertex; PRD's check finds a mechanism, and the least
// thickness with these chords is 0.097-0.100 m against its 0.0905). Without contact damping the
// DEM's settling crept through the whole hold cap without slowing down and ended undecided (not
// traced further; the voussoirs' joints are stiff against their small weights, the regime of the
// ratchet above). With it the arch falls while it settles, as its convex twin does either way.
TEST(DemContactDamping, AnArchOfNonConvexVoussoirsBelowItsLeastThicknessFalls) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/tests/dem/nonconvex-thin-arch.json");
  DemSettings s = DemSettings::from_case(c);
  s.contact_damping = 0.3;
  const RunResult r = dem_run(c, s);
  EXPECT_EQ(r.status, RunStatus::collapse) << r.message;
  EXPECT_EQ(r.stable_steps, 0);
}

// The statics do not change: a block on a slab tilting a degree per increment topples at
// atan(b/h) with contact damping as without, within the bracket and the equilibrium tolerance's
// resolution of the tipping point (as DemBracket.CapacityDoesNotMoveWithTheIncrement).
TEST(DemContactDamping, ABlockTopplesAtItsLimit) {
  const double b = 0.2, h = 0.4;
  Case c = test::tilt_case(b, h, 35);
  c.dem.contact_damping = 0.3;
  const RunResult r = test::tilt_run(c);
  ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
  const double resolution = 1e-4 * std::sqrt((b * b + h * h) / 12) / (0.5 * std::hypot(b, h));
  EXPECT_NEAR(r.capacity, std::atan(b / h), c.dem.bracket_fraction * c.motion.step + 2 * resolution + 0.1 * M_PI / 180);
}

// The time step allows for the damping of each contact: the central differences with the damping
// force taken from the half step before are stable for omega dt <= 2 (sqrt(1 + zeta^2) - zeta)
// (the amplification matrix's trace against 1 + its determinant), so the bound shrinks by that
// factor. And two increments of a capacity run on joints stiff against the weights, where the
// dampers work hardest, stay within the energy balance at the full step (dem_run throws where
// they do not: a damper feeding energy in, by its sign or its scale, blows up). The bound's own
// slack, not this factor, is what the structure's fastest modes need (dem/README.md, "Contact
// damping": a probe of the damping's first form blew up at 1.4-3.8 times the undamped bound), so
// no run here can fail on the factor alone.
TEST(DemContactDamping, TheTimeStepAllowsForTheDamping) {
  Case c = test::tilt_case(0.2, 0.4, 35);
  const double plain = DemModel(c, DemSettings::from_case(c)).critical_dt();
  for (const double zeta : {0.1, 0.5, 0.9}) {
    c.dem.contact_damping = zeta;
    EXPECT_NEAR(DemModel(c, DemSettings::from_case(c)).critical_dt(), plain * (std::sqrt(1 + zeta * zeta) - zeta), 1e-12 * plain);
  }
  Case light = load_case(std::string(MASONRY_SOURCE_DIR) + "/tests/dem/passing-hinge-arch.json");
  for (Block& b : light.blocks) b.density *= 1e-3;
  for (Load& l : light.loads) l.force *= 1e-3;
  light.motion.max_steps = 2;
  for (const double zeta : {0.3, 0.9}) {
    DemSettings s = DemSettings::from_case(light);
    s.contact_damping = zeta;
    EXPECT_NO_THROW(dem_run(light, s)) << "zeta " << zeta;
  }
}

// The convergence study varies the damping of the joints as a setting that must not matter: on
// where the case has none, off where it has some, nothing else changed.
TEST(DemContactDamping, TheConvergenceStudyVariesIt) {
  for (const double zeta : {0.0, 0.2}) {
    DemSettings base;
    base.contact_damping = zeta;
    int found = 0;
    for (const DemVariant& v : convergence_variants(base)) {
      if (v.name != "contact-damping") {
        EXPECT_EQ(v.settings.contact_damping, zeta) << v.name;
        continue;
      }
      ++found;
      EXPECT_EQ(v.settings.contact_damping, zeta > 0 ? 0.0 : 0.3);
      EXPECT_EQ(v.settings.damping, base.damping);
      EXPECT_EQ(v.settings.stiffness_reduction, base.stiffness_reduction);
      EXPECT_EQ(v.settings.kinetic_ratio, base.kinetic_ratio);
    }
    EXPECT_EQ(found, 1);
  }
}

}  // namespace
