// What the world benchmarks report of their repetitions' ratios: the
// median and range over the repetitions, and their environment settings.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace patchspin::bench {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// "1.23 (1.10-1.31)": median and range over the repetitions.
inline std::string ratioCell(const std::vector<double>& v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f (%.2f-%.2f)", median(v),
                *std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end()));
  return buf;
}

// The integer environment variable `name` in [lo, hi], `fallback` when it
// is not set; anything else ends the program (`program` names it).
inline int envInt(const char* program, const char* name, int fallback, int lo, int hi) {
  const char* e = std::getenv(name);
  if (!e) return fallback;
  char* end = nullptr;
  const long v = std::strtol(e, &end, 10);
  if (end == e || *end != '\0' || v < lo || v > hi) {
    std::fprintf(stderr, "%s: %s must be an integer in %d..%d, got '%s'\n", program, name, lo, hi,
                 e);
    std::exit(2);
  }
  return int(v);
}

}  // namespace patchspin::bench
