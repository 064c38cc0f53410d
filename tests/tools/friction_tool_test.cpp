// `patchspin friction`: JSON and table output, and one-line errors with a
// non-zero exit for bad arguments.
#include "run_tool.hpp"

#include <patchspin/models.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace patchspin {
namespace {

using testing::runTool;

// The tool prints what the library computes; its JSON carries 17 digits.
constexpr double kPrintTol = 1e-14;

TEST(FrictionToolTest, JsonPiMatchesClosedFormForLinearPressureOnDisk) {
  // disk R = 0.05 with p = p0 + cx x + cy y: Pi of Eq. (73), verified by hand:
  //   pi_y0 = cy R / (3 p0), pi_x0 = cx R / (3 p0), pi_y = cy R^2 / (4 p0),
  //   pi_xy = rho = 2R/3, so Pi31 = -3 cy R / (8 p0), Pi32 = 3 cx R / (8 p0), Pi33 = 1.
  const double R = 0.05, p0 = 1000.0, cx = 4000.0, cy = -6000.0;
  const auto run =
      runTool(PATCHSPIN_TOOL,
              "friction --patch disk:0.05 --model ellipsoidal --pressure 1000,4000,-6000 "
              "--mu 0.4 --w 1,2,2 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  Mat3 expected;
  expected << 1.0, 0.0, -cy * R / (3.0 * p0),  //
      0.0, 1.0, cx * R / (3.0 * p0),           //
      -3.0 * cy * R / (8.0 * p0), 3.0 * cx * R / (8.0 * p0), 1.0;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(j["Pi"][i][k].get<double>(), expected(i, k), 1e-12);
  const double Pz = p0 * 3.14159265358979323846 * R * R;  // Eq. (70)
  EXPECT_NEAR(j["Pz"].get<double>(), Pz, 1e-12 * Pz);
  EXPECT_NEAR(j["rho"].get<double>(), 2.0 * R / 3.0, 1e-15);
  // ellipsoidal Q = -mu Pz Pi w with w = (1,2,2)/3
  const Vec3 Q = -0.4 * Pz * expected * Vec3(1.0, 2.0, 2.0) / 3.0;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(j["Q"][i].get<double>(), Q[i], 1e-12 * Pz);
}

TEST(FrictionToolTest, ExactJsonAgreesWithLibrary) {
  const auto run = runTool(PATCHSPIN_TOOL,
                           "friction --patch rect:0.08,0.04 --model exact --loads 10,0.01,0.02 "
                           "--mu 0.5 --w 0.3,-0.4,0.5 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  const PatchShape rect = PatchShape::rectangle(0.08, 0.04);
  const FrictionPatch patch(rect, LinearPressure::fromLoads(rect, {10.0, 0.01, 0.02}), 0.5);
  const Vec3 Q = patch.exactQ(Vec3(0.3, -0.4, 0.5));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(j["Q"][i].get<double>(), Q[i], kPrintTol * 10.0);
}

TEST(FrictionToolTest, CutDiskIsTheExactHalfDisk) {
  // cut:R,0 keeps the half disk x <= 0 of the disk (O, R). Uniform pressure
  // (Pz = 1 N, mu = 1) at pure spin about O, Eq. (16) with w = (0, 0, 1):
  //   Q = -(1/A) ∫ (-y/r, x/r, r/rho) dA,  A = pi R^2 / 2,
  //   ∫ y/r dA = 0,  ∫ x/r dA = ∫cos(t) dt [pi/2, 3pi/2] R^2 / 2 = -R^2,
  //   rho (11) = ∫ r dA / A = 2R/3 (as on the whole disk),
  // so Q = (0, 2/pi, -1).
  const double R = 0.05, pi = 3.14159265358979323846;
  const auto run =
      runTool(PATCHSPIN_TOOL, "friction --patch cut:0.05,0 --model exact --w 0,0,1 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  // the arc-region law and table are closed forms: round-off only (17
  // printed digits, a few hundred operations)
  constexpr double kClosedFormTol = 1e-13;
  EXPECT_NEAR(j["rho"].get<double>(), 2.0 * R / 3.0, kClosedFormTol * R);
  EXPECT_NEAR(j["Q"][0].get<double>(), 0.0, kClosedFormTol);
  EXPECT_NEAR(j["Q"][1].get<double>(), 2.0 / pi, kClosedFormTol);
  EXPECT_NEAR(j["Q"][2].get<double>(), -1.0, kClosedFormTol);
}

TEST(FrictionToolTest, LensJsonAgreesWithLibrary) {
  // the lens spans 0.02 <= x <= 0.05: its centre of pressure at x = 0.035
  // (Ty = Pz x) is inside it
  const auto run = runTool(PATCHSPIN_TOOL,
                           "friction --patch lens:0.05,0.04,0.06 --model exact --loads 10,0,0.35 "
                           "--mu 0.5 --w 0.3,-0.4,0.5 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  const PatchShape lens =
      PatchShape::arcRegion(diskDiskIntersection(Vec2::Zero(), 0.05, Vec2(0.06, 0.0), 0.04));
  const FrictionPatch patch(lens, LinearPressure::fromLoads(lens, {10.0, 0.0, 0.35}), 0.5);
  const Vec3 Q = patch.exactQ(Vec3(0.3, -0.4, 0.5));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(j["Q"][i].get<double>(), Q[i], kPrintTol * 10.0);
}

TEST(FrictionToolTest, TableIsReadable) {
  const auto run =
      runTool(PATCHSPIN_TOOL, "friction --patch poly:0,0,0.1,0,0.05,0.08 --model exact --w 0,0,1");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("Px"), std::string::npos);
  EXPECT_NE(run.out.find("Tz"), std::string::npos);
  EXPECT_NE(run.out.find("Eq. (16)"), std::string::npos);
}

TEST(FrictionToolTest, BadArgumentsGiveOneLineErrorAndNonZeroExit) {
  const char* bad[] = {
      "friction --patch disk:-1 --w 1,0,0",                   // negative radius
      "friction --patch poly:0,0,0,1,1,0 --w 1,0,0",          // clockwise polygon
      "friction --patch disk:0.05 --w 0,0,0",                 // zero slip direction
      "friction --patch disk:0.05 --w 1,0",                   // wrong count
      "friction --patch disk:0.05 --w 1,x,0",                 // not a number
      "friction --patch disk:0.05 --loads 10,5,0 --w 1,0,0",  // tips: not admissible
      "friction --patch rect:0.1,0.1 --hertz 3 --w 1,0,0",    // Hertz needs a disk
      "friction --patch disk:0.05 --mu -1 --w 1,0,0",         // negative mu
      "friction --patch blob:1 --w 1,0,0",                    // unknown shape
      "friction --patch cut:0.05,-0.05 --w 1,0,0",            // nothing left of the disk
      "friction --patch cut:-1,0 --w 1,0,0",                  // negative radius
      "friction --patch lens:0.05,0.05,0.2 --w 1,0,0",        // disks apart
  };
  for (const char* args : bad) {
    const auto run = runTool(PATCHSPIN_TOOL, args);
    EXPECT_NE(run.exitCode, 0) << args;
    EXPECT_FALSE(run.err.empty()) << args;
    // one line: a single newline at the end
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << args << ": " << run.err;
  }
}

}  // namespace
}  // namespace patchspin
