// The fuzz test of the ways in a person writes by hand or by a drawing program: seeded mutations
// (tests/fuzz.hpp) of the example drawings and the standard case files. Each mutant is imported
// or loaded, or refused with one line naming the file; nothing crashes, hangs, or escapes as any
// other exception. CI runs it in the Release build and under AddressSanitizer and UBSan.
#include "fuzz.hpp"

#include <gtest/gtest.h>

#include "cases/dxf.hpp"
#include "common.hpp"
#include "model/case.hpp"

namespace masonry {
namespace {

using test::Scratch;
const std::string kSource = MASONRY_SOURCE_DIR;

// One line naming the file: what every refusal must be.
void expect_refusal(const std::string& msg, const std::string& file, int k) {
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "mutant " << k << ": " << msg;
  EXPECT_NE(msg.find(file), std::string::npos) << "mutant " << k << ": " << msg;
}

TEST(Fuzz, MutatedDrawingsImportOrAreRefusedInOneLine) {
  struct Drawing {
    std::string name;
    DxfImportOptions o;
  };
  std::vector<Drawing> drawings(2);
  drawings[0].name = "tilting-block";
  drawings[0].o.layers_file = kSource + "/cases/drawings/layers.json";
  drawings[1].name = "pointed-arch";
  drawings[1].o.density = 1800;
  Scratch dir("fuzz-dxf");
  const std::string path = (dir.path / "mutant.dxf").string();
  for (Drawing& d : drawings) {
    d.o.merge_file = kSource + "/cases/drawings/" + d.name + ".fragment.json";
    const std::string original = test::read(kSource + "/cases/drawings/" + d.name + ".dxf");
    test::Mutator mutate(static_cast<uint32_t>(d.name.size()));
    int imported = 0, refused = 0;
    for (int k = 0; k < 300; ++k) {
      test::write(path, mutate(original));
      try {
        const DxfImport imp = import_dxf(path, d.o);
        EXPECT_FALSE(imp.c.blocks.empty());
        ++imported;
      } catch (const CaseError& e) {
        expect_refusal(e.what(), path, k);
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << d.name << " mutant " << k << ": not a CaseError: " << e.what();
      }
    }
    // The mutations both keep drawings importable (a comment, a repeated handle) and break them.
    EXPECT_GT(imported, 0) << d.name;
    EXPECT_GT(refused, 150) << d.name;
  }
}

TEST(Fuzz, MutatedCaseFilesLoadOrAreRefusedInOneLine) {
  for (const char* name : {"tilting-block", "pointed-arch"}) {
    const std::string original = test::read(kSource + "/cases/" + name + ".json");
    test::Mutator mutate(static_cast<uint32_t>(std::string(name).size()) + 100);
    int loaded = 0, refused = 0;
    for (int k = 0; k < 300; ++k) {
      try {
        const Case c = parse_case(mutate(original), "mutant.json");
        EXPECT_FALSE(c.blocks.empty());
        ++loaded;
      } catch (const CaseError& e) {
        expect_refusal(e.what(), "mutant.json", k);
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " mutant " << k << ": not a CaseError: " << e.what();
      }
    }
    EXPECT_GT(loaded, 0) << name;
    EXPECT_GT(refused, 150) << name;
  }
}

}  // namespace
}  // namespace masonry
