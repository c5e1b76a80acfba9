// The generators' parameter tables (parameters.hpp): each entry binds a name, its help and its
// kind to a field of the generator's parameter struct, the default read from that struct.
#include "cases/parameters.hpp"

#include <cmath>

#include "cases/generators.hpp"

namespace masonry {

namespace {

constexpr double kDeg = M_PI / 180.0;

// One parameter of a generator whose parameters are the struct P.
template <class P>
struct Binding {
  GeneratorParameter parameter;
  std::function<void(P&, double)> set;
};

template <class P>
Binding<P> number(const P& d, const char* name, double P::*field, const char* help, const char* unit) {
  return {{name, ParameterKind::number, help, d.*field, unit}, [field](P& p, double v) { p.*field = v; }};
}

template <class P>
Binding<P> integer(const P& d, const char* name, int P::*field, const char* help) {
  return {{name, ParameterKind::integer, help, double(d.*field), ""}, [field](P& p, double v) { p.*field = static_cast<int>(v); }};
}

template <class P>
Binding<P> flag(const P& d, const char* name, bool P::*field, const char* help) {
  return {{name, ParameterKind::flag, help, d.*field ? 1.0 : 0.0, ""}, [field](P& p, double v) { p.*field = v != 0; }};
}

// The angle of embrace in degrees (the struct holds radians), converted as the command line
// always did: degrees * (pi / 180).
template <class P>
Binding<P> embrace_deg(double deg, const char* help, const char* unit) {
  return {{"embrace-deg", ParameterKind::number, help, deg, unit}, [](P& p, double v) { p.embrace = v * kDeg; }};
}

// --fixed: no support motion (the struct's `spreading` is its negation).
template <class P>
Binding<P> fixed(const P& d) {
  return {{"fixed", ParameterKind::flag, "No support motion", d.spreading ? 0.0 : 1.0, ""}, [](P& p, double v) { p.spreading = v == 0; }};
}

// A generator from its bindings; `build` writes the case from the struct, `standard` (when not
// empty) is the standard scene the defaults are.
template <class P>
CaseGenerator generator(const std::string& name, const std::string& summary, const P& defaults, std::vector<Binding<P>> bindings,
                        std::function<Case(const P&)> build, const std::string& standard) {
  CaseGenerator g;
  g.name = name;
  g.summary = summary;
  for (const Binding<P>& b : bindings) g.parameters.push_back(b.parameter);
  std::vector<double> at_default;
  for (const Binding<P>& b : bindings) at_default.push_back(b.parameter.value);
  g.make = [defaults, bindings, build, standard, at_default](const std::vector<double>& values) {
    if (!standard.empty() && values == at_default) return standard_case(standard);
    P p = defaults;
    for (size_t k = 0; k < bindings.size(); ++k) bindings[k].set(p, values.at(k));
    return build(p);
  };
  return g;
}

std::vector<Binding<CircularArch>> circular_arch_bindings(const CircularArch& d) {
  using P = CircularArch;
  return {number(d, "radius", &P::radius, "Centreline radius R", "m"),
          number(d, "thickness", &P::thickness, "Thickness t", "m"),
          embrace_deg<P>(d.embrace / kDeg, "Angle of embrace", "deg"),
          integer(d, "voussoirs", &P::voussoirs, "Number of voussoirs"),
          number(d, "depth", &P::depth, "Out-of-plane depth", "m"),
          number(d, "density", &P::density, "Density", "kg/m^3"),
          number(d, "step", &P::step, "Support displacement per step", "m"),
          integer(d, "max-steps", &P::max_steps, "Largest number of steps"),
          fixed(d)};
}

std::vector<Binding<PointedArch>> pointed_arch_bindings(const PointedArch& d) {
  using P = PointedArch;
  return {number(d, "rcirc", &P::rcirc, "Centreline radius of the equivalent circular arch Rcirc", "m"),
          number(d, "eccentricity", &P::eccentricity, "Eccentricity e of the two centres from the axis (Rpoint = Rcirc + e)", "m"),
          number(d, "thickness", &P::thickness, "Thickness t", "m"),
          embrace_deg<P>(150.0, "Angle of embrace (between the springing joints)", "deg"),
          integer(d, "voussoirs", &P::voussoirs, "Number of voussoirs (even: crown joint on the axis; odd: keystone)"),
          number(d, "depth", &P::depth, "Out-of-plane depth", "m"),
          number(d, "density", &P::density, "Density", "kg/m^3"),
          number(d, "step", &P::step, "Support displacement per step", "m"),
          integer(d, "max-steps", &P::max_steps, "Largest number of steps"),
          fixed(d)};
}

std::vector<Binding<GothicCathedral>> cathedral_bindings(const GothicCathedral& d) {
  using P = GothicCathedral;
  return {number(d, "nave-height", &P::nave_height, "Intrados crown of the nave arch", "m"),
          number(d, "aisle-height", &P::aisle_height, "Intrados crown of the aisle arches", "m"),
          number(d, "bay", &P::bay, "Bay: out-of-plane depth of the arches (vaults)", "m"),
          number(d, "nave-span", &P::nave_span, "Clear span of the nave between the piers", "m"),
          number(d, "pier-width", &P::pier_width, "Width of the nave pier shaft", "m"),
          number(d, "aisle-span", &P::aisle_span, "Clear span of the aisle arch", "m"),
          number(d, "buttress-width", &P::buttress_width, "Width of the outer buttress above the aisle springing", "m"),
          number(d, "nave-springing", &P::nave_springing, "Height of the nave arch's springing (pier top)", "m"),
          number(d, "aisle-springing", &P::aisle_springing, "Height of the aisle arch's springing", "m"),
          number(d, "nave-thickness", &P::nave_thickness, "Nave arch thickness", "m"),
          number(d, "aisle-thickness", &P::aisle_thickness, "Aisle arch thickness", "m"),
          number(d, "flyer-thickness", &P::flyer_thickness, "Flying buttress thickness", "m"),
          number(d, "lower-flyer-head", &P::lower_flyer_head, "Lower flyer: intrados height at the pier", "m"),
          number(d, "lower-flyer-foot", &P::lower_flyer_foot, "Lower flyer: intrados height at the buttress", "m"),
          number(d, "upper-flyer-head", &P::upper_flyer_head, "Upper flyer: intrados height at the pier", "m"),
          flag(d, "upper-flyer-at-springing", &P::upper_flyer_at_springing,
               "Upper flyer's head top at the nave springing, whatever the springing and the flyer thickness (replaces --upper-flyer-head)"),
          number(d, "upper-flyer-foot", &P::upper_flyer_foot, "Upper flyer: intrados height at the buttress", "m"),
          number(d, "buttress-height", &P::buttress_height, "Height of the outer buttress", "m"),
          number(d, "foundation-height", &P::foundation_height, "Height of the support blocks", "m"),
          number(d, "pier-depth", &P::pier_depth, "Out-of-plane depth of the piers", "m"),
          number(d, "buttress-depth", &P::buttress_depth, "Out-of-plane depth of the buttresses", "m"),
          number(d, "flyer-depth", &P::flyer_depth, "Out-of-plane depth of the flying buttresses", "m"),
          number(d, "density", &P::density, "Density", "kg/m^3"),
          number(d, "course", &P::course, "Target course height of piers and buttresses", "m"),
          integer(d, "nave-voussoirs", &P::nave_voussoirs, "Voussoirs of the nave arch (even)"),
          integer(d, "aisle-voussoirs", &P::aisle_voussoirs, "Voussoirs of each aisle arch (even)"),
          integer(d, "flyer-voussoirs", &P::flyer_voussoirs, "Voussoirs of each flying buttress"),
          integer(d, "moving-support", &P::moving_support, "Support that moves, 1..4 from the left (3: third pier)"),
          number(d, "settlement-step", &P::settlement_step, "Settlement of that support per step, downwards", "m"),
          number(d, "rotation-step", &P::rotation_step, "Counter-clockwise rotation per step about its centroid", "rad"),
          number(d, "step", &P::step, "Path parameter d per step", "m"),
          integer(d, "max-steps", &P::max_steps, "Largest number of steps")};
}

std::vector<CaseGenerator> make_generators() {
  std::vector<CaseGenerator> out;
  const CircularArch arch;
  out.push_back(generator<CircularArch>("circular-arch", "Circular arch, radial joints, on two supports; right support spreading", arch,
                                        circular_arch_bindings(arch), circular_arch, ""));
  const PointedArch pointed = standard_pointed_arch();
  out.push_back(generator<PointedArch>("pointed-arch",
                                       "Two-centred pointed arch (Romano & Ochsendorf parameters) on two supports; right support spreading. "
                                       "With the default parameters: the standard scene cases/pointed-arch.json",
                                       pointed, pointed_arch_bindings(pointed), pointed_arch, "pointed-arch"));
  const auto cathedral = [&](const std::string& name, const std::string& summary, const GothicCathedral& d, const std::string& standard) {
    out.push_back(generator<GothicCathedral>(name, summary, d, cathedral_bindings(d), gothic_cathedral, standard));
  };
  cathedral("cathedral", "Gothic cathedral cross-section after the paper (Amiens); no motion unless asked", GothicCathedral{}, "");
  cathedral("cathedral-settlement", "Standard scene: the cathedral, third pier settling 1 cm per step", standard_cathedral_settlement(),
            "cathedral-settlement");
  cathedral("cathedral-settlement-rotation", "Standard scene: the cathedral, third pier settling 1 cm and turning 0.001 rad per step",
            standard_cathedral_settlement_rotation(), "cathedral-settlement-rotation");
  return out;
}

}  // namespace

const std::vector<CaseGenerator>& case_generators() {
  static const std::vector<CaseGenerator> all = make_generators();
  return all;
}

const CaseGenerator* find_case_generator(const std::string& name) {
  for (const CaseGenerator& g : case_generators())
    if (g.name == name) return &g;
  return nullptr;
}

int parameter_index(const CaseGenerator& g, const std::string& name) {
  for (size_t k = 0; k < g.parameters.size(); ++k)
    if (g.parameters[k].name == name) return static_cast<int>(k);
  return -1;
}

std::string parameter_help(const GeneratorParameter& p) { return p.help + (p.unit.empty() ? "" : ", " + p.unit); }

std::string parameter_names(const CaseGenerator& g) {
  std::string s;
  for (const GeneratorParameter& p : g.parameters) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

double parameter_value(const CaseGenerator& g, const GeneratorParameter& p, const nlohmann::json& v) {
  const auto fail = [&](const std::string& what) {
    throw CaseError("generator " + g.name + ": parameter '" + p.name + "': " + what + ", got " + printable(v.dump()));
  };
  if (p.kind == ParameterKind::flag) {
    if (!v.is_boolean()) fail("must be true or false");
    return v.get<bool>() ? 1.0 : 0.0;
  }
  if (!v.is_number()) fail("must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail("must be a finite number");
  if (p.kind == ParameterKind::integer && (x != std::floor(x) || std::abs(x) > 1e9)) fail("must be a whole number");
  return x;
}

Case generate_case(const std::string& name, const nlohmann::json& values) {
  const CaseGenerator* g = find_case_generator(name);
  if (!g) throw CaseError("no case generator '" + printable(name) + "' (masonry cases --list)");
  if (!values.is_null() && !values.is_object()) throw CaseError("generator " + name + ": the parameters must be an object {NAME: value}");
  std::vector<double> v;
  for (const GeneratorParameter& p : g->parameters) v.push_back(p.value);
  if (values.is_object())
    for (auto it = values.begin(); it != values.end(); ++it) {
      const int k = parameter_index(*g, it.key());
      if (k < 0) throw CaseError("generator " + name + ": no parameter '" + printable(it.key()) + "' (it has " + parameter_names(*g) + ")");
      v[k] = parameter_value(*g, g->parameters[k], it.value());
    }
  return g->make(v);
}

}  // namespace masonry
