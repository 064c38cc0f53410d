// demos/scene renders a catalogue scene (the stack of 10 blocks, three small
// frames): valid PNGs of the requested size, not blank, and no fourth frame;
// --list names every catalogue scene; an unknown name is an error. Skips if
// the demo binary is not built.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <patchspin/render/image.hpp>
#include <sstream>
#include <string>

#include "demo_test_util.hpp"
#include "run_tool.hpp"

namespace patchspin::render {
namespace {

namespace fs = std::filesystem;
using namespace demo_test;

constexpr int kWidth = 160;
constexpr int kHeight = 90;
constexpr int kFrames = 3;
// A blank (uniform) frame has variance 0; sky, ground and blocks give far
// more than a standard deviation of 10 grey levels.
constexpr double kMinVariance = 100.0;

std::string demoPath() {
  const std::string demo = buildPath("demos/scene");
  return !demo.empty() && fs::exists(demo) ? demo : "";
}

TEST(SceneDemo, RendersACatalogueSceneToFrames) {
  const std::string demo = demoPath();
  if (demo.empty()) GTEST_SKIP() << "demos/scene not built";
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("patchspin_scene_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::ostringstream args;
  args << "--name stack --model exact --out " << dir.string() << " --frames " << kFrames
       << " --size " << kWidth << "x" << kHeight << " --quiet";
  const auto run = testing::runTool(demo, args.str());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (int i = 0; i < kFrames; ++i) {
    const std::string path = (dir / ("frame_0000" + std::to_string(i) + ".png")).string();
    ASSERT_TRUE(fs::exists(path)) << path;
    const Image frame = readPng(path);  // throws on an invalid PNG
    EXPECT_EQ(frame.width, kWidth);
    EXPECT_EQ(frame.height, kHeight);
    EXPECT_GT(pixelVariance(frame), kMinVariance) << path;
  }
  EXPECT_FALSE(fs::exists(dir / ("frame_0000" + std::to_string(kFrames) + ".png")));
  fs::remove_all(dir);
}

TEST(SceneDemo, ListsTheCatalogueAndRejectsAnUnknownName) {
  const std::string demo = demoPath();
  if (demo.empty()) GTEST_SKIP() << "demos/scene not built";
  const auto list = testing::runTool(demo, "--list");
  ASSERT_EQ(list.exitCode, 0) << list.err;
  for (const char* name : {"coin", "stack", "pyramid", "incline", "pour", "pile"})
    EXPECT_NE(list.out.find(name), std::string::npos) << name;
  const auto bad = testing::runTool(demo, "--name no-such-scene --quiet");
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("no scene named"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace patchspin::render
