// Reading and checking a masonry-catalogue/1 file, and building each benchmark's case.
#include "validate/catalogue.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "cases/generators.hpp"
#include "model/fields.hpp"
#include "model/io.hpp"

namespace masonry {

const char* quantity_name(Quantity q) {
  switch (q) {
    case Quantity::capacity: return "capacity";
    case Quantity::least_friction_angle: return "least_friction_angle";
    case Quantity::stands: return "stands";
    case Quantity::threshold: return "threshold";
    case Quantity::reaction: return "reaction";
    case Quantity::reaction_balance: return "reaction_balance";
    case Quantity::duality_gap: return "duality_gap";
  }
  return "?";
}

const char* quantity_unit(Quantity q) {
  switch (q) {
    case Quantity::capacity: return "m";
    case Quantity::least_friction_angle: return "deg";
    case Quantity::reaction: return "N";
    default: return "";
  }
}

double Tolerance::limit(double expected) const { return std::max(absolute, relative * std::abs(expected)); }

namespace {

// Ordered: the rows come out in the catalogue's order, methods included.
using json = nlohmann::ordered_json;

// Errors name the file, the benchmark and the field.
struct Where {
  std::string file, benchmark;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    std::string m = file;
    if (!benchmark.empty()) m += ": benchmark '" + benchmark + "'";
    if (!field.empty()) m += ": field '" + field + "'";
    throw CaseError(m + ": " + what);
  }
};

void only_fields(const json& o, const std::set<std::string>& allowed, const Where& w, const std::string& prefix) {
  for (auto it = o.begin(); it != o.end(); ++it)
    if (!allowed.count(it.key())) w.fail(prefix + it.key(), "unknown field");
}

std::string string_field(const json& o, const std::string& key, const Where& w, const std::string& prefix, bool required) {
  if (!o.contains(key)) {
    if (required) w.fail(prefix + key, "missing");
    return "";
  }
  if (!o[key].is_string() || o[key].get<std::string>().empty()) w.fail(prefix + key, "must be a non-empty string");
  return o[key].get<std::string>();
}

double number_field(const json& o, const std::string& key, const Where& w, const std::string& prefix) {
  if (!o.contains(key)) w.fail(prefix + key, "missing");
  if (!o[key].is_number() || !std::isfinite(o[key].get<double>())) w.fail(prefix + key, "must be a finite number");
  return o[key].get<double>();
}

std::map<std::string, nlohmann::json> options_field(const json& o, const Where& w, const std::string& prefix) {
  std::map<std::string, nlohmann::json> out;
  if (!o.contains("options")) return out;
  if (!o["options"].is_object()) w.fail(prefix + "options", "must be an object of case options (\"dem.friction_angle\": 30)");
  for (auto it = o["options"].begin(); it != o["options"].end(); ++it) out[it.key()] = nlohmann::json::parse(it.value().dump());
  return out;
}

Tolerance tolerance_field(const json& o, const Where& w, const std::string& prefix) {
  if (!o.contains("tolerance")) w.fail(prefix + "tolerance", "missing");
  const json& t = o["tolerance"];
  const std::string p = prefix + "tolerance.";
  if (!t.is_object()) w.fail(prefix + "tolerance", "must be an object with 'absolute' or 'relative' and 'why'");
  only_fields(t, {"absolute", "relative", "why"}, w, p);
  Tolerance tol;
  if (t.contains("absolute")) tol.absolute = number_field(t, "absolute", w, p);
  if (t.contains("relative")) tol.relative = number_field(t, "relative", w, p);
  if (!t.contains("absolute") && !t.contains("relative")) w.fail(prefix + "tolerance", "needs 'absolute' or 'relative'");
  if (tol.absolute < 0 || tol.relative < 0) w.fail(prefix + "tolerance", "must not be negative");
  tol.why = string_field(t, "why", w, p, true);
  return tol;
}

Method method_of(const std::string& s, const Where& w, const std::string& field) {
  if (const std::optional<Method> m = parse_method(s)) return *m;
  w.fail(field, "unknown method '" + s + "' (prd or dem)");
}

Quantity quantity_of(const std::string& s, const Where& w) {
  for (Quantity q : {Quantity::capacity, Quantity::least_friction_angle, Quantity::stands, Quantity::threshold, Quantity::reaction,
                     Quantity::reaction_balance, Quantity::duality_gap})
    if (s == quantity_name(q)) return q;
  w.fail("quantity", "unknown quantity '" + s + "' (capacity, least_friction_angle, stands, threshold, reaction, reaction_balance, duality_gap)");
}

Expected expected_field(const json& x, Quantity q, const Where& w, const std::string& field) {
  Expected out;
  if (q == Quantity::stands) {
    if (!x.is_boolean()) w.fail(field, "must be true (stands) or false (collapses)");
    out.value = x.get<bool>() ? 1.0 : 0.0;
  } else if (x.is_number()) {
    out.value = x.get<double>();
    if (!std::isfinite(out.value)) w.fail(field, "must be a finite number");
  } else if (x.is_object()) {
    only_fields(x, {"per_weight", "method"}, w, field + ".");
    if (x.contains("per_weight") == x.contains("method")) w.fail(field, "needs exactly one of 'per_weight', 'method'");
    if (x.contains("per_weight")) {
      out.kind = Expected::Kind::per_weight;
      out.value = number_field(x, "per_weight", w, field + ".");
    } else {
      out.kind = Expected::Kind::method;
      out.method = method_of(string_field(x, "method", w, field + ".", true), w, field + ".method");
    }
  } else {
    w.fail(field, "must be a number, {\"per_weight\": x} or {\"method\": \"prd\"}");
  }
  return out;
}

Benchmark parse_benchmark(const json& e, const Where& file_where, size_t index) {
  Where w = file_where;
  if (!e.is_object()) w.fail("benchmarks[" + std::to_string(index) + "]", "must be an object");
  // Unnamed: by position (GCC 12 warns wrongly about "#" + to_string here: -Wrestrict).
  w.benchmark = std::to_string(index + 1);
  w.benchmark.insert(0, 1, '#');
  if (e.contains("name") && e["name"].is_string()) w.benchmark = e["name"].get<std::string>();
  only_fields(
      e, {"name", "title", "source", "notes", "quick", "case", "options", "quantity", "expected", "search", "support", "component", "d", "methods"},
      w, "");
  Benchmark b;
  b.name = string_field(e, "name", w, "", true);
  b.title = string_field(e, "title", w, "", true);
  b.source = string_field(e, "source", w, "", true);
  b.notes = string_field(e, "notes", w, "", false);
  if (e.contains("quick")) {
    if (!e["quick"].is_boolean()) w.fail("quick", "must be true or false");
    b.quick = e["quick"].get<bool>();
  }

  if (!e.contains("case") || !e["case"].is_object()) w.fail("case", "missing (an object: file, standard, generator or inline)");
  const json& c = e["case"];
  only_fields(c, {"file", "standard", "generator", "parameters", "inline"}, w, "case.");
  const int kinds = int(c.contains("file")) + int(c.contains("standard")) + int(c.contains("generator")) + int(c.contains("inline"));
  if (kinds != 1) w.fail("case", "needs exactly one of 'file', 'standard', 'generator', 'inline'");
  b.case_source.file = string_field(c, "file", w, "case.", false);
  b.case_source.standard = string_field(c, "standard", w, "case.", false);
  b.case_source.generator = string_field(c, "generator", w, "case.", false);
  if (c.contains("parameters")) {
    if (b.case_source.generator.empty()) w.fail("case.parameters", "only with 'generator'");
    if (!c["parameters"].is_object()) w.fail("case.parameters", "must be an object");
    b.case_source.parameters = nlohmann::json::parse(c["parameters"].dump());
  }
  if (c.contains("inline")) {
    if (!c["inline"].is_object()) w.fail("case.inline", "must be a masonry-case/1 object");
    b.case_source.inline_case = nlohmann::json::parse(c["inline"].dump());
  }
  b.options = options_field(e, w, "");

  b.quantity = quantity_of(string_field(e, "quantity", w, "", true), w);
  if (!e.contains("expected")) w.fail("expected", "missing");
  b.expected = expected_field(e["expected"], b.quantity, w, "expected");
  if (b.quantity == Quantity::threshold) {
    if (!e.contains("search") || !e["search"].is_object()) w.fail("search", "missing (threshold needs parameter, range, resolution)");
    const json& s = e["search"];
    only_fields(s, {"parameter", "range", "resolution"}, w, "search.");
    Search q;
    q.parameter = string_field(s, "parameter", w, "search.", true);
    if (!s.contains("range") || !s["range"].is_array() || s["range"].size() != 2 || !s["range"][0].is_number() || !s["range"][1].is_number())
      w.fail("search.range", "must be [low, high]");
    q.lo = s["range"][0].get<double>();
    q.hi = s["range"][1].get<double>();
    q.resolution = number_field(s, "resolution", w, "search.");
    if (!(q.lo < q.hi) || !std::isfinite(q.lo) || !std::isfinite(q.hi)) w.fail("search.range", "needs low < high, both finite");
    if (!(q.resolution > 0)) w.fail("search.resolution", "must be positive");
    b.search = q;
  } else if (e.contains("search")) {
    w.fail("search", "only for the threshold quantity");
  }
  if (b.quantity == Quantity::reaction) {
    b.support = string_field(e, "support", w, "", true);
    b.component = string_field(e, "component", w, "", true);
    if (b.component != "x" && b.component != "y" && b.component != "moment") w.fail("component", "must be x, y or moment");
    b.at_d = number_field(e, "d", w, "");
  } else {
    for (const char* k : {"support", "component", "d"})
      if (e.contains(k)) w.fail(k, "only for the reaction quantity");
  }

  if (!e.contains("methods") || !e["methods"].is_object() || e["methods"].empty())
    w.fail("methods", "missing (an object: \"prd\" and/or \"dem\", each with its tolerance)");
  for (auto it = e["methods"].begin(); it != e["methods"].end(); ++it) {
    const std::string p = "methods." + it.key() + ".";
    MethodRun m;
    m.method = method_of(it.key(), w, "methods." + it.key());
    if (!it.value().is_object()) w.fail("methods." + it.key(), "must be an object with a tolerance");
    only_fields(it.value(), {"tolerance", "options", "expected", "source"}, w, p);
    if (it.value().contains("expected")) {
      m.expected = expected_field(it.value()["expected"], b.quantity, w, p + "expected");
      m.source = string_field(it.value(), "source", w, p, true);
    } else if (it.value().contains("source")) {
      w.fail(p + "source", "only with the method's own 'expected'");
    }
    const Expected& ref = m.expected ? *m.expected : b.expected;
    // A yes/no answer needs no tolerance.
    if (b.quantity != Quantity::stands)
      m.tolerance = tolerance_field(it.value(), w, p);
    else if (it.value().contains("tolerance"))
      w.fail(p + "tolerance", "a yes/no quantity (stands) takes none");
    m.options = options_field(it.value(), w, p);
    const bool prd_only = b.quantity == Quantity::least_friction_angle || b.quantity == Quantity::duality_gap;
    if (prd_only && m.method != Method::prd) w.fail("methods." + it.key(), std::string(quantity_name(b.quantity)) + " is a PRD quantity");
    if (ref.kind == Expected::Kind::method && ref.method == m.method)
      w.fail("methods." + it.key(), "cannot be judged against its own result (expected.method)");
    b.methods.push_back(std::move(m));
  }
  return b;
}

}  // namespace

Catalogue parse_catalogue(const std::string& text, const std::string& source, const std::string& folder) {
  const Where w{source, ""};
  json doc = parse_document<CaseError>(text, source);
  if (!doc.is_object()) w.fail("", "must be a JSON object");
  only_fields(doc, {"format", "description", "benchmarks"}, w, "");
  if (!doc.contains("format") || doc["format"] != "masonry-catalogue/1") w.fail("format", "must be \"masonry-catalogue/1\"");
  if (!doc.contains("benchmarks") || !doc["benchmarks"].is_array() || doc["benchmarks"].empty()) w.fail("benchmarks", "must be a non-empty array");
  Catalogue cat;
  cat.source = source;
  cat.folder = folder;
  std::set<std::string> names;
  for (size_t i = 0; i < doc["benchmarks"].size(); ++i) {
    Benchmark b = parse_benchmark(doc["benchmarks"][i], w, i);
    if (!names.insert(b.name).second) Where{source, b.name}.fail("name", "used twice");
    cat.benchmarks.push_back(std::move(b));
  }
  return cat;
}

Catalogue load_catalogue(const std::string& path) {
  const std::optional<std::string> text = read_text(path);
  if (!text) throw CaseError(path + ": cannot read the catalogue");
  return parse_catalogue(*text, path, std::filesystem::path(path).parent_path().string());
}

namespace {

// A generator call: the generator's parameters by name, in the units of cases/README.md
// (angles in degrees where the name says so).
Case generated(const std::string& name, const nlohmann::json& params, const Where& w) {
  constexpr double kDeg = M_PI / 180.0;
  auto num = [&](const std::string& k, const nlohmann::json& v) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) w.fail("case.parameters." + k, "must be a finite number");
    return v.get<double>();
  };
  auto count = [&](const std::string& k, const nlohmann::json& v) {
    if (!v.is_number_integer()) w.fail("case.parameters." + k, "must be an integer");
    return v.get<int>();
  };
  auto flag = [&](const std::string& k, const nlohmann::json& v) {
    if (!v.is_boolean()) w.fail("case.parameters." + k, "must be true or false");
    return v.get<bool>();
  };
  // The parameters both arch generators share; a generator's own ones come first.
  auto arch_parameter = [&](auto& p, const std::string& k, const nlohmann::json& v) {
    if (k == "thickness")
      p.thickness = num(k, v);
    else if (k == "embrace_deg")
      p.embrace = num(k, v) * kDeg;
    else if (k == "voussoirs")
      p.voussoirs = count(k, v);
    else if (k == "depth")
      p.depth = num(k, v);
    else if (k == "density")
      p.density = num(k, v);
    else if (k == "spreading")
      p.spreading = flag(k, v);
    else if (k == "step")
      p.step = num(k, v);
    else if (k == "max_steps")
      p.max_steps = count(k, v);
    else
      return false;
    return true;
  };
  auto build = [&](auto make, const auto& p) {
    try {
      return make(p);
    } catch (const CaseError& e) {
      w.fail("case.parameters", e.what());
    }
  };
  const char* shared = "thickness, embrace_deg, voussoirs, depth, density, spreading, step, max_steps";
  if (name == "circular-arch") {
    CircularArch p;
    for (auto it = params.begin(); it != params.end(); ++it) {
      if (it.key() == "radius")
        p.radius = num(it.key(), *it);
      else if (!arch_parameter(p, it.key(), *it))
        w.fail("case.parameters." + it.key(), std::string("unknown parameter of circular-arch (radius, ") + shared + ")");
    }
    return build(circular_arch, p);
  }
  if (name == "pointed-arch") {
    PointedArch p = standard_pointed_arch();
    for (auto it = params.begin(); it != params.end(); ++it) {
      if (it.key() == "rcirc")
        p.rcirc = num(it.key(), *it);
      else if (it.key() == "eccentricity")
        p.eccentricity = num(it.key(), *it);
      else if (!arch_parameter(p, it.key(), *it))
        w.fail("case.parameters." + it.key(), std::string("unknown parameter of pointed-arch (rcirc, eccentricity, ") + shared + ")");
    }
    return build(pointed_arch, p);
  }
  w.fail("case.generator", "unknown generator '" + name + "' (circular-arch, pointed-arch)");
}

}  // namespace

std::vector<const Benchmark*> chosen_benchmarks(const Catalogue& cat, bool quick, const std::vector<std::string>& only) {
  std::set<std::string> wanted(only.begin(), only.end());
  for (const std::string& n : wanted) {
    bool known = false;
    for (const Benchmark& b : cat.benchmarks) known = known || b.name == n;
    if (!known) throw CaseError(cat.source + ": no benchmark named '" + n + "' (masonry validate --list)");
  }
  std::vector<const Benchmark*> out;
  for (const Benchmark& b : cat.benchmarks)
    if ((!quick || b.quick) && (wanted.empty() || wanted.count(b.name))) out.push_back(&b);
  if (out.empty()) throw CaseError(cat.source + ": no benchmark left to run (--quick and --only exclude them all)");
  return out;
}

Case benchmark_case(const Catalogue& cat, const Benchmark& b, Method m, std::optional<double> value) {
  const Where w{cat.source, b.name};
  const CaseSource& s = b.case_source;
  nlohmann::json params = s.parameters;
  const bool generator_search = value && b.search && b.search->parameter.find('.') == std::string::npos && b.search->parameter != "gravity";
  if (generator_search) {
    if (s.generator.empty()) w.fail("search.parameter", "'" + b.search->parameter + "' is a generator parameter, but the case has no generator");
    params[b.search->parameter] = *value;
  }
  Case c;
  if (!s.generator.empty()) c = generated(s.generator, params, w);
  try {
    if (!s.file.empty()) {
      const std::filesystem::path p =
          std::filesystem::path(s.file).is_absolute() ? std::filesystem::path(s.file) : std::filesystem::path(cat.folder) / s.file;
      c = load_case(p.string());
    } else if (!s.standard.empty()) {
      c = standard_case(s.standard);
    } else if (s.generator.empty()) {
      c = parse_case(s.inline_case.dump(), cat.source + " [benchmark " + b.name + ", case.inline]");
    }
    for (const auto& [k, v] : b.options) c = with_option(c, k, v);
    for (const MethodRun& r : b.methods)
      if (r.method == m)
        for (const auto& [k, v] : r.options) c = with_option(c, k, v);
    if (value && !generator_search) c = with_option(c, b.search->parameter, *value);
  } catch (const CaseError& e) {
    w.fail("case", e.what());
  }
  return c;
}

}  // namespace masonry
