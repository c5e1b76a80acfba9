// The sweep file (masonry-sweep/1) and the plan of runs it makes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "cases/generators.hpp"
#include "cases/parameters.hpp"
#include "model/fields.hpp"
#include "model/io.hpp"
#include "model/options.hpp"
#include "sweep/runner.hpp"

namespace masonry {

using ojson = nlohmann::ordered_json;
using nlohmann::json;

namespace {

constexpr size_t kMaxValues = 10000;  // per key
constexpr size_t kMaxRuns = 100000;   // per sweep: beyond this the table is no longer a table

// The sweep format's reader: the harness's strict field checks (model/fields.hpp).
using SpecReader = FieldReader<SweepError, ojson>;

// Generated values are rounded to 15 significant digits, so a range from 0.1 by 0.1 gives 0.3
// and not 0.30000000000000004: the table shows what a person would have typed.
double tidy(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.15g", x);
  return std::strtod(b, nullptr);
}

SweepAxis parse_axis(const SpecReader& r, const std::string& key, const ojson& v) {
  const std::string where = "vary '" + key + "'";
  SweepAxis a;
  a.key = key;
  if (key.empty()) r.fail("vary", "an option name is empty");
  if (v.is_array()) {
    if (v.empty()) r.fail(where, "the list of values is empty");
    if (v.size() > kMaxValues) r.fail(where, "more than " + std::to_string(kMaxValues) + " values");
    for (const ojson& x : v) {
      if (x.is_number()) {
        r.number(x, where, "values");
      } else if (!x.is_string() && !x.is_boolean()) {
        r.fail(where, "values must be numbers, strings or booleans, got " + x.dump());
      }
      const json value = json::parse(x.dump());
      for (const json& seen : a.values)
        if (seen == value) r.fail(where, "value " + x.dump() + " is listed twice");
      a.values.push_back(value);
    }
    return a;
  }
  if (!v.is_object()) r.fail(where, "must be a list of values or a range {\"from\", \"to\", \"step\" or \"count\"}");
  for (auto it = v.begin(); it != v.end(); ++it)
    if (it.key() != "from" && it.key() != "to" && it.key() != "step" && it.key() != "count")
      r.fail(where, "unknown field '" + it.key() + "' (a range has from, to, and step or count)");
  if (!v.contains("from") || !v.contains("to")) r.fail(where, "a range needs 'from' and 'to'");
  if (v.contains("step") == v.contains("count")) r.fail(where, "a range needs either 'step' or 'count'");
  const double from = r.number(v["from"], where, "from"), to = r.number(v["to"], where, "to");
  if (to < from) r.fail(where, "field 'to' must be >= 'from'");
  if (v.contains("step")) {
    const double step = r.number(v["step"], where, "step");
    if (!(step > 0)) r.fail(where, "field 'step' must be positive");
    // A hair of slack so that 0.1 to 0.3 by 0.1 includes 0.3 despite round-off.
    const double n = std::floor((to - from) / step * (1 + 1e-12) + 1e-9) + 1;
    if (n > double(kMaxValues)) r.fail(where, "more than " + std::to_string(kMaxValues) + " values");
    // Integers stay integers, so an integer option (motion.max_steps) can be a range too.
    const bool integers = v["from"].is_number_integer() && v["to"].is_number_integer() && v["step"].is_number_integer();
    for (long k = 0; k < long(n); ++k) {
      if (integers)
        a.values.push_back(v["from"].get<long long>() + k * v["step"].get<long long>());
      else
        a.values.push_back(tidy(from + double(k) * step));
    }
  } else {
    if (!v["count"].is_number_integer() || v["count"].get<long long>() < 1) r.fail(where, "field 'count' must be a positive integer");
    const long long n = v["count"].get<long long>();
    if (n > static_cast<long long>(kMaxValues)) r.fail(where, "more than " + std::to_string(kMaxValues) + " values");
    if (n == 1 && to != from) r.fail(where, "field 'count' is 1 but 'to' differs from 'from'");
    for (long long k = 0; k < n; ++k) a.values.push_back(k + 1 == n ? to : tidy(from + (to - from) * double(k) / double(n - 1)));
  }
  for (size_t i = 1; i < a.values.size(); ++i)
    if (a.values[i] == a.values[i - 1]) r.fail(where, "the range repeats a value (step below the numbers' precision)");
  return a;
}

std::string hex16(uint64_t h) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

// "case": a file or standard case name (a string), or a generator call
// {"generator": NAME, "parameters": {...}}.
void parse_case_field(const SpecReader& r, const ojson& doc, SweepSpec& s) {
  if (!doc.contains("case"))
    r.fail("sweep", "field 'case' must name a case file (*.json), a standard case or a generator call {\"generator\": NAME, \"parameters\": {...}}");
  const ojson& c = doc["case"];
  if (c.is_string()) {
    s.case_ref = c.get<std::string>();
    if (s.case_ref.empty()) r.fail("sweep", "field 'case' must name a case file (*.json) or a standard case");
    return;
  }
  if (!c.is_object())
    r.fail("sweep", "field 'case' must be a case file (*.json), a standard case or a generator call {\"generator\": NAME, \"parameters\": {...}}");
  r.only(c, "case", {"generator", "parameters"});
  s.generator = r.string(c, "case", "generator", "");
  if (s.generator.empty()) r.fail("case", "field 'generator' must name a case generator (masonry cases --list)");
  if (!find_case_generator(s.generator))
    r.fail("case", "field 'generator': no case generator '" + printable(s.generator) + "' (masonry cases --list)");
  if (c.contains("parameters")) {
    if (!c["parameters"].is_object()) r.fail("case", "field 'parameters' must be an object {NAME: value} (masonry cases " + s.generator + " --help)");
    s.parameters = json::parse(c["parameters"].dump());
  }
}

// "sample": {"count": N, "seed": S, "ranges": {KEY: [lo, hi], ...}, "one_at_a_time": L, "only": [...]}.
SweepSample parse_sample(const SpecReader& r, const ojson& v) {
  r.only(v, "sample", {"count", "seed", "ranges", "one_at_a_time", "only"});
  SweepSample s;
  // A whole number in [lo, hi]; absent: `dflt`, or refused when dflt < 0 (required).
  const auto whole = [&](const char* field, long long lo, long long hi, long long dflt) {
    if (!v.contains(field)) {
      if (dflt < 0) r.fail("sample", std::string("field '") + field + "' is required");
      return dflt;
    }
    const ojson& x = v[field];
    // A number beyond long long's range (unsigned, or a float) is out of range too.
    const bool ok = x.is_number_integer() && !(x.is_number_unsigned() && x.get<unsigned long long>() > 9223372036854775807ull) &&
                    x.get<long long>() >= lo && x.get<long long>() <= hi;
    if (!ok) r.fail("sample", std::string("field '") + field + "' must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return x.get<long long>();
  };
  s.count = static_cast<int>(whole("count", 1, static_cast<long long>(kMaxRuns), -1));
  s.seed = static_cast<unsigned long long>(whole("seed", 0, 9007199254740991LL, -1));  // 2^53 - 1: exact in any JSON reader
  s.levels = static_cast<int>(whole("one_at_a_time", 0, 1000, 3));
  if (s.levels == 1) r.fail("sample", "field 'one_at_a_time' must be 0 (none) or at least 2 (both ends of each range)");
  if (!v.contains("ranges") || !v["ranges"].is_object() || v["ranges"].empty())
    r.fail("sample", "field 'ranges' must be an object of options and their ranges, e.g. {\"generator.thickness\": [0.1, 0.2]}");
  for (auto it = v["ranges"].begin(); it != v["ranges"].end(); ++it) {
    const std::string where = "sample range '" + it.key() + "'";
    if (it.key().empty()) r.fail("sample", "an option name is empty");
    if (!it.value().is_array() || it.value().size() != 2) r.fail(where, "must be [lo, hi]");
    SweepRange g{it.key(), r.number(it.value()[0], where, "lo"), r.number(it.value()[1], where, "hi")};
    if (!(g.hi > g.lo)) r.fail(where, "hi must be above lo (an option with one value belongs in 'set')");
    s.ranges.push_back(g);
  }
  if (v.contains("only")) {
    if (!v["only"].is_array() || v["only"].empty()) r.fail("sample", "field 'only' must be a non-empty list of sample numbers");
    for (const ojson& x : v["only"]) {
      if (!x.is_number_integer() || x.get<long long>() < 0 || x.get<long long>() >= s.count)
        r.fail("sample", "field 'only': " + x.dump() + " is not a sample number (0 to count - 1)");
      s.only.push_back(x.get<int>());
    }
    std::sort(s.only.begin(), s.only.end());
    if (std::adjacent_find(s.only.begin(), s.only.end()) != s.only.end()) r.fail("sample", "field 'only' lists a sample twice");
  }
  return s;
}

}  // namespace

namespace sweep_detail {

bool is_dem_option(const std::string& key) { return key.rfind("dem.", 0) == 0; }

uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace sweep_detail

using sweep_detail::fnv1a;
using sweep_detail::is_dem_option;

std::string value_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

SweepSpec parse_sweep(const std::string& text, const std::string& source) {
  ojson doc = parse_document<SweepError, ojson>(text, source);
  const SpecReader r{source};
  if (!doc.is_object()) r.fail("sweep", "must be a JSON object");
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    static const std::set<std::string> known{"format", "name", "description", "case", "methods", "vary", "sample", "set", "tolerance"};
    if (!known.count(it.key())) r.fail("sweep", "unknown field '" + it.key() + "'");
  }
  SweepSpec s;
  s.source = source;
  if (!doc.contains("format")) r.fail("sweep", "field 'format' is required (\"masonry-sweep/1\")");
  const std::string format = r.string(doc, "sweep", "format", "");
  if (format != "masonry-sweep/1") r.fail("sweep", "field 'format': expected \"masonry-sweep/1\", got \"" + format + "\"");
  s.name = r.string(doc, "sweep", "name", "");
  s.description = r.string(doc, "sweep", "description", "");
  parse_case_field(r, doc, s);
  if (doc.contains("methods")) {
    const ojson& m = doc["methods"];
    if (!m.is_array() || m.empty()) r.fail("sweep", "field 'methods' must be a non-empty list of \"prd\", \"dem\"");
    for (const ojson& x : m) {
      const std::optional<Method> method = x.is_string() ? parse_method(x.get<std::string>()) : std::nullopt;
      if (!method) r.fail("sweep", "field 'methods': " + x.dump() + " is not \"prd\" or \"dem\"");
      if (std::find(s.methods.begin(), s.methods.end(), *method) != s.methods.end())
        r.fail("sweep", "field 'methods': " + x.dump() + " is listed twice");
      s.methods.push_back(*method);
    }
  } else {
    s.methods = {Method::prd, Method::dem};
  }
  if (doc.contains("sample")) {
    if (doc.contains("vary")) r.fail("sweep", "a sweep has 'vary' (a grid) or 'sample' (a Latin hypercube), not both");
    s.sample = parse_sample(r, doc["sample"]);
  } else {
    if (!doc.contains("vary") || !doc["vary"].is_object() || doc["vary"].empty())
      r.fail("sweep", "field 'vary' must be an object of options to vary, e.g. {\"dem.friction_angle\": [20, 30]} (or give 'sample')");
    for (auto it = doc["vary"].begin(); it != doc["vary"].end(); ++it) s.vary.push_back(parse_axis(r, it.key(), it.value()));
  }
  if (doc.contains("set")) {
    if (!doc["set"].is_object()) r.fail("sweep", "field 'set' must be an object of options, e.g. {\"dem.hold_time\": 1}");
    for (auto it = doc["set"].begin(); it != doc["set"].end(); ++it) {
      for (const SweepAxis& a : s.vary)
        if (a.key == it.key()) r.fail("set '" + it.key() + "'", "the option is also in 'vary'");
      if (s.sample)
        for (const SweepRange& g : s.sample->ranges)
          if (g.key == it.key()) r.fail("set '" + it.key() + "'", "the option is also in 'sample'");
      s.set.emplace_back(it.key(), json::parse(it.value().dump()));
    }
  }
  if (doc.contains("tolerance")) {
    s.tolerance = r.number(doc["tolerance"], "sweep", "tolerance");
    if (!(s.tolerance > 0)) r.fail("sweep", "field 'tolerance' must be positive (a relative capacity difference, 0.05 = 5%)");
  }
  return s;
}

SweepInput read_sweep_input(const std::string& spec_path) {
  const auto slurp = [](const std::string& path, std::string& out) {
    std::optional<std::string> text = read_text(path);
    if (!text) return false;
    out = std::move(*text);
    return true;
  };
  SweepInput in;
  in.spec_source = spec_path;
  if (!slurp(spec_path, in.spec_text)) throw SweepError(spec_path + ": cannot open the sweep file");
  const SweepSpec s = parse_sweep(in.spec_text, spec_path);
  if (!s.generator.empty()) {
    in.case_source = "generator " + s.generator;  // the spec holds the call
    return in;
  }
  const std::string& ref = s.case_ref;
  if (ref.size() > 5 && ref.compare(ref.size() - 5, 5, ".json") == 0) {
    const std::filesystem::path p(ref);
    in.case_source = (p.is_absolute() ? p : std::filesystem::path(spec_path).parent_path() / p).lexically_normal().generic_string();
    if (!slurp(in.case_source, in.case_text))
      throw SweepError(spec_path + ": sweep: field 'case': cannot open " + in.case_source + " (paths are relative to the sweep file)");
  } else {
    try {
      in.case_text = case_to_json(standard_case(ref));
    } catch (const std::exception& e) {
      throw SweepError(spec_path + ": sweep: field 'case': '" + ref + "' is neither a *.json file nor a standard case (" + e.what() + ")");
    }
    in.case_source = ref;
  }
  return in;
}

namespace {

bool is_generator_key(const std::string& key) { return key.rfind(kGeneratorPrefix, 0) == 0; }
std::string parameter_of(const std::string& key) { return key.substr(std::char_traits<char>::length(kGeneratorPrefix)); }

// The generator parameter a "generator.NAME" key names; refuses the key (naming `where`) when
// the case is no generator call or the generator has no such parameter.
const GeneratorParameter& generator_parameter(const SpecReader& r, const std::string& where, const std::string& generator, const std::string& key) {
  if (generator.empty()) r.fail(where, "'" + key + "' is a generator parameter, but the case is not a generator call {\"generator\": NAME, ...}");
  const CaseGenerator& g = *find_case_generator(generator);
  const int k = parameter_index(g, parameter_of(key));
  if (k < 0) r.fail(where, "generator " + generator + " has no parameter '" + printable(parameter_of(key)) + "' (it has " + parameter_names(g) + ")");
  return g.parameters[k];
}

// The generator's parameters for the base case: the call's, then "set"'s generator.NAME.
json base_parameters(const SweepSpec& spec) {
  json params = spec.parameters;
  for (const auto& [key, value] : spec.set)
    if (is_generator_key(key)) params[parameter_of(key)] = value;
  return params;
}

// A case option's value in case c (its dotted path in the case file), null when the file has none.
json option_in(const Case& c, const std::string& key) {
  const json doc = json::parse(case_to_json(c));
  const json* at = &doc;
  for (size_t start = 0;;) {
    const size_t dot = key.find('.', start);
    const std::string name = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!at->is_object() || !at->contains(name)) return nullptr;
    at = &(*at)[name];
    if (dot == std::string::npos) return *at;
    start = dot + 1;
  }
}

// Sampled values are rounded to 6 significant digits: a table a person reads, and a value the
// sample's stratum still holds (strata are wider than 1e-6 of a range below a million samples).
double tidy6(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.6g", x);
  return std::strtod(b, nullptr);
}

// One point of the design before it becomes runs.
struct DesignPoint {
  std::vector<json> values;
  SweepPoint point = SweepPoint::grid;
  int sample = -1, line = -1;
};

// The full factorial over spec.vary, last key fastest.
std::vector<DesignPoint> grid_points(const SpecReader& r, const SweepSpec& spec) {
  double total = 1;
  for (const SweepAxis& a : spec.vary) total *= double(a.values.size());
  if (total > double(kMaxRuns)) r.fail("vary", "the grid has more than " + std::to_string(kMaxRuns) + " combinations");
  std::vector<DesignPoint> out;
  std::vector<size_t> at(spec.vary.size(), 0);
  for (size_t n = 0; n < size_t(total); ++n) {
    DesignPoint d;
    for (size_t k = 0; k < at.size(); ++k) d.values.push_back(spec.vary[k].values[at[k]]);
    out.push_back(std::move(d));
    for (size_t k = at.size(); k-- > 0;) {
      if (++at[k] < spec.vary[k].values.size()) break;
      at[k] = 0;
    }
  }
  return out;
}

// The sampled design: the base point, each range's one-at-a-time line, the Latin hypercube.
std::vector<DesignPoint> sampled_points(const SpecReader& r, const SweepSample& s, const std::vector<json>& base, const std::vector<bool>& integer) {
  const size_t nk = s.ranges.size();
  // x in [0, 1] to a value of key k: whole numbers for an integer parameter, each equally likely.
  const auto value = [&](size_t k, double u) -> json {
    const SweepRange& g = s.ranges[k];
    if (integer[k]) {
      const long long lo = static_cast<long long>(std::ceil(g.lo)), hi = static_cast<long long>(std::floor(g.hi));
      return lo + std::min(static_cast<long long>(std::floor(u * double(hi - lo + 1))), hi - lo);
    }
    return tidy6(g.lo + (g.hi - g.lo) * u);
  };
  for (size_t k = 0; k < nk; ++k)
    if (integer[k] && std::ceil(s.ranges[k].lo) > std::floor(s.ranges[k].hi))
      r.fail("sample range '" + s.ranges[k].key + "'", "holds no whole number (the parameter is an integer)");
  const double lines = double(nk) * s.levels;
  const double samples = s.only.empty() ? s.count : double(s.only.size());
  if (1 + lines + samples > double(kMaxRuns)) r.fail("sample", "the design has more than " + std::to_string(kMaxRuns) + " points");
  std::vector<DesignPoint> out;
  if (s.levels > 0) {
    out.push_back({base, SweepPoint::base, -1, -1});
    for (size_t k = 0; k < nk; ++k)
      for (int l = 0; l < s.levels; ++l) {
        DesignPoint d{base, SweepPoint::one_at_a_time, -1, static_cast<int>(k)};
        d.values[k] = l + 1 == s.levels ? value(k, 1.0) : value(k, double(l) / (s.levels - 1));
        if (integer[k] && l + 1 == s.levels) d.values[k] = static_cast<long long>(std::floor(s.ranges[k].hi));
        out.push_back(std::move(d));
      }
  }
  std::vector<std::string> names;
  for (const SweepRange& g : s.ranges) names.push_back(g.key);
  const std::vector<std::vector<double>> u = latin_hypercube(s.count, names, s.seed);
  std::vector<int> chosen = s.only;
  if (chosen.empty())
    for (int i = 0; i < s.count; ++i) chosen.push_back(i);
  for (int i : chosen) {
    DesignPoint d{std::vector<json>(nk), SweepPoint::sample, i, -1};
    for (size_t k = 0; k < nk; ++k) d.values[k] = value(k, u[i][k]);
    out.push_back(std::move(d));
  }
  // A one-at-a-time point equal to another (the base value at a level, a repeated whole number)
  // is run once.
  std::vector<DesignPoint> unique;
  std::set<std::string> seen;
  for (DesignPoint& d : out)
    if (d.point == SweepPoint::sample || seen.insert(json(d.values).dump()).second) unique.push_back(std::move(d));
  return unique;
}

}  // namespace

SweepPlan plan_sweep(const SweepInput& in) {
  const SweepSpec s = parse_sweep(in.spec_text, in.spec_source);
  if (s.generator.empty()) return plan_sweep(s, parse_case(in.case_text, in.case_source));
  const SpecReader r{s.source};
  for (const auto& [key, value] : s.set)
    if (is_generator_key(key)) generator_parameter(r, "set '" + key + "'", s.generator, key);
  try {
    return plan_sweep(s, generate_case(s.generator, base_parameters(s)));
  } catch (const CaseError& e) {
    r.fail("case", e.what());
  }
}

SweepPlan plan_sweep(const SweepSpec& spec, const Case& c) {
  const SpecReader r{spec.source};
  SweepPlan p;
  p.source = spec.source;
  p.name = spec.name.empty() ? c.name : spec.name;
  p.description = spec.description;
  p.methods = spec.methods;
  p.tolerance = spec.tolerance;
  p.base = c;
  p.generator = spec.generator;
  p.parameters = base_parameters(spec);
  p.sample = spec.sample;
  for (const auto& [key, value] : spec.set) {
    if (is_generator_key(key)) {
      generator_parameter(r, "set '" + key + "'", p.generator, key);  // in the base case already
      continue;
    }
    try {
      p.base = with_option(p.base, key, value);
    } catch (const CaseError& e) {
      r.fail("set '" + key + "'", e.what());
    }
    p.options.emplace_back(key, value);
    if (key == option_key(&PrdOptions::sliding_check)) p.sliding_check = p.base.prd.sliding_check;
  }
  const std::string base_text = case_to_json(p.base);
  // Whether the case takes a value of a key: a generator builds its case, a case option loads.
  const auto probe = [&](const std::string& key, const json& value) {
    if (is_generator_key(key)) {
      json params = p.parameters;
      params[parameter_of(key)] = value;
      generate_case(p.generator, params);
    } else {
      with_option(p.base, key, value);
    }
  };
  std::vector<bool> integer;
  for (const SweepAxis& a : spec.vary) p.keys.push_back(a.key);
  if (spec.sample)
    for (const SweepRange& g : spec.sample->ranges) p.keys.push_back(g.key);
  for (const std::string& key : p.keys) {
    const std::string where = (spec.sample ? "sample range '" : "vary '") + key + "'";
    bool whole = false;
    if (is_generator_key(key)) {
      const GeneratorParameter& gp = generator_parameter(r, where, p.generator, key);
      if (spec.sample && gp.kind == ParameterKind::flag) r.fail(where, "a switch (true or false) cannot be sampled: vary it");
      whole = gp.kind == ParameterKind::integer;
      // The base point's value: the call's (checked as the generator checks it), else the default.
      double x = gp.value;
      try {
        if (p.parameters.contains(parameter_of(key))) x = parameter_value(*find_case_generator(p.generator), gp, p.parameters[parameter_of(key)]);
      } catch (const CaseError& e) {
        r.fail("case", e.what());
      }
      p.base_values.push_back(gp.kind == ParameterKind::integer ? json(static_cast<long long>(x))
                              : gp.kind == ParameterKind::flag  ? json(x != 0)
                                                                : json(x));
    } else {
      p.base_values.push_back(option_in(p.base, key));
    }
    integer.push_back(whole);
  }
  // A key that is no option of the case would fail every run: refuse it now, when the case takes
  // none of its values (the loader's or generator's message says why). A single refused value is
  // a failed run like any other. A sampled range is tried at its middle.
  for (size_t k = 0; k < p.keys.size(); ++k) {
    std::vector<json> tries;
    if (spec.sample) {
      const SweepRange& g = spec.sample->ranges[k];
      tries.push_back(integer[k] ? json(static_cast<long long>(std::floor((g.lo + g.hi) / 2))) : json(tidy6((g.lo + g.hi) / 2)));
    } else {
      tries = spec.vary[k].values;
    }
    std::string first_error;
    bool accepted = false;
    for (size_t v = 0; !accepted && v < tries.size(); ++v) {
      try {
        probe(p.keys[k], tries[v]);
        accepted = true;
      } catch (const CaseError& e) {
        if (first_error.empty()) first_error = e.what();
      }
    }
    if (!accepted)
      r.fail(std::string(spec.sample ? "sample range '" : "vary '") + p.keys[k] + "'",
             std::string(spec.sample ? "the case refuses the range's middle: " : "the case takes none of the values: ") + first_error);
  }
  const std::vector<DesignPoint> points = spec.sample ? sampled_points(r, *spec.sample, p.base_values, integer) : grid_points(r, spec);

  const auto has = [&](Method m) { return std::find(spec.methods.begin(), spec.methods.end(), m) != spec.methods.end(); };
  const auto add = [&](Method method, std::vector<json> values, const DesignPoint& d) {
    SweepRun run;
    run.index = static_cast<int>(p.runs.size());
    run.method = method;
    run.point = d.point;
    run.sample = d.sample;
    run.line = d.line;
    std::string idtext = base_text + "\n" + method_name(method) + "\n";
    for (size_t k = 0; k < p.keys.size(); ++k) idtext += p.keys[k] + "=" + (values[k].is_null() ? "-" : values[k].dump()) + "\n";
    if (d.point == SweepPoint::sample) idtext += "sample=" + std::to_string(d.sample) + "\n";
    run.id = hex16(fnv1a(idtext));
    run.values = std::move(values);
    p.runs.push_back(std::move(run));
    return p.runs.back().index;
  };
  // PRD runs first: they are quick, and every DEM row's difference needs its PRD row. A sample
  // has a PRD run of its own; other points share one per distinct non-DEM values.
  std::map<std::string, int> prd_of;  // non-DEM values (JSON text), or the sample -> PRD run
  const auto prd_key = [&](const DesignPoint& d) {
    if (d.point == SweepPoint::sample) return "sample " + std::to_string(d.sample);
    std::vector<json> out = d.values;
    for (size_t k = 0; k < out.size(); ++k)
      if (is_dem_option(p.keys[k])) out[k] = nullptr;
    return json(out).dump();
  };
  if (has(Method::prd))
    for (const DesignPoint& d : points) {
      const std::string key = prd_key(d);
      if (prd_of.count(key)) continue;
      std::vector<json> pv = d.values;
      for (size_t k = 0; k < pv.size(); ++k)
        if (is_dem_option(p.keys[k])) pv[k] = nullptr;
      prd_of[key] = add(Method::prd, pv, d);
    }
  if (has(Method::dem))
    for (const DesignPoint& d : points) {
      const int i = add(Method::dem, d.values, d);
      auto it = prd_of.find(prd_key(d));
      if (it != prd_of.end()) p.runs[i].prd = it->second;
    }
  if (!has(Method::dem))
    for (const std::string& key : p.keys)
      if (is_dem_option(key)) p.prd_ignores.push_back(key);
  std::string all = "masonry-sweep/1\n" + base_text;
  for (const SweepRun& run : p.runs) all += std::string(method_name(run.method)) + " " + run.id + "\n";
  p.hash = hex16(fnv1a(all));
  return p;
}

Case case_of_run(const SweepPlan& p, const SweepRun& r) {
  Case c = p.base;
  json params = p.parameters;
  bool generate = false;
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (is_generator_key(p.keys[k]) && !r.values[k].is_null()) {
      params[parameter_of(p.keys[k])] = r.values[k];
      generate = true;
    }
  if (generate) {
    c = generate_case(p.generator, params);
    for (const auto& [key, value] : p.options) c = with_option(c, key, value);
  }
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (!is_generator_key(p.keys[k]) && !r.values[k].is_null()) c = with_option(c, p.keys[k], r.values[k]);
  return c;
}

std::string point_text(const SweepRun& r) {
  switch (r.point) {
    case SweepPoint::grid: return "";
    case SweepPoint::base: return "base";
    case SweepPoint::one_at_a_time: return "one-at-a-time";
    case SweepPoint::sample: return std::to_string(r.sample);
  }
  return "";
}

std::string prd_ignores_note(const SweepPlan& p) {
  if (p.prd_ignores.empty()) return "";
  std::string keys;
  for (const std::string& k : p.prd_ignores) keys += (keys.empty() ? "" : ", ") + k;
  int prd = 0;
  for (const SweepRun& r : p.runs) prd += r.method == Method::prd;
  return "PRD ignores " + keys + " (DEM option" + (p.prd_ignores.size() > 1 ? "s" : "") + "): this PRD-only sweep runs " + std::to_string(prd) +
         " PRD run" + (prd == 1 ? "" : "s") + " whatever " + (p.prd_ignores.size() > 1 ? "their values" : "its value") +
         "; add \"dem\" to 'methods' to run the DEM over " + (p.prd_ignores.size() > 1 ? "them" : "it") + ".";
}

std::string run_label(const SweepPlan& p, const SweepRun& r) {
  std::string s;
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (!r.values[k].is_null()) s += (s.empty() ? "" : ", ") + p.keys[k] + "=" + value_text(r.values[k]);
  return s;
}

}  // namespace masonry
