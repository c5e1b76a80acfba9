// Mechanism agreement (compare/mechanism.cpp), on cases whose answer is known before any DEM
// comparison of the cathedral is read, which chose its limit in reports/paper-tolerances.json
// (0.9; compare/README.md, "Mechanism agreement"). Measured 2026-11-26:
//  - the same mechanism: PRD against itself at half the step, 0.9998-1.0000 on the three standard
//    cases (the settlement cathedral's nave hinge moves one joint, nave-17/18 to 16/17); the
//    mirror image on the symmetric arch, 1.0000; the tilting block's two rungs of the friction
//    ladder on the toppling side (30 and 35 degrees), 0.994-1.000, elastic intervals included;
//  - another mechanism: PRD held closed at the settlement cathedral's springing (branch X of
//    dem/README.md, the right buttress's base lifting), 0.12-0.46; the ladder's sliding rung
//    (20 degrees) against the toppling one at collapse, 0.03.
#include <gtest/gtest.h>

#include <cmath>

#include "common.hpp"
#include "dem/util.hpp"
#include "compare/compare.hpp"
#include "compare/report.hpp"
#include "dem/dem.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;

const std::string kSource = MASONRY_SOURCE_DIR;

Case load(const std::string& name) { return load_case(kSource + "/cases/" + name + ".json"); }
RunResult prd(const Case& c) { return prd_run(c, PrdSettings::from_case(c)); }
RunResult dem(const Case& c) { return dem_run(c, DemSettings::from_case(c)); }

// The limit the standard comparisons are checked against.
double paper_limit() {
  const Tolerances t = load_tolerances(kSource + "/reports/paper-tolerances.json");
  EXPECT_TRUE(t.mechanism.has_value());
  return t.mechanism.value_or(NAN);
}

double least(const Comparison& k) {
  double x = 1.0;
  for (const MotionCheck& m : k.motion)
    if (std::isfinite(m.agreement)) x = std::min(x, m.agreement);
  return x;
}

Case half_step(const Case& c) { return with_option(with_option(c, "motion.step", c.motion.step / 2), "motion.max_steps", 2 * c.motion.max_steps); }

// The same mechanism at another resolution of the path: the step halved.
TEST(Mechanism, PrdAgainstItselfAtHalfTheStepAgrees) {
  const double limit = paper_limit();
  for (const char* name : {"pointed-arch", "cathedral-settlement", "cathedral-settlement-rotation"}) {
    SCOPED_TRACE(name);
    const Case c = load(name);
    const Comparison k = compare_runs(c, prd(c), prd(half_step(c)));
    ASSERT_EQ(k.motion.size(), 6u);  // five intervals of the common range and the collapse
    EXPECT_TRUE(k.motion.back().collapse);
    for (const MotionCheck& m : k.motion) {
      EXPECT_TRUE(m.a_moves && m.b_moves);
      EXPECT_GT(m.agreement, 0.99) << interval_text(m, k.d_unit, "a", "b");
    }
    Tolerances t;
    t.mechanism = limit;
    EXPECT_TRUE(check_tolerances(k, t).empty());
  }
}

// The settlement cathedral's PRD with its right springing's corner held closed takes another
// mechanism, known before (dem/README.md, "The branch X"): the right buttress's base lifts
// (support-4/R-buttress-00 opens at B) where PRD's right pier rocks on its base and the nave
// turns at the springing.
TEST(Mechanism, PrdHeldOnAnotherMechanismDisagrees) {
  const Case c = load("cathedral-settlement");
  const Case held = with_option(c, "prd.hold_closed", nlohmann::json::array({"nave-41/R-pier-30:A"}));
  const Comparison k = compare_runs(c, prd(c), prd(held), {}, "PRD", "PRD held");
  ASSERT_FALSE(k.motion.empty());
  EXPECT_LT(least(k), 0.5);
  for (const MotionCheck& m : k.motion) EXPECT_LT(m.agreement, paper_limit()) << interval_text(m, k.d_unit, "a", "b");
  // Another mechanism is not a shifted hinge: no joint's motion moved along its ring by up to
  // three joints makes up the difference.
  CompareOptions o;
  o.ring_shift = kMaxHingeShift;
  EXPECT_LT(least(compare_runs(c, prd(c), prd(held), o)), 0.5);
  // Where they differ: the buttress's base, which only the held run lifts.
  const MotionCheck& first = k.motion.front();
  ASSERT_FALSE(first.differ.empty());
  bool buttress = false;
  for (const MotionDiff& x : first.differ)
    if (x.label == "support-4/R-buttress-00") {
      buttress = true;
      EXPECT_NEAR(x.a.open_b, 0.0, 1e-9);
      EXPECT_GT(x.b.open_b, 1e-3);  // lifts by millimetres
    }
  EXPECT_TRUE(buttress);
  Tolerances t;
  t.mechanism = paper_limit();
  const std::vector<std::string> v = check_tolerances(k, t);
  ASSERT_EQ(v.size(), k.motion.size() - 1);  // every interval of the common range
  EXPECT_EQ(v.front().rfind("mechanism: from d = 0 to ", 0), 0u) << v.front();
  EXPECT_NE(v.front().find("support-4/R-buttress-00"), std::string::npos) << v.front();
}

// PRD with the haunch hinge's open corner held closed (nave-07/nave-08:B) turns about the next
// joint along the nave instead, at the same capacity and with its other hinges where they were:
// the same mechanism with a hinge one voussoir along, which the hinge check accepts within one
// joint (compare/README.md, "Hinges one joint apart"). Read joint by joint the motions differ
// where that hinge (26 mm open) sits; moved along the ring by one joint they agree.
TEST(Mechanism, AHingeOneJointAlongARingIsTheSameMechanismWithinOneJoint) {
  const Case c = load("cathedral-settlement");
  const RunResult a = prd(c), b = prd(with_option(c, "prd.hold_closed", nlohmann::json::array({"nave-07/nave-08:B"})));
  ASSERT_EQ(b.capacity, a.capacity);
  const Comparison strict = compare_runs(c, a, b);
  for (const HingeCheck& h : strict.hinges) EXPECT_TRUE(h.ok(1)) << "d = " << h.d;
  CompareOptions o;
  o.ring_shift = 1;
  const Comparison along = compare_runs(c, a, b, o);
  ASSERT_EQ(along.motion.size(), strict.motion.size());
  EXPECT_LT(strict.motion[0].agreement, 0.95);
  for (size_t n = 0; n < along.motion.size(); ++n) {
    EXPECT_EQ(along.motion[n].same_joints, strict.motion[n].agreement);
    EXPECT_GE(along.motion[n].agreement, strict.motion[n].agreement);
    EXPECT_GT(along.motion[n].agreement, paper_limit());
  }
  EXPECT_GT(along.motion[0].agreement, 0.999);
  EXPECT_GT(along.motion[1].agreement, 0.999);
}

// The arch pushed outwards on the left instead of the right: the mirror image of the same
// mechanism, which counts as agreement on a symmetric structure (the paper's Remark 3).
TEST(Mechanism, TheMirrorImageOnASymmetricArchAgrees) {
  const Case c = load("pointed-arch");
  Case mirrored = c;
  const Bounds box = scene_bounds(c);
  for (SupportMotion& s : mirrored.motion.supports) {
    s.block = c.block_index("left");
    s.translation.x() = -s.translation.x();
    s.about.x() = box.lo.x() + box.hi.x() - s.about.x();
  }
  const RunResult a = prd(c), b = prd(mirrored);
  const Comparison k = compare_runs(c, a, b);
  ASSERT_TRUE(k.symmetric);
  EXPECT_EQ(k.capacity_rel_diff, 0.0);
  ASSERT_EQ(k.motion.size(), 6u);
  for (const MotionCheck& m : k.motion) {
    EXPECT_TRUE(m.mirror);
    EXPECT_GT(m.agreement, 0.999) << interval_text(m, k.d_unit, "a", "b");
    EXPECT_TRUE(m.differ.empty()) << interval_text(m, k.d_unit, "a", "b");  // the same motion to round-off
  }
  // Read directly, without the mirror, they move at other joints.
  Case lopsided = c;
  lopsided.blocks[c.block_index("left")].vertices[0].x() -= 0.01;  // no longer its own mirror image
  const Comparison direct = compare_runs(lopsided, a, b);
  ASSERT_FALSE(direct.symmetric);
  EXPECT_LT(least(direct), 0.5);
}

// The mirror image is the same answer only under a loading that is its own mirror image up to a
// translation of the whole scene: one support spreading (the other spreading, moved back), both
// spreading; not the right support settling (the left settling is another loading, and a run
// that moved the wrong support matched by mirror), nor a slab that tilts one way.
TEST(Mechanism, TheMirrorImageCountsOnlyUnderALoadingThatIsItsOwnMirrorImage) {
  const Case c = load("pointed-arch");
  ASSERT_FALSE(mirror_blocks(c).empty());  // the right support spreading
  Case both = c;
  SupportMotion left;
  left.block = c.block_index("left");
  left.translation = Vec2(-1, 0);
  both.motion.supports.push_back(left);
  EXPECT_FALSE(mirror_blocks(both).empty());
  Case settles = c;
  settles.motion.supports[0].translation = Vec2(0, -1);
  EXPECT_TRUE(mirror_blocks(settles).empty());
  // Both settling alike is a translation of the whole scene: symmetric again.
  Case both_settle = settles;
  left.translation = Vec2(0, -1);
  both_settle.motion.supports.push_back(left);
  EXPECT_FALSE(mirror_blocks(both_settle).empty());
  EXPECT_TRUE(mirror_blocks(load("tilting-block")).empty());  // geometry symmetric, the tilt not
  // The dead loads mirror too: a point load on one voussoir, or one voussoir heavier.
  Case loaded = c;
  Load l;
  l.block = c.block_index("v2");
  l.force = Vec2(0, -2000);
  l.point = centroid(c.blocks[size_t(l.block)].vertices);
  loaded.loads.push_back(l);
  EXPECT_TRUE(mirror_blocks(loaded).empty());
  Load twin = l;
  twin.block = mirror_blocks(c)[size_t(l.block)];
  twin.point = centroid(c.blocks[size_t(twin.block)].vertices);
  loaded.loads.push_back(twin);
  EXPECT_FALSE(mirror_blocks(loaded).empty());
  Case heavier = c;
  heavier.blocks[size_t(c.block_index("v2"))].density *= 1.5;
  EXPECT_TRUE(mirror_blocks(heavier).empty());
  // A PRD run of the right support settling against one of the left settling: read directly,
  // not as mirror images.
  Case left_settles = settles;
  left_settles.motion.supports[0].block = c.block_index("left");
  const Bounds box = scene_bounds(c);
  left_settles.motion.supports[0].about.x() = box.lo.x() + box.hi.x() - settles.motion.supports[0].about.x();
  const Comparison k = compare_runs(settles, prd(settles), prd(left_settles));
  EXPECT_FALSE(k.symmetric);
  for (const MotionCheck& m : k.motion) EXPECT_FALSE(m.mirror);
  EXPECT_LT(least(k), 0.5);
}

// A structure that does not stand as drawn: a block 0.2 x 0.4 m whose centroid stands 0.05 m
// beyond the edge of the slab it rests on falls as the DEM settles it. The run says so, and a
// comparison with it compares nothing but the capacities: its failed state at d = 0 is no
// equilibrium, no settled crack pattern and no thrust (the comparison says it did not settle as
// drawn, which covers a start that still moves at the hold's cap too).
TEST(Mechanism, ARunThatDoesNotStandAsDrawnIsNotCompared) {
  Case c = test::slab_case();
  c.blocks.push_back(test::rect("block", 0.55, 0, 0.75, 0.4, 2000, false));
  SupportMotion m;
  m.block = 0;
  m.translation = Vec2(0, -1);
  c.motion.supports.push_back(m);
  c.motion.step = 0.001;
  c.motion.max_steps = 3;
  const RunResult d = dem(c), p = prd(c);
  ASSERT_EQ(d.status, RunStatus::collapse) << d.message;
  EXPECT_NE(d.message.find("does not stand"), std::string::npos) << d.message;
  ASSERT_FALSE(d.steps.empty());
  EXPECT_FALSE(d.steps.front().settled.value_or(true));
  EXPECT_TRUE(stable_records(d).empty());
  const Comparison k = compare_runs(c, p, d);
  for (const std::string* why : {&k.thrust_skipped, &k.hinges_skipped, &k.mechanism_skipped})
    EXPECT_NE(why->find("did not settle as drawn"), std::string::npos) << *why;
  EXPECT_EQ(settled_gap(d), 0.0);
}

// The tilting block's friction ladder (cases/tilting-block-sweep.json): below atan(b/h) = 26.57
// degrees it slides at the friction angle, above it topples at 26.57 degrees. Two rungs on the
// toppling side move the same way throughout; a sliding rung against a toppling one collapses
// by another mechanism, while their elastic motion before is alike.
TEST(Mechanism, TheFrictionLaddersSlidingAndTopplingRungsDisagreeAtCollapse) {
  const Case c = load("tilting-block");
  const RunResult slides = dem(with_option(c, "dem.friction_angle", 20.0)), topples = dem(with_option(c, "dem.friction_angle", 35.0)),
                  topples_too = dem(with_option(c, "dem.friction_angle", 30.0));
  ASSERT_EQ(slides.status, RunStatus::collapse);
  ASSERT_EQ(topples.status, RunStatus::collapse);
  const Comparison same = compare_runs(c, topples_too, topples);
  EXPECT_EQ(same.d_unit, "rad");
  ASSERT_EQ(same.motion.size(), 6u);
  for (const MotionCheck& m : same.motion) EXPECT_GT(m.agreement, 0.99) << interval_text(m, same.d_unit, "a", "b");
  const Comparison other = compare_runs(c, slides, topples);
  ASSERT_EQ(other.motion.size(), 6u);
  const MotionCheck& collapse = other.motion.back();
  ASSERT_TRUE(collapse.collapse);
  EXPECT_LT(collapse.agreement, 0.1);
  ASSERT_FALSE(collapse.differ.empty());
  // The sliding rung slides without turning, the toppling one turns. The DEM calls a failure no
  // sooner than a block has drifted a tenth of the collapse drift (dem/README.md, the hold), 2 mm
  // here, which a slide without turning slips: half of it is still 15 times the joint's elastic
  // shear at the sliding tilt (W sin 20 deg / (ks A) = 0.07 mm).
  ASSERT_GT(c.dem.collapse_drift, 0);
  EXPECT_GT(std::abs(collapse.differ[0].a.slip), 0.5 * 0.1 * c.dem.collapse_drift);
  EXPECT_LT(std::abs(collapse.differ[0].a.rotation), 1e-4);
  EXPECT_GT(std::abs(collapse.differ[0].b.rotation), 0.05);  // the toppling one turns
  for (size_t n = 0; n + 1 < other.motion.size(); ++n) EXPECT_GT(other.motion[n].agreement, paper_limit());
  // So the check over the common range passes, and the one at collapse fails.
  Tolerances t;
  t.mechanism = paper_limit();
  EXPECT_TRUE(check_tolerances(other, t).empty());
  t.collapse_mechanism = paper_limit();
  const std::vector<std::string> v = check_tolerances(other, t);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].rfind("collapse_mechanism: at collapse", 0), 0u) << v[0];
  EXPECT_NE(v[0].find("ground/block"), std::string::npos) << v[0];
  EXPECT_TRUE(check_tolerances(same, t).empty());
  // PRD's block is carried rigidly by the tilting ground until it topples: no joint moves, so its
  // agreement with any run over the range is not determined (null), and the check does not fail
  // on it. At collapse PRD's side is its collapse mechanism (the collapse configuration moved
  // along it, `moved_poses`): the block turning about its downhill corner, as the toppling rung
  // does and the sliding one does not. (Before, PRD's collapse state was the last step's motion
  // alone, no joint moving: "n/a", and the sliding rung passed against it.)
  const RunResult p = prd(c);
  const Comparison rigid = compare_runs(c, p, topples);
  ASSERT_EQ(rigid.motion.size(), 6u);
  for (size_t n = 0; n + 1 < rigid.motion.size(); ++n) {
    EXPECT_FALSE(rigid.motion[n].a_moves);
    EXPECT_TRUE(std::isnan(rigid.motion[n].agreement));
  }
  EXPECT_TRUE(to_json(rigid)["mechanism_agreement"][0]["agreement"].is_null());
  ASSERT_TRUE(rigid.motion.back().collapse);
  EXPECT_TRUE(rigid.motion.back().a_moves);
  EXPECT_GT(rigid.motion.back().agreement, 0.99);
  EXPECT_TRUE(check_tolerances(rigid, t).empty());
  const Comparison wrong = compare_runs(c, p, slides);
  EXPECT_LT(wrong.motion.back().agreement, 0.1);
  ASSERT_EQ(check_tolerances(wrong, t).size(), 1u);
  // The moved configuration is the collapse configuration plus the boxed increments: the block
  // turns relative to the ground by a part of a step (its increments at most one step of
  // displacement each, its turn's times its radius, 0.22 m, among them).
  ASSERT_TRUE(p.collapse.has_value());
  ASSERT_EQ(p.collapse->moved_poses.size(), p.collapse->poses.size());
  const double turn = (p.collapse->moved_poses[1].angle - p.collapse->poses[1].angle) - (p.collapse->moved_poses[0].angle - p.collapse->poses[0].angle);
  EXPECT_GT(std::abs(turn), 0.1 * c.motion.step);
  EXPECT_LE(std::abs(turn), c.motion.step / 0.2);
}

// The command: PRD against PRD held on another mechanism exits 1 and names the mechanism check;
// PRD against itself at half the step passes.
TEST(MechanismCommand, AnotherMechanismFailsTheCheckAndHalfTheStepPasses) {
  const test::Scratch scratch("mechanism-cli");
  const fs::path d = scratch.path;
  const std::string exe = MASONRY_EXE, cs = kSource + "/cases/cathedral-settlement.json";
  ASSERT_EQ(test::run(exe + " prd " + cs + " --out " + (d / "prd").string() + " 2>/dev/null"), 0);
  ASSERT_EQ(test::run(exe + " prd " + cs + " --hold nave-41/R-pier-30:A --out " + (d / "held").string() + " 2>/dev/null"), 0);
  ASSERT_EQ(test::run(exe + " prd " + cs + " --step 0.005 --max-steps 600 --out " + (d / "half").string() + " 2>/dev/null"), 0);
  const std::string base =
      exe + " compare " + cs + " --quiet --tolerances " + kSource + "/reports/paper-tolerances.json --runs " + (d / "prd").string();
  EXPECT_EQ(test::run(base + " " + (d / "held").string() + " --out " + (d / "c-held").string() + " 2>" + (d / "err.txt").string()), 1);
  const std::string err = test::read(d / "err.txt");
  EXPECT_NE(err.find("limit exceeded: mechanism: from d = 0 to "), std::string::npos) << err;
  EXPECT_EQ(err.find("collapse"), std::string::npos) << "the paper's limits do not check the collapse: " << err;
  const auto j = nlohmann::json::parse(test::read(d / "c-held" / "comparison.json"));
  const auto& ma = j["comparisons"][0]["mechanism_agreement"];
  ASSERT_EQ(ma.size(), 6u);
  EXPECT_LT(ma[0]["agreement"].get<double>(), 0.5);
  EXPECT_FALSE(j["comparisons"][0]["tolerances"]["pass"].get<bool>());
  EXPECT_NE(test::read(d / "c-held" / "report.md").find("### Mechanism agreement"), std::string::npos);
  EXPECT_EQ(test::run(base + " " + (d / "half").string() + " --out " + (d / "c-half").string() + " 2>/dev/null"), 0);
  const auto h = nlohmann::json::parse(test::read(d / "c-half" / "comparison.json"));
  for (const auto& m : h["comparisons"][0]["mechanism_agreement"]) EXPECT_GT(m["agreement"].get<double>(), 0.99);
}

TEST(Mechanism, TheLimitIsANumberFromZeroToOne) {
  EXPECT_EQ(parse_tolerances(R"({"mechanism": 0.9})", "t.json").mechanism, 0.9);
  EXPECT_EQ(parse_tolerances(R"({"collapse_mechanism": 0.5})", "t.json").collapse_mechanism, 0.5);
  for (const char* bad : {R"({"mechanism": 1.5})", R"({"mechanism": -0.1})", R"({"mechanism": "high"})", R"({"mechanism": true})"}) {
    try {
      parse_tolerances(bad, "t.json");
      ADD_FAILURE() << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("t.json: \"mechanism\""), std::string::npos) << e.what();
    }
  }
}

// Sliding over the common range (compare/README.md, "Sliding"). Closed forms: a block moved along
// its joint by 2 mm slid 2 mm there; one turned about a corner of its joint slid nowhere (that
// corner stays in contact); a joint's elastic shear is its shear force over ks A.
TEST(Sliding, ASlideIsItsLengthAndAHingeNone) {
  const Case c = load("tilting-block");  // ground, then a 0.2 x 0.4 m block on it
  const RunResult base = prd(with_option(c, "motion.max_steps", 1));
  ASSERT_EQ(base.joints.size(), 1u);
  ASSERT_GE(base.steps.size(), 2u);
  // Two records: the start, then the block moved with the ground held.
  const auto moved = [&](const Pose& q) {
    RunResult r = base;
    r.steps.resize(2);
    r.steps[1].poses = r.steps[0].poses;
    r.steps[1].poses[1] = q;
    r.capacity = r.steps[1].d;
    r.status = RunStatus::max_steps;
    return r;
  };
  const Vec2 c0 = centroid(c.blocks[1].vertices);
  const RunResult slid = moved({c0.x() + 0.002, c0.y(), 0.0});
  // Toppled by 0.05 rad to the right, about its right bottom corner (0.1, 0): the centroid goes
  // round it and the left corner lifts.
  const double t = -0.05;
  const Vec2 pivot(0.1, 0.0), arm = c0 - pivot;
  const Vec2 turned_c = pivot + Vec2(std::cos(t) * arm.x() - std::sin(t) * arm.y(), std::sin(t) * arm.x() + std::cos(t) * arm.y());
  const RunResult hinged = moved({turned_c.x(), turned_c.y(), t});
  const Comparison k = compare_runs(c, slid, hinged);
  ASSERT_TRUE(k.sliding.has_value());
  EXPECT_EQ(k.sliding->largest_a.label, "ground/block");
  EXPECT_NEAR(k.sliding->largest_a.a, 0.002, 1e-12);
  EXPECT_LT(k.sliding->largest_a.b, 1e-12);  // the pivot corner stays where it was
  EXPECT_NEAR(k.sliding->largest_b.a, 0.002, 1e-12);
  const nlohmann::ordered_json j = to_json(k);
  EXPECT_NEAR(j["sliding"]["largest_a"]["a"].get<double>(), 0.002, 1e-12);
  EXPECT_EQ(j["sliding"]["largest_b"]["joint"], "ground/block");
}

// Jumps (compare/README.md, "Jumps"): between two records one step apart (1 degree of the
// tilting block's slab, whose farthest point travels the scene's size per radian), the block
// moved by ten times that travel is a jump, by twice it none, and by less than a thousandth of
// the scene none however small the step; and where one run collapses at the other's jump, which
// the other went through, the report says so.
TEST(Jumps, AMotionFarBeyondTheSupportsTravelIsAJump) {
  const Case c = load("tilting-block");
  RunResult base = prd(with_option(c, "motion.max_steps", 8));  // standing on well past the jump
  ASSERT_GE(base.steps.size(), 9u);
  base.steps.resize(9);
  const double travel = support_travel_per_d(c) * (base.steps[1].d - base.steps[0].d);
  const auto moved_by = [&](double k) {
    RunResult r = base;
    for (size_t i = 1; i < r.steps.size(); ++i) r.steps[i].poses = r.steps[0].poses;
    for (size_t i = 2; i < r.steps.size(); ++i) r.steps[i].poses[1].x += k * travel;  // the block, between the second and third records
    r.capacity = r.steps.back().d;
    r.status = RunStatus::max_steps;
    return r;
  };
  const RunResult jumped = moved_by(10), crept = moved_by(2);
  const std::vector<Jump> j = jumps(c, jumped);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0].block, "block");
  EXPECT_NEAR(j[0].drift, 10 * travel, 1e-12);
  EXPECT_DOUBLE_EQ(j[0].from, base.steps[1].d);
  EXPECT_DOUBLE_EQ(j[0].to, base.steps[2].d);
  EXPECT_TRUE(jumps(c, crept).empty());
  // Far beyond the supports' travel but under a thousandth of the scene: no jump (a settling).
  const double floor = kJumpFloor * scene_size(c);
  RunResult tiny = base;
  tiny.steps.resize(3);
  for (StepRecord& s : tiny.steps) s.poses = base.steps[0].poses;
  tiny.steps[2].poses[1].x += 0.5 * floor;
  tiny.steps[2].d = tiny.steps[1].d + 1e-3 * (base.steps[2].d - base.steps[1].d);  // a thousandth of a step: 0.5 floor is far beyond its travel
  ASSERT_GT(0.5 * floor, kJumpRatio * travel * 1e-3);
  tiny.capacity = tiny.steps[2].d;
  EXPECT_TRUE(jumps(c, tiny).empty());
  // The other run collapsed at the first record: near the jump, which the first went through.
  RunResult fell = crept;
  fell.steps.resize(2);
  fell.capacity = fell.steps[1].d;
  fell.collapsed = true;
  fell.status = RunStatus::collapse;
  const Comparison k = compare_runs(c, jumped, fell);
  ASSERT_EQ(k.jumps_a.size(), 1u);
  EXPECT_TRUE(k.jumps_b.empty());
  EXPECT_EQ(to_json(k)["jumps"]["a"].size(), 1u);
  const std::string md = report_markdown(make_report(c, {{"PRD", &jumped, "a"}, {"other", &fell, "b"}}), {});
  EXPECT_NE(md.find("Jumps: "), std::string::npos);
  EXPECT_NE(md.find("other collapsed at 17.5 mrad, near PRD's jump at 17.5 to 34.9 mrad, which PRD went through"), std::string::npos) << md;
  // A run that stood no further than the jump's end did not go through it: no such sentence
  // (PRD's last sub-step into a located limit is a jump, and a run collapsing beside it met the
  // same limit).
  RunResult ended = jumped;
  ended.steps.resize(3);
  ended.capacity = ended.steps[2].d;
  ended.collapsed = true;
  ended.status = RunStatus::collapse;
  const std::string md2 = report_markdown(make_report(c, {{"PRD", &ended, "a"}, {"other", &fell, "b"}}), {});
  EXPECT_NE(md2.find("Jumps: "), std::string::npos);
  EXPECT_EQ(md2.find("which PRD went through"), std::string::npos) << md2;
}

TEST(Sliding, ADemBlockOnATiltingSlabShearsElasticallyAndPrdRidesRigidly) {
  // Tilted to 10 degrees, where both of the joint's contact points stay within friction: the
  // uphill point carries N (1/2 - e/b), e = (h/2) tan(t), and its shear reaches tan(35 deg) of
  // that past about 16 degrees, after which the downhill point carries nearly all the shear on
  // half the area (about twice the slip below).
  const Case c = with_option(load("tilting-block"), "motion.max_steps", 10);
  const RunResult p = prd(c), d = dem(c);
  const Comparison k = compare_runs(c, p, d);
  ASSERT_TRUE(k.sliding.has_value());
  // PRD's block rides the slab rigidly: its joint does not move.
  EXPECT_LT(k.sliding->largest_a.a, 1e-9);
  // The DEM's joint shears by its elastic spring: W sin(tilt) / (ks A) (the tilt in rad, 1 rad
  // of tilt per m of d).
  const double W = 0.2 * 0.4 * 1.0 * 2000 * 9.81, A = 0.2 * 1.0;
  ASSERT_NEAR(k.sliding->b_to, 10 * c.motion.step, 1e-12);
  const double elastic = W * std::sin(k.sliding->b_to) / (*c.dem.ks * A);
  EXPECT_NEAR(k.sliding->largest_b.b, elastic, 0.02 * elastic);
}

}  // namespace
}  // namespace masonry
