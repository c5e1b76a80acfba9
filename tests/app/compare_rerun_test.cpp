// `masonry compare` runs the DEM again with contact damping where its first run slid a joint PRD's
// did not and statics does not ask for it (compare/README.md, "A slide statics does not ask for").
// The structure: the zoo's jack arch scaled by 0.05 (a 6 cm opening of the same material, so its
// joints are twenty times stiffer against its weights), whose undamped DEM ratchets at the right
// skewback; the expected answer is the other method's: PRD's capacity, within the 3% the two
// methods are held to on the zoo (validate's catalogue).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "common.hpp"

namespace masonry {
namespace {

namespace fs = std::filesystem;
using test::Scratch;
const std::string kExe = MASONRY_EXE;

// The jack arch scaled by 0.05, as reports/unseen-structures.sh makes it (its lengths and the
// turning support's centre times 0.05; d stays in rad).
const std::string kJack = std::string(MASONRY_SOURCE_DIR) + "/reports/unseen-structures/cases/jack-scale-0.05.json";

nlohmann::json comparison(const fs::path& out) { return nlohmann::json::parse(test::read(out / "comparison.json")); }

TEST(CompareRerun, ADemJointSlidWhereStaticsDoesNotAskIsRunAgainWithContactDamping) {
  Scratch dir("compare-rerun");
  const std::string& c = kJack;
  const fs::path out = dir.path / "o";
  ASSERT_EQ(test::run(kExe + " compare " + c + " --out " + out.string() + " --quiet --frames 2 >/dev/null 2>&1"), 0);
  const nlohmann::json j = comparison(out);
  const double prd = j["runs"][0]["capacity"], dem = j["runs"][1]["capacity"];
  EXPECT_NEAR(dem / prd, 1.0, 0.03) << "PRD " << prd << " rad, DEM " << dem << " rad";
  ASSERT_TRUE(j["runs"][1].contains("damped_rerun")) << j["runs"][1].dump();
  const nlohmann::json& x = j["runs"][1]["damped_rerun"];
  EXPECT_EQ(x["contact_damping"], j["runs"][1]["settings"]["contact_damping"]);
  EXPECT_GT(x["contact_damping"].get<double>(), 0.0);
  EXPECT_GT(x["slip"].get<double>(), 0.01 * x["travel"].get<double>());
  EXPECT_EQ(x["friction_angle"], 35.0);
  EXPECT_LT(x["statics_needs"].get<double>(), 35.0);
  // The rerun removed the slide: the compared DEM's joints slid less than the rule's 1%, and that
  // is what the comparison's own sliding check reads of it.
  EXPECT_EQ(x["removed"], true);
  EXPECT_LT(x["rerun_slip"].get<double>(), 0.01 * x["travel"].get<double>());
  EXPECT_EQ(x["rerun_slip"], j["comparisons"][0]["sliding"]["largest_b"]["b"]);
  EXPECT_EQ(x["rerun_dir"], "dem");
  // The first run is kept beside the rerun, and the report says why it was made.
  EXPECT_TRUE(fs::exists(out / x["first_dir"].get<std::string>() / "results.json"));
  EXPECT_FALSE(fs::exists(out / "dem-damped"));
  EXPECT_NE(test::read(out / "report.md").find("A slide statics does not ask for"), std::string::npos);

  // --no-damped-rerun keeps the first run: the slide the rerun answered is in its sliding check.
  const fs::path kept = dir.path / "kept";
  const fs::path err = dir.path / "kept.err";
  const int rc = test::run(kExe + " compare " + c + " --out " + kept.string() + " --quiet --frames 2 --no-damped-rerun >/dev/null 2>" + err.string());
  EXPECT_EQ(rc, 0);
  // Even with --quiet the slide it kept is said.
  EXPECT_NE(test::read(err).find("compare: note: the DEM slid joint jamb-R/v4"), std::string::npos) << test::read(err);
  const nlohmann::json k = comparison(kept);
  EXPECT_FALSE(k["runs"][1].contains("damped_rerun"));
  EXPECT_EQ(k["runs"][1]["settings"]["contact_damping"], 0.0);
  EXPECT_FALSE(fs::exists(kept / "dem-undamped"));
  // Into the directory of the first comparison: what its rerun left there goes.
  ASSERT_EQ(test::run(kExe + " compare " + c + " --out " + out.string() + " --quiet --frames 2 --no-damped-rerun >/dev/null 2>&1"), 0);
  EXPECT_FALSE(fs::exists(out / "dem-undamped"));
  EXPECT_EQ(k["runs"][1]["capacity"], x["first_capacity"]);
  EXPECT_EQ(k["comparisons"][0]["sliding"]["largest_b"]["joint"], x["joint"]);
  EXPECT_EQ(k["comparisons"][0]["sliding"]["largest_b"]["b"], x["slip"]);
}

}  // namespace
}  // namespace masonry
