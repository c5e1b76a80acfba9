// The wall generator's parameter table (wall_fields.hpp).
#include "cases/wall_fields.hpp"

#include <array>
#include <cmath>
#include <type_traits>

namespace masonry {

namespace {
using W = BrickWall;
const std::array<WallField, 18> kFields{{
    {"bond", &W::bond, "running, stack or header"},
    {"courses", &W::courses, "Number of courses"},
    {"bricks", &W::bricks, "Units per course: stretchers, or headers in header bond"},
    {"brick-length", &W::brick_length, "Stretcher length, m"},
    {"header-length", &W::header_length, "Header face length (the brick's width), m; header bond"},
    {"course-height", &W::course_height, "Course height, m"},
    {"depth", &W::depth, "Out-of-plane thickness of the wall, m"},
    {"density", &W::density, "Density, kg/m3"},
    {"lintel-bearing", &W::lintel_bearing, "A lintel's bearing on each side of its opening, m"},
    {"arch-thickness", &W::arch_thickness, "Thickness of an arch's ring, m"},
    {"arch-voussoirs", &W::arch_voussoirs, "Voussoirs of each arch (0: about one per course height)"},
    {"ground-height", &W::ground_height, "Height of the two ground blocks, m"},
    {"ground-split", &W::ground_split, "Where the ground splits, m from the wall's left end (default: the middle)", false},
    {"moving", &W::moving, "Which ground block moves: left, right or none"},
    {"settlement-step", &W::settlement_step, "Settlement of the moving ground per step, m (down)"},
    {"rotation-step", &W::rotation_step, "Counter-clockwise rotation of the moving ground per step, rad, about the split's top point"},
    {"step", &W::step, "Path parameter d per step, m"},
    {"max-steps", &W::max_steps, "Largest number of steps"},
}};

// The value of a word field: one of `words`, else a one-line refusal listing them.
template <class E>
E word_value(const std::map<std::string, E>& words, const std::string& where, const std::string& name, const nlohmann::json& v) {
  if (v.is_string())
    if (const auto it = words.find(v.get<std::string>()); it != words.end()) return it->second;
  std::string list;
  for (const auto& [w, e] : words) list += (list.empty() ? "" : ", ") + w;
  throw CaseError(where + ": parameter '" + name + "' must be one of " + list);
}
}  // namespace

const char* const kWallOpeningHelp =
    "An opening X,SILL,WIDTH,HEIGHT[,lintel|arch] (m from the wall's left end and base; sill and top move to the nearest course "
    "joint; default top: lintel); repeatable";

std::span<const WallField> wall_fields() { return kFields; }

template <>
std::map<std::string, WallBond> wall_words() {
  std::map<std::string, WallBond> out;
  for (WallBond b : {WallBond::running, WallBond::stack, WallBond::header}) out[wall_bond_name(b)] = b;
  return out;
}

template <>
std::map<std::string, MovingGround> wall_words() {
  return {{"none", MovingGround::none}, {"left", MovingGround::left}, {"right", MovingGround::right}};
}

BrickWall wall_parameters(const nlohmann::json& values, const std::string& where) {
  if (!values.is_object()) throw CaseError(where + ": the parameters must be an object NAME -> value");
  BrickWall p;
  for (auto it = values.begin(); it != values.end(); ++it) {
    const std::string& name = it.key();
    const nlohmann::json& v = it.value();
    if (name == kWallOpeningName) {  // one text or a list of them
      for (const nlohmann::json& o : v.is_array() ? v : nlohmann::json::array({v})) {
        if (!o.is_string()) throw CaseError(where + ": parameter 'opening' must be \"X,SILL,WIDTH,HEIGHT[,lintel|arch]\" or a list of them");
        p.openings.push_back(parse_wall_opening(o.get<std::string>()));
      }
      continue;
    }
    const WallField* f = nullptr;
    for (const WallField& g : kFields)
      if (name == g.name) f = &g;
    if (!f) throw CaseError(where + ": no parameter '" + printable(name) + "' (masonry cases wall --help)");
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(p.*member)>;
          if constexpr (std::is_same_v<T, int>) {
            if (!v.is_number_integer()) throw CaseError(where + ": parameter '" + name + "' must be a whole number");
            p.*member = v.get<int>();
          } else if constexpr (std::is_same_v<T, double>) {
            if (!v.is_number() || !std::isfinite(v.get<double>())) throw CaseError(where + ": parameter '" + name + "' must be a number");
            p.*member = v.get<double>();
          } else {
            p.*member = word_value(wall_words<T>(), where, name, v);
          }
        },
        f->member);
  }
  return p;
}

}  // namespace masonry
