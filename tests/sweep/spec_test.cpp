// The sweep file, the plan and the table, without running a solver: strict parsing with one-line
// errors naming the file and the field, the full-factorial plan, sweep.csv read back, and the
// disagreement boundary's definition.
#include <gtest/gtest.h>

#include <algorithm>

#include "util.hpp"

namespace masonry {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

SweepInput input(const std::string& spec) { return {spec, "s.json", test::read(test::kTiltCase), "tilt.json"}; }

// The message of the SweepError that `f` throws ("" when it throws none).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const SweepError& e) {
    return e.what();
  }
  return "";
}

// Every bad file gets one line that starts with the file's name and names the field.
void expect_refused(const std::string& spec, const std::string& field) {
  const std::string msg = error_of([&] { plan_sweep(input(spec)); });
  ASSERT_FALSE(msg.empty()) << spec;
  EXPECT_EQ(msg.rfind("s.json", 0), 0u) << msg;
  EXPECT_NE(msg.find(field), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

const std::string kHead = R"("format": "masonry-sweep/1", "case": "tilting-block.json", )";

TEST(SweepSpec, RefusesBadFilesWithOneLineNamingTheField) {
  expect_refused("{\"format\": \"masonry-sweep/1\",\n \"vary\": }", "s.json:2:");  // line and column
  expect_refused(R"({"case": "x.json", "vary": {"dem.friction_angle": [30]}})", "'format'");
  expect_refused(R"({"format": "masonry-case/1", "case": "x.json", "vary": {"dem.friction_angle": [30]}})", "'format'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "colour": 1})", "unknown field 'colour'");
  expect_refused(R"({"format": "masonry-sweep/1", "vary": {"dem.friction_angle": [30]}})", "'case'");
  expect_refused("{" + kHead + R"("vary": {}})", "'vary'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": []}})", "vary 'dem.friction_angle'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30, [1]]}})", "vary 'dem.friction_angle'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30, 30]}})", "listed twice");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 10}}})", "'to'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 10, "to": 20, "step": 0}}})", "'step'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 20, "to": 10, "step": 1}}})", "'to'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 10, "to": 20, "step": 1, "count": 3}}})", "'step' or 'count'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 10, "to": 20, "by": 1}}})", "unknown field 'by'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "methods": ["fem"]})", "'methods'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "methods": []})", "'methods'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "tolerance": -0.1})", "'tolerance'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "set": {"dem.friction_angle": 20}})", "set 'dem.friction_angle'");
  // Not an option of the case: refused before any run, naming the key and what the case said.
  expect_refused("{" + kHead + R"("vary": {"dem.frction_angle": [30, 40]}})", "vary 'dem.frction_angle'");
  expect_refused("{" + kHead + R"("vary": {"blocks": [1]}})", "vary 'blocks'");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": [30]}, "set": {"dem.hold_time": -1}})", "hold_time");
  expect_refused("{" + kHead + R"("vary": {"dem.friction_angle": {"from": 0, "to": 1, "step": 1e-9}}})", "more than");
}

TEST(SweepSpec, TheCaseIsAFileBesideTheSpecOrAStandardCase) {
  test::Scratch d("case-ref");
  test::write(d.path / "sub" / "a.json", "{" + kHead + R"("vary": {"dem.friction_angle": [30]}})");
  const std::string missing = error_of([&] { read_sweep_input((d.path / "sub" / "a.json").string()); });
  EXPECT_NE(missing.find("field 'case'"), std::string::npos) << missing;
  EXPECT_NE(missing.find((d.path / "sub" / "tilting-block.json").string()), std::string::npos) << "relative to the sweep file: " << missing;
  fs::copy_file(test::kTiltCase, d.path / "sub" / "tilting-block.json");
  EXPECT_EQ(read_sweep_input((d.path / "sub" / "a.json").string()).case_source, (d.path / "sub" / "tilting-block.json").string());
  test::write(d.path / "b.json", R"({"format": "masonry-sweep/1", "case": "no-such-case", "vary": {"dem.friction_angle": [30]}})");
  EXPECT_NE(error_of([&] { read_sweep_input((d.path / "b.json").string()); }).find("field 'case'"), std::string::npos);
  test::write(d.path / "c.json", R"({"format": "masonry-sweep/1", "case": "pointed-arch", "methods": ["prd"], "vary": {"motion.step": [0.002]}})");
  const SweepPlan p = plan_sweep(read_sweep_input((d.path / "c.json").string()));
  EXPECT_EQ(p.base.name, "pointed-arch");
  EXPECT_NE(error_of([&] { read_sweep_input((d.path / "none.json").string()); }).find("cannot open"), std::string::npos);
}

TEST(SweepSpec, RangesGiveTheValuesAPersonWouldType) {
  const SweepSpec s = parse_sweep("{" + kHead + R"("vary": {
      "dem.friction_angle": {"from": 10.25, "to": 40.25, "step": 2.5},
      "prd.contact_tolerance": {"from": 0.1, "to": 0.3, "step": 0.1},
      "motion.max_steps": {"from": 10, "to": 30, "step": 10},
      "dem.damping": {"from": 0.5, "to": 0.7, "count": 3}}})",
                                  "s.json");
  ASSERT_EQ(s.vary.size(), 4u);
  EXPECT_EQ(s.vary[0].values.size(), 13u);
  EXPECT_EQ(s.vary[0].values.front().get<double>(), 10.25);
  EXPECT_EQ(s.vary[0].values.back().get<double>(), 40.25);
  EXPECT_EQ(json(s.vary[1].values).dump(), "[0.1,0.2,0.3]");
  EXPECT_EQ(json(s.vary[2].values).dump(), "[10,20,30]");  // integers stay integers
  EXPECT_EQ(json(s.vary[3].values).dump(), "[0.5,0.6,0.7]");
  EXPECT_EQ(s.methods, (std::vector<Method>{Method::prd, Method::dem}));  // the default
  EXPECT_EQ(s.tolerance, 0.05);
}

TEST(SweepPlan, FullFactorialWithOnePrdRunPerNonDemCombination) {
  const SweepPlan p = plan_sweep(input("{" + kHead + R"("vary": {
      "motion.step": [0.02, 0.01], "dem.friction_angle": [20, 30, 40]}, "set": {"dem.hold_time": 0.5}})"));
  ASSERT_EQ(p.keys, (std::vector<std::string>{"motion.step", "dem.friction_angle"}));
  // Friction does not change a PRD run: 2 PRD runs (one per step), then 2 x 3 DEM runs, last key fastest.
  ASSERT_EQ(p.runs.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(p.runs[i].index, i);
  EXPECT_EQ(p.runs[0].method, Method::prd);
  EXPECT_EQ(p.runs[1].method, Method::prd);
  EXPECT_TRUE(p.runs[0].values[1].is_null());
  EXPECT_EQ(p.runs[1].values[0].get<double>(), 0.01);
  const double expected[6][2] = {{0.02, 20}, {0.02, 30}, {0.02, 40}, {0.01, 20}, {0.01, 30}, {0.01, 40}};
  for (int k = 0; k < 6; ++k) {
    const SweepRun& r = p.runs[2 + k];
    EXPECT_EQ(r.method, Method::dem);
    EXPECT_EQ(r.values[0].get<double>(), expected[k][0]);
    EXPECT_EQ(r.values[1].get<double>(), expected[k][1]);
    EXPECT_EQ(r.prd, k < 3 ? 0 : 1);
    // The run's case carries its values and the fixed ones.
    const Case c = case_of_run(p, r);
    EXPECT_EQ(c.motion.step, expected[k][0]);
    EXPECT_EQ(c.dem.friction_angle, expected[k][1]);
    EXPECT_EQ(c.dem.hold_time, 0.5);
  }
  EXPECT_EQ(run_label(p, p.runs[0]), "motion.step=0.02");
  EXPECT_EQ(run_label(p, p.runs[7]), "motion.step=0.01, dem.friction_angle=40");
  // Ids: distinct, the same for the same input, different when the case changes.
  std::vector<std::string> ids;
  for (const SweepRun& r : p.runs) ids.push_back(r.id);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end());
  const SweepPlan again = plan_sweep(input("{" + kHead + R"("vary": {
      "motion.step": [0.02, 0.01], "dem.friction_angle": [20, 30, 40]}, "set": {"dem.hold_time": 0.5}})"));
  EXPECT_EQ(again.hash, p.hash);
  EXPECT_EQ(again.runs[5].id, p.runs[5].id);
  const SweepPlan other = plan_sweep(input("{" + kHead + R"("vary": {
      "motion.step": [0.02, 0.01], "dem.friction_angle": [20, 30, 40]}, "set": {"dem.hold_time": 0.6}})"));
  EXPECT_NE(other.hash, p.hash);
  EXPECT_NE(other.runs[5].id, p.runs[5].id);
  // One method only.
  EXPECT_EQ(plan_sweep(input("{" + kHead + R"("methods": ["dem"], "vary": {"dem.friction_angle": [20, 30]}})")).runs.size(), 2u);
  EXPECT_EQ(plan_sweep(input("{" + kHead + R"("methods": ["prd"], "vary": {"dem.friction_angle": [20, 30]}})")).runs.size(), 1u);
}

SweepRow row(const SweepPlan& p, int i, RunStatus status, double cap, const std::string& msg = "") {
  SweepRow r;
  r.index = i;
  r.id = p.runs[i].id;
  r.method = p.runs[i].method;
  r.status = status;
  r.capacity = cap;
  r.time_s = 0.1 + i / 7.0;  // not a short decimal: the table must read back the same double
  r.message = msg;
  return r;
}

TEST(SweepTable, ReadsBackWhatItWrites) {
  const SweepPlan p = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [20, 30, 40]}})"));
  SweepTable t(p.runs.size());
  t[0] = row(p, 0, RunStatus::collapse, 0.45);
  t[0]->required_friction_angle = 26.0;
  t[0]->hinges = "block/slab:A";
  t[1] = row(p, 1, RunStatus::collapse, 0.3490658503988659);
  t[2] = row(p, 2, RunStatus::error, 0, "dem: bad, \"very\" bad");
  const std::string csv = sweep_csv(p, t);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "run,id,method,dem.friction_angle,capacity,stopped,time_s,diff_prd,required_friction_angle,hinges,message");
  const SweepTable back = read_sweep_csv(p, csv, "sweep.csv");
  ASSERT_EQ(back.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(back[i]) << i;
    EXPECT_EQ(back[i]->status, t[i]->status);
    EXPECT_EQ(back[i]->time_s, t[i]->time_s);
    EXPECT_EQ(back[i]->message, t[i]->message);
    if (t[i]->status != RunStatus::error) {
      EXPECT_EQ(back[i]->capacity, t[i]->capacity);
    }
  }
  EXPECT_EQ(back[0]->required_friction_angle, 26.0);
  EXPECT_EQ(back[0]->hinges, "block/slab:A");
  EXPECT_FALSE(back[3]);
  EXPECT_EQ(sweep_csv(p, back), csv);
  // diff_prd = (cap_dem - cap_prd) / cap_prd, in the DEM row; none for the failed run.
  const auto rows = test::csv_rows(csv);
  const size_t dc = test::column(rows[0], "diff_prd");
  EXPECT_NEAR(std::stod(rows[2][dc]), (0.3490658503988659 - 0.45) / 0.45, 1e-15);
  EXPECT_EQ(rows[3][dc], "");
  // A torn last line is an unfinished run: left out, so it is run again.
  const std::string torn = csv + "3," + p.runs[3].id + ",dem,40,0.4";
  EXPECT_FALSE(read_sweep_csv(p, torn, "sweep.csv")[3]);
  // A line with a field that does not read back is left out too.
  std::string bad = csv;
  bad.replace(bad.find(",collapse,", bad.find(p.runs[1].id)), 10, ",colapse,");
  EXPECT_FALSE(read_sweep_csv(p, bad, "sweep.csv")[1]);
  EXPECT_TRUE(read_sweep_csv(p, bad, "sweep.csv")[0]);
}

TEST(SweepTable, ARowNoRunCanGiveIsRunAgain) {
  // A row someone edited, or a program other than this one wrote: a capacity below 0, beyond
  // the end of the run's loading path (step x max_steps: 60 x 1 degree of tilt here) or not a
  // number, a negative time, a friction angle beyond 90 degrees. Its run is done again, as a
  // NaN row's always was; the others are kept.
  const SweepPlan p = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [20, 30, 40]}})"));
  const double end = p.base.motion.step * p.base.motion.max_steps;
  SweepTable t(p.runs.size());
  for (int i = 0; i < 4; ++i) t[i] = row(p, i, RunStatus::collapse, 0.3);
  const std::string good = sweep_csv(p, t);
  const auto with = [&](int i, const std::string& column, const std::string& value) {
    auto rows = test::csv_rows(good);
    rows[i + 1][test::column(rows[0], column)] = value;
    std::string csv;
    for (const auto& r : rows) {
      for (size_t k = 0; k < r.size(); ++k) csv += (k ? "," : "") + r[k];
      csv += "\n";
    }
    return read_sweep_csv(p, csv, "sweep.csv");
  };
  EXPECT_TRUE(with(1, "capacity", "0.3")[1]);
  EXPECT_TRUE(with(1, "capacity", json(end).dump())[1]);  // the path's end: a max_steps run's answer
  for (const std::string& bad : std::vector<std::string>{"-1e308", "-0.001", "1e308", json(end * 1.001).dump(), "nan", "inf", ""}) {
    const SweepTable back = with(1, "capacity", bad);
    EXPECT_FALSE(back[1]) << bad;
    EXPECT_TRUE(back[0] && back[2] && back[3]) << bad;
  }
  EXPECT_FALSE(with(2, "time_s", "-1")[2]);
  EXPECT_FALSE(with(0, "required_friction_angle", "91")[0]);
  EXPECT_TRUE(with(0, "required_friction_angle", "26")[0]);
}

TEST(SweepTable, RefusesATableOfAnotherSweep) {
  const SweepPlan p = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [20, 30]}})"));
  SweepTable t(p.runs.size());
  t[1] = row(p, 1, RunStatus::collapse, 0.3);
  const std::string csv = sweep_csv(p, t);
  // The same columns, another case setting: every id differs.
  const SweepPlan q = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [20, 30]}, "set": {"dem.damping": 0.7}})"));
  const std::string msg = error_of([&] { read_sweep_csv(q, csv, "out/sweep.csv"); });
  EXPECT_NE(msg.find("out/sweep.csv:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--restart"), std::string::npos) << msg;
  // Other columns.
  const SweepPlan r = plan_sweep(input("{" + kHead + R"("vary": {"dem.damping": [0.7]}})"));
  EXPECT_NE(error_of([&] { read_sweep_csv(r, csv, "out/sweep.csv"); }).find("--restart"), std::string::npos);
  // The tolerance is the report's: changing it keeps the table.
  const SweepPlan s = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [20, 30]}, "tolerance": 0.1})"));
  EXPECT_TRUE(read_sweep_csv(s, csv, "out/sweep.csv")[1]);
}

TEST(SweepSummary, BoundaryIsTheLargestFrictionAngleWhereTheyDiffer) {
  const SweepPlan p = plan_sweep(input("{" + kHead + R"("vary": {"dem.friction_angle": [10, 20, 30, 40]}})"));
  SweepTable t(p.runs.size());
  t[0] = row(p, 0, RunStatus::collapse, 1.0);
  // |diff| = 0.5, 0.1, 0.03, 0: beyond 5% up to 20 degrees, then within.
  const double caps[] = {0.5, 0.9, 0.97, 1.0};
  for (int k = 0; k < 4; ++k) t[1 + k] = row(p, 1 + k, RunStatus::collapse, caps[k]);
  SweepSummary s = summarize(p, t);
  EXPECT_EQ(s.x, "dem.friction_angle");
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.curves[0].runs, (std::vector<int>{1, 2, 3, 4}));
  ASSERT_TRUE(s.curves[0].boundary);
  EXPECT_EQ(*s.curves[0].boundary, 20.0);
  EXPECT_TRUE(s.curves[0].boundary_clean);
  // Agreement at 20 and disagreement at 30: the largest disagreeing angle, not a clean boundary.
  t[2] = row(p, 2, RunStatus::collapse, 1.0);
  t[3] = row(p, 3, RunStatus::collapse, 0.8);
  s = summarize(p, t);
  EXPECT_EQ(*s.curves[0].boundary, 30.0);
  EXPECT_FALSE(s.curves[0].boundary_clean);
  // Agreement everywhere: no boundary. A failed run is left out of the curve.
  for (int k = 1; k <= 3; ++k) t[k] = row(p, k, RunStatus::collapse, 1.0);
  t[4] = row(p, 4, RunStatus::error, 0, "boom");
  s = summarize(p, t);
  EXPECT_FALSE(s.curves[0].boundary);
  EXPECT_EQ(s.curves[0].runs, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(s.errors, 1);
  // The reports name no NaN, whatever is missing.
  ASSERT_TRUE(test::says_nan("capacity: NaN m") && !test::says_nan("finance"));
  t[0].reset();
  s = summarize(p, t);
  for (const std::string& text : {sweep_markdown(p, t, s, "cmd"), sweep_html(p, t, s, "cmd"), sweep_json(p, t, s).dump()}) {
    EXPECT_FALSE(test::says_nan(text)) << text;
  }
}

}  // namespace
}  // namespace masonry
