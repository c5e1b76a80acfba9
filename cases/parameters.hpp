// The case generators' parameters: one table per generator, the single definition of each
// parameter's name, meaning and unit, kind and default. `masonry cases NAME --PARAM` and a
// sweep's `generator.PARAM` (sweep/README.md) both read it, so the command line and a sweep take
// the same names and build the same case from the same values.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/case.hpp"

namespace masonry {

enum class ParameterKind { number, integer, flag };

struct GeneratorParameter {
  std::string name;  // "thickness", "embrace-deg": the option --NAME, a sweep's generator.NAME
  ParameterKind kind = ParameterKind::number;
  std::string help;  // meaning, without the unit (parameter_help adds it)
  double value = 0;  // the default (a flag: 0 or 1)
  // The case format's units ("m", "kg/m^3", "rad"; "deg" for names ending in -deg); "" for a
  // count or a flag. What the value is in wherever it is shown: --help, a validation threshold.
  std::string unit;
};

struct CaseGenerator {
  std::string name;     // "circular-arch", "cathedral-settlement", ...
  std::string summary;  // one line
  std::vector<GeneratorParameter> parameters;
  // The case from one value per parameter, in the table's order (CaseError for impossible
  // geometry). With every value at its default, a generator of a standard scene returns the
  // standard case (its name and description included).
  std::function<Case(const std::vector<double>&)> make;
};

// Every generator, in the order `masonry cases --list` shows them.
const std::vector<CaseGenerator>& case_generators();
// The generator called `name`, or nullptr.
const CaseGenerator* find_case_generator(const std::string& name);
// Index of parameter `name` in g.parameters, -1 when it has none of that name.
int parameter_index(const CaseGenerator& g, const std::string& name);
// The parameter's help line: its meaning and unit ("Thickness t, m").
std::string parameter_help(const GeneratorParameter& p);
// "radius, thickness, embrace-deg, ...": the names, for messages.
std::string parameter_names(const CaseGenerator& g);

// The value a JSON value gives parameter p: a finite number (an integer for an integer
// parameter, a whole number written 12.0 included), a boolean for a flag. Throws CaseError
// "generator NAME: parameter 'P': ..." otherwise.
double parameter_value(const CaseGenerator& g, const GeneratorParameter& p, const nlohmann::json& v);
// The case generator `name` writes from `values` (an object: parameter name -> value); the
// parameters it does not name keep their defaults. Throws CaseError for an unknown generator
// or parameter, a value of the wrong kind, or geometry the generator refuses.
Case generate_case(const std::string& name, const nlohmann::json& values);

}  // namespace masonry
