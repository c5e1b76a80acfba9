// The fuzz test of the catalogue format (masonry-catalogue/1): seeded mutations (tests/fuzz.hpp)
// of the built-in catalogue. A mutant parses or is refused with one line naming the file.
#include "fuzz.hpp"

#include <gtest/gtest.h>

#include "common.hpp"
#include "validate/catalogue.hpp"

namespace masonry {
namespace {

TEST(Fuzz, MutatedCataloguesParseOrAreRefusedInOneLine) {
  const std::string original = test::read(std::string(MASONRY_SOURCE_DIR) + "/validate/catalogue.json");
  test::Mutator mutate(14);
  int parsed = 0, refused = 0;
  for (int k = 0; k < 300; ++k) {
    try {
      const Catalogue c = parse_catalogue(mutate(original), "mutant.json", MASONRY_SOURCE_DIR);
      EXPECT_FALSE(c.benchmarks.empty());
      ++parsed;
    } catch (const CaseError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "mutant " << k << ": " << msg;
      EXPECT_NE(msg.find("mutant.json"), std::string::npos) << "mutant " << k << ": " << msg;
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutant " << k << ": not a CaseError: " << e.what();
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace masonry
