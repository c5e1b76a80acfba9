// The fuzz test of the sweep's ways in: seeded mutations (tests/fuzz.hpp) of the example sweep
// file, planned against its case, and of a sweep.csv being resumed. A mutant is planned or
// refused with one line naming the file; a resumed table keeps only rows a run could have given.
#include "fuzz.hpp"

#include <gtest/gtest.h>

#include "util.hpp"

namespace masonry {
namespace {

const std::string kSpec = std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block-sweep.json";

TEST(Fuzz, MutatedSweepFilesPlanOrAreRefusedInOneLine) {
  const std::string original = test::read(kSpec), case_text = test::read(test::kTiltCase);
  test::Mutator mutate(36);
  int planned = 0, refused = 0;
  for (int k = 0; k < 300; ++k) {
    try {
      const SweepPlan p = plan_sweep(SweepInput{mutate(original), "mutant.json", case_text, "tilting-block.json"});
      EXPECT_FALSE(p.runs.empty());
      ++planned;
    } catch (const std::exception& e) {
      const std::string msg = e.what();
      EXPECT_TRUE(dynamic_cast<const SweepError*>(&e) || dynamic_cast<const CaseError*>(&e)) << "mutant " << k << ": " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "mutant " << k << ": " << msg;
      EXPECT_NE(msg.find("mutant.json"), std::string::npos) << "mutant " << k << ": " << msg;
      ++refused;
    }
  }
  EXPECT_GT(planned, 0);
  EXPECT_GT(refused, 150);
}

TEST(Fuzz, AMutatedSweepTableResumesWithRowsARunCouldGive) {
  const SweepPlan p = plan_sweep(SweepInput{test::read(kSpec), "s.json", test::read(test::kTiltCase), "tilting-block.json"});
  SweepTable t(p.runs.size());
  for (size_t i = 0; i < t.size(); ++i) {
    SweepRow r;
    r.index = static_cast<int>(i);
    r.id = p.runs[i].id;
    r.method = p.runs[i].method;
    r.status = i % 5 == 4 ? RunStatus::error : RunStatus::collapse;
    r.capacity = 0.01 * static_cast<double>(i % 40);
    r.time_s = 0.5;
    r.message = i % 5 == 4 ? "dem: refused, \"quoted\", and cut" : "";
    t[i] = r;
  }
  const std::string csv = sweep_csv(p, t);
  test::Mutator mutate(3636);
  for (int k = 0; k < 300; ++k) {
    try {
      const SweepTable back = read_sweep_csv(p, mutate(csv), "sweep.csv");
      ASSERT_EQ(back.size(), p.runs.size());
      for (const auto& r : back) {
        if (!r) continue;
        EXPECT_GE(r->time_s, 0) << "mutant " << k;
        if (r->status != RunStatus::error) {
          EXPECT_GE(r->capacity, 0) << "mutant " << k;
          EXPECT_LE(r->capacity, 1.05 * p.base.motion.step * p.base.motion.max_steps) << "mutant " << k;
        }
      }
    } catch (const SweepError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "mutant " << k << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace masonry
