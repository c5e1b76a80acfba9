// The rigid-block discrete-element model (DEM) that stands in for 3DEC (see
// shared/docs/dem-method.md): rigid convex (or compound) blocks, Mohr-Coulomb joint springs at the
// manifold points of Box2D-style polygon contacts, explicit central-difference integration with
// local damping, and the paper's incremental loading protocol. SI units: m, kg, N, s, rad; the
// friction angle alone is in degrees.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "model/case.hpp"
#include "model/interfaces.hpp"
#include "model/results.hpp"

namespace masonry {

// The gravity the DEM's inertia is scaled to, m/s^2 (DemModel::mass_scale): the protocol's times
// and speeds are those of a structure under this gravity, whatever the case's.
constexpr double kReferenceGravity = 9.81;

// Contact damping's zeta where a run is checked against the ratchet of joints stiff against the
// weights: the convergence study's variant and compare's damped rerun (dem/README.md, "Contact
// damping": on the standard scenes and the zoo it moves the capacity by 0.00-0.15%).
constexpr double kCheckContactDamping = 0.3;

// The DEM's settings (model/case.hpp's DemOptions, declared once there) and the motion's
// increment, as one run takes them.
struct DemSettings : DemOptions {
  double step = 0.001;  // increment of d, m
  int max_steps = 1000;
  // Tests only: accept a time-step factor above 1, so the run's blow-up guard (an energy balance
  // checked every few cycles, dem_run) can be exercised. No case field or option sets it.
  bool allow_unstable_timestep = false;
  static DemSettings from_case(const Case& c);
};

// The factor contact damping (DemOptions::contact_damping, zeta) puts on the time step's bound:
// with the damping force taken from the velocity of the half step before, an oscillator of
// damping ratio zeta is stable for omega dt <= 2 (sqrt(1 + zeta^2) - zeta). 1 without it.
inline double contact_damping_step_factor(double zeta) { return zeta > 0 ? std::sqrt(1 + zeta * zeta) - zeta : 1.0; }

// One block's state for tests and diagnostics.
struct DemBlockState {
  Vec2 position{0, 0};  // centroid, m
  double angle = 0.0;   // rotation since the start, rad
  Vec2 velocity{0, 0};  // m/s (at the last half step)
  double spin = 0.0;    // rad/s
};

// A copy of a model's dynamic state (poses, velocities, contact history, support position), to
// go back to an equilibrium and try again (the collapse bracket).
struct DemSnapshot {
  struct Data;
  std::shared_ptr<const Data> data;
};

// The simulator: build it from a case, then place the supports and cycle.
class DemModel {
 public:
  // Throws std::runtime_error for settings it cannot run with (e.g. an unstable time step).
  DemModel(const Case& c, const DemSettings& s);
  ~DemModel();
  DemModel(const DemModel&) = delete;
  DemModel& operator=(const DemModel&) = delete;

  double kn() const;  // normal joint stiffness used, Pa/m
  double ks() const;  // shear joint stiffness used, Pa/m
  // Bound on the critical time step: 2 / sqrt(2 max_b [(kn+ks) depth P_b / m_b + max(kn,ks)
  // depth J_b / I_b]), P_b the perimeter and J_b = sum over edges of L (|p-c|^2 + |q-c|^2) / 2:
  // every manifold point carries at most (its share of) the edge length, a block's stiffness is
  // bounded by its whole perimeter in contact, and the 2 covers coupling to a neighbour.
  double critical_dt() const;
  double dt() const;  // timestep_factor * critical_dt
  // Factor on every free block's inertia (mass and moment): the acceleration the dead loads give
  // the structure over kReferenceGravity (1 at g = 9.81). Times, speeds and kinetic
  // energies are those of the scaled model.
  double mass_scale() const;
  double time() const;  // model time, s
  long long cycles() const;

  // Places the prescribed supports at path parameter d (they move there during the next cycle).
  void set_support_parameter(double d);
  double support_parameter() const;
  void cycle(long long n = 1);

  double unbalanced_ratio() const;  // of the last cycle: max over free blocks of max(|F|,|M|/r)/W
  double max_speed() const;         // max over free blocks of |v| + |omega| r (r: radius of gyration)
  // Of the last cycle: max over free blocks of the block's kinetic energy over its weight (plus
  // its dead loads), m: the height the fastest block's motion would lift it. The move's servo
  // reads it, so that a light block is loaded as gently as a heavy one.
  double max_kinetic_per_weight() const;
  DemBlockState block(int b) const;
  // Energies at the time of the last force evaluation, J: kinetic, gravity (relative to the
  // start), elastic (joint springs), and the work done by the dead loads (relative to the start).
  double kinetic_energy() const;
  // Every free block at rest (velocities and spins zero), the supports as they are: kinetic
  // damping's reset.
  void stop_free_blocks();
  double gravity_energy() const;
  double spring_energy() const;
  double load_work() const;
  double support_work() const;  // work done on the blocks by the moving supports since the start
  // Work done on the blocks since the start by gravity, the loads and the moving supports, up to
  // the current positions (half a step ahead of the energies above, so a bound on them):
  // kinetic + spring energy + dissipation equals it, to within the scheme's error.
  double energy_input() const;
  int contact_points() const;  // manifold points in contact
  // The block pairs (lower index first, sorted) with a contact point pressed together (positive
  // overlap) that lies on none of their `joints` (a part resting on a face it was not cut
  // against: dem_run's landing stage).
  std::vector<std::pair<int, int>> off_joint_contacts(const std::vector<Interface>& joints) const;
  double max_overlap() const;  // m
  long long broadphase_rebuilds() const;

  DemSnapshot save() const;
  // Back to a saved state of this model (the cycle count and the timing keep counting).
  void restore(const DemSnapshot& s);

  // Normal gap of each joint corner (A then B per joint), m (negative: overlap), by
  // model/interfaces.hpp's corner_gap, the rule PRD started from a DEM's configuration reads too.
  std::vector<double> corner_gaps(const std::vector<Interface>& joints) const;
  // The current state as a step record (poses, reactions, open corners, joint forces, energy).
  // A corner is open when its gap exceeds open_gap beyond `gap_reference` (its gap in the
  // settled initial state, so elastic settling under gravity is not read as a hinge; empty: 0).
  StepRecord record(const std::vector<Interface>& joints, const std::vector<double>& gap_reference = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

// The capacity run (loading protocol of dem-method.md). `on_step` is called after step 0 (the
// initial configuration settled under gravity) and after every increment.
RunResult dem_run(const Case& c, const DemSettings& s, const std::function<void(const RunResult&)>& on_step = {});

// Throws what dem_run would refuse the case and settings with before its first cycle (one line,
// naming the file and field), and nothing else: a command that runs PRD first (compare) asks
// this before, so a DEM refusal does not come after PRD's run.
void dem_check(const Case& c, const DemSettings& s);

}  // namespace masonry
