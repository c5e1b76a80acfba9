// The DEM's convergence study: the same case at the default settings and at settings that must
// not change a quasi-static answer (loading twice as slow, half the increment, another damping,
// half the time step, joints three times stiffer and softer, the holds' damping, contact damping,
// more friction). Running them is runs/parallel.hpp's business, reading the spread
// compare/convergence.hpp's.
#pragma once

#include <string>
#include <vector>

#include "dem/dem.hpp"

namespace masonry {

struct DemVariant {
  std::string name;  // file-name safe: the run's directory
  std::string what;  // what differs from the default, for tables
  DemSettings settings;
};

// The default first, then one variation per setting that must not matter.
std::vector<DemVariant> convergence_variants(const DemSettings& base);

// The joint-stiffness study: the default first, then the joints (kn and ks together) 10 and 3
// times softer and 3, 10 and 30 times stiffer. PRD's blocks are rigid, the limit of stiffening
// joints; the elastic gaps and the elastic settling shrink as 1/kn. So this measures whether a
// difference from PRD is elastic (it shrinks as the joints stiffen), not whether the protocol
// converged: stiffness is a property of the structure, not a setting that must not matter.
std::vector<DemVariant> stiffness_variants(const DemSettings& base);

}  // namespace masonry
