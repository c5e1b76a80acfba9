// Strict reading of JSON fields, for every file format of the harness that a person writes
// (cases, sweep specs, tradeoff plans): one message shape, "FILE: WHERE: field 'X' ...", on one
// line, and one set of checks (no unknown field, a number is finite, a switch is true or false).
// `Error` is the format's exception type (CaseError, SweepError, ...); `Json` nlohmann's plain or
// ordered JSON, as the format keeps its keys.
#pragma once

#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>

#include "model/case.hpp"  // printable

namespace masonry {

template <class Error, class Json>
struct FieldReader {
  std::string source;  // the file, as messages name it

  [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw Error(source + ": " + where + ": " + what); }

  void only(const Json& obj, const std::string& where, std::initializer_list<const char*> keys) const {
    if (!obj.is_object()) fail(where, "must be a JSON object");
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) fail(where, "unknown field '" + printable(it.key()) + "'");
    }
  }

  double number(const Json& v, const std::string& where, const std::string& field) const {
    if (!v.is_number()) fail(where, "field '" + field + "' must be a number");
    const double x = v.template get<double>();
    if (!std::isfinite(x)) fail(where, "field '" + field + "' is not a finite number");
    return x;
  }

  double number(const Json& obj, const std::string& where, const char* field, double dflt) const {
    auto it = obj.find(field);
    return it == obj.end() ? dflt : number(*it, where, field);
  }

  // The physically meaningful range of a quantity (README, "Ranges"): outside it the solvers'
  // arithmetic (GLPK's scaled LPs, the DEM's time step and energies) overflows or loses every
  // digit, so the input is refused before the first step.
  void range(double x, double lo, double hi, const std::string& where, const std::string& field, const char* unit,
             bool lo_open = false) const {
    if ((lo_open ? x > lo : x >= lo) && x <= hi) return;
    std::ostringstream m;
    m << "field '" << field << "' = " << x << " is outside " << (lo_open ? "(" : "[") << lo << ", " << hi << "]" << (*unit ? " " : "")
      << unit;
    fail(where, m.str());
  }

  bool boolean(const Json& obj, const std::string& where, const char* field, bool dflt) const {
    auto it = obj.find(field);
    if (it == obj.end()) return dflt;
    if (!it->is_boolean()) fail(where, std::string("field '") + field + "' must be true or false");
    return it->template get<bool>();
  }

  std::string string(const Json& obj, const std::string& where, const char* field, const std::string& dflt) const {
    auto it = obj.find(field);
    if (it == obj.end()) return dflt;
    if (!it->is_string()) fail(where, std::string("field '") + field + "' must be a string");
    return it->template get<std::string>();
  }
};

}  // namespace masonry
