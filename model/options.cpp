#include "model/options.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <type_traits>

#include "model/fields.hpp"

namespace masonry {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// Ranges of the options (README, "Options"), wide enough for any masonry structure and narrow
// enough that every derived quantity stays finite in double precision.
constexpr double kMaxLength = 1e5;           // m: steps, tolerances, drifts
constexpr double kMaxGravity = 1e3;          // m/s^2 (100 g)
constexpr double kMaxModulus = 1e13;         // Pa (diamond: 1.2e12)
constexpr double kMaxJointStiffness = 1e18;  // Pa/m
constexpr double kMaxModelTime = 1e4;        // s of DEM model time
constexpr double kMaxSteps = 1e8;            // steps of one run: 1e8 LPs or DEM increments is days of work

// A joint corner as results name it, BLOCK/BLOCK:A, as corner_name writes it: a letter A to Z (C and on for a further joint between
// the same blocks), or A or B and the joint's number past Z.
bool is_joint_corner(const std::string& s) {
  const size_t slash = s.find('/'), colon = s.find(':');
  if (slash == std::string::npos || slash == 0 || s.rfind('/') != slash || colon == std::string::npos || s.rfind(':') != colon ||
      colon < slash + 2 || colon + 1 >= s.size())
    return false;
  const std::string x = s.substr(colon + 1);
  if (x.size() == 1) return x[0] >= 'A' && x[0] <= 'Z';
  if ((x[0] != 'A' && x[0] != 'B') || x[1] == '0' || x.find_first_not_of("0123456789", 1) != std::string::npos) return false;
  return x.size() > 3 || std::stoi(x.substr(1)) >= 14;  // the letters run out at the 14th joint
}

const Option<Case> kCaseRows[] = {
    {.name = "gravity",
     .member = &Case::gravity,
     .unit = "m/s^2",
     .range = {0, kMaxGravity},
     .note = "it acts along -y",
     .help = "Acceleration of gravity; with 0 some load must act"},
};

const Option<Motion> kMotionRows[] = {
    {.name = "step",
     .member = &Motion::step,
     .unit = "m",
     .range = {0, kMaxLength, true},
     .note = "rad where every moving support only turns; a support point must travel 1e-9 to 1 times the scene size per step: "
             "step x (the translation's length + the rotation x the scene size)",
     .help = "Increment of the path parameter d per step (rad where every moving support only turns: d is then an angle)",
     .flag = "--step",
     .on_compare = true},
    {.name = "max_steps",
     .member = &Motion::max_steps,
     .range = {0, kMaxSteps},
     .help = "Largest number of steps (0: the structure as it stands)",
     .flag = "--max-steps",
     .on_compare = true},
};

const Option<PrdOptions> kPrdRows[] = {
    {.name = "contact_tolerance",
     .member = &PrdOptions::contact_tolerance,
     .unit = "m",
     .range = {0, kMaxLength, true},
     .scene = {kFinestFraction, 0.1},
     .help = "A corner with a gap below this is closed; also the tolerance of joint detection",
     .flag = "--tolerance"},
    {.name = "adaptive",
     .member = &PrdOptions::adaptive,
     .help = "Event-driven steps: long while the mechanism holds, each event (a corner opening or closing, collapse) located "
             "within event_tolerance",
     .flag = "--adaptive"},
    {.name = "event_tolerance",
     .member = &PrdOptions::event_tolerance,
     .unit = "m",
     .range = {0, kMaxLength},
     .note = "0: 1e-4 of the scene size (where d is an angle, the turn that moves the scene's points by that)",
     .scene = {kFinestFraction, 0.1},
     .help = "With adaptive: how closely events are located",
     .flag = "--event-tolerance"},
    {.name = "max_step",
     .member = &PrdOptions::max_step,
     .unit = "m",
     .range = {0, kMaxLength},
     .note = "0: the smaller of 16 x motion.step and 0.4 sqrt(event_tolerance x scene size), 1/250 of the scene at the default "
             "tolerance (where d is an angle, as turns that move the scene's points by those lengths)",
     .scene = {kFinestFraction, 1},
     .help = "With adaptive: the longest step",
     .flag = "--max-step"},
    {.name = "sliding_check",
     .member = &PrdOptions::sliding_check,
     .help = "The sliding check on every step: the friction demand of the joint forces and the least friction angle an "
             "admissible force state needs (results: \"sliding\" in each step and at the top)",
     .flag = "--sliding"},
    {.name = "hold_closed",
     .member = &PrdOptions::hold_closed,
     .note = "a joint corner BLOCK/BLOCK:A or :B (:C, :D and on for further joints between the same blocks), as results name them",
     .word_ok = is_joint_corner,
     .help = "Joint corners kept closed over the whole run, each step recording their forces (held_corners, N, negative: a "
             "tension): the next mechanism's capacity where two are near-tied (dem/README.md, \"The branch X\")",
     .flag = "--hold",
     .on_compare = true,
     .in_case = Shown::when_set},
};

const Option<DemOptions> kDemRows[] = {
    {.name = "young_modulus",
     .member = &DemOptions::young_modulus,
     .unit = "Pa",
     .range = {0, kMaxModulus, true},
     .help = "Young's modulus E of the blocks, for the joints' default stiffness"},
    {.name = "poisson",
     .member = &DemOptions::poisson,
     .range = {-1, 0.5, true, true},
     .help = "Poisson's ratio nu, for the shear stiffness's default"},
    {.name = "friction_angle",
     .member = &DemOptions::friction_angle,
     .unit = "deg",
     .range = {0, 90},
     .note = "90: no slip limit",
     .help = "Friction angle of the joints",
     .flag = "--friction"},
    {.name = "stiffness_reduction",
     .member = &DemOptions::stiffness_reduction,
     .range = {1e-6, 1e6},
     .help = "kn and ks are divided by this (the paper used 10)",
     .flag = "--stiffness-reduction",
     .on_compare = true},
    {.name = "damping",
     .member = &DemOptions::damping,
     .range = {0, 1, false, true},
     .note = "0 only with hold_damping kinetic: a hold with local damping settles by this alone",
     .help = "Local non-viscous damping coefficient alpha",
     .flag = "--damping",
     .on_compare = true},
    {.name = "contact_damping",
     .member = &DemOptions::contact_damping,
     .range = {0, 1, false, true},
     .note = "of critical, at each contact point; 0: none",
     .help = "Viscous damping of the joints' relative motion (dem/README.md, \"Contact damping\")",
     .flag = "--contact-damping",
     .on_compare = true},
    {.name = "timestep_factor",
     .member = &DemOptions::timestep_factor,
     .range = {0, 1, true},
     .note = "of the critical time step, the stability limit of the explicit integration",
     .help = "The time step dt, as a fraction of the bound on the critical time step",
     .flag = "--timestep-factor",
     .on_compare = true},
    {.name = "equilibrium_tolerance",
     .member = &DemOptions::equilibrium_tolerance,
     .range = {0, 1, true},
     .note = "of a block's weight",
     .help = "Largest unbalanced force over a block's weight at equilibrium",
     .flag = "--equilibrium-tolerance"},
    {.name = "velocity_tolerance",
     .member = &DemOptions::velocity_tolerance,
     .unit = "m/s",
     .range = {0, 1, true},
     .help = "Largest block speed at equilibrium",
     .flag = "--velocity-tolerance"},
    {.name = "hold_time",
     .member = &DemOptions::hold_time,
     .unit = "s",
     .range = {0, kMaxModelTime, true},
     .help = "Model-time cap of one hold: a hold that neither settles nor runs away by then is undecided",
     .flag = "--hold-time",
     .on_compare = true},
    {.name = "kinetic_ratio",
     .member = &DemOptions::kinetic_ratio,
     .range = {0, 1, true},
     .help = "The support-speed servo's target: moves keep every block's kinetic energy below this x its weight x the support "
             "travel over the increment (dem/README.md, \"The loading rate\")",
     .flag = "--kinetic-ratio",
     .on_compare = true},
    {.name = "move_time",
     .member = &DemOptions::move_time,
     .unit = "s",
     .range = {0, kMaxModelTime},
     .note = "0: the support speed servoed on the kinetic energy",
     .help = "A move at constant speed over this model time per increment, instead of the servo",
     .flag = "--move-time",
     .on_compare = true},
    {.name = "ramp_fraction",
     .member = &DemOptions::ramp_fraction,
     .range = {0, 0.5},
     .note = "0: the paper's abrupt constant velocity",
     .help = "With move_time: the fraction of the move spent speeding up (and slowing down)",
     .flag = "--ramp-fraction"},
    {.name = "collapse_drift",
     .member = &DemOptions::collapse_drift,
     .unit = "m",
     .range = {0, kMaxLength},
     .note = "0: 2% of the scene size",
     .scene = {1e-4, 1, "a smaller drift is the elastic settling"},
     .help = "Block travel within a hold that does not settle that means collapse",
     .flag = "--collapse-drift"},
    {.name = "bracket_fraction",
     .member = &DemOptions::bracket_fraction,
     .range = {0, 1, false, true},
     .note = "of the step; 0: no bisection, the capacity is the last settled increment",
     .help = "A failed increment is bisected down to this fraction of the step",
     .flag = "--bracket-fraction"},
    {.name = "kn",
     .member = &DemOptions::kn,
     .unit = "Pa/m",
     .range = {0, kMaxJointStiffness, true},
     .absent = "E / h_block, h_block = sqrt(mean free block area)",
     .help = "Normal stiffness of the joints"},
    {.name = "ks",
     .member = &DemOptions::ks,
     .unit = "Pa/m",
     .range = {0, kMaxJointStiffness, true},
     .absent = "G / h_block, G = E / (2 (1 + nu))",
     .help = "Shear stiffness of the joints"},
    {.name = "open_gap",
     .member = &DemOptions::open_gap,
     .unit = "m",
     .range = {0, kMaxLength},
     .absent = "prd.contact_tolerance, so both methods call hinges alike",
     .help = "Gap growth since the settled start above which a joint corner is open",
     .flag = "--open-gap"},
    {.name = "confirm_collapse",
     .member = &DemOptions::confirm_collapse,
     .note = "--confirm-collapse=false turns it off (with a space, false is taken for another argument and refused)",
     .help = "Confirm a located collapse by the short move from the bracket's last equilibrium; a failure it does not "
             "reproduce becomes an equilibrium and the run goes on (dem/README.md, \"Protocol\", stage 4)",
     .flag = "--confirm-collapse",
     .on_compare = true,
     .in_case = Shown::when_set},
    {.name = "hold_damping",
     .member = &DemOptions::hold_damping,
     .words = kHoldDampingNames,
     .help = "How holds come to rest: local damping alone, or kinetic (also every free block stopped whenever the kinetic "
             "energy passes a peak; dem/README.md, \"Holds: local or kinetic damping\")",
     .flag = "--hold-damping",
     .in_case = Shown::when_set},
};

// "1e-5", "0.25", "3e10": a number as people write it, for help texts and the README: the
// fewest digits that give it back, an exponent from 1e4 up and below 1e-3.
std::string short_num(double x) {
  const double a = std::abs(x);
  const bool exponent = a >= 1e4 || (a > 0 && a < 1e-3);
  char b[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(b, sizeof b, exponent ? "%.*e" : "%.*g", exponent ? digits - 1 : digits, x);
    if (std::strtod(b, nullptr) == x && (exponent || !std::strchr(b, 'e'))) break;
  }
  std::string s = b;
  const size_t e = s.find('e');
  if (e == std::string::npos) return s;
  // "3e+10" -> "3e10", "1e-05" -> "1e-5"
  std::string exp = s.substr(e + 1);
  const bool neg = exp[0] == '-';
  exp = exp.substr(1);
  while (exp.size() > 1 && exp[0] == '0') exp.erase(0, 1);
  return s.substr(0, e) + "e" + (neg ? "-" : "") + exp;
}

// A bound as the refusals write it: as a stream writes a double (1e+05), a count in full.
std::string bound_text(double x, bool integer) {
  std::ostringstream o;
  if (integer)
    o << static_cast<long long>(x);
  else
    o << x;
  return o.str();
}

std::string interval_text(const Interval& r, bool integer, std::string (*num)(double, bool)) {
  return (r.lo_open ? "(" : "[") + num(r.lo, integer) + ", " + num(r.hi, integer) + (r.hi_open ? ")" : "]");
}

// The struct's own defaults, the options' defaults.
template <class S>
const S& defaults() {
  static const S s{};
  return s;
}

template <class S>
OptionType type_of(const Option<S>& o) {
  return std::visit(
      [](auto p) {
        using T = std::remove_cvref_t<decltype(std::declval<S>().*p)>;
        if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>)
          return OptionType::number;
        else if constexpr (std::is_same_v<T, int>)
          return OptionType::integer;
        else if constexpr (std::is_same_v<T, bool>)
          return OptionType::boolean;
        else if constexpr (std::is_same_v<T, HoldDamping>)
          return OptionType::word;
        else
          return OptionType::words;
      },
      o.member);
}

template <class S>
std::string where_of(const OptionSection<S>& sec) {
  return *sec.name ? sec.name : "case";
}

using Reader = FieldReader<CaseError, json>;

// "field 'X' = V is outside [lo, hi] UNIT (NOTE)": the one refusal of a value out of its range.
template <class S>
void refuse_range(const Reader& r, const std::string& where, const Option<S>& o, const std::string& value, bool integer) {
  std::string m = "field '" + std::string(o.name) + "' = " + value + " is outside " + interval_text(o.range, integer, bound_text);
  if (*o.unit) m += std::string(" ") + o.unit;
  if (*o.note) m += std::string(" (") + o.note + ")";
  r.fail(where, m);
}

template <class S>
void check_range(const Reader& r, const std::string& where, const Option<S>& o, double x) {
  if (o.range.contains(x)) return;
  std::ostringstream v;
  v << x;
  refuse_range(r, where, o, v.str(), false);
}

template <class S>
void read_one(const Reader& r, const std::string& where, const json& v, const Option<S>& o, S& s) {
  const std::string f = o.name;
  std::visit(
      [&](auto p) {
        using T = std::remove_cvref_t<decltype(s.*p)>;
        if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>) {
          s.*p = r.number(v, where, f);
        } else if constexpr (std::is_same_v<T, int>) {
          if (!v.is_number_integer()) r.fail(where, "field '" + f + "' must be a whole number");
          // The range on the JSON value itself: a count beyond an int is refused, not wrapped.
          const bool in = v.is_number_unsigned() ? v.template get<unsigned long long>() <= o.range.hi
                                                 : o.range.contains(static_cast<double>(v.template get<long long>()));
          if (!in) refuse_range(r, where, o, v.dump(), true);
          s.*p = v.template get<int>();
        } else if constexpr (std::is_same_v<T, bool>) {
          if (!v.is_boolean()) r.fail(where, "field '" + f + "' must be true or false");
          s.*p = v.template get<bool>();
        } else if constexpr (std::is_same_v<T, HoldDamping>) {
          if (!v.is_string()) r.fail(where, "field '" + f + "' must be a string");
          const std::string w = v.template get<std::string>();
          std::string choices;
          for (size_t k = 0; k < o.words.size(); ++k) {
            if (w == o.words[k]) {
              s.*p = static_cast<T>(k);
              return;
            }
            choices += std::string(k == 0 ? "" : k + 1 == o.words.size() ? " or " : ", ") + "\"" + o.words[k] + "\"";
          }
          r.fail(where, "field '" + f + "' must be " + choices + ", not \"" + printable(w) + "\"");
        } else {
          if (!v.is_array()) r.fail(where, "field '" + f + "' must be a list, each " + o.note);
          T list;
          for (const json& x : v) {
            const std::string w = x.is_string() ? x.template get<std::string>() : std::string();
            if (!x.is_string() || (o.word_ok && !o.word_ok(w)))
              r.fail(where, "field '" + f + "': '" + printable(x.is_string() ? w : x.dump()) + "' is not " + o.note);
            list.push_back(w);
          }
          s.*p = std::move(list);
        }
      },
      o.member);
}

template <class S>
void check_one(const Reader& r, const std::string& where, const Option<S>& o, const S& s) {
  std::visit(
      [&](auto p) {
        using T = std::remove_cvref_t<decltype(s.*p)>;
        if constexpr (std::is_same_v<T, double>)
          check_range(r, where, o, s.*p);
        else if constexpr (std::is_same_v<T, std::optional<double>>) {
          if (s.*p) check_range(r, where, o, *(s.*p));
        }
      },
      o.member);
}

// Whether a writer gives the option under rule `rule`.
template <class S>
bool shown(const Option<S>& o, const S& s, Shown rule) {
  return std::visit(
      [&](auto p) {
        using T = std::remove_cvref_t<decltype(s.*p)>;
        if constexpr (std::is_same_v<T, std::optional<double>>)
          return (s.*p).has_value();
        else if constexpr (std::is_same_v<T, std::vector<std::string>>)
          return rule == Shown::always || !(s.*p).empty();
        else
          return rule == Shown::always || !(s.*p == defaults<S>().*p);
      },
      o.member);
}

template <class S, class Json>
void put(Json& obj, const Option<S>& o, const S& s) {
  std::visit(
      [&](auto p) {
        using T = std::remove_cvref_t<decltype(s.*p)>;
        if constexpr (std::is_same_v<T, std::optional<double>>)
          obj[o.name] = *(s.*p);
        else if constexpr (std::is_same_v<T, HoldDamping>)
          obj[o.name] = o.words[static_cast<size_t>(s.*p)];
        else
          obj[o.name] = s.*p;
      },
      o.member);
}

template <class S>
std::string default_text(const Option<S>& o) {
  const S& s = defaults<S>();
  return std::visit(
      [&](auto p) -> std::string {
        using T = std::remove_cvref_t<decltype(s.*p)>;
        if constexpr (std::is_same_v<T, double>)
          return short_num(s.*p);
        else if constexpr (std::is_same_v<T, int>)
          return std::to_string(s.*p);
        else if constexpr (std::is_same_v<T, bool>)
          return s.*p ? "true" : "false";
        else if constexpr (std::is_same_v<T, HoldDamping>)
          return o.words[static_cast<size_t>(s.*p)];
        else if constexpr (std::is_same_v<T, std::optional<double>>)
          return s.*p ? short_num(*(s.*p)) : std::string("absent: ") + o.absent;
        else
          return (s.*p).empty() ? "none" : "";
      },
      o.member);
}

template <class S>
std::string range_text(const Option<S>& o) {
  std::string t;
  switch (type_of(o)) {
    case OptionType::number:
    case OptionType::integer: t = interval_text(o.range, false, [](double x, bool) { return short_num(x); }); break;
    case OptionType::boolean: return "true, false";
    case OptionType::word:
      for (size_t k = 0; k < o.words.size(); ++k) t += std::string(k ? ", " : "") + o.words[k];
      return t;
    case OptionType::words: return std::string("each ") + o.note;
  }
  if (o.scene.hi > 0)
    t += "; " + std::string(o.range.lo == 0 && !o.range.lo_open ? "0 or " : "") + short_num(o.scene.lo) + " to " + short_num(o.scene.hi) +
         " x the scene size";
  return t;
}

template <class S>
void add_infos(std::vector<OptionInfo>& out, std::initializer_list<OptionCommand> commands) {
  const OptionSection<S>& sec = options<S>();
  for (const Option<S>& o : sec.rows) {
    OptionInfo i;
    i.section = sec.name;
    i.key = (*sec.name ? i.section + "." : std::string()) + o.name;
    i.type = type_of(o);
    i.default_text = default_text(o);
    i.range_text = range_text(o);
    i.unit = o.unit;
    i.note = type_of(o) == OptionType::words ? "" : o.note;
    i.help = o.help;
    i.flag = o.flag;
    if (*o.flag) {
      i.commands = commands;
      if (o.on_compare) i.commands.push_back(OptionCommand::compare);
    }
    out.push_back(std::move(i));
  }
}

}  // namespace

template <>
const OptionSection<Case>& options<Case>() {
  static const OptionSection<Case> s{"", kCaseRows};
  return s;
}
template <>
const OptionSection<Motion>& options<Motion>() {
  static const OptionSection<Motion> s{"motion", kMotionRows};
  return s;
}
template <>
const OptionSection<PrdOptions>& options<PrdOptions>() {
  static const OptionSection<PrdOptions> s{"prd", kPrdRows};
  return s;
}
template <>
const OptionSection<DemOptions>& options<DemOptions>() {
  static const OptionSection<DemOptions> s{"dem", kDemRows};
  return s;
}

const char* option_type_name(OptionType t) {
  switch (t) {
    case OptionType::number: return "number";
    case OptionType::integer: return "integer";
    case OptionType::boolean: return "true/false";
    case OptionType::word: return "word";
    case OptionType::words: return "list of words";
  }
  return "?";
}

template <class S>
void read_options(const json& obj, S& s, const std::string& source, std::initializer_list<const char*> others) {
  const OptionSection<S>& sec = options<S>();
  const Reader r{source};
  const std::string where = where_of(sec);
  if (!obj.is_object()) r.fail(where, "must be a JSON object");
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool known = false;
    for (const Option<S>& o : sec.rows) known = known || it.key() == o.name;
    for (const char* k : others) known = known || it.key() == k;
    if (!known) r.fail(where, "unknown field '" + printable(it.key()) + "'");
  }
  for (const Option<S>& o : sec.rows) {
    const auto it = obj.find(o.name);
    if (it == obj.end()) continue;
    read_one(r, where, *it, o, s);
    check_one(r, where, o, s);
  }
}

template <class S>
void check_options(const S& s, const std::string& source, bool allow_unstable_timestep) {
  const OptionSection<S>& sec = options<S>();
  const Reader r{source};
  for (const Option<S>& o : sec.rows) {
    if constexpr (std::is_same_v<S, DemOptions>) {
      // Above 1 the explicit integration is unstable (dem/README.md): refused for every command,
      // the DEM's tests of a blow-up alone may ask for it.
      if (allow_unstable_timestep && o.member == typename Option<S>::Member(&DemOptions::timestep_factor) && s.timestep_factor > 1 &&
          std::isfinite(s.timestep_factor))
        continue;
    }
    check_one(r, where_of(sec), o, s);
  }
}

template <class S>
void check_scene_options(const S& s, double L, const std::string& source) {
  const OptionSection<S>& sec = options<S>();
  const Reader r{source};
  for (const Option<S>& o : sec.rows) {
    const auto* p = std::get_if<double S::*>(&o.member);
    if (!p || !(o.scene.hi > 0)) continue;
    const double x = s.**p, lo = o.scene.lo * L, hi = o.scene.hi * L;
    if (!(x > 0) || (x >= lo && x <= hi)) continue;
    std::ostringstream m;
    m << "field '" << o.name << "' = " << x << " " << o.unit << " is outside [" << lo << ", " << hi << "] " << o.unit << " for a scene of " << L
      << " m (" << short_num(o.scene.lo) << " to " << short_num(o.scene.hi) << " times the scene size"
      << (*o.scene.why ? std::string(": ") + o.scene.why : std::string()) << ")";
    r.fail(where_of(sec), m.str());
  }
}

template <class S>
void write_options(ordered_json& obj, const S& s) {
  for (const Option<S>& o : options<S>().rows)
    if (shown(o, s, o.in_case)) put(obj, o, s);
}

template <class S>
ordered_json valued_options(const S& s) {
  ordered_json obj = ordered_json::object();
  for (const Option<S>& o : options<S>().rows)
    if (shown(o, s, Shown::always)) put(obj, o, s);
  return obj;
}

#define MASONRY_OPTION_SECTION(S)                                                                         \
  template void read_options<S>(const json&, S&, const std::string&, std::initializer_list<const char*>); \
  template void check_options<S>(const S&, const std::string&, bool);                                     \
  template void check_scene_options<S>(const S&, double, const std::string&);                             \
  template void write_options<S>(ordered_json&, const S&);                                                \
  template ordered_json valued_options<S>(const S&);
MASONRY_OPTION_SECTION(Case)
MASONRY_OPTION_SECTION(Motion)
MASONRY_OPTION_SECTION(PrdOptions)
MASONRY_OPTION_SECTION(DemOptions)
#undef MASONRY_OPTION_SECTION

std::vector<OptionInfo> option_infos() {
  std::vector<OptionInfo> out;
  add_infos<Case>(out, {});
  add_infos<Motion>(out, {OptionCommand::prd, OptionCommand::dem});
  add_infos<PrdOptions>(out, {OptionCommand::prd});
  add_infos<DemOptions>(out, {OptionCommand::dem});
  return out;
}

const char* option_command_name(OptionCommand c) {
  switch (c) {
    case OptionCommand::prd: return "prd";
    case OptionCommand::dem: return "dem";
    case OptionCommand::compare: return "compare";
  }
  return "?";
}

std::vector<std::string> idle_options(const PrdOptions& p) {
  std::vector<std::string> out;
  const auto idle = [&](const std::string& key, const char* flag) {
    out.push_back(key + " (" + flag + ") has no effect without prd.adaptive (--adaptive): the steps are fixed");
  };
  if (!p.adaptive && p.event_tolerance != PrdOptions{}.event_tolerance) idle(option_key(&PrdOptions::event_tolerance), "--event-tolerance");
  if (!p.adaptive && p.max_step != PrdOptions{}.max_step) idle(option_key(&PrdOptions::max_step), "--max-step");
  return out;
}

std::vector<std::string> idle_options(const DemOptions& d) {
  std::vector<std::string> out;
  if (d.move_time == 0 && d.ramp_fraction != DemOptions{}.ramp_fraction)
    out.push_back(option_key(&DemOptions::ramp_fraction) +
                  " (--ramp-fraction) has no effect without dem.move_time (--move-time): the servo paces the moves");
  return out;
}

std::string options_markdown() {
  std::ostringstream md;
  md << "| key | type | default | range | unit | flag | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const OptionInfo& i : option_infos()) {
    std::string flag = "-";
    if (*i.flag) {
      flag = std::string("`") + i.flag + "` (";
      for (size_t k = 0; k < i.commands.size(); ++k) flag += std::string(k ? ", " : "") + option_command_name(i.commands[k]);
      flag += ")";
    }
    md << "| `" << i.key << "` | " << option_type_name(i.type) << " | " << (i.default_text.empty() ? "-" : i.default_text) << " | " << i.range_text
       << (*i.note ? std::string(" (") + i.note + ")" : "") << " | " << (*i.unit ? i.unit : "-") << " | " << flag << " | " << i.help << " |\n";
  }
  return md.str();
}

}  // namespace masonry
