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

// Per endpoint, from the LP just solved with step h: the gap on the current configuration and
// its rate of change along the mechanism (m per m of d).
void gaps_and_rates(const Model& m, double h, std::vector<double>& gap, std::vector<double>& rate) {
  const std::vector<double> after = slacks(m, h);
  gap.resize(m.ends.size());
  rate.resize(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) {
    const Endpoint& ep = m.ends[e];
    const Interface& jt = m.joints[ep.joint];
    gap[e] = (m.pos(jt.j, ep.X) - m.pos(jt.i, ep.X)).dot(m.normal(ep));
    rate[e] = (after[e] - gap[e]) / h;
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

// The finite update by h along the mechanism U (column values per unit of d): every free
// block rotates about its own pole, supports move as prescribed.
void advance(Model& m, const std::vector<double>& U, double h) {
  const Case& c = *m.c;
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    if (m.col[b] > 0) {
      const Vec2 u(U[m.col[b]] * h, U[m.col[b] + 1] * h);
      const double th = U[m.col[b] + 2] * h / m.radius[b];
      m.cen[b] += pole_displacement(u, th);
      m.angle[b] += th;
    } else if (m.motion_of[b] >= 0) {
      const Increment inc = support_increment(m, static_cast<int>(b), h);
      m.cen[b] = inc.at + rot(inc.th) * (m.cen[b] - inc.at) + inc.u;
      m.angle[b] += inc.th;
    }
  }
}

std::vector<double> column_values(const Model& m) {
  std::vector<double> U(m.ncols + 1, 0.0);
  for (int j = 1; j <= m.ncols; ++j) U[j] = glp_get_col_prim(m.lp.get(), j);
  return U;
}

// A configuration the run accepted, with what it takes to step from it again.
struct Accepted {
  double d = 0;
  int index = 0;
  std::vector<Vec2> cen;
  std::vector<double> angle;
  std::vector<char> closed;        // the contact state its LP used
  std::vector<double> U, gap, rate;  // its LP's mechanism, gaps and their rates
  double h_lp = 0;                   // the step its LP was solved with
  std::vector<double> fn;            // its LP's normal force at each corner, N
  bool event = false;                // its LP changed the mechanism
};

// Where the next event is expected along the current mechanism, as distances in d from the
// configuration a: an open corner closes where its gap, shrinking at its rate, reaches the
// tolerance; a closed corner opens where its normal force, extrapolated from the previous
// configuration b on the same mechanism (same basis, so the force varies smoothly), reaches 0.
struct Prediction {
  double to_open = std::numeric_limits<double>::infinity();
  double to_close = std::numeric_limits<double>::infinity();
};

Prediction predict_event(const Model& m, const Accepted& a, const Accepted* b) {
  Prediction p;
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (!a.closed[e]) {
      if (a.rate[e] < 0) p.to_close = std::min(p.to_close, std::max(a.gap[e] - m.tol, 0.0) / -a.rate[e]);
    } else if (b && b->closed[e] && a.d > b->d) {
      const double slope = (a.fn[e] - b->fn[e]) / (a.d - b->d);
      if (a.fn[e] > 0 && slope < 0) p.to_open = std::min(p.to_open, a.fn[e] / -slope);
    }
  }
  return p;
}

void set_closed(Model& m, const std::vector<char>& closed) {
  for (size_t e = 0; e < m.ends.size(); ++e) m.ends[e].closed = closed[e];
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
  const double h_max = !s.adaptive ? h_ref : std::max(s.max_step > 0 ? s.max_step : 16 * h_ref, tol_ev);
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
  //
  // Events. A corner that opens, or the collapse, is a property of the configuration the LP is
  // solved on: seen on d_k, it happened in (d_{k-1}, d_k]. If that step was longer than the
  // tolerance, the run goes back to d_{k-1} and steps half the bracket along d_{k-1}'s
  // mechanism (no LP needed for the move), and so on until the bracket is within tolerance.
  // A corner that closes does so during the step being taken: the step is halved until it is
  // within tolerance.
  Accepted cur;
  SlidingLp sliding;
  std::optional<Accepted> prev;
  StepRecord rec = configuration_record(m, 0, 0.0);
  double h_in = 0;                                          // the step that led to cur
  double seen = std::numeric_limits<double>::infinity();    // d where an event was seen, not yet located
  double h_next = h_ref;
  std::vector<double> gap, rate;
  try {
    for (;;) {
      double h = h_next;
      if (s.adaptive) {
        // Halve the open bracket, or close it once it is small; at its end, step on.
        const double rem = seen - cur.d;
        if (std::isfinite(seen) && rem > 1e-9 * h_ref) h = rem > tol_ev ? rem / 2 : rem;
        if (d_end - cur.d > 1e-9 * h_ref) h = std::min(h, d_end - cur.d);
      }
      update_lp(m, h, h);
      const int st = m.ncols == 0 ? GLP_OPT : solve(m);
      if (st != GLP_OPT && st != GLP_UNBND) {
        r.stopped = "error";
        r.message = "d = " + std::to_string(cur.d) +
                    " m: the LP is infeasible: the prescribed motion cannot be accommodated without penetration";
        break;
      }
      std::vector<size_t> opened, closing;
      std::vector<char> next;
      if (st == GLP_OPT) {
        gaps_and_rates(m, h, gap, rate);
        next = closed_after(m, gap, rate, h, h, h_ref);
        for (size_t e = 0; e < m.ends.size(); ++e)
          if (m.ends[e].closed != next[e]) (next[e] ? closing : opened).push_back(e);
      }
      if ((st == GLP_UNBND || !opened.empty()) && prev && h_in > tol_ev * (1 + 1e-9)) {
        // Back to the last accepted configuration, half way to where the event was seen.
        seen = cur.d;
        const Accepted& p = *prev;
        m.cen = p.cen;
        m.angle = p.angle;
        set_closed(m, p.closed);
        const double rem = seen - p.d;
        h_in = rem > tol_ev ? rem / 2 : rem;
        const std::vector<char> closed = closed_after(m, p.gap, p.rate, p.h_lp, h_in, h_ref);
        advance(m, p.U, h_in);
        set_closed(m, closed);
        cur.d = p.d + h_in;
        cur.index = p.index + 1;
        rec = configuration_record(m, cur.index, cur.d);
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
      if (!closing.empty() && h > tol_ev * (1 + 1e-9)) {
        // A corner closes during the step: take a much shorter one from here. The closing
        // comes first, so a bracket further on is dropped (it is found again if it holds).
        // Its rate is hidden by the bound that stopped it; from the shorter step on, where it
        // is still open, the prediction below lands on it.
        h_next = std::max(tol_ev, h / 8);
        seen = std::numeric_limits<double>::infinity();
        continue;
      }

      // cur is accepted.
      read_forces(m, rec);
      lp_check_fields(m, h, rec);
      if (s.sliding_check) sliding_check(m, sliding, rec);
      r.steps.push_back(rec);
      r.capacity = cur.d;
      r.stable_steps = cur.index;
      if (!opened.empty()) {
        r.extra["events"].push_back(event_json(m, "open", cur.d, h_in, opened));
        seen = std::numeric_limits<double>::infinity();
      }
      if (!closing.empty()) r.extra["events"].push_back(event_json(m, "close", cur.d + h, h, closing));
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
      cur.event = !opened.empty() || !closing.empty();
      double h_take = h;
      if (s.adaptive) {
        // An LP that changed the mechanism already holds the new one, so its forces and the
        // next configuration's lie on one mechanism unless the next LP changes it again.
        const Prediction p = predict_event(m, cur, prev && !cur.event ? &*prev : nullptr);
        // Land half a tolerance short of the predicted event, then half a tolerance past it,
        // so that it is bracketed within the tolerance without bisection. A wrong prediction
        // costs a step; the mechanism check above still finds every event.
        const auto land = [&](double x) { return x > tol_ev ? x - tol_ev / 2 : std::min(x + tol_ev / 2, tol_ev); };
        const double to_event = std::min(p.to_open, p.to_close);
        if (!std::isfinite(seen)) h_take = std::min(h, land(to_event));
        // Past an event (or landing just past a predicted one) a short step gives the new
        // mechanism's force trend and finds the corners that close as the hinge moves; after
        // that the step is as long as allowed, cut short by the prediction.
        h_next = cur.event || to_event <= tol_ev ? std::min(h_max, 2 * tol_ev) : h_max;
        // The next LP's step is what finds a closing: keep it short enough to locate it.
        if (std::isfinite(p.to_close)) h_next = std::min(h_next, land(std::max(p.to_close - h_take, 0.0)));
      }
      prev = cur;
      advance(m, cur.U, h_take);
      set_closed(m, closed_after(m, gap, rate, h, h_take, h_ref));
      h_in = h_take;
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
