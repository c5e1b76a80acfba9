// Case files: parsing, validation messages (one line naming file, block and field), interface
// detection against hand-drawn geometry.
#include "model/case.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "model/interfaces.hpp"

namespace masonry {
namespace {

const char* kGround = R"({"id": "ground", "vertices": [[-2, -0.5], [2, -0.5], [2, 0], [-2, 0]], "support": true})";

std::string with_blocks(const std::string& blocks, const std::string& rest = "") {
  return std::string(R"({"format": "masonry-case/1", "name": "t", "blocks": [)") + blocks + "]" + rest + "}";
}

// The message of the CaseError that parsing throws, or "" if it parses.
std::string error_of(const std::string& json) {
  try {
    parse_case(json, "bad.json");
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& json, const std::vector<std::string>& parts) {
  const std::string msg = error_of(json);
  ASSERT_FALSE(msg.empty()) << "parsed without error: " << json;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_EQ(msg.rfind("bad.json", 0), 0u) << msg;
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

TEST(CaseFile, TheIssueExampleParses) {
  const std::string json = R"({
    "format": "masonry-case/1", "name": "tilting block", "gravity": 9.81,
    "blocks": [
      {"id": "ground", "vertices": [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.0], [-2.0, 0.0]], "depth": 1.0, "support": true},
      {"id": "block", "vertices": [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]], "depth": 1.0, "density": 2000.0}
    ],
    "loads": [{"block": "block", "force": [0.0, -500.0], "point": [0.25, 1.0]}],
    "motion": {"step": 0.001, "max_steps": 2000,
               "supports": [{"block": "ground", "translation": [0.0, 0.0], "rotation": 1.0, "about": [-2.0, -0.5]}]},
    "prd": {"contact_tolerance": 1e-5},
    "dem": {"young_modulus": 3.0e10, "poisson": 0.2, "friction_angle": 35.0}
  })";
  const Case c = parse_case(json, "example.json");
  ASSERT_EQ(c.blocks.size(), 2u);
  EXPECT_TRUE(c.blocks[0].support);
  EXPECT_DOUBLE_EQ(block_mass(c.blocks[1]), 1000.0);
  ASSERT_EQ(c.loads.size(), 1u);
  ASSERT_EQ(c.motion.supports.size(), 1u);
  EXPECT_DOUBLE_EQ(c.motion.supports[0].rotation, 1.0);
  EXPECT_EQ(c.motion.supports[0].about, Vec2(-2.0, -0.5));
  // Round trip through the writer gives the same case.
  const Case d = parse_case(case_to_json(c), "again.json");
  EXPECT_EQ(case_to_json(c), case_to_json(d));
}

TEST(CaseFile, ClockwiseBlocksAreAccepted) {
  const Case c =
      parse_case(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [0, 1], [0.5, 1], [0.5, 0]], "density": 1})"), "cw.json");
  EXPECT_GT(signed_area(c.blocks[1].vertices), 0);
  EXPECT_EQ(detect_interfaces(c, 1e-6).size(), 1u);
}

TEST(CaseFile, AboutDefaultsToTheSupportCentroid) {
  const Case c = parse_case(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1})",
                                        R"(, "motion": {"supports": [{"block": "ground", "translation": [1, 0]}]})"),
                            "m.json");
  EXPECT_NEAR(c.motion.supports[0].about.x(), 0.0, 1e-12);
  EXPECT_NEAR(c.motion.supports[0].about.y(), -0.25, 1e-12);
}

// A support turning about a point of the scene carries its points on a lever of at most the
// scene's size (the rule's measure of the arc the scene turns through); about a hinge outside the
// scene, on the hinge's distance from them: a point of the scene 3 m left of a hinge at (5, 0)
// travels 3 m per rad, one at its far end 7 m; the rule counts the size (4 m: the ground's width)
// plus the hinge's distance outside the scene's bounds (3 m), 7 m.
TEST(CaseFile, ASupportTurningAboutAFarHingeTravelsOnItsLever) {
  const std::string motion = R"(, "motion": {"supports": [{"block": "ground", "rotation": 2, "translation": [0, -1], "about": [X, 0]}]})";
  auto with_about = [&](const char* x) {
    std::string m = motion;
    m.replace(m.find('X'), 1, x);
    return parse_case(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1})", m), "m.json");
  };
  EXPECT_NEAR(support_travel_per_d(with_about("0")), 1 + 2 * 4.0, 1e-12);   // inside: the scene's size
  EXPECT_NEAR(support_travel_per_d(with_about("2")), 1 + 2 * 4.0, 1e-12);   // on its edge
  EXPECT_NEAR(support_travel_per_d(with_about("5")), 1 + 2 * 7.0, 1e-12);   // 3 m outside
  EXPECT_NEAR(support_travel_per_d(with_about("-6")), 1 + 2 * 8.0, 1e-12);  // 4 m outside, left
}

const std::string kBlock = R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1000})";

TEST(CaseErrors, FewerThanThreeVertices) {
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "thin", "vertices": [[0, 0], [1, 0]], "density": 1})"),
               {"block 'thin'", "vertices", "fewer than 3"});
}

TEST(CaseErrors, ZeroArea) {
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "flat", "vertices": [[0, 0], [1, 0], [2, 0]], "density": 1})"),
               {"block 'flat'", "vertices", "zero area"});
}

TEST(CaseErrors, SelfIntersection) {
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "bow", "vertices": [[0, 0], [1, 1], [1, 0], [0, 1]], "density": 1})"),
               {"block 'bow'", "vertices", "self-intersecting"});
  // A comb of 2000 teeth (8002 vertices) whose last tooth is bent back across the first: the
  // crossing edges are thousands of vertices apart, and a tooth tip touching its neighbour's
  // counts too.
  auto comb = [](bool bent, bool touching) {
    // Counter-clockwise: the spine's bottom, then leftwards over the teeth (k = 1999 .. 0).
    nlohmann::json v = {{0.0, -0.05}, {2.0, -0.05}, {2.0, 0.0}};
    for (int k = 1999; k >= 0; --k) {
      const double x = 0.001 * k;
      v.push_back({x + 0.0004, 0.0});
      v.push_back({touching && k == 10 ? 0.011 : x + 0.0004, 0.1});  // touching: reaches tooth 11
      // bent: the first tooth visited dives into the last one (k = 0), across every tooth between.
      v.push_back({bent && k == 1999 ? 0.0002 : x, bent && k == 1999 ? 0.05 : 0.1});
      v.push_back({x, 0.0});
    }
    return nlohmann::json{{"format", "masonry-case/1"},
                          {"name", "t"},
                          {"blocks",
                           {{{"id", "ground"}, {"vertices", {{-1, -1}, {3, -1}, {3, -0.05}, {-1, -0.05}}}, {"support", true}},
                            {{"id", "comb"}, {"vertices", v}, {"density", 1}}}}}
        .dump();
  };
  EXPECT_EQ(error_of(comb(false, false)), "");
  expect_error(comb(true, false), {"block 'comb'", "vertices", "self-intersecting"});
  expect_error(comb(false, true), {"block 'comb'", "vertices", "self-intersecting"});
}

TEST(CaseErrors, OverlappingBlocks) {
  expect_error(
      with_blocks(std::string(kGround) + kBlock + R"(, {"id": "b2", "vertices": [[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]], "density": 1})"),
      {"block 'b2'", "vertices", "overlaps block 'b'"});
  // A copy of a block exactly on top of it overlaps too.
  expect_error(with_blocks(std::string(kGround) + kBlock + R"(, {"id": "twin", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1})"),
               {"block 'twin'", "overlaps"});
}

TEST(CaseErrors, BlockTouchingNothing) {
  expect_error(with_blocks(std::string(kGround) + kBlock + R"(, {"id": "floating", "vertices": [[5, 5], [6, 5], [6, 6], [5, 6]], "density": 1})"),
               {"block 'floating'", "vertices", "touches no other block"});
}

TEST(CaseErrors, NoSupport) {
  expect_error(with_blocks(R"({"id": "a", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1},
                              {"id": "b", "vertices": [[0, 1], [1, 1], [1, 2], [0, 2]], "density": 1})"),
               {"no support"});
}

TEST(CaseErrors, MotionOnAFreeBlock) {
  expect_error(with_blocks(std::string(kGround) + kBlock, R"(, "motion": {"supports": [{"block": "b", "translation": [1, 0]}]})"),
               {"block 'b'", "'block'", "not a support"});
}

TEST(CaseErrors, MotionOnAnUnknownBlock) {
  expect_error(with_blocks(std::string(kGround) + kBlock, R"(, "motion": {"supports": [{"block": "nope"}]})"),
               {"motion", "'block'", "no block 'nope'"});
}

TEST(CaseErrors, NonFiniteNumbers) {
  // JSON has no NaN literal: it is a syntax error with a position.
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [NaN, 0], [1, 1]], "density": 1})"), {"malformed JSON"});
  // An overflowing literal is refused with its position.
  const std::string inf = with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1e999})");
  expect_error(inf, {"not a finite number"});
  EXPECT_NE(error_of(inf).find("bad.json:1:" + std::to_string(inf.find("1e999") + 1)), std::string::npos) << error_of(inf);
}

TEST(CaseErrors, NonPositiveDensityOrDepth) {
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 0})"),
               {"block 'b'", "density", "outside (0, "});
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": -5})"),
               {"block 'b'", "density", "outside (0, "});
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1, "depth": 0})"),
               {"block 'b'", "depth", "outside (0, "});
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]]})"),
               {"block 'b'", "density", "required"});
}

TEST(CaseErrors, MalformedJsonGivesLineAndColumn) {
  const std::string json = "{\n  \"format\": \"masonry-case/1\",\n  \"blocks\": [ oops ]\n}";
  expect_error(json, {"bad.json:3:", "malformed JSON"});
  const std::string msg = error_of(json);
  // Column of the offending token "oops" on line 3.
  EXPECT_NE(msg.find("bad.json:3:15"), std::string::npos) << msg;
}

TEST(CaseErrors, UnknownFields) {
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1, "colour": "red"})"),
               {"block 'b'", "unknown field 'colour'"});
  expect_error(with_blocks(std::string(kGround) + kBlock, R"(, "prd": {"tolerance": 1e-5})"), {"prd", "unknown field 'tolerance'"});
  expect_error(with_blocks(std::string(kGround) + kBlock, R"(, "extra": 1)"), {"case", "unknown field 'extra'"});
}

TEST(CaseErrors, DuplicateIdsAndWrongFormat) {
  expect_error(with_blocks(std::string(kGround) + kBlock + R"(, {"id": "b", "vertices": [[0, 1], [1, 1], [1, 2], [0, 2]], "density": 1})"),
               {"block 'b'", "duplicate"});
  expect_error(R"({"format": "other/2", "blocks": []})", {"format"});
}

// Joints are named BLOCK/BLOCK and corners BLOCK/BLOCK:A (README, "Case files"): blocks 'a' on
// 'b/c' and 'a/b' on 'c' named two joints a/b/c, and only --hold noticed, at run time. An id
// holding '/' or ':' is refused by the loader, naming the block by index and id and the field.
TEST(CaseErrors, AnIdHoldingASeparatorOfJointNamesIsRefused) {
  const std::string g = R"({"id": "g", "vertices": [[-1, -0.1], [2, -0.1], [2, 0], [-1, 0]], "support": true})";
  const auto block = [](const std::string& id, double x, double y) {
    std::ostringstream o;
    o << R"({"id": ")" << id << R"(", "vertices": [[)" << x << ", " << y << "], [" << x + 0.2 << ", " << y << "], [" << x + 0.2 << ", " << y + 0.4
      << "], [" << x << ", " << y + 0.4 << R"(]], "density": 2000})";
    return o.str();
  };
  const std::string ambiguous = g + ", " + block("a", 0, 0) + ", " + block("b/c", 0, 0.4) + ", " + block("a/b", 1, 0) + ", " + block("c", 1, 0.4);
  expect_error(with_blocks(ambiguous), {"bad.json: block #2 'b/c': field 'id' holds '/'"});
  expect_error(with_blocks(g + ", " + block("v:A", 0, 0)), {"bad.json: block #1 'v:A': field 'id' holds ':'"});
  expect_error(with_blocks(g + ", " + block("x", 0, 0) + ", " + block("y/", 0, 0.4)), {"block #2 'y/': field 'id'"});
  // Any other text is an id (a drawing's "Pier 2", markup, non-ASCII), and then each corner name
  // splits at its one '/' and one ':' into the joint's two ids: the names are the joints'.
  const Case c = parse_case(with_blocks(g + ", " + block("Pier 2", 0, 0) + ", " + block("<b>&\u00e8", 0, 0.4)), "ok.json");
  for (const Interface& j : detect_interfaces(c, c.prd.contact_tolerance)) {
    const std::string name = corner_name(c, j.i, j.j, 1);
    ASSERT_EQ(std::count(name.begin(), name.end(), '/'), 1) << name;
    ASSERT_EQ(std::count(name.begin(), name.end(), ':'), 1) << name;
    EXPECT_EQ(name.substr(0, name.find('/')), c.blocks[j.i].id);
    EXPECT_EQ(name.substr(name.find('/') + 1, name.find(':') - name.find('/') - 1), c.blocks[j.j].id);
  }
}

// A block seated in a support's notch meets it at three joints (both sides and the floor): each
// corner has a name of its own, the further joints' corners lettered on in the joints' order
// (the right wall A and B, the floor C and D, the left wall E and F), so a report's hinge and
// `--hold` point at one corner.
TEST(CaseErrors, ABlockInANotchHasOneNamePerCorner) {
  const Case c = parse_case(R"({"format": "masonry-case/1", "name": "notch", "gravity": 9.81, "blocks": [
    {"id": "base", "support": true, "vertices": [[-1, -0.5], [1, -0.5], [1, 0.5], [0.25, 0.5], [0.25, 0], [-0.25, 0], [-0.25, 0.5], [-1, 0.5]]},
    {"id": "post", "density": 2000, "vertices": [[-0.25, 0], [0.25, 0], [0.25, 1], [-0.25, 1]]}],
    "motion": {"step": 0.01, "max_steps": 1, "supports": [{"block": "base", "rotation": 1, "about": [0, -0.5]}]}})",
                            "notch.json");
  const std::vector<Interface> joints = detect_interfaces(c, c.prd.contact_tolerance);
  ASSERT_EQ(joints.size(), 3u);
  EXPECT_EQ(pair_ordinals(joints), (std::vector<int>{0, 1, 2}));
  std::set<std::string> names;
  const std::vector<int> nth = pair_ordinals(joints);
  for (size_t k = 0; k < joints.size(); ++k)
    for (int corner : {0, 1}) names.insert(corner_name(c, joints[k].i, joints[k].j, corner, nth[k]));
  EXPECT_EQ(names, (std::set<std::string>{"base/post:A", "base/post:B", "base/post:C", "base/post:D", "base/post:E", "base/post:F"}));
  // The floor (normal up) is the second joint: C at (0.25, 0), D at (-0.25, 0).
  ASSERT_NEAR(joints[1].normal.y(), 1.0, 1e-12);
  EXPECT_EQ(corner_name(c, joints[1].i, joints[1].j, 0, nth[1]), "base/post:C");
  EXPECT_EQ(joints[1].a, Vec2(0.25, 0.0));
  EXPECT_EQ(joint_name(c, joints[1].i, joints[1].j, nth[1]), "base/post:CD");
  EXPECT_EQ(joint_name(c, joints[0].i, joints[0].j, nth[0]), "base/post");
  EXPECT_EQ(corner_letter(0, 13), "A14");  // past Z
  EXPECT_EQ(corner_letter(1, 13), "B14");
}

TEST(CaseErrors, MissingFileIsOneLine) {
  try {
    load_case("/nonexistent/case.json");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/case.json"), std::string::npos);
  }
}

// Interfaces ---------------------------------------------------------------------------

Case blocks_case(const std::string& blocks) { return parse_case(with_blocks(blocks), "i.json"); }

TEST(Interfaces, PartialOverlapGivesTheOverlapSegment) {
  // A block straddling the edge of another: the joint is the common part of the edges.
  const Case c = blocks_case(std::string(kGround) +
                             R"(, {"id": "low", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1},
                                 {"id": "top", "vertices": [[0.6, 1], [1.6, 1], [1.6, 1.5], [0.6, 1.5]], "density": 1})");
  const auto f = detect_interfaces(c, 1e-6);
  // ground-low and low-top (top overhangs the void: no joint there).
  ASSERT_EQ(f.size(), 2u);
  const Interface& j = f[1];
  EXPECT_EQ(c.blocks[j.i].id, "low");
  EXPECT_EQ(c.blocks[j.j].id, "top");
  EXPECT_NEAR(j.length(), 0.4, 1e-12);
  EXPECT_NEAR(j.normal.y(), 1.0, 1e-12);  // out of "low", into "top"
  EXPECT_NEAR(std::min(j.a.x(), j.b.x()), 0.6, 1e-12);
  EXPECT_NEAR(std::max(j.a.x(), j.b.x()), 1.0, 1e-12);
}

TEST(Interfaces, SplitEdgePiecesOfOnePairAreMerged) {
  // The lower block's top edge has a vertex in its middle; the joint is still one segment.
  const Case c = blocks_case(std::string(kGround) +
                             R"(, {"id": "low", "vertices": [[0, 0], [1, 0], [1, 1], [0.5, 1], [0, 1]], "density": 1},
                                 {"id": "top", "vertices": [[0, 1], [1, 1], [1, 1.5], [0, 1.5]], "density": 1})");
  const auto f = detect_interfaces(c, 1e-6);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[1].length(), 1.0, 1e-12);
}

TEST(Interfaces, GapsBeyondTheToleranceAreNotJoints) {
  const Case c = blocks_case(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1},
                                 {"id": "near", "vertices": [[1.001, 0], [2, 0], [2, 1], [1.001, 1]], "density": 1})");
  EXPECT_EQ(detect_interfaces(c, 1e-4).size(), 2u);  // each on the ground, not to each other
  EXPECT_EQ(detect_interfaces(c, 1e-2).size(), 3u);  // within a 1 cm tolerance they touch
}

TEST(Interfaces, WallOfBricksMatchesCounting) {
  // A running-bond wall: rows of n bricks, alternate rows offset by half a brick with half
  // bricks at the ends. Joints are countable by hand: head joints within rows and bed joints.
  const int rows = 6, n = 8;
  std::string blocks = R"({"id": "ground", "vertices": [[-1, -1], [9, -1], [9, 0], [-1, 0]], "support": true})";
  int head = 0;
  for (int r = 0; r < rows; ++r) {
    std::vector<double> xs;
    if (r % 2 == 0) {
      for (int k = 0; k <= n; ++k) xs.push_back(k);
    } else {
      xs.push_back(0);
      for (int k = 0; k < n; ++k) xs.push_back(k + 0.5);
      xs.push_back(n);
    }
    head += static_cast<int>(xs.size()) - 2;
    for (size_t k = 0; k + 1 < xs.size(); ++k) {
      const double y0 = 0.5 * r, y1 = 0.5 * (r + 1);
      blocks += ", {\"id\": \"r" + std::to_string(r) + "b" + std::to_string(k) + "\", \"vertices\": [[" + std::to_string(xs[k]) + "," +
                std::to_string(y0) + "],[" + std::to_string(xs[k + 1]) + "," + std::to_string(y0) + "],[" + std::to_string(xs[k + 1]) + "," +
                std::to_string(y1) + "],[" + std::to_string(xs[k]) + "," + std::to_string(y1) + "]], \"density\": 1}";
    }
  }
  const Case c = blocks_case(blocks);
  // Bed joints: first row on the ground (n); between an even row (n bricks) and an odd row
  // (n + 1 pieces) every brick meets two pieces: 2n per pair of rows.
  const int bed = n + 2 * n * (rows - 1);
  EXPECT_EQ(static_cast<int>(detect_interfaces(c, 1e-6).size()), head + bed);
}

}  // namespace
}  // namespace masonry

// with_option: one setting changed through the file format, validated like a loaded file.
TEST(WithOption, ChangesOneSettingAndKeepsTheRest) {
  const masonry::Case c = masonry::load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  const masonry::Case d = masonry::with_option(c, "dem.friction_angle", 20.0);
  EXPECT_DOUBLE_EQ(d.dem.friction_angle, 20.0);
  EXPECT_DOUBLE_EQ(d.motion.step, c.motion.step);
  ASSERT_EQ(d.blocks.size(), c.blocks.size());
  const masonry::Case e = masonry::with_option(c, "dem.kn", 1e9);  // optional field, absent before
  ASSERT_TRUE(e.dem.kn.has_value());
  EXPECT_DOUBLE_EQ(*e.dem.kn, 1e9);
  EXPECT_DOUBLE_EQ(masonry::with_option(c, "motion.step", 0.004).motion.step, 0.004);
  // The DEM's hinge threshold and stage 4 are options too (flags map onto them), and survive
  // the file format.
  const masonry::Case g = masonry::with_option(masonry::with_option(c, "dem.open_gap", 0.002), "dem.confirm_collapse", false);
  const masonry::Case back = masonry::parse_case(masonry::case_to_json(g), "back.json");
  ASSERT_TRUE(back.dem.open_gap.has_value());
  EXPECT_DOUBLE_EQ(*back.dem.open_gap, 0.002);
  EXPECT_FALSE(back.dem.confirm_collapse);
  EXPECT_FALSE(c.dem.open_gap.has_value());
  EXPECT_TRUE(c.dem.confirm_collapse);
  // How holds come to rest: a word, local by default.
  EXPECT_EQ(c.dem.hold_damping, masonry::HoldDamping::local);
  const masonry::Case k = masonry::with_option(c, "dem.hold_damping", "kinetic");
  EXPECT_EQ(masonry::parse_case(masonry::case_to_json(k), "back.json").dem.hold_damping, masonry::HoldDamping::kinetic);
}

TEST(WithOption, BadKeysAndValuesGetTheLoadersError) {
  const masonry::Case c = masonry::load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  auto message = [&](const std::string& key, const nlohmann::json& v) {
    try {
      masonry::with_option(c, key, v);
    } catch (const masonry::CaseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("dem.friction_angle", 120.0).find("friction_angle"), std::string::npos);
  EXPECT_NE(message("dem.friction_angle", 120.0).find("[dem.friction_angle=120.0]"), std::string::npos);
  EXPECT_NE(message("dem.frictoin", 30.0).find("frictoin"), std::string::npos);
  EXPECT_NE(message("nosuch.x", 1.0).find("no section 'nosuch'"), std::string::npos);
  EXPECT_NE(message("blocks", 1.0).find("not an option"), std::string::npos);
  EXPECT_NE(message("motion.step", "big").find("step"), std::string::npos);
  EXPECT_NE(message("dem.open_gap", -1.0).find("field 'open_gap'"), std::string::npos);
  EXPECT_NE(message("dem.confirm_collapse", 1.0).find("confirm_collapse"), std::string::npos);
  EXPECT_NE(message("dem.hold_damping", "kinetik").find("field 'hold_damping' must be \"local\" or \"kinetic\""), std::string::npos)
      << message("dem.hold_damping", "kinetik");
  EXPECT_NE(message("dem.hold_damping", 1.0).find("field 'hold_damping' must be a string"), std::string::npos);
}

namespace masonry {
namespace {

// Out-of-range quantities (the README's ranges) are refused before any solver sees them: each
// value below made GLPK abort or left NaN in results with exit code 0, or a capacity silently
// wrong (a scene 1e15 m from the origin keeps no digit of a 1e-5 m contact tolerance).
TEST(CaseErrors, QuantitiesOutsideTheirRangeAreRefusedNamingTheField) {
  const std::string path = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";
  const Case block = load_case(path);
  struct Bad {
    std::string key;
    nlohmann::json value;
    std::string field;
  };
  const std::vector<Bad> options = {
      {"gravity", 1e308, "gravity"},
      {"motion.step", 1e-300, "step"},
      {"prd.event_tolerance", 1e308, "event_tolerance"},
      {"prd.max_step", 1e308, "max_step"},
      {"prd.contact_tolerance", 10.0, "contact_tolerance"},
      {"dem.stiffness_reduction", 1e308, "stiffness_reduction"},
      {"dem.kn", 1e300, "kn"},
      {"dem.hold_time", 1e300, "hold_time"},
  };
  for (const Bad& b : options) {
    try {
      with_option(block, b.key, b.value);
      ADD_FAILURE() << b.key << " accepted";
    } catch (const CaseError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("field '" + b.field + "'"), std::string::npos) << msg;
      EXPECT_NE(msg.find("outside"), std::string::npos) << msg;
    }
  }
  // Geometry and motion: edit the document.
  const nlohmann::json doc = nlohmann::json::parse(case_to_json(block));
  auto refused = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& field) {
    nlohmann::json d = doc;
    edit(d);
    const std::string msg = error_of(d.dump());
    EXPECT_NE(msg.find("field '" + field + "'"), std::string::npos) << field << ": " << msg;
  };
  refused([](nlohmann::json& d) { d["blocks"][1]["density"] = 1e308; }, "density");
  refused([](nlohmann::json& d) { d["blocks"][1]["depth"] = 1e308; }, "depth");
  refused([](nlohmann::json& d) { d["motion"]["supports"][0]["rotation"] = 1e308; }, "rotation");
  refused([](nlohmann::json& d) { d["motion"]["supports"][0]["translation"] = {1e308, 0}; }, "translation");
  refused([](nlohmann::json& d) { d["motion"]["supports"][0]["about"] = {1e308, 0}; }, "about");
  // The whole scene scaled by 1e120, or moved by 1e15 m.
  for (double scale : {1e120, 1.0}) {
    nlohmann::json d = doc;
    for (auto& b : d["blocks"])
      for (auto& v : b["vertices"]) v = {v[0].get<double>() * scale + (scale == 1.0 ? 1e15 : 0.0), v[1].get<double>() * scale};
    d["motion"]["supports"][0]["about"] = {0.0, 0.0};
    const std::string msg = error_of(d.dump());
    EXPECT_NE(msg.find("field 'vertices'"), std::string::npos) << msg;
  }
  // Nothing loads the structure.
  refused([](nlohmann::json& d) { d["gravity"] = 0.0; }, "gravity");
  EXPECT_NE(error_of([&] {
              nlohmann::json d = doc;
              d["gravity"] = 0.0;
              return d.dump();
            }())
                .find("nothing loads"),
            std::string::npos);
}

}  // namespace
}  // namespace masonry

namespace masonry {
namespace {

// Text from a case reaches messages escaped and shortened: one readable line, whatever it held.
TEST(CaseErrors, EchoedInputIsEscapedAndShortened) {
  EXPECT_EQ(printable("a\x1b[31mb\n"), "a\\x1b[31mb\\x0a");
  EXPECT_EQ(printable(std::string(100, 'x'), 10), "xxxxxxxxxx... (100 characters)");
  const std::string long_key = std::string(200000, 'k');
  const std::string msg = error_of(with_blocks(std::string(kGround), ", \"" + long_key + "\": 1"));
  EXPECT_LT(msg.size(), 300u) << msg.size();
  EXPECT_NE(msg.find("unknown field"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(200000 characters)"), std::string::npos);
  const std::string escaped =
      error_of(with_blocks(std::string(kGround) + R"(, {"id": "b\u001b[2J", "vertices": [[5, 5], [6, 5], [6, 6], [5, 6]], "density": 1})"));
  EXPECT_EQ(escaped.find('\x1b'), std::string::npos) << escaped;
  EXPECT_NE(escaped.find("block 'b\\x1b[2J'"), std::string::npos) << escaped;
}

}  // namespace
}  // namespace masonry

namespace masonry {
namespace {

// A key given twice in one object is refused, at any depth, naming its path: nlohmann keeps the
// last one silently, and `"step": 0.0175, "step": 0.5` ran the tilting block at 0.5 (capacity 0).
TEST(CaseErrors, DuplicateKeysAreRefusedNamingTheirPath) {
  const std::string tilt = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json";
  const Case block = load_case(tilt);
  std::string text = case_to_json(block);
  const size_t at = text.find("\"step\":");
  ASSERT_NE(at, std::string::npos);
  const std::string twice = text.substr(0, at) + "\"step\": 0.0175, " + text.substr(at);
  expect_error(twice, {"field 'motion.step' given twice"});
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1, "density": 2})"),
               {"field 'blocks[1].density' given twice"});
  expect_error(R"({"format": "masonry-case/1", "format": "masonry-case/1", "blocks": []})", {"field 'format' given twice"});
  // Equal keys in different objects are no duplicates.
  EXPECT_EQ(error_of(with_blocks(std::string(kGround) + kBlock)), "");
}

TEST(CaseErrors, TheFormatFieldIsRequired) {
  std::string text = with_blocks(std::string(kGround) + kBlock);
  EXPECT_EQ(error_of(text), "");
  text.replace(text.find(R"("format": "masonry-case/1", )"), std::string(R"("format": "masonry-case/1", )").size(), "");
  expect_error(text, {"field 'format' is required", "masonry-case/1"});
}

// A count beyond the range names it and the range, not the type: 2147483647 is an integer.
TEST(CaseErrors, MaxStepsBeyondItsRangeSaysSo) {
  for (const char* n : {"2147483647", "100000001", "18446744073709551615", "-1"}) {
    expect_error(with_blocks(std::string(kGround) + kBlock, std::string(R"(, "motion": {"max_steps": )") + n + "}"),
                 {"motion", "field 'max_steps' = " + std::string(n) + " is outside [0, 100000000]"});
  }
  expect_error(with_blocks(std::string(kGround) + kBlock, R"(, "motion": {"max_steps": 2.5})"), {"field 'max_steps' must be a whole number"});
  EXPECT_EQ(error_of(with_blocks(std::string(kGround) + kBlock, R"(, "motion": {"max_steps": 100000000})")), "");
}

// A step stands against the scene by what it moves a support point: its translation plus its
// turn times the scene size. So the tilting block drawn at a hundredth of its size (a scene of
// 0.012 m) takes the same 1-degree step, which was refused as a step of 0.017 m against 0.012 m;
// a turn of 0.01 rad per unit of d takes a step of 50; and a turn of 2 rad per step is refused,
// and so is one of 9 rad per step beside a support that translates (d in m then: the step was
// checked as a length, 0.01 m in a scene of 0.014 m, and passed).
TEST(CaseErrors, AStepStandsAgainstTheSceneByTheTravelOfTheSupports) {
  const std::string small = R"({"id": "ground", "vertices": [[-0.006, -0.002], [0.006, -0.002], [0.006, 0], [-0.006, 0]], "support": true},
      {"id": "b", "vertices": [[0, 0], [0.005, 0], [0.005, 0.01], [0, 0.01]], "density": 1})";
  const auto turning = [&](const std::string& step, const std::string& rotation) {
    return with_blocks(small, R"(, "motion": {"step": )" + step + R"(, "max_steps": 10, "supports": [{"block": "ground", "rotation": )" + rotation +
                                  "}]}");
  };
  EXPECT_EQ(error_of(turning("0.017453292519943295", "1")), "");
  EXPECT_EQ(error_of(turning("50", "0.01")), "");
  expect_error(turning("2", "1"), {"motion", "field 'step' = 2 rad moves a support point by 0.024 m per step", "for a scene of 0.012 m"});
  expect_error(turning("1e-12", "1"), {"motion", "field 'step' = 1e-12 rad"});
  // Two supports, one settling, one turning 900 rad per m of d: 0.01 m of d turns it 9 rad.
  const std::string two = small + R"(, {"id": "other", "vertices": [[0.006, -0.002], [0.008, -0.002], [0.008, 0], [0.006, 0]], "support": true})";
  const auto mixed = [&](const std::string& turn) {
    return with_blocks(two, R"(, "motion": {"step": 0.01, "max_steps": 5, "supports": [{"block": "ground", "translation": [0, -1]}, {"block": "other", "rotation": )" +
                                turn + "}]}");
  };
  EXPECT_EQ(error_of(mixed("1")), "");
  expect_error(mixed("900"), {"motion", "field 'step' = 0.01 m moves a support point by"});
}

// A load acts at a point of its block: 5 m off a 1 m block it was accepted and moved the
// capacity by a third (a lever the block does not have); on the outline it is the block's, and
// without a point it acts at the centroid.
TEST(CaseErrors, ALoadOffItsBlockIsRefused) {
  const auto with_load = [](const std::string& point) {
    return with_blocks(std::string(kGround) + R"(, {"id": "b", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1})",
                       R"(, "loads": [{"block": "b", "force": [0, -100])" + point + "}]");
  };
  expect_error(with_load(R"(, "point": [5, 5])"), {"load #0", "field 'point' (5, 5) m lies", "outside block 'b'"});
  expect_error(with_load(R"(, "point": [0.5, 1.001])"), {"field 'point'", "0.001 m outside"});
  EXPECT_EQ(error_of(with_load(R"(, "point": [1, 0.5])")), "");   // on the outline
  EXPECT_EQ(error_of(with_load(R"(, "point": [0.2, 0.7])")), "");  // inside
  const Case c = parse_case(with_load(""), "c.json");
  ASSERT_EQ(c.loads.size(), 1u);
  EXPECT_DOUBLE_EQ(c.loads[0].point.x(), 0.5);
  EXPECT_DOUBLE_EQ(c.loads[0].point.y(), 0.5);
}

// One range for the time-step factor, the DEM's stability bound (0, 1], whichever command loads
// the case: `prd` accepted 2 while `dem` refused it.
TEST(CaseErrors, TheTimestepFactorHasOneRangeForEveryCommand) {
  const Case block = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  for (double f : {2.0, 1.0000001, 0.0, -1.0}) {
    try {
      with_option(block, "dem.timestep_factor", f);
      ADD_FAILURE() << f << " accepted";
    } catch (const CaseError& e) {
      EXPECT_NE(std::string(e.what()).find("field 'timestep_factor'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("(0, 1]"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(with_option(block, "dem.timestep_factor", 1.0).dem.timestep_factor, 1.0);
}

// A block no wider than the contact tolerance standing on its end touches the ground over less
// than the tolerance: no joint, and the message says why instead of "touches no other block".
TEST(CaseErrors, ABlockWhoseContactIsShorterThanTheToleranceIsToldSo) {
  const std::string thin = R"(, {"id": "needle", "vertices": [[0, 0], [1e-6, 0], [1e-6, 1], [0, 1]], "density": 2000})";
  expect_error(
      with_blocks(std::string(kGround) + thin),
      {"block 'needle'", "meets block 'ground' only at a point or over less than the contact tolerance (1e-05 m", "the block is 1e-06 by 1 m"});
  // A triangle standing on its apex meets the ground at a point.
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "apex", "vertices": [[0, 0], [1, 1], [-1, 1]], "density": 2000})"),
               {"block 'apex'", "meets block 'ground' only at a point"});
  // Far from everything: as before.
  expect_error(with_blocks(std::string(kGround) + R"(, {"id": "far", "vertices": [[0, 1], [1, 1], [1, 2], [0, 2]], "density": 1})"),
               {"block 'far'", "touches no other block"});
}

}  // namespace
}  // namespace masonry
