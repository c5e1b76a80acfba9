// The checked-in standard case files are exactly what the generators write, and load.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "case_checks.hpp"
#include "cases/generators.hpp"

namespace masonry {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(StandardFiles, EqualWhatTheGeneratorsWrite) {
  ASSERT_EQ(standard_cases().size(), 3u);
  for (const StandardCase& s : standard_cases()) {
    const std::string path = std::string(MASONRY_SOURCE_DIR) + "/cases/" + s.name + ".json";
    const std::string file = read(path);
    ASSERT_FALSE(file.empty()) << path << " is missing: run `masonry cases " << s.name << " --out " << path << "`";
    // Byte for byte: regenerate with `masonry cases NAME --out cases/NAME.json` after a change.
    EXPECT_TRUE(file == case_to_json(standard_case(s.name))) << path << " differs from the generator's output";
    const Case c = load_case(path);
    EXPECT_EQ(c.name, s.name);
    test::expect_valid_case(c);
  }
}

TEST(StandardFiles, TheCommandWritesThem) {
  // `masonry cases NAME --out FILE` with no parameters writes the standard file.
  for (const StandardCase& s : standard_cases()) {
    const std::string out = ::testing::TempDir() + "/standard-" + s.name + ".json";
    const std::string cmd = std::string(MASONRY_EXE) + " cases " + s.name + " --out " + out + " 2>/dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    EXPECT_TRUE(read(out) == case_to_json(standard_case(s.name))) << s.name;
  }
  EXPECT_EQ(std::system((std::string(MASONRY_EXE) + " cases --list > /dev/null").c_str()), 0);
  EXPECT_NE(std::system((std::string(MASONRY_EXE) + " cases no-such-case --out x.json 2>/dev/null").c_str()), 0);
}

TEST(StandardFiles, Parameters) {
  // The parameters, from the paper (Sections 3 and 4).
  const PointedArch a = standard_pointed_arch();
  EXPECT_DOUBLE_EQ(a.rcirc, 1.0);
  EXPECT_DOUBLE_EQ(a.thickness / a.rcirc, 0.12);
  EXPECT_NEAR(a.embrace, 150.0 * 3.14159265358979323846 / 180, 1e-15);
  EXPECT_EQ(a.voussoirs, 14);
  EXPECT_DOUBLE_EQ(a.density, 1800.0);
  EXPECT_DOUBLE_EQ(a.step, 0.001);
  EXPECT_GE(a.eccentricity / a.rcirc, 0.0);
  EXPECT_LE(a.eccentricity / a.rcirc, 0.3);
  const Case arch = standard_case("pointed-arch");
  ASSERT_EQ(arch.motion.supports.size(), 1u);
  EXPECT_EQ(arch.blocks[arch.motion.supports[0].block].id, "right");
  EXPECT_EQ(arch.motion.supports[0].translation, Vec2(1, 0));
  for (const std::string name : {"cathedral-settlement", "cathedral-settlement-rotation"}) {
    const Case c = standard_case(name);
    ASSERT_EQ(c.motion.supports.size(), 1u);
    const SupportMotion& m = c.motion.supports[0];
    EXPECT_EQ(c.blocks[m.block].id, "support-3");
    EXPECT_NEAR(m.translation.y() * c.motion.step, -0.01, 1e-15);
    EXPECT_NEAR(m.rotation * c.motion.step, name == "cathedral-settlement" ? 0.0 : 0.001, 1e-15);
  }
}

}  // namespace
}  // namespace masonry
