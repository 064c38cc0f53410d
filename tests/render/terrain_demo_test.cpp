// demos/terrain runs headless with a few small frames: valid PNGs of the
// requested size, not blank, changing from frame to frame. summary.json: under
// the patch laws the level bodies on the triangle mesh stop as on the plane
// (the demo's plane_reference), every body on coplanar triangles is patched at
// every step, the slope bodies stop and hold, the coin on the crease is left
// to Bullet's points and counted as a crease; stock Bullet gets no patch.
// Skips if the demo binary is not built.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <patchspin/render/image.hpp>
#include <sstream>
#include <string>

#include "demo_suite.hpp"
#include "demo_test_util.hpp"

namespace patchspin::render {
namespace {

namespace fs = std::filesystem;
using namespace demo_test;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kFrames = 3;
// Simulated time [s]: every patch-law body but the crease coin stops within
// 0.43 s (the slope bodies last); 0.6 s leaves 0.17 s of holding after it.
constexpr double kTMax = 0.6;
constexpr double kRate = 240.0;
// A face on coplanar level triangles gets the patch of the plane z = 0: the
// mesh's vertices have z = 0 exactly, so its normal is (0, 0, 1) exactly and
// the run is the plane's (measured: equal to all 17 printed digits, float
// and double). 1e-6 (relative, absolute below 1) leaves room for round-off
// only; the issue asks 1 %.
constexpr double kPlaneTol = 1e-6;
// The exact law's stopping ratio v/(R omega) of a uniformly pressed thin
// disk, 0.653 (Farkas et al. 2003); Bullet at 240 Hz records it at 1 % of r0
// and gets 0.634 on the plane (coin demo): 5 %.
constexpr double kReferenceRatio = 0.653;
constexpr double kRatioTol = 0.05;
// A patch that stuck on the 8 degree slope (below the friction angle) holds
// the body exactly: its slip after the stop is round-off (measured 2e-18
// m/s); stock Bullet creeps at 1e-3 to 1e-1 m/s. 1e-9 m/s.
constexpr double kHoldSlip = 1e-9;

class TerrainDemo : public DemoSuite<TerrainDemo> {
 public:
  static constexpr const char* kDemo = "terrain";
  static std::string flags(const std::string& dir) {
    std::ostringstream args;
    args << frameFlags(dir, kFrames, kWidth, kHeight) << " --rate " << kRate << " --t-max " << kTMax
         << " --no-plot";
    return args.str();
  }
};

TEST_F(TerrainDemo, FramesAreValidPngsNotBlankAndChanging) {
  expectDemoFrames(dir_, kFrames, kWidth, kHeight);
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "terrain_ratio.png"));  // --no-plot
}

TEST_F(TerrainDemo, SummaryHasEveryLawAndBodyOnATriangleMesh) {
  const nlohmann::json s = summary();
  EXPECT_EQ(s["ground"]["kind"], "mesh");
  // 60 x 60 cells of 1 cm, two triangles each
  EXPECT_EQ(s["ground"]["triangles"].get<long>(), 7200);
  EXPECT_EQ(s["steps"].get<long>(), std::lround(kTMax * kRate));
  for (const char* law : {"exact", "ellipsoidal", "stock"}) {
    ASSERT_TRUE(s["laws"].contains(law)) << law;
    for (const char* body :
         {"level_coin", "level_block", "slope_coin", "slope_block", "crease_coin"}) {
      ASSERT_TRUE(s["laws"][law]["bodies"].contains(body)) << law << " " << body;
      const nlohmann::json& b = s["laws"][law]["bodies"][body];
      EXPECT_TRUE(std::isfinite(b["travel"].get<double>())) << law << " " << body;
      EXPECT_TRUE(std::isfinite(b["final_yaw"].get<double>())) << law << " " << body;
      const nlohmann::json& st = b["steps"];
      // every step is counted once: patched, left to Bullet, or no contact
      EXPECT_EQ(
          st["patched"].get<long>() + st["not_patched"].get<long>() + st["no_contact"].get<long>(),
          s["steps"].get<long>())
          << law << " " << body;
    }
  }
}

// Issue 32 item 2: a coin (and a block) on a flat triangle mesh stops as on
// the plane, with the exact law's stopping ratio.
TEST_F(TerrainDemo, PatchLawsOnTheLevelMeshStopAsOnThePlane) {
  const nlohmann::json s = summary();
  for (const char* law : {"exact", "ellipsoidal"}) {
    for (const char* body : {"level_coin", "level_block"}) {
      const nlohmann::json& b = s["laws"][law]["bodies"][body];
      const nlohmann::json& p = b["plane_reference"];
      ASSERT_TRUE(b["stopped"].get<bool>()) << law << " " << body;
      ASSERT_TRUE(p["stopped"].get<bool>()) << law << " " << body;
      EXPECT_TRUE(near(b["t_stop"].get<double>(), p["t_stop"].get<double>(), kPlaneTol))
          << law << " " << body << ": " << b["t_stop"] << " vs " << p["t_stop"];
      EXPECT_TRUE(near(b["travel"].get<double>(), p["travel"].get<double>(), kPlaneTol))
          << law << " " << body << ": " << b["travel"] << " vs " << p["travel"];
      EXPECT_TRUE(near(b["ratio_stop"].get<double>(), p["ratio_stop"].get<double>(), kPlaneTol))
          << law << " " << body << ": " << b["ratio_stop"] << " vs " << p["ratio_stop"];
    }
    const nlohmann::json& coin = s["laws"][law]["bodies"]["level_coin"];
    EXPECT_TRUE(near(coin["eps_stop"].get<double>(),
                     coin["plane_reference"]["eps_stop"].get<double>(), kPlaneTol))
        << law;
  }
  const double eps = s["laws"]["exact"]["bodies"]["level_coin"]["eps_stop"].get<double>();
  EXPECT_NEAR(eps, kReferenceRatio, kRatioTol * kReferenceRatio);
}

// A face on coplanar triangles (level or sloped) is one patch at every step;
// the slope holds what stops on it.
TEST_F(TerrainDemo, PatchLawsPatchCoplanarTrianglesAtEveryStepAndHoldOnTheSlope) {
  const nlohmann::json s = summary();
  const long steps = s["steps"].get<long>();
  for (const char* law : {"exact", "ellipsoidal"}) {
    for (const char* body : {"level_coin", "level_block", "slope_coin", "slope_block"}) {
      const nlohmann::json& b = s["laws"][law]["bodies"][body];
      EXPECT_EQ(b["steps"]["patched"].get<long>(), steps) << law << " " << body;
      EXPECT_EQ(b["steps"]["reasons"]["total"].get<long>(), 0) << law << " " << body;
      EXPECT_FALSE(b["fell_through"].get<bool>()) << law << " " << body;
    }
    for (const char* body : {"slope_coin", "slope_block"}) {
      const nlohmann::json& b = s["laws"][law]["bodies"][body];
      ASSERT_TRUE(b["stopped"].get<bool>()) << law << " " << body;
      EXPECT_LT(b["t_stop"].get<double>(), kTMax) << law << " " << body;
      EXPECT_LE(b["max_slip_after_stop"].get<double>(), kHoldSlip) << law << " " << body;
    }
  }
}

// The coin sliding onto the crease is left to Bullet's points while its face
// spans both planes, and the solver says so (never silent).
TEST_F(TerrainDemo, TheCreaseIsLeftToBulletAndCounted) {
  const nlohmann::json s = summary();
  for (const char* law : {"exact", "ellipsoidal"}) {
    const nlohmann::json& b = s["laws"][law]["bodies"]["crease_coin"];
    EXPECT_GT(b["steps"]["not_patched"].get<long>(), 0) << law;
    EXPECT_GT(b["steps"]["reasons"]["crease"].get<long>(), 0) << law;
    // the world's count includes the coin's
    EXPECT_GE(s["laws"][law]["not_patched"]["crease"].get<long>(),
              b["steps"]["reasons"]["crease"].get<long>())
        << law;
  }
}

TEST_F(TerrainDemo, StockBulletGetsNoPatch) {
  const nlohmann::json s = summary();
  const nlohmann::json& stock = s["laws"]["stock"];
  EXPECT_FALSE(stock["opted_in"].get<bool>());
  EXPECT_EQ(stock["not_patched"]["total"].get<long>(), 0);
  for (const auto& [key, b] : stock["bodies"].items()) {
    EXPECT_EQ(b["steps"]["patched"].get<long>(), 0) << key;
    EXPECT_EQ(b["steps"]["not_patched"].get<long>(), 0) << key;
  }
}

}  // namespace
}  // namespace patchspin::render
