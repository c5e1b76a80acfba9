// The settled cathedral's nave vault, against a closed form. Settled under gravity at d = 0, the
// DEM's piers lean elastically and the nave vault rests on four hinges (corners open by a few
// hundred microns, far above the elastic gaps of its closed joints). Four hinges make the vault a
// four-bar linkage: two side segments turning about their springing hinges and the crown segment
// between them. Rigid-block statics says such a linkage is in equilibrium at the symmetric pose,
// and its stability is the sign of the second variation of the potential energy along its one
// degree of freedom; when negative, the sway grows as exp(lambda t), lambda^2 = -V'' / I, I the
// linkage's generalised inertia. With local damping alpha every block's unbalanced force is cut
// to (1 - alpha) of itself while the motion grows, so the DEM's rate is lambda sqrt(1 - alpha).
// The geometry, the masses and the hinge corners fix the closed form: no DEM output enters it
// except which joints are open.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dem/dem.hpp"
#include "model/case.hpp"
#include "model/interfaces.hpp"

namespace masonry {
namespace {

Vec2 turn(double t, const Vec2& v) { return Vec2(std::cos(t) * v.x() - std::sin(t) * v.y(), std::sin(t) * v.x() + std::cos(t) * v.y()); }

// A four-bar linkage: ground pivots p1, p4; segment 0 turns about p1, 1 hangs between p2 and p3,
// 2 turns about p4.
struct Linkage {
  const Case* c = nullptr;
  Vec2 p1, p2, p3, p4;
  std::vector<int> seg[3];  // the blocks of each segment

  // The crown's and the right segment's rotations for a left rotation th (loop closure, Newton).
  void close(double th, double& phi, double& psi) const {
    const Vec2 q2 = p1 + turn(th, p2 - p1);
    phi = psi = 0;
    for (int it = 0; it < 60; ++it) {
      const Vec2 a = turn(phi, p3 - p2), b = turn(psi, p3 - p4);
      const Vec2 f = q2 + a - p4 - b;
      const Vec2 ja = perp(a), jb = -perp(b);  // d f / d phi, d f / d psi
      const double det = ja.x() * jb.y() - jb.x() * ja.y();
      const double dphi = (f.x() * jb.y() - jb.x() * f.y()) / det, dpsi = (ja.x() * f.y() - f.x() * ja.y()) / det;
      phi -= dphi;
      psi -= dpsi;
      if (std::abs(dphi) + std::abs(dpsi) < 1e-17) break;
    }
  }
  // Potential energy of gravity (J) at left rotation th, relative to any fixed datum.
  double potential(double th) const {
    double phi, psi;
    close(th, phi, psi);
    const Vec2 q2 = p1 + turn(th, p2 - p1);
    double v = 0;
    for (int s = 0; s < 3; ++s)
      for (int b : seg[s]) {
        const Vec2 x = centroid(c->blocks[b].vertices);
        const Vec2 y = s == 0 ? Vec2(p1 + turn(th, x - p1)) : s == 1 ? Vec2(q2 + turn(phi, x - p2)) : Vec2(p4 + turn(psi, x - p4));
        v += block_mass(c->blocks[b]) * c->gravity * y.y();
      }
    return v;
  }
  // Generalised inertia for the left rotation's rate (kinetic energy = I th'^2 / 2), kg m^2.
  double inertia(double& r_crown, double& r_right) const {
    const double h = 1e-7;
    double phi, psi;
    close(h, phi, psi);
    r_crown = phi / h;
    r_right = psi / h;
    double I = 0;
    for (int s = 0; s < 3; ++s)
      for (int b : seg[s]) {
        const Block& bl = c->blocks[b];
        const Vec2 x = centroid(bl.vertices);
        const double w = s == 0 ? 1 : s == 1 ? r_crown : r_right;
        const Vec2 v = s == 0 ? perp(x - p1) : s == 1 ? Vec2(perp(p2 - p1) + r_crown * perp(x - p2)) : Vec2(r_right * perp(x - p4));
        I += block_mass(bl) * v.squaredNorm() + bl.density * bl.depth * polar_moment(bl.vertices) * w * w;
      }
    return I;
  }
};

int nave_index(const Case& c, int b) {
  const std::string& id = c.blocks[b].id;
  return id.rfind("nave-", 0) == 0 ? std::stoi(id.substr(5)) : -1;
}

TEST(DemSettledCathedral, TheNaveSwaysAsTheFourBarLinkageOfItsOpenJoints) {
  const Case c = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/cathedral-settlement.json");
  const DemSettings s = DemSettings::from_case(c);
  DemModel m(c, s);
  const auto cycles_to = [&](double t) { m.cycle(std::max(0LL, static_cast<long long>(std::ceil((t - m.time()) / m.dt())))); };
  cycles_to(1.5);  // settled under gravity (the run's step 0 ends about here)

  // The open joints of the vault (nave-k/nave-k+1), in order, with the closed corner as hinge.
  const std::vector<Interface> joints = detect_interfaces(c, c.prd.contact_tolerance);
  const std::vector<double> gap = m.corner_gaps(joints);
  Linkage lk;
  lk.c = &c;
  std::vector<int> at;  // k of each hinge
  std::vector<Vec2> pivot;
  for (size_t j = 0; j < joints.size(); ++j) {
    const int ki = nave_index(c, joints[j].i), kj = nave_index(c, joints[j].j);
    if (ki < 0 || kj != ki + 1) continue;
    const double ga = gap[2 * j], gb = gap[2 * j + 1];
    if (std::max(ga, gb) < 50e-6) continue;  // closed: elastic gaps are a few microns
    at.push_back(ki);
    pivot.push_back(ga > gb ? joints[j].b : joints[j].a);
  }
  ASSERT_EQ(at.size(), 4u) << "the settled nave vault is not on four hinges";
  std::vector<int> order{0, 1, 2, 3};
  std::sort(order.begin(), order.end(), [&](int x, int y) { return at[x] < at[y]; });
  lk.p1 = pivot[order[0]];
  lk.p2 = pivot[order[1]];
  lk.p3 = pivot[order[2]];
  lk.p4 = pivot[order[3]];
  for (int b = 0; b < static_cast<int>(c.blocks.size()); ++b) {
    const int k = nave_index(c, b);
    for (int s = 0; s < 3; ++s)
      if (k > at[order[s]] && k <= at[order[s + 1]]) lk.seg[s].push_back(b);
  }

  // The closed form: V'' by central differences of the exact (finite-rotation) potential.
  const double h = 1e-3;
  const double v2 = (lk.potential(h) - 2 * lk.potential(0) + lk.potential(-h)) / (h * h);
  double r_crown, r_right;
  const double I = lk.inertia(r_crown, r_right);
  ASSERT_LT(v2, 0) << "the linkage is stable by the closed form (V'' = " << v2 << " J/rad^2)";
  const double rate = std::sqrt(-v2 / I) * std::sqrt(1 - s.damping);

  // The DEM: the left segment's spin while the sway grows from rounding noise to where a hinge
  // closes (about 1e-4 rad/s on this scene); fit log|spin| against time between 1e-6 and 1e-5
  // rad/s, once the settling's own decaying motion (which still shows below 1e-6) is gone.
  const int probe = lk.seg[0][lk.seg[0].size() / 2], crown = lk.seg[1][lk.seg[1].size() / 2], right = lk.seg[2][lk.seg[2].size() / 2];
  std::vector<double> ts, ls;
  double w = 0;
  for (double t = 1.75; t < 15 && std::abs(w) < 1e-5; t += 0.25) {
    cycles_to(t);
    w = m.block(probe).spin;
    if (std::abs(w) > 1e-6) ts.push_back(m.time()), ls.push_back(std::log(std::abs(w)));
  }
  ASSERT_GE(ts.size(), 6u) << "the sway did not grow through 1e-6..1e-5 rad/s within 15 s";
  double st = 0, sl = 0, stt = 0, stl = 0;
  const double n = static_cast<double>(ts.size());
  for (size_t i = 0; i < ts.size(); ++i) st += ts[i], sl += ls[i], stt += ts[i] * ts[i], stl += ts[i] * ls[i];
  const double measured = (n * stl - st * sl) / (n * stt - st * st);
  EXPECT_NEAR(measured, rate, 0.05 * rate) << "closed form lambda sqrt(1 - alpha) = " << rate << " 1/s, V'' = " << v2 << " J/rad^2, I = " << I;
  // The mode: every block of a segment turns at the segment's rate, in the linkage's ratios.
  EXPECT_NEAR(m.block(crown).spin / m.block(probe).spin, r_crown, 0.02 * std::abs(r_crown));
  EXPECT_NEAR(m.block(right).spin / m.block(probe).spin, r_right, 0.02 * std::abs(r_right));
}

}  // namespace
}  // namespace masonry
