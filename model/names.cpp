#include "model/names.hpp"

#include <algorithm>

namespace masonry {

namespace {

// Edits from a to b, two neighbouring letters swapped counting as one (optimal string alignment).
size_t edits(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::string nearest_name(const std::string& typed, const std::vector<std::string>& names) {
  std::string best;
  size_t best_d = 3;
  for (const std::string& n : names) {
    const size_t d = edits(typed, n);
    if (d < best_d && 2 * d < typed.size()) best = n, best_d = d;
  }
  if (!best.empty()) return best;
  std::string prefixed;
  for (const std::string& n : names)
    if (typed.size() >= 3 + (typed.rfind("--", 0) == 0 ? 2 : 0) && n.rfind(typed, 0) == 0) {
      if (!prefixed.empty()) return "";  // two names begin so: no guess
      prefixed = n;
    }
  return prefixed;
}

std::string did_you_mean(const std::string& typed, const std::vector<std::string>& names) {
  const std::string best = nearest_name(typed, names);
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

}  // namespace masonry
