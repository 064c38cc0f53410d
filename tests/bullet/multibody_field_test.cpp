// The multibody world benchmark's fields (scenes/multibody_field.hpp,
// bench/bench_bullet_multibody.cpp) are what they claim: 100 grippers whose
// cubes hold against their twist, 100 feet that do not spin under theirs,
// every pad and foot a patch, under the patch law (exact and ellipsoidal);
// stock btMultiBodyConstraintSolver's figures printed beside them.
#include <patchspin/scenes/mean_distance.hpp>
#include <patchspin/scenes/multibody_field.hpp>

#include "oracle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace patchspin::scenes {
namespace {

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr int kN = 100;  // the benchmark's field size

TEST(MultiBodyField, MeanDistanceOfRectangleMatchesQuadrature) {
  // the midpoint rule's error is ~1e-6 relative here (smooth but at the
  // centre); 1e-5 leaves room and still catches a wrong term (each log term
  // is >= 10 % of the total for these shapes)
  for (const auto& [a, b] : {std::pair{0.02, 0.02}, {0.08, 0.04}, {0.04, 0.08}, {0.1, 0.01}})
    EXPECT_NEAR(meanDistanceOfRectangle(a, b), testing::rectangleMeanDistance(a, b),
                1e-5 * testing::rectangleMeanDistance(a, b))
        << a << " x " << b;
  // the square's known closed form h (sqrt 2 + asinh 1) / 3
  EXPECT_NEAR(meanDistanceOfRectangle(0.02, 0.02), 0.02 * (std::sqrt(2.0) + std::asinh(1.0)) / 3,
              1e-12);
}

struct FieldRun {
  double turn = 0.0, slip = 0.0;
  int reports = 0;
};

FieldRun runField(MultiBodyFieldKind kind, SpeedVariant v) {
  MultiBodyField field(kind, kN, v);
  for (int k = 0; k < MultiBodyField::episodeSteps(); ++k) field.step();
  FieldRun run{field.largestTurn(), field.largestSlip(), 0};
  if (field.scene().patch()) run.reports = int(field.scene().solver().patchReports().size());
  return run;
}

// Held: each cube turns less than the 1e-4 rad (given there over
// 2 s; here the twist lasts 0.5 s) and moves less than 10 um in the pads'
// plane (a turn of 1e-4 rad moves the pad's edge 2 um; stock's cubes move
// centimetres); both pads of every gripper are patches.
TEST(MultiBodyField, EveryCubeOfTheGripperFieldHolds) {
  MultiBodyField probe(MultiBodyFieldKind::Grippers, kN, SpeedVariant::Stock);
  EXPECT_NEAR(probe.twist(), 0.5 * probe.limit(), 1e-12);
  const FieldRun stock = runField(MultiBodyFieldKind::Grippers, SpeedVariant::Stock);
  std::printf(
      "[grippers, %s] twist %.4f N m (half the grasp's limit): stock: largest turn %.3g "
      "rad, slip %.3g m\n",
      kDouble ? "double" : "float", probe.twist(), stock.turn, stock.slip);
  for (SpeedVariant v : {SpeedVariant::Exact, SpeedVariant::Ellipsoidal}) {
    const FieldRun run = runField(MultiBodyFieldKind::Grippers, v);
    std::printf("[grippers, %s] %s: largest turn %.3g rad, slip %.3g m, %d patches\n",
                kDouble ? "double" : "float", toString(v), run.turn, run.slip, run.reports);
    EXPECT_EQ(run.reports, 2 * kN) << toString(v);
    EXPECT_LT(run.turn, 1e-4) << toString(v);
    EXPECT_LT(run.slip, 1e-5) << toString(v);
  }
}

// Not spinning: each foot turns less than 1e-4 rad over the 0.5 s twist
// (the flat-foot test's bound) and is a patch.
TEST(MultiBodyField, NoFootOfTheFootFieldSpins) {
  MultiBodyField probe(MultiBodyFieldKind::Feet, kN, SpeedVariant::Stock);
  EXPECT_NEAR(probe.twist(), 0.8 * probe.limit(), 1e-12);
  const FieldRun stock = runField(MultiBodyFieldKind::Feet, SpeedVariant::Stock);
  std::printf("[feet, %s] twist %.4f N m (0.8 of the yaw limit): stock: largest turn %.3g rad\n",
              kDouble ? "double" : "float", probe.twist(), stock.turn);
  for (SpeedVariant v : {SpeedVariant::Exact, SpeedVariant::Ellipsoidal}) {
    const FieldRun run = runField(MultiBodyFieldKind::Feet, v);
    std::printf("[feet, %s] %s: largest turn %.3g rad, %d patches\n", kDouble ? "double" : "float",
                toString(v), run.turn, run.reports);
    EXPECT_EQ(run.reports, kN) << toString(v);
    EXPECT_LT(run.turn, 1e-4) << toString(v);
  }
}

}  // namespace
}  // namespace patchspin::scenes
