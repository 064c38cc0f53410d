// demos/pushed_disk, demos/thick_disk and demos/disk_torque run headless with
// two small frames: valid PNGs of the requested size, not blank, changing
// from frame to frame; summary.json finite, its scene parameters those the
// flags ask for (computed here from the paper's definitions), and one body's
// stopping data in agreement with `patchspin simulate --engine bullet`.
// Each test skips if its demo binary is not built.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
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
constexpr int kHeight = 120;
constexpr int kFrames = 2;
// Simulated time [s]: long enough for the stopping disks (0.2-0.5 s with the
// flags below), short enough to keep each demo run well under a second.
constexpr double kTMax = 1.0;
// The demos run patchspin::scenes::simulate itself with the parameters they
// report, so they agree with the tool to the 17 significant digits of the
// JSON round trip; 1e-12 relative leaves room for the last printed digit.
constexpr double kAgreementTol = 1e-12;
// Scene parameters (force, torque) against the test's own products of the
// flags: a few ulps of double arithmetic.
constexpr double kParameterTol = 1e-12;
constexpr double kG = 9.81;

// Runs one demo, checks frames and summary; returns the summary (null on a
// skip or failure).
nlohmann::json runDemo(const std::string& name, const std::string& flags) {
  const fs::path dir = freshTempDir(name);
  std::ostringstream args;
  args << frameFlags(dir.string(), kFrames, kWidth, kHeight) << " --t-max " << kTMax
       << " --no-plot " << flags;
  const auto run = testing::runTool(demoPath(name), args.str());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  if (run.exitCode != 0) return nullptr;
  if (!expectDemoFrames(dir, kFrames, kWidth, kHeight)) return nullptr;
  expectCompleteProgress(run.err, kFrames);
  const nlohmann::json s = nlohmann::json::parse(fileBytes((dir / "summary.json").string()));
  // every body: finite stopping data (t_stop null only if it never stopped)
  for (const auto& [key, m] : s["bodies"].items()) {
    SCOPED_TRACE(key);
    if (m["stopped"].get<bool>()) {
      const double t = m["t_stop"].get<double>();
      EXPECT_TRUE(std::isfinite(t) && t > 0.0 && t <= kTMax) << t;
    } else {
      EXPECT_TRUE(m["t_stop"].is_null());
    }
    for (const char* k : {"w_stop", "displacement"}) {
      for (const auto& v : m[k]) {
        EXPECT_TRUE(std::isfinite(v.get<double>())) << k;
      }
    }
    EXPECT_TRUE(std::isfinite(m["rotation"].get<double>()));
  }
  fs::remove_all(dir);
  return s;
}

// The body `key` of summary s through `patchspin simulate --engine bullet`
// with the parameters the summary reports.
void expectAgreesWithSimulate(const nlohmann::json& s, const std::string& key) {
  ASSERT_TRUE(s["bodies"].contains(key));
  const nlohmann::json& m = s["bodies"][key];
  const nlohmann::json& p = m["parameters"];
  std::ostringstream args;
  args << "simulate --engine bullet --model " << m["model"].get<std::string>()
       << " --shape cylinder:" << g17(p["R"].get<double>()) << "," << g17(p["H"].get<double>())
       << " --mass " << g17(p["mass"].get<double>()) << " --mu " << g17(p["mu"].get<double>())
       << " --g " << g17(p["g"].get<double>()) << " --force " << g17(p["force"][0].get<double>())
       << "," << g17(p["force"][1].get<double>()) << " --torque "
       << g17(p["torque"][0].get<double>()) << "," << g17(p["torque"][1].get<double>()) << ","
       << g17(p["torque"][2].get<double>()) << " --v0 " << g17(p["v0"][0].get<double>()) << ","
       << g17(p["v0"][1].get<double>()) << " --omega0 " << g17(p["omega0"].get<double>())
       << " --dt " << g17(s["dt"].get<double>()) << " --t-max " << g17(s["t_max"].get<double>())
       << " --precision " << s["precision"].get<std::string>() << " --json";
  const auto run = testing::runTool(toolPath(), args.str());
  ASSERT_EQ(run.exitCode, 0) << run.err << "\n" << args.str();
  const nlohmann::json ref = nlohmann::json::parse(run.out);
  ASSERT_EQ(m["stopped"].get<bool>(), ref["stopped"].get<bool>());
  if (ref["stopped"].get<bool>()) {
    EXPECT_TRUE(near(m["t_stop"].get<double>(), ref["t_stop"].get<double>(), kAgreementTol));
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(near(m["w_stop"][i].get<double>(), ref["w_stop"][i].get<double>(), kAgreementTol))
        << i;
  }
  for (int i = 0; i < 2; ++i) {
    EXPECT_TRUE(near(m["displacement"][i].get<double>(), ref["displacement"][i].get<double>(),
                     kAgreementTol))
        << i;
  }
  EXPECT_TRUE(near(m["rotation"].get<double>(), ref["rotation"].get<double>(), kAgreementTol));
}

#define SKIP_WITHOUT(name)                                                                       \
  if (!demoBuilt(name))                                                                          \
    GTEST_SKIP() << "demos/" name " not built (needs the Bullet integration and the renderer): " \
                 << demoPath(name);

// Sect. 6.1: F = (1.2, 0.5, 0.05) mu m g along +x for Cases 1-3.
TEST(SceneDemos, PushedDisk) {
  SKIP_WITHOUT("pushed_disk")
  const double m = 0.03, mu = 0.3;
  const nlohmann::json s =
      runDemo("pushed_disk", "--model exact --mass 0.03 --mu 0.3 --v0 0.5 --omega0 20");
  ASSERT_FALSE(s.is_null());
  const double factor[3] = {1.2, 0.5, 0.05};
  for (int i = 0; i < 3; ++i) {
    const nlohmann::json& b = s["bodies"]["case" + std::to_string(i + 1)];
    EXPECT_TRUE(
        near(b["parameters"]["force"][0].get<double>(), factor[i] * mu * m * kG, kParameterTol))
        << i;
    EXPECT_EQ(b["parameters"]["force"][1].get<double>(), 0.0);
  }
  // Case 1: |F| > mu m g, the disk cannot stick (Sect. 6.1)
  EXPECT_FALSE(s["bodies"]["case1"]["stopped"].get<bool>());
  expectAgreesWithSimulate(s, "case2");
}

// Sect. 6.2: mu h / R = 0.2, h = H / 2, F below Eq. (127).
TEST(SceneDemos, ThickDisk) {
  SKIP_WITHOUT("thick_disk")
  const double R = 0.05, mu = 0.3, ratio = 0.2;
  const nlohmann::json s =
      runDemo("thick_disk", "--radius 0.05 --mu 0.3 --mu-h-over-r 0.2 --force 0.1");
  ASSERT_FALSE(s.is_null());
  for (const char* model : {"ellipsoidal", "exact"}) {
    ASSERT_TRUE(s["bodies"].contains(model)) << model;
    EXPECT_TRUE(near(s["bodies"][model]["parameters"]["H"].get<double>(), 2.0 * ratio * R / mu,
                     kParameterTol));
  }
  expectAgreesWithSimulate(s, "exact");
}

// Sect. 6.3, Case 4: T = zeta m g R about x, parallel to F.
TEST(SceneDemos, DiskTorque) {
  SKIP_WITHOUT("disk_torque")
  const double R = 0.05, m = 0.03, zeta = 0.15;
  const nlohmann::json s =
      runDemo("disk_torque", "--radius 0.05 --mass 0.03 --zeta 0.15 --force 0.1");
  ASSERT_FALSE(s.is_null());
  const nlohmann::json& b = s["bodies"]["ellipsoidal"];
  EXPECT_TRUE(near(b["parameters"]["torque"][0].get<double>(), zeta * m * kG * R, kParameterTol));
  EXPECT_GT(b["parameters"]["force"][0].get<double>(), 0.0);  // parallel, same sense
  expectAgreesWithSimulate(s, "ellipsoidal");
}

}  // namespace
}  // namespace patchspin::render
