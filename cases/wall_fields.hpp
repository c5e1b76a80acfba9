// The wall generator's parameters (`masonry cases wall --NAME`, Python's generate("wall",
// NAME=...)), one row each. Both front ends read this table, so a parameter's name and help are
// written once and its default is BrickWall's own. The wall is not in the generators' parameter
// table (parameters.hpp) because its bond and ground are words and its openings a list.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <variant>

#include "cases/generators.hpp"

namespace masonry {

struct WallField {
  const char* name;  // the option without "--"; Python's keyword with '_' for '-'
  std::variant<int BrickWall::*, double BrickWall::*, WallBond BrickWall::*, MovingGround BrickWall::*> member;
  const char* help;
  bool show_default = true;  // false where the struct's default is a sentinel ("the middle")
};
std::span<const WallField> wall_fields();

// The repeatable opening "X,SILL,WIDTH,HEIGHT[,lintel|arch]" (parse_wall_opening).
inline constexpr const char* kWallOpeningName = "opening";
extern const char* const kWallOpeningHelp;

// The words of a word field (WallBond, MovingGround), as the command line and Python take them,
// each with the value it stands for.
template <class E>
std::map<std::string, E> wall_words();
template <>
std::map<std::string, WallBond> wall_words();
template <>
std::map<std::string, MovingGround> wall_words();
// The word of a value (the default's, in the help).
template <class E>
std::string wall_word(E value) {
  for (const auto& [w, e] : wall_words<E>())
    if (e == value) return w;
  return "?";
}

// BrickWall from an object NAME -> value (a number, a word, or for "opening" one text or a list
// of them); the names it does not give keep their defaults. Throws CaseError "WHERE: parameter
// 'NAME' ..." for an unknown name or a value of the wrong kind.
BrickWall wall_parameters(const nlohmann::json& values, const std::string& where);

}  // namespace masonry
