// Case generators: parametric structures written as Case values (and, through
// case_to_json, as case files). SI units; angles in rad unless a name says deg.
// The geometry of every generator, and where its dimensions come from, is in cases/README.md.
#pragma once

#include <string>
#include <vector>

#include "model/case.hpp"

namespace masonry {

// A circular arch of `voussoirs` convex quadrilateral voussoirs with joints normal to the
// centreline (radial), centred on the origin, symmetric about x = 0, standing on two support
// blocks ("left", "right") whose top faces are the springing joints and whose bases are
// horizontal, `thickness` below the lower springing point. The voussoirs are "v0" (left) to
// "v<n-1>" (right). With `spreading` the right support moves outward (+x) by `step` per step.
struct CircularArch {
  double radius = 1.0;                      // centreline radius R, m
  double thickness = 0.12;                  // t, m
  double embrace = 3.14159265358979323846;  // angle of embrace, rad (pi: semicircle)
  int voussoirs = 20;
  double depth = 1.0;       // m
  double density = 1800.0;  // kg/m^3
  bool spreading = true;    // the right support moves outward
  double step = 0.001;      // m
  int max_steps = 2000;
};
Case circular_arch(const CircularArch& p);

// A two-centred pointed arch in the notation of Romano & Ochsendorf (2010), as used by the
// paper (Section 3.1):
//   Rcirc  centreline radius of the circular arch of the same angle of embrace,
//   e      eccentricity: each half is a circular arc whose centre lies e from the axis, on the
//          opposite side (left half centred at (+e, 0), right half at (-e, 0)),
//   Rpoint = Rcirc + e, the centreline radius of each half,
//   t      thickness (intrados radius Rpoint - t/2, extrados Rpoint + t/2),
//   alpha  angle of embrace: the angle between the two springing joints, exactly as for the
//          circular arch, so the springing joints are radial at pi/2 + alpha/2 (left, about the
//          left centre) and pi/2 - alpha/2 (right, about the right centre). With alpha = pi the
//          span of the centreline stays 2 Rcirc whatever e (R&O's convention).
// The centreline of the left half runs from the springing angle down to the crown angle
// pi/2 + gamma, gamma = asin(e / Rpoint), where it meets the axis; each half subtends
// beta = alpha/2 - gamma. The voussoirs divide the two halves into `voussoirs` equal angles
// delta = 2 beta / n (so equal centreline lengths). Joints are radial about their half's centre
// except on the axis:
//   - n even: the crown joint is the vertical segment of the axis between the intrados apex
//     (0, sqrt(ri^2 - e^2)) and the extrados apex (0, sqrt(re^2 - e^2)); the n/2 voussoirs of
//     each half are quadrilaterals;
//   - n odd: a keystone straddles the axis between the last radial joints of the two halves;
//     its extrados has a vertex at the extrados apex, its intrados is the chord between its two
//     lower corners (following the pointed intrados would make it non-convex), a pentagon.
// With e = 0 both rules fall back on the circular arch's radial joints and the result is
// circular_arch() with the same radius, thickness, embrace and voussoirs, bit for bit.
// Supports, ids and motion as in circular_arch ("left", "v0".."v<n-1>", "right").
struct PointedArch {
  double rcirc = 1.0;                                       // Rcirc, m
  double eccentricity = 0.0;                                // e, m (standard case: see standard_case("pointed-arch"))
  double thickness = 0.12;                                  // t, m
  double embrace = 150.0 * 3.14159265358979323846 / 180.0;  // alpha, rad
  int voussoirs = 14;
  double depth = 1.0;       // m
  double density = 1800.0;  // kg/m^3
  bool spreading = true;    // the right support moves outward (+x)
  double step = 0.001;      // m
  int max_steps = 400;
};
Case pointed_arch(const PointedArch& p);

// The cross-section of a Gothic cathedral after the paper's Section 4 (an approximation of
// Amiens): symmetric about x = 0, ground at y = 0. From the axis outwards on each side: the nave
// pier, the aisle, the outer buttress (culee); the nave arch spans between the two piers, each
// aisle arch between a pier and a buttress, two flying buttresses (lower, upper) between each
// buttress and the upper shaft of the nave pier. Every pier and buttress stands on a support
// block (its foundation): "support-1" .. "support-4" from the left, so the paper's "third pier
// from the left" is "support-3", under the right nave pier.
// Every dimension, its source or reasoning, and the derived geometry are documented in
// cases/README.md ("Gothic cathedral") and in cathedral.cpp.
struct GothicCathedral {
  // Main dimensions (paper, Fig. 13): intrados crown heights and the bay.
  double nave_height = 42.0;   // intrados crown of the nave arch (nave vault), m
  double aisle_height = 19.0;  // intrados crown of the aisle arches (aisle vaults), m
  double bay = 7.3;            // distance between cross-sections: depth of arches (vaults), m
  // Chosen dimensions: not in the paper's text (its Fig. 13 is not available); High Gothic and
  // Amiens proportions, reasoning in cases/README.md. None was tuned towards a capacity.
  double nave_span = 12.8;         // clear, between pier faces: Amiens ~14.6 m between pier axes
  double pier_width = 1.8;         // pier shaft; Amiens' cantoned piers are ~2 m across
  double aisle_span = 7.0;         // clear; the aisle about half the nave, as at Amiens
  double buttress_width = 4.0;     // culee above the aisle springing (deep, ~1/3 nave span)
  double nave_springing = 31.0;    // pier top: 11 m rise over 12.8 m, near-equilateral (e/Rcirc 0.92)
  double aisle_springing = 13.0;   // 6 m rise over 7 m, the same profile (e/Rcirc 0.89)
  double nave_thickness = 0.8;     // nave arch, radial: a transverse rib with the web lumped in, ~span/16
  double aisle_thickness = 0.6;    // aisle arch, radial, ~span/12 (also the ledges it springs from)
  double flyer_thickness = 0.8;    // flying buttresses, radial (Amiens' are ~0.8-1 m deep)
  double lower_flyer_head = 24.0;  // intrados of the lower flyer's head on the pier, m
  double lower_flyer_foot = 20.0;  // intrados of its foot on the buttress (clears the aisle extrados, 19.6 m)
  double upper_flyer_head = 30.2;  // head top at the nave springing, where the nave arch thrusts
  // Place the upper flyer's head top at the nave springing whatever the springing and the flyer
  // thickness (upper_flyer_head = nave_springing - flyer_thickness: 30.2 m with the defaults),
  // for studies that vary either (sweep/README.md).
  bool upper_flyer_at_springing = false;
  double upper_flyer_foot = 26.0;  // on the buttress' second stage
  double buttress_height = 33.0;   // a stage above the upper seat (26.5 m)
  double foundation_height = 1.0;  // support blocks, m
  // Out-of-plane depths (paper, Fig. 13b: arches and vaults get the bay).
  double pier_depth = 2.0;
  double buttress_depth = 2.0;
  double flyer_depth = 1.0;
  double density = 1800.0;  // kg/m^3
  // Discretisation.
  double course = 1.0;       // target height of the courses of piers and buttresses, m
  int nave_voussoirs = 42;   // even: the crown joint lies on the axis (42: 276 blocks in all)
  int aisle_voussoirs = 20;  // even
  int flyer_voussoirs = 17;
  // Prescribed motion of one support per step: settlement (down) and a counter-clockwise turn
  // about the support's centroid. Both zero: no motion (the structure as it stands).
  int moving_support = 3;        // 1..4 from the left
  double settlement_step = 0.0;  // m per step
  double rotation_step = 0.0;    // rad per step
  double step = 0.01;            // m of the path parameter d per step
  int max_steps = 300;
};
Case gothic_cathedral(const GothicCathedral& p);

// A brick wall in elevation (cases/README.md, "Brick wall"): `courses` courses of `course_height`,
// each of `bricks` units laid in a bond, on two support blocks that split the ground at
// `ground_split` (m from the wall's left end); one of them settles and/or turns. Left end of the
// wall at x = 0, its base at y = 0. Block ids: "c<course>-<k>" (course 0 at the bottom, k from
// the left), "lintel-<o>", "arch-<o>-v<k>" (voussoirs), "arch-<o>-s<k>" (spandrel pieces),
// "ground-left", "ground-right".
//   running: stretchers of brick_length, alternate courses offset by half a brick (half bricks
//            at the ends);
//   stack:   stretchers, every head joint on one vertical line;
//   header:  headers of header_length (the brick's width), alternate courses offset by half a
//            header.
enum class WallBond { running, stack, header };
const char* wall_bond_name(WallBond b);  // "running", "stack", "header": the CLI's words
// An opening: its left edge x, sill and height (m, from the wall's left end and base; sill and
// top are moved to the nearest course joint), closed above by a lintel (one course high,
// bearing `lintel_bearing` on each side) or a semicircular arch of `arch_voussoirs` voussoirs
// (0: about one per course height of the centreline) whose span is the opening's width and
// whose springing is the opening's top; the arch's ring is `arch_thickness` thick and its
// spandrels are cut radially up to the first course joint half a course above the extrados.
enum class OpeningTop { lintel, arch };
struct WallOpening {
  double x = 0, sill = 0, width = 0, height = 0;  // m
  OpeningTop top = OpeningTop::lintel;
};
// Which ground block moves: the part left or right of the split, or neither.
enum class MovingGround { none, left, right };
struct BrickWall {
  WallBond bond = WallBond::running;
  int courses = 10;
  int bricks = 10;               // units per course: stretchers (running, stack) or headers
  double brick_length = 0.25;    // m
  double header_length = 0.125;  // m: a header's face (the brick's width), header bond
  double course_height = 0.125;  // m
  double depth = 0.25;           // out-of-plane thickness of the wall, m
  double density = 1800.0;       // kg/m^3
  std::vector<WallOpening> openings;
  double lintel_bearing = 0.125;  // m, on each side of an opening
  double arch_thickness = 0.125;  // m
  int arch_voussoirs = 0;
  double ground_height = 0.25;  // m
  double ground_split = -1;     // m from the left end; < 0: the middle
  MovingGround moving = MovingGround::right;
  double settlement_step = 0.001;  // m down per step
  double rotation_step = 0.0;      // rad counter-clockwise per step, about the split's top point
  double step = 0.001;             // m of d per step
  int max_steps = 100;
};
Case brick_wall(const BrickWall& p);
// Parses "X,SILL,WIDTH,HEIGHT[,lintel|arch]" (m); throws CaseError naming the text.
WallOpening parse_wall_opening(const std::string& text);

// The standard scenes checked in under cases/ ("pointed-arch", "cathedral-settlement",
// "cathedral-settlement-rotation"): name, one-line summary, and the case itself.
struct StandardCase {
  std::string name;
  std::string summary;
};
std::vector<StandardCase> standard_cases();
// Parameters of the standard scenes (the generators' defaults where they coincide).
PointedArch standard_pointed_arch();
GothicCathedral standard_cathedral_settlement();
GothicCathedral standard_cathedral_settlement_rotation();
Case standard_case(const std::string& name);  // throws CaseError for an unknown name

}  // namespace masonry
