// The sensitivity of the capacity, through `masonry sweep`: the semicircular arch's spreading
// capacity against its thickness, zero below Milankovitch's least thickness and growing above it,
// in sensitivity.json and the report, on a grid and on a sample; sampled percentiles reproducible
// by seed and resumable; PRD against DEM per sample with each run kept for compare --runs; and a
// PRD-only sweep over options PRD ignores saying so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "util.hpp"

namespace masonry {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;
const std::string kExe = MASONRY_EXE;

// Milankovitch (1907): a semicircular arch with radial joints under its own weight stands only
// when t/R >= 0.1075 (Cocchetti & Rizzi 2020, Table 3: 0.107426; an arch of 20 voussoirs has a
// joint within 0.5 degrees of the continuous haunch hinge, so its least thickness is within 0.5%
// of it). Thicknesses within 2% of it are not asked about.
constexpr double kLeastThickness = 0.1075;
bool clearly_below(double t_over_r) { return t_over_r < kLeastThickness * 0.98; }
bool clearly_above(double t_over_r) { return t_over_r > kLeastThickness * 1.02; }

// The semicircular arch of radius 1 m on spreading supports, 1 mm steps.
const std::string kArch = R"({"format": "masonry-sweep/1", "name": "semicircular arch",
  "case": {"generator": "circular-arch", "parameters": {"radius": 1, "voussoirs": 20, "step": 0.001}}, "methods": ["prd"], )";

json read_json(const fs::path& p) { return json::parse(test::read(p)); }

int sweep(const fs::path& spec, const fs::path& out, const std::string& extra, const fs::path& err) {
  return test::run(kExe + " sweep " + spec.string() + " --out " + out.string() + " " + extra + " 2>" + err.string());
}

// The example cases/arch-thickness-sweep.json: the arch of kArch over a grid of thicknesses.
TEST(Sensitivity, ArchCapacityGrowsWithThicknessAndIsZeroBelowMilankovitch) {
  test::Scratch d("arch-grid");
  const fs::path spec = fs::path(MASONRY_SOURCE_DIR) / "cases" / "arch-thickness-sweep.json";
  const std::vector<double> t = json::parse(test::read(spec))["vary"]["generator.thickness"];
  ASSERT_EQ(t.size(), 7u);
  ASSERT_EQ(sweep(spec, d.path / "out", "", d.path / "err"), 0) << test::read(d.path / "err");
  const json s = read_json(d.path / "out" / "sensitivity.json");
  const json& line = s["methods"]["prd"]["parameters"]["generator.thickness"]["one_at_a_time"];
  ASSERT_EQ(line["values"].size(), t.size()) << line;
  double last = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double x = line["values"][i], cap = line["capacities"][i];
    EXPECT_EQ(x, t[i]);
    if (clearly_below(x)) {
      EXPECT_EQ(cap, 0.0) << "t/R = " << x;
    }
    if (clearly_above(x)) {
      EXPECT_GT(cap, last) << "t/R = " << x << ": the capacity grows with the thickness";
      last = cap;
    }
  }
  const json& e = s["methods"]["prd"]["parameters"]["generator.thickness"];
  EXPECT_GT(e["elasticity"].get<double>(), 1.0) << e;  // more than in proportion: zero at the least thickness
  EXPECT_EQ(e["n"], 4);                                // the runs above the least thickness
  EXPECT_EQ(s["methods"]["prd"]["zero_capacity"], 3);
  // Every run collapses by a mechanism of at least four hinges (a three-hinged arch is statically
  // determinate: it stands; Heyman 1966), and the groups of hinge sets hold every run.
  int grouped = 0;
  for (const json& g : s["methods"]["prd"]["mechanisms"]["groups"]) {
    const std::string h = g["hinges"];
    EXPECT_GE(std::count(h.begin(), h.end(), ':'), 4) << h;
    grouped += g["count"].get<int>();
  }
  EXPECT_EQ(grouped, int(t.size()));
  // The report says where the capacity is 0 and that it rises, and draws the tornado chart.
  const std::string md = test::read(d.path / "out" / "report.md");
  EXPECT_NE(md.find("| 0.09, 0.1, 0.104 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| rises |"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(d.path / "out" / "figures" / "tornado-prd.svg"));
  EXPECT_FALSE(test::says_nan(md));
}

// A run that fails (a thickness the generator refuses) enters no fit, so it must not decide how
// the others are fitted either: its x <= 0 turned the thickness's elasticity (ln on ln) into a
// slope against x, 38.5 instead of 5.98, with the same four runs fitted.
TEST(Sensitivity, AFailedRunDoesNotChangeTheOthersElasticity) {
  test::Scratch d("arch-failed");
  const std::string head = std::string(R"({"format": "masonry-sweep/1", "name": "arch", "methods": ["prd"],
    "case": {"generator": "circular-arch", "parameters": {"radius": 1, "voussoirs": 20, "step": 0.002, "max-steps": 300}},
    "set": {"prd.sliding_check": false}, "vary": {"generator.thickness": )");
  test::write(d.path / "with.json", head + "[-0.05, 0.11, 0.12, 0.15, 0.2]}}");
  test::write(d.path / "without.json", head + "[0.11, 0.12, 0.15, 0.2]}}");
  EXPECT_EQ(sweep(d.path / "with.json", d.path / "with", "", d.path / "err"), 1) << "a failed run is the sweep's exit 1";
  ASSERT_EQ(sweep(d.path / "without.json", d.path / "without", "", d.path / "err"), 0) << test::read(d.path / "err");
  const json a = read_json(d.path / "with" / "sensitivity.json")["methods"]["prd"]["parameters"]["generator.thickness"];
  const json b = read_json(d.path / "without" / "sensitivity.json")["methods"]["prd"]["parameters"]["generator.thickness"];
  EXPECT_EQ(a["log"], true) << a;
  EXPECT_EQ(a["n"], 4) << a;
  EXPECT_EQ(a["elasticity"], b["elasticity"]) << a << "\n" << b;
}

// The sampled capacities' percentiles, by their definition (linear interpolation between the
// sorted values at (n - 1) q / 100).
double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double h = (v.size() - 1) * q / 100;
  const size_t lo = static_cast<size_t>(h);
  return lo + 1 < v.size() ? v[lo] + (h - lo) * (v[lo + 1] - v[lo]) : v.back();
}

TEST(Sensitivity, SampledArchPercentilesReproducibleBySeedAndResumable) {
  test::Scratch d("arch-sample");
  const auto spec = [](int seed) {
    return kArch + R"("sample": {"count": 14, "seed": )" + std::to_string(seed) +
           R"(, "one_at_a_time": 0, "ranges": {"generator.thickness": [0.09, 0.17]}}})";
  };
  test::write(d.path / "a.json", spec(4));
  test::write(d.path / "b.json", spec(5));
  ASSERT_EQ(sweep(d.path / "a.json", d.path / "a", "--quiet", d.path / "err"), 0) << test::read(d.path / "err");
  // Every sample: zero below the least thickness, positive above; the capacity rises with t.
  const auto rows = test::csv_rows(test::read(d.path / "a" / "sweep.csv"));
  const size_t tc = test::column(rows[0], "generator.thickness"), cc = test::column(rows[0], "capacity"), sc = test::column(rows[0], "sample");
  ASSERT_LT(sc, rows[0].size());
  ASSERT_EQ(rows.size(), 15u);
  std::vector<double> caps;
  std::vector<std::pair<double, double>> above;
  for (size_t i = 1; i < rows.size(); ++i) {
    const double x = std::stod(rows[i][tc]), cap = std::stod(rows[i][cc]);
    EXPECT_GE(x, 0.09);
    EXPECT_LE(x, 0.17);
    if (clearly_below(x)) {
      EXPECT_EQ(cap, 0.0) << x;
    }
    if (clearly_above(x)) {
      EXPECT_GT(cap, 0.0) << x;
      above.emplace_back(x, cap);
    }
    caps.push_back(cap);
  }
  std::sort(above.begin(), above.end());
  for (size_t i = 1; i < above.size(); ++i) EXPECT_GE(above[i].second, above[i - 1].second) << above[i].first;
  const json s = read_json(d.path / "a" / "sensitivity.json");
  const json& prd = s["methods"]["prd"];
  for (const char* q : {"5", "50", "95"}) EXPECT_DOUBLE_EQ(prd["percentiles"][q].get<double>(), percentile(caps, std::stod(q))) << q;
  EXPECT_GT(prd["parameters"]["generator.thickness"]["spearman"].get<double>(), 0.9);
  EXPECT_GT(prd["parameters"]["generator.thickness"]["elasticity"].get<double>(), 1.0);
  EXPECT_EQ(s["design"]["kind"], "latin-hypercube");
  const std::string md = test::read(d.path / "a" / "report.md");
  EXPECT_NE(md.find("Latin hypercube of 14 samples (seed 4)"), std::string::npos);
  EXPECT_TRUE(fs::exists(d.path / "a" / "figures" / "histogram-prd.svg"));

  // The same seed: the same samples and percentiles; another seed: other samples.
  const auto without_time = [](const std::string& csv) {
    auto r = test::csv_rows(csv);
    const size_t c = test::column(r.at(0), "time_s");
    for (auto& row : r) row.at(c) = "";
    return r;
  };
  ASSERT_EQ(sweep(d.path / "a.json", d.path / "a2", "--quiet", d.path / "err"), 0);
  EXPECT_EQ(without_time(test::read(d.path / "a2" / "sweep.csv")), without_time(test::read(d.path / "a" / "sweep.csv")));
  EXPECT_EQ(read_json(d.path / "a2" / "sensitivity.json")["methods"]["prd"]["percentiles"], prd["percentiles"]);
  ASSERT_EQ(sweep(d.path / "b.json", d.path / "b", "--quiet", d.path / "err"), 0);
  const auto other = test::csv_rows(test::read(d.path / "b" / "sweep.csv"));
  EXPECT_NE(other[1][tc], rows[1][tc]);

  // Resumed: a table that lost its last rows runs those samples only, and ends the same.
  const std::string full = test::read(d.path / "a" / "sweep.csv");
  std::string cut = full;
  for (int k = 0; k < 4; ++k) cut.erase(cut.rfind('\n', cut.size() - 2) + 1);
  test::write(d.path / "a" / "sweep.csv", cut);
  ASSERT_EQ(sweep(d.path / "a.json", d.path / "a", "", d.path / "err"), 0);
  EXPECT_EQ(test::runs_done(test::read(d.path / "err")), (std::set<int>{10, 11, 12, 13})) << test::read(d.path / "err");
  EXPECT_EQ(without_time(test::read(d.path / "a" / "sweep.csv")), without_time(full));
  // On two MPI ranks: the same table.
  if (test::run("command -v mpirun >/dev/null 2>&1") == 0) {
    ASSERT_EQ(test::run(test::mpirun(2, d.path) + kExe + " sweep " + (d.path / "a.json").string() + " --out " + (d.path / "np2").string() +
                        " --quiet </dev/null >/dev/null 2>" + (d.path / "err").string()),
              0)
        << test::read(d.path / "err");
    EXPECT_EQ(without_time(test::read(d.path / "np2" / "sweep.csv")), without_time(full));
  }
}

TEST(Sensitivity, PrdAgainstDemPerSampleWithEveryRunKept) {
  test::Scratch d("keep");
  // The tilting block over sampled friction angles: the DEM slides at phi below atan(b/h) and
  // topples at it above (tests/sweep/util.hpp); PRD, without sliding, topples at every angle.
  test::write(d.path / "s.json", R"({"format": "masonry-sweep/1", "case": ")" + test::kTiltCase +
                                     R"(", "sample": {"count": 3, "seed": 2, "one_at_a_time": 0, "ranges": {"dem.friction_angle": [15, 40]}}})");
  ASSERT_EQ(sweep(d.path / "s.json", d.path / "out", "--keep-runs --quiet", d.path / "err"), 0) << test::read(d.path / "err");
  const json s = read_json(d.path / "out" / "sensitivity.json");
  ASSERT_EQ(s["prd_dem"].size(), 3u) << s["prd_dem"];
  const test::TiltBlock b = test::tilt_block();
  const auto rows = test::csv_rows(test::read(d.path / "out" / "sweep.csv"));
  const size_t ic = test::column(rows[0], "id"), mc = test::column(rows[0], "method"), pc = test::column(rows[0], "dem.friction_angle"),
               cc = test::column(rows[0], "capacity");
  for (const json& pair : s["prd_dem"]) {
    const auto& dem = rows.at(pair["dem_run"].get<int>() + 1);
    const double phi = std::stod(dem[pc]) * M_PI / 180;
    EXPECT_NEAR(pair["prd"].get<double>(), b.topple() / b.rate, b.increment / b.rate + 1e-9);
    EXPECT_NEAR(pair["dem"].get<double>(), b.collapse(phi) / b.rate, b.increment / b.rate + 1e-9) << "phi " << dem[pc];
  }
  EXPECT_TRUE(fs::exists(d.path / "out" / "figures" / "prd-dem.svg"));
  // Every run kept; a sample's PRD and DEM runs open with compare --runs, their capacities the rows'.
  for (size_t i = 1; i < rows.size(); ++i)
    for (const char* f : {"case.json", "results.json", "steps.csv"})
      EXPECT_TRUE(fs::exists(d.path / "out" / "runs" / rows[i][ic] / f)) << rows[i][ic] << f;
  const json& first = s["prd_dem"][0];
  const fs::path prd = d.path / "out" / "runs" / rows.at(first["prd_run"].get<int>() + 1)[ic];
  const fs::path dem = d.path / "out" / "runs" / rows.at(first["dem_run"].get<int>() + 1)[ic];
  EXPECT_EQ(rows.at(first["prd_run"].get<int>() + 1)[mc], "prd");
  const int rc = test::run(kExe + " compare " + (prd / "case.json").string() + " --out " + (d.path / "cmp").string() + " --runs " + prd.string() +
                           " " + dem.string() + " >/dev/null 2>" + (d.path / "err").string());
  EXPECT_TRUE(rc == 0 || rc == 1) << test::read(d.path / "err");
  const json c = read_json(d.path / "cmp" / "comparison.json");
  EXPECT_EQ(c.dump().find("nan"), std::string::npos);
  EXPECT_NE(c.dump().find(rows.at(first["dem_run"].get<int>() + 1)[cc]), std::string::npos) << "the DEM row's capacity";
}

TEST(Sensitivity, APrdOnlySweepOverDemOptionsSaysSo) {
  test::Scratch d("ignored");
  test::write(d.path / "s.json", R"({"format": "masonry-sweep/1", "case": ")" + test::kTiltCase +
                                     R"(", "methods": ["prd"], "vary": {"dem.friction_angle": [20, 30, 40]}})");
  ASSERT_EQ(sweep(d.path / "s.json", d.path / "out", "", d.path / "err"), 0) << test::read(d.path / "err");
  const std::string err = test::read(d.path / "err");
  const std::string line = "sweep: PRD ignores dem.friction_angle (DEM option): this PRD-only sweep runs 1 PRD run";
  EXPECT_NE(err.find(line), std::string::npos) << err;
  EXPECT_EQ(err.find(line), err.rfind(line)) << "one line";
  EXPECT_NE(test::read(d.path / "out" / "report.html").find("PRD ignores dem.friction_angle"), std::string::npos);
  EXPECT_NE(test::read(d.path / "out" / "report.md").find("PRD ignores dem.friction\\_angle"), std::string::npos);
  const json s = read_json(d.path / "out" / "sensitivity.json");
  EXPECT_EQ(s["prd_ignores"], json({"dem.friction_angle"}));
  EXPECT_TRUE(s["methods"]["prd"]["parameters"]["dem.friction_angle"]["ignored"].get<bool>());
  EXPECT_EQ(read_json(d.path / "out" / "sweep.json")["runs"].size(), 1u);
}

// Block ids may hold spaces (never '/' or ':'), so a set of hinges is read label by label, not
// word by word, and grouped by its members as lists.
TEST(Sensitivity, HingesOfIdsWithSpacesKeepTheirMembers) {
  const std::string hinges = "pier L0/pier L1:A arch 3/arch 4:open nave-06/nave-07:B";
  EXPECT_EQ(hinge_labels(hinges), (std::vector<std::string>{"pier L0/pier L1:A", "arch 3/arch 4:open", "nave-06/nave-07:B"}));
  EXPECT_EQ(members_of(hinges), (std::vector<std::string>{"arch", "nave", "pier L"}));
  EXPECT_EQ(join_members(members_of(hinges)), "arch, nave, pier L");
  EXPECT_EQ(members_of("L pier 2/aisle 1:B"), (std::vector<std::string>{"L pier/aisle"}));
  EXPECT_TRUE(hinge_labels("").empty());
}

}  // namespace
}  // namespace masonry
