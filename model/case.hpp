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

namespace masonry {

using Vec2 = Eigen::Vector2d;

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

struct PrdOptions {
  // Length (m) below which an endpoint's gap counts as closed; also the geometric tolerance of
  // interface detection.
  double contact_tolerance = 1e-5;
  // Event-driven stepping (prd/prd.hpp): large steps while the mechanism stays the same, each
  // change of mechanism located to `event_tolerance` (m; 0: 1e-4 of the scene size, 0.1 mm
  // for a metre-size scene) by bisection; steps up to `max_step` (m; 0: 16 motion.step).
  bool adaptive = false;
  double event_tolerance = 0.0;
  double max_step = 0.0;
  // The sliding check on every step (friction demand and the least friction angle an
  // admissible force state needs; prd/prd.hpp).
  bool sliding_check = false;
};

struct DemOptions {
  double young_modulus = 3.0e10;        // Pa
  double poisson = 0.2;
  double friction_angle = 35.0;         // degrees
  std::optional<double> kn;             // normal joint stiffness, Pa/m (default E / h_block)
  std::optional<double> ks;             // shear joint stiffness, Pa/m (default G / h_block)
  double stiffness_reduction = 1.0;     // kn and ks are divided by this (the paper used 10)
  double damping = 0.8;                 // local non-viscous damping coefficient, 0..1
  double timestep_factor = 0.8;         // safety factor on the critical time step
  double equilibrium_tolerance = 1e-4;  // largest unbalanced force / block weight
  double velocity_tolerance = 1e-5;     // largest block speed at equilibrium, m/s
  double hold_time = 30.0;              // model-time cap of one hold, s (dem/README.md)
  // The loading protocol (dem/README.md): the support speed is servoed to keep the kinetic energy
  // below kinetic_ratio x total weight x increment; move_time > 0 (s) moves at constant speed over
  // that time instead, with half-cosine speed ramps over ramp_fraction of it at each end. The
  // drift during a hold that counts as collapse (m; 0 means 2% of the scene size). A failed
  // increment is bisected down to bracket_fraction x step (0: not bisected).
  double kinetic_ratio = 1e-3;
  double move_time = 0.0;
  double ramp_fraction = 0.25;
  double collapse_drift = 0.0;
  double bracket_fraction = 0.01;
  // A joint corner whose gap has grown by more than this since the settled start is open, m
  // (absent: prd.contact_tolerance, so both methods call hinges alike).
  std::optional<double> open_gap;
  // Confirm a located collapse by the short move from the bracket's last equilibrium
  // (dem/README.md, "Protocol", stage 4).
  bool confirm_collapse = false;
};

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
