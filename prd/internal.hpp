// Internal to prd/: the solver's shared state and the functions its files hand each other.
// lp.cpp is the layer over GLPK (the LP's variables and rows are described at its top);
// motion.cpp the finite rigid motion and the contact state; events.cpp the event location of
// adaptive runs; sliding.cpp the sliding check; run.cpp prd_check and the run loop.
#pragma once

#include <glpk.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "model/case.hpp"
#include "model/interfaces.hpp"
#include "model/io.hpp"
#include "model/results.hpp"
#include "prd/glpk_hooks.hpp"
#include "prd/interior.hpp"
#include "prd/kept_basis.hpp"
#include "prd/prd.hpp"

namespace masonry::prd_detail {

// Times are the thread's CPU time, as the DEM's: on a machine shared with other work the wall
// clock measures that work too (a 412-block wall's run: 1.7 s of wall time for 0.66 s of CPU).
inline double cpu_now() { return thread_cpu_s(); }
inline double seconds_since(double t0) { return thread_cpu_s() - t0; }

inline Eigen::Matrix2d rot(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// A GLPK problem, deleted with its owner unless an error freed GLPK's environment since it was
// made (glpk_guarded): then it is gone already.
struct GlpDeleter {
  unsigned generation = 0;  // prd::glpk_generation() when it was made
  void operator()(glp_prob* p) const {
    if (generation == prd::glpk_generation()) glp_delete_prob(p);
  }
};
using GlpProblem = std::unique_ptr<glp_prob, GlpDeleter>;
inline GlpProblem new_glp_problem() { return GlpProblem(glp_create_prob(), GlpDeleter{prd::glpk_generation()}); }

struct Endpoint {
  int joint;
  int corner;  // 0 = A, 1 = B
  // The corner's material points on blocks i and j (initial configuration): the joint's end,
  // shared by both blocks, unless a run started from a deformed configuration keeps the
  // corner's offset there (PrdStart, start_from).
  Vec2 X, Xj;
  bool closed = true;
  bool held = false;  // kept closed whatever the loads do (PrdOptions::hold_closed): its row an equality
};

// Whether solve() tries the kept basis before GLPK (kept_basis.hpp). Always on in the solver;
// tests turn it off on their thread to compare with GLPK's simplex on every LP, the reference.
inline thread_local bool t_use_kept_basis = true;

// From this many free blocks up a run's first LP starts from GLPK's advanced basis (solve).
constexpr int kAdvancedBasisBlocks = 300;
// How the first solve of a model starts: GLPK's advanced basis from kAdvancedBasisBlocks free
// blocks up (a run), always (a single analysis), or never (the standard basis: tests compare);
// or the structure's load path by the dual simplex (set_static_basis; where the load path is not
// admissible, the advanced basis): solve() takes it from kAdvancedBasisBlocks free blocks up where
// it is optimal as it stands; `statics` takes it wherever it is admissible (tests compare).
enum class FirstBasis { by_size, advanced, standard, statics };

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
  double force_unit = 1.0;     // N: the LP's objective is the loads over this (build_model)
  int ncols = 0;
  GlpProblem lp;
  bool fresh = true;             // not solved yet (solve)
  std::vector<double> row_coef;  // per LP row: its entry count and coefficients as GLPK holds them (update_lp)
  std::vector<int> row_cols;     // per LP row: the columns of those coefficients (6 per row)
  std::vector<double> row_lb;    // per LP row: its lower bound (the fixed value of a fixed row)
  std::vector<char> row_type;    // per LP row: GLP_FR, GLP_LO or GLP_FX
  std::vector<double> obj_coef;  // per column (1-based): the objective's coefficient
  // update_lp writes the LP here; sync_glpk gives GLPK what changed when GLPK is asked.
  std::vector<char> row_dirty;  // per LP row: coefficients GLPK does not hold yet
  bool glpk_behind = false;     // bounds and objective not given to GLPK yet
  KeptBasis kept;               // the basis of the last GLPK solve, for the next (kept_basis.hpp)
  InteriorSolution interior;    // the last interior-point solution (interior.hpp)
  // The columns are boxed in GLPK (collapse_mechanism): neither the kept basis's nor the interior
  // point's tests know the boxes, so GLPK solves.
  bool columns_boxed = false;
  // Whether solve() tries the kept basis: in fixed-step runs. An event-driven run locates its
  // events on the force state, which a statically indeterminate structure does not fix: the
  // round-off between KLU's vertex and GLPK's moved a wall's events, so those runs stay GLPK's.
  bool kept_basis_allowed = false;
  FirstBasis first_basis = FirstBasis::by_size;
  double lp_s = 0;
  long long lp_solves = 0;
  long long basis_evaluations = 0;
  long long kept_basis_solves = 0;  // LPs solved by the kept basis, without GLPK (kept_basis.hpp)
  long long load_path_solves = 0;   // LPs solved from the load path (set_static_basis)
  long long interior_solves = 0;    // LPs solved by the interior point (interior.hpp)

  Vec2 pos(int b, const Vec2& X) const { return cen[b] + rot(angle[b]) * (X - c0[b]); }
  Vec2 material(int b, const Vec2& x) const { return c0[b] + rot(-angle[b]) * (x - cen[b]); }  // pos's inverse
  Vec2 normal(const Endpoint& e) const { return rot(angle[joints[e.joint].i]) * joints[e.joint].normal; }
  // Where corner e stands on each of its joint's blocks, and its gap (m, along the normal).
  Vec2 on_i(const Endpoint& e) const { return pos(joints[e.joint].i, e.X); }
  Vec2 on_j(const Endpoint& e) const { return pos(joints[e.joint].j, e.Xj); }
  double gap(const Endpoint& e) const { return (on_j(e) - on_i(e)).dot(normal(e)); }
  // Whether endpoint e carries its joint's no-sliding row (see the top of this file).
  bool sliding_row(size_t e) const { return ends[e].closed && (ends[e].corner == 0 || !ends[e - 1].closed); }
  // LP row i's coefficients (0-based, as update_lp wrote them) on the three columns of the block
  // whose first column is k.
  Eigen::Vector3d row_on_block(size_t i, int k) const {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    const double* held = &row_coef[7 * i];
    const int* cols = &row_cols[6 * i];
    for (int q = 0; q < static_cast<int>(held[0]); ++q)
      if (cols[q] >= k && cols[q] < k + 3) a[cols[q] - k] += held[q + 1];
    return a;
  }
  // LP row i's activity (0-based, as update_lp wrote it) for column values x (1-based).
  double row_activity(size_t i, const std::vector<double>& x) const {
    const double* held = &row_coef[7 * i];
    const int* cols = &row_cols[6 * i];
    double s = 0;
    for (int q = 0; q < static_cast<int>(held[0]); ++q) s += held[q + 1] * x[cols[q]];
    return s;
  }
};

// Prescribed small increment of a support at the current configuration, for a step h.
struct Increment {
  Vec2 u{0, 0};  // at point `at`
  double th = 0;
  Vec2 at{0, 0};
  Vec2 at_point(const Vec2& x) const { return u + th * perp(x - at); }
};

// What an LP solve proved (GLPK's status, in the solver's terms).
enum class LpStatus { optimal, unbounded, infeasible };

// A way forward from the current configuration: the mechanism U (column values per unit of
// d) and, when known, its rate of change dU along the way (per m of d). A move h follows
// U + h/2 dU, which is second-order accurate in h where the first-order update along U alone
// drifts off the path of ever smaller steps.
struct Path {
  const std::vector<double>& U;
  const std::vector<double>& dU;
  double at(int j, double h) const { return dU.empty() ? U[j] : U[j] + 0.5 * h * dU[j]; }
};

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

// A configuration the run accepted, with what it takes to step from it again.
struct Accepted {
  double d = 0;
  int index = 0;
  std::vector<Vec2> cen;
  std::vector<double> angle;
  std::vector<char> closed;             // the contact state its LP used
  std::vector<Vec2> X, Xj;              // its corners' material points (Endpoint; close_corners moves them)
  std::vector<double> U, gap, rate;     // its LP's mechanism, gaps and their rates
  std::vector<double> dU;               // the mechanism's change along d (empty: not known)
  double h_lp = 0;                      // the step its LP was solved with
  std::vector<double> fn;               // its LP's normal force at each corner, N
  bool same = true;                     // its LP kept the contact state (no corner opens or closes)
  std::vector<int> row_stat, col_stat;  // its LP's final basis
  std::vector<double> slack;            // its LP's no-penetration rows' slacks (LP units)
};

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
//
// The feasibility problem's data (no GLPK in it): columns f_n per closed corner, then f_t per
// joint in contact; rows: equilibrium of each free block (numbered as the PRD LP's columns),
// then two friction rows per joint in contact, |f_t| <= mu sum f_n written as two.
struct FrictionProblem {
  int ncols = 0, nrows_eq = 0;
  std::vector<int> ia{0}, ja{0};  // equilibrium coefficients, GLPK's 1-based triplets
  std::vector<double> ar{0.0};
  std::vector<double> loads;  // generalised_loads: each equilibrium row's right-hand side is -loads
  std::vector<int> fn_col;    // per corner: its f_n column, 0 if open
  std::vector<int> ft_col;    // per joint: its f_t column, 0 if not in contact
  std::vector<int> joints_in_contact;
};
// Its GLPK problem, loaded once per configuration and solved for several mu, warm started.
struct SlidingLp {
  GlpProblem lp = new_glp_problem();
  long long solves = 0;
  bool fresh = true;  // no solve yet on the loaded problem: start from the standard basis
};

constexpr double kDeg = 180.0 / 3.14159265358979323846;

// ---- lp.cpp: the layer over GLPK (the PRD LP's rows, bounds, solves and what they give).
Model build_model(const Case& c, double tol);
std::vector<double> generalised_loads(const Model& m);  // N (and N m / L_b)
void update_lp(Model& m, double h, double scale, double h_open = 0);
void sync_glpk(Model& m);
// Sets GLPK's basis to one built from the statics of the structure as it stands, after update_lp
// (static_basis.cpp): true where every free block found rows that carry its loads in compression,
// so the basis is dual feasible; false, the basis untouched, otherwise.
bool set_static_basis(Model& m);
// confirm_infeasible: "no feasible point" only where two of GLPK's own starts find it (lp.cpp).
LpStatus solve(Model& m, bool confirm_infeasible = true);
// GLPK's exact (rational) simplex, solve()'s last resort, only up to this many rows: its time
// grows as the rows to the power 2.2 (the first LP of generated walls from the advanced basis:
// 1,140 rows 0.5 s, 2,612 rows 2.8 s, 5,676 rows 15.7 s), so that 10,000 rows take about a
// minute and a 6,442-block wall's 76,320 rows ran for hours.
constexpr int kExactRows = 10000;
// How far a row may fail a collapse mechanism's conditions, relative to its largest increment
// (is_mechanism): round-off on the O(1) coefficients is far below it, and it is a thousand times
// the pivot tolerance below which GLPK's own ratio test ignores a row (1e-10).
constexpr double kRayTolerance = 1e-7;
bool is_mechanism(const Model& m, const std::vector<double>& du);  // du per column, 1-based
// The direction GLPK's primal simplex found the last LP unbounded along (per column, 1-based;
// empty where GLPK names none: the exact simplex, or an LP it did not find unbounded).
std::vector<double> unbounded_ray(const Model& m);
double objective(const Model& m);               // of the last solve: N times the columns' unit (x the LP's scale: J)
double col_value(const Model& m, int j);        // column j's primal value (1-based)
double corner_force(const Model& m, size_t e);  // dual of corner e's no-penetration row, N
double corner_slack(const Model& m, size_t e);  // primal minus bound of that row, LP units
// Marks the corners named BLOCK/BLOCK:A held (Endpoint::held); throws naming the case for a name no corner has.
void hold_corners(Model& m, const std::vector<std::string>& names);
// Stage "start": places every block where a PrdStart's poses put it and sets each corner's
// contact state from its gap there (and, keeping offsets, its material points).
void start_from(Model& m, const PrdStart& start);
// The held corners' normal forces from the LP just solved (N; negative: the hold pulls, a tension
// no-tension masonry cannot give), as the record's "held_corners".
void record_held(const Model& m, StepRecord& rec);
void read_forces(const Model& m, StepRecord& rec);
std::vector<double> slacks(const Model& m, double scale);
Mechanism collapse_mechanism(Model& m, double scale, std::vector<Pose>* moved = nullptr);
void lp_check_fields(const Model& m, double scale, StepRecord& rec);
std::vector<double> column_values(const Model& m);
void save_basis(const Model& m, Accepted& a);
int evaluate_basis(Model& m, const Accepted& a, double h, double h_open);
// The sliding check's feasibility LP (sliding.cpp builds the problem).
void load_friction_lp(SlidingLp& S, const FrictionProblem& p);
bool friction_feasible(SlidingLp& S, const FrictionProblem& p, double mu);  // an admissible state at mu
double friction_col_value(const SlidingLp& S, int j);                       // of the last feasible solve

// ---- motion.cpp: finite rigid motion, gaps and the contact state, configuration records.
Vec2 pole_displacement(const Vec2& u, double th);
Increment support_increment(const Model& m, int b, double h);
std::vector<JointInfo> joint_infos(const Model& m);
std::vector<Pose> poses(const Model& m);
void record_corners(const Model& m, StepRecord& rec);
void gaps_and_rates(const Model& m, double h, double h_open, std::vector<double>& gap, std::vector<double>& rate);
std::vector<char> closed_after(const Model& m, const std::vector<double>& gap, const std::vector<double>& rate, double h_lp, double h, double h_ref);
void pose_after(const Model& m, const Path& path, size_t b, double h, Vec2& cen, double& angle);
void advance(Model& m, const Path& path, double h);
double gap_after(const Model& m, const Path& U, size_t e, double h);
void set_closed(Model& m, const std::vector<char>& closed);
void close_corners(Model& m, const std::vector<char>& closed);
StepRecord configuration_record(const Model& m, int index, double d);

// ---- events.cpp: where the next event is, for adaptive runs.
Closing first_closing(const Model& m, const Path& U, const std::vector<double>& gap, const std::vector<double>& rate, double limit);
std::optional<double> basis_crossing(Model& m, const Accepted& a, double span, double tol_ev);
double first_zero(double f, double b, double k);
Move predict_opening(const Accepted& a, const std::vector<double>& slope, const std::vector<double>& curve, const std::vector<char>& ignored);
Move plan_move(Model& m, Accepted& a, double h, double h_open, double x, const Move& guess, const std::vector<double>& slope,
               const std::vector<char>& ignored, double short_move, const std::function<double(double)>& land);
Event make_event(const Model& m, EventKind kind, double d, double within, const std::vector<size_t>& corners);

// ---- sliding.cpp
void sliding_check(const Model& m, SlidingLp& S, StepRecord& rec);

}  // namespace masonry::prd_detail
