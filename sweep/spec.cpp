// The sweep file (masonry-sweep/1) and the plan of runs it makes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "cases/generators.hpp"
#include "model/fields.hpp"
#include "model/io.hpp"
#include "sweep/sweep.hpp"

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

bool is_dem_option(const std::string& key) { return key.rfind("dem.", 0) == 0; }

uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex16(uint64_t h) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

}  // namespace

std::string value_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

SweepSpec parse_sweep(const std::string& text, const std::string& source) {
  ojson doc = parse_document<SweepError, ojson>(text, source);
  const SpecReader r{source};
  if (!doc.is_object()) r.fail("sweep", "must be a JSON object");
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    static const std::set<std::string> known{"format", "name", "description", "case", "methods", "vary", "set", "tolerance"};
    if (!known.count(it.key())) r.fail("sweep", "unknown field '" + it.key() + "'");
  }
  SweepSpec s;
  s.source = source;
  if (!doc.contains("format")) r.fail("sweep", "field 'format' is required (\"masonry-sweep/1\")");
  const std::string format = r.string(doc, "sweep", "format", "");
  if (format != "masonry-sweep/1") r.fail("sweep", "field 'format': expected \"masonry-sweep/1\", got \"" + format + "\"");
  s.name = r.string(doc, "sweep", "name", "");
  s.description = r.string(doc, "sweep", "description", "");
  s.case_ref = r.string(doc, "sweep", "case", "");
  if (s.case_ref.empty()) r.fail("sweep", "field 'case' must name a case file (*.json) or a standard case");
  if (doc.contains("methods")) {
    const ojson& m = doc["methods"];
    if (!m.is_array() || m.empty()) r.fail("sweep", "field 'methods' must be a non-empty list of \"prd\", \"dem\"");
    for (const ojson& x : m) {
      if (!x.is_string() || (x != "prd" && x != "dem")) r.fail("sweep", "field 'methods': " + x.dump() + " is not \"prd\" or \"dem\"");
      for (const std::string& seen : s.methods)
        if (seen == x.get<std::string>()) r.fail("sweep", "field 'methods': " + x.dump() + " is listed twice");
      s.methods.push_back(x.get<std::string>());
    }
  } else {
    s.methods = {"prd", "dem"};
  }
  if (!doc.contains("vary") || !doc["vary"].is_object() || doc["vary"].empty())
    r.fail("sweep", "field 'vary' must be an object of options to vary, e.g. {\"dem.friction_angle\": [20, 30]}");
  for (auto it = doc["vary"].begin(); it != doc["vary"].end(); ++it) s.vary.push_back(parse_axis(r, it.key(), it.value()));
  if (doc.contains("set")) {
    if (!doc["set"].is_object()) r.fail("sweep", "field 'set' must be an object of options, e.g. {\"dem.hold_time\": 1}");
    for (auto it = doc["set"].begin(); it != doc["set"].end(); ++it) {
      for (const SweepAxis& a : s.vary)
        if (a.key == it.key()) r.fail("set '" + it.key() + "'", "the option is also in 'vary'");
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

SweepPlan plan_sweep(const SweepInput& in) {
  const SweepSpec s = parse_sweep(in.spec_text, in.spec_source);
  return plan_sweep(s, parse_case(in.case_text, in.case_source));
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
  for (const auto& [key, value] : spec.set) {
    try {
      p.base = with_option(p.base, key, value);
    } catch (const CaseError& e) {
      r.fail("set '" + key + "'", e.what());
    }
  }
  const std::string base_text = case_to_json(p.base);
  // A key that is no option of the case would fail every run: refuse it now, when the case takes
  // none of its values (with_option's message says why). A single refused value is a failed run
  // like any other.
  for (const SweepAxis& a : spec.vary) {
    p.keys.push_back(a.key);
    std::string first_error;
    bool accepted = false;
    for (size_t k = 0; !accepted && k < a.values.size(); ++k) {
      try {
        with_option(p.base, a.key, a.values[k]);
        accepted = true;
      } catch (const CaseError& e) {
        if (first_error.empty()) first_error = e.what();
      }
    }
    if (!accepted) r.fail("vary '" + a.key + "'", "the case takes none of the values: " + first_error);
  }
  double total = 1;
  for (const SweepAxis& a : spec.vary) total *= double(a.values.size());
  if (total > double(kMaxRuns)) r.fail("vary", "the grid has more than " + std::to_string(kMaxRuns) + " combinations");

  // The grid, last key fastest.
  std::vector<std::vector<json>> combos;
  std::vector<size_t> at(spec.vary.size(), 0);
  for (size_t n = 0; n < size_t(total); ++n) {
    std::vector<json> v;
    for (size_t k = 0; k < at.size(); ++k) v.push_back(spec.vary[k].values[at[k]]);
    combos.push_back(std::move(v));
    for (size_t k = at.size(); k-- > 0;) {
      if (++at[k] < spec.vary[k].values.size()) break;
      at[k] = 0;
    }
  }
  const auto has = [&](const char* m) {
    for (const std::string& x : spec.methods)
      if (x == m) return true;
    return false;
  };
  const auto add = [&](const std::string& method, std::vector<json> values) {
    SweepRun run;
    run.index = static_cast<int>(p.runs.size());
    run.method = method;
    std::string idtext = base_text + "\n" + method + "\n";
    for (size_t k = 0; k < p.keys.size(); ++k) idtext += p.keys[k] + "=" + (values[k].is_null() ? "-" : values[k].dump()) + "\n";
    run.id = hex16(fnv1a(idtext));
    run.values = std::move(values);
    p.runs.push_back(std::move(run));
    return p.runs.back().index;
  };
  // PRD runs first: they are quick, and every DEM row's difference needs its PRD row.
  std::map<std::string, int> prd_of;  // non-DEM values (JSON text) -> PRD run
  const auto prd_values = [&](const std::vector<json>& v) {
    std::vector<json> out = v;
    for (size_t k = 0; k < out.size(); ++k)
      if (is_dem_option(p.keys[k])) out[k] = nullptr;
    return out;
  };
  if (has("prd"))
    for (const auto& v : combos) {
      const std::vector<json> pv = prd_values(v);
      const std::string key = json(pv).dump();
      if (!prd_of.count(key)) prd_of[key] = add("prd", pv);
    }
  if (has("dem"))
    for (const auto& v : combos) {
      const int i = add("dem", v);
      auto it = prd_of.find(json(prd_values(v)).dump());
      if (it != prd_of.end()) p.runs[i].prd = it->second;
    }
  std::string all = "masonry-sweep/1\n" + base_text;
  for (const SweepRun& run : p.runs) all += run.method + " " + run.id + "\n";
  p.hash = hex16(fnv1a(all));
  return p;
}

Case case_of_run(const SweepPlan& p, const SweepRun& r) {
  Case c = p.base;
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (!r.values[k].is_null()) c = with_option(c, p.keys[k], r.values[k]);
  return c;
}

std::string run_label(const SweepPlan& p, const SweepRun& r) {
  std::string s;
  for (size_t k = 0; k < p.keys.size(); ++k)
    if (!r.values[k].is_null()) s += (s.empty() ? "" : ", ") + p.keys[k] + "=" + value_text(r.values[k]);
  return s;
}

}  // namespace masonry
