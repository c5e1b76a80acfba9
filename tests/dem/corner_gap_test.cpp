// The gap at a joint corner (corner_gap): a block turning about its corner on a longer face opens
// its other corner by L sin(theta) and keeps the turning corner closed, however far the joint
// has slipped; both copies pressed into each other read the overlap. Expected values from the
// geometry of a rigid turn and slide.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/dem.hpp"

namespace masonry {
namespace {

// Block i's face is the x axis (its outward normal +y, into block j); block j's joint face runs
// from P = (0, 0) to Q = (L, 0) before it turns by theta about P and then slides by s along the
// face (block i's face runs on past both: the pier's top under the voussoir).
struct TurnAndSlide {
  double L, theta, s;
  Vec2 ni{0, 1};
  Vec2 nj() const { return Vec2(std::sin(theta), -std::cos(theta)); }  // (0, -1) turned by theta
  Vec2 moved(const Vec2& p) const {                                    // a point of block j
    const double c = std::cos(theta), n = std::sin(theta);
    return Vec2(c * p.x() - n * p.y() + s, n * p.x() + c * p.y());
  }
  double gap(const Vec2& corner) const { return corner_gap(corner, ni, moved(corner), nj()); }
};

TEST(DemCornerGap, TheCornerATurnIsAboutStaysClosedWhateverTheSlip) {
  const double L = 0.8;
  for (double theta : {0.01, 0.07}) {
    for (double s : {-3e-4, 0.0, 3e-4}) {
      const TurnAndSlide j{L, theta, s};
      // The turning corner: block j's copy sits on block i's face (0); block i's copy, a point of
      // its face that the slip carried away, stands |s| sin(theta) off j's turned face on one side
      // of the slip and inside it on the other. Closed either way.
      EXPECT_LE(j.gap(Vec2(0, 0)), 1e-15) << "theta " << theta << ", slip " << s;
      // The other corner opens by L sin(theta), to within the slip's own term.
      EXPECT_NEAR(j.gap(Vec2(L, 0)), L * std::sin(theta), std::abs(s) * std::sin(theta) + 1e-15) << "theta " << theta << ", slip " << s;
    }
  }
  // The cathedral's springing at joints 30 times stiffer: with 0.3 mm of slip at 70 mrad block
  // i's copy of the turning corner stands 21 um off j's turned face, twice the 10 um at which the
  // DEM calls a corner open, so the larger of the two readings would call it open; the gap does
  // not.
  const TurnAndSlide x{L, 0.07, -3e-4};
  const Vec2 p(0, 0);
  EXPECT_GT((p - x.moved(p)).dot(x.nj()), 2e-5);
  EXPECT_LE(x.gap(p), 0.0);
}

TEST(DemCornerGap, PressedTogetherTheCornerReadsTheOverlap) {
  const Vec2 ni(0, 1), nj(0, -1);
  const double overlap = 2.7e-6;
  const Vec2 p(0.3, 0.0);
  EXPECT_NEAR(corner_gap(p, ni, p - overlap * ni, nj), -overlap, 1e-18);
  EXPECT_NEAR(corner_gap(p, ni, p + 1e-3 * ni, nj), 1e-3, 1e-18);  // lifted straight off: open
}

}  // namespace
}  // namespace masonry
