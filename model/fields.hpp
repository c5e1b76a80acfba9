// Strict reading of JSON fields, for every file format of the harness that a person writes
// (cases, sweep specs, tradeoff plans): one message shape, "FILE: WHERE: field 'X' ...", on one
// line, and one set of checks (no unknown field, a number is finite, a switch is true or false).
// `Error` is the format's exception type (CaseError, SweepError, ...); `Json` nlohmann's plain or
// ordered JSON, as the format keeps its keys.
#pragma once

#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "model/case.hpp"  // printable

namespace masonry {

// Line and column of a byte offset, for messages about a document's text.
inline std::pair<int, int> line_col(const std::string& text, size_t offset) {
  int line = 1, col = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

// Parses a JSON document a person wrote: nlohmann's strict grammar (no comments, no trailing
// bytes), and a key given twice in one object refused, where nlohmann keeps the last one
// silently (`"step": 0.0175, "step": 0.5` ran at 0.5). Throws Error, one line: a syntax error or
// a number beyond a double with its line and column, a duplicate key with its path.
template <class Error, class Json = nlohmann::json>
Json parse_document(const std::string& text, const std::string& source) {
  struct Frame {
    bool object = false;
    std::set<std::string> keys;
    std::string key;
    long long index = -1;  // an array's element being read: "benchmarks[3].expected", not "benchmarks[].expected"
  };
  std::vector<Frame> frames;
  const auto path = [&] {
    std::string p;
    for (const Frame& f : frames) {
      // Appended piece by piece: GCC 12 warns falsely on "[" + std::to_string(...) (PR105651).
      if (f.object) {
        if (!p.empty()) p += '.';
        p += f.key;
      } else {
        p += '[';
        p += std::to_string(f.index);
        p += ']';
      }
    }
    return p;
  };
  using Event = typename Json::parse_event_t;
  const auto cb = [&](int, Event ev, Json& parsed) {
    const bool element = ev == Event::object_start || ev == Event::array_start || ev == Event::value;
    if (element && !frames.empty() && !frames.back().object) ++frames.back().index;
    if (ev == Event::object_start || ev == Event::array_start) frames.push_back({ev == Event::object_start, {}, {}, -1});
    if ((ev == Event::object_end || ev == Event::array_end) && !frames.empty()) frames.pop_back();
    if (ev == Event::key && !frames.empty()) {
      Frame& f = frames.back();
      f.key = parsed.template get<std::string>();
      if (!f.keys.insert(f.key).second)
        throw Error(source + ": field '" + printable(path(), 200) + "' given twice (a key appears once in an object)");
    }
    return true;
  };
  try {
    return Json::parse(text, cb);
  } catch (const typename Json::parse_error& e) {
    const auto [line, col] = line_col(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string msg = e.what();
    // Keep nlohmann's reason, drop its own "[json.exception...] parse error at ..." prefix.
    const auto pos = msg.find(": syntax error");
    const std::string reason = pos == std::string::npos ? msg : msg.substr(pos + 2);
    throw Error(source + ":" + std::to_string(line) + ":" + std::to_string(col) + ": malformed JSON: " + printable(reason, 300));
  } catch (const typename Json::out_of_range&) {
    // A literal too large for a double (1e999): nlohmann gives no position, so find it.
    size_t at = 0;
    for (size_t i = 0; i < text.size(); ++i) {
      const char ch = text[i];
      if ((ch == '-' || (ch >= '0' && ch <= '9')) && (i == 0 || std::string(",[: \n\t\r").find(text[i - 1]) != std::string::npos) &&
          !std::isfinite(std::strtod(text.c_str() + i, nullptr))) {
        at = i;
        break;
      }
    }
    const auto [line, col] = line_col(text, at);
    throw Error(source + ":" + std::to_string(line) + ":" + std::to_string(col) + ": malformed JSON: number out of range (not a finite number)");
  }
}

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
  void range(double x, double lo, double hi, const std::string& where, const std::string& field, const char* unit, bool lo_open = false) const {
    if ((lo_open ? x > lo : x >= lo) && x <= hi) return;
    std::ostringstream m;
    m << "field '" << field << "' = " << x << " is outside " << (lo_open ? "(" : "[") << lo << ", " << hi << "]" << (*unit ? " " : "") << unit;
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
