// Number formats of every report and figure: no exponent a reader has to decode, and "n/a"
// (never "nan") for a missing number. One definition per quantity, so a capacity reads the same
// in a comparison, a sweep and a trade-off report.
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

// `prec` significant digits.
inline std::string g(double x, int prec = 3) { return number(x, "%.*g", prec, x); }

// kN with a sensible number of digits: 5.77, 577, 19350.
inline std::string kn(double newton) {
  const double k = newton / 1000;
  return number(k, std::abs(k) >= 100 ? "%.0f" : std::abs(k) >= 10 ? "%.1f" : "%.3g", k);
}

// A length in m shown in mm, with `decimals` decimals and no unit.
inline std::string mm(double m, int decimals = 0) { return number(m, "%.*f", decimals, m * 1000); }

// A ratio as a signed percentage: +1.8%, -0.25%.
inline std::string pct(double x, int decimals = 1) { return number(x, "%+.*f%%", decimals, x * 100); }

// Seconds with three significant digits and no exponent: 0.0123, 4.56, 2222.
inline std::string secs(double s) {
  if (std::abs(s) >= 100) return number(s, "%.0f", s);
  if (std::abs(s) >= 1e-3) return number(s, "%.3g", s);
  return number(s, "%.2g", s);
}

// A duration as a reader says it: "0.96 ms", "3.8 ms", "790 ms" below a second, "12.5 s" above.
inline std::string duration(double s) {
  const double ms = s * 1000;
  if (!std::isfinite(s)) return "n/a";
  if (std::abs(s) < 1) return number(ms, std::abs(ms) >= 100 ? "%.0f ms" : "%.2g ms", ms);
  return secs(s) + " s";
}

// An SVG coordinate in px: one decimal; a non-finite one (an empty range) at 0 rather than a
// "n/a" that would break the drawing.
inline std::string px(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", std::isfinite(x) ? x : 0.0);
  return b;
}

}  // namespace masonry::fmt
