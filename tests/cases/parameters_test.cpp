// The generators' parameter tables: one definition of each parameter, which the command line
// (`masonry cases NAME --PARAM`) and generate_case (a sweep's generator.PARAM) both read, so the
// same names give the same case.
#include "cases/parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "cases/generators.hpp"
#include "common.hpp"

namespace masonry {
namespace {

using nlohmann::json;

// Standard output of a command.
std::string output_of(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) return out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, p.get())) > 0;) out.append(buf, n);
  return out;
}

const std::string kExe = MASONRY_EXE;

TEST(GeneratorParameters, HelpListsEveryParameterOfTheTable) {
  ASSERT_EQ(case_generators().size(), 5u);
  for (const CaseGenerator& g : case_generators()) {
    const std::string help = output_of(kExe + " cases " + g.name + " --help 2>&1");
    for (const GeneratorParameter& p : g.parameters) EXPECT_NE(help.find("--" + p.name), std::string::npos) << g.name << ": --" << p.name;
  }
}

TEST(GeneratorParameters, TheCommandLineAndGenerateCaseBuildTheSameCase) {
  const struct {
    std::string generator, args;
    json values;
  } calls[] = {
      {"circular-arch",
       "--thickness 0.15 --voussoirs 12 --embrace-deg 160 --fixed",
       {{"thickness", 0.15}, {"voussoirs", 12}, {"embrace-deg", 160}, {"fixed", true}}},
      {"pointed-arch", "--eccentricity 0.1", {{"eccentricity", 0.1}}},
      {"cathedral-settlement", "--nave-thickness 0.7 --buttress-width 3.5", {{"nave-thickness", 0.7}, {"buttress-width", 3.5}}},
  };
  for (const auto& c : calls) {
    const std::string file = output_of(kExe + " cases " + c.generator + " " + c.args + " --out - 2>/dev/null");
    ASSERT_FALSE(file.empty()) << c.generator;
    EXPECT_TRUE(file == case_to_json(generate_case(c.generator, c.values))) << c.generator << " " << c.args;
  }
  // No parameter: the standard scene, name and description included.
  EXPECT_EQ(case_to_json(generate_case("pointed-arch", json::object())), case_to_json(standard_case("pointed-arch")));
  EXPECT_EQ(case_to_json(generate_case("cathedral-settlement", json::object())), case_to_json(standard_case("cathedral-settlement")));
}

TEST(GeneratorParameters, RefusalsNameTheGeneratorAndTheParameter) {
  const auto error_of = [](const std::string& g, const json& v) -> std::string {
    try {
      generate_case(g, v);
    } catch (const CaseError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of("circular-arch", {{"thikness", 0.1}}).find("no parameter 'thikness' (it has radius, thickness"), std::string::npos);
  EXPECT_NE(error_of("circular-arch", {{"voussoirs", 12.5}}).find("parameter 'voussoirs': must be a whole number"), std::string::npos);
  EXPECT_NE(error_of("circular-arch", {{"fixed", 1}}).find("parameter 'fixed': must be true or false"), std::string::npos);
  EXPECT_NE(error_of("circular-arch", {{"radius", "1"}}).find("parameter 'radius': must be a number"), std::string::npos);
  EXPECT_NE(error_of("no-such", json::object()).find("no case generator 'no-such'"), std::string::npos);
  // Geometry the generator refuses: its own message.
  EXPECT_NE(error_of("cathedral", {{"nave-thickness", 2.0}}).find("thinner than the pier"), std::string::npos);
  // A whole number written as 12.0 is an integer.
  EXPECT_EQ(error_of("circular-arch", {{"voussoirs", 12.0}}), "");
}

// cases/README.md: the upper flyer's head top lies at the nave springing (30.2 + 0.8 = 31.0 m);
// upper-flyer-at-springing keeps it there when the springing or the flyer thickness change.
TEST(GeneratorParameters, UpperFlyerAtTheSpringing) {
  const auto blocks = [](const Case& c) {
    std::ostringstream s;
    s.precision(17);
    for (const Block& b : c.blocks) {
      s << b.id;
      for (const Vec2& v : b.vertices) s << " " << v.x() << "," << v.y();
      s << "\n";
    }
    return s.str();
  };
  EXPECT_EQ(blocks(generate_case("cathedral-settlement", {{"upper-flyer-at-springing", true}})), blocks(standard_case("cathedral-settlement")));
  const double springing = 32.0, t = 1.0;
  const Case c = generate_case("cathedral", {{"upper-flyer-at-springing", true}, {"nave-springing", springing}, {"flyer-thickness", t}});
  // The head joint: the voussoir's face on the pier (its least x), from springing - t to the springing.
  const Block& head = c.blocks.at(c.block_index("R-flyer-up-00"));
  double face = 1e9;
  for (const Vec2& v : head.vertices) face = std::min(face, v.x());
  std::vector<double> ys;
  for (const Vec2& v : head.vertices)
    if (v.x() == face) ys.push_back(v.y());
  std::sort(ys.begin(), ys.end());
  ASSERT_EQ(ys.size(), 2u);
  EXPECT_NEAR(ys[0], springing - t, 1e-9);
  EXPECT_NEAR(ys[1], springing, 1e-9);
}

}  // namespace
}  // namespace masonry
