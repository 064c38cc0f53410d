// demos/coin run headless with a few small frames: valid PNGs of the
// requested size, not blank, changing from frame to frame, byte-identical on a
// second run; summary.json finite and in agreement with `patchspin simulate
// --engine bullet` for the same coin.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <patchspin/render/image.hpp>
#include <sstream>
#include <string>

#include "demo_suite.hpp"
#include "demo_test_util.hpp"
#include "run_tool.hpp"

namespace patchspin::render {
namespace {

namespace fs = std::filesystem;
using namespace demo_test;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kFrames = 3;
// The coin's parameters, passed to the demo and to `patchspin simulate`.
// --slowmo 1 at 30 fps: a frame every 8 steps of 1/240 s, so the coins move
// about 1.6 cm and turn about 0.6 rad between frames.
const char* kCoinFlags = "--radius 0.05 --height 0.005 --mass 0.03 --mu 0.3 --v0 0.5 --omega0 20";
const char* kSimulateFlags =
    "--shape cylinder:0.05,0.005 --mass 0.03 --mu 0.3 --v0 0.5,0 --omega0 20 --dt "
    "0.004166666666666667";
// Simulated time [s]: the patch coins stop after about 0.32 s, stock Bullet's
// after about 0.52 s.
constexpr double kTMax = 1.0;

// The demo and `patchspin simulate --engine bullet` build the same Bullet
// world (ground, coin, margin, friction, solver) and step it identically, so
// they agree to the 17 significant digits of the JSON round trip; 1e-12
// relative leaves room for the last printed digit only.
constexpr double kAgreementTol = 1e-12;

// The demo, run once per test suite (the second run for the byte comparison
// is done by that test only).
class CoinDemo : public DemoSuite<CoinDemo> {
 public:
  static constexpr const char* kDemo = "coin";
  static std::string flags(const std::string& dir) {
    std::ostringstream args;
    args << frameFlags(dir, kFrames, kWidth, kHeight) << " --t-max " << kTMax << " --no-plot "
         << kCoinFlags;
    return args.str();
  }
};

TEST_F(CoinDemo, FramesAreValidPngsOfTheRequestedSizeNotBlankAndChanging) {
  expectDemoFrames(dir_, kFrames, kWidth, kHeight);
  // the progress bar goes to stderr and ends complete
  expectCompleteProgress(run_.err, kFrames);
}

TEST_F(CoinDemo, TwoRunsGiveIdenticalBytes) {
  expectSameOnRerun(kFrames);
}

TEST_F(CoinDemo, SummaryIsFiniteForEveryModel) {
  const nlohmann::json s = summary();
  for (const char* model : {"exact", "ellipsoidal", "stock"}) {
    SCOPED_TRACE(model);
    ASSERT_TRUE(s["models"].contains(model));
    const nlohmann::json& m = s["models"][model];
    // every coin comes to rest well within kTMax (see above)
    EXPECT_TRUE(m["stopped"].get<bool>());
    const double tStop = m["t_stop"].get<double>();
    EXPECT_TRUE(std::isfinite(tStop) && tStop > 0.0 && tStop < kTMax) << tStop;
    const double eps = m["eps_stop"].get<double>();
    EXPECT_TRUE(std::isfinite(eps) && eps >= 0.0) << eps;
    for (const char* key : {"max_tilt_rate", "max_slip_after_stop"}) {
      const double v = m[key].get<double>();
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << key << " = " << v;
    }
    for (const char* key : {"displacement", "final_displacement"}) {
      ASSERT_EQ(m[key].size(), 2u);
      for (const auto& v : m[key]) EXPECT_TRUE(std::isfinite(v.get<double>()));
    }
  }
}

// Same coin through `patchspin simulate --engine bullet --json`: same t_stop,
// eps_stop, w_stop and displacement semantics (simulate.hpp).
TEST_F(CoinDemo, SummaryAgreesWithPatchspinSimulate) {
  const nlohmann::json s = summary();
  const std::string precision = s["precision"].get<std::string>();
  auto near = [](double a, double b) {
    return std::abs(a - b) <= kAgreementTol * std::max(1.0, std::abs(b));
  };
  for (const char* model : {"exact", "ellipsoidal", "stock"}) {
    SCOPED_TRACE(model);
    std::ostringstream args;
    args << "simulate --engine bullet --model " << model << " " << kSimulateFlags << " --t-max "
         << kTMax << " --precision " << precision << " --json";
    const auto run = testing::runTool(toolPath(), args.str());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json ref = nlohmann::json::parse(run.out);
    const nlohmann::json& m = s["models"][model];
    EXPECT_EQ(m["stopped"].get<bool>(), ref["stopped"].get<bool>());
    EXPECT_PRED2(near, m["t_stop"].get<double>(), ref["t_stop"].get<double>());
    EXPECT_PRED2(near, m["eps_stop"].get<double>(), ref["eps_stop"].get<double>());
    for (int i = 0; i < 3; ++i)
      EXPECT_PRED2(near, m["w_stop"][i].get<double>(), ref["w_stop"][i].get<double>());
    for (int i = 0; i < 2; ++i)
      EXPECT_PRED2(near, m["displacement"][i].get<double>(), ref["displacement"][i].get<double>());
    EXPECT_PRED2(near, m["rotation"].get<double>(), ref["rotation"].get<double>());
  }
}

}  // namespace
}  // namespace patchspin::render
