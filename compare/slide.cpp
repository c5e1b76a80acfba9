// A slide one run made and the other did not, against the supports' travel (compare/slide.hpp;
// compare/README.md, "A slide statics does not ask for").
#include "compare/slide.hpp"

#include <cmath>

#include "compare/compare.hpp"

namespace masonry {

std::optional<SlideSuspect> slide_suspect(const Case& c, const Comparison& k) {
  if (!k.sliding || k.sliding->largest_b.joint < 0) return std::nullopt;
  const SlipCheck& s = *k.sliding;
  const double travel = path_travel_per_d(c) * std::abs(s.b_to);
  const double limit = kUnexplainedSlide * travel;
  const JointSlip& j = s.largest_b;
  if (!(travel > 0) || !(j.b > limit)) return std::nullopt;
  // Where the other run's joint slid as far, the runs agree on a sliding mechanism.
  if (j.a >= limit) return std::nullopt;
  return SlideSuspect{j.label, j.b, j.a, travel, s.b_to};
}

}  // namespace masonry
