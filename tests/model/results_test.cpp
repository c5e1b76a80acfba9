// The results reader (masonry-results/1) as the gate for results an outside solver writes: the
// minimal file the README promises is enough, everything masonry writes reads back to itself
// (declared fields only, nothing lost), and each kind of nonsense is refused with one line that
// names the file and the JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "model/version.hpp"
#include "runs/run.hpp"

namespace masonry {
namespace {

using ojson = nlohmann::ordered_json;

const Case& block() {
  static const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  return c;
}

// The smallest file an outside solver may write (README, "Gate your own solver in CI").
ojson minimal() {
  return ojson::parse(R"({"format": "masonry-results/1", "method": "my-lp", "case": "tilting block", "capacity": 0.02,
                          "stopped": "collapse", "steps": [{"step": 0, "d": 0.0}, {"step": 1, "d": 0.01}, {"step": 2, "d": 0.02}]})");
}

// The reader's message for `doc`, or "" when it reads.
std::string refusal(const ojson& doc) {
  try {
    parse_results(doc.dump(), block(), "out/results.json");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ResultsReader, TheMinimalFileOfAnOutsideSolverReads) {
  const RunResult r = parse_results(minimal().dump(), block(), "out/results.json");
  EXPECT_EQ(r.method, "my-lp");
  EXPECT_EQ(r.status, RunStatus::collapse);
  EXPECT_TRUE(r.collapsed);
  EXPECT_EQ(r.capacity, 0.02);
  ASSERT_EQ(r.steps.size(), 3u);
  // What the file leaves out: stable_steps from the steps, the weight from the case, no number
  // made up for the rest.
  EXPECT_EQ(r.stable_steps, 2);
  EXPECT_DOUBLE_EQ(r.total_weight, 2000 * 9.81 * 0.2 * 0.4);
  EXPECT_TRUE(std::isnan(r.timing.total_s));
  EXPECT_TRUE(std::isnan(r.steps[1].energy));
  EXPECT_TRUE(r.joints.empty());
  EXPECT_TRUE(r.steps[1].reactions.empty());
  EXPECT_TRUE(is_equilibrium(r, r.steps[2]));
}

TEST(ResultsReader, NonsenseIsRefusedWithOneLineNamingTheFileAndThePath) {
  struct Bad {
    std::function<void(ojson&)> change;
    std::string needle;
  };
  const std::vector<Bad> bad = {
      {[](ojson& j) { j.erase("capacity"); }, "results: field 'capacity' is required"},
      {[](ojson& j) { j.erase("method"); }, "field 'method' is required"},
      {[](ojson& j) { j["method"] = ""; }, "field 'method' must name the method"},
      {[](ojson& j) { j["format"] = "masonry-results/2"; }, "field 'format' must be \"masonry-results/1\""},
      {[](ojson& j) { j["capacity"] = -5; }, "field 'capacity' = -5 rad is outside [0, the last equilibrium's d = 0.02 rad (step 2)]"},
      {[](ojson& j) { j["capacity"] = 1e300; }, "field 'capacity' = 1e+300 rad is outside"},
      {[](ojson& j) { j["capacity"] = nullptr; }, "field 'capacity' must be a number"},
      {[](ojson& j) { j["capacity"] = "0.02"; }, "field 'capacity' must be a number"},
      {[](ojson& j) { j["stopped"] = "xyz"; }, "field 'stopped' = \"xyz\" is not a run status"},
      {[](ojson& j) { std::swap(j["steps"][0]["d"], j["steps"][2]["d"]); }, "steps[1]: field 'd' = 0.01 rad is less than the step before (0.02 rad)"},
      {[](ojson& j) { j["steps"][2]["step"] = 1; }, "steps[2]: field 'step' = 1 after 1: step indices must be consecutive"},
      {[](ojson& j) { j["steps"][1].erase("d"); }, "steps[1]: field 'd' is required"},
      {[](ojson& j) { j["stable_steps"] = 1000; }, "field 'stable_steps' = 1000, but the last equilibrium at or before the capacity is step 2"},
      {[](ojson& j) { j["collapsed"] = false; }, "field 'collapsed' = false contradicts 'stopped' = \"collapse\""},
      {[](ojson& j) { j["capacty"] = 0.02; }, "results: unknown field 'capacty'"},
      // A capacity is where the structure stands: no file may claim one past its equilibria
      // (these passed the gate with any capacity: no steps, none settled, or the start missing).
      {[](ojson& j) { j["steps"] = ojson::array(); }, "field 'capacity' = 0.02 rad, but no step is an equilibrium: a run that never stands has the capacity of its start, d = 0 rad"},
      {[](ojson& j) {
         for (ojson& s : j["steps"]) s["settled"] = false;
       },
       "field 'capacity' = 0.02 rad, but no step is an equilibrium"},
      {[](ojson& j) { j["steps"][2]["settled"] = false; }, "field 'capacity' = 0.02 rad is outside [0, the last equilibrium's d = 0.01 rad (step 1)]"},
      {[](ojson& j) {
         for (ojson& s : j["steps"]) s["step"] = s["step"].get<int>() + 1;
       },
       "steps[0]: field 'step' = 1: the first record is step 0"},
      // The weight thrusts are measured in is the case's: a file's own is checked against it.
      {[](ojson& j) { j["total_weight"] = 1e6; }, "field 'total_weight' = 1e+06 N, but the case's dead loads weigh 1569.6 N"},
      {[](ojson& j) { j["total_weight"] = 0; }, "field 'total_weight' = 0 N, but the case's dead loads weigh"},
      {[](ojson& j) { j["steps"][1]["energy_J"] = 1; }, "steps[1]: unknown field 'energy_J'"},
      {[](ojson& j) { j["steps"][1]["reactions"] = ojson::parse(R"([{"support": "block", "force": [0, 1]}])"); },
       "steps[1].reactions[0]: field 'support': block \"block\" is not a support of the case"},
      {[](ojson& j) { j["steps"][1]["reactions"] = ojson::parse(R"([{"support": "moon", "force": [0, 1]}])"); },
       "steps[1].reactions[0]: field 'support': block \"moon\" is not in case \"tilting block\""},
      {[](ojson& j) { j["steps"][1]["reactions"] = ojson::parse(R"([{"support": "ground", "force": [0]}])"); },
       "steps[1].reactions[0]: field 'force' must be [x, y]"},
      {[](ojson& j) { j["steps"][1]["open_corners"] = ojson::parse(R"([{"joint": 0, "corner": "A"}])"); },
       "steps[1].open_corners[0]: field 'joint' = 0 is not one of the file's 0 joints"},
      {[](ojson& j) { j["steps"][1]["poses"] = ojson::parse(R"([[0, 0, 0]])"); }, "steps[1]: field 'poses' has 1 poses, one per block"},
      {[](ojson& j) { j["steps"][1]["cycles"] = 10; }, "steps[1]: field 'cycles' is one of the DEM hold's fields"},
      {[](ojson& j) { j["blocks"] = ojson::parse(R"([{"id": "block"}, {"id": "ground"}])"); }, "blocks[0]: field 'id': not the case's block"},
      {[](ojson& j) { j["joints"] = ojson::parse(R"([{"blocks": ["ground", "ground"], "a": [0, 0], "b": [1, 0]}])"); },
       "joints[0]: field 'blocks' names one block twice"},
  };
  EXPECT_EQ(refusal(minimal()), "");
  for (const Bad& b : bad) {
    ojson doc = minimal();
    b.change(doc);
    const std::string msg = refusal(doc);
    EXPECT_EQ(msg.rfind("out/results.json: ", 0), 0u) << msg;
    EXPECT_NE(msg.find(b.needle), std::string::npos) << msg << "\n  expected: " << b.needle;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  EXPECT_NE(refusal(ojson::parse("[1]")).find("must be a JSON object"), std::string::npos);
  try {
    parse_results("{\"format\": ", block(), "x.json");
    ADD_FAILURE() << "read malformed JSON";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.json:1:12: malformed JSON"), std::string::npos) << e.what();
  }
  // A key given twice is refused (nlohmann would keep the last: a capacity of 0 to the gate).
  try {
    parse_results(R"({"format": "masonry-results/1", "capacity": 0.5, "capacity": 0})", block(), "x.json");
    ADD_FAILURE() << "read a key given twice";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.json: field 'capacity' given twice"), std::string::npos) << e.what();
  }
}

TEST(ResultsReader, NoStepsAndAnErrorRead) {
  // A solver that gave up before any step: capacity 0 and its reason.
  const ojson doc = ojson::parse(R"({"format": "masonry-results/1", "method": "m", "case": "c", "capacity": 0, "stopped": "error",
                                     "message": "no convergence", "steps": []})");
  const RunResult r = parse_results(doc.dump(), block(), "r.json");
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_EQ(r.message, "no convergence");
  EXPECT_EQ(r.stable_steps, 0);
}

// Everything a method writes is a declared field: writing what was read gives the same file.
void expect_round_trip(const RunResult& r, const Case& c) {
  const std::string once = to_json(r, c).dump(1);
  const RunResult back = parse_results(once, c, "results.json");
  EXPECT_EQ(to_json(back, c).dump(1), once);
}

TEST(ResultsReader, WhatPrdAndTheDemWriteReadsBackToTheSameFile) {
  const Case& c = block();
  const RunResult prd = run_case(c, Method::prd);
  ASSERT_EQ(prd.status, RunStatus::collapse) << prd.message;
  ASSERT_TRUE(prd.events && prd.collapse);
  ASSERT_TRUE(prd.steps.at(1).lp);
  expect_round_trip(prd, c);
  const RunResult dem = run_case(c, Method::dem);
  ASSERT_EQ(dem.status, RunStatus::collapse) << dem.message;
  ASSERT_TRUE(dem.collapse_bracket && dem.wall_s);
  ASSERT_TRUE(dem.steps.at(1).hold && dem.steps.at(1).settled);
  EXPECT_FALSE(is_equilibrium(dem, dem.steps.back()));  // the failed state closing the run
  expect_round_trip(dem, c);
  // The follow stage's fields (a creep that settled when held on, a followed trial).
  RunResult followed = dem;
  followed.settled_creeps.push_back({0.01, 2, 31.5});
  followed.settled_snaps.push_back({0.015, 0.0149, 0.05, 0.13});  // the landing stage's
  followed.collapse_bracket->trials.push_back({0.02, "creep", 1000, false, true});
  expect_round_trip(followed, c);
  const auto written = to_json(followed, c);
  EXPECT_EQ(written["settled_creeps"].size(), 1u);
  EXPECT_EQ(written["collapse_bracket"]["trials"].back().value("followed", false), true);
  EXPECT_EQ(parse_results(written.dump(), c, "results.json").settled_creeps.at(0).holds, 2);
  EXPECT_EQ(written["settled_snaps"].size(), 1u);
  const RunResult back = parse_results(written.dump(), c, "results.json");
  ASSERT_EQ(back.settled_snaps.size(), 1u);
  EXPECT_EQ(back.settled_snaps[0].d, 0.015);
  EXPECT_EQ(back.settled_snaps[0].from, 0.0149);
  EXPECT_EQ(back.settled_snaps[0].drift, 0.05);
  EXPECT_EQ(back.settled_snaps[0].time, 0.13);
  // PRD with the sliding check and a corner held closed: their fields too.
  Case checked = with_option(with_option(c, "prd.sliding_check", true), "prd.hold_closed", nlohmann::json::array({"ground/block:B"}));
  const RunResult held = run_case(checked, Method::prd);
  ASSERT_TRUE(held.sliding && held.steps.at(1).sliding);
  ASSERT_FALSE(held.steps.at(1).held_corners.empty());
  expect_round_trip(held, checked);
}

TEST(ResultsReader, EveryFileRecordsTheVersionThatMadeIt) {
  const RunResult r = parse_results(minimal().dump(), block(), "r.json");
  EXPECT_EQ(to_json(r, block())["version"], version_text());
  ojson theirs = minimal();
  theirs["version"] = "my-lp 2.1";
  EXPECT_EQ(parse_results(theirs.dump(), block(), "r.json").version, "my-lp 2.1");
  EXPECT_EQ(std::string(version_number()), MASONRY_VERSION);
  EXPECT_EQ(version_text().rfind(std::string("masonry ") + MASONRY_VERSION, 0), 0u) << version_text();
}

}  // namespace
}  // namespace masonry
