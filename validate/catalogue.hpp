// The validation catalogue (masonry-catalogue/1, JSON): benchmarks whose expected values come
// from outside the code (closed forms, published results, physical laws), each run on PRD and/or
// the DEM and judged against a tolerance argued in one sentence. The format is documented in
// validate/README.md; the built-in catalogue (validate/catalogue.json) is written in it.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"
#include "model/method.hpp"

namespace masonry {

// What a benchmark measures. Units: capacity m; least_friction_angle and threshold on a friction
// angle deg; stands 1 (stands) or 0; reaction N (moment N m); reaction_balance and duality_gap
// dimensionless (relative to the dead loads' resultant).
enum class Quantity {
  capacity,              // the run's capacity (the last stable d)
  least_friction_angle,  // PRD: the sliding check's least friction angle over the run
  stands,                // the structure as it stands: PRD check, DEM settling under gravity
  threshold,             // bisection on one parameter for where the structure starts to stand
  reaction,              // one support's reaction component at one d
  reaction_balance,      // max over recorded equilibria of |sum of reactions - dead loads| / |loads|
  duality_gap,           // PRD: max over steps of |primal - dual| / (|primal| + W)
};
const char* quantity_name(Quantity q);
const char* quantity_unit(Quantity q);

// Where the structure comes from: exactly one of these.
struct CaseSource {
  std::string file;       // a case file, relative to the catalogue's folder
  std::string standard;   // a standard scene: "pointed-arch", "cathedral-settlement", ...
  std::string generator;  // "circular-arch" or "pointed-arch", with `parameters`
  nlohmann::json parameters = nlohmann::json::object();
  nlohmann::json inline_case;  // a masonry-case/1 document
};

struct Tolerance {
  double absolute = 0.0;  // in the quantity's unit
  double relative = 0.0;  // of |expected|; the limit is the larger of the two
  std::string why;        // the one-sentence argument for it
  double limit(double expected) const;
};

struct Expected {
  enum class Kind { value, per_weight, method } kind = Kind::value;
  double value = 0.0;           // value, or the multiple of the dead loads' vertical resultant
  Method method = Method::prd;  // Kind::method: the other method's result on the same case
};

struct MethodRun {
  Method method = Method::prd;
  // A reference of this method's own (the paper's 3DEC for the DEM beside its PRD for PRD),
  // overriding the benchmark's expected value and source.
  std::optional<Expected> expected;
  std::string source;
  Tolerance tolerance;
  std::map<std::string, nlohmann::json> options;  // case options for this method only
};

// Quantity::threshold: the structure stands on one side of the range and not on the other.
struct Search {
  std::string parameter;  // a generator parameter ("thickness") or a case option ("dem.friction_angle")
  double lo = 0.0, hi = 0.0;
  double resolution = 0.0;  // the bisection stops when the bracket is narrower
};

struct Benchmark {
  std::string name;
  std::string title;   // one line
  std::string source;  // short citation of where the expected value comes from
  std::string notes;   // the derivation, longer (reports only)
  bool quick = false;  // in the --quick subset
  CaseSource case_source;
  std::map<std::string, nlohmann::json> options;  // case options for every method
  Quantity quantity = Quantity::capacity;
  Expected expected;
  std::optional<Search> search;
  std::string support;    // Quantity::reaction: the support block's id
  std::string component;  // Quantity::reaction: "x", "y" or "moment"
  double at_d = 0.0;      // Quantity::reaction: the d of the record, m
  std::vector<MethodRun> methods;
};

struct Catalogue {
  std::string source;  // file name (or "built-in catalogue"), for messages
  std::string folder;  // case files are relative to it
  std::vector<Benchmark> benchmarks;
};

// Parses and checks a catalogue; throws CaseError with one line naming the file, the benchmark
// and the field.
Catalogue parse_catalogue(const std::string& text, const std::string& source, const std::string& folder);
Catalogue load_catalogue(const std::string& path);
// validate/catalogue.json, compiled in.
Catalogue builtin_catalogue();
// The benchmarks `masonry validate --quick --only NAME...` runs, in catalogue order: the quick
// ones where `quick`, those named in `only` where it names any. Throws CaseError for a name the
// catalogue does not have, or when nothing is left to run.
std::vector<const Benchmark*> chosen_benchmarks(const Catalogue& cat, bool quick, const std::vector<std::string>& only);

// The benchmark's structure for one method: the case, the catalogue's options, the method's
// options, and (for a threshold search) the searched parameter at `value`.
Case benchmark_case(const Catalogue& cat, const Benchmark& b, Method m, std::optional<double> value = std::nullopt);

}  // namespace masonry
