// DemModel's public accessors that read the simulator's state: energies, contact diagnostics,
// snapshots, corner gaps and the step record.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "dem/model_impl.hpp"
#include "model/energy.hpp"
#include "model/interfaces.hpp"

namespace masonry {

using namespace dem_detail;

std::vector<std::pair<int, int>> DemModel::off_joint_contacts(const std::vector<Interface>& joints) const {
  const Impl& m = *p_;
  const auto key = [](int a, int b) { return std::pair<int, int>(std::min(a, b), std::max(a, b)); };
  std::map<std::pair<int, int>, std::vector<int>> joints_of;
  for (size_t k = 0; k < joints.size(); ++k) joints_of[key(joints[k].i, joints[k].j)].push_back(static_cast<int>(k));
  // A point is on a joint when it lies on the joint's segment as either block carries it: a
  // joint that slid keeps its contact on the one copy or the other. Within a tenth of the broad
  // phase's margin (half a percent of the smallest block): the overlaps are microns.
  const double tol = 0.1 * m.margin;
  const auto on_joint = [&](const Interface& J, const Vec2& x) {
    for (const int b : {J.i, J.j}) {
      const double c = std::cos(m.ang[b]), sn = std::sin(m.ang[b]);
      const Vec2 a = m.pos[b] + rotate(J.a - m.origin - m.c0[b], c, sn), e = m.pos[b] + rotate(J.b - m.origin - m.c0[b], c, sn) - a;
      const double t = std::clamp((x - a).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
      if ((a + t * e - x).norm() <= tol) return true;
    }
    return false;
  };
  std::vector<std::pair<int, int>> out;
  for (const Pair& pr : m.pairs) {
    const std::pair<int, int> k = key(pr.ba, pr.bb);
    const auto it = joints_of.find(k);
    for (int i = 0; i < pr.n; ++i) {
      const PointState& ps = pr.pt[i];
      if (!(ps.overlap > 0)) continue;  // a touch without force (corners meeting at zero gap)
      bool on = false;
      if (it != joints_of.end())
        for (const int j : it->second) on = on || on_joint(joints[size_t(j)], ps.point);
      if (!on) {
        out.push_back(k);
        break;
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double DemModel::kn() const { return p_->kn; }
double DemModel::ks() const { return p_->ks; }
double DemModel::critical_dt() const { return p_->dt_crit; }
double DemModel::dt() const { return p_->dt; }
double DemModel::mass_scale() const { return p_->mass_scale; }
double DemModel::time() const { return p_->time; }
long long DemModel::cycles() const { return p_->cycles; }
void DemModel::set_support_parameter(double d) { p_->d_target = d; }
double DemModel::support_parameter() const { return p_->d_now; }
// The diagnostics of the last cycle, read from its arrays once asked for (model_impl.hpp): each
// the largest over the free blocks of a block's value, computed at most once per cycle. (The
// same expressions and order as when integrate() computed them every cycle.)
template <class Value>
double DemModel::Impl::once_per_cycle(bool& known, double& cached, Value value) const {
  if (!known) {
    double largest = 0;
    for (int b = 0; b < nb; ++b)
      if (!support[b]) largest = std::max(largest, value(b));
    cached = largest;
    known = true;
  }
  return cached;
}

double DemModel::Impl::unbalanced_of_cycle() const {
  // With contact damping the dampers' force is part of what is out of balance.
  const bool dampers = s.contact_damping > 0;
  return once_per_cycle(unbalanced_known, unbalanced, [&](int b) {
    const Vec2 F = dampers ? Vec2(force[b] + damp_force[b]) : force[b];
    const double M = dampers ? torque[b] + damp_torque[b] : torque[b];
    return std::max(F.norm(), std::abs(M) / gyr[b]) / wref[b];
  });
}
double DemModel::Impl::speed_of_cycle() const {
  return once_per_cycle(speed_known, speed, [&](int b) { return vel[b].norm() + std::abs(spin[b]) * gyr[b]; });
}
double DemModel::Impl::ke_per_weight_of_cycle() const {
  return once_per_cycle(ke_per_weight_known, ke_per_weight, [&](int b) { return kin[b] / wref[b]; });
}

double DemModel::unbalanced_ratio() const { return p_->unbalanced_of_cycle(); }
double DemModel::max_speed() const { return p_->speed_of_cycle(); }
double DemModel::max_kinetic_per_weight() const { return p_->ke_per_weight_of_cycle(); }
void DemModel::stop_free_blocks() {
  Impl& m = *p_;
  m.speed_of_cycle();  // the cycle's speed is the one before the stop
  for (int b = 0; b < m.nb; ++b)
    if (!m.support[b]) m.vel[b] = Vec2::Zero(), m.spin[b] = 0;
}
DemBlockState DemModel::block(int b) const { return {p_->pos[b] + p_->origin, p_->ang[b], p_->vel[b], p_->spin[b]}; }
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
    if (!m.support[b]) e += m.weight[b] * (m.pos[b].y() - m.dt * m.vel[b].y() - m.c0[b].y());
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
    if (!m.support[b]) w -= m.weight[b] * (m.pos[b].y() - m.c0[b].y());
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
  d->unbalanced = m.unbalanced_of_cycle();
  d->speed = m.speed_of_cycle();
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
  m.unbalanced_known = m.speed_known = true;
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
      const Vec2 P = (corner == 0 ? J.a : J.b) - m.origin;  // joints come in the world frame
      const Vec2 pi = m.pos[J.i] + rotate(P - m.c0[J.i], ci, si), pj = m.pos[J.j] + rotate(P - m.c0[J.j], cj, sj);
      g.push_back(corner_gap(pi, ni, pj, nj));
    }
  }
  return g;
}

StepRecord DemModel::record(const std::vector<Interface>& joints, const std::vector<double>& gap_reference) const {
  const Impl& m = *p_;
  StepRecord r;
  r.d = m.d_now;
  for (int b = 0; b < m.nb; ++b) r.poses.push_back({m.pos[b].x(), m.pos[b].y(), m.ang[b]});
  // Energy in the model's frame (it is relative to the initial configuration), poses in the world's.
  r.energy = potential_energy(m.c, r.poses);
  for (Pose& p : r.poses) p.x += m.origin.x(), p.y += m.origin.y();

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
  std::map<std::pair<int, int>, std::vector<int>> joints_of;
  for (size_t k = 0; k < joints.size(); ++k) joints_of[{joints[k].i, joints[k].j}].push_back(static_cast<int>(k));
  struct Acc {
    double n = 0, s = 0;
    double moment = 0;  // of the contact forces about the model's frame's origin
    Vec2 np{0, 0};
  };
  std::vector<Acc> acc(joints.size());
  const std::vector<double> gaps = corner_gaps(joints);
  if (!gap_reference.empty() && gap_reference.size() != gaps.size()) throw std::logic_error("DemModel::record: gap reference of another joint list");
  auto joint_frame = [&](const Interface& J, Vec2& n, Vec2& t) {
    const double th = m.ang[J.i];
    n = rotate(J.normal, std::cos(th), std::sin(th));
    t = rotate((J.b - J.a).normalized(), std::cos(th), std::sin(th));
  };
  // The joint a contact point between blocks i0 < j0 belongs to. Two blocks may meet at several
  // joints (a block seated in a support's notch: its floor and both sides), and then the point
  // goes to the joint whose face it lies on: among those whose normal is within 8 degrees of the
  // contact's, the nearest (its segment as block i carries it), else the best aligned.
  auto joint_for = [&](int i0, int j0, const PointState& ps) {
    const auto it = joints_of.find({i0, j0});
    if (it == joints_of.end()) return -1;
    if (it->second.size() == 1) return it->second.front();
    int best = -1;
    double best_align = -1, best_dist = INFINITY;
    for (const int k : it->second) {
      const Interface& J = joints[size_t(k)];
      Vec2 n, t;
      joint_frame(J, n, t);
      const double align = std::abs(n.dot(ps.normal)), ci = std::cos(m.ang[J.i]), si = std::sin(m.ang[J.i]);
      const Vec2 a = m.pos[J.i] + rotate(J.a - m.origin - m.c0[J.i], ci, si), b = m.pos[J.i] + rotate(J.b - m.origin - m.c0[J.i], ci, si);
      const double dist = distance_to_segment(ps.point, a, b);
      const bool aligned = align > 0.99, best_aligned = best_align > 0.99;
      if (best < 0 || (aligned && (!best_aligned || dist < best_dist)) || (!aligned && !best_aligned && align > best_align))
        best = k, best_align = align, best_dist = dist;
    }
    return best;
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
      const int k = joint_for(std::min(pr.ba, pr.bb), std::max(pr.ba, pr.bb), ps);
      if (k < 0) continue;
      const Interface& J = joints[size_t(k)];
      Vec2 n, t;
      joint_frame(J, n, t);
      const Vec2 fj = pr.bb == J.j ? f : Vec2(-f);
      Acc& a = acc[size_t(k)];
      const double fn = fj.dot(n);
      a.n += fn;
      a.s += fj.dot(t);
      a.np += fn * ps.point;
      a.moment += cross(ps.point, fj);
    }
  for (size_t k = 0; k < joints.size(); ++k) {
    const Interface& J = joints[k];
    if (acc[k].n > 0) {
      JointForce f;
      f.joint = static_cast<int>(k);
      f.normal = acc[k].n;
      f.shear = acc[k].s;
      Vec2 t;
      joint_frame(J, f.n, t);
      // On the resultant's line of action (on_line_of_action), nearest to the normal forces'
      // centre: the contact points stand at different levels across the joint (overlaps, a
      // hinge's turn), and the shear placed at that centre left the resultant's moment off by
      // the shear times that.
      const Vec2 c = acc[k].np / acc[k].n;
      const Vec2 R = f.normal * f.n + f.shear * t;
      f.point = on_line_of_action(c, R, acc[k].moment - cross(c, R)) + m.origin;
      r.forces.push_back(f);
    }
    // A corner is open when both blocks' copies of it stand off the other block's face
    // (corner_gap) by more than open_gap beyond its gap in the reference state (a settled gap is
    // not a hinge).
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
