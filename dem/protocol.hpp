// The stages of the DEM's quasi-static loading protocol (dem/README.md, "Protocol"): the hold,
// which cycles with the supports still until equilibrium or evidence of collapse, and the move,
// which carries the supports from one path parameter to the next at a speed the structure's
// kinetic energy allows. Internal to dem/: dem_run strings them together.
#pragma once

#include <cmath>
#include <vector>

#include "dem/dem.hpp"

namespace masonry::dem {

enum class HoldEnd {
  equilibrium,  // unbalanced-force ratio and block speeds below their tolerances
  collapse,     // a block drifted past collapse_drift, or the kinetic energy kept growing
  // The cap came first and the structure was still moving without slowing down: over the cap's
  // second half it travelled at least kCreepRatio of what it travelled over the first (see
  // hold()). No equilibrium within reach: at the capacity of a structure, the growth of the
  // collapse mode tends to zero, and this is how a hold just past it ends.
  creep,
  undecided,  // the cap came first while the motion was still dying out (after kExtensions more caps)
};
const char* hold_end_name(HoldEnd e);

// What the stages need besides the model and the settings.
struct Limits {
  double collapse_drift = 0;  // m
  // m: the largest block displacement a move may carry, its support travel plus collapse_drift;
  // beyond it the structure collapsed during the move (a slow move can carry a whole toppling).
  double move_drift = INFINITY;
  double energy_floor = 0;  // J, floor of the blow-up guard
  // The move's largest acceleration of the path parameter, m/s^2 per m/m of travel (d's units
  // per s^2): the servo never speeds the supports up or brakes them faster (see move()).
  double move_accel = INFINITY;
  // J: kinetic energy above which, growing over consecutive windows of a hold, the structure is
  // running away (infinite: only the drift decides, as for the settling at d = 0).
  double ke_collapse = 0;
  // m: the least travel over half a cap that counts as motion in the hold's verdict at the cap
  // (below it a creep is not told from round-off and the last vibrations).
  double creep_floor = 0;
  // Whether a hold calls a motion far out and speeding up a collapse before it has drifted
  // collapse_drift (over the cap's early windows and at the cap). Off while dem_run's follow
  // stage holds a creep on to see where it ends (ke_collapse infinite then too): a hinge passing
  // to another joint moves that far, speeding up, and then settles.
  bool read_early = true;
};

struct HoldOutcome {
  HoldEnd end = HoldEnd::undecided;
  double drift = 0;  // m, largest block displacement since the hold began
  // At the cap (creep, undecided): the largest block travel over the last cap's first and second
  // halves, m (0 for a hold that ended before its cap).
  double first_half = 0, second_half = 0;
  long long cycles = 0;
  double time = 0;  // s of model time
};

// Free blocks' centroids, and the largest distance a free block has moved from them, m.
std::vector<Vec2> positions(const DemModel& m, const Case& c);
double largest_move(const DemModel& m, const Case& c, const std::vector<Vec2>& from);
// The largest distance between two sets of the free blocks' centroids, m.
double largest_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b, const Case& c);

// Cycles with the supports where they are until one of the ends. Throws
// std::runtime_error when the state turns non-finite or the energy balance is broken. With
// `watch` > 0 an equilibrium reached before `watch` cycles (or the cap) does not end the hold:
// the collapse criteria go on being checked, and only an equilibrium after that ends it. A
// structure tipping past an unstable equilibrium starts from rest with an unbalanced force
// below the tolerance, so it meets the equilibrium criteria at first and only its growing motion
// shows what it is. `drift_from` (default: where the hold starts) is where the collapse drift
// counts from: a creep held on hold after hold (dem_run's follow stage) has fallen once it is
// collapse_drift from where the following began, however many holds that took.
HoldOutcome hold(DemModel& m, const Case& c, const DemSettings& s, const Limits& lim, long long watch = 0,
                 const std::vector<Vec2>* drift_from = nullptr);

struct MoveOutcome {
  bool collapsed = false;  // a block moved farther than lim.move_drift: the move stopped there
  long long cycles = 0;
  double speed = 0;  // the support speed (of d, m/s) at the end of the move
};

// Carries the supports from path parameter d0 to d1. Servoed (move_time 0): the speed grows by
// 0.2% per cycle while every block's kinetic energy over its weight is below `ke_height` (m) and
// shrinks by 2% per cycle while some block's is above and while braking to stop at d1 (cycles of
// the default time-step factor: the rates are kept in model time at any other), starting
// from `start_speed`, never below (d1 - d0) / hold_time; with move_time > 0, the constant-speed
// move with half-cosine ramps.
MoveOutcome move(DemModel& m, const Case& c, const DemSettings& s, double d0, double d1, double ke_height, double start_speed, const Limits& lim);

}  // namespace masonry::dem
