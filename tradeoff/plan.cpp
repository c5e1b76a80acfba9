// The plan: parsing (one-line errors naming the file and field), the built-in plans, and their
// expansion against a case into validated settings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "model/fields.hpp"
#include "model/io.hpp"
#include "tradeoff/tradeoff.hpp"

namespace masonry {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

namespace {

const char* kFormat = "masonry-tradeoff-plan/1";

// The built-in plans, in the file format so that they read like a plan file (README).
//
// PRD: the reference takes a quarter of the case's step and a tenth of its contact tolerance;
// both only refine the path (capacity resolution and the contact decision), and PRD runs are
// cheap enough to afford it. The adaptive (event-driven) mode is one more setting.
//
// DEM: the reference takes, for each knob with a direction of accuracy, its accurate end: half
// the increment, no stiffness reduction (the case's own material, the closest the DEM gets to
// PRD's rigid blocks), a tenth of the equilibrium tolerance, twice the hold and twice the move
// time (slower, so more nearly quasi-static). Damping has no accurate end (a settled state does
// not depend on it) and the time-step factor is already a fifth of a stability bound, so the
// reference keeps the case's values of both; their variations show whether that was right.
const char* kFullPlan = R"({
  "format": "masonry-tradeoff-plan/1",
  "prd": {
    "repeat": 3,
    "reference": {"motion.step": "x0.25", "prd.contact_tolerance": "x0.1"},
    "vary": {
      "motion.step": ["x0.25", "x0.5", "x2", "x5", "x10"],
      "prd.contact_tolerance": ["x0.1", "x10", "x100"]
    },
    "combined": [
      {"label": "adaptive", "options": {"prd.adaptive": true}}
    ]
  },
  "dem": {
    "repeat": 1,
    "reference": {"motion.step": "x0.5", "dem.stiffness_reduction": 1, "dem.equilibrium_tolerance": "x0.1",
                  "dem.kinetic_ratio": "x0.25"},
    "vary": {
      "motion.step": ["x0.5", "x2", "x5"],
      "dem.stiffness_reduction": [1, 3, 10, 30],
      "dem.timestep_factor": [0.1, 0.5, 1.0],
      "dem.damping": [0.6, 0.9],
      "dem.equilibrium_tolerance": ["x0.1", "x10"],
      "dem.kinetic_ratio": ["x0.25", "x4"],
      "dem.bracket_fraction": [0.1]
    },
    "combined": [
      {"label": "fast", "options": {"motion.step": "x2", "dem.kinetic_ratio": "x4", "dem.equilibrium_tolerance": "x10"}}
    ]
  }
})";

const char* kQuickPlan = R"({
  "format": "masonry-tradeoff-plan/1",
  "prd": {
    "repeat": 1,
    "reference": {"motion.step": "x0.5", "prd.contact_tolerance": "x0.1"},
    "vary": {"motion.step": ["x2", "x10"], "prd.contact_tolerance": ["x100"]}
  },
  "dem": {
    "repeat": 1,
    "reference": {"motion.step": "x0.5"},
    "vary": {"motion.step": ["x2"], "dem.kinetic_ratio": ["x4"], "dem.stiffness_reduction": ["x10"]}
  }
})";

// nlohmann's two JSON types do not convert into each other directly.
ojson to_ordered(const json& v) { return ojson::parse(v.dump()); }

// The harness's message shape for a refused field (model/fields.hpp): "FILE: WHERE: what".
[[noreturn]] void fail(const std::string& source, const std::string& where, const std::string& what) {
  FieldReader<std::runtime_error, ojson>{source}.fail(where, what);
}

// Plans are read in file order (ordered_json); option values are scalars, kept as plain json.
json to_plain(const ojson& v) { return json::parse(v.dump()); }

// A relative value "x<factor>": the factor, or nullopt for any other value.
std::optional<double> relative_factor(const json& v) {
  if (!v.is_string()) return std::nullopt;
  const std::string s = v.get<std::string>();
  if (s.size() < 2 || s[0] != 'x') return std::nullopt;
  char* end = nullptr;
  const double f = std::strtod(s.c_str() + 1, &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return f;
}

void check_value(const ojson& ov, const std::string& source, const std::string& where) {
  const json v = ov.is_structured() ? json(nullptr) : to_plain(ov);
  if (ov.is_structured()) fail(source, where, "a value must be a number, true/false or \"x<factor>\", not " + ov.dump());
  if (v.is_number() || v.is_boolean()) return;
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (!s.empty() && s[0] == 'x') {
      const auto f = relative_factor(v);
      if (!f) fail(source, where, "'" + s + "' is not a relative value (x followed by a number, e.g. \"x0.5\")");
      if (!std::isfinite(*f) || *f <= 0) fail(source, where, "the factor of '" + s + "' must be positive");
    }
    return;
  }
  fail(source, where, "a value must be a number, true/false or \"x<factor>\", not " + v.dump());
}

// Options a method reads: its own section and the motion (the increment, the number of steps).
void check_key(const std::string& method, const std::string& key, const std::string& source, const std::string& where) {
  if (key.rfind(method + ".", 0) == 0 || key.rfind("motion.", 0) == 0) return;
  fail(source, where, "'" + key + "' is not a " + method + " setting (expected " + method + ".* or motion.*)");
}

std::vector<CaseOption> parse_options(const ojson& j, const std::string& method, const std::string& source, const std::string& where) {
  if (!j.is_object() || j.empty()) fail(source, where, "must be a non-empty object of option: value");
  std::vector<CaseOption> out;
  for (auto it = j.begin(); it != j.end(); ++it) {
    check_key(method, it.key(), source, where + "." + it.key());
    check_value(it.value(), source, where + "." + it.key());
    out.push_back({it.key(), to_plain(it.value())});
  }
  return out;
}

MethodPlan parse_method_plan(const ojson& j, Method which, const std::string& source) {
  const std::string method = method_name(which);
  if (!j.is_object()) fail(source, method, "must be an object");
  MethodPlan m;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const ojson& v = it.value();
    const std::string where = method + "." + k;
    if (k == "comment") {
      continue;
    } else if (k == "repeat") {
      if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 1000) fail(source, where, "must be a whole number from 1 to 1000");
      m.repeat = v.get<int>();
    } else if (k == "baseline") {
      if (!v.is_boolean()) fail(source, where, "must be true or false");
      m.baseline = v.get<bool>();
    } else if (k == "reference") {
      if (v.is_object() && v.empty()) continue;  // {}: the baseline is the reference
      m.reference = parse_options(v, method, source, where);
    } else if (k == "vary") {
      if (!v.is_object()) fail(source, where, "must be an object of option: [values]");
      for (auto p = v.begin(); p != v.end(); ++p) {
        const std::string w = where + "." + p.key();
        check_key(method, p.key(), source, w);
        if (!p.value().is_array() || p.value().empty()) fail(source, w, "must be a non-empty list of values");
        std::vector<json> values;
        for (size_t i = 0; i < p.value().size(); ++i) {
          check_value(p.value()[i], source, w + "[" + std::to_string(i) + "]");
          values.push_back(to_plain(p.value()[i]));
        }
        m.vary.push_back({p.key(), values});
      }
    } else if (k == "combined") {
      if (!v.is_array()) fail(source, where, "must be a list of {\"label\": ..., \"options\": {...}}");
      for (size_t i = 0; i < v.size(); ++i) {
        const std::string w = where + "[" + std::to_string(i) + "]";
        const ojson& e = v[i];
        if (!e.is_object()) fail(source, w, "must be {\"label\": ..., \"options\": {...}}");
        for (auto p = e.begin(); p != e.end(); ++p)
          if (p.key() != "label" && p.key() != "options") fail(source, w + "." + p.key(), "unknown field (expected label, options)");
        if (!e.contains("label") || !e["label"].is_string() || e["label"].get<std::string>().empty())
          fail(source, w + ".label", "must be a non-empty string");
        if (!e.contains("options")) fail(source, w + ".options", "missing");
        Setting s;
        s.method = which;
        s.parameter = "combined";
        s.label = e["label"].get<std::string>();
        s.options = parse_options(e["options"], method, source, w + ".options");
        m.combined.push_back(s);
      }
    } else {
      fail(source, where, "unknown field (expected repeat, baseline, reference, vary, combined, comment)");
    }
  }
  return m;
}

// A value as text for labels and directory names: numbers with 12 significant digits.
std::string value_text(const json& v) {
  if (v.is_number()) {
    char b[40];
    std::snprintf(b, sizeof b, "%.12g", v.get<double>());
    return b;
  }
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

std::string options_text(const std::vector<CaseOption>& o, const char* sep) {
  std::string s;
  for (const CaseOption& x : o) s += (s.empty() ? "" : sep) + x.key + "=" + value_text(x.value);
  return s;
}

std::string file_safe(const std::string& s) {
  std::string o;
  for (char ch : s) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' || ch == '_' || ch == '=' ||
                    ch == '+' || ch == '-';
    o += ok ? ch : '_';
  }
  return o;
}

const json* walk(const json& doc, const std::string& key) {
  const json* at = &doc;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    const std::string name = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!at->is_object() || !at->contains(name)) return nullptr;
    at = &(*at)[name];
    if (dot == std::string::npos) return at;
    start = dot + 1;
  }
}

}  // namespace

Plan parse_plan(const std::string& text, const std::string& source) {
  ojson j;
  try {
    j = ojson::parse(text);
  } catch (const ojson::parse_error& e) {
    std::string m = e.what();
    for (char& ch : m)
      if (ch == '\n') ch = ' ';
    throw std::runtime_error(source + ": not valid JSON: " + m);
  }
  if (!j.is_object()) fail(source, "plan", "must be a JSON object");
  Plan p;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    if (k == "format") {
      if (it.value() != kFormat) fail(source, "format", std::string("must be \"") + kFormat + "\"");
    } else if (k == "comment") {
      continue;
    } else if (const std::optional<Method> m = parse_method(k)) {
      p.methods[*m] = parse_method_plan(it.value(), *m, source);
    } else {
      fail(source, k, "unknown field (expected format, comment, prd, dem)");
    }
  }
  if (p.methods.empty()) fail(source, "plan", "names no method (prd, dem)");
  return p;
}

Plan load_plan(const std::string& path) {
  const std::optional<std::string> text = read_text(path);
  if (!text) throw std::runtime_error(path + ": cannot read the plan file");
  return parse_plan(*text, path);
}

Plan default_plan(bool quick) { return parse_plan(quick ? kQuickPlan : kFullPlan, quick ? "(built-in quick plan)" : "(built-in plan)"); }

ojson plan_to_json(const Plan& p) {
  ojson j;
  j["format"] = kFormat;
  for (Method method : kMethods) {
    const auto it = p.methods.find(method);
    if (it == p.methods.end()) continue;
    const MethodPlan& m = it->second;
    ojson o;
    o["repeat"] = m.repeat;
    o["baseline"] = m.baseline;
    o["reference"] = ojson::object();
    for (const CaseOption& x : m.reference) o["reference"][x.key] = to_ordered(x.value);
    o["vary"] = ojson::object();
    for (const auto& [key, values] : m.vary) {
      o["vary"][key] = ojson::array();
      for (const json& v : values) o["vary"][key].push_back(to_ordered(v));
    }
    o["combined"] = ojson::array();
    for (const Setting& s : m.combined) {
      ojson e;
      e["label"] = s.label;
      e["options"] = ojson::object();
      for (const CaseOption& x : s.options) e["options"][x.key] = to_ordered(x.value);
      o["combined"].push_back(e);
    }
    j[method_name(method)] = o;
  }
  return j;
}

json case_option(const Case& c, const std::string& key) {
  const json doc = json::parse(case_to_json(c));
  const json* v = walk(doc, key);
  return v ? *v : json(nullptr);
}

CaseOption parse_assignment(const std::string& text, const std::string& what) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) throw std::runtime_error(what + ": '" + text + "' is not KEY=VALUE");
  CaseOption o{text.substr(0, eq), nullptr};
  const std::string v = text.substr(eq + 1);
  try {
    o.value = json::parse(v);
  } catch (const json::parse_error&) {
    o.value = v;  // a bare word: a string ("x0.5", a name)
  }
  return o;
}

std::vector<PlannedRun> expand_plan(const Case& base, const Plan& plan, const std::vector<Method>& methods, const std::string& plan_source,
                                    const std::vector<Method>& reused_references) {
  const json doc = json::parse(case_to_json(base));
  const double travel = base.motion.step * base.motion.max_steps;
  // Relative values to numbers, and the path length kept when only the step changes.
  const auto resolve = [&](const std::vector<CaseOption>& in, const std::string& where) {
    std::vector<CaseOption> out;
    bool step = false, max_steps = false;
    for (const CaseOption& o : in) {
      CaseOption r = o;
      if (const auto f = relative_factor(o.value)) {
        const json* b = walk(doc, o.key);
        if (!b || !b->is_number())
          throw std::runtime_error(plan_source + ": " + where + "." + o.key + ": the case has no number for '" + o.key + "' to scale by " +
                                   o.value.get<std::string>());
        // 12 significant digits: 1e-5 x 0.1 is 1e-6, not 1.0000000000000002e-06.
        char b12[40];
        std::snprintf(b12, sizeof b12, "%.12g", b->get<double>() * *f);
        r.value = std::strtod(b12, nullptr);
        if (o.key == "motion.max_steps") r.value = std::max(1LL, std::llround(r.value.get<double>()));
      }
      step = step || o.key == "motion.step";
      max_steps = max_steps || o.key == "motion.max_steps";
      out.push_back(r);
    }
    if (step && !max_steps) {
      for (const CaseOption& o : out)
        if (o.key == "motion.step" && o.value.is_number() && o.value.get<double>() > 0) {
          const long long n = std::max(1LL, (long long)std::ceil(travel / o.value.get<double>() - 1e-9));
          out.push_back({"motion.max_steps", n});
          break;
        }
    }
    return out;
  };
  std::vector<PlannedRun> runs;
  std::vector<std::string> seen;  // the cases already planned, as JSON text
  for (const Method which : methods) {
    const std::string method = method_name(which);
    const auto it = plan.methods.find(which);
    if (it == plan.methods.end()) throw std::runtime_error(plan_source + ": " + method + ": the plan has no settings for this method");
    const MethodPlan& m = it->second;
    const auto add = [&](Setting s, const std::string& id_tail, bool reference, bool baseline, const std::string& where) {
      const std::vector<CaseOption> plan_options = s.options;
      s.options = resolve(s.options, where);
      PlannedRun p;
      p.c = base;
      try {
        for (const CaseOption& o : s.options) p.c = with_option(p.c, o.key, o.value);
      } catch (const std::exception& e) {
        throw std::runtime_error(plan_source + ": " + where + ": " + e.what());
      }
      // A reused reference is some finished run: its settings are not the planned ones.
      const bool reused = reference && std::find(reused_references.begin(), reused_references.end(), which) != reused_references.end();
      const std::string text = method + "\n" + case_to_json(p.c);
      if (!reused) {
        for (const std::string& t : seen)
          if (t == text) return;  // the same case as an earlier setting
        seen.push_back(text);
      }
      // Names from the plan's options (before the path length was added).
      std::vector<CaseOption> shown = s.options;
      shown.resize(plan_options.size());
      if (s.parameter != "combined" && !reference && !baseline) s.label = options_text(shown, ", ");
      // Directory names do not depend on the order options are written in.
      std::sort(shown.begin(), shown.end(), [](const CaseOption& a, const CaseOption& b) { return a.key < b.key; });
      p.id = file_safe(method + "-" + (id_tail.empty() ? options_text(shown, "+") : id_tail));
      p.setting = s;
      p.reference = reference;
      p.baseline = baseline;
      p.repeat = m.repeat;
      runs.push_back(std::move(p));
    };
    add({which, "reference", "reference", m.reference}, "reference", true, false, method + ".reference");
    if (m.baseline) add({which, "baseline", "baseline", {}}, "baseline", false, true, method + ".baseline");
    for (const auto& [key, values] : m.vary)
      for (size_t i = 0; i < values.size(); ++i) {
        const json b = case_option(base, key);
        // A value equal to the case's own is the baseline.
        std::vector<CaseOption> one = resolve({{key, values[i]}}, method + ".vary");
        if (!b.is_null() && one.front().value == b) continue;
        add({which, key, "", {{key, values[i]}}}, "", false, false, method + ".vary." + key + "[" + std::to_string(i) + "]");
      }
    for (size_t i = 0; i < m.combined.size(); ++i) add(m.combined[i], "", false, false, method + ".combined[" + std::to_string(i) + "]");
  }
  return runs;
}

}  // namespace masonry
