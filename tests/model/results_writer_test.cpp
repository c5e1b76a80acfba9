// The results writers: steps.csv parses with one column count whatever the ids hold, and a run
// still going is written as its records stand. (The reader: results_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "model/results.hpp"

namespace masonry {
namespace {

// RFC 4180's grammar, read independently of the writer: records of fields separated by commas,
// a field in double quotes may hold commas, line breaks and doubled quotes.
std::vector<std::vector<std::string>> rfc4180(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row(1);
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"')
        row.back() += '"', ++i;
      else if (ch == '"')
        quoted = false;
      else
        row.back() += ch;
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      row.emplace_back();
    } else if (ch == '\n') {
      rows.push_back(row);
      row.assign(1, "");
    } else {
      row.back() += ch;
    }
  }
  EXPECT_FALSE(quoted) << "a quote left open";
  return rows;
}

TEST(StepsCsv, OneColumnCountWhateverTheIds) {
  // Support ids with a comma, a quote, a line break and a carriage return (all valid case ids).
  const std::vector<std::string> ids = {"left,pier", "the \"right\" pier", "new\nline", "cr\rhere", "plain"};
  Case c;
  c.blocks.push_back(Block{});  // a free block between the supports: not a column
  c.blocks.back().id = "free";
  for (const std::string& id : ids) {
    Block b;
    b.id = id;
    b.support = true;
    c.blocks.push_back(b);
  }
  RunResult r;
  r.method = "prd";
  for (int k = 0; k < 3; ++k) {
    StepRecord s;
    s.index = k;
    s.d = 0.001 * k;
    for (size_t i = 0; i < ids.size(); ++i) s.reactions.push_back({ids[i], Vec2(1.0 + k, -2.0 * static_cast<double>(i)), 0});
    r.steps.push_back(s);
  }
  const auto rows = rfc4180(steps_csv(r, c));
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), 5 + 2 * ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(rows[0][5 + 2 * i], "Fx_" + ids[i] + "_N");
    EXPECT_EQ(rows[0][6 + 2 * i], "Fy_" + ids[i] + "_N");
    EXPECT_EQ(std::stod(rows[2][6 + 2 * i]), -2.0 * static_cast<double>(i));
  }
  EXPECT_EQ(rows[0][1], "d_m");
  // d's column is named in d's unit: rad on a slab that only turns.
  const Case tilt = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  EXPECT_EQ(rfc4180(steps_csv(RunResult{}, tilt))[0][1], "d_rad");
  // Reactions listed in another order, or not at all, still go under their own support's columns.
  std::reverse(r.steps[1].reactions.begin(), r.steps[1].reactions.end());
  r.steps[2].reactions.clear();
  const auto moved = rfc4180(steps_csv(r, c));
  ASSERT_EQ(moved.size(), 4u);
  for (const auto& row : moved) EXPECT_EQ(row.size(), 5 + 2 * ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(std::stod(moved[2][6 + 2 * i]), -2.0 * static_cast<double>(i));
    EXPECT_EQ(moved[3][5 + 2 * i], "");
  }
  // A run without a step (a structure that does not stand as drawn) has the same header.
  r.steps.clear();
  const auto empty = rfc4180(steps_csv(r, c));
  ASSERT_EQ(empty.size(), 1u);
  EXPECT_EQ(empty[0], rows[0]);
}

StepRecord dem_record(int index, double d, bool settled) {
  StepRecord s;
  s.index = index;
  s.d = d;
  s.settled = settled;
  return s;
}

// A solver hands its results out as it records a step and may count the step after: the file
// holds the capacity and stable steps of its records, never the lagging count.
TEST(ResultsJson, ARunStillGoingIsWrittenAsItsRecordsStand) {
  Case c;
  RunResult r;
  r.method = "dem";
  r.status = RunStatus::running;
  r.steps = {dem_record(0, 0, true), dem_record(1, 0.028, true), dem_record(2, 0.029, true)};
  r.capacity = 0.028;  // the DEM's count before it takes in the record at 0.029
  r.stable_steps = 1;
  {
    const auto j = to_json(r, c);
    EXPECT_EQ(j["capacity"].get<double>(), 0.029);
    EXPECT_EQ(j["stable_steps"].get<int>(), 2);
  }
  // A failed hold beyond it is no equilibrium.
  r.steps.push_back(dem_record(3, 0.030, false));
  EXPECT_EQ(to_json(r, c)["capacity"].get<double>(), 0.029);
  // A finished run is written as the solver concluded.
  r.status = RunStatus::collapse;
  EXPECT_EQ(to_json(r, c)["capacity"].get<double>(), 0.028);
}

}  // namespace
}  // namespace masonry
