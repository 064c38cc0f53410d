// Helpers shared by the demo tests (coin, scene demos, blocks, terrain): where
// the build put the programs, fresh output directories, the frame flags, file
// bytes, pixel differences, the frames' checks, exact numbers for command
// lines. A suite that runs one demo once: demo_suite.hpp.
#pragma once

#include <patchspin/render/image.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <unistd.h>

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

// <build>/demos/<name>; empty without the tool.
inline std::string demoPath(const std::string& name) {
  return buildPath("demos/" + name);
}

// demos/<name> is built (it needs the Bullet integration and the renderer).
inline bool demoBuilt(const std::string& name) {
  const std::string path = demoPath(name);
  return !path.empty() && std::filesystem::exists(path);
}

// <test temp dir>/patchspin_<stem>_<pid>, removed if it exists.
inline std::string freshTempDir(const std::string& stem) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("patchspin_" + stem + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

// --out <dir> and the frames expectDemoFrames checks: `frames` of width x
// height, at 30 fps with --slowmo 1 (1/30 s of simulated time apart).
inline std::string frameFlags(const std::string& dir, int frames, int width, int height) {
  std::ostringstream flags;
  flags << "--out " << dir << " --frames " << frames << " --size " << width << "x" << height
        << " --fps 30 --slowmo 1";
  return flags.str();
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

// What every frame of a demo run must be (expectDemoFrames):
//  * not blank: a uniform frame has variance 0; sky, ground, bodies and text
//    give far more than a standard deviation of 10 grey levels;
//  * changed from the frame before: frames 1/30 s of simulated time apart
//    (--slowmo 1) move the bodies by centimetres and change the overlay
//    numbers, which alters far more than 50 of a 160 x 120 frame's 19200
//    pixels by more than 8 levels (the renderer is deterministic, so any
//    change is real).
constexpr double kMinFrameVariance = 100.0;
constexpr int kMinChangedPixels = 50;
constexpr int kChangeThreshold = 8;

// <dir>/frame_00000.png ... (fewer than 10 frames): each a valid PNG of
// width x height, not blank and changed from the one before, and no frame
// beyond `frames`. False if a frame is missing (the failure is recorded).
inline bool expectDemoFrames(const std::filesystem::path& dir, int frames, int width, int height) {
  Image previous;
  for (int i = 0; i < frames; ++i) {
    const std::string path = (dir / ("frame_0000" + std::to_string(i) + ".png")).string();
    EXPECT_TRUE(std::filesystem::exists(path)) << path;
    if (!std::filesystem::exists(path)) return false;
    const Image frame = readPng(path);  // throws on an invalid PNG
    EXPECT_EQ(frame.width, width) << path;
    EXPECT_EQ(frame.height, height) << path;
    EXPECT_GT(pixelVariance(frame), kMinFrameVariance) << path;
    if (i > 0) {
      EXPECT_GT(countDifferentPixels(previous, frame, kChangeThreshold), kMinChangedPixels) << path;
    }
    previous = frame;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / ("frame_0000" + std::to_string(frames) + ".png")));
  return true;
}

// Two runs into dirs `a` and `b` wrote the same bytes: frames 0 .. frames-1
// (none empty) and summary.json.
inline void expectSameOutput(const std::filesystem::path& a, const std::filesystem::path& b,
                             int frames) {
  for (int i = 0; i < frames; ++i) {
    const std::string name = "frame_0000" + std::to_string(i) + ".png";
    const std::string bytes = fileBytes((a / name).string());
    EXPECT_FALSE(bytes.empty()) << name;
    if (bytes.empty()) return;
    EXPECT_TRUE(bytes == fileBytes((b / name).string())) << name;
  }
  EXPECT_EQ(fileBytes((a / "summary.json").string()), fileBytes((b / "summary.json").string()));
}

// The progress bar went to stderr and ended complete.
inline void expectCompleteProgress(const std::string& err, int frames) {
  EXPECT_NE(err.find(std::to_string(frames) + "/" + std::to_string(frames) + " frames"),
            std::string::npos)
      << err;
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
