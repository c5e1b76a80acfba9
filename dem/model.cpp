#include <box2d/b2_collision.h>
#include <box2d/b2_dynamic_tree.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "dem/contact.hpp"
#include "dem/dem.hpp"

namespace masonry {

using dem::Manifold;

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 rotate(const Vec2& v, double c, double s) { return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y()); }
Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }  // omega x r for unit omega

struct PointState {
  int key = -1;          // feature id: reference edge, incident edge, flip, end of the incident edge
  double fn = 0, fs = 0;  // N: normal (compression) and shear along perp(normal), on body B
  double area = 0;       // m^2
  double overlap = 0;    // m
  Vec2 point{0, 0};
  Vec2 normal{0, 0};     // A -> B
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

struct QueryCollector {
  const b2DynamicTree* tree;
  int self;
  std::vector<int>* out;
  bool QueryCallback(int32 proxy) {
    const int other = static_cast<int>(reinterpret_cast<intptr_t>(tree->GetUserData(proxy)));
    if (other > self) out->push_back(other);
    return true;
  }
};

}  // namespace

DemSettings DemSettings::from_case(const Case& c) {
  DemSettings s;
  s.young_modulus = c.dem.young_modulus;
  s.poisson = c.dem.poisson;
  s.kn = c.dem.kn;
  s.ks = c.dem.ks;
  s.stiffness_reduction = c.dem.stiffness_reduction;
  s.friction_angle = c.dem.friction_angle;
  s.damping = c.dem.damping;
  s.timestep_factor = c.dem.timestep_factor;
  s.equilibrium_tolerance = c.dem.equilibrium_tolerance;
  s.velocity_tolerance = c.dem.velocity_tolerance;
  s.hold_time = c.dem.hold_time;
  s.move_time = c.dem.move_time;
  s.ramp_fraction = c.dem.ramp_fraction;
  s.collapse_drift = c.dem.collapse_drift;
  s.kinetic_ratio = c.dem.kinetic_ratio;
  s.bracket_fraction = c.dem.bracket_fraction;
  if (c.dem.open_gap) s.open_gap = *c.dem.open_gap;
  s.confirm_collapse = c.dem.confirm_collapse;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  return s;
}

struct DemModel::Impl {
  const Case& c;
  DemSettings s;
  double kn = 0, ks = 0, tan_phi = 0, dt_crit = 0, dt = 0, time = 0, margin = 0, open_gap = 0;
  long long cycles = 0, rebuilds = 0;
  double d_target = 0, d_now = 0;

  // Blocks (contiguous arrays, case order).
  int nb = 0;
  std::vector<char> support;
  std::vector<double> mass, inertia, wref, gyr, rmax, depth;
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

  // Diagnostics of the last cycle (the contact ones are summed from `pairs` on demand).
  double unbalanced = INFINITY, speed = INFINITY, ke = 0;
  double support_work = 0;  // J, done on the blocks by the moving supports since the start

  Impl(const Case& cs, const DemSettings& st) : c(cs), s(st) {}

  // Setup, in this order.
  void setup();
  void check_settings() const;
  void build_blocks();     // blocks' arrays, convex pieces, dead loads
  void set_time_step();    // joint stiffnesses, the critical time step, dt

  void place_support(int b, double d, Vec2& x, double& th) const;
  void transform_pieces(bool all);
  void rebuild();
  // One cycle: its stages, in this order (each a loop of its own over contiguous arrays).
  void step();
  void body_forces();     // gravity and the dead loads
  void contact_forces();  // narrow phase and the joint law, on both blocks of each pair
  void integrate();       // supports to their prescribed pose; free blocks by damped central differences
};

void DemModel::Impl::setup() {
  check_settings();
  build_blocks();
  set_time_step();
  transform_pieces(true);
  rebuild();
}

void DemModel::Impl::check_settings() const {
  // Settings come from the case's dem section or from the command line: a refusal names the
  // file and the case field (the option of the same name), with the value.
  auto refuse = [&](const char* field, double value, const char* rule) {
    std::ostringstream m;
    m << c.source << ": dem: field '" << field << "' = " << value << " " << rule;
    throw std::runtime_error(m.str());
  };
  const std::pair<const char*, double> numbers[] = {
      {"young_modulus", s.young_modulus},   {"poisson", s.poisson},         {"stiffness_reduction", s.stiffness_reduction},
      {"hold_time", s.hold_time},           {"move_time", s.move_time},     {"step", s.step},
      {"equilibrium_tolerance", s.equilibrium_tolerance}, {"velocity_tolerance", s.velocity_tolerance},
      {"collapse_drift", s.collapse_drift}, {"open_gap", s.open_gap},       {"kn", s.kn.value_or(1.0)},
      {"ks", s.ks.value_or(1.0)},           {"kinetic_ratio", s.kinetic_ratio}, {"bracket_fraction", s.bracket_fraction},
      {"friction_angle", s.friction_angle}, {"damping", s.damping},         {"ramp_fraction", s.ramp_fraction}};
  for (const auto& [name, v] : numbers)
    if (!std::isfinite(v)) refuse(name, v, "is not a finite number");
  if (!(s.friction_angle >= 0 && s.friction_angle <= 90)) refuse("friction_angle", s.friction_angle, "must lie in [0, 90] degrees");
  if (!(s.damping >= 0 && s.damping < 1)) refuse("damping", s.damping, "must lie in [0, 1)");
  if (!(s.stiffness_reduction > 0)) refuse("stiffness_reduction", s.stiffness_reduction, "must be positive");
  if (!(s.young_modulus > 0)) refuse("young_modulus", s.young_modulus, "must be positive (Pa)");
  if (!(s.poisson > -1 && s.poisson < 0.5)) refuse("poisson", s.poisson, "must lie in (-1, 0.5)");
  if (!(s.hold_time > 0)) refuse("hold_time", s.hold_time, "must be positive (s)");
  if (!(s.move_time >= 0)) refuse("move_time", s.move_time, "must be >= 0 (s)");
  if (!(s.kinetic_ratio > 0)) refuse("kinetic_ratio", s.kinetic_ratio, "must be positive");
  if (!(s.bracket_fraction >= 0 && s.bracket_fraction < 1)) refuse("bracket_fraction", s.bracket_fraction, "must lie in [0, 1)");
  if (!(s.ramp_fraction >= 0 && s.ramp_fraction <= 0.5)) refuse("ramp_fraction", s.ramp_fraction, "must lie in [0, 0.5]");
  if (!(s.equilibrium_tolerance > 0)) refuse("equilibrium_tolerance", s.equilibrium_tolerance, "must be positive");
  if (!(s.velocity_tolerance > 0)) refuse("velocity_tolerance", s.velocity_tolerance, "must be positive (m/s)");
  if (!(s.step > 0)) refuse("step", s.step, "(motion.step) must be positive (m)");
  if (s.max_steps < 0) refuse("max_steps", s.max_steps, "(motion.max_steps) must be >= 0");
}

void DemModel::Impl::build_blocks() {
  nb = static_cast<int>(c.blocks.size());
  support.assign(nb, 0);
  mass.assign(nb, 0);
  inertia.assign(nb, 0);
  wref.assign(nb, 0);
  gyr.assign(nb, 0);
  rmax.assign(nb, 0);
  depth.assign(nb, 0);
  c0.assign(nb, Vec2::Zero());
  vel.assign(nb, Vec2::Zero());
  force.assign(nb, Vec2::Zero());
  ang.assign(nb, 0);
  spin.assign(nb, 0);
  torque.assign(nb, 0);
  cs.assign(nb, 1.0);
  sn.assign(nb, 0.0);
  moved.assign(nb, 0.0);
  turned.assign(nb, 0.0);
  motion_of.assign(nb, -1);
  for (size_t k = 0; k < c.motion.supports.size(); ++k) motion_of[c.motion.supports[k].block] = static_cast<int>(k);

  double min_size = INFINITY;
  int nfree = 0;
  for (int b = 0; b < nb; ++b) {
    const Block& bl = c.blocks[b];
    support[b] = bl.support;
    depth[b] = bl.depth;
    c0[b] = centroid(bl.vertices);
    for (const Vec2& v : bl.vertices) rmax[b] = std::max(rmax[b], (v - c0[b]).norm());
    if (!bl.support) {
      const double area = std::abs(signed_area(bl.vertices));
      mass[b] = block_mass(bl);
      inertia[b] = bl.density * bl.depth * polar_moment(bl.vertices);
      if (!(mass[b] > 0) || !(inertia[b] > 0) || !std::isfinite(mass[b]) || !std::isfinite(inertia[b]))
        throw std::runtime_error(c.source + ": block '" + bl.id + "': field 'density': the block's mass (" + std::to_string(mass[b]) +
                                 " kg) or moment of inertia is not positive and finite");
      gyr[b] = std::sqrt(inertia[b] / mass[b]);
      wref[b] = mass[b] * c.gravity;
      min_size = std::min(min_size, std::sqrt(area));
      ++nfree;
    }
    for (const std::vector<Vec2>& piece : dem::convex_pieces(bl.vertices)) {
      piece_block.push_back(b);
      piece_off.push_back(static_cast<int>(local_v.size()));
      piece_cnt.push_back(static_cast<int>(piece.size()));
      const int n = static_cast<int>(piece.size());
      for (int i = 0; i < n; ++i) {
        local_v.push_back(piece[i] - c0[b]);
        const Vec2 e = piece[(i + 1) % n] - piece[i];
        local_n.push_back(Vec2(e.y(), -e.x()).normalized());
      }
    }
  }
  if (nfree == 0) throw std::runtime_error(c.source + ": blocks: the case has no free block");
  pos = c0;
  world_v = local_v;
  world_n = local_n;
  for (const Load& l : c.loads) {
    load_block.push_back(l.block);
    load_force.push_back(l.force);
    load_r.push_back(l.point - c0[l.block]);
    if (!support[l.block]) wref[l.block] += l.force.norm();
  }
  for (int b = 0; b < nb; ++b)
    if (!support[b] && !(wref[b] > 0)) wref[b] = 1.0;  // weightless, unloaded: ratio in newtons
  margin = 0.05 * min_size;
}

void DemModel::Impl::set_time_step() {
  double area_sum = 0;
  int nfree = 0;
  for (int b = 0; b < nb; ++b)
    if (!support[b]) area_sum += std::abs(signed_area(c.blocks[b].vertices)), ++nfree;
  const double h_block = std::sqrt(area_sum / nfree);
  const double G = s.young_modulus / (2 * (1 + s.poisson));
  kn = (s.kn ? *s.kn : s.young_modulus / h_block) / s.stiffness_reduction;
  ks = (s.ks ? *s.ks : G / h_block) / s.stiffness_reduction;
  tan_phi = s.friction_angle >= 90 ? INFINITY : std::tan(s.friction_angle * M_PI / 180);
  if (!(kn > 0) || !(ks > 0) || !std::isfinite(kn) || !std::isfinite(ks)) {
    std::ostringstream m;
    m << c.source << ": dem: fields 'kn', 'ks' (or 'young_modulus' / 'stiffness_reduction'): the joint stiffnesses must be positive "
      << "and finite (kn " << kn << " Pa/m, ks " << ks << " Pa/m)";
    throw std::runtime_error(m.str());
  }

  double lam = 0;  // bound on omega^2 / (kn + ks)
  for (int b = 0; b < nb; ++b) {
    if (support[b]) continue;
    // The faces contacts see: a straight-angle vertex would split a face in the bound's sum.
    const std::vector<Vec2> v = dem::without_straight_vertices(c.blocks[b].vertices);
    double P = 0, J = 0;
    for (size_t i = 0, n = v.size(); i < n; ++i) {
      const Vec2 &p = v[i], &q = v[(i + 1) % n];
      const double L = (q - p).norm();
      P += L;
      J += L * ((p - c0[b]).squaredNorm() + (q - c0[b]).squaredNorm()) / 2;
    }
    lam = std::max(lam, 2 * depth[b] * ((kn + ks) * P / mass[b] + std::max(kn, ks) * J / inertia[b]));
  }
  dt_crit = 2 / std::sqrt(lam);
  if (!(s.timestep_factor > 0) || !std::isfinite(s.timestep_factor) || (s.timestep_factor > 1 && !s.allow_unstable_timestep)) {
    std::ostringstream m;
    m << c.source << ": dem: field 'timestep_factor' = " << s.timestep_factor << " is outside (0, 1]: the time step would be "
      << s.timestep_factor * dt_crit << " s against a stability limit of " << dt_crit
      << " s (kn " << kn << " Pa/m, lightest/stiffest block); refusing to run an unstable integration";
    throw std::runtime_error(m.str());
  }
  dt = s.timestep_factor * dt_crit;
  open_gap = s.open_gap >= 0 ? s.open_gap : c.prd.contact_tolerance;
}

void DemModel::Impl::place_support(int b, double d, Vec2& x, double& th) const {
  const int k = motion_of[b];
  if (k < 0) {
    x = c0[b];
    th = 0;
    return;
  }
  const SupportMotion& m = c.motion.supports[k];
  th = d * m.rotation;
  x = m.about + rotate(c0[b] - m.about, std::cos(th), std::sin(th)) + d * m.translation;
}

// World vertices and normals of the pieces. Fixed supports never move, so after the first call
// (all = true) only free blocks and moving supports are transformed.
void DemModel::Impl::transform_pieces(bool all) {
  for (int b = 0; b < nb; ++b) {
    if (!all && support[b] && motion_of[b] < 0) continue;
    ::sincos(ang[b], &sn[b], &cs[b]);  // one call for both, as GCC makes of adjacent cos and sin
  }
  const int np = static_cast<int>(piece_block.size());
  for (int p = 0; p < np; ++p) {
    const int b = piece_block[p];
    if (!all && support[b] && motion_of[b] < 0) continue;
    const double cb = cs[b], sb = sn[b];
    const Vec2 x = pos[b];
    for (int i = piece_off[p], e = piece_off[p] + piece_cnt[p]; i < e; ++i) {
      world_v[i] = x + rotate(local_v[i], cb, sb);
      world_n[i] = rotate(local_n[i], cb, sb);
    }
  }
}

// Candidate pairs: pieces of different blocks (not two supports) whose boxes, grown by the
// margin, overlap. Valid until some block has moved half the margin.
void DemModel::Impl::rebuild() {
  ++rebuilds;
  transform_pieces(false);
  const int np = static_cast<int>(piece_block.size());
  std::vector<Vec2> lo(np), hi(np);
  b2DynamicTree tree;
  for (int p = 0; p < np; ++p) {
    lo[p] = Vec2(INFINITY, INFINITY);
    hi[p] = -lo[p];
    for (int i = piece_off[p], e = piece_off[p] + piece_cnt[p]; i < e; ++i) {
      lo[p] = lo[p].cwiseMin(world_v[i]);
      hi[p] = hi[p].cwiseMax(world_v[i]);
    }
    lo[p].array() -= margin;
    hi[p].array() += margin;
    b2AABB box;
    box.lowerBound.Set(static_cast<float>(lo[p].x()), static_cast<float>(lo[p].y()));
    box.upperBound.Set(static_cast<float>(hi[p].x()), static_cast<float>(hi[p].y()));
    tree.CreateProxy(box, reinterpret_cast<void*>(static_cast<intptr_t>(p)));
  }
  std::vector<Pair> fresh;
  for (int p = 0; p < np; ++p) {
    scratch.clear();
    QueryCollector q{&tree, p, &scratch};
    b2AABB box;
    box.lowerBound.Set(static_cast<float>(lo[p].x()), static_cast<float>(lo[p].y()));
    box.upperBound.Set(static_cast<float>(hi[p].x()), static_cast<float>(hi[p].y()));
    tree.Query(&q, box);
    std::sort(scratch.begin(), scratch.end());
    for (int o : scratch) {
      const int ba = piece_block[p], bb = piece_block[o];
      if (ba == bb || (support[ba] && support[bb])) continue;
      // The tree's boxes are fattened in float; the exact test is in double.
      if ((lo[p].array() > hi[o].array()).any() || (lo[o].array() > hi[p].array()).any()) continue;
      Pair pr;
      pr.pa = p;
      pr.pb = o;
      pr.ba = ba;
      pr.bb = bb;
      // The boxes grown by the margin overlap, so the centroids are within sqrt 2 (r_a + r_b + 2
      // margin); each block moves at most about half a margin before the next rebuild. Any vertex
      // pair is then within (1 + sqrt 2)(r_a + r_b) + 2 sqrt 2 margin + margin, rounded up.
      pr.lever = 2.5 * (rmax[ba] + rmax[bb]) + 5 * margin;
      fresh.push_back(pr);
    }
  }
  // Keep the contact history of pairs that stay candidates (both lists sorted by (pa, pb)).
  size_t k = 0;
  for (Pair& f : fresh) {
    while (k < pairs.size() && std::make_pair(pairs[k].pa, pairs[k].pb) < std::make_pair(f.pa, f.pb)) ++k;
    if (k < pairs.size() && pairs[k].pa == f.pa && pairs[k].pb == f.pb) f = pairs[k];
  }
  pairs.swap(fresh);
  pos_rb = pos;
  ang_rb = ang;
  rebuild_due = false;
}

void DemModel::Impl::step() {
  if (rebuild_due) rebuild();
  transform_pieces(false);
  body_forces();
  contact_forces();
  integrate();
  time += dt;
  ++cycles;
}

void DemModel::Impl::body_forces() {
  for (int b = 0; b < nb; ++b) {
    force[b] = Vec2(0, -mass[b] * c.gravity);
    torque[b] = 0;
  }
  for (size_t l = 0; l < load_block.size(); ++l) {
    const int b = load_block[l];
    const Vec2 r = rotate(load_r[l], cs[b], sn[b]);
    force[b] += load_force[l];
    torque[b] += cross(r, load_force[l]);
  }
}

void DemModel::Impl::contact_forces() {
  Manifold m;
  for (Pair& pr : pairs) {
    const int pa = pr.pa, pb = pr.pb, ba = pr.ba, bb = pr.bb;
    // Only the shear history is carried from one cycle to the next.
    const int nold = pr.n;
    const int old_key[2] = {pr.pt[0].key, pr.pt[1].key};
    const double old_fs[2] = {pr.pt[0].fs, pr.pt[1].fs};
    pr.n = 0;
    const double motion = moved[ba] + moved[bb] + (turned[ba] + turned[bb]) * pr.lever;
    if (!dem::collide_cached(&world_v[piece_off[pa]], &world_n[piece_off[pa]], piece_cnt[pa], &world_v[piece_off[pb]],
                             &world_n[piece_off[pb]], piece_cnt[pb], motion, pr.lever, pr.sat, m))
      continue;
    const double dep = std::min(depth[ba], depth[bb]);
    // Each point stands for half of the clipped joint, whether or not its partner is in contact,
    // so a joint's stiffness does not jump when a hinge opens. The floor keeps corner-to-corner
    // contacts from being arbitrarily soft.
    const double area = std::max(m.clip_length, 0.1 * margin) * dep / 2;
    const Vec2 n = m.normal, t = perp(n);
    for (int i = 0; i < m.count; ++i) {
      const dem::ManifoldPoint& mp = m.points[i];
      const int key = ((m.ref_edge * dem::kMaxPieceVertices + m.inc_edge) * 2 + m.flip) * 2 + mp.slot;
      double fs = 0;
      for (int o = 0; o < nold; ++o)
        if (old_key[o] == key) fs = old_fs[o];
      const Vec2 ra = mp.point - pos[ba], rb = mp.point - pos[bb];
      const Vec2 vr = vel[bb] + spin[bb] * perp(rb) - vel[ba] - spin[ba] * perp(ra);
      const double overlap = -mp.separation;
      const double fn = kn * area * overlap;
      fs -= ks * area * vr.dot(t) * dt;
      const double cap = fn * tan_phi;
      if (std::abs(fs) > cap) fs = std::copysign(cap, fs);
      const Vec2 f = fn * n + fs * t;  // on B
      force[bb] += f;
      torque[bb] += cross(rb, f);
      force[ba] -= f;
      torque[ba] -= cross(ra, f);
      PointState& ps = pr.pt[pr.n++];
      ps.key = key;
      ps.fn = fn;
      ps.fs = fs;
      ps.area = area;
      ps.overlap = overlap;
      ps.point = mp.point;
      ps.normal = n;
    }
  }
}

void DemModel::Impl::integrate() {
  double unb = 0, spd = 0, kin = 0;
  const double alpha = s.damping;
  const double half_margin = 0.5 * margin;
  bool due = false;
  for (int b = 0; b < nb; ++b) {
    const Vec2 x_old = pos[b];
    const double th_old = ang[b];
    if (support[b]) {
      if (motion_of[b] < 0) {  // fixed: stays at its initial pose, at rest
        vel[b] = Vec2::Zero();
        spin[b] = 0;
        moved[b] = turned[b] = 0;
        continue;
      }
      Vec2 x;
      double th;
      place_support(b, d_target, x, th);
      // force[b] and torque[b] (about pos[b]) are what the blocks exert on the support.
      support_work -= force[b].dot(x - pos[b]) + torque[b] * (th - ang[b]);
      vel[b] = (x - pos[b]) / dt;
      spin[b] = (th - ang[b]) / dt;
      pos[b] = x;
      ang[b] = th;
    } else {
      const Vec2 F = force[b];
      const double M = torque[b];
      unb = std::max(unb, std::max(F.norm(), std::abs(M) / gyr[b]) / wref[b]);
      // Local (non-viscous) damping: a fraction of the unbalanced force opposes the motion.
      Vec2 Fd(F.x() - alpha * std::abs(F.x()) * (vel[b].x() > 0 ? 1 : vel[b].x() < 0 ? -1 : 0),
              F.y() - alpha * std::abs(F.y()) * (vel[b].y() > 0 ? 1 : vel[b].y() < 0 ? -1 : 0));
      const double Md = M - alpha * std::abs(M) * (spin[b] > 0 ? 1 : spin[b] < 0 ? -1 : 0);
      const Vec2 v_new = vel[b] + dt * Fd / mass[b];
      const double w_new = spin[b] + dt * Md / inertia[b];
      // Kinetic energy at the force time: mean of the two half-step velocities.
      kin += 0.5 * mass[b] * (0.5 * (v_new + vel[b])).squaredNorm() + 0.5 * inertia[b] * std::pow(0.5 * (w_new + spin[b]), 2);
      vel[b] = v_new;
      spin[b] = w_new;
      pos[b] += dt * v_new;
      ang[b] += dt * w_new;
      spd = std::max(spd, v_new.norm() + std::abs(w_new) * gyr[b]);
    }
    // The motion actually taken (differences of the stored doubles, so rounding is included).
    turned[b] = std::abs(ang[b] - th_old);
    moved[b] = (pos[b] - x_old).norm() + turned[b] * rmax[b];
    if ((pos[b] - pos_rb[b]).norm() + std::abs(ang[b] - ang_rb[b]) * rmax[b] > half_margin) due = true;
  }
  rebuild_due = due;
  d_now = d_target;
  unbalanced = unb;
  speed = spd;
  ke = kin;
}

DemModel::DemModel(const Case& c, const DemSettings& s) : p_(std::make_unique<Impl>(c, s)) { p_->setup(); }
DemModel::~DemModel() = default;

double DemModel::kn() const { return p_->kn; }
double DemModel::ks() const { return p_->ks; }
double DemModel::critical_dt() const { return p_->dt_crit; }
double DemModel::dt() const { return p_->dt; }
double DemModel::time() const { return p_->time; }
long long DemModel::cycles() const { return p_->cycles; }
void DemModel::set_support_parameter(double d) { p_->d_target = d; }
double DemModel::support_parameter() const { return p_->d_now; }
void DemModel::cycle(long long n) {
  for (long long i = 0; i < n; ++i) p_->step();
}
double DemModel::unbalanced_ratio() const { return p_->unbalanced; }
double DemModel::max_speed() const { return p_->speed; }
DemBlockState DemModel::block(int b) const {
  return {p_->pos[b], p_->ang[b], p_->vel[b], p_->spin[b]};
}
double DemModel::kinetic_energy() const { return p_->ke; }
double DemModel::support_work() const { return p_->support_work; }
double DemModel::spring_energy() const {
  double e = 0;
  for (const Pair& pr : p_->pairs)
    for (int i = 0; i < pr.n; ++i)
      e += 0.5 * pr.pt[i].fn * pr.pt[i].fn / (p_->kn * pr.pt[i].area) + 0.5 * pr.pt[i].fs * pr.pt[i].fs / (p_->ks * pr.pt[i].area);
  return e;
}
int DemModel::contact_points() const {
  int n = 0;
  for (const Pair& pr : p_->pairs) n += pr.n;
  return n;
}
double DemModel::max_overlap() const {
  double o = 0;
  for (const Pair& pr : p_->pairs)
    for (int i = 0; i < pr.n; ++i) o = std::max(o, pr.pt[i].overlap);
  return o;
}
long long DemModel::broadphase_rebuilds() const { return p_->rebuilds; }

// Gravity and load terms use the positions at the last force evaluation's time only to within a
// step; callers compare them over many steps, where that lag is immaterial... except for energy
// conservation, so the positions are rewound by the last half-step velocity.
double DemModel::gravity_energy() const {
  const Impl& m = *p_;
  double e = 0;
  for (int b = 0; b < m.nb; ++b)
    if (!m.support[b]) e += m.mass[b] * m.c.gravity * (m.pos[b].y() - m.dt * m.vel[b].y() - m.c0[b].y());
  return e;
}
double DemModel::load_work() const {
  const Impl& m = *p_;
  double w = 0;
  for (size_t l = 0; l < m.load_block.size(); ++l) {
    const int b = m.load_block[l];
    const double th = m.ang[b] - m.dt * m.spin[b];
    const Vec2 x = m.pos[b] - m.dt * m.vel[b] + rotate(m.load_r[l], std::cos(th), std::sin(th));
    w += m.load_force[l].dot(x - (m.c0[b] + m.load_r[l]));
  }
  return w;
}

double DemModel::energy_input() const {
  const Impl& m = *p_;
  double w = m.support_work;
  for (int b = 0; b < m.nb; ++b)
    if (!m.support[b]) w -= m.mass[b] * m.c.gravity * (m.pos[b].y() - m.c0[b].y());
  for (size_t l = 0; l < m.load_block.size(); ++l) {
    const int b = m.load_block[l];
    const Vec2 x = m.pos[b] + rotate(m.load_r[l], std::cos(m.ang[b]), std::sin(m.ang[b]));
    w += m.load_force[l].dot(x - (m.c0[b] + m.load_r[l]));
  }
  return w;
}

struct DemSnapshot::Data {
  std::vector<Vec2> pos, vel, pos_rb;
  std::vector<double> ang, spin, ang_rb, moved, turned;
  std::vector<Pair> pairs;
  bool rebuild_due = false;
  double d_target = 0, d_now = 0, time = 0, support_work = 0, unbalanced = 0, speed = 0, ke = 0;
};

DemSnapshot DemModel::save() const {
  const Impl& m = *p_;
  auto d = std::make_shared<DemSnapshot::Data>();
  d->pos = m.pos;
  d->vel = m.vel;
  d->pos_rb = m.pos_rb;
  d->ang = m.ang;
  d->spin = m.spin;
  d->ang_rb = m.ang_rb;
  d->moved = m.moved;
  d->turned = m.turned;
  d->pairs = m.pairs;
  d->rebuild_due = m.rebuild_due;
  d->d_target = m.d_target;
  d->d_now = m.d_now;
  d->time = m.time;
  d->support_work = m.support_work;
  d->unbalanced = m.unbalanced;
  d->speed = m.speed;
  d->ke = m.ke;
  return {d};
}

void DemModel::restore(const DemSnapshot& snap) {
  Impl& m = *p_;
  const DemSnapshot::Data& d = *snap.data;
  m.pos = d.pos;
  m.vel = d.vel;
  m.pos_rb = d.pos_rb;
  m.ang = d.ang;
  m.spin = d.spin;
  m.ang_rb = d.ang_rb;
  m.moved = d.moved;
  m.turned = d.turned;
  m.pairs = d.pairs;
  m.rebuild_due = d.rebuild_due;
  m.d_target = d.d_target;
  m.d_now = d.d_now;
  m.time = d.time;
  m.support_work = d.support_work;
  m.unbalanced = d.unbalanced;
  m.speed = d.speed;
  m.ke = d.ke;
  // The world vertices and the cosines follow the restored poses (all blocks: a moving support
  // is back where it was too).
  m.transform_pieces(true);
}

std::vector<double> DemModel::corner_gaps(const std::vector<Interface>& joints) const {
  const Impl& m = *p_;
  std::vector<double> g;
  g.reserve(2 * joints.size());
  for (const Interface& J : joints) {
    const double ci = std::cos(m.ang[J.i]), si = std::sin(m.ang[J.i]), cj = std::cos(m.ang[J.j]), sj = std::sin(m.ang[J.j]);
    const Vec2 ni = rotate(J.normal, ci, si), nj = rotate(-J.normal, cj, sj);
    for (int corner = 0; corner < 2; ++corner) {
      const Vec2 P = corner == 0 ? J.a : J.b;
      const Vec2 pi = m.pos[J.i] + rotate(P - m.c0[J.i], ci, si), pj = m.pos[J.j] + rotate(P - m.c0[J.j], cj, sj);
      g.push_back(std::max((pj - pi).dot(ni), (pi - pj).dot(nj)));
    }
  }
  return g;
}

StepRecord DemModel::record(const std::vector<Interface>& joints, const std::vector<double>& gap_reference) const {
  const Impl& m = *p_;
  StepRecord r;
  r.d = m.d_now;
  double eg = 0, wl = 0;
  for (int b = 0; b < m.nb; ++b) {
    r.poses.push_back({m.pos[b].x(), m.pos[b].y(), m.ang[b]});
    if (!m.support[b]) eg += m.mass[b] * m.c.gravity * (m.pos[b].y() - m.c0[b].y());
  }
  for (size_t l = 0; l < m.load_block.size(); ++l) {
    const int b = m.load_block[l];
    const Vec2 x = m.pos[b] + rotate(m.load_r[l], std::cos(m.ang[b]), std::sin(m.ang[b]));
    wl += m.load_force[l].dot(x - (m.c0[b] + m.load_r[l]));
  }
  r.energy = eg - wl;

  // Reactions: what the structure receives from each support, moments about the support's
  // `about` point where it moves (its centroid when fixed), current configuration.
  std::vector<int> react_index(m.nb, -1);
  for (int b = 0; b < m.nb; ++b) {
    if (!m.support[b]) continue;
    react_index[b] = static_cast<int>(r.reactions.size());
    r.reactions.push_back({m.c.blocks[b].id, Vec2(0, 0), 0.0});
  }
  auto about = [&](int b) {
    const int k = m.motion_of[b];
    if (k < 0) return m.c0[b];
    const SupportMotion& sm = m.c.motion.supports[k];
    return Vec2(sm.about + m.d_now * sm.translation);
  };
  std::map<std::pair<int, int>, int> joint_of;
  for (size_t k = 0; k < joints.size(); ++k) joint_of.emplace(std::make_pair(joints[k].i, joints[k].j), static_cast<int>(k));
  struct Acc {
    double n = 0, s = 0, mom = 0;
    Vec2 np{0, 0};
  };
  std::vector<Acc> acc(joints.size());
  const std::vector<double> gaps = corner_gaps(joints);
  if (!gap_reference.empty() && gap_reference.size() != gaps.size())
    throw std::logic_error("DemModel::record: gap reference of another joint list");
  auto joint_frame = [&](const Interface& J, Vec2& n, Vec2& t) {
    const double th = m.ang[J.i];
    n = rotate(J.normal, std::cos(th), std::sin(th));
    t = rotate((J.b - J.a).normalized(), std::cos(th), std::sin(th));
  };
  for (const Pair& pr : m.pairs)
    for (int i = 0; i < pr.n; ++i) {
      const PointState& ps = pr.pt[i];
      const Vec2 f = ps.fn * ps.normal + ps.fs * perp(ps.normal);  // on B
      if (m.support[pr.ba]) {
        Reaction& R = r.reactions[react_index[pr.ba]];
        R.force += f;
        R.moment += cross(ps.point - about(pr.ba), f);
      } else if (m.support[pr.bb]) {
        Reaction& R = r.reactions[react_index[pr.bb]];
        R.force -= f;
        R.moment -= cross(ps.point - about(pr.bb), f);
      }
      const int i0 = std::min(pr.ba, pr.bb), j0 = std::max(pr.ba, pr.bb);
      const auto it = joint_of.find({i0, j0});
      if (it == joint_of.end()) continue;
      const Interface& J = joints[it->second];
      Vec2 n, t;
      joint_frame(J, n, t);
      const Vec2 fj = pr.bb == J.j ? f : Vec2(-f);
      Acc& a = acc[it->second];
      const double fn = fj.dot(n);
      a.n += fn;
      a.s += fj.dot(t);
      a.np += fn * ps.point;
    }
  for (size_t k = 0; k < joints.size(); ++k) {
    const Interface& J = joints[k];
    if (acc[k].n > 0) {
      JointForce f;
      f.joint = static_cast<int>(k);
      f.normal = acc[k].n;
      f.shear = acc[k].s;
      f.point = acc[k].np / acc[k].n;
      Vec2 t;
      joint_frame(J, f.n, t);
      r.forces.push_back(f);
    }
    // A corner is open when either block's copy of it stands off the other block's face by more
    // than open_gap beyond its gap in the reference state (a settled gap is not a hinge).
    bool cracked = false;
    for (int corner = 0; corner < 2; ++corner) {
      const double gap = gaps[2 * k + corner];
      const double ref = gap_reference.empty() ? 0.0 : std::max(0.0, gap_reference[2 * k + corner]);
      if (gap - ref > m.open_gap) {
        r.open_corners.push_back({static_cast<int>(k), corner, gap});
        cracked = true;
      }
    }
    if (cracked) r.cracked.push_back(static_cast<int>(k));
  }
  return r;
}

}  // namespace masonry
