#include "dem/variants.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace masonry {

namespace {

std::string num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

std::vector<DemVariant> convergence_variants(const DemSettings& base) {
  std::vector<DemVariant> v;
  v.push_back({"default", "the case's settings", base});
  DemVariant slow{"slower-loading", "", base};
  if (base.move_time > 0) {
    slow.settings.move_time = 2 * base.move_time;
    slow.what = "move time x2 (" + num(slow.settings.move_time) + " s)";
  } else {
    // The servo holds the kinetic energy near its target, so the support speed goes as its
    // square root: a quarter of the energy is half the speed.
    slow.settings.kinetic_ratio = base.kinetic_ratio / 4;
    slow.what = "loading twice as slow (kinetic ratio / 4 = " + num(slow.settings.kinetic_ratio) + ")";
  }
  v.push_back(slow);
  DemVariant half{"half-step", "half the increment (" + num(base.step / 2) + " m)", base};
  half.settings.step = base.step / 2;
  half.settings.max_steps = 2 * base.max_steps;
  v.push_back(half);
  DemVariant damp{"damping", "", base};
  damp.settings.damping = std::abs(base.damping - 0.8) < 1e-12 ? 0.6 : 0.8;
  damp.what = "damping " + num(damp.settings.damping);
  v.push_back(damp);
  DemVariant dt{"half-timestep", "time-step factor / 2 (" + num(base.timestep_factor / 2) + ")", base};
  dt.settings.timestep_factor = base.timestep_factor / 2;
  v.push_back(dt);
  DemVariant stiff{"stiffer-joints", "joints x3 stiffer (kn, ks)", base};
  stiff.settings.stiffness_reduction = base.stiffness_reduction / 3;
  v.push_back(stiff);
  DemVariant soft{"softer-joints", "joints x3 softer (kn, ks)", base};
  soft.settings.stiffness_reduction = base.stiffness_reduction * 3;
  v.push_back(soft);
  // How a hold comes to rest must not matter either: the equilibrium it ends on is the same
  // whether momentum is removed by local damping alone or also by kinetic damping.
  const bool kinetic = base.hold_damping == HoldDamping::local;
  DemVariant hd{"hold-damping", kinetic ? "holds with kinetic damping" : "holds with local damping alone", base};
  hd.settings.hold_damping = kinetic ? HoldDamping::kinetic : HoldDamping::local;
  v.push_back(hd);
  // Nor how the joints' own vibration is damped: contact damping at the zeta measured harmless
  // on the structures that do not need it (within 0.2%), or none where the case has some. Where
  // the joints are stiff against the weights the undamped joints ratchet (dem/README.md,
  // "Contact damping"), and this variant is the one that parts from the default.
  const bool add = !(base.contact_damping > 0);
  DemVariant cd{"contact-damping", add ? "contact damping " + num(kCheckContactDamping) : "no contact damping", base};
  cd.settings.contact_damping = add ? kCheckContactDamping : 0.0;
  v.push_back(cd);
  if (base.friction_angle < 90) {
    DemVariant fr{"more-friction", "", base};
    fr.settings.friction_angle = std::min(90.0, base.friction_angle + 10);
    fr.what = "friction angle " + num(fr.settings.friction_angle) + " deg";
    v.push_back(fr);
  }
  return v;
}

std::vector<DemVariant> stiffness_variants(const DemSettings& base) {
  std::vector<DemVariant> v;
  v.push_back({"default", "the case's joints", base});
  // (name, how many times softer or stiffer), softest first after the default. The reduction is
  // multiplied or divided by a whole number, so x3 is exactly the convergence study's x3.
  struct Scale {
    const char* name;
    int times;
    bool stiffer;
  };
  for (const Scale& k : {Scale{"softer-x10", 10, false}, Scale{"softer-x3", 3, false}, Scale{"stiffer-x3", 3, true}, Scale{"stiffer-x10", 10, true},
                         Scale{"stiffer-x30", 30, true}}) {
    DemVariant var{k.name, "joints x" + std::to_string(k.times) + (k.stiffer ? " stiffer" : " softer"), base};
    var.settings.stiffness_reduction = k.stiffer ? base.stiffness_reduction / k.times : base.stiffness_reduction * k.times;
    v.push_back(var);
  }
  return v;
}

}  // namespace masonry
