// The comparison's numbers: a run against itself differs by exactly nothing, doctored results
// trip the tolerance gate, results.json reads back to the same comparison, missing numbers are
// null, and the pointed arch is recognised as symmetric with the mirror pairs its generator
// documents (cases/generators.hpp: "left".."right", "v0".."v13").
#include "compare/compare.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "common.hpp"
#include "compare/convergence.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

const Case& arch() {
  static const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  return c;
}

const RunResult& arch_prd() {
  static const RunResult r = prd_run(arch(), PrdSettings::from_case(arch()));
  return r;
}

TEST(Compare, RunAgainstItselfDiffersByNothing) {
  const RunResult& r = arch_prd();
  ASSERT_GT(r.capacity, 0.0);
  const Comparison k = compare_runs(arch(), r, r);
  EXPECT_EQ(k.capacity_rel_diff, 0.0);
  EXPECT_EQ(k.thrust_max_diff, 0.0);
  EXPECT_EQ(k.thrust_rms_diff, 0.0);
  EXPECT_EQ(k.d_max, r.capacity);
  EXPECT_EQ(k.supports.size(), 2u);  // "left" and "right"
  ASSERT_FALSE(k.hinges.empty());
  for (const HingeCheck& h : k.hinges) EXPECT_TRUE(h.match) << "d = " << h.d;
  EXPECT_EQ(k.a.changes, k.b.changes);
  EXPECT_TRUE(check_tolerances(k, {0.0, 0.0, true}).empty());
}

TEST(Compare, TwoPrdRunsOfOneCaseDifferByNothing) {
  // PRD is deterministic: a second run of the same case is the same run.
  const RunResult again = prd_run(arch(), PrdSettings::from_case(arch()));
  const Comparison k = compare_runs(arch(), arch_prd(), again);
  EXPECT_EQ(k.capacity_rel_diff, 0.0);
  EXPECT_EQ(k.thrust_max_diff, 0.0);
  for (const HingeCheck& h : k.hinges) EXPECT_TRUE(h.match);
  EXPECT_TRUE(check_tolerances(k, {0.05, 0.10, true}).empty());
}

TEST(Compare, ToleranceGateFailsOnDoctoredCapacity) {
  RunResult doctored = arch_prd();
  doctored.capacity *= 1.2;
  const Tolerances t = parse_tolerances(R"({"capacity": 0.05, "thrust": 0.10, "hinges": true})", "test");
  const auto v = check_tolerances(compare_runs(arch(), arch_prd(), doctored), t);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].rfind("capacity", 0), 0u) << v[0];
  EXPECT_TRUE(check_tolerances(compare_runs(arch(), arch_prd(), arch_prd()), t).empty());
}

TEST(Compare, ToleranceGateFailsOnDoctoredThrust) {
  RunResult doctored = arch_prd();
  // 0.2 W more horizontal reaction on the left support at one record in the middle.
  StepRecord& s = doctored.steps[doctored.steps.size() / 2];
  s.reactions[0].force.x() += 0.2 * doctored.total_weight;
  const Comparison k = compare_runs(arch(), arch_prd(), doctored);
  EXPECT_NEAR(k.thrust_max_diff, 0.2, 1e-12);
  const auto v = check_tolerances(k, {std::nullopt, 0.10, false});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].rfind("thrust", 0), 0u) << v[0];
  EXPECT_TRUE(check_tolerances(k, {std::nullopt, 0.25, false}).empty());
}

TEST(Compare, ToleranceGateFailsOnDoctoredHinges) {
  RunResult doctored = arch_prd();
  for (StepRecord& s : doctored.steps) {
    s.open_corners.clear();
    s.cracked.clear();
  }
  const Comparison k = compare_runs(arch(), arch_prd(), doctored);
  EXPECT_FALSE(check_tolerances(k, {std::nullopt, std::nullopt, true}).empty());
  EXPECT_TRUE(check_tolerances(k, {std::nullopt, std::nullopt, false}).empty());
  EXPECT_TRUE(k.b.changes.empty());
  EXPECT_FALSE(k.a.changes.empty());
}

TEST(Compare, AnAbsoluteCapacityLimitJudgesWhereARelativeOneCannot) {
  // 1.5 mm more capacity: 0.54% of the arch's 0.278 m.
  RunResult more = arch_prd();
  more.capacity += 0.0015;
  const Comparison k = compare_runs(arch(), arch_prd(), more);
  const auto violations = [&](const char* limits) { return check_tolerances(k, parse_tolerances(limits, "t.json")); };
  EXPECT_EQ(violations(R"({"capacity": 0.001})").size(), 1u);
  EXPECT_EQ(violations(R"({"capacity_abs": 0.001})").size(), 1u);
  EXPECT_TRUE(violations(R"({"capacity_abs": 0.002})").empty());
  // Both: the larger limit holds (as a catalogue's tolerance).
  EXPECT_TRUE(violations(R"({"capacity": 0.001, "capacity_abs": 0.002})").empty());
  EXPECT_TRUE(violations(R"({"capacity": 0.01, "capacity_abs": 0.001})").empty());
  const auto v = violations(R"({"capacity": 0.001, "capacity_abs": 0.001})");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].find("difference 0.0015 m"), std::string::npos) << v[0];
  // A reference capacity of 0 has no relative difference; an absolute limit still judges it.
  RunResult zero = arch_prd(), small = arch_prd();
  zero.capacity = 0;
  small.capacity = 0.0005;
  const Comparison z = compare_runs(arch(), zero, small);
  EXPECT_EQ(check_tolerances(z, parse_tolerances(R"({"capacity": 0.05})", "t.json")).size(), 1u);
  EXPECT_TRUE(check_tolerances(z, parse_tolerances(R"({"capacity_abs": 0.001})", "t.json")).empty());
  EXPECT_THROW(parse_tolerances(R"({"capacity_abs": -1})", "t.json"), std::runtime_error);
}

TEST(Compare, WhatARunsResultsDoNotGiveIsNotComparedAndSaysSo) {
  // An outside solver's minimal results: its capacity and steps, no reactions, no joints.
  const RunResult& a = arch_prd();
  RunResult lean;
  lean.method = "my-lp";
  lean.capacity = a.capacity;
  lean.status = RunStatus::collapse;
  for (const StepRecord& s : a.steps) {
    StepRecord t;
    t.index = s.index;
    t.d = s.d;
    lean.steps.push_back(t);
  }
  const Comparison k = compare_runs(arch(), a, lean);
  EXPECT_EQ(k.thrust_skipped, "not compared: my-lp gives no reactions");
  EXPECT_EQ(k.hinges_skipped, "not compared: my-lp gives no joints");
  EXPECT_TRUE(k.supports.empty());
  EXPECT_TRUE(k.hinges.empty());
  EXPECT_EQ(k.capacity_rel_diff, 0.0);
  // The limits on what is not compared are not checked; the capacity is.
  EXPECT_TRUE(check_tolerances(k, {0.05, 0.10, true}).empty());
  const auto j = to_json(k);
  EXPECT_FALSE(j["thrust"]["compared"].get<bool>());
  EXPECT_FALSE(j["hinges"]["compared"].get<bool>());
  EXPECT_TRUE(compare_runs(arch(), a, a).thrust_skipped.empty());
  EXPECT_TRUE(to_json(compare_runs(arch(), a, a))["thrust"]["compared"].get<bool>());
  // The mechanism agreement moves corners with the poses and weights joints by their forces: a
  // run with joints and poses but no forces gives no agreement, and says so instead of passing.
  EXPECT_EQ(k.mechanism_skipped, "not compared: my-lp gives no joints, poses and forces at every record");
  EXPECT_TRUE(k.motion.empty());
  Tolerances mech;
  mech.mechanism = 0.9;
  mech.collapse_mechanism = 0.9;
  EXPECT_TRUE(check_tolerances(k, mech).empty());
  EXPECT_EQ(j["mechanism_note"], k.mechanism_skipped);
  EXPECT_FALSE(j.contains("mechanism_joints_apart"));
  RunResult no_forces = a;
  for (StepRecord& s : no_forces.steps) s.forces.clear();
  no_forces.method = "my-lp";
  const Comparison f = compare_runs(arch(), a, no_forces);
  EXPECT_FALSE(f.mechanism_skipped.empty());
  EXPECT_TRUE(f.hinges_skipped.empty());
  const Comparison same = compare_runs(arch(), a, a);
  EXPECT_TRUE(same.mechanism_skipped.empty());
  EXPECT_FALSE(same.motion.empty());
  Tolerances strict;
  strict.mechanism = 0.999;
  EXPECT_TRUE(check_tolerances(same, strict).empty());  // a run agrees with itself
}

TEST(Compare, PointedArchIsItsOwnMirrorImage) {
  const Case& c = arch();
  const std::vector<int> m = mirror_blocks(c);
  ASSERT_EQ(m.size(), c.blocks.size());
  EXPECT_EQ(m[c.block_index("left")], c.block_index("right"));
  EXPECT_EQ(m[c.block_index("v0")], c.block_index("v13"));
  EXPECT_EQ(m[c.block_index("v6")], c.block_index("v7"));
}

TEST(Compare, MirroredHingesMatchAsMirrorImage) {
  // The hinges of a run, moved to their mirror joints: not a match, but a mirror match.
  const Case& c = arch();
  const RunResult& r = arch_prd();
  const std::vector<int> m = mirror_blocks(c);
  RunResult mirrored = r;
  for (StepRecord& s : mirrored.steps) {
    std::vector<OpenCorner> oc;
    for (const OpenCorner& o : s.open_corners) {
      const JointInfo& j = r.joints[o.joint];
      const Vec2 p = o.corner == 0 ? j.a : j.b;
      const Vec2 q(-p.x(), p.y());  // the arch is symmetric about x = 0
      for (size_t k = 0; k < r.joints.size(); ++k) {
        const JointInfo& g = r.joints[k];
        const bool pair = (g.i == m[j.i] && g.j == m[j.j]) || (g.i == m[j.j] && g.j == m[j.i]);
        if (!pair) continue;
        OpenCorner x = o;
        x.joint = int(k);
        x.corner = (g.a - q).norm() < (g.b - q).norm() ? 0 : 1;
        oc.push_back(x);
      }
    }
    s.open_corners = oc;
  }
  const Comparison k = compare_runs(c, r, mirrored);
  EXPECT_TRUE(k.symmetric);
  bool some_hinge = false;
  for (const HingeCheck& h : k.hinges) {
    some_hinge = some_hinge || !h.a.empty();
    EXPECT_TRUE(h.ok()) << "d = " << h.d;
    if (!h.a.empty()) {
      EXPECT_FALSE(h.match);
    }
  }
  EXPECT_TRUE(some_hinge);
  EXPECT_TRUE(check_tolerances(k, {std::nullopt, std::nullopt, true}).empty());
}

// A DEM on compliant joints settles with gaps open (on the cathedral up to 0.23 mm), and the
// support motion moves such gaps by a fraction of that as it redistributes the weight: the hinge
// check counts what opens beyond the widest settled gap, the same rule for both runs. Built on
// PRD's arch run: a copy with a settled crack at a joint PRD keeps closed, which grows
// elastically by 0.1 mm (the cathedral's left-side joints), matches PRD; the same crack opening
// by 0.3 mm does not, and its opening since d = 0 is what the check reports.
TEST(Compare, HingesAreWhatTheMotionOpensBeyondTheSettledGaps) {
  const Case& c = arch();
  const RunResult& r = arch_prd();
  ASSERT_FALSE(r.steps.empty());
  EXPECT_EQ(settled_gap(r), 0.0);  // rigid blocks settle closed
  // A joint whose corners PRD never opens.
  std::set<int> used;
  for (const StepRecord& s : r.steps)
    for (const OpenCorner& o : s.open_corners) used.insert(o.joint);
  int quiet = -1;
  for (int j = 0; j < int(r.joints.size()) && quiet < 0; ++j)
    if (!used.count(j)) quiet = j;
  ASSERT_GE(quiet, 0);
  const double g0 = 0.23e-3;
  const auto with_crack = [&](double growth) {
    RunResult x = r;
    for (StepRecord& s : x.steps) s.open_corners.push_back({quiet, 0, s.index == 0 ? g0 : g0 + growth});
    return x;
  };
  const RunResult elastic = with_crack(0.1e-3);
  EXPECT_DOUBLE_EQ(settled_gap(elastic), g0);
  // Read without the rule, the settled crack is a hinge PRD does not have.
  ASSERT_FALSE(hinges_of(c, elastic, elastic.steps.back()).empty());
  EXPECT_NE(hinges_of(c, elastic, elastic.steps.back()).size(), hinges_of(c, r, r.steps.back()).size());
  const Comparison k = compare_runs(c, r, elastic);
  EXPECT_DOUBLE_EQ(k.hinge_gap, g0);
  ASSERT_FALSE(k.hinges.empty());
  for (const HingeCheck& h : k.hinges) EXPECT_TRUE(h.match) << "d = " << h.d;
  EXPECT_TRUE(check_tolerances(k, {std::nullopt, std::nullopt, true}).empty());
  // Opening by more than the settled gap is the motion's hinge.
  const Comparison wide = compare_runs(c, r, with_crack(0.3e-3));
  for (const HingeCheck& h : wide.hinges) {
    EXPECT_FALSE(h.ok()) << "d = " << h.d;
    // The extra hinge is the crack, opened by what it grew since d = 0.
    int found = 0;
    for (const Hinge& x : h.b)
      if (x.joint == quiet) {
        ++found;
        EXPECT_NEAR(x.opening, 0.3e-3, 1e-15);
      }
    EXPECT_EQ(found, 1) << "d = " << h.d;
  }
  // PRD settles closed: a hinge's opening is its open corner's gap.
  for (const HingeCheck& h : k.hinges)
    for (const Hinge& x : h.a) {
      const StepRecord* s = record_at(stable_records(r), h.d);
      bool seen = false;
      for (const OpenCorner& o : s->open_corners)
        if (o.joint == x.joint && o.corner == 1 - x.corner) {
          seen = true;
          EXPECT_EQ(x.opening, o.gap);
        }
      EXPECT_TRUE(seen) << x.label;
    }
  // PRD's own hinges at every check open by more than 0.23 mm: the rule drops none of them.
  for (const HingeCheck& h : k.hinges) EXPECT_EQ(h.a.size(), hinges_of(c, r, *record_at(stable_records(r), h.d)).size());
}

TEST(Compare, ResultsJsonReadsBackToTheSameRun) {
  const RunResult& r = arch_prd();
  const std::string text = to_json(r, arch()).dump(1);
  const RunResult back = parse_results(text, arch(), "results.json");
  EXPECT_EQ(back.method, "prd");
  EXPECT_EQ(back.status, r.status);
  EXPECT_EQ(back.steps.size(), r.steps.size());
  EXPECT_EQ(back.joints.size(), r.joints.size());
  const Comparison k = compare_runs(arch(), r, back);
  EXPECT_EQ(k.capacity_rel_diff, 0.0);
  EXPECT_EQ(k.thrust_max_diff, 0.0);
  for (const HingeCheck& h : k.hinges) EXPECT_TRUE(h.match);
  // A method's own fields come back too (a convergence study read back from disk reports the
  // DEM's collapse bracket).
  RunResult with = r;
  with.collapse_bracket = CollapseBracket{0.1, 0.10008, 8e-5, {{0.10008, "collapse", 12, false}}};
  const RunResult back2 = parse_results(to_json(with, arch()).dump(1), arch(), "results.json");
  ASSERT_TRUE(back2.collapse_bracket);
  EXPECT_EQ(back2.collapse_bracket->width, 8e-5);
  ASSERT_EQ(back2.collapse_bracket->trials.size(), 1u);
  EXPECT_EQ(back2.collapse_bracket->trials[0].end, "collapse");
}

// The runs kept under reports/ are xz-compressed (results.json.xz): read back through the same
// path as results.json, to the same run; a damaged file is refused with its name.
TEST(Compare, CompressedResultsReadBackToTheSameRun) {
  if (test::run("command -v xz >/dev/null 2>&1") != 0) GTEST_SKIP() << "xz is not installed (scripts/install-deps.sh installs it)";
  const test::Scratch scratch("results-xz");
  const std::filesystem::path d = scratch.path;
  write_results(d.string(), arch_prd(), arch());
  ASSERT_EQ(test::run("xz -1 " + (d / "results.json").string()), 0);
  ASSERT_FALSE(std::filesystem::exists(d / "results.json"));
  const RunResult back = load_results((d / "results.json").string(), arch());
  EXPECT_EQ(back.steps.size(), arch_prd().steps.size());
  EXPECT_EQ(to_json(back, arch()).dump(), to_json(arch_prd(), arch()).dump());  // bit for bit
  EXPECT_EQ(load_results((d / "results.json.xz").string(), arch()).steps.size(), back.steps.size());
  test::write(d / "results.json.xz", "not xz at all");
  try {
    load_results((d / "results.json").string(), arch());
    ADD_FAILURE() << "a damaged file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("results.json.xz: not a valid xz file"), std::string::npos) << e.what();
  }
}

TEST(Compare, ResultsOfAnotherCaseAreRefused) {
  Case other = arch();
  other.blocks[3].id = "not-v2";
  EXPECT_THROW(parse_results(to_json(arch_prd(), arch()).dump(), other, "results.json"), std::runtime_error);
  EXPECT_THROW(parse_results("{", arch(), "results.json"), std::runtime_error);
}

// Every status a run can end with is written by its name and read back as itself; a name that
// is none of them is refused with the field named, not read as some default.
TEST(Compare, RunStatusReadsBackAndAnUnknownOneIsRefused) {
  for (RunStatus s : {RunStatus::running, RunStatus::collapse, RunStatus::max_steps, RunStatus::undecided, RunStatus::error}) {
    RunResult r = arch_prd();
    r.status = s;
    r.collapsed = s == RunStatus::collapse;  // the reader checks that they agree
    EXPECT_EQ(parse_results(to_json(r, arch()).dump(), arch(), "results.json").status, s) << s;
  }
  EXPECT_TRUE(located(RunStatus::collapse) && located(RunStatus::max_steps));
  EXPECT_FALSE(located(RunStatus::undecided) || located(RunStatus::error) || located(RunStatus::running));
  auto j = to_json(arch_prd(), arch());
  j["stopped"] = "finished";
  try {
    parse_results(j.dump(), arch(), "results.json");
    ADD_FAILURE() << "an unknown status was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("stopped"), std::string::npos) << e.what();
  }
}

// Two runs part where their open joints differ for good; a joint that opens one record later in
// one run is a difference that closes again, not a parting.
TEST(Compare, HingesPartWhereTheyDifferForGood) {
  const RunResult& base = arch_prd();
  ASSERT_GE(base.joints.size(), 3u);
  auto run = [&](const std::vector<std::vector<OpenCorner>>& open) {
    RunResult r;
    r.joints = base.joints;
    r.status = RunStatus::collapse;
    for (size_t k = 0; k < open.size(); ++k) {
      StepRecord s;
      s.index = int(k);
      s.d = 0.1 * double(k);
      s.open_corners = open[k];
      r.steps.push_back(s);
    }
    r.capacity = r.steps.back().d;
    return r;
  };
  const OpenCorner j1{0, 0, 2e-3}, j2{1, 1, 3e-3}, j3{2, 1, 4e-3}, tiny{2, 0, 1e-5};
  const RunResult a = run({{}, {j1}, {j1, tiny}, {j1, j2}, {j1, j2}});
  const RunResult b = run({{}, {}, {j1}, {j1, j3}, {j1, j3}});
  const std::optional<Parting> p = hinges_part(arch(), a, b, 1e-4);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->d, 0.3, 1e-12);
  const auto name = [&](const OpenCorner& o) {
    const JointInfo& ji = base.joints[o.joint];
    return arch().blocks[ji.i].id + "/" + arch().blocks[ji.j].id + (o.corner == 0 ? ":A" : ":B");
  };
  ASSERT_EQ(p->only_a.size(), 1u);
  ASSERT_EQ(p->only_b.size(), 1u);
  EXPECT_EQ(p->only_a[0].rfind(name(j2), 0), 0u) << p->only_a[0];
  EXPECT_EQ(p->only_b[0].rfind(name(j3), 0), 0u) << p->only_b[0];
  // And as they stand at the end of the common range.
  EXPECT_NEAR(p->end_d, 0.4, 1e-12);
  ASSERT_EQ(p->end_only_a.size(), 1u);
  EXPECT_EQ(p->end_only_a[0].rfind(name(j2), 0), 0u) << p->end_only_a[0];
  ASSERT_EQ(p->end_only_b.size(), 1u);
  EXPECT_FALSE(hinges_part(arch(), a, a, 1e-4));  // a run does not part from itself
  EXPECT_FALSE(hinges_part(arch(), a, b, 5e-3));  // nothing open that wide
  // A difference at the last record alone is the approach to collapse, not a parting.
  EXPECT_FALSE(hinges_part(arch(), run({{}, {j1}, {j1, j2}}), run({{}, {j1}, {j1}}), 1e-4));
  // The settled state (step 0) is no mechanism: a DEM's elastic settling gaps there, wide with
  // soft joints, are not where the mechanisms part; the first increment's difference is.
  const std::optional<Parting> q = hinges_part(arch(), run({{j3}, {j1, j2}, {j1, j2}, {j1, j2}}), run({{}, {j1}, {j1}, {j1}}), 1e-4);
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->d, 0.1, 1e-12);
  ASSERT_EQ(q->only_a.size(), 1u);
  EXPECT_EQ(q->only_a[0].rfind(name(j2), 0), 0u) << q->only_a[0];
}

TEST(Compare, MissingNumbersAreNullNotNaN) {
  RunResult b = arch_prd();
  b.capacity = std::numeric_limits<double>::quiet_NaN();
  const Comparison k = compare_runs(arch(), arch_prd(), b);
  const auto j = to_json(k);
  EXPECT_TRUE(j["capacity"]["b"].is_null());
  EXPECT_TRUE(j["capacity"]["relative_difference"].is_null());
  EXPECT_EQ(j.dump().find("NaN"), std::string::npos);
  EXPECT_FALSE(check_tolerances(k, {0.05, std::nullopt, false}).empty());  // unknown is not a pass
}

// A study whose runs end at the end of their path (max_steps, as a study of the first
// centimetres does) agrees on that end, not on a collapse, and its verdict says so.
TEST(Convergence, AStudyOfPathEndsDoesNotReadAsOneOfCollapses) {
  const auto study = [](RunStatus s) {
    Convergence c;
    c.case_name = "t";
    for (const char* name : {"default", "other"}) {
      RunResult r;
      r.status = s;
      r.capacity = 0.1;
      r.settings = {{"hold_time", 150.0}};
      c.entries.push_back({name, name, r, std::nullopt});
    }
    c.prd_capacity = 0.1;
    return c;
  };
  const Convergence ends = study(RunStatus::max_steps), collapses = study(RunStatus::collapse);
  ASSERT_TRUE(judge(ends).ok);
  ASSERT_TRUE(judge(collapses).ok);
  const std::string a = convergence_markdown(ends), b = convergence_markdown(collapses);
  EXPECT_EQ(a.find("located its collapse"), std::string::npos) << a;
  EXPECT_NE(a.find("end of its path"), std::string::npos) << a;
  EXPECT_NE(b.find("located its collapse"), std::string::npos) << b;
  // The default's settings, as its run recorded them, make the study reproducible.
  EXPECT_NE(a.find("\"hold_time\":150"), std::string::npos) << a;
}

// A spread beyond the limit names its two ends, and for each what PRD on that run's deformed
// configuration gave: the reader sees whether the runs differ by their geometry or otherwise.
TEST(Convergence, ASpreadBeyondTheLimitNamesItsEndsAndPrdOnTheirConfigurations) {
  Convergence c;
  c.case_name = "t";
  const auto add = [&](const char* name, double capacity, std::optional<PrdOnRun> p) {
    RunResult r;
    r.status = RunStatus::collapse;
    r.capacity = capacity;
    c.entries.push_back({name, std::string(name) + " what", r, p});
  };
  add("default", 1.00, std::nullopt);
  add("soft", 0.97, PrdOnRun{0.9, 1e-4, 0.975, 1.01, 1.01});
  add("stiff", 1.01, std::nullopt);
  const ConvergenceVerdict v = judge(c);
  ASSERT_FALSE(v.ok);
  ASSERT_EQ(v.problems.size(), 1u);
  EXPECT_NE(v.problems[0].find("spread by 4.00%"), std::string::npos) << v.problems[0];
  EXPECT_NE(
      v.problems[0].find("from soft (soft what): 0.9700 m (PRD on its deformed configuration: 0.9750 m, +0.52%) to stiff (stiff what): 1.0100 m"),
      std::string::npos)
      << v.problems[0];
}

// The joints' stiffness belongs to the structure: a spread that only the runs at other joints
// make, with the runs at the default's joints within the limit, is converged over the protocol
// (and still beyond the gate's limit), and so is a converged default that PRD does not meet; a
// spread among the default's joints is not converged.
TEST(Convergence, ASpreadOfTheJointsAloneIsConvergedOverTheProtocol) {
  const auto study = [](double slow, double prd = 1.0) {
    Convergence c;
    c.prd_capacity = prd;
    const auto add = [&](const std::string& name, double capacity, double kn) {
      RunResult r;
      r.status = RunStatus::collapse;
      r.capacity = capacity;
      r.settings = {{"kn", kn}};
      c.entries.push_back({name, name, r, std::nullopt});
    };
    add("default", 1.00, 1e9);
    add("slow", slow, 1e9);
    add("soft", 0.97, 1e9 / 3);
    add("stiff", 1.01, 3e9);
    return c;
  };
  const ConvergenceVerdict a = judge(study(1.005));
  EXPECT_FALSE(a.ok);
  EXPECT_TRUE(a.protocol_converged);
  EXPECT_NEAR(a.spread, 0.04, 1e-12);
  EXPECT_NEAR(a.protocol_spread, 0.005, 1e-12);
  EXPECT_STREQ(verdict_name(Study::convergence, a), "converged over the protocol");
  ASSERT_EQ(a.problems.size(), 1u);
  EXPECT_NE(a.problems[0].find("over the protocol's settings alone (the runs at the default's joint stiffness) by 0.50%"), std::string::npos)
      << a.problems[0];
  EXPECT_NE(convergence_markdown(study(1.005)).find("**Converged over the protocol**"), std::string::npos);
  EXPECT_TRUE(convergence_json(study(1.005))["protocol_converged"].get<bool>());
  EXPECT_EQ(convergence_json(study(1.005))["verdict"], "converged over the protocol");

  const ConvergenceVerdict p = judge(study(1.005, 1.05));
  EXPECT_TRUE(p.protocol_converged);
  ASSERT_EQ(p.problems.size(), 2u);
  EXPECT_NE(p.problems[1].find("differs from PRD's by -4.76%"), std::string::npos) << p.problems[1];

  const ConvergenceVerdict b = judge(study(1.03));
  EXPECT_FALSE(b.ok);
  EXPECT_FALSE(b.protocol_converged);
  EXPECT_NEAR(b.protocol_spread, 0.03, 1e-12);
  EXPECT_STREQ(verdict_name(Study::convergence, b), "NOT shown converged");
  EXPECT_NE(convergence_markdown(study(1.03)).find("**Not shown converged**"), std::string::npos);
  // With a scene whose moving support only turns, capacities and brackets are in rad and mrad.
  const Case tilt = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  Convergence turning = study(1.03);
  turning.scene = &tilt;
  const std::string md = convergence_markdown(turning);
  EXPECT_NE(md.find("capacity (rad)"), std::string::npos) << md;
  EXPECT_NE(md.find("bracket (mrad)"), std::string::npos) << md;
  EXPECT_EQ(md.find("(m)"), std::string::npos) << md;
  EXPECT_NE(convergence_markdown(study(1.03)).find("capacity (m)"), std::string::npos);

  // A stiffness study varies only the joints: no protocol spread to report.
  Convergence k = study(1.005);
  k.study = Study::stiffness;
  EXPECT_TRUE(std::isnan(judge(k).protocol_spread));
  EXPECT_TRUE(convergence_json(k)["protocol_spread"].is_null());
}

TEST(Compare, ToleranceFileIsStrict) {
  EXPECT_THROW(parse_tolerances(R"({"capacty": 0.05})", "t.json"), std::runtime_error);
  EXPECT_THROW(parse_tolerances(R"({"capacity": "5%"})", "t.json"), std::runtime_error);
  EXPECT_THROW(parse_tolerances(R"({"hinges": 1})", "t.json"), std::runtime_error);
  // A key given twice: nlohmann would keep the last, so the order of two limits decided the gate.
  EXPECT_THROW(parse_tolerances(R"({"capacity": 0.5, "capacity": 0.001})", "t.json"), std::runtime_error);
  // A file that checks nothing would pass everything.
  EXPECT_THROW(parse_tolerances(R"({})", "t.json"), std::runtime_error);
  EXPECT_THROW(parse_tolerances(R"({"comment": "mine", "hinges": false})", "t.json"), std::runtime_error);
  EXPECT_THROW(parse_tolerances(R"({"comment": 5, "thrust": 0.1})", "t.json"), std::runtime_error);
  EXPECT_NO_THROW(parse_tolerances(R"({"comment": "mine", "hinges": true})", "t.json"));
  const Tolerances t = parse_tolerances(R"({"capacity": 0.05, "capacity_abs": 0.002, "thrust": 0.1, "hinges": true})", "t.json");
  EXPECT_EQ(*t.capacity, 0.05);
  EXPECT_EQ(*t.capacity_abs, 0.002);
  EXPECT_EQ(*t.thrust, 0.1);
  EXPECT_TRUE(t.hinges);
}

}  // namespace
}  // namespace masonry
