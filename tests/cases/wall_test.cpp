// The brick wall generator (`masonry cases wall`). Expected values are counted by hand from the
// bond (bricks, half bricks, head and bed joints), from areas (the wall less its openings, the
// arch's intrados polygon (n/2) ri^2 sin(pi/n)) and from symmetry.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "case_checks.hpp"
#include "cases/generators.hpp"
#include "cases/wall_fields.hpp"
#include "model/interfaces.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

BrickWall plain(WallBond bond, int courses, int bricks) {
  BrickWall p;
  p.bond = bond;
  p.courses = courses;
  p.bricks = bricks;
  return p;
}

int free_blocks(const Case& c) {
  int n = 0;
  for (const Block& b : c.blocks) n += !b.support;
  return n;
}

TEST(Wall, RunningBondCountsBricksHalvesAndJointsByHand) {
  const int courses = 7, bricks = 9;
  const Case c = brick_wall(plain(WallBond::running, courses, bricks));
  test::expect_valid_case(c);
  // Even courses: 9 whole bricks; odd courses: 8 whole and two halves.
  const int even = (courses + 1) / 2, odd = courses / 2;
  EXPECT_EQ(free_blocks(c), even * bricks + odd * (bricks + 1));
  EXPECT_EQ(c.blocks.size(), static_cast<size_t>(free_blocks(c) + 2));
  // Head joints: pieces - 1 per course. Bed joints: the first course on the two ground blocks
  // (a brick over the split at 4.5 bricks rests on both: bricks + 1), then every brick of an even
  // course meets two pieces of the odd course next to it: 2 bricks per pair of courses.
  const int head = even * (bricks - 1) + odd * bricks;
  const int bed = (bricks + 1) + 2 * bricks * (courses - 1);
  EXPECT_EQ(static_cast<int>(detect_interfaces(c, c.prd.contact_tolerance).size()), head + bed);
  EXPECT_NEAR(test::free_area(c), courses * 0.125 * bricks * 0.25, 1e-12);
}

TEST(Wall, StackAndHeaderBondsCountByHand) {
  const Case stack = brick_wall(plain(WallBond::stack, 5, 6));
  test::expect_valid_case(stack);
  EXPECT_EQ(free_blocks(stack), 30);
  // Header bond: units of the header's face, alternate courses offset by half a header with
  // quarter bricks (half headers) at the ends.
  BrickWall h = plain(WallBond::header, 4, 10);
  const Case header = brick_wall(h);
  test::expect_valid_case(header);
  EXPECT_EQ(free_blocks(header), 2 * 10 + 2 * 11);
  EXPECT_NEAR(test::free_area(header), 4 * 0.125 * 10 * 0.125, 1e-12);
}

TEST(Wall, OpeningsLeaveTheirAreaAndTheArchIsSymmetric) {
  BrickWall p = plain(WallBond::running, 14, 12);
  p.openings = {parse_wall_opening("0.5,0.25,0.5,0.5,arch"), parse_wall_opening("2.0,0.25,0.375,0.5")};
  const Case c = brick_wall(p);
  test::expect_valid_case(c);
  // The arch: auto voussoirs round(pi rc / course) with rc = ri + t/2 = 0.3125.
  const int n = static_cast<int>(std::lround(M_PI * 0.3125 / 0.125));
  const double ri = 0.25;
  const double intrados = 0.5 * n * ri * ri * std::sin(M_PI / n);
  // Wall area less the two voids below the springing and the lintel, less the space under the
  // arch's intrados polygon.
  const double wall = 14 * 0.125 * 12 * 0.25;
  EXPECT_NEAR(test::free_area(c), wall - 0.5 * 0.5 - 0.375 * 0.5 - intrados, 1e-12);
  int voussoirs = 0, spandrels = 0, lintels = 0;
  for (const Block& b : c.blocks) {
    voussoirs += b.id.rfind("arch-1-v", 0) == 0;
    spandrels += b.id.rfind("arch-1-s", 0) == 0;
    lintels += b.id.rfind("lintel-2", 0) == 0;
  }
  EXPECT_EQ(voussoirs, n);
  EXPECT_EQ(spandrels, n);
  EXPECT_EQ(lintels, 1);
  // Voussoir k and voussoir n-1-k are mirror images about the opening's axis, x = 0.75.
  for (int k = 0; k < n; ++k) {
    const Block& a = c.blocks[c.block_index("arch-1-v" + std::to_string(k))];
    const Block& b = c.blocks[c.block_index("arch-1-v" + std::to_string(n - 1 - k))];
    for (const Vec2& v : a.vertices) {
      const Vec2 mirror(1.5 - v.x(), v.y());
      double best = INFINITY;
      for (const Vec2& w : b.vertices) best = std::min(best, (w - mirror).norm());
      EXPECT_LT(best, 1e-12) << k;
    }
  }
}

TEST(Wall, GroundMotionAndTheStructureStandsOnFixedGround) {
  BrickWall p = plain(WallBond::running, 6, 8);
  p.moving = MovingGround::left;
  p.ground_split = 0.75;
  p.settlement_step = 0.002;
  p.rotation_step = 0.0005;
  p.step = 0.001;
  const Case c = brick_wall(p);
  ASSERT_EQ(c.motion.supports.size(), 1u);
  EXPECT_EQ(c.blocks[c.motion.supports[0].block].id, "ground-left");
  EXPECT_NEAR(c.motion.supports[0].translation.y(), -2.0, 1e-12);  // m per m of d
  EXPECT_NEAR(c.motion.supports[0].rotation, 0.5, 1e-12);
  EXPECT_NEAR((c.motion.supports[0].about - Vec2(0.75, 0)).norm(), 0, 1e-12);
  p.moving = MovingGround::none;
  const Case fixed = brick_wall(p);
  EXPECT_TRUE(fixed.motion.supports.empty());
  EXPECT_TRUE(prd_check(fixed, fixed.prd.contact_tolerance).stable);
}

TEST(Wall, BadOpeningsAreRefusedNamingThem) {
  BrickWall p = plain(WallBond::running, 6, 8);
  p.openings = {parse_wall_opening("1.9,0.25,0.5,0.5")};  // its lintel runs past the wall's end
  try {
    brick_wall(p);
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("opening 1"), std::string::npos) << e.what();
  }
  p.openings = {parse_wall_opening("0.3,0.25,0.5,0.5"), parse_wall_opening("0.9,0.25,0.5,0.5")};
  EXPECT_THROW(brick_wall(p), CaseError);  // their lintels overlap
  p.openings = {parse_wall_opening("0.3,0.25,0.5,0.5,arch")};
  EXPECT_THROW(brick_wall(p), CaseError);  // the arch needs more courses than 6
  EXPECT_THROW(parse_wall_opening("1,2,3"), CaseError);
  EXPECT_THROW(parse_wall_opening("1,2,3,x"), CaseError);
  EXPECT_THROW(parse_wall_opening("1,2,3,4,vault"), CaseError);
}

// Parameters that cannot make what they ask for are refused naming the parameter: an arch of one
// voussoir (its two joints are both springings, on one line: it failed as "block 'arch-1-v0':
// field 'vertices': zero area"), and a moving ground with no settlement and no rotation (it was
// written as a case with no support motion, exit code 0).
TEST(Wall, AnArchOfOneVoussoirAndAGroundThatDoesNotMoveAreRefused) {
  const auto refusal = [](const BrickWall& p) {
    try {
      brick_wall(p);
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  BrickWall p = plain(WallBond::running, 10, 10);
  p.openings = {parse_wall_opening("1.0,0.25,0.5,0.5,arch")};
  for (const int n : {1, -2}) {
    p.arch_voussoirs = n;
    const std::string msg = refusal(p);
    EXPECT_EQ(msg.rfind("wall: arch-voussoirs " + std::to_string(n) + ": must be 0 (about one per course height) or at least 2", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // Two voussoirs are the fewest: two quadrilaterals meeting at the crown.
  p.arch_voussoirs = 2;
  const Case two = brick_wall(p);
  int voussoirs = 0;
  for (const Block& b : two.blocks) voussoirs += b.id.rfind("arch-1-v", 0) == 0;
  EXPECT_EQ(voussoirs, 2);
  p.arch_voussoirs = 0;

  p.settlement_step = 0;
  for (const MovingGround m : {MovingGround::right, MovingGround::left}) {
    p.moving = m;
    const std::string msg = refusal(p);
    EXPECT_EQ(msg.rfind(std::string("wall: moving ") + (m == MovingGround::left ? "left" : "right") +
                            ", but settlement-step and rotation-step are both 0: the ground would not move",
                        0),
              0u)
        << msg;
  }
  // A turn alone moves it; a fixed ground needs neither.
  p.rotation_step = 0.001;
  EXPECT_EQ(brick_wall(p).motion.supports.size(), 1u);
  p.rotation_step = 0;
  p.moving = MovingGround::none;
  EXPECT_TRUE(brick_wall(p).motion.supports.empty());
}

// Each row of the parameter table sets its own member, under its own name: setting every field
// to a value other than its default changes each member once, and each refusal names its field.
TEST(Wall, EveryParameterSetsItsOwnMemberAndBadValuesNameIt) {
  std::set<std::string> names;
  nlohmann::json values = nlohmann::json::object();
  for (const WallField& f : wall_fields()) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name << " twice";
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(BrickWall{}.*member)>;
          if constexpr (std::is_same_v<T, WallBond>)
            values[f.name] = "header";
          else if constexpr (std::is_same_v<T, MovingGround>)
            values[f.name] = "none";
          else
            values[f.name] = BrickWall{}.*member + 7;
        },
        f.member);
  }
  const BrickWall d, p = wall_parameters(values, "test");
  int changed = 0;
  for (const WallField& f : wall_fields()) std::visit([&](auto member) { changed += !(p.*member == d.*member); }, f.member);
  EXPECT_EQ(changed, static_cast<int>(wall_fields().size()));
  EXPECT_EQ(p.bond, WallBond::header);
  EXPECT_EQ(p.courses, d.courses + 7);
  EXPECT_EQ(p.moving, MovingGround::none);
  EXPECT_EQ(wall_parameters({{"opening", {"0.5,0.25,0.5,0.5,arch", "2,0.25,0.5,0.5"}}}, "t").openings.size(), 2u);
  for (const auto& [bad, field] :
       std::vector<std::pair<nlohmann::json, std::string>>{{{{"bond", "flemish"}}, "'bond' must be one of header, running, stack"},
                                                           {{{"courses", 2.5}}, "'courses' must be a whole number"},
                                                           {{{"depth", "thick"}}, "'depth' must be a number"},
                                                           {{{"colour", 1}}, "no parameter 'colour'"},
                                                           {{{"opening", 3}}, "'opening' must be"}}) {
    try {
      wall_parameters(bad, "generate('wall')");
      ADD_FAILURE() << bad.dump() << " accepted";
    } catch (const CaseError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("generate('wall'): ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace masonry
