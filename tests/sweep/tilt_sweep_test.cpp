// A friction sweep on the tilting block against the closed form: below atan(b/h) the DEM block
// slides when the tilt reaches the friction angle, above it topples at atan(b/h); the PRD, whose
// mechanisms do not slide, topples; and the report puts the DEM-PRD disagreement boundary where
// the closed forms put it.
#include <gtest/gtest.h>

#include "util.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180;

TEST(TiltSweep, SlidesBelowAtanBOverHAndTopplesAbove) {
  test::Scratch d("tilt");
  const test::TiltBlock blk = test::tilt_block();
  ASSERT_NEAR(blk.topple() / kDeg, 26.565, 1e-3);  // b/h = 0.5
  // Friction angles half a degree off the 1-degree tilt grid (at a whole degree the block would
  // stand exactly at limit equilibrium), on both sides of atan(b/h).
  const double tolerance = 0.05, from = 12.5, to = 37.5, step = 5;
  test::write(d.path / "tilt-sweep.json", R"({"format": "masonry-sweep/1", "case": ")" + test::kTiltCase + R"(",
      "methods": ["prd", "dem"], "tolerance": 0.05,
      "vary": {"dem.friction_angle": {"from": 12.5, "to": 37.5, "step": 5}}})");
  SweepOptions o;
  o.out_dir = (d.path / "out").string();
  o.jobs = 2;
  o.quiet = true;
  const SweepInput in = read_sweep_input((d.path / "tilt-sweep.json").string());
  const SweepPlan p = plan_sweep(in);
  const SweepTable t = run_sweep(in, o);
  ASSERT_EQ(p.runs.size(), 7u);
  ASSERT_EQ(t.size(), 7u);

  // PRD: no sliding in its mechanisms, so it topples: the last stable tilt within one increment
  // below atan(b/h).
  ASSERT_TRUE(t[0]);
  ASSERT_EQ(t[0]->status, RunStatus::collapse) << t[0]->message;
  const double prd_tilt = t[0]->capacity * blk.rate;
  EXPECT_LE(prd_tilt, blk.topple());
  EXPECT_GT(prd_tilt, blk.topple() - blk.increment);
  // Its sliding check: a block at rest on a slope theta needs tan(phi) >= tan(theta), so over
  // the stable steps the friction angle it needs is the last stable tilt.
  ASSERT_TRUE(t[0]->required_friction_angle);
  EXPECT_NEAR(*t[0]->required_friction_angle * kDeg, prd_tilt, 1e-9);

  // DEM: each run within one increment below min(phi, atan(b/h)) (sliding or toppling).
  int sliding = 0, toppling = 0;
  for (int i = 1; i < 7; ++i) {
    ASSERT_TRUE(t[i]) << i;
    ASSERT_EQ(t[i]->status, RunStatus::collapse) << t[i]->message;
    const double phi = p.runs[i].values[0].get<double>() * kDeg;
    const double expected = blk.collapse(phi);
    const double tilt = t[i]->capacity * blk.rate;
    EXPECT_LE(tilt, expected) << "phi " << phi / kDeg;
    EXPECT_GT(tilt, expected - blk.increment) << "phi " << phi / kDeg;
    (std::tan(phi) < blk.b / blk.h ? sliding : toppling)++;
    // Grouped by mechanism: a sliding block opens no joint; a toppling one turns about its
    // downhill corner, PRD's hinge (its collapse mechanism's).
    EXPECT_EQ(t[i]->hinges, std::tan(phi) < blk.b / blk.h ? std::string() : t[0]->hinges) << "phi " << phi / kDeg;
  }
  EXPECT_FALSE(t[0]->hinges.empty());
  EXPECT_EQ(sliding, 3);  // 12.5, 17.5, 22.5
  EXPECT_EQ(toppling, 3);

  // The transition: the largest friction angle at which DEM and PRD differ by more than the
  // tolerance. From the closed forms (DEM phi, PRD atan(b/h)), they differ for phi below
  // atan(b/h) (1 - tolerance); the grid keeps a clear margin (more than an increment) from it.
  const double threshold = blk.topple() * (1 - tolerance);
  double expected_boundary = NAN;
  for (double phi = from; phi <= to; phi += step) {
    ASSERT_GT(std::abs(phi * kDeg - threshold), 2 * blk.increment) << "a grid value is too close to call";
    if (phi * kDeg < threshold) expected_boundary = phi;
  }
  const auto j = nlohmann::json::parse(test::read(d.path / "out" / "sweep.json"));
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_EQ(j["x"], "dem.friction_angle");
  ASSERT_EQ(j["curves"].size(), 1u);
  const auto& curve = j["curves"][0];
  ASSERT_TRUE(curve["boundary"].is_number()) << curve.dump();
  const double boundary = curve["boundary"].get<double>();
  EXPECT_EQ(boundary, expected_boundary);
  EXPECT_TRUE(curve["boundary_clean"].get<bool>());
  // So the transition sits within one sweep step below atan(b/h).
  EXPECT_LT(boundary * kDeg, blk.topple());
  EXPECT_GT(boundary * kDeg, blk.topple() - step * kDeg);
  EXPECT_NEAR(curve["prd_capacity"].get<double>(), t[0]->capacity, 1e-15);
  EXPECT_NEAR(curve["prd_required_friction_angle"].get<double>() * kDeg, prd_tilt, 1e-9);

  // The table has a row per run, the report its figure, and no report says NaN.
  const auto rows = test::csv_rows(test::read(d.path / "out" / "sweep.csv"));
  EXPECT_EQ(rows.size(), 8u);
  EXPECT_TRUE(fs::exists(d.path / "out" / "figures" / "capacity.svg"));
  for (const char* f : {"report.md", "report.html", "sweep.json", "figures/capacity.svg", "sweep.csv"})
    EXPECT_FALSE(test::says_nan(test::read(d.path / "out" / f))) << f;
  const std::string md = test::read(d.path / "out" / "report.md");
  std::ostringstream says;
  says << "up to " << expected_boundary << " deg";
  EXPECT_NE(md.find(says.str()), std::string::npos) << md;
}

}  // namespace
}  // namespace masonry
