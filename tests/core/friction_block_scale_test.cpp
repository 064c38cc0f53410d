// The friction block far from unit scale (friction_block.cpp's unit-scale path): the
// block is homogeneous (K -> a K, b -> c b, L -> (c / a) L scale s by c and
// lambda by c / a), so every case is checked against the law itself at the
// returned slip, or against b + K lambda = 0 for a stick.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "error_matchers.hpp"
#include "oracle.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace patchspin {
namespace {

// fuzz round 3, items 23, 26, 27, 28 and 35
// b, K and L from 1e-180 to 1e300, |b| = 8.8e223 with a stale warm start,
// det K = inf: slips are the law at their slip and sticks stop the slip, each
// comparison divided by the scale first; or an Error naming the range.
TEST(FrictionBlockScale, FarFromUnitScaleIsTheLaw) {
  const PatchShape disk = PatchShape::disk(0.5);
  const FrictionPatch patch(disk, LinearPressure::uniform(disk, 1.0), 0.5, 0.0);
  // the law's round-off on a uniform disk, with room for the solver's 1e-14
  constexpr double kLawTol = 1e-12;
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    // slips: L far below |b| / |K|
    FrictionBlockInput in;
    in.b = Vec3(1e-170, 0.0, 1e-170);
    in.L = 1e-180;
    FrictionBlockResult r = solveFrictionBlock(patch, model, in);
    ASSERT_FALSE(r.sticking);
    EXPECT_LT((r.impulse / in.L - patch.unitQ(model, r.slip)).norm(), kLawTol);
    EXPECT_LT(((r.slip - in.b - in.K * r.impulse) / 1e-170).norm(), kLawTol);
    // sticks: -K^-1 b = -b well inside L E (L = 1, the set's force radius)
    in.b = Vec3(1e-170, 0.0, 0.0);
    in.L = 1.0;
    r = solveFrictionBlock(patch, model, in);
    ASSERT_TRUE(r.sticking);
    EXPECT_LT(((r.impulse + in.b) / 1e-170).norm(), kLawTol);
    // K = 1e-160 I: positive definite, slips with impulse L q(s^)
    in.b = Vec3(1.0, 0.0, 1.0);
    in.L = 1e-10;
    in.K = 1e-160 * Mat3::Identity();
    r = solveFrictionBlock(patch, model, in);
    ASSERT_FALSE(r.sticking);
    EXPECT_LT((r.impulse / in.L - patch.unitQ(model, r.slip)).norm(), kLawTol);
  }
  // K = 1e300 I and L = 1e300 against |b| = 0.5: sticks with lambda = -K^-1 b
  // (L K Pi overflowed: refused before; at unit scale with L clamped to keep
  // |L K Pi| in range, b first underflowed to 0 and the block stuck with a
  // zero impulse, found by fuzzing the unit-scale path)
  // (fifth round: on the uniform disk; the fuzz input's patch, rho = 1e-8
  // on a 0.5 m disk with a negative couple, is outside the block's domain
  // now, and the bug was in the scale of b, K and L)
  const FrictionPatch& lever = patch;
  FrictionBlockInput stiff;
  stiff.b = Vec3(1e-8, 0.5, 1e-300);
  stiff.L = 1e300;
  stiff.K = 1e300 * Mat3::Identity();
  stiff.warmSlip = Vec3(1e300, 6e-310, 0.0);
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(lever, model, stiff);
    ASSERT_TRUE(r.sticking);
    EXPECT_LT((stiff.b + stiff.K * r.impulse).norm(), kLawTol * stiff.b.norm());
  }
  // |b| = 1e300 against L |K| = 1.6e-9 with a warm start along x: the block
  // kept the warm start's q (0.77 of the set off the law at the slip, which
  // is b's direction to 1e-308); now the law at b's direction (found by
  // fuzzing)
  FrictionBlockInput huge;
  huge.b = Vec3(1e-8, 1e300, 1e-8);
  huge.L = 0.5;
  huge.K = 3.2233629197666603e-09 * Mat3::Identity();
  huge.warmSlip = Vec3(0.5, 1e-8, 1e-8);
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(patch, model, huge);
    ASSERT_FALSE(r.sticking);
    EXPECT_LT((r.impulse / huge.L - patch.unitQ(model, r.slip)).norm(), kLawTol);
  }
  // det K = inf (entries 6e17 to 1.2e148, a diagonal spanning 2e130): K^-1
  // came out 0 and the exact block stuck with a zero impulse against
  // b = (0, 0, 2.8e-4), so b + K lambda = b != 0 (found by fuzzing). Now an
  // Error, or a stick with b + K lambda = 0 to round-off, or a slip
  FrictionBlockInput overflowing;
  overflowing.b = Vec3(0.0, 0.0, 0.00027956068515777588);
  overflowing.L = 2.2204460492503131e-16;
  overflowing.K << 6.0026327207929446e+17, 2.432376922470289e+58, 7.7476659200000002,
      2.432376922470289e+58, 1.2000001427493119e+148, 1.0954451801661788e+66, 7.7476659200000002,
      1.0954451801661788e+66, 1.2241048138797834e+148;
  try {
    const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, overflowing);
    const Vec3 residual = overflowing.b + overflowing.K * r.impulse - r.slip;
    EXPECT_LT(residual.stableNorm(),
              kLawTol * (overflowing.b.norm() +
                         internal::stableMatrixNorm(overflowing.K) * r.impulse.stableNorm()));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
  // |b| = 8.8e223 (|b|^2 overflows; refused before) with a stale warm start
  // 1e88 times shorter: at unit scale the ellipsoidal root search began at
  // r = 1e-88, where |N(r)| underflowed, and returned a zero impulse (found
  // by fuzzing the unit-scale path). Slips with the law at its slip.
  const PatchShape offset = PatchShape::disk(1.0, Vec2(1.0, 1.0));
  // (fifth round: the uniform pressure; the fuzz input's loads (0.5, 0.5,
  // 0.5) are negative on part of the disk, outside the block's domain now)
  const FrictionPatch tilted(offset, LinearPressure::fromLoads(offset, {0.5, -0.5, 0.5}), 0.5, 0.5);
  FrictionBlockInput far;
  far.b = Vec3(8.2454865162493023e+136, 8.8001147761699866e+223, 1.0);
  far.L = 1.0;
  far.warmSlip = Vec3(2.8177690084182086e-202, 4.0132898972871156e+135, 1.0);
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(tilted, model, far);
    ASSERT_FALSE(r.sticking);
    EXPECT_LT((r.impulse / far.L - tilted.unitQ(model, r.slip)).norm(),
              kLawTol * tilted.Pi().norm());
  }
}

// fuzz round 4, item 37
// A free slip of 1.1e74 against L |K| = 0.25: both laws slip with
// s = b + K lambda and lambda = L q(s^), not a zero impulse.
TEST(FrictionBlockScale, HugeFreeSlipIsTheLawAtItsSlip) {
  const PatchShape disk = PatchShape::disk(1.0, Vec2(1.0, 1.0));
  // (fifth round: the uniform pressure, Tx = -Pz y_c, Ty = Pz x_c; the
  // fuzz input's loads (1, 1, 1) are negative on part of the disk, outside
  // the block's domain now, and the bug was in the scale of b)
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, {1.0, -1.0, 1.0}), 1.0, 1.0);
  ASSERT_GE(minPressure(disk, patch.pressure()), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(184.71875, 1.106409418319547e+74, 0.5);
  in.L = 0.5;
  in.K << 0.50000268673971981, -4.2896462844848639e-12, 2.0000000000000002e-16,
      -4.2896462844848639e-12, 0.50000146447053262, 1.2101631028747559e-11, 2.0000000000000002e-16,
      1.2101631028747559e-11, 0.50000000000000022;
  in.warmSlip = Vec3(0.5, 1e-8, 1e-8);
  // the law's round-off at an ordinary disk, with room for the solver's 1e-14
  constexpr double kLawTol = 1e-12;
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
    ASSERT_FALSE(r.sticking);
    // |lambda| ~ L |q| ~ 1 cannot move a slip of 1e74: s = b to round-off
    EXPECT_LT((r.slip - in.b - in.K * r.impulse).norm(), kLawTol * in.b.norm());
    const Vec3 q = patch.unitQ(model, r.slip);
    ASSERT_GT(q.norm(), 0.1);  // the law has a size here: not the zero impulse
    EXPECT_LT((r.impulse / in.L - q).norm(), kLawTol * q.norm());
  }
}

// fuzz round 4, item 39
// b = 1.1e74 against L = 1e-8 scaled to unit size: the ellipsoidal block slips
// inside |lambda| <= L |Pi|_F with the law q = -Pi s^, not a false stick.
TEST(FrictionBlockScale, EllipsoidalWithATinyLDoesNotStick) {
  const PatchShape speck = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  // (fifth round: the uniform pressure of the fuzz input's Pz; its couple
  // left p negative on part of the speck, outside the block's domain now,
  // and the bug was in the scale of L)
  const double Pz = 1.106355352524917e+74;
  const FrictionPatch patch(speck, LinearPressure::fromLoads(speck, {Pz, -Pz * 1e-8, Pz * 1e-8}),
                            1e-8, 1e-8);
  ASSERT_GE(minPressure(speck, patch.pressure()), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(1e-08, 0.5, 1.130272745509552e+74);
  in.L = 1e-8;
  in.K = Mat3::Constant(3.0000000000000004e-16);
  in.K.diagonal().setConstant(1.00000003e-08);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Ellipsoidal, in);
  ASSERT_FALSE(r.sticking);
  // the ellipsoidal set |lambda| <= L |Pi|_F and the law q = -Pi s^, to the
  // round-off of a few 3x3 products (1e-12)
  constexpr double kTol = 1e-12;
  EXPECT_LE(r.impulse.norm(), in.L * patch.Pi().norm() * (1.0 + kTol));
  EXPECT_LT((r.impulse / in.L - patch.unitQ(Model::Ellipsoidal, r.slip)).norm(),
            kTol * patch.Pi().norm());
}

// fuzz round 2, item 18
// |b| = 8e230: the impulse is the law at the returned slip (b's direction),
// to kLawTol of L times the set's size.
TEST(FrictionBlockScale, ExactWithAFreeSlipOf1e230IsTheLawAtItsSlip) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  // (fifth round: the fuzz input's rho = 1e-8, a lever of 5e7, is outside
  // the block's domain now; the longest lever inside it, 1e5, instead)
  const double kRhoAtMaxLever = disk.maxDistanceFromOrigin() / 1e5;
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(
          disk, {9.860043733131926e+299, -3.0247296913024801e+297, 1.2321343576385495e+299}),
      0.5, kRhoAtMaxLever);
  FrictionBlockInput in;
  in.b = Vec3(1e-08, 8.0428159874152501e+230, 0.5);
  in.L = 0.5;
  in.K = Vec3(1e-8, 1e-8, 1e-8).asDiagonal();
  in.warmSlip = Vec3(0.5, 0.5, 0.5);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
  ASSERT_FALSE(r.sticking);
  // the slip's direction is b's to ~1e-238, so the law at it is known to
  // round-off of q: 1e-12 of L times the set's size (1 + max|r| / rho)
  constexpr double kLawTol = 1e-12;
  const double setSize = 1.0 + disk.maxDistanceFromOrigin() / patch.rho();
  EXPECT_LT((r.impulse - in.L * patch.unitQ(Model::Exact, r.slip)).norm(),
            kLawTol * in.L * setSize);
}

}  // namespace
}  // namespace patchspin
