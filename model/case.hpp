// The case model shared by every method: blocks, loads, the prescribed support motion and the
// per-method options. SI units throughout: lengths in m, forces in N, density in kg/m^3,
// gravity in m/s^2, rotations in rad. The one exception is friction_angle, in degrees, as
// every masonry text quotes it.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/geometry.hpp"

namespace masonry {

// m: how far from the origin a vertex, load point or pivot may lie (README, "Ranges"): 100 km,
// far beyond any structure, near enough that every derived quantity keeps its digits.
inline constexpr double kMaxCoordinate = 1e5;

// Bad input: the message is one line naming the file, the block and the field.
struct CaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Block {
  std::string id;
  std::vector<Vec2> vertices;  // counter-clockwise after loading (input may be either way)
  double depth = 1.0;          // out-of-plane thickness, m
  double density = 0.0;        // kg/m^3; unused for supports
  bool support = false;        // prescribed motion (or fixed), no unknowns
};

struct Load {
  int block = -1;    // index into Case::blocks
  Vec2 force{0, 0};  // N, dead load: keeps its direction as the block moves
  Vec2 point{0, 0};  // m, material point of the block, in the initial configuration
};

// Per unit of the path parameter d, a support translates by `translation` and turns by
// `rotation` about `about`, a point attached to it (initial configuration).
struct SupportMotion {
  int block = -1;
  Vec2 translation{0, 0};  // m per m of d
  double rotation = 0.0;   // rad per m of d
  Vec2 about{0, 0};
};

struct Motion {
  double step = 0.001;  // increment of d per step, m
  int max_steps = 1000;
  std::vector<SupportMotion> supports;
};

// PRD's settings, the case's "prd" section; prd/prd.hpp's PrdSettings adds the motion's increment
// to them; nothing else declares them. Each field's key, range, unit, help and flag are its row in
// model/options.cpp (as for Motion, DemOptions and Case::gravity).
struct PrdOptions {
  // Length (m) below which an endpoint's gap counts as closed; also the geometric tolerance of
  // interface detection.
  double contact_tolerance = 1e-5;
  // Event-driven stepping: moves up to max_step long while the mechanism stays the same, cut
  // short where the next event is predicted (a corner's force reaching 0, a gap closing), so
  // that every event (a corner opening or closing, collapse) is located within
  // event_tolerance; an event found at the end of a longer move is bracketed again by going
  // back. Whether a closed corner opens is judged by its opening rate over motion.step, so the
  // contact state does not depend on the step being taken. Besides the LPs, the predictions
  // evaluate an LP's basis at nearby configurations (timing.basis_evaluations).
  bool adaptive = false;
  double event_tolerance = 0.0;  // m; 0: 1e-4 of the scene size (0.1 mm for a metre-size scene)
  double max_step = 0.0;         // m; 0: the smaller of 16 * step and 0.4 sqrt(event_tolerance * scene size)
  // The sliding check on every recorded step (StepRecord::sliding; the run's summary in
  // RunResult::sliding, see sliding_summary). Angles in degrees, as friction angles are.
  bool sliding_check = false;
  // Joint corners kept closed over the whole run ("BLOCK/BLOCK:A", as results name them): the
  // mechanism the structure would follow if those corners could not open (they may carry
  // tension). Where two mechanisms release almost the same energy, holding the first one's hinge
  // shows the second one's capacity (dem/README.md, "The branch X").
  std::vector<std::string> hold_closed;
};

// How a hold brings the structure to rest at fixed supports (dem/README.md, "Holds: local or
// kinetic damping"): local damping alone, or kinetic damping on top of it (every free block
// stopped whenever the structure's kinetic energy passes a peak, so no momentum carries the
// structure through a hold).
enum class HoldDamping { local, kinetic };
// The case field's values, in the enum's order.
inline constexpr const char* kHoldDampingNames[] = {"local", "kinetic"};
const char* hold_damping_name(HoldDamping h);

// The DEM's settings, the case's "dem" section (dem/README.md has the model and the protocol).
// dem/dem.hpp's DemSettings adds the motion's increment to them; nothing else declares them.
struct DemOptions {
  double young_modulus = 3.0e10;  // Pa
  double poisson = 0.2;
  double friction_angle = 35.0;      // degrees; 90 means no slip limit
  std::optional<double> kn;          // Pa/m; default E / h_block, h_block = sqrt(mean free block area)
  std::optional<double> ks;          // Pa/m; default G / h_block, G = E / (2 (1 + nu))
  double stiffness_reduction = 1.0;  // kn and ks are divided by this (the paper used 10)
  double damping = 0.8;              // local non-viscous damping coefficient alpha in [0, 1)
  // Viscous damping at each contact point, as a fraction of the critical damping of the point's
  // own oscillator (its normal or shear spring against the two blocks' effective mass at the
  // point). Local damping opposes each block's own velocity, so it leaves alone a vibration of
  // the joints riding on a block's steady motion (a move, a lag, a creep); this damps the joints'
  // relative motion. 0: none (dem/README.md, "Contact damping").
  double contact_damping = 0.0;
  // dt = timestep_factor * dt_crit, dt_crit = 2 / omega_bound (see DemModel::critical_dt);
  // factors above 1 are refused.
  double timestep_factor = 1.0;
  double equilibrium_tolerance = 1e-4;  // largest unbalanced force / block weight at equilibrium
  double velocity_tolerance = 1e-5;     // largest block speed at equilibrium, m/s
  // Model-time cap of one hold, s: a hold ends on equilibrium or on evidence of collapse; one that
  // reaches this cap without either is "undecided" (never a capacity, never an error).
  double hold_time = 30.0;
  // The quasi-static protocol (dem/README.md). While the supports move, their speed is servoed so
  // that every block's kinetic energy stays below kinetic_ratio x its own weight x the support
  // travel over the move: the loading rate follows from the structure's own response. (A target
  // on the whole structure's energy over its whole weight let the light right aisle arch of
  // cathedral-settlement-rotation, carried by its moving pier, move fast enough to open the hinge
  // on the other side of its crown: dem/README.md, "The loading rate".)
  double kinetic_ratio = 1e-3;
  // move_time > 0 replaces the servo by a move at constant speed over that model time (s, the
  // paper's protocol), with smooth (half-cosine) speed ramps over `ramp_fraction` of it at each
  // end. A velocity that jumps from zero hits the structure with an elastic shock of v sqrt(k m):
  // a fast move (0.02 s per 4 mm on the test arch) makes the springing joint slip and inflates
  // the capacity (README.md). ramp_fraction = 0 is the paper's abrupt constant velocity.
  double move_time = 0.0;
  double ramp_fraction = 0.25;  // in [0, 0.5]
  // A hold that moves some block farther than this from where the hold began, without settling,
  // is a collapse, m; <= 0 means 2% of the scene size.
  double collapse_drift = 0.0;
  // Once an increment fails (collapse, or a hold that neither settles nor runs away), the run
  // goes back to the last equilibrium and bisects the failed increment until the bracket is
  // narrower than bracket_fraction x step (0: no bisection, the capacity is the last settled
  // increment).
  double bracket_fraction = 0.01;
  // A joint corner whose gap has grown by more than this since the settled start is open, m
  // (absent: prd.contact_tolerance, so both methods call hinges alike).
  std::optional<double> open_gap;
  // Confirm a located collapse by the short move from the bracket's final equilibrium
  // (dem/README.md, "Protocol", stage 4); a failure it does not reproduce becomes an equilibrium
  // and the run goes on. On by default: a failure only a long move produces is that move's
  // dynamics, not the structure's (a slender block toppled 13% early without it).
  bool confirm_collapse = true;
  HoldDamping hold_damping = HoldDamping::local;
};

// Refuses (CaseError, naming `source`, "dem" and the field) settings outside their ranges: the
// loader's own check, for settings a study derives in code. A time-step factor above 1 only
// where `allow_unstable_timestep` (the DEM's blow-up tests).
void check_dem_options(const DemOptions& d, const std::string& source, bool allow_unstable_timestep = false);

struct Case {
  std::string source;  // file name, for messages
  std::string name;
  std::string description;
  double gravity = 9.81;  // m/s^2, acting along -y
  std::vector<Block> blocks;
  std::vector<Load> loads;
  Motion motion;
  PrdOptions prd;
  DemOptions dem;

  int block_index(const std::string& id) const;  // -1 if absent
};

// Text from a case (ids, names, field names) as it may be shown on a terminal: control characters
// (an ANSI escape, a newline) written as \xNN, and more than `max` characters shortened to their
// beginning and a count, so a message stays one readable line whatever the input held.
std::string printable(const std::string& text, size_t max = 80);

// Why `id` cannot name a block, one clause for a message ("" when it can). Joints are named
// BLOCK/BLOCK and their corners BLOCK/BLOCK:A or :B (:C, :D and on for further joints between the
// same blocks; results, --hold, compare's and sweeps' mechanism keys): with '/' in ids, blocks 'a' with 'b/c' and 'a/b' with 'c' name two joints
// a/b/c, so an id may hold neither separator, and every name splits at its one '/' and one ':'.
// The case loader refuses such an id; the drawing import refuses the text that would make one.
std::string id_fault(const std::string& id);

// Parses and validates a case (JSON text). `source` names the file in messages.
Case parse_case(const std::string& text, const std::string& source);
// Reads, parses and validates a case file.
Case load_case(const std::string& path);
// Serialises a case to the masonry-case/1 JSON format (deterministic, round-trips).
std::string case_to_json(const Case& c);

// The case with one option changed: `key` is a dotted path into the masonry-case/1 format
// ("dem.friction_angle", "motion.step", "prd.contact_tolerance", "gravity"; blocks and loads are
// not options). The result is parsed and validated again, so a bad value gets the loader's
// one-line error; the source is named as "FILE [key=value]". Throws CaseError.
Case with_option(const Case& c, const std::string& key, const nlohmann::json& value);

// Geometric validity of the blocks alone (vertex count, area, self-intersection, overlaps,
// finite numbers); throws CaseError. parse_case calls it; generators call it too.
void validate_geometry(const Case& c);

// Polygon helpers (any orientation).
double signed_area(const std::vector<Vec2>& poly);
Vec2 centroid(const std::vector<Vec2>& poly);
// How far p lies outside the polygon (0 inside or on it), m: the distance to its nearest edge
// where an even-odd crossing test puts p outside.
double distance_outside(const std::vector<Vec2>& poly, const Vec2& p);
// Second moment of area about the centroid (polar), m^4.
double polar_moment(const std::vector<Vec2>& poly);
// An axis-aligned bounding box; empty (lo > hi) until a point is added.
struct Bounds {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
  Vec2 extent() const { return hi - lo; }
  double size() const { return extent().maxCoeff(); }  // the larger side
};
Bounds bounds(const std::vector<Vec2>& points);
// Every block's vertices, as the case gives them.
Bounds scene_bounds(const Case& c);
// Largest extent of all blocks' bounding box: the scene size used to scale tolerances.
double scene_size(const Case& c);
// How far a point a support carries travels per unit of d, m/m: its translation plus its
// rotation times its lever, the scene's size L plus how far the point it turns about stands
// outside the scene's bounds (a slab turning about a hinge 4 m from a 1 m stack carries it on a
// lever of 4 m, not 1); for the case, the largest over its supports (0 where none moves).
double support_travel_per_d(const SupportMotion& m, const Bounds& scene);
double support_travel_per_d(const Case& c);
// The same, 1 where no support moves: the scale of d against the structure's lengths that the
// DEM's loading and compare's jumps read (d then moves nothing, and a metre of it counts as one).
double path_travel_per_d(const Case& c);
// The SI unit of the path parameter d, as reports write it: "rad" when every moving support only
// turns (d is then an angle, a tilt), else "m" (a support that translates, with or without
// turning, moves by d metres per unit).
std::string path_unit(const Case& c);
// Mass (kg) and weight (N) of a block: density * area * depth (* gravity).
double block_mass(const Block& b);
// Resultant of the dead loads (the free blocks' weights and the point loads), N: what the
// supports together carry in any equilibrium.
Vec2 dead_load_resultant(const Case& c);
// The total weight W, N: the vertical part of the dead-load resultant, downwards positive (the
// free blocks' weights minus the loads' upward components), which is what the supports carry
// vertically in any equilibrium. Thrusts are reported over it by both methods, so it has this one
// definition: PRD once counted only downward loads and the DEM every vertical component, and an
// upward load gave the two methods different W.
double total_weight(const Case& c);

}  // namespace masonry
