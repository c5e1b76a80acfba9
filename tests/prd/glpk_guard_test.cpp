// GLPK's internal errors end the one call that met them, not the process (prd/glpk_hooks.hpp).
// GLPK's error path is the same for a failed assertion inside the simplex (numbers it cannot
// handle) and for a parameter it refuses (glp_error, then the error hook): the refused
// parameter triggers it deterministically. Expected values come from GLPK's reference manual
// (an invalid glp_smcp::meth is an error; after glp_free_env GLPK starts a fresh environment)
// and from the LP itself (min x subject to x >= 1 is 1).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <thread>

#include "prd/internal.hpp"

namespace masonry {
namespace {

using namespace prd_detail;

// min x subject to x >= 1: a one-column LP whose optimum is 1.
GlpProblem small_lp() {
  GlpProblem p = new_glp_problem();
  glp_set_obj_dir(p.get(), GLP_MIN);
  glp_add_cols(p.get(), 1);
  glp_set_col_bnds(p.get(), 1, GLP_LO, 1.0, 0.0);
  glp_set_obj_coef(p.get(), 1, 1.0);
  return p;
}

// The LP solved through the guard: its objective, or NaN.
double solve_small(glp_prob* lp) {
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  const int rc = prd::glpk_guarded([&] { return glp_simplex(lp, &parm); });
  return rc == 0 && glp_get_status(lp) == GLP_OPT ? glp_get_obj_val(lp) : NAN;
}

// A simplex call GLPK refuses: an error inside GLPK.
int refused_call(glp_prob* lp) {
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.meth = 12345;
  return glp_simplex(lp, &parm);
}

TEST(GlpkGuard, AnErrorInGlpkIsTheCallersExceptionAndGlpkWorksAfter) {
  prd::install_glpk_hooks();
  const unsigned before = prd::glpk_generation();
  GlpProblem held = small_lp();  // made before the error: freed by it, never deleted again
  ASSERT_DOUBLE_EQ(solve_small(held.get()), 1.0);
  std::string what;
  try {
    prd::glpk_guarded([&] { return refused_call(held.get()); });
    ADD_FAILURE() << "GLPK accepted meth = 12345";
  } catch (const prd::GlpkError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("meth = 12345"), std::string::npos) << what;  // GLPK's own text, one line
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  EXPECT_EQ(prd::glpk_generation(), before + 1);
  // A fresh environment: problems made now solve as before.
  GlpProblem again = small_lp();
  EXPECT_DOUBLE_EQ(solve_small(again.get()), 1.0);
}

TEST(GlpkGuard, AnErrorOnOneThreadLeavesAnotherThreadsProblems) {
  GlpProblem mine = small_lp();
  ASSERT_DOUBLE_EQ(solve_small(mine.get()), 1.0);
  bool thrown = false;
  std::thread other([&] {
    GlpProblem theirs = small_lp();
    try {
      prd::glpk_guarded([&] { return refused_call(theirs.get()); });
    } catch (const prd::GlpkError&) {
      thrown = true;
    }
  });
  other.join();
  EXPECT_TRUE(thrown);
  // GLPK's environment is per thread: this one's problem is untouched.
  EXPECT_DOUBLE_EQ(solve_small(mine.get()), 1.0);
}

TEST(GlpkGuardDeathTest, AnErrorOutsideAGuardIsABugAndAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        prd::install_glpk_hooks();
        GlpProblem p = small_lp();
        refused_call(p.get());
      },
      "outside the guarded solves");
}

}  // namespace
}  // namespace masonry
