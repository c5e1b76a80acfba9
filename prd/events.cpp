// Event location for adaptive runs: where a corner closes on a move, where a basis stops being
// optimal, where a closed corner's force reaches zero.
#include "prd/internal.hpp"

namespace masonry::prd_detail {

// The first open corner that closes within a move of `limit` along the path, and the move

Closing first_closing(const Model& m, const Path& U, const std::vector<double>& gap, const std::vector<double>& rate, double limit) {
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
    for (int it = 0; it < 100 && hi - lo > 1e-12 * limit && gap_after(m, U, e, lo) - gap_after(m, U, e, hi) > 0.1 * target; ++it) {
      const double mid = 0.5 * (lo + hi);
      (gap_after(m, U, e, mid) > target ? lo : hi) = mid;
    }
    c = {hi, e, hi - lo};
  }
  return c;
}

// Where, between configuration a and the current one (a distance `span` further on), the
// basis of a's LP stopped being the optimum: that basis (and contact state) is evaluated here
// without a simplex iteration, and where a closed corner's normal force or an open corner's
// slack has turned negative, it is interpolated linearly to its zero. Infinite when nothing
// has; empty when GLPK cannot evaluate the basis. A corner that closed on the way (open in a,
// closed here) is not counted: its closing was located where it happened. Leaves the contact
// state as a's.
std::optional<double> basis_crossing(Model& m, const Accepted& a, double span, double tol_ev) {
  std::vector<char> closed_since(m.ends.size());
  for (size_t e = 0; e < m.ends.size(); ++e) closed_since[e] = !a.closed[e] && m.ends[e].closed;
  set_closed(m, a.closed);
  if (evaluate_basis(m, a, a.h_lp, std::min(a.h_lp, tol_ev)) != 0) return std::nullopt;
  double at = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < m.ends.size(); ++e) {
    if (closed_since[e]) continue;
    const double was = a.closed[e] ? a.fn[e] : a.slack[e];
    const double now = a.closed[e] ? corner_force(m, e) : corner_slack(m, e);
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

// Where a closed corner of configuration a is expected to open, as a distance x in d: where
// its normal force f + slope x + curve x^2 reaches 0. (For a fixed basis the duals vary
// smoothly with the geometry; the basis changes where one of them would turn negative.)
// Corners `ignored` are left out (see prd_run).
Move predict_opening(const Accepted& a, const std::vector<double>& slope, const std::vector<double>& curve, const std::vector<char>& ignored) {
  Move mv;
  for (size_t e = 0; e < slope.size(); ++e)
    if (a.closed[e] && a.fn[e] > 0 && !ignored[e]) mv.consider(first_zero(a.fn[e], slope[e], curve.empty() ? 0.0 : curve[e]), e);
  return mv;
}

// The move x from a along its LP's basis, checked where it would end: the basis is evaluated
// there (no simplex iteration). Where a closed corner's force has turned negative, the move is
// cut to land short of where it reaches 0, and checked again. The zero is that of the
// quadratic through a's force, its trend `slope` when known, and the value there; of the chord
// otherwise. `guess` is the prediction the move came from. A move longer than `short_move`
// follows the mean of the mechanisms at both ends (a.dU: Heun's second-order step); a shorter
// one needs no check. (Closings are left to first_closing, on the move's exact path.)
Move plan_move(Model& m, Accepted& a, double h, double h_open, double x, const Move& guess, const std::vector<double>& slope,
               const std::vector<char>& ignored, double short_move, const std::function<double(double)>& land) {
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
      if (a.closed[e] && a.fn[e] > 0) {
        const double f0 = a.fn[e], f1 = corner_force(m, e);
        at.consider(slope.empty() ? first_zero(f0, (f1 - f0) / x, 0.0) : first_zero(f0, slope[e], (f1 - f0 - slope[e] * x) / (x * x)), e);
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
        const double th = col_value(m, k + 2) / m.radius[b];
        const Vec2 v = Vec2(col_value(m, k), col_value(m, k + 1)) + th * perp(cen[b] - there[b]);
        dU[k] = (v.x() - a.U[k]) / x;
        dU[k + 1] = (v.y() - a.U[k + 1]) / x;
        dU[k + 2] = (col_value(m, k + 2) - a.U[k + 2]) / x;
      }
    } else {
      a.dU = dU;
      break;
    }
  }
  return mv;
}

Event make_event(const Model& m, EventKind kind, double d, double within, const std::vector<size_t>& corners) {
  Event ev{kind, d, within, {}};
  for (size_t e : corners) ev.corners.push_back({m.ends[e].joint, m.ends[e].corner});
  return ev;
}

}  // namespace masonry::prd_detail
