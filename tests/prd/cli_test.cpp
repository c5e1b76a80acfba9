// The `masonry prd` and `masonry check` front ends, run as a user would run them.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "model/options.hpp"

namespace {

namespace fs = std::filesystem;

struct CmdResult {
  int code;
  std::string out, err;
};

CmdResult run(const std::string& args) {
  const fs::path dir = fs::temp_directory_path() / ("masonry-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "stdout").string(), err = (dir / "stderr").string();
  const int rc = std::system((std::string(MASONRY_EXE) + " " + args + " >" + out + " 2>" + err).c_str());
  auto slurp = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  return {WEXITSTATUS(rc), slurp(out), slurp(err)};
}

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("masonry-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

const char* kBlock = R"({
  "format": "masonry-case/1", "name": "tilting block",
  "blocks": [
    {"id": "ground", "vertices": [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.0], [-2.0, 0.0]], "support": true},
    {"id": "block", "vertices": [[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]], "density": 2000.0}
  ],
  "motion": {"step": 0.01, "max_steps": 2000,
             "supports": [{"block": "ground", "rotation": 1.0, "about": [-2.0, -0.5]}]}
})";

TEST(Cli, PrdWritesResultsAndSteps) {
  const fs::path c = write_case("block.json", kBlock);
  const fs::path out = c.parent_path() / "out-prd";
  fs::remove_all(out);
  const CmdResult r = run("prd " + c.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(out / "results.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["method"], "prd");
  EXPECT_EQ(j["stopped"], "collapse");
  EXPECT_TRUE(j["collapsed"].get<bool>());
  const double capacity = j["capacity"].get<double>();
  EXPECT_LE(capacity, std::atan(0.5));
  EXPECT_GT(capacity, std::atan(0.5) - 0.01);
  const int stable = j["stable_steps"].get<int>();
  ASSERT_EQ(j["steps"].size(), static_cast<size_t>(stable + 1));
  for (const char* key : {"d", "energy", "open_corners", "cracked", "reactions"}) EXPECT_TRUE(j["steps"][1].contains(key)) << key;
  EXPECT_EQ(j["steps"][1]["reactions"][0]["support"], "ground");
  EXPECT_EQ(j["steps"][1]["reactions"][0]["force"].size(), 2u);
  for (const char* key : {"total_s", "lp_s", "lp_solves", "basis_evaluations"}) EXPECT_TRUE(j["timing"].contains(key)) << key;
  EXPECT_GE(j["timing"]["lp_solves"].get<int>(), stable + 1);
  EXPECT_EQ(j["timing"]["basis_evaluations"].get<int>(), 0);  // a fixed run predicts nothing
  // steps.csv: a header and one row per step.
  std::ifstream csv(out / "steps.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, stable + 2);
  EXPECT_FALSE(fs::exists(out / "results.json.tmp"));
}

TEST(Cli, PrdOptionsOverrideTheCase) {
  const fs::path c = write_case("block.json", kBlock);
  const fs::path out = c.parent_path() / "out-prd-opts";
  const CmdResult r = run("prd " + c.string() + " --out " + out.string() + " --step 0.005 --max-steps 7 --tolerance 1e-6");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(out / "results.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["stopped"], "max_steps");
  EXPECT_EQ(j["stable_steps"], 7);
  EXPECT_NEAR(j["capacity"].get<double>(), 0.035, 1e-12);
  EXPECT_EQ(j["settings"]["contact_tolerance"].get<double>(), 1e-6);
}

// results.json's settings give every setting the run used, defaults included, as the DEM's do: a
// case that sets no PRD option echoed only step and max_steps, so a results file did not say
// whether it was adaptive, checked sliding or held corners. Expected: the defaults of README.md's
// options table ("Options"), and every option of the prd section.
TEST(Cli, PrdSettingsEchoEveryOptionWithItsDefault) {
  const fs::path c = write_case("block.json", kBlock);
  const fs::path out = c.parent_path() / "out-prd-defaults";
  const CmdResult r = run("prd " + c.string() + " --out " + out.string() + " --max-steps 3 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(out / "results.json");
  const auto settings = nlohmann::json::parse(in)["settings"];
  const nlohmann::json expected = {
      {"step", 0.01},           {"max_steps", 3},  {"contact_tolerance", 1e-5}, {"adaptive", false},
      {"event_tolerance", 0.0}, {"max_step", 0.0}, {"sliding_check", false},    {"hold_closed", nlohmann::json::array()}};
  EXPECT_EQ(settings, expected) << settings.dump();
  for (const auto& o : masonry::options<masonry::PrdOptions>().rows) EXPECT_TRUE(settings.contains(o.name)) << o.name;
}

// `--friction-angle DEG` was said on stderr only: a results file did not tell which angle its
// sliding report judged against. Its settings record the flag's value, and the sliding check it
// implies (README, the prd row).
TEST(Cli, PrdFrictionAngleIsRecordedInTheSettings) {
  const fs::path c = write_case("block.json", kBlock);
  const fs::path out = c.parent_path() / "out-prd-friction";
  const CmdResult r = run("prd " + c.string() + " --out " + out.string() + " --max-steps 3 --friction-angle 27.5");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("needs more than 27.5 deg of friction"), std::string::npos) << r.err;
  std::ifstream in(out / "results.json");
  const auto settings = nlohmann::json::parse(in)["settings"];
  EXPECT_EQ(settings["friction_angle"].get<double>(), 27.5) << settings.dump();
  EXPECT_EQ(settings["sliding_check"].get<bool>(), true) << settings.dump();
}

TEST(Cli, CheckPrintsOneJsonObject) {
  const fs::path c = write_case("block.json", kBlock);
  const CmdResult r = run("check " + c.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["stable"].get<bool>());
  EXPECT_NEAR(j["reactions"][0]["force"][1].get<double>(), 2000.0 * 9.81 * 0.5, 1e-6);
  EXPECT_FALSE(j["forces"].empty());
}

// `check --step`: the run's first LP. The block rides on the ground tilting about (-2, -0.5):
// at first order its centroid (0.25, 0.5) rises by h (0.25 + 2) per radian, so the loads'
// potential energy changes by W x 2.25 h, W = 2000 x 9.81 x 0.5 N, and no corner opens (tipping
// about either corner would lift the centroid more or push a corner into the ground).
TEST(Cli, CheckStepGivesTheFirstStepsMechanismAndEnergy) {
  const fs::path c = write_case("block.json", kBlock);
  const double h = 0.01, W = 2000.0 * 9.81 * 0.5;
  const CmdResult r = run("check " + c.string() + " --step 0.01 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["bounded"].get<bool>());
  EXPECT_NEAR(j["energy_change"].get<double>(), W * 2.25 * h, 1e-9 * W);
  EXPECT_TRUE(j["opening"].empty()) << j["opening"].dump();
  const CmdResult bad = run("check " + c.string() + " --step 0.01 --hold ground/nosuch:A");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("ground/nosuch:A"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

TEST(Cli, BadCaseIsOneLineNamingBlockAndField) {
  std::string bad = kBlock;
  bad.replace(bad.find("\"density\": 2000.0"), 17, "\"density\": -1");
  const fs::path c = write_case("bad.json", bad);
  for (const std::string& cmd : {"prd " + c.string() + " --out " + (c.parent_path() / "x").string(), "check " + c.string()}) {
    const CmdResult r = run(cmd);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("block 'block'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("density"), std::string::npos) << r.err;
  }
  const CmdResult missing = run("check /nonexistent.json");
  EXPECT_NE(missing.code, 0);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* sub : {"prd", "check"}) {
    const CmdResult r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

}  // namespace
