// The case's options, one table per section of the case file (the case itself, motion, prd, dem):
// one record per option, with its key, type, range, unit, help and command-line flag, which the
// case loader (reading and range checks), the case writer, the settings echoed into results.json,
// the commands' flags and their help, and README.md's options table (`masonry options
// --markdown`) all read. The default is the plain struct's own (model/case.hpp): the table holds
// a pointer to the member, so values land in Case, Motion, PrdOptions and DemOptions as before.
#pragma once

#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "model/case.hpp"

namespace masonry {

// The values a number may take: [lo, hi], an end open where said.
struct Interval {
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;
  bool contains(double x) const { return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi); }
};

// Of the scene size: the finest length a case may set; below it a length is lost in the
// round-off of the coordinates.
constexpr double kFinestFraction = 1e-9;

// A length checked against the scene size L too (once the blocks are read): [lo L, hi L], where
// the value is above 0 (0 is "the default" for those that allow it). hi = 0: no such check.
struct SceneRange {
  double lo = 0, hi = 0;
  const char* why = "";  // said after the fractions in a refusal
};

// When a writer gives an option: always, or only where it is set (an optional present, a list
// not empty, a switch on, a word other than the default).
enum class Shown { always, when_set };

enum class OptionType { number, integer, boolean, word, words };
const char* option_type_name(OptionType t);  // "number", "integer", "true/false", "word", "list of words"

// One option of section S. Rows are written with designated initialisers (options.cpp).
template <class S>
struct Option {
  using Member = std::variant<double S::*, int S::*, bool S::*, std::optional<double> S::*, std::vector<std::string> S::*, HoldDamping S::*>;
  const char* name = "";  // the field in its section of the case file: "kinetic_ratio"
  Member member{};
  const char* unit = "";    // SI; "" for a ratio, a count or a switch
  Interval range{};         // numbers and integers
  const char* note = "";    // said with the range, in a refusal and in the README: what 0 or the unit means
  const char* absent = "";  // an optional number: what its absence gives
  SceneRange scene{};
  // A word: its values (the enum's, in order); a list of words: what each must be, and the check.
  std::span<const char* const> words{};
  bool (*word_ok)(const std::string&) = nullptr;
  const char* help = "";             // one line: what the option does
  const char* flag = "";             // "--kinetic-ratio"; "": none
  bool on_compare = false;           // the flag is on `compare` as well as on its method's command
  Shown in_case = Shown::always;     // case_to_json (results.json's settings give every option: valued_options)
};

// A section of the case file: its name ("dem"; "" for the case's own fields, written at the top
// level) and its options in the order the writer gives them.
template <class S>
struct OptionSection {
  const char* name;
  std::span<const Option<S>> rows;
};

template <class S>
const OptionSection<S>& options();
template <>
const OptionSection<Case>& options<Case>();
template <>
const OptionSection<Motion>& options<Motion>();
template <>
const OptionSection<PrdOptions>& options<PrdOptions>();
template <>
const OptionSection<DemOptions>& options<DemOptions>();

// Which of the commands that set case options gives an option a flag.
enum class OptionCommand { prd, dem, compare };
const char* option_command_name(OptionCommand c);  // "prd", "dem", "compare"

// An option of any section, as the flags and the README show it.
struct OptionInfo {
  std::string key;      // "dem.kinetic_ratio", "gravity"
  std::string section;  // "dem", "" for the case's own fields
  OptionType type = OptionType::number;
  std::string default_text;  // "1e-3", "absent: E / h_block, ...", "local"
  std::string range_text;    // "(0, 1]; 1e-9 to 0.1 x the scene size"
  const char* unit = "";
  const char* note = "";
  const char* help = "";
  const char* flag = "";
  std::vector<OptionCommand> commands;  // where the flag is offered
};
// Every option, sections in the case file's order.
std::vector<OptionInfo> option_infos();
// README.md's options table (Markdown), made from option_infos().
std::string options_markdown();

// The row of a member (&DemOptions::kinetic_ratio), its name in the section and its key
// ("dem.kinetic_ratio"): code that names an option in a key or a message uses these, so the key
// is written once, in its row. Throws std::logic_error for a member no row holds.
template <class S, class T>
const Option<S>& option_of(T S::*member) {
  for (const Option<S>& o : options<S>().rows)
    if (const auto* p = std::get_if<T S::*>(&o.member); p && *p == member) return o;
  throw std::logic_error("masonry: no option row holds this member");
}
template <class S, class T>
std::string option_key(T S::*member) {
  const char* section = options<S>().name;
  return (*section ? std::string(section) + "." : std::string()) + option_of(member).name;
}
// Sets one option's field in a results.json settings object (a value the run derived, such as the
// DEM's kn where the case left it absent).
template <class S, class T, class V>
void set_setting(nlohmann::ordered_json& settings, T S::*member, const V& value) {
  settings[option_of(member).name] = value;
}

// Reads section `obj` (the case document itself for the case's own fields) into `s`: an unknown
// field refused (`others` are the section's fields that are not options, read by the caller),
// each option's type and range checked. `where` names the section in messages ("dem", "case").
// Throws CaseError "SOURCE: WHERE: field 'X' ...".
template <class S>
void read_options(const nlohmann::json& obj, S& s, const std::string& source, std::initializer_list<const char*> others = {});
// The ranges alone, for settings a study derives in code; a time-step factor above 1 only where
// `allow_unstable_timestep` (the DEM's blow-up tests).
template <class S>
void check_options(const S& s, const std::string& source, bool allow_unstable_timestep = false);
// The ranges relative to the scene size L (SceneRange), once the blocks are known.
template <class S>
void check_scene_options(const S& s, double L, const std::string& source);
// The section as case_to_json writes it (Option::in_case) into `obj`, after what it holds.
template <class S>
void write_options(nlohmann::ordered_json& obj, const S& s);
// Every option of the section that has a value (all but an optional number left absent, which
// a run derives when it starts), as the writers give them, defaults included: the settings
// results.json echoes (both methods, so a results file says everything its run used, not only
// what the case changed) and what Python's case[key] reads.
template <class S>
nlohmann::ordered_json valued_options(const S& s);

// Options the case sets that act only with another one it leaves off (prd.event_tolerance and
// prd.max_step without prd.adaptive, dem.ramp_fraction without dem.move_time): one line each
// for the user, since the run accepts them, echoes them in its settings and ignores them.
std::vector<std::string> idle_options(const PrdOptions& p);
std::vector<std::string> idle_options(const DemOptions& d);

}  // namespace masonry
