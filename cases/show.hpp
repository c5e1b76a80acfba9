// Seeing a case before running it: an SVG drawing of what the solvers will get.
#pragma once

#include <string>

#include "model/case.hpp"

namespace masonry {

// The blocks (one <polygon class="block"> each, supports hatched, with data-id), their ids, the
// joints the loader detects (<line class="joint">), the point loads and the support motion as
// arrows. Case coordinates in metres, y up (the SVG flips it).
std::string case_svg(const Case& c);

}  // namespace masonry
