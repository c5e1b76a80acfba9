// PRD: one GLPK problem per run, rows and bounds rewritten in place each step.
//
// Variables: per free block b, U'_b = (u_x, u_y, theta * L_b) / step, the rigid increment at
// the current centroid in units of the step (so GLPK's tolerances are relative to the step)
// with the rotation scaled by the block's radius L_b (so all coefficients are O(1)).
// Rows: per joint endpoint k, a no-penetration row  n.[u]_k >= -g_k  and a no-sliding row
// t.[u]_k = 0. For a rigid relative motion t.[u] is the same at both ends of a joint, so the
// two no-sliding rows of a closed joint are one constraint written twice; kept both, their
// right-hand sides differ by round-off and the simplex cycles between phases. So a joint has
// one active no-sliding row, at its first closed endpoint; the others are made free. The row
// duals are then the endpoint forces in N: f_n >= 0 on the first, f_t on the second.
#include <glpk.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "interfaces.hpp"
#include "prd.hpp"

namespace masonry {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Eigen::Matrix2d rot(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}
Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

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

struct GlpDeleter {
  void operator()(glp_prob* p) const { glp_delete_prob(p); }
};

struct Endpoint {
  int joint;
  int corner;    // 0 = A, 1 = B
  Vec2 X;        // material point (initial configuration), shared by both blocks at the start
  bool closed = true;
};

struct Model {
  const Case* c = nullptr;
  double tol = 1e-5;
  std::vector<Interface> joints;
  std::vector<Endpoint> ends;  // 2 per joint: rows 2e+1 (normal) and 2e+2 (tangential)
  std::vector<int> col;        // first GLPK column of each block (1-based), -1 for supports
  std::vector<double> radius;  // L_b, m
  std::vector<Vec2> c0;        // initial centroids
  std::vector<Vec2> cen;       // current centroids
  std::vector<double> angle;   // rotation since the start
  std::vector<int> motion_of;  // index into c->motion.supports, or -1
  std::vector<double> weight;  // N
  int ncols = 0;
  std::unique_ptr<glp_prob, GlpDeleter> lp;
  double lp_s = 0;
  long long lp_solves = 0;

  Vec2 pos(int b, const Vec2& X) const { return cen[b] + rot(angle[b]) * (X - c0[b]); }
  Vec2 normal(const Endpoint& e) const { return rot(angle[joints[e.joint].i]) * joints[e.joint].normal; }
  // Whether endpoint e carries its joint's no-sliding row (see the top of this file).
  bool sliding_row(size_t e) const { return ends[e].closed && (ends[e].corner == 0 || !ends[e - 1].closed); }
};

// Prescribed small increment of a support at the current configuration, for a step h.
struct Increment {
  Vec2 u{0, 0};  // at point `at`
  double th = 0;
  Vec2 at{0, 0};
  Vec2 at_point(const Vec2& x) const { return u + th * perp(x - at); }
};

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

Model build_model(const Case& c, double tol) {
  Model m;
  m.c = &c;
  m.tol = tol;
  m.joints = detect_interfaces(c, tol);
  const size_t nb = c.blocks.size();
  m.col.assign(nb, -1);
  m.radius.assign(nb, 1.0);
  m.c0.resize(nb);
  m.weight.assign(nb, 0.0);
  m.motion_of.assign(nb, -1);
  for (size_t k = 0; k < c.motion.supports.size(); ++k) m.motion_of[c.motion.supports[k].block] = static_cast<int>(k);
  for (size_t b = 0; b < nb; ++b) {
    const Block& bl = c.blocks[b];
    m.c0[b] = centroid(bl.vertices);
    double r = 0;
    for (const Vec2& v : bl.vertices) r = std::max(r, (v - m.c0[b]).norm());
    m.radius[b] = r;
    if (!bl.support) {
      m.col[b] = m.ncols + 1;
      m.ncols += 3;
      m.weight[b] = block_mass(bl) * c.gravity;
    }
  }
  m.cen = m.c0;
  m.angle.assign(nb, 0.0);
  for (size_t k = 0; k < m.joints.size(); ++k) {
    m.ends.push_back({static_cast<int>(k), 0, m.joints[k].a});
    m.ends.push_back({static_cast<int>(k), 1, m.joints[k].b});
  }

  m.lp.reset(glp_create_prob());
  glp_prob* lp = m.lp.get();
  glp_set_obj_dir(lp, GLP_MIN);
  if (m.ncols > 0) glp_add_cols(lp, m.ncols);
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_FR, 0, 0);
  if (!m.ends.empty()) glp_add_rows(lp, 2 * static_cast<int>(m.ends.size()));
  return m;
}

// Generalised loads on the current configuration: (F_x, F_y, M / L_b) per free block, so the
// objective is -F.U' in the scaled variables.
std::vector<double> generalised_loads(const Model& m) {
  std::vector<double> f(m.ncols + 1, 0.0);
  const Case& c = *m.c;
  for (size_t b = 0; b < c.blocks.size(); ++b)
    if (m.col[b] > 0) f[m.col[b] + 1] -= m.weight[b];
  for (const Load& l : c.loads) {
    const int k = m.col[l.block];
    const Vec2 p = m.pos(l.block, l.point);
    f[k] += l.force.x();
    f[k + 1] += l.force.y();
    f[k + 2] += cross(p - m.cen[l.block], l.force) / m.radius[l.block];
  }
  return f;
}

// Rewrites every row, bound and objective coefficient for the current configuration and a
// support step h (0 for the analysis as it stands). The problem's structure never changes.
void update_lp(Model& m, double h, double scale) {
  glp_prob* lp = m.lp.get();
  const std::vector<double> f = generalised_loads(m);
  for (int j = 1; j <= m.ncols; ++j) glp_set_obj_coef(lp, j, -f[j]);
  std::vector<Increment> inc(m.c->blocks.size());
  for (size_t b = 0; b < inc.size(); ++b)
    if (m.col[b] < 0) inc[b] = support_increment(m, static_cast<int>(b), h);

  int ind[7];
  double val[7];
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const Vec2 pi = m.pos(jt.i, ep.X), pj = m.pos(jt.j, ep.X);
    const Vec2 n = m.normal(ep), t = perp(n);
    // Both blocks' velocities are taken at the midpoint of the corner's two material points:
    // they coincide up to the second-order drift of the finite update, and one point makes the
    // duals an exact equilibrium of forces applied where read_forces reports them.
    const Vec2 p = 0.5 * (pi + pj);
    for (int r = 0; r < 2; ++r) {
      const Vec2 d = r == 0 ? n : t;
      int cnt = 0;
      double known = 0;  // d.[u] from the supports' prescribed increments
      for (int side = 0; side < 2; ++side) {
        const int b = side == 0 ? jt.i : jt.j;
        const double sgn = side == 0 ? -1.0 : 1.0;
        if (m.col[b] > 0) {
          const int k = m.col[b];
          ind[++cnt] = k, val[cnt] = sgn * d.x();
          ind[++cnt] = k + 1, val[cnt] = sgn * d.y();
          ind[++cnt] = k + 2, val[cnt] = sgn * cross(p - m.cen[b], d) / m.radius[b];
        } else {
          known += sgn * d.dot(inc[b].at_point(p));
        }
      }
      const int row = 2 * static_cast<int>(e) + 1 + r;
      glp_set_mat_row(lp, row, cnt, ind, val);
      if (r == 0) {
        const double gap = (pj - pi).dot(n);
        glp_set_row_bnds(lp, row, GLP_LO, (-gap - known) / scale, 0);
      } else if (m.sliding_row(e)) {
        // The tangential offset left by earlier finite updates is taken back here, so that
        // the drift of a closed corner never accumulates over the run.
        const double slip = (pj - pi).dot(t);
        glp_set_row_bnds(lp, row, GLP_FX, (-slip - known) / scale, (-slip - known) / scale);
      } else {
        glp_set_row_bnds(lp, row, GLP_FR, 0, 0);
      }
    }
  }
}

// Runs the primal simplex from the previous step's basis (the warm start that makes a run
// fast). Degenerate LPs can stall; an iteration limit catches that, and the solve is repeated
// from a fresh basis with the textbook ratio test, then, as a last resort, in exact rational
// arithmetic, so a run never hangs and never reports a status GLPK did not prove.
int solve(Model& m) {
  glp_prob* lp = m.lp.get();
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.meth = GLP_PRIMAL;
  parm.it_lim = 1000 + 50 * (glp_get_num_rows(lp) + glp_get_num_cols(lp));
  auto conclusive = [&](int rc) {
    const int st = glp_get_status(lp);
    return rc == 0 && (st == GLP_OPT || st == GLP_UNBND || st == GLP_NOFEAS);
  };
  const auto t0 = Clock::now();
  int rc = glp_simplex(lp, &parm);
  if (!conclusive(rc)) {
    glp_adv_basis(lp, 0);
    parm.r_test = GLP_RT_STD;
    rc = glp_simplex(lp, &parm);
  }
  if (!conclusive(rc)) {
    glp_adv_basis(lp, 0);
    rc = glp_exact(lp, &parm);
  }
  m.lp_s += seconds_since(t0);
  ++m.lp_solves;
  if (!conclusive(rc)) throw std::runtime_error("GLPK could not solve the step's LP (code " + std::to_string(rc) + ")");
  return glp_get_status(lp);
}

double total_weight(const Model& m) {
  double w = 0;
  for (double x : m.weight) w += x;
  for (const Load& l : m.c->loads) w -= std::min(0.0, l.force.y());
  return w;
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

// Forces from the row duals: joint resultants and support reactions, on the current geometry.
void read_forces(const Model& m, StepRecord& rec) {
  glp_prob* lp = m.lp.get();
  const Case& c = *m.c;
  std::vector<Reaction> reac;
  std::vector<int> reac_of(c.blocks.size(), -1);
  for (size_t b = 0; b < c.blocks.size(); ++b)
    if (c.blocks[b].support) {
      reac_of[b] = static_cast<int>(reac.size());
      reac.push_back({c.blocks[b].id, Vec2(0, 0), 0.0});
    }
  for (size_t k = 0; k < m.joints.size(); ++k) {
    const Interface& jt = m.joints[k];
    double N = 0, T = 0;
    Vec2 moment_point(0, 0);
    Vec2 n(0, 0);
    for (int corner = 0; corner < 2; ++corner) {
      const size_t e = 2 * k + corner;
      const Endpoint& ep = m.ends[e];
      const double fn = glp_get_row_dual(lp, 2 * static_cast<int>(e) + 1);
      const double ft = m.sliding_row(e) ? glp_get_row_dual(lp, 2 * static_cast<int>(e) + 2) : 0.0;
      n = m.normal(ep);
      const Vec2 p = 0.5 * (m.pos(jt.i, ep.X) + m.pos(jt.j, ep.X));
      N += fn;
      T += ft;
      moment_point += fn * p;
      const Vec2 fk = fn * n + ft * perp(n);  // on block j
      // Reactions: the force the structure receives from the support, and its moment.
      for (int side = 0; side < 2; ++side) {
        const int b = side == 0 ? jt.i : jt.j;
        if (reac_of[b] < 0) continue;
        const Vec2 on_structure = side == 0 ? fk : Vec2(-fk);
        Reaction& r = reac[reac_of[b]];
        r.force += on_structure;
        const Vec2 about = m.motion_of[b] >= 0 ? m.pos(b, c.motion.supports[m.motion_of[b]].about) : m.cen[b];
        r.moment += cross(p - about, on_structure);
      }
    }
    if (N > 0 || T != 0) {
      JointForce jf;
      jf.joint = static_cast<int>(k);
      jf.normal = N;
      jf.shear = T;
      jf.n = n;
      jf.point = N > 0 ? Vec2(moment_point / N) : Vec2(0.5 * (m.pos(jt.i, jt.a) + m.pos(jt.i, jt.b)));
      rec.forces.push_back(jf);
    }
  }
  rec.reactions = std::move(reac);
}

// Slack of each no-penetration row in m: the endpoint's gap at the end of the increment,
// to first order.
std::vector<double> slacks(const Model& m, double scale) {
  std::vector<double> s(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const int row = 2 * static_cast<int>(e) + 1;
    s[e] = (glp_get_row_prim(m.lp.get(), row) - glp_get_row_lb(m.lp.get(), row)) * scale;
  }
  return s;
}

void record_corners(const Model& m, StepRecord& rec) {
  std::vector<char> cracked(m.joints.size(), 0);
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (m.ends[e].closed) continue;
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const double gap = (m.pos(jt.j, ep.X) - m.pos(jt.i, ep.X)).dot(m.normal(ep));
    rec.open_corners.push_back({ep.joint, ep.corner, gap});
    cracked[ep.joint] = 1;
  }
  for (size_t k = 0; k < cracked.size(); ++k)
    if (cracked[k]) rec.cracked.push_back(static_cast<int>(k));
}

double energy(const Model& m) {
  double e = 0;
  for (size_t b = 0; b < m.cen.size(); ++b) e += m.weight[b] * (m.cen[b].y() - m.c0[b].y());
  for (const Load& l : m.c->loads) e -= l.force.dot(m.pos(l.block, l.point) - l.point);
  return e;
}

// The collapse mechanism: the same LP with every increment boxed to one unit, so that it has
// an optimum whose open corners show the mechanism. The columns are freed again afterwards.
nlohmann::ordered_json collapse_mechanism(Model& m, double scale) {
  glp_prob* lp = m.lp.get();
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_DB, -1, 1);
  nlohmann::ordered_json out;
  out["open_corners"] = nlohmann::ordered_json::array();
  out["moving_blocks"] = nlohmann::ordered_json::array();
  if (solve(m) == GLP_OPT) {
    const std::vector<double> s = slacks(m, scale);
    for (size_t e = 0; e < m.ends.size(); ++e)
      if (s[e] > 1e-6 * scale)
        out["open_corners"].push_back({{"joint", m.ends[e].joint}, {"corner", m.ends[e].corner == 0 ? "A" : "B"}});
    for (size_t b = 0; b < m.col.size(); ++b) {
      if (m.col[b] < 0) continue;
      double v = 0;
      for (int k = 0; k < 3; ++k) v = std::max(v, std::abs(glp_get_col_prim(lp, m.col[b] + k)));
      if (v > 1e-6) out["moving_blocks"].push_back(m.c->blocks[b].id);
    }
  }
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_bnds(lp, j, GLP_FR, 0, 0);
  return out;
}

void lp_check_fields(const Model& m, double scale, StepRecord& rec) {
  // Strong duality: the primal optimum equals sum(dual * bound) over the active rows.
  glp_prob* lp = m.lp.get();
  double dual = 0;
  for (int r = 1; r <= glp_get_num_rows(lp); ++r) {
    const int type = glp_get_row_type(lp, r);
    if (type == GLP_FR) continue;
    dual += glp_get_row_dual(lp, r) * glp_get_row_lb(lp, r);
  }
  rec.extra["lp_primal"] = glp_get_obj_val(lp) * scale;
  rec.extra["lp_dual"] = dual * scale;
}

}  // namespace

PrdSettings PrdSettings::from_case(const Case& c) {
  PrdSettings s;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  s.contact_tolerance = c.prd.contact_tolerance;
  return s;
}

PrdCheck prd_check(const Case& c, double contact_tolerance) {
  Model m = build_model(c, contact_tolerance);
  PrdCheck out;
  out.joints = joint_infos(m);
  out.total_weight = total_weight(m);
  const double scale = std::max(scene_size(c), 1e-12) * 1e-3;
  update_lp(m, 0.0, scale);
  const int status = m.ncols == 0 ? GLP_OPT : solve(m);
  out.state.poses = poses(m);
  if (status == GLP_OPT) {
    out.stable = true;
    out.energy_rate = glp_get_obj_val(m.lp.get()) * scale;
    read_forces(m, out.state);
    lp_check_fields(m, scale, out.state);
  } else if (status == GLP_UNBND) {
    out.stable = false;
    out.state.extra["collapse"] = collapse_mechanism(m, scale);
    glp_prob* lp = m.lp.get();
    out.mechanism.assign(c.blocks.size(), Pose{});
    for (size_t b = 0; b < c.blocks.size(); ++b)
      if (m.col[b] > 0)
        out.mechanism[b] = {glp_get_col_prim(lp, m.col[b]), glp_get_col_prim(lp, m.col[b] + 1),
                            glp_get_col_prim(lp, m.col[b] + 2) / m.radius[b]};
  } else {
    throw std::runtime_error(c.source + ": the analysis LP is infeasible (blocks overlap beyond the tolerance?)");
  }
  return out;
}

RunResult prd_run(const Case& c, const PrdSettings& s, const std::function<void(const RunResult&)>& on_step) {
  if (!(s.step > 0) || !std::isfinite(s.step)) throw std::invalid_argument("prd: the step must be a positive number");
  if (s.max_steps < 0) throw std::invalid_argument("prd: max_steps must not be negative");
  if (!(s.contact_tolerance > 0)) throw std::invalid_argument("prd: the contact tolerance must be positive");
  const auto t_start = Clock::now();
  double io_s = 0;
  RunResult r;
  r.method = "prd";
  r.case_name = c.name;
  r.settings = {{"step", s.step}, {"max_steps", s.max_steps}, {"contact_tolerance", s.contact_tolerance}};
  Model m = build_model(c, s.contact_tolerance);
  r.joints = joint_infos(m);
  r.total_weight = total_weight(m);
  auto sync_timing = [&] {
    r.timing.lp_s = m.lp_s;
    r.timing.lp_solves = m.lp_solves;
    r.timing.total_s = seconds_since(t_start) - io_s;
  };
  auto emit = [&] {
    sync_timing();
    if (!on_step) return;
    const auto t0 = Clock::now();
    on_step(r);
    io_s += seconds_since(t0);
  };

  // The record of configuration d_k is completed by the LP solved on it (with the increment to
  // d_{k+1}): its duals are the forces in equilibrium on d_k, and a bounded optimum is what
  // makes d_k stable. An unbounded LP on d_k means d_k admits a collapse mechanism: the
  // capacity is then d_{k-1}, the last configuration with an admissible force state.
  StepRecord rec;
  rec.poses = poses(m);
  try {
    for (int k = 0;; ++k) {
      update_lp(m, s.step, s.step);
      const int st = m.ncols == 0 ? GLP_OPT : solve(m);
      if (st == GLP_UNBND) {
        r.collapsed = true;
        r.stopped = "collapse";
        r.extra["collapse"] = collapse_mechanism(m, s.step);
        r.extra["collapse"]["d"] = k * s.step;
        r.extra["collapse"]["poses"] = nlohmann::ordered_json::array();
        for (const Pose& p : rec.poses) r.extra["collapse"]["poses"].push_back({p.x, p.y, p.angle});
        if (k == 0) r.message = "unstable as it stands";
        break;
      }
      if (st != GLP_OPT) {
        r.stopped = "error";
        r.message = "d = " + std::to_string(k * s.step) +
                    " m: the LP is infeasible: the prescribed motion cannot be accommodated without penetration";
        break;
      }
      read_forces(m, rec);
      lp_check_fields(m, s.step, rec);
      r.steps.push_back(rec);
      r.capacity = k * s.step;
      r.stable_steps = k;
      if (k == s.max_steps) {
        r.stopped = "max_steps";
        break;
      }
      emit();

      // Contact state from the step's own solution: a corner whose no-penetration row is
      // (nearly) tight stays or becomes closed, whatever residual gap the finite update leaves.
      const std::vector<double> sl = slacks(m, s.step);
      for (size_t e = 0; e < m.ends.size(); ++e) m.ends[e].closed = sl[e] <= s.contact_tolerance;
      // Finite update: every free block rotates about its own pole, supports move as prescribed.
      glp_prob* lp = m.lp.get();
      for (size_t b = 0; b < c.blocks.size(); ++b) {
        if (m.col[b] > 0) {
          const Vec2 u(glp_get_col_prim(lp, m.col[b]) * s.step, glp_get_col_prim(lp, m.col[b] + 1) * s.step);
          const double th = glp_get_col_prim(lp, m.col[b] + 2) * s.step / m.radius[b];
          m.cen[b] += pole_displacement(u, th);
          m.angle[b] += th;
        } else if (m.motion_of[b] >= 0) {
          const Increment inc = support_increment(m, static_cast<int>(b), s.step);
          m.cen[b] = inc.at + rot(inc.th) * (m.cen[b] - inc.at) + inc.u;
          m.angle[b] += inc.th;
        }
      }
      rec = StepRecord{};
      rec.index = k + 1;
      rec.d = (k + 1) * s.step;
      rec.poses = poses(m);
      rec.energy = energy(m);
      record_corners(m, rec);
    }
  } catch (const std::exception& e) {
    r.stopped = "error";
    r.message = e.what();
  }
  emit();
  return r;
}

}  // namespace masonry
