// Helpers shared by the demo tests (coin, scene demos, blocks): where the
// build put the programs, file bytes, pixel differences, exact numbers for
// command lines.
#pragma once

#include <patchspin/render/image.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace patchspin::render::demo_test {

// <build>/<sub>, found next to <build>/tools/patchspin; empty without the tool.
inline std::string buildPath(const std::string& sub) {
#ifdef PATCHSPIN_TOOL
  return (std::filesystem::path(PATCHSPIN_TOOL).parent_path().parent_path() / sub).string();
#else
  (void)sub;
  return "";
#endif
}

inline std::string toolPath() {
#ifdef PATCHSPIN_TOOL
  return PATCHSPIN_TOOL;
#else
  return "";
#endif
}

inline std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Pixels whose largest channel difference exceeds `threshold`.
inline int countDifferentPixels(const Image& a, const Image& b, int threshold) {
  int n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(p[c]) - int(q[c])));
      if (d > threshold) ++n;
    }
  }
  return n;
}

// A double with all 17 significant digits, for command-line flags.
inline std::string g17(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%.17g", v);
  return s;
}

// |a - b| within tol, relative to |b| (absolute below 1).
inline bool near(double a, double b, double tol) {
  return std::abs(a - b) <= tol * std::max(1.0, std::abs(b));
}

}  // namespace patchspin::render::demo_test
