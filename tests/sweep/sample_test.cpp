// Sweeps over a generator's parameters and sampled sweeps, without running a solver: the Latin
// hypercube's strata, streams and seeds; the sampled plan (base point, one-at-a-time lines,
// samples, `only`); a run's case is the case `masonry cases` writes with the same parameters; and
// one-line refusals naming the file and the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

#include "cases/generators.hpp"
#include "cases/parameters.hpp"
#include "util.hpp"

namespace masonry {
namespace {

using nlohmann::json;

// `body`: the sweep file after its format field, closing brace included.
SweepPlan plan_of(const std::string& body) { return plan_sweep(SweepInput{"{\"format\": \"masonry-sweep/1\", " + body, "s.json", "", ""}); }

std::string error_of(const std::string& body) {
  try {
    plan_of(body);
  } catch (const SweepError& e) {
    return e.what();
  }
  return "";
}

const std::string kArch = R"("case": {"generator": "circular-arch", "parameters": {"voussoirs": 20}}, "methods": ["prd"], )";

TEST(LatinHypercube, OnePointInEachStratumOfEveryColumn) {
  const int n = 37;
  const auto u = latin_hypercube(n, {"a", "b", "c"}, 11);
  ASSERT_EQ(u.size(), size_t(n));
  for (size_t j = 0; j < 3; ++j) {
    std::vector<int> strata;
    for (const auto& point : u) {
      ASSERT_GE(point[j], 0.0);
      ASSERT_LT(point[j], 1.0);
      strata.push_back(static_cast<int>(point[j] * n));
    }
    std::sort(strata.begin(), strata.end());
    for (int s = 0; s < n; ++s) EXPECT_EQ(strata[s], s) << "column " << j;
  }
}

TEST(LatinHypercube, SameSeedSamePointsEachColumnItsOwnStream) {
  const auto a = latin_hypercube(20, {"x", "y"}, 5);
  EXPECT_EQ(a, latin_hypercube(20, {"x", "y"}, 5));
  // A column depends on its name and the seed only: not on the other columns or their order.
  const auto b = latin_hypercube(20, {"y", "z", "x"}, 5);
  for (size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(a[i][0], b[i][2]);
    EXPECT_EQ(a[i][1], b[i][0]);
  }
  // Another seed, other points; the columns' pairings differ from one another.
  const auto c = latin_hypercube(20, {"x", "y"}, 6);
  int same = 0, paired = 0;
  for (size_t i = 0; i < 20; ++i) {
    same += a[i][0] == c[i][0];
    paired += static_cast<int>(a[i][0] * 20) == static_cast<int>(a[i][1] * 20);
  }
  EXPECT_EQ(same, 0);
  EXPECT_LT(paired, 20);
}

TEST(SweepPlan, SampledDesignBasePointLinesAndSamples) {
  const SweepPlan p = plan_of(kArch + R"("sample": {"count": 20, "seed": 3,
      "ranges": {"generator.thickness": [0.1, 0.2], "generator.voussoirs": [10, 13]}}})");
  ASSERT_TRUE(p.sample);
  EXPECT_EQ(p.keys, (std::vector<std::string>{"generator.thickness", "generator.voussoirs"}));
  // The base point: the generator's default thickness (CircularArch) and the call's 20 voussoirs.
  const double t0 = CircularArch{}.thickness;
  EXPECT_EQ(json(p.base_values).dump(), json::array({t0, 20}).dump());
  std::map<SweepPoint, int> count;
  std::vector<int> per_voussoirs(14, 0);
  for (const SweepRun& r : p.runs) {
    count[r.point]++;
    EXPECT_EQ(r.method, Method::prd);
    if (r.point != SweepPoint::sample) continue;
    const double t = r.values[0].get<double>();
    EXPECT_GE(t, 0.1);
    EXPECT_LE(t, 0.2);
    ASSERT_TRUE(r.values[1].is_number_integer()) << r.values[1];  // an integer parameter
    const long long v = r.values[1].get<long long>();
    ASSERT_GE(v, 10);
    ASSERT_LE(v, 13);
    per_voussoirs[v]++;
  }
  EXPECT_EQ(count[SweepPoint::base], 1);
  EXPECT_EQ(count[SweepPoint::one_at_a_time], 6);  // 3 levels of each range, none the base point
  EXPECT_EQ(count[SweepPoint::sample], 20);
  // 20 strata over 4 whole numbers: each number holds exactly 5 of them.
  for (int v = 10; v <= 13; ++v) EXPECT_EQ(per_voussoirs[v], 5) << v;
  // The one-at-a-time lines: each range's ends and middle, the other option at the base point.
  std::vector<std::string> lines;
  for (const SweepRun& r : p.runs)
    if (r.point == SweepPoint::one_at_a_time) lines.push_back(p.keys[r.line] + "=" + json(r.values).dump());
  EXPECT_EQ(lines, (std::vector<std::string>{"generator.thickness=[0.1,20]", "generator.thickness=[0.15,20]", "generator.thickness=[0.2,20]",
                                             "generator.voussoirs=[0.12,10]", "generator.voussoirs=[0.12,12]", "generator.voussoirs=[0.12,13]"}));
  // Ids are unique (a sample's includes its number).
  std::set<std::string> ids;
  for (const SweepRun& r : p.runs) ids.insert(r.id);
  EXPECT_EQ(ids.size(), p.runs.size());
}

TEST(SweepPlan, OnlyRunsThoseSamplesOfTheSameDesign) {
  const std::string ranges = R"("ranges": {"generator.thickness": [0.1, 0.2], "generator.radius": [0.5, 2]})";
  const std::string arch = R"("case": {"generator": "circular-arch", "parameters": {"voussoirs": 20}}, )";
  const SweepPlan all = plan_of(arch + R"("methods": ["prd", "dem"], "sample": {"count": 10, "seed": 9, )" + ranges + "}}");
  const SweepPlan some =
      plan_of(arch + R"("methods": ["prd", "dem"], "sample": {"count": 10, "seed": 9, "one_at_a_time": 0, "only": [7, 2], )" + ranges + "}}");
  ASSERT_EQ(some.runs.size(), 4u);  // PRD and DEM of samples 2 and 7
  for (const SweepRun& r : some.runs) {
    ASSERT_EQ(r.point, SweepPoint::sample);
    const auto same = std::find_if(all.runs.begin(), all.runs.end(), [&](const SweepRun& q) { return q.sample == r.sample && q.method == r.method; });
    ASSERT_NE(same, all.runs.end());
    EXPECT_EQ(json(r.values).dump(), json(same->values).dump());
    EXPECT_EQ(r.id, same->id);  // so the rows of the two sweeps name the same runs
    if (r.method == Method::dem) {
      ASSERT_GE(r.prd, 0);
      EXPECT_EQ(some.runs[r.prd].sample, r.sample);
    }
  }
  EXPECT_EQ(some.runs[0].sample, 2);
}

// Standard output of a command.
std::string output_of(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> f(popen(cmd.c_str(), "r"), pclose);
  char buf[4096];
  for (size_t n; f && (n = fread(buf, 1, sizeof buf, f.get())) > 0;) out.append(buf, n);
  return out;
}

TEST(SweepPlan, ARunsCaseIsWhatTheCasesCommandWritesWithItsParameters) {
  const SweepPlan p = plan_of(R"("case": {"generator": "cathedral-settlement", "parameters": {"upper-flyer-at-springing": true}},
      "methods": ["prd"], "set": {"generator.course": 1.5, "dem.damping": 0.6},
      "vary": {"generator.nave-thickness": [0.7, 0.9], "motion.max_steps": [50]}})");
  ASSERT_EQ(p.runs.size(), 2u);
  const SweepRun& r = p.runs[1];
  const std::string cmd = std::string(MASONRY_EXE) + " cases cathedral-settlement --upper-flyer-at-springing --course 1.5 --nave-thickness " +
                          value_text(r.values[0]) + " --out - 2>/dev/null";
  Case expected = parse_case(output_of(cmd), "cases");
  expected = with_option(with_option(expected, "dem.damping", 0.6), "motion.max_steps", 50);
  const Case c = case_of_run(p, r);
  EXPECT_EQ(c.blocks.size(), expected.blocks.size());
  EXPECT_TRUE(case_to_json(c) == case_to_json(expected));
}

TEST(SweepSpec, GeneratorAndSampleRefusalsAreOneLineNamingTheField) {
  const auto expect = [](const std::string& body, const std::string& field) {
    const std::string msg = error_of(body);
    ASSERT_FALSE(msg.empty()) << body;
    EXPECT_EQ(msg.rfind("s.json: ", 0), 0u) << msg;
    EXPECT_NE(msg.find(field), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  const std::string s = R"("sample": {"count": 4, "seed": 1, "ranges": {"generator.thickness": [0.1, 0.2]}}})";
  expect(kArch + R"("vary": {"generator.thikness": [0.1]}})", "generator circular-arch has no parameter 'thikness' (it has radius, thickness");
  expect(R"("case": {"generator": "no-such"}, "vary": {"generator.x": [1]}})", "no case generator 'no-such'");
  expect(R"("case": {"generator": "circular-arch", "colour": 1}, "vary": {"generator.radius": [1]}})", "unknown field 'colour'");
  expect(R"("case": {"generator": "circular-arch", "parameters": {"radius": -1}}, "vary": {"generator.thickness": [0.1]}})", "case");
  expect(R"("case": 12, "vary": {"generator.thickness": [0.1]}})", "field 'case'");
  expect(kArch + R"("vary": {"generator.thickness": [-1, -2]}})", "vary 'generator.thickness'");
  expect(kArch + R"("set": {"generator.voussoirs": 2.5}, "vary": {"generator.thickness": [0.1]}})", "case");
  expect(kArch + R"("vary": {"generator.thickness": [0.1]}, )" + s, "not both");
  expect(kArch + R"("sample": {"count": 0, "seed": 1, "ranges": {"generator.thickness": [0.1, 0.2]}}})", "'count'");
  expect(kArch + R"("sample": {"count": 4, "ranges": {"generator.thickness": [0.1, 0.2]}}})", "'seed'");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "ranges": {"generator.thickness": [0.2, 0.1]}}})", "sample range 'generator.thickness'");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "ranges": {"generator.thickness": [0.1]}}})", "[lo, hi]");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "ranges": {"generator.fixed": [0, 1]}}})", "cannot be sampled");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "ranges": {"generator.voussoirs": [10.2, 10.8]}}})", "no whole number");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "only": [4], "ranges": {"generator.thickness": [0.1, 0.2]}}})", "'only'");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "one_at_a_time": 1, "ranges": {"generator.thickness": [0.1, 0.2]}}})", "'one_at_a_time'");
  expect(kArch + R"("sample": {"count": 4, "seed": 1, "by": 2, "ranges": {"generator.thickness": [0.1, 0.2]}}})", "unknown field 'by'");
  expect(kArch + R"("set": {"generator.thickness": 0.1}, )" + s, "also in 'sample'");
  // A generator parameter needs a generator call; a case file has options only.
  const std::string msg = [] {
    try {
      plan_sweep(SweepInput{R"({"format": "masonry-sweep/1", "case": "t.json", "vary": {"generator.thickness": [0.1]}})", "s.json",
                            test::read(test::kTiltCase), "t.json"});
    } catch (const SweepError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(msg.find("not a generator call"), std::string::npos) << msg;
}

}  // namespace
}  // namespace masonry
