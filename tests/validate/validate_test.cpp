// `masonry validate` and its catalogue: the format's refusals, the judging of rows (a tolerance
// that cannot be met fails, expected values from another method), and the command's exit codes.
// The physics of the built-in catalogue is checked by running it: CI runs `masonry validate
// --quick` (.ci/run); here only its cheapest entries run.
#include "validate/validate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "common.hpp"

namespace masonry {
namespace {

using test::Scratch;

const std::string kExe = MASONRY_EXE;

// The tilting block of cases/tilting-block.json: b/h = 0.5, 1 degree of tilt per step.
std::string block_file() { return std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json"; }

// A catalogue with one benchmark on the tilting block's capacity: toppling at atan(b/h).
std::string one_benchmark(const std::string& methods, const std::string& expected = "0.4636476090008061", const std::string& extra = "") {
  return R"x({"format": "masonry-catalogue/1", "benchmarks": [{"name": "topple", "title": "Toppling.",
    "source": "closed form atan(b/h)", "case": {"file": ")x" +
         block_file() + R"("}, "quantity": "capacity", "expected": )" + expected + extra + R"(, "methods": )" + methods + "}]}";
}

std::string one_line_error(const std::string& text) {
  try {
    parse_catalogue(text, "mine.json", ".");
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateCatalogue, BuiltInCataloguesEveryEntryWithItsSourceAndArgument) {
  const Catalogue cat = builtin_catalogue();
  ASSERT_FALSE(cat.benchmarks.empty());
  int quick = 0;
  for (const Benchmark& b : cat.benchmarks) {
    EXPECT_FALSE(b.source.empty()) << b.name;
    quick += b.quick;
    for (const MethodRun& m : b.methods)
      if (b.quantity != Quantity::stands) {
        EXPECT_FALSE(m.tolerance.why.empty()) << b.name;
      }
  }
  EXPECT_GT(quick, 0);
  // What the issue asks the catalogue to hold, by name.
  for (const char* name : {"block-topples", "block-slides", "block-least-friction", "milankovitch-n20", "arch-friction-rotational",
                           "arch-friction-sliding", "pointed-arch-paper", "pointed-arch-test", "agreement-cathedral-settlement",
                           "reactions-cathedral-settlement", "duality-cathedral-settlement-rotation"}) {
    bool found = false;
    for (const Benchmark& b : cat.benchmarks) found = found || b.name == name;
    EXPECT_TRUE(found) << name;
  }
}

TEST(ValidateCatalogue, RefusesWithOneLineNamingFileBenchmarkAndField) {
  const std::string prd = R"({"prd": {"tolerance": {"absolute": 0.02, "why": "one step"}}})";
  EXPECT_EQ(one_line_error(one_benchmark(prd)), "");
  struct Bad {
    std::string text, needle;
  };
  const std::vector<Bad> bad = {
      {"{\"format\": \"masonry-catalogue/1\", \"benchmarks\": [", "malformed JSON"},
      {R"({"format": "masonry-catalogue/2", "benchmarks": []})", "field 'format'"},
      {one_benchmark(R"({"prd": {}})"), "benchmark 'topple': field 'methods.prd.tolerance': missing"},
      {one_benchmark(R"({"prd": {"tolerance": {"absolute": 0.02}}})"), "field 'methods.prd.tolerance.why': missing"},
      {one_benchmark(R"({"fem": {"tolerance": {"absolute": 0.02, "why": "x"}}})"), "unknown method 'fem'"},
      {one_benchmark(prd, "0.46", R"(, "colour": "red")"), "field 'colour': unknown field"},
      {one_benchmark(R"({"dem": {"tolerance": {"absolute": 0.1, "why": "x"}}})", "{\"method\": \"dem\"}"), "its own result"},
      {one_benchmark(prd, "\"tall\""), "field 'expected'"},
      {one_benchmark(R"({"prd": {"source": "a paper", "tolerance": {"absolute": 0.02, "why": "x"}}})"),
       "field 'methods.prd.source': only with the method's own 'expected'"},
      {one_benchmark(R"({"prd": {"expected": 0.46, "tolerance": {"absolute": 0.02, "why": "x"}}})"), "field 'methods.prd.source': missing"},
  };
  for (const Bad& b : bad) {
    const std::string msg = one_line_error(b.text);
    EXPECT_NE(msg.find("mine.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find(b.needle), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // A PRD-only quantity on the DEM, and a search without its range.
  std::string text = one_benchmark(R"({"dem": {"tolerance": {"absolute": 0.1, "why": "x"}}})");
  text.replace(text.find("\"capacity\""), 10, "\"least_friction_angle\"");
  EXPECT_NE(one_line_error(text).find("is a PRD quantity"), std::string::npos);
  text = one_benchmark(prd);
  text.replace(text.find("\"capacity\""), 10, "\"threshold\"");
  EXPECT_NE(one_line_error(text).find("field 'search'"), std::string::npos);
}

TEST(ValidateRun, ATightToleranceFailsAndTheOtherMethodCanBeTheReference) {
  // PRD's capacity is the last stable step, 26 degrees = 0.4538 rad, one step below atan(0.5):
  // inside a tolerance of one step (0.0175 rad), outside one of 1e-6.
  const Catalogue cat = parse_catalogue(one_benchmark(R"({"prd": {"tolerance": {"absolute": 0.0175, "why": "one step"}}})"), "a.json", ".");
  RunCache cache;
  auto rows = run_benchmark(cat, cat.benchmarks[0], cache);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].pass) << rows[0].note;
  EXPECT_NEAR(rows[0].obtained, 26 * M_PI / 180, 1e-9);

  const Catalogue tight = parse_catalogue(one_benchmark(R"({"prd": {"tolerance": {"absolute": 1e-6, "why": "impossible"}}})"), "b.json", ".");
  rows = run_benchmark(tight, tight.benchmarks[0], cache);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_FALSE(rows[0].pass);
  const std::string why = validation_failures(rows);
  EXPECT_NE(why.find("FAIL topple (prd): expected capacity 0.463648"), std::string::npos) << why;
  EXPECT_NE(why.find("closed form atan(b/h)"), std::string::npos) << why;

  // The DEM judged against PRD on the same case: the two methods agree within one step.
  const Catalogue vs =
      parse_catalogue(one_benchmark(R"({"dem": {"tolerance": {"absolute": 0.0175, "why": "one step"}}})", R"({"method": "prd"})"), "c.json", ".");
  rows = run_benchmark(vs, vs.benchmarks[0], cache);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].expected_from, "PRD on the same case");
  EXPECT_NEAR(rows[0].expected, 26 * M_PI / 180, 1e-9);
  EXPECT_TRUE(rows[0].pass) << rows[0].note;
}

// A DEM judged against PRD whose first run slid a joint where PRD's did not and statics does not
// ask for it is judged by its rerun with contact damping, as `masonry compare` takes it
// (compare/README.md, "A slide statics does not ask for"): the zoo's jack arch scaled by 0.05,
// whose undamped DEM ratchets at the skewback (tests/app/compare_rerun_test.cpp), within the 3%
// the zoo's rows hold the two methods to.
TEST(ValidateRun, ADemThatSlidWhereStaticsDoesNotAskIsJudgedByItsDampedRerun) {
  const std::string jack = std::string(MASONRY_SOURCE_DIR) + "/reports/unseen-structures/cases/jack-scale-0.05.json";
  const nlohmann::json cat_json = {{"format", "masonry-catalogue/1"},
                                   {"benchmarks",
                                    {{{"name", "jack-0.05"},
                                      {"title", "The jack arch scaled by 0.05."},
                                      {"source", "agreement of two independent methods"},
                                      {"case", {{"file", jack}}},
                                      {"quantity", "capacity"},
                                      {"expected", {{"method", "prd"}}},
                                      {"methods", {{"dem", {{"tolerance", {{"relative", 0.03}, {"why", "the zoo's"}}}}}}}}}}};
  const Catalogue cat = parse_catalogue(cat_json.dump(), "jack.json", ".");
  RunCache cache;
  const auto rows = run_benchmark(cat, cat.benchmarks[0], cache);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].pass) << rows[0].obtained << " against " << rows[0].expected << ": " << rows[0].note;
  EXPECT_TRUE(rows[0].damped_rerun);
  EXPECT_NE(rows[0].note.find("judged by a rerun with contact damping 0.3: the first run slid jamb-R/v4"), std::string::npos) << rows[0].note;
  EXPECT_NE(validation_table(rows).find("pass (damped rerun)"), std::string::npos);
}

TEST(ValidateRun, ASearchThatDoesNotBracketTheThresholdFailsWithAReason) {
  // The block stands whatever its density: no threshold within the range.
  const std::string text = R"({"format": "masonry-catalogue/1", "benchmarks": [{"name": "density", "title": "t",
    "source": "s", "case": {"file": ")" +
                           block_file() + R"("}, "options": {"motion.max_steps": 0},
    "quantity": "threshold", "search": {"parameter": "blocks_density_is_not_an_option", "range": [1, 2], "resolution": 0.1},
    "expected": 1.5, "methods": {"prd": {"tolerance": {"absolute": 0.1, "why": "x"}}}}]})";
  const Catalogue cat = parse_catalogue(text, "d.json", ".");
  RunCache cache;
  // A searched parameter that is neither an option nor a generator parameter is bad input.
  EXPECT_THROW(run_benchmark(cat, cat.benchmarks[0], cache), CaseError);

  std::string g = text;
  g.replace(g.find("blocks_density_is_not_an_option"), 31, "gravity");
  g.replace(g.find("[1, 2]"), 6, "[5, 20]");
  const Catalogue stands = parse_catalogue(g, "e.json", ".");
  const auto rows = run_benchmark(stands, stands.benchmarks[0], cache);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_FALSE(rows[0].pass);
  EXPECT_FALSE(rows[0].measured);
  EXPECT_NE(rows[0].note.find("stands at both ends"), std::string::npos) << rows[0].note;
}

// A threshold's unit was "m" for thickness, "deg" for a friction angle and "" for anything else:
// it is its parameter's own, the case format's (README, "Options": gravity m/s^2, dem.kn Pa/m,
// dem.damping none, motion.step rad where the supports only turn) or the generator's
// (cases/README.md: radius m, the angle of embrace in degrees).
TEST(ValidateRun, AThresholdIsInItsParametersOwnUnit) {
  const auto threshold = [](const std::string& name, const std::string& case_json, const std::string& parameter, const std::string& range) {
    return R"({"name": ")" + name + R"(", "title": "t", "source": "s", "case": )" + case_json + R"(, "options": {"motion.max_steps": 0},
      "quantity": "threshold", "search": {"parameter": ")" +
           parameter + R"(", "range": )" + range + R"(, "resolution": 0.1},
      "expected": 1, "methods": {"prd": {"tolerance": {"absolute": 0.1, "why": "x"}}}})";
  };
  const std::string block = R"({"file": ")" + block_file() + R"("})";
  const std::string arch = R"({"generator": "circular-arch", "parameters": {"thickness": 0.2, "max_steps": 0}})";
  const std::string text = R"({"format": "masonry-catalogue/1", "benchmarks": [)" + threshold("gravity", block, "gravity", "[5, 20]") + ", " +
                           threshold("kn", block, "dem.kn", "[1e9, 2e9]") + ", " + threshold("damping", block, "dem.damping", "[0.5, 0.6]") + ", " +
                           threshold("step", block, "motion.step", "[0.01, 0.02]") + ", " + threshold("radius", arch, "radius", "[1, 2]") + ", " +
                           threshold("embrace", arch, "embrace_deg", "[150, 160]") + "]}";
  const Catalogue cat = parse_catalogue(text, "u.json", ".");
  const std::map<std::string, std::string> expected = {{"gravity", "m/s^2"}, {"kn", "Pa/m"},  {"damping", ""},
                                                       {"step", "rad"},      {"radius", "m"}, {"embrace", "deg"}};
  RunCache cache;
  for (const Benchmark& b : cat.benchmarks) {
    const auto rows = run_benchmark(cat, b, cache);
    ASSERT_EQ(rows.size(), 1u) << b.name;
    EXPECT_EQ(rows[0].unit, expected.at(b.name)) << b.name;
  }
}

TEST(ValidateRun, AGeneratorParameterItDoesNotKnowIsBadInput) {
  const std::string text = R"({"format": "masonry-catalogue/1", "benchmarks": [{"name": "arch", "title": "t", "source": "s",
    "case": {"generator": "circular-arch", "parameters": {"thickness": 0.12, "spreading": false, "max_steps": 0, "height": 2}},
    "quantity": "stands", "expected": true, "methods": {"prd": {}}}]})";
  const Catalogue cat = parse_catalogue(text, "g.json", ".");
  RunCache cache;
  try {
    run_benchmark(cat, cat.benchmarks[0], cache);
    ADD_FAILURE() << "ran with an unknown parameter";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("g.json: benchmark 'arch': field 'case.parameters.height': unknown parameter of circular-arch"),
              std::string::npos)
        << e.what();
  }
}

TEST(ValidateCommand, ExitCodesTablesAndFiles) {
  Scratch dir("validate");
  // Two cheap built-in benchmarks pass: exit 0, the table, the JSON and Markdown files.
  const std::string json = (dir.path / "v.json").string(), md = (dir.path / "v.md").string();
  const std::string out = (dir.path / "out").string(), err = (dir.path / "err").string();
  EXPECT_EQ(test::run(kExe + " validate --only block-topples arch-stands --json " + json + " --markdown " + md + " >" + out + " 2>" + err), 0);
  const std::string table = test::read(out);
  EXPECT_NE(table.find("4 of 4 passed"), std::string::npos) << table;
  EXPECT_NE(table.find("source"), std::string::npos);
  EXPECT_NE(test::read(err).find("validate: [2/2] arch-stands"), std::string::npos);  // progress lines
  const auto j = nlohmann::json::parse(test::read(json));
  EXPECT_EQ(j["rows"].size(), 4u);
  EXPECT_EQ(j["passed"], 4);
  EXPECT_NE(test::read(md).find("| block-topples | prd |"), std::string::npos);
  // Whether it stands is written as the catalogue writes it, true or false, not 1.0 (and no error).
  for (const auto& row : j["rows"])
    if (row["benchmark"] == "arch-stands") {
      EXPECT_EQ(row["expected"], true) << row.dump();
      EXPECT_EQ(row["obtained"], true) << row.dump();
      EXPECT_TRUE(row["error"].is_null()) << row.dump();
    }

  // A failing row: exit 1 and what was expected, from where.
  const std::string cat = (dir.path / "tight.json").string();
  test::write(cat, one_benchmark(R"({"prd": {"tolerance": {"absolute": 1e-6, "why": "impossible"}}})"));
  EXPECT_EQ(test::run(kExe + " validate --quiet --catalogue " + cat + " >" + out + " 2>" + err), 1);
  EXPECT_NE(test::read(out).find("FAIL topple (prd)"), std::string::npos) << test::read(out);

  // Bad input: exit 2 with one line naming the file and the entry.
  test::write(cat, one_benchmark(R"({"prd": {"tolerance": {"why": "no number"}}})"));
  EXPECT_EQ(test::run(kExe + " validate --catalogue " + cat + " >" + out + " 2>" + err), 2);
  const std::string e = test::read(err);
  EXPECT_NE(e.find("tight.json: benchmark 'topple': field 'methods.prd.tolerance'"), std::string::npos) << e;
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
  EXPECT_EQ(test::run(kExe + " validate --only no-such-benchmark >" + out + " 2>" + err), 2);
  EXPECT_NE(test::read(err).find("no benchmark named 'no-such-benchmark'"), std::string::npos);
  EXPECT_EQ(test::run(kExe + " validate --catalogue " + (dir.path / "missing.json").string() + " >" + out + " 2>" + err), 2);
}

}  // namespace
}  // namespace masonry
