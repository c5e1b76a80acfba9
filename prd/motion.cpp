// Finite rigid motion along a mechanism, the gaps it gives, the contact state and the
// configuration records.
#include "model/energy.hpp"
#include "prd/internal.hpp"

namespace masonry::prd_detail {

// Rigid increment (u at point c, rotation th) applied as a finite rotation about its pole:
// returns the displacement of c. (R(th) - I)/th is evaluated without cancellation, and tends
// to the plain translation as th -> 0.
Vec2 pole_displacement(const Vec2& u, double th) {
  double s, q;  // s = sin(th)/th, q = (cos(th) - 1)/th
  if (std::abs(th) < 1e-6) {
    s = 1 - th * th / 6;
    q = -th / 2 + th * th * th / 24;
  } else {
    const double h = std::sin(th / 2);
    s = std::sin(th) / th;
    q = -2 * h * h / th;
  }
  // (R - I)/th = [[q, -s], [s, q]]; displacement = -((R - I)/th) perp(u).
  const Vec2 w = perp(u);
  return -Vec2(q * w.x() - s * w.y(), s * w.x() + q * w.y());
}

Increment support_increment(const Model& m, int b, double h) {
  Increment inc;
  inc.at = m.cen[b];
  if (m.motion_of[b] < 0 || h == 0) return inc;
  const SupportMotion& s = m.c->motion.supports[m.motion_of[b]];
  inc.at = m.pos(b, s.about);
  inc.u = h * s.translation;
  inc.th = h * s.rotation;
  return inc;
}

std::vector<JointInfo> joint_infos(const Model& m) {
  std::vector<JointInfo> out;
  for (const Interface& f : m.joints) out.push_back({f.i, f.j, f.a, f.b});
  return out;
}

std::vector<Pose> poses(const Model& m) {
  std::vector<Pose> out;
  for (size_t b = 0; b < m.cen.size(); ++b) out.push_back({m.cen[b].x(), m.cen[b].y(), m.angle[b]});
  return out;
}

void record_corners(const Model& m, StepRecord& rec) {
  std::vector<char> cracked(m.joints.size(), 0);
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (m.ends[e].closed) continue;
    const Endpoint& ep = m.ends[e];
    rec.open_corners.push_back({ep.joint, ep.corner, m.gap(ep)});
    cracked[ep.joint] = 1;
  }
  for (size_t k = 0; k < cracked.size(); ++k)
    if (cracked[k]) rec.cracked.push_back(static_cast<int>(k));
}

// Per endpoint, from the LP just solved with step h (open corners held over h_open, see
// update_lp): the gap on the current configuration and its rate of change along the mechanism
// (m per m of d).
void gaps_and_rates(const Model& m, double h, double h_open, std::vector<double>& gap, std::vector<double>& rate) {
  const std::vector<double> slack = slacks(m, h);
  gap.resize(m.ends.size());
  rate.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Endpoint& ep = m.ends[e];
    gap[e] = m.gap(ep);
    const double held = !ep.closed && h_open < h ? gap[e] * h / h_open : gap[e];  // the row's gap
    rate[e] = (slack[e] - held) / h;
  }
}

// Contact state after a step h along the mechanism of the LP solved with step h_lp. An open
// corner closes when its gap at the end of the step is below the tolerance. A closed corner
// opens when it would open by more than the tolerance over the reference step h_ref: its gap
// at the end of the LP's step (the residual gap of earlier finite updates is taken back in
// that step) scaled to h_ref, so the state does not depend on the step being taken. With
// h = h_lp = h_ref both rules are "gap at the end of the step below the tolerance".
std::vector<char> closed_after(const Model& m, const std::vector<double>& gap, const std::vector<double>& rate, double h_lp, double h, double h_ref) {
  std::vector<char> out(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e)
    out[e] = m.ends[e].closed ? (gap[e] + rate[e] * h_lp) * (h_ref / h_lp) <= m.tol : gap[e] + rate[e] * h <= m.tol;
  return out;
}

// Where block b is after a finite update by h along the path: a free block rotates about its
// own pole, a support moves as prescribed.
void pose_after(const Model& m, const Path& path, size_t b, double h, Vec2& cen, double& angle) {
  cen = m.cen[b];
  angle = m.angle[b];
  if (m.col[b] > 0) {
    const Vec2 u(path.at(m.col[b], h) * h, path.at(m.col[b] + 1, h) * h);
    const double th = path.at(m.col[b] + 2, h) * h / m.radius[b];
    cen += pole_displacement(u, th);
    angle += th;
  } else if (m.motion_of[b] >= 0) {
    const Increment inc = support_increment(m, static_cast<int>(b), h);
    cen = inc.at + rot(inc.th) * (cen - inc.at) + inc.u;
    angle += inc.th;
  }
}

void advance(Model& m, const Path& path, double h) {
  for (size_t b = 0; b < m.cen.size(); ++b) {
    Vec2 cen;
    double angle;
    pose_after(m, path, b, h, cen, angle);
    m.cen[b] = cen;
    m.angle[b] = angle;
  }
}

// The gap of corner e after a finite update by h along the path, exactly (not to first order).
double gap_after(const Model& m, const Path& U, size_t e, double h) {
  const Endpoint& ep = m.ends[e];
  const Interface& jt = m.joints[ep.joint];
  Vec2 ci, cj;
  double ai, aj;
  pose_after(m, U, jt.i, h, ci, ai);
  pose_after(m, U, jt.j, h, cj, aj);
  const Vec2 pi = ci + rot(ai) * (ep.X - m.c0[jt.i]), pj = cj + rot(aj) * (ep.Xj - m.c0[jt.j]);
  return (pj - pi).dot(rot(ai) * jt.normal);
}

namespace {
// Whether x is one of the polygon's vertices (within tol, m).
bool is_vertex(const std::vector<Vec2>& poly, const Vec2& x, double tol) {
  for (const Vec2& v : poly)
    if ((v - x).norm() <= tol) return true;
  return false;
}

// Whether corner e's copy on block j is the contact point, its copy on block i then a point of
// i's face: the copy that is a corner of its block (where one face runs on past the other, the
// other copy is a point of that face, and a slip moves it away from the contact), or of two
// corners the inner one.
bool j_copy_touches(const Model& m, const Endpoint& ep) {
  const Case& c = *m.c;
  const Interface& jt = m.joints[ep.joint];
  const bool ci = is_vertex(c.blocks[jt.i].vertices, ep.X, m.tol), cj = is_vertex(c.blocks[jt.j].vertices, ep.Xj, m.tol);
  if (ci != cj) return cj;
  const Vec2 along = rot(m.angle[jt.i]) * (jt.b - jt.a);  // from corner A to B
  return (ep.corner == 0) == ((m.on_j(ep) - m.on_i(ep)).dot(along) > 0);
}
}  // namespace

void start_from(Model& m, const PrdStart& start) {
  const Case& c = *m.c;
  if (start.poses.size() != c.blocks.size())
    throw std::invalid_argument(c.source + ": prd: the start configuration has " + std::to_string(start.poses.size()) + " poses for " +
                                std::to_string(c.blocks.size()) + " blocks (" + start.source + ")");
  if (!std::isfinite(start.d)) throw std::invalid_argument(c.source + ": prd: the start's d is not a number (" + start.source + ")");
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    const Pose& q = start.poses[b];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.angle))
      throw std::invalid_argument(c.source + ": block '" + printable(c.blocks[b].id) + "': the start pose is not a number (" + start.source + ")");
    m.cen[b] = Vec2(q.x, q.y);
    m.angle[b] = q.angle;
  }
  // Touching as a DEM reads it (corner_gap): where one block's face runs on past the corner, its
  // copy's stand-off from the other's turned face is slip x sin(theta), not an opening.
  std::vector<double> gap(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    gap[e] = corner_gap(m.on_i(ep), m.normal(ep), m.on_j(ep), rot(m.angle[jt.j]) * Vec2(-jt.normal));
    ep.closed = gap[e] <= m.tol;
  }
  if (start.offsets == StartOffsets::take_back) return;
  // Kept offsets: both blocks' material points of a touching corner move to where a DEM applies
  // its force (dem/README.md, "Manifold"), so that its overlap and elastic shear are the joint's
  // geometry from here on. Along the joint: at the end of the faces' overlap, the copy that is
  // the contact point (j_copy_touches). Across it: midway between the two faces at the more
  // compressed of the joint's touching corners, and both touching corners at that level, so that
  // the joint stays a straight line along block i's face: PRD keeps a joint from slipping by one
  // row at one corner, which holds the whole joint only while its corners lie on such a line
  // (with them a few tenths of a mm apart across it, a block rocking about one corner would have
  // to slip there; a tilting block on joints ten times softer then stood 1.4 mrad past the DEM's
  // toppling). An open corner's gap is a real one and stays.
  for (size_t k = 0; k < m.joints.size(); ++k) {
    const Interface& jt = m.joints[k];
    const Vec2 n = m.normal(m.ends[2 * k]);
    Vec2 at[2];
    int deepest = -1;
    for (int corner = 0; corner < 2; ++corner) {
      const size_t e = 2 * k + corner;
      const Endpoint& ep = m.ends[e];
      if (!ep.closed) continue;
      const Vec2 pi = m.on_i(ep), pj = m.on_j(ep);
      const Vec2 p = j_copy_touches(m, ep) ? pj : pi;
      at[corner] = p + (0.5 * (pi + pj) - p).dot(n) * n;
      if (deepest < 0 || gap[e] < gap[2 * k + deepest]) deepest = corner;
    }
    for (int corner = 0; corner < 2; ++corner) {
      Endpoint& ep = m.ends[2 * k + corner];
      if (!ep.closed) continue;
      const Vec2 x = at[corner] + (at[deepest] - at[corner]).dot(n) * n;
      ep.X = m.material(jt.i, x);
      ep.Xj = m.material(jt.j, x);
    }
  }
}

void hold_corners(Model& m, const std::vector<std::string>& names) {
  if (names.empty()) return;
  const std::vector<int> nth = pair_ordinals(m.joints);
  for (const std::string& want : names) {
    // A name is one corner's: the case loader refuses ids holding '/' or ':' (id_fault), and
    // joints between the same two blocks take further corner letters.
    bool found = false;
    for (size_t e = 0; e < m.ends.size(); ++e) {
      const Interface& jt = m.joints[m.ends[e].joint];
      if (corner_name(*m.c, jt.i, jt.j, m.ends[e].corner, nth[size_t(m.ends[e].joint)]) != want) continue;
      m.ends[e].held = found = true;
    }
    if (!found)
      throw std::runtime_error(m.c->source + ": prd: field 'hold_closed': no joint corner '" + printable(want) +
                               "' (names as BLOCK/BLOCK:A, the blocks in the results' order; C, D and on for a second joint between them)");
  }
}

void record_held(const Model& m, StepRecord& rec) {
  std::vector<int> nth;  // only where a corner is held
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (!m.ends[e].held) continue;
    if (nth.empty()) nth = pair_ordinals(m.joints);
    const Interface& jt = m.joints[m.ends[e].joint];
    rec.held_corners.push_back({corner_name(*m.c, jt.i, jt.j, m.ends[e].corner, nth[size_t(m.ends[e].joint)]), corner_force(m, e)});
  }
}

void set_closed(Model& m, const std::vector<char>& closed) {
  for (size_t e = 0; e < m.ends.size(); ++e) m.ends[e].closed = closed[e];
}

// The contact state after a move, where the corners it sets closed that were open have just
// touched: each such corner's no-sliding row holds from where it touched. While it was open it
// could slide, so the tangential offset of its two material points is that slide, not the drift
// of the finite update that update_lp takes back for a corner closed all along; taken back in
// one step, the slides of several corners that touch together ask the blocks for motions that
// agree only to second order, and the LP is infeasible by a few nanometres (a stack-bond wall's
// settling half landing on its ground). So the copy that is not the contact point (a point of
// the other block's face, j_copy_touches) moves along the face to the contact point; the gap
// across the joint is left for the no-penetration row to take back.
void close_corners(Model& m, const std::vector<char>& closed) {
  for (size_t e = 0; e < m.ends.size(); ++e) {
    Endpoint& ep = m.ends[e];
    if (!closed[e] || ep.closed) continue;
    const Interface& jt = m.joints[ep.joint];
    const Vec2 pi = m.on_i(ep), pj = m.on_j(ep), t = perp(m.normal(ep));
    const double slip = (pj - pi).dot(t);
    if (j_copy_touches(m, ep))
      ep.X = m.material(jt.i, pi + slip * t);
    else
      ep.Xj = m.material(jt.j, pj - slip * t);
  }
  set_closed(m, closed);
}

StepRecord configuration_record(const Model& m, int index, double d) {
  StepRecord rec;
  rec.index = index;
  rec.d = d;
  rec.poses = poses(m);
  rec.energy = potential_energy(*m.c, rec.poses);
  record_corners(m, rec);
  return rec;
}

}  // namespace masonry::prd_detail
