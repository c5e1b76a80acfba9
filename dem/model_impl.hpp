// Internal to dem/: the simulator's state (DemModel::Impl) and the small helpers its two files
// share. model.cpp builds it and runs the cycle; observe.cpp reads it (energies, records,
// snapshots) for DemModel's public accessors.
#pragma once

#include <box2d/b2_collision.h>

#include <cmath>
#include <vector>

#include "dem/contact.hpp"
#include "dem/dem.hpp"

namespace masonry {

namespace dem_detail {

inline Vec2 rotate(const Vec2& v, double c, double s) { return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y()); }

struct PointState {
  int key = -1;           // feature id: reference edge, incident edge, flip, end of the incident edge
  double fn = 0, fs = 0;  // N: normal (compression) and shear along perp(normal), on body B
  double area = 0;        // m^2
  double overlap = 0;     // m
  Vec2 point{0, 0};
  Vec2 normal{0, 0};  // A -> B
};

struct Pair {
  int pa = -1, pb = -1;  // pieces, pa < pb
  int ba = -1, bb = -1;  // their blocks
  int n = 0;             // points in contact
  PointState pt[2];
  // The separating-axis decisions of the last cycle, reused while provably unchanged, and the
  // largest distance between a vertex of pa and one of pb while they are candidates (m).
  dem::SatCache sat;
  double lever = 0;
};

}  // namespace dem_detail

// Largest lower bound on a joint's elastic overlap under its block's weight, as a fraction of
// the block's size, the DEM accepts (check_joint_stiffness).
constexpr double kMaxOverlap = 0.05;

struct DemModel::Impl {
  using Pair = dem_detail::Pair;
  // The case in the model's frame: the world shifted by -origin (DemModel::Impl::frame). Every
  // position inside the model is in this frame; the public accessors add origin back.
  Vec2 origin{0, 0};
  Case framed;
  const Case& c;
  DemSettings s;
  double kn = 0, ks = 0, tan_phi = 0, dt_crit = 0, dt = 0, time = 0, margin = 0, open_gap = 0;
  long long cycles = 0, rebuilds = 0;
  double d_target = 0, d_now = 0;

  // Blocks (contiguous arrays, case order).
  int nb = 0;
  std::vector<char> support;
  // mass and inertia are the inertial ones, scaled by mass_scale (setup: the structure's own
  // gravity brought to kReferenceGravity); weight is the gravitational force, N, never scaled.
  std::vector<double> mass, inertia, weight, wref, gyr, rmax, depth;
  double mass_scale = 1.0;
  std::vector<double> inv_mass, inv_inertia;  // of the inertial ones; 0 for supports (contact damping)
  // The contacts' dampers' force and moment on each block in the last cycle (contact damping only).
  std::vector<Vec2> damp_force;
  std::vector<double> damp_torque;
  std::vector<Vec2> c0, pos, vel, force;
  std::vector<double> ang, spin, torque;
  std::vector<double> cs, sn;  // cos and sin of ang, once per cycle for all pieces of the block
  // Motion of the last cycle: |dx| + |dth| rmax, and |dth|; they bound how far the contact
  // decisions cached in the pairs can have drifted (dem::collide_cached).
  std::vector<double> moved, turned;
  bool rebuild_due = false;  // some block has moved half the margin since the last rebuild
  std::vector<Vec2> pos_rb;  // at the last broad-phase rebuild
  std::vector<double> ang_rb;
  std::vector<int> motion_of;  // index into c.motion.supports, or -1

  // Pieces: local vertices relative to the block centroid in the initial orientation.
  std::vector<int> piece_block, piece_off, piece_cnt;
  std::vector<Vec2> local_v, local_n, world_v, world_n;

  std::vector<int> load_block;
  std::vector<Vec2> load_force, load_r;

  std::vector<Pair> pairs;
  std::vector<int> scratch;

  // Diagnostics of the last cycle. The kinetic energy is summed by integrate(); the others are
  // read from the cycle's arrays when asked for (observe.cpp), once per cycle at most, since
  // most cycles read only some of them (a move the largest kinetic energy per weight, a hold the
  // unbalanced force and, once that is small, the speed): force and torque stay as the cycle
  // left them until the next, vel and spin until stop_free_blocks() (which reads the speed
  // first), and kin holds each block's kinetic energy. The same expressions over the same
  // blocks, so the same values to the bit as when integrate() computed them every cycle.
  double ke = 0;
  std::vector<double> kin;  // J, per free block, of the last cycle
  mutable double unbalanced = INFINITY, speed = INFINITY;
  mutable double ke_per_weight = INFINITY;  // m: max over free blocks of KE_b / wref_b
  mutable bool unbalanced_known = true, speed_known = true, ke_per_weight_known = true;
  double unbalanced_of_cycle() const;
  double speed_of_cycle() const;
  double ke_per_weight_of_cycle() const;
  // The largest over the free blocks of value(b), into `cached` unless `known` (observe.cpp).
  template <class Value>
  double once_per_cycle(bool& known, double& cached, Value value) const;
  double support_work = 0;  // J, done on the blocks by the moving supports since the start

  Impl(const Case& cs, const DemSettings& st) : origin(frame_origin(cs)), framed(shifted(cs, origin)), c(framed), s(st) {}
  static Vec2 frame_origin(const Case& cs);
  static Case shifted(const Case& cs, const Vec2& by);

  // Setup, in this order.
  void setup();
  void check_settings() const;
  void build_blocks();                 // blocks' arrays, convex pieces, dead loads
  void scale_masses();                 // the inertia of the free blocks (mass_scale)
  void set_time_step();                // joint stiffnesses, the critical time step, dt
  void check_joint_stiffness() const;  // overlaps small against the blocks (or CaseError)

  void place_support(int b, double d, Vec2& x, double& th) const;
  void transform_pieces(bool all);
  b2AABB float_box(const Vec2& lo, const Vec2& hi) const;
  void rebuild();
  // One cycle: its stages, in this order (each a loop of its own over contiguous arrays).
  void step();
  void body_forces();     // gravity and the dead loads
  void contact_forces();  // narrow phase and the joint law, on both blocks of each pair
  void integrate();       // supports to their prescribed pose; free blocks by damped central differences
  // contact_damping's force at a contact point (contact_forces).
  Vec2 damping_force(double fn, double fs, bool slipping, const Vec2& n, const Vec2& t, const Vec2& vr, const Vec2& ra, const Vec2& rb, int ba,
                     int bb, double area) const;
};

}  // namespace masonry
