// Number formatting shared by the reports and the SVG figures: no exponent a reader has to
// decode, and "n/a" (never "nan") for a missing number.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace masonry::fmt {

// printf of one number, or "n/a" when it is not finite.
template <typename... Args>
std::string number(double x, const char* format, Args... args) {
  if (!std::isfinite(x)) return "n/a";
  char b[48];
  std::snprintf(b, sizeof b, format, args...);
  return b;
}

inline std::string g(double x, int prec = 3) { return number(x, "%.*g", prec, x); }

// kN with a sensible number of digits: 5.77, 577, 19350.
inline std::string kn(double newton) {
  const double k = newton / 1000;
  return number(k, std::abs(k) >= 100 ? "%.0f" : std::abs(k) >= 10 ? "%.1f" : "%.3g", k);
}

}  // namespace masonry::fmt
