// A test suite that runs one demo once for all its tests (ctest runs each
// test in a process of its own, so each process runs it once): `Suite`
// derives from DemoSuite<Suite> and gives kDemo, the demo's name, and
// flags(dir), its command line into `dir`. Every test skips if the demo is
// not built and fails at once if its run failed.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "demo_test_util.hpp"
#include "run_tool.hpp"

namespace patchspin::render::demo_test {

template <class Suite>
class DemoSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!demoBuilt(Suite::kDemo)) return;
    dir_ = freshTempDir(std::string(Suite::kDemo) + "_run");
    run_ = patchspin::testing::runTool(demoPath(Suite::kDemo), Suite::flags(dir_));
  }
  static void TearDownTestSuite() {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  void SetUp() override {
    if (!demoBuilt(Suite::kDemo))
      GTEST_SKIP() << "demos/" << Suite::kDemo
                   << " not built (needs the Bullet integration and the renderer): "
                   << demoPath(Suite::kDemo);
    ASSERT_EQ(run_.exitCode, 0) << run_.err;
  }
  // Runs the demo again into a fresh directory (removed after): it exits with
  // 0 and writes the same bytes as the suite's run (expectSameOutput).
  static void expectSameOnRerun(int frames) {
    const std::string again = freshTempDir(std::string(Suite::kDemo) + "_rerun");
    const patchspin::testing::ToolRun rerun =
        patchspin::testing::runTool(demoPath(Suite::kDemo), Suite::flags(again));
    EXPECT_EQ(rerun.exitCode, 0) << rerun.err;
    if (rerun.exitCode == 0) expectSameOutput(dir_, again, frames);
    std::filesystem::remove_all(again);
  }
  // The run's summary.json.
  static nlohmann::json summary() {
    return nlohmann::json::parse(
        fileBytes((std::filesystem::path(dir_) / "summary.json").string()));
  }

  static inline std::string dir_;  // the run's output directory
  static inline patchspin::testing::ToolRun run_;
};

}  // namespace patchspin::render::demo_test
