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
#include <limits>
#include <optional>
#include <memory>
#include <stdexcept>

#include "interfaces.hpp"
#include "glpk_hooks.hpp"
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
  long long basis_evaluations = 0;

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
// Closed corners take back their residual gap over h; open corners must not penetrate over
// h_open (<= h; 0: h), so that an event-driven run can plan a long step without the bound of
// a corner that closes part way changing the mechanism: the step is cut short there instead.
void update_lp(Model& m, double h, double scale, double h_open = 0) {
  // GLPK aborts the process on a non-finite or zero scale; this is the one place to stop it.
  if (!(scale > 0) || !std::isfinite(scale) || !(h >= 0) || !std::isfinite(h))
    throw std::logic_error(std::string("prd: invalid step for the LP (m): ").append(std::to_string(h)));
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
        double gap = (pj - pi).dot(n);
        if (!ep.closed && h_open > 0 && h_open < h) gap *= h / h_open;
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

// glp_adv_basis prints whatever msg_lev says; the harness's output is its own.
void quiet_adv_basis(glp_prob* lp) {
  const int was = glp_term_out(GLP_OFF);
  glp_adv_basis(lp, 0);
  glp_term_out(was);
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
    quiet_adv_basis(lp);
    parm.r_test = GLP_RT_STD;
    rc = glp_simplex(lp, &parm);
  }
  if (!conclusive(rc)) {
    quiet_adv_basis(lp);
    rc = glp_exact(lp, &parm);
  }
  m.lp_s += seconds_since(t0);
  ++m.lp_solves;
  if (!conclusive(rc)) throw std::runtime_error("GLPK could not solve the step's LP (code " + std::to_string(rc) + ")");
  return glp_get_status(lp);
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

// The sliding check of one configuration (PrdSettings::sliding_check). PRD's kinematics forbid
// sliding, so its forces need not respect any friction limit; the question is how much
// friction they need.
//  - demand: |T|/N of each joint resultant of the step's dual forces, as an angle, largest
//    over the joints. The dual state is one admissible state among many.
//  - required: the smallest friction angle for which SOME admissible state avoids sliding:
//    forces only at closed corners (f_n >= 0), one shear per joint in contact, equilibrium
//    with the loads on the current geometry, and |T_j| <= mu N_j at every joint. For a given
//    mu that is a linear feasibility problem, so mu is found by bisection between 0 and the
//    dual state's demand (feasible by construction).
struct SlidingLp {
  std::unique_ptr<glp_prob, GlpDeleter> lp{glp_create_prob()};
  long long solves = 0;
};

constexpr double kDeg = 180.0 / 3.14159265358979323846;

void sliding_check(const Model& m, SlidingLp& S, StepRecord& rec) {
  // Demand of the dual state.
  double demand = 0;
  int demand_joint = -1;
  for (const JointForce& f : rec.forces) {
    const double a = f.normal > 0 ? std::atan(std::abs(f.shear) / f.normal) : (f.shear != 0 ? M_PI / 2 : 0.0);
    if (a > demand) demand = a, demand_joint = f.joint;
  }

  // The feasibility LP: columns f_n per closed corner, then f_t per joint in contact; rows:
  // equilibrium of each free block (numbered as the PRD LP's columns), then two friction rows
  // per joint in contact.
  glp_prob* lp = S.lp.get();
  glp_erase_prob(lp);
  const int nrows_eq = m.ncols;
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  std::vector<int> fn_col(m.ends.size(), 0), ft_col(m.joints.size(), 0);
  std::vector<int> joints_in_contact;
  int ncols = 0;
  auto add_force = [&](int col, int b, const Vec2& F, const Vec2& p) {
    if (m.col[b] < 0) return;
    const int k = m.col[b];
    const double v[3] = {F.x(), F.y(), cross(p - m.cen[b], F) / m.radius[b]};
    for (int r = 0; r < 3; ++r)
      if (v[r] != 0) ia.push_back(k + r), ja.push_back(col), ar.push_back(v[r]);
  };
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (!m.ends[e].closed) continue;
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    const Vec2 n = m.normal(ep), p = 0.5 * (m.pos(jt.i, ep.X) + m.pos(jt.j, ep.X));
    fn_col[e] = ++ncols;
    add_force(ncols, jt.j, n, p);
    add_force(ncols, jt.i, -n, p);
    if (m.sliding_row(e)) {  // the joint's shear acts along its line, at any of its points
      ft_col[ep.joint] = ++ncols;
      add_force(ncols, jt.j, perp(n), p);
      add_force(ncols, jt.i, -perp(n), p);
      joints_in_contact.push_back(ep.joint);
    }
  }
  if (ncols == 0 || nrows_eq == 0) return;
  glp_add_cols(lp, ncols);
  for (int j = 1; j <= ncols; ++j) glp_set_col_bnds(lp, j, GLP_LO, 0, 0);
  for (int jt : joints_in_contact) glp_set_col_bnds(lp, ft_col[jt], GLP_FR, 0, 0);
  glp_add_rows(lp, nrows_eq + 2 * static_cast<int>(joints_in_contact.size()));
  const std::vector<double> f = generalised_loads(m);
  for (int r = 1; r <= nrows_eq; ++r) glp_set_row_bnds(lp, r, GLP_FX, -f[r], -f[r]);
  for (size_t q = 0; q < joints_in_contact.size(); ++q)
    for (int s = 0; s < 2; ++s) glp_set_row_bnds(lp, nrows_eq + 2 * static_cast<int>(q) + 1 + s, GLP_UP, 0, 0);
  glp_load_matrix(lp, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());

  std::vector<int> ind;
  std::vector<double> val;
  auto set_mu = [&](double mu) {
    for (size_t q = 0; q < joints_in_contact.size(); ++q) {
      const int jt = joints_in_contact[q];
      for (int s = 0; s < 2; ++s) {
        ind.assign(1, 0);
        val.assign(1, 0.0);
        ind.push_back(ft_col[jt]), val.push_back(s == 0 ? 1.0 : -1.0);
        for (int c = 0; c < 2; ++c)
          if (fn_col[2 * jt + c]) ind.push_back(fn_col[2 * jt + c]), val.push_back(-mu);
        glp_set_mat_row(lp, nrows_eq + 2 * static_cast<int>(q) + 1 + s, static_cast<int>(ind.size()) - 1, ind.data(),
                        val.data());
      }
    }
  };
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.it_lim = 1000 + 50 * (glp_get_num_rows(lp) + ncols);
  bool fresh = true;
  auto feasible = [&](double mu) {
    set_mu(mu);
    if (fresh) glp_std_basis(lp), fresh = false;
    ++S.solves;
    int rc = glp_simplex(lp, &parm);
    if (rc != 0) {  // a stalled warm start: once more from the standard basis
      glp_std_basis(lp);
      rc = glp_simplex(lp, &parm);
    }
    return rc == 0 && glp_get_status(lp) == GLP_OPT;
  };
  // The binding joint of a feasible state: the largest |T|/N.
  auto binding = [&]() {
    int best = -1;
    double worst = -1;
    for (int jt : joints_in_contact) {
      double N = 0;
      for (int c = 0; c < 2; ++c)
        if (fn_col[2 * jt + c]) N += glp_get_col_prim(lp, fn_col[2 * jt + c]);
      const double T = std::abs(glp_get_col_prim(lp, ft_col[jt]));
      const double ratio = N > 0 ? T / N : (T > 0 ? 1e300 : 0);
      if (ratio > worst) worst = ratio, best = jt;
    }
    return best;
  };

  // Where the force state is unique (a mechanism leaves the moving part statically
  // determinate) no state does better than the dual one: one LP just below its demand shows it.
  constexpr double resolution = 0.01 / kDeg;  // rad
  double lo = 0, hi = std::tan(std::min(demand, 89.9 / kDeg));
  int required_joint = demand_joint;
  if (demand > resolution && !feasible(std::tan(demand - resolution))) {
    lo = hi;
  } else if (feasible(0)) {
    hi = 0;  // no shear needed anywhere
  } else {
    // The dual state is admissible, so hi is feasible but for round-off; widen it if needed.
    bool ok = false;
    for (int widen = 0; !(ok = feasible(hi)) && widen < 20; ++widen) hi = std::max(2 * hi, 1e-3);
    if (!ok) return;  // no admissible state found: leave the field out rather than guess
    required_joint = binding();
    while (std::atan(hi) - std::atan(lo) > resolution) {
      const double mid = 0.5 * (lo + hi);
      if (feasible(mid)) {
        hi = mid;
        required_joint = binding();
      } else {
        lo = mid;
      }
    }
  }
  rec.extra["sliding"] = {{"demand_angle", demand * kDeg},
                          {"demand_joint", demand_joint},
                          {"required_angle", std::atan(hi) * kDeg},
                          {"required_joint", required_joint}};
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

// Per endpoint, from the LP just solved with step h (open corners held over h_open, see
// update_lp): the gap on the current configuration and its rate of change along the mechanism
// (m per m of d).
void gaps_and_rates(const Model& m, double h, double h_open, std::vector<double>& gap, std::vector<double>& rate) {
  const std::vector<double> slack = slacks(m, h);
  gap.resize(m.ends.size());
  rate.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    gap[e] = (m.pos(jt.j, ep.X) - m.pos(jt.i, ep.X)).dot(m.normal(ep));
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
std::vector<char> closed_after(const Model& m, const std::vector<double>& gap, const std::vector<double>& rate,
                               double h_lp, double h, double h_ref) {
  std::vector<char> out(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e)
    out[e] = m.ends[e].closed ? (gap[e] + rate[e] * h_lp) * (h_ref / h_lp) <= m.tol : gap[e] + rate[e] * h <= m.tol;
  return out;
}

// A way forward from the current configuration: the mechanism U (column values per unit of
// d) and, when known, its rate of change dU along the way (per m of d). A move h follows
// U + h/2 dU, which is second-order accurate in h where the first-order update along U alone
// drifts off the path of ever smaller steps.
struct Path {
  const std::vector<double>& U;
  const std::vector<double>& dU;
  double at(int j, double h) const { return dU.empty() ? U[j] : U[j] + 0.5 * h * dU[j]; }
};

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
  const Vec2 pi = ci + rot(ai) * (ep.X - m.c0[jt.i]), pj = cj + rot(aj) * (ep.X - m.c0[jt.j]);
  return (pj - pi).dot(rot(ai) * jt.normal);
}

// The first open corner that closes within a move of `limit` along the path, and the move
// that brings its gap to the contact tolerance (as a fixed step closes it), found on the exact finite update (a long
// step's rotations, and the mechanism's change along it, make the first-order gap rate miss
// by more than the tolerance). Each open corner's gap is looked at where its rate closes it
// and at four points along the move, so that one closing and opening again within the move is
// seen too.
struct Closing {
  double at = std::numeric_limits<double>::infinity();
  size_t corner = 0;
  double within = 0;  // m of d: the bracket left by the search
};

Closing first_closing(const Model& m, const Path& U, const std::vector<double>& gap,
                      const std::vector<double>& rate, double limit) {
  Closing c;
  const double target = m.tol;
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (m.ends[e].closed) continue;
    const double lim = std::min(limit, c.at);
    double hi = std::numeric_limits<double>::infinity();
    if (rate[e] < 0) {
      const double lin = (gap[e] - target) / -rate[e];
      if (lin < lim && gap_after(m, U, e, lin) <= target) hi = lin;
    }
    for (int k = 1; k <= 4 && !std::isfinite(hi); ++k)
      if (gap_after(m, U, e, lim * k / 4) <= target) hi = lim * k / 4;
    if (!std::isfinite(hi)) continue;
    double lo = 0;
    // Bisection to a bracket whose gaps differ by a tenth of the target (or whose length is
    // round-off), so that the end reached is closed but not penetrating.
    for (int it = 0; it < 100 && hi - lo > 1e-12 * limit &&
                     gap_after(m, U, e, lo) - gap_after(m, U, e, hi) > 0.1 * target; ++it) {
      const double mid = 0.5 * (lo + hi);
      (gap_after(m, U, e, mid) > target ? lo : hi) = mid;
    }
    c = {hi, e, hi - lo};
  }
  return c;
}

std::vector<double> column_values(const Model& m) {
  std::vector<double> U(m.ncols + 1, 0.0);
  for (int j = 1; j <= m.ncols; ++j) U[j] = glp_get_col_prim(m.lp.get(), j);
  return U;
}

void set_closed(Model& m, const std::vector<char>& closed) {
  for (size_t e = 0; e < m.ends.size(); ++e) m.ends[e].closed = closed[e];
}

// A configuration the run accepted, with what it takes to step from it again.
struct Accepted {
  double d = 0;
  int index = 0;
  std::vector<Vec2> cen;
  std::vector<double> angle;
  std::vector<char> closed;        // the contact state its LP used
  std::vector<double> U, gap, rate;  // its LP's mechanism, gaps and their rates
  std::vector<double> dU;            // the mechanism's change along d (empty: not known)
  double h_lp = 0;                   // the step its LP was solved with
  std::vector<double> fn;            // its LP's normal force at each corner, N
  bool same = true;                  // its LP kept the contact state (no corner opens or closes)
  std::vector<int> row_stat, col_stat;  // its LP's final basis
  std::vector<double> slack;            // its LP's no-penetration rows' slacks (LP units)
};

void save_basis(const Model& m, Accepted& a) {
  glp_prob* lp = m.lp.get();
  a.row_stat.resize(glp_get_num_rows(lp) + 1);
  a.col_stat.resize(m.ncols + 1);
  for (size_t i = 1; i < a.row_stat.size(); ++i) a.row_stat[i] = glp_get_row_stat(lp, static_cast<int>(i));
  for (int j = 1; j <= m.ncols; ++j) a.col_stat[j] = glp_get_col_stat(lp, j);
  a.slack.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const int row = 2 * static_cast<int>(e) + 1;
    a.slack[e] = glp_get_row_prim(lp, row) - glp_get_row_lb(lp, row);
  }
}

// The LP of the current configuration and contact state for a step h (open corners held over
// h_open) with a's basis, evaluated without a simplex iteration (glp_warm_up's code).
int evaluate_basis(Model& m, const Accepted& a, double h, double h_open) {
  glp_prob* lp = m.lp.get();
  update_lp(m, h, h, h_open);
  for (size_t i = 1; i < a.row_stat.size(); ++i) glp_set_row_stat(lp, static_cast<int>(i), a.row_stat[i]);
  for (int j = 1; j <= m.ncols; ++j) glp_set_col_stat(lp, j, a.col_stat[j]);
  const auto t0 = Clock::now();
  const int rc = glp_warm_up(lp);
  m.lp_s += seconds_since(t0);
  ++m.basis_evaluations;
  return rc;
}

// Where, between configuration a and the current one (a distance `span` further on), the
// basis of a's LP stopped being the optimum: that basis (and contact state) is evaluated here
// without a simplex iteration, and where a closed corner's normal force or an open corner's
// slack has turned negative, it is interpolated linearly to its zero. Infinite when nothing
// has; empty when GLPK cannot evaluate the basis. A corner that closed on the way (open in a,
// closed here) is not counted: its closing was located where it happened. Leaves the contact
// state as a's.
std::optional<double> basis_crossing(Model& m, const Accepted& a, double span, double tol_ev) {
  glp_prob* lp = m.lp.get();
  std::vector<char> closed_since(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) closed_since[e] = !a.closed[e] && m.ends[e].closed;
  set_closed(m, a.closed);
  if (evaluate_basis(m, a, a.h_lp, std::min(a.h_lp, tol_ev)) != 0) return std::nullopt;
  double at = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (closed_since[e]) continue;
    const int row = 2 * static_cast<int>(e) + 1;
    const double was = a.closed[e] ? a.fn[e] : a.slack[e];
    const double now = a.closed[e] ? glp_get_row_dual(lp, row) : glp_get_row_prim(lp, row) - glp_get_row_lb(lp, row);
    if (was > 0 && now < 0) at = std::min(at, span * was / (was - now));
  }
  return at;
}

// The first x > 0 where f + b x + k x^2 = 0 (f > 0), infinite if none.
double first_zero(double f, double b, double k) {
  double x = std::numeric_limits<double>::infinity();
  if (std::abs(k) * f < 1e-6 * b * b) {
    if (b < 0) x = f / -b;
  } else {
    const double disc = b * b - 4 * k * f;
    // The smaller positive root (k < 0 has one; k > 0 has two or none).
    if (disc >= 0 && (k < 0 || b < 0)) x = (-b - std::sqrt(disc)) / (2 * k);
  }
  return x > 0 ? x : std::numeric_limits<double>::infinity();
}

// A planned move from configuration a, where the next opening is expected from it, and the
// corner expected to open (-1: none).
struct Move {
  double h = 0;
  double to_open = std::numeric_limits<double>::infinity();
  long corner = -1;
  void consider(double x, size_t e) {
    if (x < to_open) to_open = x, corner = static_cast<long>(e);
  }
};

// Where a closed corner of configuration a is expected to open, as a distance x in d: where
// its normal force f + slope x + curve x^2 reaches 0. (For a fixed basis the duals vary
// smoothly with the geometry; the basis changes where one of them would turn negative.)
// Corners `ignored` are left out (see prd_run).
Move predict_opening(const Accepted& a, const std::vector<double>& slope, const std::vector<double>& curve,
                     const std::vector<char>& ignored) {
  Move mv;
  for (size_t e = 0; e < slope.size(); ++e)
    if (a.closed[e] && a.fn[e] > 0 && !ignored[e])
      mv.consider(first_zero(a.fn[e], slope[e], curve.empty() ? 0.0 : curve[e]), e);
  return mv;
}

// The move x from a along its LP's basis, checked where it would end: the basis is evaluated
// there (no simplex iteration). Where a closed corner's force has turned negative, the move is
// cut to land short of where it reaches 0, and checked again. The zero is that of the
// quadratic through a's force, its trend `slope` when known, and the value there; of the chord
// otherwise. `guess` is the prediction the move came from. A move longer than `short_move`
// follows the mean of the mechanisms at both ends (a.dU: Heun's second-order step); a shorter
// one needs no check. (Closings are left to first_closing, on the move's exact path.)
template <class Land>
Move plan_move(Model& m, Accepted& a, double h, double h_open, double x, const Move& guess,
               const std::vector<double>& slope, const std::vector<char>& ignored, double short_move,
               const Land& land) {
  Move mv = guess;
  mv.h = x;
  a.dU.clear();
  const std::vector<Vec2> cen = m.cen;
  const std::vector<double> angle = m.angle;
  std::vector<double> dU;
  // Each check: the basis where the move along U alone ends, then, with the mechanism's rate
  // of change that gives, where the move along the mean ends (the end actually reached).
  for (int it = 0; it < 6 && x > short_move; ++it) {
    advance(m, Path{a.U, dU}, x);
    const int rc = evaluate_basis(m, a, h, h_open);
    const std::vector<Vec2> there = m.cen;
    m.cen = cen;
    m.angle = angle;
    if (rc != 0) break;
    Move at;
    at.h = x;
    for (size_t e = 0; e < m.ends.size(); ++e) {
      if (ignored[e]) continue;
      const int row = 2 * static_cast<int>(e) + 1;
      if (a.closed[e] && a.fn[e] > 0) {
        const double f0 = a.fn[e], f1 = glp_get_row_dual(m.lp.get(), row);
        at.consider(slope.empty() ? first_zero(f0, (f1 - f0) / x, 0.0)
                                  : first_zero(f0, slope[e], (f1 - f0 - slope[e] * x) / (x * x)), e);
      }
    }
    mv = at;
    if (at.to_open < x) {
      x = mv.h = land(at.to_open);
      dU.clear();
    } else if (dU.empty()) {
      // The change of each block's motion, with the velocity there taken at the centroid's
      // place here: a block turning about a fixed pole has no change to follow (its centroid
      // velocity turns with it), and the move's finite rotation about the pole stays exact.
      dU.assign(m.ncols + 1, 0.0);
      for (size_t b = 0; b < m.col.size(); ++b) {
        const int k = m.col[b];
        if (k < 0) continue;
        const double th = glp_get_col_prim(m.lp.get(), k + 2) / m.radius[b];
        const Vec2 v = Vec2(glp_get_col_prim(m.lp.get(), k), glp_get_col_prim(m.lp.get(), k + 1)) + th * perp(cen[b] - there[b]);
        dU[k] = (v.x() - a.U[k]) / x;
        dU[k + 1] = (v.y() - a.U[k + 1]) / x;
        dU[k + 2] = (glp_get_col_prim(m.lp.get(), k + 2) - a.U[k + 2]) / x;
      }
    } else {
      a.dU = dU;
      break;
    }
  }
  return mv;
}

StepRecord configuration_record(const Model& m, int index, double d) {
  StepRecord rec;
  rec.index = index;
  rec.d = d;
  rec.poses = poses(m);
  rec.energy = energy(m);
  record_corners(m, rec);
  return rec;
}

nlohmann::ordered_json event_json(const Model& m, const char* kind, double d, double within,
                                  const std::vector<size_t>& corners) {
  nlohmann::ordered_json ev = {{"kind", kind}, {"d", d}, {"within", within}};
  ev["joints"] = nlohmann::ordered_json::array();
  for (size_t e : corners) {
    const Interface& jt = m.joints[m.ends[e].joint];
    ev["joints"].push_back({{"joint", m.ends[e].joint},
                            {"corner", m.ends[e].corner == 0 ? "A" : "B"},
                            {"blocks", {m.c->blocks[jt.i].id, m.c->blocks[jt.j].id}}});
  }
  return ev;
}

}  // namespace

PrdSettings PrdSettings::from_case(const Case& c) {
  PrdSettings s;
  s.step = c.motion.step;
  s.max_steps = c.motion.max_steps;
  s.contact_tolerance = c.prd.contact_tolerance;
  s.adaptive = c.prd.adaptive;
  s.event_tolerance = c.prd.event_tolerance;
  s.max_step = c.prd.max_step;
  s.sliding_check = c.prd.sliding_check;
  return s;
}

PrdCheck prd_check(const Case& c, double contact_tolerance) {
  prd::install_glpk_hooks();
  Model m = build_model(c, contact_tolerance);
  PrdCheck out;
  out.joints = joint_infos(m);
  out.total_weight = total_weight(*m.c);
  const double scale = std::max(scene_size(c), 1e-12) * 1e-3;
  update_lp(m, 0.0, scale);
  // A fresh LP: GLPK's standard basis (every row slack basic) makes the simplex bring each
  // block's columns in one pivot at a time, about two pivots per block, each costing in
  // proportion to the rows, so the analysis grows with the square of the blocks. Bixby's
  // advanced basis starts with most columns basic and halves the pivots (a wall of 4000 blocks:
  // 8000 pivots, 3.4 s, became 4040, 1.9 s); the growth stays quadratic, which is the simplex's.
  if (m.ncols > 0) quiet_adv_basis(m.lp.get());
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
  prd::install_glpk_hooks();
  if (!(s.step > 0) || !std::isfinite(s.step)) throw std::invalid_argument("prd: the step must be a positive number");
  if (s.max_steps < 0) throw std::invalid_argument("prd: max_steps must not be negative");
  if (!(s.contact_tolerance > 0)) throw std::invalid_argument("prd: the contact tolerance must be positive");
  if (!std::isfinite(s.event_tolerance) || !std::isfinite(s.max_step))
    throw std::invalid_argument("prd: the event tolerance and the largest step must be finite");
  const auto t_start = Clock::now();
  double io_s = 0;
  RunResult r;
  r.method = "prd";
  r.case_name = c.name;
  // A fixed-step run is the event-driven one with every step accepted: the step never changes
  // and no event is bracketed more finely than one step.
  const double h_ref = s.step;
  const double tol_ev = !s.adaptive ? h_ref : s.event_tolerance > 0 ? s.event_tolerance : 1e-4 * scene_size(c);
  // The longest move. A move's path error (second order, see Path) grows as the square of its
  // length against the scene's, so the default keeps it within the event tolerance:
  // 0.4 sqrt(tolerance x scene size), 1/250 of the scene at the default tolerance.
  const double h_max =
      !s.adaptive ? h_ref
                  : std::max(s.max_step > 0 ? s.max_step : std::min(16 * h_ref, 0.4 * std::sqrt(tol_ev * scene_size(c))), tol_ev);
  const double d_end = s.max_steps * h_ref;
  r.settings = {{"step", s.step}, {"max_steps", s.max_steps}, {"contact_tolerance", s.contact_tolerance}};
  if (s.adaptive) {
    r.settings["adaptive"] = true;
    r.settings["event_tolerance"] = tol_ev;
    r.settings["max_step"] = h_max;
  }
  r.extra["events"] = nlohmann::ordered_json::array();
  Model m = build_model(c, s.contact_tolerance);
  r.joints = joint_infos(m);
  r.total_weight = total_weight(*m.c);
  auto sync_timing = [&] {
    r.timing.lp_s = m.lp_s;
    r.timing.lp_solves = m.lp_solves;
    r.timing.basis_evaluations = m.basis_evaluations;
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
  //
  // Events (adaptive runs; a fixed run is the same loop with every move one step long).
  //  - Opening or collapse: a property of the configuration the LP is solved on: seen on d_k,
  //    it happened in (d_{k-1}, d_k]. Moves are planned so that this bracket is within the
  //    tolerance: the forces' trend on the current basis (from the previous configurations on
  //    it) guesses where one of them reaches 0, the basis evaluated where the move would end
  //    corrects the guess (plan_move), and the run stops half a tolerance short of the zero,
  //    then steps half a tolerance past. A longer bracket is closed by going back
  //    to d_{k-1}, to where its basis's forces, interpolated to d_k, reach 0, or else half way
  //    (no LP is needed for the move back), until it is within the tolerance.
  //  - Closing: found on the move itself: the move stops where the first open corner's gap
  //    reaches the contact tolerance. Only a corner that the LP already holds at its bound
  //    (closing within the tolerance) closes at the end of a move.
  //  - An opening seen where a move stopped at a closing, while the previous basis still holds
  //    there, is the closing's consequence and is located with it.
  //  - A corner whose force reached 0 without the mechanism changing (a statically
  //    indeterminate part's duals are one admissible force state of many) is left out of the
  //    predictions once the run has stepped past its predicted opening.
  // Moves follow the mechanism and its rate of change (Path), so that long moves stay on the
  // path of ever smaller fixed steps.
  Accepted cur;
  SlidingLp sliding;
  std::optional<Accepted> prev, prev2;  // the last accepted configurations, newest first
  StepRecord rec = configuration_record(m, 0, 0.0);
  double h_in = 0;                                          // the move that led to cur
  double seen = std::numeric_limits<double>::infinity();    // d where an event was seen, not yet located
  double h_plan = h_ref;                                    // the step the next LP is solved for
  double arrived_closing = -1;  // the move to cur ended where a corner closed: located within this
  long passing = -1;            // the corner the move to cur was to take past its predicted opening
  std::vector<char> ignored(m.ends.size(), 0);
  // A move stops half a tolerance short of a predicted opening, and the next one goes half a
  // tolerance past it, so that it is bracketed within the tolerance without bisection.
  const auto land = [&](double x) { return x > tol_ev ? x - tol_ev / 2 : std::min(x + tol_ev / 2, tol_ev); };
  // Inside a bracket (an event seen at `seen`, not yet located), the move from d: to land by
  // the estimated crossing while it lies ahead, else to halve the bracket; once the bracket
  // is within the tolerance, to its end.
  double crossing = std::numeric_limits<double>::infinity();
  const auto toward_event = [&](double d) {
    const double left = seen - d;
    if (left <= tol_ev) return left;
    const double x = crossing - d;
    if (x > 0 && x < left) return std::min(land(x), left - tol_ev / 2);
    return left / 2;
  };
  std::vector<double> gap, rate;
  try {
    for (;;) {
      // The LP is solved for the step planned, with open corners held over the event tolerance
      // only: a corner that closes later in the step cuts the move short where it closes (on
      // the exact motion), so the LP's mechanism is the one of this configuration.
      const double h = h_plan, h_open = std::min(h, tol_ev);
      update_lp(m, h, h, h_open);
      const int st = m.ncols == 0 ? GLP_OPT : solve(m);
      if (st != GLP_OPT && st != GLP_UNBND) {
        r.stopped = "error";
        r.message = "d = " + std::to_string(cur.d) +
                    " m: the LP is infeasible: the prescribed motion cannot be accommodated without penetration";
        break;
      }
      std::vector<size_t> opened, closing;
      if (st == GLP_OPT) {
        gaps_and_rates(m, h, h_open, gap, rate);
        const std::vector<char> next = closed_after(m, gap, rate, h, h_open, h_ref);
        for (size_t e = 0; e < m.ends.size(); ++e)
          if (m.ends[e].closed != next[e]) (next[e] ? closing : opened).push_back(e);
      }
      // An event seen at the end of a move longer than the tolerance is located by going back.
      // Unless the move ended where a corner closed, and the previous mechanism held all the
      // way (its basis is still the optimum here, that corner aside): then the closing set
      // the event off, and it is located with the closing.
      bool back = (st == GLP_UNBND || !opened.empty()) && prev && h_in > tol_ev * (1 + 1e-9);
      if (back && s.adaptive) {
        const Accepted& p = *prev;
        Accepted here;
        save_basis(m, here);
        here.closed.resize(m.ends.size());
        for (size_t e = 0; e < m.ends.size(); ++e) here.closed[e] = m.ends[e].closed;
        const std::optional<double> x = basis_crossing(m, p, cur.d - p.d, tol_ev);
        set_closed(m, here.closed);
        crossing = x ? p.d + *x : std::numeric_limits<double>::infinity();
        if (x && !std::isfinite(*x) && arrived_closing >= 0) {
          back = false;
          h_in = arrived_closing;
          // basis_crossing left the previous basis in the LP: this configuration's back.
          if (evaluate_basis(m, here, h, h_open) != 0) throw std::runtime_error("GLPK could not restore the step's basis");
        }
      }
      if (back) {
        // Back to the last accepted configuration, and from there to where the previous
        // basis's forces, interpolated between there and here, reach 0 (half way when they
        // do not tell).
        seen = cur.d;
        const Accepted& p = *prev;
        m.cen = p.cen;
        m.angle = p.angle;
        set_closed(m, p.closed);
        h_in = toward_event(p.d);
        const std::vector<char> closed = closed_after(m, p.gap, p.rate, p.h_lp, h_in, h_ref);
        advance(m, Path{p.U, p.dU}, h_in);
        set_closed(m, closed);
        cur.d = p.d + h_in;
        cur.index = p.index + 1;
        rec = configuration_record(m, cur.index, cur.d);
        h_plan = toward_event(cur.d);
        arrived_closing = -1;
        continue;
      }
      if (st == GLP_UNBND) {
        r.collapsed = true;
        r.stopped = "collapse";
        r.extra["events"].push_back(event_json(m, "collapse", cur.d, h_in, {}));
        r.extra["collapse"] = collapse_mechanism(m, h);
        r.extra["collapse"]["d"] = cur.d;
        r.extra["collapse"]["poses"] = nlohmann::ordered_json::array();
        for (const Pose& p : rec.poses) r.extra["collapse"]["poses"].push_back({p.x, p.y, p.angle});
        if (!prev) r.message = "unstable as it stands";
        break;
      }

      // cur is accepted. A corner the move was to take past its predicted opening that is still
      // closed has a force that reached 0 without changing the mechanism (a statically
      // indeterminate part's dual forces are one admissible state of many): it is left out of
      // the predictions from here on, and should it open after all, the LP sees it.
      if (passing >= 0 && m.ends[passing].closed && opened.empty() && !ignored[passing]) ignored[passing] = 1;
      passing = -1;
      read_forces(m, rec);
      lp_check_fields(m, h, rec);
      if (s.sliding_check) sliding_check(m, sliding, rec);
      require_finite(rec);
      r.steps.push_back(rec);
      r.capacity = cur.d;
      r.stable_steps = cur.index;
      // An event seen on the way here that did not recur at the same d (the way there
      // differed) is over.
      if (seen - cur.d <= 1e-9 * h_ref) seen = std::numeric_limits<double>::infinity();
      if (!opened.empty()) {
        r.extra["events"].push_back(event_json(m, "open", cur.d, h_in, opened));
        seen = std::numeric_limits<double>::infinity();
      }
      if (s.adaptive ? d_end - cur.d <= 1e-9 * h_ref : cur.index == s.max_steps) {
        r.stopped = "max_steps";
        break;
      }
      emit();

      cur.cen = m.cen;
      cur.angle = m.angle;
      cur.U = column_values(m);
      cur.gap = gap;
      cur.rate = rate;
      cur.h_lp = h;
      cur.closed.resize(m.ends.size());
      for (size_t e = 0; e < m.ends.size(); ++e) cur.closed[e] = m.ends[e].closed;
      cur.fn.resize(m.ends.size());
      for (size_t e = 0; e < m.ends.size(); ++e) cur.fn[e] = glp_get_row_dual(m.lp.get(), 2 * static_cast<int>(e) + 1);
      cur.same = opened.empty() && closing.empty();
      cur.dU.clear();
      save_basis(m, cur);
      double h_take = h;
      Closing shut;  // a closing the move is cut short at
      Move planned;  // the opening the move was planned against
      if (s.adaptive) {
        if (std::isfinite(seen)) {
          h_take = std::min(h, toward_event(cur.d));
        } else if (closing.empty()) {
          // The forces' trend, when the previous configurations had the same mechanism (their
          // chord, with its curvature when there are three), gives a first guess of the move;
          // plan_move checks it on the basis where it would end.
          const auto on_same = [&](const std::optional<Accepted>& a, const Accepted& b) {
            return a && a->same && b.same && a->closed == b.closed && b.d > a->d;
          };
          std::vector<double> slope, curve;
          double x = h;
          Move guess;
          if (on_same(prev, cur)) {
            slope.resize(m.ends.size());
            for (size_t e = 0; e < m.ends.size(); ++e) slope[e] = (cur.fn[e] - prev->fn[e]) / (cur.d - prev->d);
            if (on_same(prev2, *prev)) {
              curve.resize(m.ends.size());
              for (size_t e = 0; e < m.ends.size(); ++e) {
                curve[e] = (slope[e] - (prev->fn[e] - prev2->fn[e]) / (prev->d - prev2->d)) / (cur.d - prev2->d);
                slope[e] += curve[e] * (cur.d - prev->d);  // at cur
              }
            }
            guess = predict_opening(cur, slope, curve, ignored);
            x = std::min(x, land(guess.to_open));
          }
          if (d_end - cur.d > 1e-9 * h_ref) x = std::min(x, d_end - cur.d);
          planned = plan_move(m, cur, h, h_open, x, guess, slope, ignored, 2 * tol_ev, land);
          h_take = planned.h;
        }
        if (d_end - cur.d > 1e-9 * h_ref) h_take = std::min(h_take, d_end - cur.d);
        if (!closing.empty()) {
          h_take = std::min(h_take, h_open);  // the LP holds the closing corner at the end of it
        } else {
          shut = first_closing(m, Path{cur.U, cur.dU}, gap, rate, h_take);
          if (std::isfinite(shut.at)) h_take = shut.at;
        }
        if (planned.to_open <= h_take) passing = planned.corner;
        // The next LP's step: inside a bracket, the next move in it; else as long as allowed,
        // the predictions cutting the move short.
        h_plan = h_max;
        if (std::isfinite(seen) && seen - cur.d - h_take > 1e-9 * h_ref) h_plan = toward_event(cur.d + h_take);
      }
      if (!(h_take > 0)) throw std::logic_error("prd: the step came to a stop at d = " + std::to_string(cur.d) + " m");
      prev2 = std::move(prev);
      prev = cur;
      advance(m, Path{cur.U, cur.dU}, h_take);
      std::vector<char> closed = closed_after(m, gap, rate, h, h_take, h_ref);
      if (std::isfinite(shut.at)) closed[shut.corner] = 1;
      if (!cur.dU.empty())  // off the first-order update, a corner's gap is what it is
        for (size_t e = 0; e < m.ends.size(); ++e) {
          const Interface& jt = m.joints[m.ends[e].joint];
          if (!m.ends[e].closed && (m.pos(jt.j, m.ends[e].X) - m.pos(jt.i, m.ends[e].X)).dot(m.normal(m.ends[e])) <= m.tol)
            closed[e] = 1;
        }
      std::vector<size_t> shut_now;
      for (size_t e = 0; e < m.ends.size(); ++e)
        if (closed[e] && !m.ends[e].closed) shut_now.push_back(e);
      set_closed(m, closed);
      if (!shut_now.empty()) {
        const bool exact = std::isfinite(shut.at) && shut_now.size() == 1;
        r.extra["events"].push_back(event_json(m, "close", cur.d + h_take, exact ? shut.within : h_take, shut_now));
      }
      h_in = h_take;
      arrived_closing = std::isfinite(shut.at) ? shut.within : -1;
      cur.index += 1;
      cur.d = s.adaptive ? prev->d + h_take : cur.index * h_ref;
      rec = configuration_record(m, cur.index, cur.d);
    }
  } catch (const std::exception& e) {
    r.stopped = "error";
    r.message = e.what();
  }
  if (s.sliding_check) {
    r.extra["sliding"] = sliding_summary(c, r);
    r.extra["sliding"]["lp_solves"] = sliding.solves;
  }
  emit();
  return r;
}

nlohmann::ordered_json sliding_summary(const Case& c, const RunResult& r) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  auto joint_name = [&](int k) {
    if (k < 0 || k >= static_cast<int>(r.joints.size())) return std::string();
    return c.blocks[r.joints[k].i].id + "/" + c.blocks[r.joints[k].j].id;
  };
  const StepRecord* req = nullptr;
  const StepRecord* dem = nullptr;
  for (const StepRecord& s : r.steps) {
    if (!s.extra.contains("sliding")) continue;
    const auto& x = s.extra["sliding"];
    if (!req || x["required_angle"].get<double>() > req->extra["sliding"]["required_angle"].get<double>()) req = &s;
    if (!dem || x["demand_angle"].get<double>() > dem->extra["sliding"]["demand_angle"].get<double>()) dem = &s;
  }
  if (!req) return out;
  const auto& xr = req->extra["sliding"];
  const auto& xd = dem->extra["sliding"];
  out["required_friction_angle"] = xr["required_angle"];
  out["d"] = req->d;
  out["step"] = req->index;
  out["joint"] = joint_name(xr["required_joint"].get<int>());
  out["max_demand_angle"] = xd["demand_angle"];
  out["demand_d"] = dem->d;
  out["demand_joint"] = joint_name(xd["demand_joint"].get<int>());
  return out;
}

std::optional<SlidingExceedance> first_sliding(const Case& c, const RunResult& r, double angle_deg, bool required) {
  const char* key = required ? "required_angle" : "demand_angle";
  const char* joint_key = required ? "required_joint" : "demand_joint";
  for (const StepRecord& s : r.steps) {
    if (!s.extra.contains("sliding")) continue;
    const auto& x = s.extra["sliding"];
    if (x[key].get<double>() <= angle_deg) continue;
    SlidingExceedance e;
    e.step = s.index;
    e.d = s.d;
    e.angle = x[key].get<double>();
    e.joint = x[joint_key].get<int>();
    if (e.joint >= 0) e.blocks = c.blocks[r.joints[e.joint].i].id + "/" + c.blocks[r.joints[e.joint].j].id;
    return e;
  }
  return std::nullopt;
}

}  // namespace masonry
