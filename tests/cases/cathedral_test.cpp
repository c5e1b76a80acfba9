// The Gothic cathedral generator: validity, the paper's main dimensions, the area of the drawing
// computed from the parameters, joints where the drawing has them.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "case_checks.hpp"
#include "cases/generators.hpp"

namespace masonry {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

const Case& default_cathedral() {
  static const Case c = gothic_cathedral(GothicCathedral{});
  return c;
}

TEST(Cathedral, ValidWith276BlocksAndFourSupports) {
  const Case& c = default_cathedral();
  test::expect_valid_case(c);
  int supports = 0, free = 0;
  for (const Block& b : c.blocks) (b.support ? supports : free)++;
  EXPECT_EQ(supports, 4);
  EXPECT_EQ(free, 276);  // the paper's count (Fig. 14)
  // Supports numbered from the left, the paper's pillars: buttress, pier, pier, buttress.
  double last = -INFINITY;
  for (int k = 1; k <= 4; ++k) {
    const int i = c.block_index("support-" + std::to_string(k));
    ASSERT_GE(i, 0);
    EXPECT_TRUE(c.blocks[i].support);
    const double x = centroid(c.blocks[i].vertices).x();
    EXPECT_GT(x, last);
    last = x;
  }
  // The third from the left is under the right nave pier: between the nave and the aisle.
  const GothicCathedral p;
  const Vec2 s3 = centroid(c.blocks[c.block_index("support-3")].vertices);
  EXPECT_GT(s3.x(), p.nave_span / 2);
  EXPECT_LT(s3.x(), p.nave_span / 2 + p.pier_width + p.aisle_thickness);
  EXPECT_TRUE(c.motion.supports.empty());  // the generator's default: as it stands
}

TEST(Cathedral, PaperDimensions) {
  const Case& c = default_cathedral();
  const GothicCathedral p;
  // Nave and aisle heights are the intrados crowns: the lower ends of the crown joints.
  const auto ifs = detect_interfaces(c, c.prd.contact_tolerance);
  auto crown_height = [&](const std::string& a, const std::string& b) {
    const int i = c.block_index(a), j = c.block_index(b);
    for (const Interface& f : ifs)
      if ((f.i == i && f.j == j) || (f.i == j && f.j == i)) {
        EXPECT_NEAR(f.a.x(), f.b.x(), 1e-12) << a << "|" << b << ": crown joint not vertical";
        return std::min(f.a.y(), f.b.y());
      }
    ADD_FAILURE() << "no crown joint " << a << "|" << b;
    return 0.0;
  };
  const int half = p.nave_voussoirs / 2;
  char a[32], b[32];
  std::snprintf(a, sizeof a, "nave-%02d", half - 1);
  std::snprintf(b, sizeof b, "nave-%02d", half);
  EXPECT_NEAR(crown_height(a, b), 42.00, 1e-9);
  std::snprintf(a, sizeof a, "R-aisle-%02d", p.aisle_voussoirs / 2 - 1);
  std::snprintf(b, sizeof b, "R-aisle-%02d", p.aisle_voussoirs / 2);
  EXPECT_NEAR(crown_height(a, b), 19.00, 1e-9);
  // Depths: arches (vaults) get the bay, 7.30 m.
  for (const Block& blk : c.blocks) {
    if (starts_with(blk.id, "nave-") || blk.id.find("aisle-") != std::string::npos) {
      EXPECT_DOUBLE_EQ(blk.depth, 7.30) << blk.id;
    }
    if (!blk.support) {
      EXPECT_DOUBLE_EQ(blk.density, 1800.0) << blk.id;
    }
  }
}

TEST(Cathedral, MirrorSymmetric) {
  const Case& c = default_cathedral();
  std::map<std::string, const Block*> by_id;
  for (const Block& b : c.blocks) by_id[b.id] = &b;
  int pairs = 0;
  for (const Block& b : c.blocks) {
    if (!starts_with(b.id, "L-")) continue;
    const auto it = by_id.find("R-" + b.id.substr(2));
    ASSERT_NE(it, by_id.end()) << b.id;
    const Block& r = *it->second;
    ASSERT_EQ(b.vertices.size(), r.vertices.size());
    for (const Vec2& v : b.vertices) {
      double best = INFINITY;
      for (const Vec2& w : r.vertices) best = std::min(best, (Vec2(-v.x(), v.y()) - w).norm());
      EXPECT_LT(best, 1e-12) << b.id;
    }
    EXPECT_EQ(b.depth, r.depth);
    ++pairs;
  }
  EXPECT_GT(pairs, 100);
}

// The drawing's area from the parameters alone: rectangles of the piers and buttresses minus the
// buttresses' step-backs at the flyer seats, the flyers' ring sectors, and the arches' halves.
double cathedral_area(const GothicCathedral& p) {
  const double x1 = p.nave_span / 2, x2 = x1 + p.pier_width, x3 = x2 + p.aisle_thickness;
  const double x4 = x3 + p.aisle_span, x5 = x4 + p.aisle_thickness, x6 = x5 + p.buttress_width;
  const double ya = p.aisle_springing, yn = p.nave_springing, yb = p.buttress_height, t = p.flyer_thickness;
  double area = 0;
  // Pier: wide part up to the aisle springing, shaft up to the nave springing.
  const double pier = (x3 - x1) * ya + (x2 - x1) * (yn - ya);
  // A flyer is the ring between ri and ri + t over the angle from its foot up to its head
  // (the top of the circle), the intrados circle through the head (its top) and the foot.
  struct Flyer {
    double area;
    Vec2 pe;  // the foot's extrados corner, where the buttress steps back
  };
  auto flyer = [&](double xh, double yh, double xf, double yf) {
    const double s = xf - xh, h = yh - yf, ri = (s * s + h * h) / (2 * h), re = ri + t;
    const Vec2 c(xh, yh - ri);
    const double psi = std::atan2(yf - c.y(), s);
    return Flyer{(re * re - ri * ri) / 2 * (kPi / 2 - psi), c + re / ri * Vec2(s, yf - c.y())};
  };
  const Flyer lower = flyer(x2, p.lower_flyer_head, x5, p.lower_flyer_foot);
  const Flyer upper = flyer(x2, p.upper_flyer_head, lower.pe.x(), p.upper_flyer_foot);
  // Buttress: [x4, x6] up to the aisle springing, [x5, x6] above, less what lies inside the
  // step-backs: over each seat the triangle above the sloping foot joint, then the strip up to the
  // top.
  double buttress = (x6 - x4) * ya + (x6 - x5) * (yb - ya);
  const Vec2 pi1(x5, p.lower_flyer_foot), pi2(lower.pe.x(), p.upper_flyer_foot);
  buttress -= 0.5 * (lower.pe.x() - pi1.x()) * (lower.pe.y() - pi1.y()) + (lower.pe.x() - x5) * (yb - lower.pe.y());
  buttress -= 0.5 * (upper.pe.x() - pi2.x()) * (upper.pe.y() - pi2.y()) + (upper.pe.x() - lower.pe.x()) * (yb - upper.pe.y());
  // Arches with horizontal springing: half clear span a, rise f, eccentricity from
  // (a + e)^2 - e^2 = f^2.
  auto arch = [&](double a, double f, double th) {
    const double e = (f * f - a * a) / (2 * a), ri = a + e;
    return 2 * test::pointed_half_area(e, ri, ri + th, kPi);
  };
  const double nave = arch(x1, p.nave_height - yn, p.nave_thickness);
  const double aisle = arch(p.aisle_span / 2, p.aisle_height - ya, p.aisle_thickness);
  area = 2 * (pier + buttress + lower.area + upper.area + aisle) + nave;
  return area;
}

TEST(Cathedral, AreaOfTheDrawing) {
  for (double course : {1.0, 0.5}) {
    GothicCathedral p;
    p.course = course;
    const Case c = gothic_cathedral(p);
    EXPECT_NEAR(test::free_area(c) / cathedral_area(p), 1.0, 0.005) << "course " << course;
  }
}

TEST(Cathedral, DiscretisationIsAParameter) {
  GothicCathedral p;
  p.course = 0.5;
  p.nave_voussoirs = 60;
  p.aisle_voussoirs = 30;
  p.flyer_voussoirs = 25;
  const Case c = gothic_cathedral(p);
  test::expect_valid_case(c);
  EXPECT_GT(c.blocks.size(), 450u);
  p = GothicCathedral{};
  p.course = 2.0;
  p.nave_voussoirs = 20;
  p.aisle_voussoirs = 10;
  p.flyer_voussoirs = 8;
  test::expect_valid_case(gothic_cathedral(p));
  p.nave_voussoirs = 21;  // the crown joint must lie on the axis
  EXPECT_THROW(gothic_cathedral(p), CaseError);
}

TEST(Cathedral, JointsWhereTheDrawingHasThem) {
  const Case& c = default_cathedral();
  const GothicCathedral p;
  const double x1 = p.nave_span / 2, x2 = x1 + p.pier_width;
  const auto ifs = detect_interfaces(c, c.prd.contact_tolerance);
  auto id = [&](int i) { return c.blocks[i].id; };
  for (size_t i = 0; i < c.blocks.size(); ++i) {
    const std::string& name = c.blocks[i].id;
    const auto nb = test::neighbours(ifs, static_cast<int>(i));
    // Arch and flyer voussoirs: exactly their two neighbours along the arch.
    if (starts_with(name, "nave-") || name.find("aisle-") != std::string::npos || name.find("flyer-") != std::string::npos) {
      EXPECT_EQ(nb.size(), 2u) << name;
    }
    // Courses of piers and buttresses: a horizontal joint with the block below.
    if (name.find("pier-") != std::string::npos || name.find("buttress-") != std::string::npos) {
      const double ylo = [&] {
        double y = INFINITY;
        for (const Vec2& v : c.blocks[i].vertices) y = std::min(y, v.y());
        return y;
      }();
      bool below = false;
      for (const Interface& f : ifs)
        if ((f.i == static_cast<int>(i) || f.j == static_cast<int>(i)) && std::abs(f.a.y() - ylo) < 1e-9 && std::abs(f.b.y() - ylo) < 1e-9)
          below = true;
      EXPECT_TRUE(below) << name << " has no bed joint";
    }
  }
  // Flyer heads bear on the pier face (vertical joint at x2, one flyer thickness long) and feet on
  // a buttress (a joint one flyer thickness long); nave and aisle arches spring from piers and
  // buttresses on horizontal joints one arch thickness long.
  auto joint_between = [&](const std::string& a, const std::string& prefix) -> const Interface* {
    const int i = c.block_index(a);
    for (const Interface& f : ifs) {
      const int o = f.i == i ? f.j : (f.j == i ? f.i : -1);
      if (o >= 0 && id(o).find(prefix) != std::string::npos) return &f;
    }
    return nullptr;
  };
  char last[32];
  std::snprintf(last, sizeof last, "%02d", p.flyer_voussoirs - 1);
  for (const std::string side : {"L-", "R-"}) {
    const double sx = side == "L-" ? -1 : 1;
    for (const std::string fl : {"flyer-low-", "flyer-up-"}) {
      const Interface* head = joint_between(side + fl + "00", "pier-");
      ASSERT_NE(head, nullptr) << side << fl << " head";
      EXPECT_NEAR(head->a.x(), sx * x2, 1e-9);
      EXPECT_NEAR(head->b.x(), sx * x2, 1e-9);
      EXPECT_NEAR(head->length(), p.flyer_thickness, 1e-9);
      const Interface* foot = joint_between(side + fl + last, "buttress-");
      ASSERT_NE(foot, nullptr) << side << fl << " foot";
      EXPECT_NEAR(foot->length(), p.flyer_thickness, 1e-9);
    }
    const Interface* aisle_pier = joint_between(side + "aisle-00", "pier-");
    ASSERT_NE(aisle_pier, nullptr);
    EXPECT_NEAR(aisle_pier->a.y(), p.aisle_springing, 1e-9);
    EXPECT_NEAR(aisle_pier->length(), p.aisle_thickness, 1e-9);
    char al[32];
    std::snprintf(al, sizeof al, "aisle-%02d", p.aisle_voussoirs - 1);
    const Interface* aisle_buttress = joint_between(side + al, "buttress-");
    ASSERT_NE(aisle_buttress, nullptr);
    EXPECT_NEAR(aisle_buttress->length(), p.aisle_thickness, 1e-9);
  }
  char nl[32];
  std::snprintf(nl, sizeof nl, "nave-%02d", p.nave_voussoirs - 1);
  for (const std::string& v : {std::string("nave-00"), std::string(nl)}) {
    const Interface* s = joint_between(v, "pier-");
    ASSERT_NE(s, nullptr) << v;
    EXPECT_NEAR(s->a.y(), p.nave_springing, 1e-9);
    EXPECT_NEAR(s->b.y(), p.nave_springing, 1e-9);
    EXPECT_NEAR(s->length(), p.nave_thickness, 1e-9);
  }
  // The foundations carry exactly one block each.
  for (int k = 1; k <= 4; ++k) EXPECT_EQ(test::neighbours(ifs, c.block_index("support-" + std::to_string(k))).size(), 1u);
}

TEST(Cathedral, SettlementMotion) {
  GothicCathedral p = standard_cathedral_settlement_rotation();
  const Case c = gothic_cathedral(p);
  ASSERT_EQ(c.motion.supports.size(), 1u);
  const SupportMotion& m = c.motion.supports[0];
  EXPECT_EQ(c.blocks[m.block].id, "support-3");
  // Per step of d = 1 cm: 1 cm down and 0.001 rad counter-clockwise about the centroid.
  EXPECT_DOUBLE_EQ(c.motion.step, 0.01);
  EXPECT_NEAR(m.translation.y() * c.motion.step, -0.01, 1e-15);
  EXPECT_EQ(m.translation.x(), 0.0);
  EXPECT_NEAR(m.rotation * c.motion.step, 0.001, 1e-15);
  const Vec2 centre = centroid(c.blocks[m.block].vertices);
  EXPECT_NEAR((m.about - centre).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace masonry
