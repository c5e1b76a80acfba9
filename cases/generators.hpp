// Case generators: parametric structures written as Case values (and, through
// case_to_json, as case files). SI units; angles in rad unless a name says deg.
#pragma once

#include "case.hpp"

namespace masonry {

// A circular arch of `voussoirs` convex quadrilateral voussoirs with joints normal to the
// centreline (radial), centred on the origin, symmetric about x = 0, standing on two support
// blocks ("left", "right") whose top faces are the springing joints and whose bases are
// horizontal, `thickness` below the lower springing point. The voussoirs are "v0" (left) to
// "v<n-1>" (right). With `spreading` the right support moves outward (+x) by `step` per step.
struct CircularArch {
  double radius = 1.0;        // centreline radius R, m
  double thickness = 0.12;    // t, m
  double embrace = 3.14159265358979323846;  // angle of embrace, rad (pi: semicircle)
  int voussoirs = 20;
  double depth = 1.0;         // m
  double density = 1800.0;    // kg/m^3
  bool spreading = true;      // the right support moves outward
  double step = 0.001;        // m
  int max_steps = 2000;
};
Case circular_arch(const CircularArch& p);

}  // namespace masonry
