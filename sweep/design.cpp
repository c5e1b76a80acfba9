// The sampled design: a Latin hypercube (McKay, Beckman & Conover 1979), portable by seed.
#include <cstdint>
#include <random>

#include "sweep/runner.hpp"

namespace masonry {

namespace {

// FNV-1a of the name, mixed with the seed by SplitMix64's finaliser: one stream per column.
uint64_t column_seed(unsigned long long seed, const std::string& name) {
  uint64_t z = sweep_detail::fnv1a(name) ^ (seed + 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1): the top 53 bits.
double uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

// Uniform in [0, n) without modulo bias (rejection below the largest multiple of n).
uint64_t below(std::mt19937_64& g, uint64_t n) {
  const uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  for (;;) {
    const uint64_t x = g();
    if (x < limit) return x % n;
  }
}

}  // namespace

std::vector<std::vector<double>> latin_hypercube(int n, const std::vector<std::string>& names, unsigned long long seed) {
  std::vector<std::vector<double>> points(static_cast<size_t>(std::max(n, 0)), std::vector<double>(names.size()));
  for (size_t j = 0; j < names.size(); ++j) {
    std::mt19937_64 g(column_seed(seed, names[j]));
    // Fisher-Yates: stratum[i] is the stratum of point i.
    std::vector<int> stratum(points.size());
    for (size_t i = 0; i < stratum.size(); ++i) stratum[i] = static_cast<int>(i);
    for (size_t i = stratum.size(); i > 1; --i) std::swap(stratum[i - 1], stratum[below(g, i)]);
    for (size_t i = 0; i < points.size(); ++i) points[i][j] = (stratum[i] + uniform01(g)) / n;
  }
  return points;
}

}  // namespace masonry
