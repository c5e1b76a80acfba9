// The trade-off measurement: plan parsing (one-line errors naming the file and field), the
// Pareto front on hand-made points (closed forms), and PRD end to end on a block toppling off a
// tilting support, where the capacity for each step is known in closed form.
#include "tradeoff/tradeoff.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "common.hpp"
#include "compare/compare.hpp"
#include "prd/prd.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;

using test::read;
using test::run;
using test::write;

// The error message of parse_plan for `text`, or "" when it parses.
std::string plan_error(const std::string& text) {
  try {
    parse_plan(text, "plan.json");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A 0.5 m x 1 m block (1000 kg) with a 500 N load on its top centre, on a ground slab that turns
// counter-clockwise about its far left corner by d rad (1 rad per m of d). The block tips about
// its left bottom corner, the origin, when the centre of gravity of block and load passes over
// it: tan(theta*) = x_g / y_g, x_g = 0.25 m, y_g = (9810 * 0.5 + 500 * 1.0) / 10310 m.
const char* kTiltCase = R"({
  "format": "masonry-case/1", "name": "tilting block", "gravity": 9.81,
  "blocks": [
    {"id": "ground", "vertices": [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.0], [-2.0, 0.0]], "depth": 1.0, "support": true},
    {"id": "block", "vertices": [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]], "depth": 1.0, "density": 2000.0}
  ],
  "loads": [{"block": "block", "force": [0.0, -500.0], "point": [0.25, 1.0]}],
  "motion": {"step": 0.004, "max_steps": 200,
             "supports": [{"block": "ground", "translation": [0.0, 0.0], "rotation": 1.0, "about": [-2.0, -0.5]}]},
  "prd": {"contact_tolerance": 1e-5}
})";

double topple_angle() {
  const double w_block = 2000.0 * 0.5 * 1.0 * 9.81, p = 500.0;
  const double yg = (w_block * 0.5 + p * 1.0) / (w_block + p);
  return std::atan(0.25 / yg);
}

// The last grid point d = k s below the toppling angle: the PRD capacity with step s.
double grid_capacity(double s) { return std::floor(topple_angle() / s) * s; }

// ---- Plan ------------------------------------------------------------------------------------

TEST(TradeoffPlan, BuiltInPlansParseAndHaveAReferencePerMethod) {
  for (bool quick : {false, true}) {
    const Plan p = default_plan(quick);
    ASSERT_EQ(p.methods.count(Method::prd), 1u);
    ASSERT_EQ(p.methods.count(Method::dem), 1u);
    EXPECT_FALSE(p.methods.at(Method::prd).reference.empty());
    EXPECT_FALSE(p.methods.at(Method::dem).vary.empty());
    // Round trip through the file format.
    const Plan q = parse_plan(plan_to_json(p).dump(), "round trip");
    EXPECT_EQ(plan_to_json(q).dump(), plan_to_json(p).dump());
  }
}

TEST(TradeoffPlan, BadPlansGetOneLineNamingFileAndField) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"not json", "not valid JSON"},
      {"[1, 2]", "must be a JSON object"},
      {R"({"fem": {}})", "fem: unknown field"},
      {R"({"format": "other/1", "prd": {}})", "format: must be"},
      {R"({"prd": {"colour": 1}})", "prd.colour: unknown field"},
      {R"({"prd": {"repeat": 0}})", "prd.repeat: must be a whole number"},
      {R"({"prd": {"repeat": 1.5}})", "prd.repeat: must be a whole number"},
      {R"({"prd": {"baseline": "yes"}})", "prd.baseline: must be true or false"},
      {R"({"prd": {"vary": {"motion.step": []}}})", "prd.vary.motion.step: must be a non-empty list"},
      {R"({"prd": {"vary": {"motion.step": 0.001}}})", "prd.vary.motion.step: must be a non-empty list"},
      {R"({"prd": {"vary": {"dem.damping": [0.5]}}})", "'dem.damping' is not a prd setting"},
      {R"({"dem": {"vary": {"prd.contact_tolerance": [1e-4]}}})", "'prd.contact_tolerance' is not a dem setting"},
      {R"({"prd": {"vary": {"motion.step": [0.001, "x-2"]}}})", "prd.vary.motion.step[1]: the factor of 'x-2' must be positive"},
      {R"({"prd": {"vary": {"motion.step": ["xfoo"]}}})", "prd.vary.motion.step[0]: 'xfoo' is not a relative value"},
      {R"({"prd": {"vary": {"motion.step": [[1]]}}})", "prd.vary.motion.step[0]: a value must be"},
      {R"({"prd": {"reference": {"motion.step": null}}})", "prd.reference.motion.step: a value must be"},
      {R"({"prd": {"combined": [{"label": "", "options": {"motion.step": 0.01}}]}})", "prd.combined[0].label: must be a non-empty string"},
      {R"({"prd": {"combined": [{"label": "a"}]}})", "prd.combined[0].options: missing"},
      {R"({"prd": {"combined": [{"label": "a", "options": {}, "x": 1}]}})", "prd.combined[0].x: unknown field"},
      {R"({"comment": "nothing"})", "names no method"},
  };
  for (const auto& [text, expected] : bad) {
    const std::string e = plan_error(text);
    EXPECT_EQ(e.rfind("plan.json: ", 0), 0u) << text << " -> " << e;
    EXPECT_NE(e.find(expected), std::string::npos) << text << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_EQ(plan_error(R"({"format": "masonry-tradeoff-plan/1", "comment": "ok", "prd": {"reference": {}}})"), "");
}

TEST(TradeoffPlan, ExpansionResolvesRelativeValuesAndKeepsThePathLength) {
  const Case c = parse_case(kTiltCase, "tilt.json");
  const Plan p = parse_plan(R"({"prd": {"reference": {"motion.step": "x0.5", "prd.contact_tolerance": "x0.1"},
                                        "vary": {"motion.step": ["x1", 0.004, "x0.5", "x2"], "prd.contact_tolerance": [1e-4]},
                                        "combined": [{"label": "same as x2", "options": {"motion.step": 0.008}}]}})",
                            "plan.json");
  const std::vector<PlannedRun> runs = expand_plan(c, p, {Method::prd}, "plan.json");
  // reference, baseline, step x0.5 (not the reference: the tolerance differs), step x2,
  // tolerance 1e-4; x1 and 0.004 are the baseline, the combined one repeats step x2.
  ASSERT_EQ(runs.size(), 5u);
  EXPECT_TRUE(runs[0].reference);
  EXPECT_DOUBLE_EQ(runs[0].c.motion.step, 0.002);
  EXPECT_DOUBLE_EQ(runs[0].c.prd.contact_tolerance, 1e-6);  // 1e-5 x 0.1, printed as 1e-06
  EXPECT_EQ(runs[0].c.motion.max_steps, 400);               // 0.8 m of travel kept
  EXPECT_TRUE(runs[1].baseline);
  EXPECT_EQ(runs[1].c.motion.max_steps, 200);
  EXPECT_EQ(runs[2].setting.label, "motion.step=0.002");
  EXPECT_EQ(runs[3].setting.label, "motion.step=0.008");
  EXPECT_EQ(runs[3].c.motion.max_steps, 100);
  EXPECT_EQ(runs[3].id, "prd-motion.step=0.008");
  EXPECT_DOUBLE_EQ(runs[4].c.prd.contact_tolerance, 1e-4);
  EXPECT_DOUBLE_EQ(runs[4].c.motion.step, 0.004);
}

TEST(TradeoffPlan, ValuesTheCaseRefusesFailBeforeAnyRun) {
  const Case c = parse_case(kTiltCase, "tilt.json");
  const auto error = [&](const std::string& plan) {
    try {
      expand_plan(c, parse_plan(plan, "plan.json"), {Method::prd, Method::dem}, "plan.json");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = error(R"({"prd": {"vary": {"motion.step": [-0.001]}}, "dem": {}})");
  EXPECT_EQ(e.rfind("plan.json: prd.vary.motion.step[0]: tilt.json [motion.step=-0.001]", 0), 0u) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
  e = error(R"({"prd": {}, "dem": {"vary": {"dem.kn": ["x2"]}}})");
  EXPECT_NE(e.find("dem.vary.dem.kn: the case has no number for 'dem.kn'"), std::string::npos) << e;
  e = error(R"({"prd": {}})");
  EXPECT_NE(e.find("dem: the plan has no settings for this method"), std::string::npos) << e;
}

// ---- Pareto front ----------------------------------------------------------------------------

TEST(TradeoffPareto, HandMadePoints) {
  const double nan = std::nan("");
  const std::vector<ParetoPoint> pts = {{1, 0.5},
                                        {2, 0.2},
                                        {3, 0.3} /* dominated by 1 */,
                                        {4, 0.0},
                                        {0.5, 1.0},
                                        {2, 0.2} /* twin of 1 */,
                                        {nan, 0.1},
                                        {5, 0.0} /* dominated by 3 */,
                                        {0.5, 2.0} /* dominated by 4 */,
                                        {0.1, nan}};
  const std::vector<size_t> front = pareto_front(pts);
  EXPECT_EQ(front, (std::vector<size_t>{4, 0, 1, 3}));
  // Steps along the front: 4 -> 0 buys 0.5 for 0.5 s, 0 -> 1 buys 0.3 for 1 s, 1 -> 3 buys 0.2
  // for 2 s; ranked by error reduction per second.
  const std::vector<Buy> buys = best_buys(pts, front);
  ASSERT_EQ(buys.size(), 3u);
  EXPECT_EQ(buys[0].from, 4u);
  EXPECT_EQ(buys[0].to, 0u);
  EXPECT_DOUBLE_EQ(buys[0].rate, 1.0);
  EXPECT_EQ(buys[1].from, 0u);
  EXPECT_DOUBLE_EQ(buys[1].rate, 0.3);
  EXPECT_EQ(buys[2].to, 3u);
  EXPECT_DOUBLE_EQ(buys[2].gain, 0.2);
  EXPECT_DOUBLE_EQ(buys[2].cost_s, 2.0);
  EXPECT_TRUE(pareto_front({}).empty());
}

TEST(TradeoffPareto, HyperbolaIsItsOwnFront) {
  // e = 1 / t for t = 1..10 is a front; the same points raised by 0.01 are all dominated. The
  // step from t to t + 1 buys 1 / (t (t + 1)) per second, largest first.
  std::vector<ParetoPoint> pts;
  for (int t = 10; t >= 1; --t) pts.push_back({double(t), 1.0 / t + 0.01});
  for (int t = 1; t <= 10; ++t) pts.push_back({double(t), 1.0 / t});
  const std::vector<size_t> front = pareto_front(pts);
  ASSERT_EQ(front.size(), 10u);
  for (size_t k = 0; k < 10; ++k) EXPECT_EQ(front[k], 10 + k);
  const std::vector<Buy> buys = best_buys(pts, front);
  ASSERT_EQ(buys.size(), 9u);
  for (size_t k = 0; k < 9; ++k) {
    const double t = double(k + 1);
    EXPECT_NEAR(buys[k].rate, 1.0 / (t * (t + 1)), 1e-15);
  }
}

// ---- Thrust errors and the summary ---------------------------------------------------------

// A settled state that is one admissible state of a statically indeterminate structure, and the
// thrust falling from it to the minimum thrust over the first step (the DEM arch: 1311 N to
// 1086 N): a run recorded every 2 mm against one recorded every 1 mm, both with that jump and
// otherwise alike, differ by nothing where both are determined. Read half way through the first
// 2 mm step it did not resolve, the coarse run differs by half the jump.
TEST(TradeoffErrors, ThrustsAreComparedWhereBothRunsAreRecorded) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/pointed-arch.json");
  RunResult fine = prd_run(c, PrdSettings::from_case(c));
  ASSERT_GT(fine.steps.size(), 10u);
  const double jump = 0.1 * fine.total_weight;
  fine.steps[0].reactions[0].force.x() += jump;
  RunResult coarse = fine;
  coarse.steps.clear();
  for (const StepRecord& s : fine.steps)
    if (s.index % 2 == 0) coarse.steps.push_back(s);
  coarse.capacity = coarse.steps.back().d;
  const Comparison every = compare_runs(c, fine, coarse);
  EXPECT_NEAR(every.thrust_max_diff, 0.05, 1e-5);  // half the jump, at d = 1 mm (and the curve's own bend)
  EXPECT_NEAR(every.thrust_max_d, 0.001, 1e-12);
  CompareOptions o;
  o.thrust_grid = ThrustGrid::coarser_run;
  const Comparison coarser = compare_runs(c, fine, coarse, o);
  EXPECT_EQ(coarser.thrust_max_diff, 0.0);
  EXPECT_EQ(coarser.d.size(),
            size_t(std::count_if(coarse.steps.begin(), coarse.steps.end(), [&](const StepRecord& s) { return s.d <= coarser.d_max; })));
  EXPECT_EQ(compare_runs(c, coarse, fine, o).thrust_max_diff, 0.0);  // whichever comes first
}

// The summary says what a step along the front buys in the reader's terms: the error before and
// after and the extra time, not a rate in "points per second".
TEST(TradeoffSummary, AStepAlongTheFrontReadsAsTheErrorFallingForExtraTime) {
  Tradeoff t;
  t.case_name = "arch";
  t.methods = {Method::dem};
  const auto row = [](const std::string& label, bool reference, double time, double cap_err) {
    Row r;
    r.method = Method::dem;
    r.label = label;
    r.parameter = reference ? "reference" : "motion.step";
    r.reference = reference;
    r.status = RunStatus::collapse;
    r.time_s = time;
    r.capacity = 0.276;
    r.capacity_err = cap_err;
    r.thrust_max_err = r.thrust_rms_err = 0.0;
    return r;
  };
  t.rows = {row("reference", true, 27.5, 0.0), row("fast", false, 0.0038, 0.0072), row("slower", false, 0.0076, 0.0)};
  std::string all;
  for (const std::string& s : summary_lines(t)) all += s + "\n";
  EXPECT_NE(all.find("from fast to slower the error falls from 0.72% to 0% for 3.8 ms more"), std::string::npos) << all;
  EXPECT_EQ(all.find("points of"), std::string::npos) << all;
  EXPECT_EQ(all.find("per s)"), std::string::npos) << all;
  EXPECT_EQ(all.find("->"), std::string::npos) << all;
  EXPECT_NE(all.find("the fastest setting within 1% in capacity and 0.0100 W in thrust of the reference is fast (0.0038 s"), std::string::npos)
      << all;
}

// ---- End to end ------------------------------------------------------------------------------

const char* kTiltPlan = R"({
  "prd": {"repeat": 2, "reference": {},
          "vary": {"motion.step": ["x2", "x4", 0.012], "prd.contact_tolerance": ["x10"]}}
})";

TEST(TradeoffRun, PrdCapacitiesOnTheGridBelowTheToppleAngle) {
  const Case c = parse_case(kTiltCase, "tilt.json");
  const test::Scratch scratch("tradeoff-run");
  const fs::path d = scratch.path;
  const std::vector<PlannedRun> plan = expand_plan(c, parse_plan(kTiltPlan, "plan.json"), {Method::prd}, "plan.json");
  RunOptions o;
  o.runs_dir = (d / "runs").string();
  int calls = 0;
  const std::vector<Row> rows = run_plan(c, plan, o, [&](const Row&) { ++calls; });
  // The reference is the case's own settings, so the baseline is not run twice.
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(calls, 5);
  const double s_ref = 0.004;
  const Row& ref = rows[0];
  ASSERT_TRUE(ref.reference);
  ASSERT_EQ(ref.status, RunStatus::collapse) << ref.message;
  EXPECT_NEAR(ref.capacity, grid_capacity(s_ref), 1e-9);
  EXPECT_LE(ref.capacity, topple_angle());
  EXPECT_GT(ref.capacity, topple_angle() - s_ref);
  // The reference against itself.
  EXPECT_EQ(ref.capacity_err, 0.0);
  EXPECT_EQ(ref.thrust_max_err, 0.0);
  EXPECT_EQ(ref.thrust_rms_err, 0.0);
  for (const Row& r : rows) {
    SCOPED_TRACE(r.label);
    ASSERT_EQ(r.status, RunStatus::collapse) << r.message;
    EXPECT_EQ(r.repeats, 2);
    EXPECT_LE(r.time_min_s, r.time_s);
    EXPECT_LE(r.time_s, r.time_max_s);
    EXPECT_GT(r.lp_solves, 0);
    EXPECT_TRUE(fs::exists(fs::path(o.runs_dir) / r.id / "results.json"));
    // One block, statically determinate: the ground carries the weight and the load, vertical,
    // at every tilt, so the thrust curves of every setting coincide.
    EXPECT_LT(r.thrust_max_err, 1e-9);
  }
  // A step k times the reference's finds the capacity on its own grid, within one of its steps
  // below the reference's: the error is bounded by step / capacity.
  for (size_t i = 1; i <= 3; ++i) {
    const Row& r = rows[i];
    const double s = r.options.front().value.get<double>();
    SCOPED_TRACE(r.label);
    EXPECT_NEAR(r.capacity, grid_capacity(s), 1e-9);
    EXPECT_LE(std::abs(r.capacity - ref.capacity), s + 1e-12);
    EXPECT_LE(std::abs(r.capacity_err), s / ref.capacity + 1e-12);
    EXPECT_NEAR(r.capacity_err, (grid_capacity(s) - grid_capacity(s_ref)) / grid_capacity(s_ref), 1e-9);
  }
  EXPECT_LT(rows[2].capacity_err, 0.0);  // 16 mm steps stop at 0.432, below the reference's 0.444
  // The block stays closed on the ground until it topples: the contact tolerance cannot move the
  // capacity.
  EXPECT_EQ(rows[4].parameter, "prd.contact_tolerance");
  EXPECT_EQ(rows[4].capacity_err, 0.0);
}

TEST(TradeoffRun, FailedRunsAreRecordedAndTheRestGoOn) {
  // A case whose support does not move passes the case check, but no capacity run takes it (it
  // has no loading path): each run is refused before its first cycle.
  std::string still = kTiltCase;
  still.replace(still.find("\"rotation\": 1.0"), 15, "\"rotation\": 0.0");
  const Case c = parse_case(still, "tilt.json");
  const Plan p = parse_plan(R"({"dem": {"reference": {"dem.timestep_factor": 0.5}, "baseline": false,
                                         "vary": {"dem.timestep_factor": [0.4]}}})",
                            "plan.json");
  const std::vector<Row> rows = run_plan(c, expand_plan(c, p, {Method::dem}, "plan.json"), {});
  ASSERT_EQ(rows.size(), 2u);
  Tradeoff t;
  t.case_name = c.name;
  t.methods = {Method::dem};
  t.rows = rows;
  for (const Row& r : rows) {
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_FALSE(r.message.empty());
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(std::isnan(r.capacity_err));
  }
  const test::Scratch scratch("tradeoff-failed");
  const fs::path d = scratch.path;
  write_tradeoff(d.string(), t);
  const std::string md = read(d / "report.md");
  EXPECT_NE(md.find("2 settings did not finish"), std::string::npos) << md;
  EXPECT_EQ(md.find("nan"), std::string::npos);
  EXPECT_NE(read(d / "tradeoff.csv").find(rows[0].message.substr(0, 20)), std::string::npos);
}

// No NaN or infinity in any output: missing numbers are "n/a" (text) or null (JSON).
// Words (runs of letters) are compared whole, case-insensitively, so "infinite" or "finance"
// would pass and "NaN", "-nan", "inf" would not.
void expect_no_nan(const fs::path& p) {
  const std::string s = read(p);
  EXPECT_FALSE(s.empty()) << p;
  std::string word;
  for (size_t i = 0; i <= s.size(); ++i) {
    const char ch = i < s.size() ? s[i] : ' ';
    if (std::isalpha(static_cast<unsigned char>(ch))) {
      word += char(std::tolower(static_cast<unsigned char>(ch)));
      continue;
    }
    EXPECT_TRUE(word != "nan" && word != "inf" && word != "infinity") << p << ": '" << word << "' before offset " << i;
    word.clear();
  }
}

TEST(TradeoffCommand, WritesEveryFileWithoutNaN) {
  const test::Scratch scratch("tradeoff-cli");
  const fs::path d = scratch.path;
  write(d / "tilt.json", kTiltCase);
  write(d / "plan.json", kTiltPlan);
  const std::string out = (d / "out").string();
  const std::string cmd = std::string(MASONRY_EXE) + " tradeoff " + (d / "tilt.json").string() + " --out " + out + " --methods prd --plan " +
                          (d / "plan.json").string() + " --repeat 1 --quiet";
  ASSERT_EQ(run(cmd + " 2>/dev/null"), 0) << cmd;
  for (const char* f : {"tradeoff.csv", "tradeoff.json", "report.md", "report.html", "figures/pareto-prd.svg"}) {
    SCOPED_TRACE(f);
    ASSERT_TRUE(fs::exists(fs::path(out) / f));
    expect_no_nan(fs::path(out) / f);
  }
  // One CSV line per setting after the header.
  const std::string csv = read(fs::path(out) / "tradeoff.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);
  const auto j = nlohmann::json::parse(read(fs::path(out) / "tradeoff.json"));
  ASSERT_EQ(j["rows"].size(), 5u);
  EXPECT_EQ(j["rows"][0]["role"], "reference");
  EXPECT_EQ(j["rows"][0]["capacity_err"], 0.0);
  // The front ends at the smallest error, which is zero: the reference's, and that of every
  // setting that finds the same grid point (12 mm steps stop at 0.444 as well).
  const std::string last = j["pareto"]["prd"]["capacity"]["front"].back();
  for (const auto& row : j["rows"]) {
    if (row["setting"] == last) {
      EXPECT_EQ(row["capacity_err"], 0.0) << last;
    }
  }
  // --resume reads every finished run back instead of running it again.
  const std::string resumed = (d / "resumed.txt").string();
  ASSERT_EQ(run(std::string(MASONRY_EXE) + " tradeoff " + (d / "tilt.json").string() + " --out " + out + " --methods prd --plan " +
                (d / "plan.json").string() + " --repeat 1 --resume 2>" + resumed),
            0);
  const std::string log = read(resumed);
  size_t reused = 0;
  for (size_t at = log.find("reused from"); at != std::string::npos; at = log.find("reused from", at + 1)) ++reused;
  EXPECT_EQ(reused, 5u) << log;
}

// A finished run kept compressed (results.json.xz, as the runs under reports/ are) serves as a
// method's reference.
TEST(TradeoffCommand, ACompressedRunServesAsTheReference) {
  if (run("command -v xz >/dev/null 2>&1") != 0) GTEST_SKIP() << "xz is not installed (scripts/install-deps.sh installs it)";
  const test::Scratch scratch("tradeoff-xz");
  const fs::path d = scratch.path;
  write(d / "tilt.json", kTiltCase);
  write(d / "plan.json", kTiltPlan);
  const std::string ref = (d / "ref").string();
  ASSERT_EQ(run(std::string(MASONRY_EXE) + " prd " + (d / "tilt.json").string() + " --out " + ref + " 2>/dev/null"), 0);
  ASSERT_EQ(run("xz -1 " + ref + "/results.json"), 0);
  const std::string out = (d / "out").string();
  ASSERT_EQ(run(std::string(MASONRY_EXE) + " tradeoff " + (d / "tilt.json").string() + " --out " + out + " --methods prd --plan " +
                (d / "plan.json").string() + " --repeat 1 --reference-prd " + ref + " --quiet 2>/dev/null"),
            0);
  const auto j = nlohmann::json::parse(read(fs::path(out) / "tradeoff.json"));
  EXPECT_EQ(j["rows"][0]["role"], "reference");
  EXPECT_EQ(j["rows"][0]["source"], ref);
  EXPECT_NEAR(j["rows"][0]["capacity"].get<double>(), grid_capacity(0.004), 1e-9);
}

TEST(TradeoffCommand, BadOptionsGetOneLine) {
  const test::Scratch scratch("tradeoff-bad");
  const fs::path d = scratch.path;
  write(d / "tilt.json", kTiltCase);
  const std::string base = std::string(MASONRY_EXE) + " tradeoff " + (d / "tilt.json").string() + " --out " + (d / "out").string();
  const std::vector<std::pair<std::string, std::string>> bad = {
      {" --methods prd --vary prd:dem.damping=0.5", "no selected method reads 'dem.damping'"},
      {" --methods prd --vary motion.step=x-1", "the factor of 'x-1' must be positive"},
      {" --methods fem", "unknown method 'fem'"},
      {" --methods prd --set motion.step=-1", "tilt.json [motion.step=-1]"},
      {" --methods prd --reference-prd " + (d / "nowhere").string(), "nowhere/results.json: no such file"},
  };
  for (const auto& [args, expected] : bad) {
    const fs::path err = d / "err.txt";
    EXPECT_EQ(run(base + args + " 2>" + err.string()), 2) << args;
    const std::string e = read(err);
    EXPECT_NE(e.find(expected), std::string::npos) << args << " -> " << e;
    EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
  }
}

}  // namespace
}  // namespace masonry
