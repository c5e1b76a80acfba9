#include <box2d/b2_collision.h>
#include <box2d/b2_dynamic_tree.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "dem/model_impl.hpp"
#include "model/interfaces.hpp"
#include "model/options.hpp"

namespace masonry {

using dem::Manifold;
using namespace dem_detail;

namespace {

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

// The model's frame. A block's motion per cycle is often 1e-11 m or less (a creep of 1e-6 m/s at
// a time step of 1e-5 s), which a double at 7e4 m (resolution 1.5e-11 m) no longer holds: the
// pointed arch moved to (7e4, 7e4) m found its limit at 0.091 m instead of 0.276 m, and the
// broad phase's float boxes lose the margin there too (float resolution 7.8 mm at 6.5e4 m). So a
// scene farther from the world origin than its own size is computed about its centre. Nearer,
// the coordinates carry the scene's resolution to within a factor 2, and the frame is the world's
// (the results do not change by a rounding).
Vec2 DemModel::Impl::frame_origin(const Case& cs) {
  const Bounds bb = scene_bounds(cs);
  const Vec2 centre = 0.5 * (bb.lo + bb.hi);
  return centre.norm() > bb.size() ? centre : Vec2(0, 0);
}

Case DemModel::Impl::shifted(const Case& cs, const Vec2& by) {
  Case f = cs;
  if (by == Vec2(0, 0)) return f;
  for (Block& b : f.blocks)
    for (Vec2& v : b.vertices) v -= by;
  for (Load& l : f.loads) l.point -= by;
  for (SupportMotion& m : f.motion.supports) m.about -= by;
  return f;
}

DemSettings DemSettings::from_case(const Case& c) {
  DemSettings s;
  static_cast<DemOptions&>(s) = c.dem;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  return s;
}

void DemModel::Impl::setup() {
  check_settings();
  build_blocks();
  set_time_step();
  check_joint_stiffness();
  transform_pieces(true);
  rebuild();
}

void DemModel::Impl::check_settings() const {
  // The case loader's own check (one definition of every range), for settings a study derives
  // in code; then the motion's increment, which DemSettings carries beside them.
  check_dem_options(s, c.source, s.allow_unstable_timestep);
  if (!(s.step > 0) || !std::isfinite(s.step)) throw CaseError(c.source + ": motion: field 'step' must be a positive number of m");
  if (s.max_steps < 0) throw CaseError(c.source + ": motion: field 'max_steps' must be >= 0");
}

void DemModel::Impl::build_blocks() {
  nb = static_cast<int>(c.blocks.size());
  support.assign(nb, 0);
  mass.assign(nb, 0);
  inertia.assign(nb, 0);
  weight.assign(nb, 0);
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
  kin.assign(nb, 0);
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
      weight[b] = mass[b] * c.gravity;
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
  scale_masses();
}

// Mass scaling (3DEC's density scaling for static problems): a quasi-static answer does not
// depend on the blocks' inertia, only on their weights and the joints, so the inertia of every
// free block is scaled by one factor that brings the acceleration the dead loads give the
// structure (its gravity, or loads over mass where gravity is 0) to kReferenceGravity. The
// protocol's times and speeds (hold cap, velocity tolerance, the servo's limits) then mean the
// same at any gravity: at g = 1e-4 a gravity mechanism otherwise takes 313 times longer in model
// time than at 9.81, and the 30 s hold cap, the 1e-5 m/s tolerance and the servo met a structure
// 313 times slower than the one they were set for (the tilting block "toppled" at 1 degree).
// Joint stiffness against weight is not scaled: it is physics (the overlaps under the weights).
// At g = 9.81 the factor is exactly 1.
void DemModel::Impl::scale_masses() {
  double m_sum = 0, loads = 0;
  for (int b = 0; b < nb; ++b)
    if (!support[b]) m_sum += mass[b];
  for (size_t l = 0; l < load_block.size(); ++l)
    if (!support[load_block[l]]) loads += load_force[l].norm();
  const double g = c.gravity > 0 ? c.gravity : loads / m_sum;
  mass_scale = g / kReferenceGravity;
  if (!(mass_scale > 0) || !std::isfinite(mass_scale))
    throw std::runtime_error(c.source + ": gravity and loads: the dead loads give the blocks no finite acceleration");
  if (mass_scale == 1.0) return;
  for (int b = 0; b < nb; ++b) mass[b] *= mass_scale, inertia[b] *= mass_scale;
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

  // Per block, the edges a contact can take as its incident edge are those of the block's convex
  // pieces: its faces, and for a block split into pieces (more than 8 vertices, or not convex)
  // the pieces' inner edges too, since a piece touching another block at a corner may clip one
  // of them. Each counts with the area a manifold point gives it (contact_forces: the clipped
  // length, at least 0.1 margin). For a convex block of at most 8 vertices this is its faces.
  double lam = 0;  // bound on omega^2
  for (int b = 0; b < nb; ++b) {
    if (support[b]) continue;
    double P = 0, J = 0;
    for (const std::vector<Vec2>& v : dem::convex_pieces(c.blocks[b].vertices))
      for (size_t i = 0, n = v.size(); i < n; ++i) {
        const Vec2 &p = v[i], &q = v[(i + 1) % n];
        const double L = std::max((q - p).norm(), 0.1 * margin);
        P += L;
        J += L * ((p - c0[b]).squaredNorm() + (q - c0[b]).squaredNorm()) / 2;
      }
    lam = std::max(lam, 2 * depth[b] * ((kn + ks) * P / mass[b] + std::max(kn, ks) * J / inertia[b]));
  }
  dt_crit = 2 / std::sqrt(lam);
  // Viscous damping at the contacts lowers the central differences' stability limit, for each
  // contact's own oscillator by contact_damping_step_factor (the amplification matrix's trace
  // against 1 + its determinant, 1 - 2 zeta omega dt). The damping grows with the frequency, so
  // the structure's fastest modes are damped more than zeta; the bound's own slack covers that
  // (dem/README.md, "Contact damping").
  dt_crit *= contact_damping_step_factor(s.contact_damping);  // exactly 1 without it
  inv_mass.assign(nb, 0.0);
  inv_inertia.assign(nb, 0.0);
  damp_force.assign(nb, Vec2::Zero());
  damp_torque.assign(nb, 0.0);
  for (int b = 0; b < nb; ++b)
    if (!support[b]) inv_mass[b] = 1 / mass[b], inv_inertia[b] = 1 / inertia[b];
  if (!(s.timestep_factor > 0) || !std::isfinite(s.timestep_factor) || (s.timestep_factor > 1 && !s.allow_unstable_timestep)) {
    std::ostringstream m;
    m << c.source << ": dem: field 'timestep_factor' = " << s.timestep_factor << " is outside (0, 1]: the time step would be "
      << s.timestep_factor * dt_crit << " s against a stability limit of " << dt_crit << " s (kn " << kn << " Pa/m, lightest/stiffest block"
      << (s.contact_damping > 0 ? ", contact damping " + std::to_string(s.contact_damping) : std::string())
      << "); refusing to run an unstable integration";
    throw std::runtime_error(m.str());
  }
  dt = s.timestep_factor * dt_crit;
  open_gap = s.open_gap.value_or(c.prd.contact_tolerance);
}

// A rigid-block model needs the joints' elastic overlaps small against the blocks. A lower bound
// on a block's overlap is its own weight (and loads) over kn times the area of all its joints
// (each joint's length times the smaller depth, as contact_forces takes it): the real overlap is
// larger, since only some joints carry it, and so are the blocks above. Where even that bound is
// 5% of the block's size, the DEM would compute a block sinking into its neighbours, not a
// masonry structure: a block 1e5 m deep on a 1 m deep ground carries its weight on 1 m of depth
// and sank 7.8 m into it at the tilting block's kn. Refused with the numbers instead, naming the
// field that makes the joints too soft: the depth where the joints at the block's own depth
// would hold it (its neighbours are shallower: a block's weight and joints both grow with its
// depth, so at matched depths the overlap does not depend on it), else the stiffness, by the
// option that set it (the tilting block at --stiffness-reduction 1e6 was told to match depths
// that matched, and not which of its settings made kn 100 Pa/m).
void DemModel::Impl::check_joint_stiffness() const {
  std::vector<double> area(nb, 0.0), own(nb, 0.0);  // joints at the smaller depth; at the block's own
  for (const Interface& J : detect_interfaces(c, c.prd.contact_tolerance)) {
    const double a = J.length() * std::min(depth[J.i], depth[J.j]);
    area[J.i] += a;
    area[J.j] += a;
    own[J.i] += J.length() * depth[J.i];
    own[J.j] += J.length() * depth[J.j];
  }
  for (int b = 0; b < nb; ++b) {
    if (support[b] || !(area[b] > 0)) continue;
    const double overlap = wref[b] / (kn * area[b]);
    const double size = std::sqrt(std::abs(signed_area(c.blocks[b].vertices)));
    if (overlap <= kMaxOverlap * size) continue;
    std::ostringstream m;
    m << c.source << ": block '" << printable(c.blocks[b].id) << "': ";
    const bool depths = wref[b] / (kn * own[b]) <= kMaxOverlap * size;
    if (depths)
      m << "field 'depth'";
    else if (s.stiffness_reduction != 1)
      m << "field '" << option_key(&DemOptions::stiffness_reduction) << "' = " << s.stiffness_reduction;
    else
      m << "field '" << (s.kn ? option_key(&DemOptions::kn) : option_key(&DemOptions::young_modulus)) << "' = " << (s.kn ? *s.kn : s.young_modulus);
    m << ": its joints would overlap by at least " << overlap << " m under its own weight (" << wref[b] << " N over kn " << kn << " Pa/m x "
      << area[b] << " m^2 of joints, each at the smaller depth of its two blocks), over " << kMaxOverlap * 100
      << "% of its size: far too soft a joint for a rigid-block model; "
      << (depths ? "match the depths, or stiffen the joints: " : "stiffen the joints: ") << "kn is "
      << (s.kn ? option_key(&DemOptions::kn) : option_key(&DemOptions::young_modulus) + " / h_block") << " divided by "
      << option_key(&DemOptions::stiffness_reduction) << " (" << s.stiffness_reduction << ")";
    throw CaseError(m.str());
  }
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
// A box in the tree's float coordinates, rounded outwards: it always contains the double box, so
// the exact test below never meets a pair the tree dropped.
b2AABB DemModel::Impl::float_box(const Vec2& lo, const Vec2& hi) const {
  const auto down = [](double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) <= x ? f : std::nextafter(f, -INFINITY);
  };
  const auto up = [](double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) >= x ? f : std::nextafter(f, INFINITY);
  };
  b2AABB box;
  box.lowerBound.Set(down(lo.x()), down(lo.y()));
  box.upperBound.Set(up(hi.x()), up(hi.y()));
  return box;
}

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
    tree.CreateProxy(float_box(lo[p], hi[p]), reinterpret_cast<void*>(static_cast<intptr_t>(p)));
  }
  std::vector<Pair> fresh;
  for (int p = 0; p < np; ++p) {
    scratch.clear();
    QueryCollector q{&tree, p, &scratch};
    tree.Query(&q, float_box(lo[p], hi[p]));
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
    force[b] = Vec2(0, -weight[b]);
    torque[b] = 0;
  }
  if (s.contact_damping > 0) {
    std::fill(damp_force.begin(), damp_force.end(), Vec2::Zero());
    std::fill(damp_torque.begin(), damp_torque.end(), 0.0);
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
    // Only the shear history is carried from one cycle to the next (with where it acted).
    const int nold = pr.n;
    const int old_key[2] = {pr.pt[0].key, pr.pt[1].key};
    const double old_fs[2] = {pr.pt[0].fs, pr.pt[1].fs};
    const Vec2 old_point[2] = {pr.pt[0].point, pr.pt[1].point};
    pr.n = 0;
    const double motion = moved[ba] + moved[bb] + (turned[ba] + turned[bb]) * pr.lever;
    if (!dem::collide_cached(&world_v[piece_off[pa]], &world_n[piece_off[pa]], piece_cnt[pa], &world_v[piece_off[pb]], &world_n[piece_off[pb]],
                             piece_cnt[pb], motion, pr.lever, pr.sat, m))
      continue;
    const double dep = std::min(depth[ba], depth[bb]);
    // Each point stands for half of the clipped joint, whether or not its partner is in contact,
    // so a joint's stiffness does not jump when a hinge opens. The floor keeps corner-to-corner
    // contacts from being arbitrarily soft.
    const double area = std::max(m.clip_length, 0.1 * margin) * dep / 2;
    const Vec2 n = m.normal, t = perp(n);
    // A point whose feature id is new inherits the shear of an old point within a quarter of the
    // joint of it: the same physical contact under another id. At an open hinge the two faces
    // meet at an angle, and which of them the manifold takes as its reference face (Box2D's
    // preference for A unless B is better by 0.1 b2_linearSlop, 0.5 mm) flips back and forth
    // once the hinge has opened about that far; each flip changed the id and dropped the
    // point's shear, and the nave's springing on the settlement cathedral lost 3.2e5 N (|T|/N
    // 0.23, far from friction) every 40 ms and slid some 11 um after each loss, a creep no
    // friction law allows (dem/README.md, "Shear history follows the contact, not the id").
    // The two points of a manifold are a clipped joint apart, so a quarter of it never pairs a
    // point with the other end's.
    const double same_point = 0.25 * std::max(m.clip_length, 0.1 * margin);
    for (int i = 0; i < m.count; ++i) {
      const dem::ManifoldPoint& mp = m.points[i];
      const int key = ((m.ref_edge * dem::kMaxPieceVertices + m.inc_edge) * 2 + m.flip) * 2 + mp.slot;
      double fs = 0;
      bool found = false;
      for (int o = 0; o < nold; ++o)
        if (old_key[o] == key) fs = old_fs[o], found = true;
      for (int o = 0; o < nold && !found; ++o)
        if ((old_point[o] - mp.point).squaredNorm() < same_point * same_point) fs = old_fs[o], found = true;
      const Vec2 ra = mp.point - pos[ba], rb = mp.point - pos[bb];
      const Vec2 vr = vel[bb] + spin[bb] * perp(rb) - vel[ba] - spin[ba] * perp(ra);
      const double overlap = -mp.separation;
      const double fn = kn * area * overlap;
      fs -= ks * area * vr.dot(t) * dt;
      const double cap = fn * tan_phi;
      const bool slipping = std::abs(fs) > cap;
      if (slipping) fs = std::copysign(cap, fs);
      const Vec2 f = fn * n + fs * t;  // on B
      if (s.contact_damping > 0) {
        // Kept apart from the springs' forces, so that local damping does not scale it
        // (integrate()): the damper's force is zeta of critical as it stands.
        const Vec2 g = damping_force(fn, fs, slipping, n, t, vr, ra, rb, ba, bb, area);
        damp_force[bb] += g;
        damp_torque[bb] += cross(rb, g);
        damp_force[ba] -= g;
        damp_torque[ba] -= cross(ra, g);
      }
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

// The viscous damping of the joint's relative motion at a contact point (contact_damping), on B:
// on each direction, zeta times the critical damping of the point's own oscillator, its spring
// against the effective mass of the two blocks at the point along that direction (translation
// and rotation about each centroid; a support's is infinite). The springs' history (fs) stays
// elastic, so the damping acts only while the joint moves. With it the normal force does not
// pull (nor does a point without one carry shear); a slipping point gets no shear damping (the
// friction already dissipates there); and the shear stays within friction of the damped normal
// force. Returned as what it adds to the springs' force fn n + fs t.
Vec2 DemModel::Impl::damping_force(double fn, double fs, bool slipping, const Vec2& n, const Vec2& t, const Vec2& vr, const Vec2& ra, const Vec2& rb,
                                   int ba, int bb, double area) const {
  const double zeta = s.contact_damping;
  const auto inv_mass_along = [&](const Vec2& u) {
    const double la = cross(ra, u), lb = cross(rb, u);
    return inv_mass[ba] + la * la * inv_inertia[ba] + inv_mass[bb] + lb * lb * inv_inertia[bb];
  };
  const double fn_d = std::max(0.0, fn - 2 * zeta * std::sqrt(kn * area / inv_mass_along(n)) * vr.dot(n));
  double fs_d = fs;
  if (!slipping) fs_d -= 2 * zeta * std::sqrt(ks * area / inv_mass_along(t)) * vr.dot(t);
  const double cap = fn_d > 0 ? fn_d * tan_phi : 0.0;  // no normal force, no shear (at phi = 90 too: 0 x inf)
  if (std::abs(fs_d) > cap) fs_d = std::copysign(cap, fs_d);
  return (fn_d - fn) * n + (fs_d - fs) * t;
}

void DemModel::Impl::integrate() {
  double ke_sum = 0;
  const double alpha = s.damping;
  const bool damping_on = s.contact_damping > 0;
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
      if (damping_on) support_work -= damp_force[b].dot(x - pos[b]) + damp_torque[b] * (th - ang[b]);
      vel[b] = (x - pos[b]) / dt;
      spin[b] = (th - ang[b]) / dt;
      pos[b] = x;
      ang[b] = th;
    } else {
      const Vec2 F = force[b];
      const double M = torque[b];
      // Local (non-viscous) damping: a fraction of the unbalanced force opposes the motion.
      Vec2 Fd(F.x() - alpha * std::abs(F.x()) *
                          (vel[b].x() > 0   ? 1
                           : vel[b].x() < 0 ? -1
                                            : 0),
              F.y() - alpha * std::abs(F.y()) *
                          (vel[b].y() > 0   ? 1
                           : vel[b].y() < 0 ? -1
                                            : 0));
      const double Md = M - alpha * std::abs(M) * (spin[b] > 0 ? 1 : spin[b] < 0 ? -1 : 0);
      // The contacts' dampers (contact_damping) act besides, not through, local damping.
      const Vec2 v_new = damping_on ? Vec2(vel[b] + dt * (Fd + damp_force[b]) / mass[b]) : Vec2(vel[b] + dt * Fd / mass[b]);
      const double w_new = damping_on ? spin[b] + dt * (Md + damp_torque[b]) / inertia[b] : spin[b] + dt * Md / inertia[b];
      // Kinetic energy at the force time: mean of the two half-step velocities.
      const double kb = 0.5 * mass[b] * (0.5 * (v_new + vel[b])).squaredNorm() + 0.5 * inertia[b] * std::pow(0.5 * (w_new + spin[b]), 2);
      ke_sum += kb;
      kin[b] = kb;
      vel[b] = v_new;
      spin[b] = w_new;
      pos[b] += dt * v_new;
      ang[b] += dt * w_new;
    }
    // The motion actually taken (differences of the stored doubles, so rounding is included).
    // Both are bounds, so |dx| + |dy| stands for the length: it is never shorter, and a looser
    // bound only means an earlier search or rebuild, never another result (collide_cached gives
    // collide()'s manifold whatever its cache holds; a rebuild keeps every touching pair).
    turned[b] = std::abs(ang[b] - th_old);
    moved[b] = (pos[b] - x_old).cwiseAbs().sum() + turned[b] * rmax[b];
    if ((pos[b] - pos_rb[b]).cwiseAbs().sum() + std::abs(ang[b] - ang_rb[b]) * rmax[b] > half_margin) due = true;
  }
  rebuild_due = due;
  d_now = d_target;
  ke = ke_sum;
  unbalanced_known = speed_known = ke_per_weight_known = false;
}

DemModel::DemModel(const Case& c, const DemSettings& s) : p_(std::make_unique<Impl>(c, s)) { p_->setup(); }
DemModel::~DemModel() = default;
void DemModel::cycle(long long n) {
  for (long long i = 0; i < n; ++i) p_->step();
}

}  // namespace masonry
