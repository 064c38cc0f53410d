// The friction block's domain (friction_block.hpp): what solveFrictionBlock refuses,
// by name (a bad K, a negative pressure, a lever max|r| / rho outside
// [1e-5, 1e5], K's diagonal spanning more than 1e30), its documented
// fallbacks, and the law at its slip everywhere inside the domain.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "error_matchers.hpp"
#include "oracle.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::throwsNaming;

constexpr double kPi = 3.14159265358979323846;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// fuzz round 1, item 9
// An indefinite K, a NaN warm start, an infinite bound L: an Error naming it.
// L = 0 gives no friction (slip = b, zero impulse); b = 0 sticks with a zero
// impulse.
TEST(FrictionBlock, RefusesBadInputAndFallsBackWithoutFriction) {
  const PatchShape disk = PatchShape::disk(0.05);
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, {10.0, 0.05, 0.0}), 0.5);
  FrictionBlockInput in;
  in.b = Vec3(1.0, 1.0, 1.0);
  in.L = 1.0;
  // an indefinite K: the ellipsoidal path gave a NaN impulse (found by fuzzing)
  in.K = Vec3(-1.0, 0.0, 0.0).asDiagonal();
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, model, in); }, {"positive definite"}));
  }
  in.K = Mat3::Identity();
  in.warmSlip = Vec3(kNan, 0.0, 0.0);
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); }, {"warm"}));
  in.warmSlip.setZero();
  in.L = kInf;
  EXPECT_TRUE(
      throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); }, {"bound l"}));
  // documented fallbacks: no normal impulse, no friction (slip = b, sticking
  // only if b = 0, also for a denormal b whose |b|^2 underflows)
  in.L = 0.0;
  in.b = Vec3(1.6e-319, 0.0, 0.0);
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
    EXPECT_FALSE(r.sticking);
    EXPECT_EQ(r.slip, in.b);
    EXPECT_EQ(r.impulse, Vec3::Zero());
  }
  // at rest: stick with zero impulse
  in.L = 1.0;
  in.b.setZero();
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
    EXPECT_TRUE(r.sticking);
    EXPECT_EQ(r.impulse, Vec3::Zero());
  }
}

// fuzz round 4, item 38
// K must be SPD: an asymmetric K is refused for both laws; one ulp of asymmetry
// is accepted, and its stick has b + K lambda = 0 to round-off.
TEST(FrictionBlock, RefusesAnAsymmetricK) {
  const PatchShape disk = PatchShape::disk(0.5);
  const FrictionPatch patch(disk, LinearPressure::uniform(disk, 1.0), 0.5, 0.0);
  FrictionBlockInput in;
  in.b = Vec3(-9.3299951151919497e-223, 0.0, 0.0);
  in.L = 1e-8;
  in.K << 0.5, 0.00021065026521682739, 1e-08, 0.5, 0.5, 0.5, 0.5, 1e-08, 0.5;
  in.warmSlip = Vec3(0.5, 0.5, 0.5);
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, model, in); }, {"symmetric"}));
  }
  // one ulp of asymmetry: solved, and a stick has b + K lambda = 0 to round-off
  FrictionBlockInput nearly;
  nearly.b = Vec3(0.1, 0.05, 0.0);
  nearly.L = 1.0;
  nearly.K << 1.0, 0.25, 0.0, std::nextafter(0.25, 1.0), 1.0, 0.0, 0.0, 0.0, 1.0;
  // the stick residual: a few ulps of |K| |lambda| (~0.1)
  constexpr double kStickTol = 1e-14;
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(patch, model, nearly);
    ASSERT_TRUE(r.sticking);
    EXPECT_LT((nearly.b + nearly.K * r.impulse).norm(), kStickTol);
  }
}

// fuzz round 5, item 45
// K must be positive definite on every path, also where L |K| is below
// 2^-1022 of |b|.
TEST(FrictionBlock, WithNegligibleFrictionRefusesAnIndefiniteK) {
  const PatchShape disk = PatchShape::disk(1.6624690033495426e-06, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(
          disk, {0.0041942096751453693, 1.1958354410194534e-09, 1.2693800097189958e-09}),
      0.5, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-08, 0.023433685302734375, 2.8527919536056827e+180);
  in.L = 4.9406564584124654e-324;
  in.K = Vec3(-0.09902191162109375, -0.07080841064453125, 0.00067901611328125).asDiagonal();
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, model, in); }, {"positive definite"}));
  }
}

// fuzz round 5 (the block's domain)
// A pressure negative beyond 1e-6 of its mean is refused by both laws; just
// inside the edge it is solved, and every pressure nearestAdmissibleLoads
// returns is inside.
TEST(FrictionBlock, RefusesANegativePressure) {
  const PatchShape sliver = PatchShape::polygon({{-2.5000000000000001e-09, -0.24999999000000006},
                                                 {7.500000000000001e-09, -0.24999998999999995},
                                                 {2.5000000000000001e-09, 0.25000001000000005},
                                                 {-7.500000000000001e-09, 0.25000000999999994}});
  const FrictionPatch tipped(
      sliver, LinearPressure::fromLoads(sliver, {1e-8, 4.9406564584124654e-324, 1.0}), 1e-8, 0.5);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 0.5;
  in.K = Vec3(1e-8, 456416.0, 0.5).asDiagonal();
  in.warmSlip = Vec3(1e-8, 4.9406564584124654e-324, 0.0);
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(
        throwsNaming([&] { solveFrictionBlock(tipped, model, in); }, {"pressure is negative"}));
  }
  // the edge, on a unit disk at O: p = p0 + cx x has its minimum p0 - cx
  // (R = 1) by construction, mean p0 = Pz / A
  const PatchShape disk = PatchShape::disk(1.0);
  const double p0 = 1.0 / kPi;
  auto withMinimum = [&](double relative) {  // min p = relative * p0
    return FrictionPatch(disk, LinearPressure{p0, p0 * (1.0 - relative), 0.0}, 0.5, 0.0);
  };
  FrictionBlockInput ordinary;
  ordinary.b = Vec3(1.0, 0.5, 0.25);
  ordinary.L = 0.5;
  constexpr double kJustInside = -0.5e-6, kJustOutside = -2e-6;  // the domain's edge is -1e-6
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_NO_THROW(solveFrictionBlock(withMinimum(kJustInside), model, ordinary));
    EXPECT_TRUE(
        throwsNaming([&] { solveFrictionBlock(withMinimum(kJustOutside), model, ordinary); },
                     {"pressure is negative"}));
  }
  // nearestAdmissibleLoads' projections, of loads tipping far out, on a disk
  // and on a polygon (deterministic angles)
  const PatchShape hexagon = PatchShape::regularPolygon(6, 0.3, Vec2(0.1, -0.05));
  for (const PatchShape& shape : {disk, hexagon}) {
    for (int i = 0; i < 24; ++i) {
      // centre of pressure 0.3 to 1.2 times max|r| from O: mostly outside
      // the kern (a quarter of the radius on the disk)
      const double angle = 2.0 * kPi * i / 24.0,
                   reach = 0.3 * (1 + i % 4) * shape.maxDistanceFromOrigin();
      const PatchLoads raw{1.0, -reach * std::sin(angle), reach * std::cos(angle)};
      const PatchLoads loads = nearestAdmissibleLoads(shape, raw, shape.defaultRho());
      ASSERT_GT(loads.Pz, 0.0);
      const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), 0.5, 0.0);
      for (Model model : {Model::Exact, Model::Ellipsoidal}) {
        EXPECT_NO_THROW(solveFrictionBlock(patch, model, ordinary))
            << "loads " << i << " " << toString(model);
      }
    }
  }
}

// fuzz round 3, item 34 (since round 5 outside the domain)
// A couple of 6e228 on a 0.5 m disk leaves the pressure almost all negative:
// both laws refuse it, naming the pressure.
TEST(FrictionBlock, BothLawsRefuseAnAlmostAllNegativePressure) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const LinearPressure pressure =
      LinearPressure::fromLoads(disk, {0.5, -14630256640.0, 5.9567624915341203e+228});
  const FrictionPatch patch(disk, pressure, 2.2204460492503131e-16, 0.0);
  ASSERT_LT(minPressure(disk, pressure), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 1e-8;
  in.K = Vec3(0.5, 220.71875, 1e-8).asDiagonal();
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(
        throwsNaming([&] { solveFrictionBlock(patch, model, in); }, {"pressure is negative"}));
  }
}

// fuzz round 5 (the block's domain)
// A lever max|r| / rho outside [1e-5, 1e5] is refused by both laws, naming
// the lever; levers 1% inside either edge are solved.
TEST(FrictionBlock, RefusesALeverOutsideItsDomain) {
  const PatchShape triangle = PatchShape::polygon({{0.0, 1e-8}, {1e-8, 1e-8}, {1e-8, 0.5}});
  const FrictionPatch longLever(
      triangle,
      LinearPressure::fromLoads(
          triangle, {1.5039998458623872e-07, -1.8799999201279856e-08, 1.1279998843967906e-15}),
      0.5, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(2.2250738585072014e-308, 1e-08, 27.607421875);
  in.L = 0.5;
  // (the fuzz input's K, whose diagonal spans 1e36, is refused for that
  // first now; any K will do here: the lever alone is refused)
  in.K = Mat3::Identity();
  const PatchShape speck = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  const FrictionPatch shortLever(
      speck,
      LinearPressure::fromLoads(
          speck, {0.082551611533770858, -6.680727410960975e-10, 9.5894732401865139e-10}),
      0.5, 0.5);
  FrictionBlockInput kink;
  kink.b = Vec3(1e-08, 0.5, 0.5);
  kink.L = 1e-8;
  kink.K << 7633478.7669410771, 7633578.4965439122, 3284467.8871689122, 7633578.4965439122,
      22900435.296875, 18551324.1875, 3284467.8871689122, 18551324.1875, 16680083.59375;
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(longLever, model, in); }, {"lever"}));
    EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(shortLever, model, kink); }, {"lever"}));
  }
  const PatchShape disk = PatchShape::disk(0.5, Vec2(0.1, 0.0));
  FrictionBlockInput ordinary;
  ordinary.b = Vec3(1.0, 0.5, 0.25);
  ordinary.L = 0.5;
  constexpr double kInside = 0.99;
  for (double lever : {1e5 * kInside, 1e-5 / kInside}) {
    const FrictionPatch patch(disk, LinearPressure::uniform(disk, 1.0), 0.5,
                              disk.maxDistanceFromOrigin() / lever);
    for (Model model : {Model::Exact, Model::Ellipsoidal}) {
      EXPECT_NO_THROW(solveFrictionBlock(patch, model, ordinary))
          << "lever " << lever << " " << toString(model);
    }
  }
}

// fuzz round 1, item 10 (since round 5 outside the domain)
// The exact block with a lever of 5e7 is refused, naming the lever.
TEST(FrictionBlock, ExactRefusesALongLever) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const PatchLoads loads{2.271553102614555e-08, 2.0077880525071972e-09, 2.0077884542030355e-09};
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, loads), 1e-8, 1e-8);
  ASSERT_GE(minPressure(disk, patch.pressure()), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(0.5, -524288.0, 1e-8);
  in.L = 1e-8;
  in.K = Vec3(1e-8, 1e-8, 0.5).asDiagonal();
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"lever"}));
}

// fuzz round 2, item 11 (since round 5 outside the domain)
// The ellipsoidal block with a lever of 5e7 and an ill-scaled K is refused,
// naming the lever.
TEST(FrictionBlock, EllipsoidalRefusesALongLever) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, {0.5, 0.5, 0.5}), 1e-8, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, -1.0);
  in.L = 1e-8;
  in.K = Vec3(1e-8, 0.5, 28835840.0).asDiagonal();
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); }, {"lever"}));
}

// fuzz round 2, item 17 (since round 5 outside the domain)
// A lever of 1e8 (O on the rim), where the block once stuck outside its limit
// set, is refused, naming the lever.
TEST(FrictionBlock, ExactRefusesALongLeverWithOOnTheRim) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(0.5, 1e-8));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(
          disk, {0.34742866443796361, -9.2650840233638689e-10, 0.13028574916423646}),
      1e-8, 1e-8);
  ASSERT_GE(minPressure(disk, patch.pressure()), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 1e-8;
  in.K = Vec3(0.5, 0.5, 9701425152.0).asDiagonal();
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"lever"}));
}

// fuzz round 2, item 17 (since round 5 outside the domain)
// A lever of 5e7 whose every separating direction lies in the force plane is
// refused, naming the lever.
TEST(FrictionBlock, ExactRefusesALongLeverWithASlipInTheForcePlane) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(
          disk, {2.271553102614555e-08, 2.0077880525071972e-09, 2.0077884542030355e-09}),
      0.5, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 0.5;
  in.K = Vec3(1e-8, 1e-8, 1e-8).asDiagonal();
  in.warmSlip = Vec3(0.5, 0.5, 0.5);
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"lever"}));
}

// fuzz round 3, item 25 (since round 5 outside the domain)
// A lever of 5e7 with K = diag(1e-8, 0.5, 7.4e9) is refused, naming the lever.
TEST(FrictionBlock, ExactRefusesALongLeverWithAStiffSpin) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, {0.5, 0.5, 0.5}), 1e-8, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-300, -1.0);
  in.L = 1e-8;
  in.K = Vec3(1e-8, 0.5, 7410810880.0).asDiagonal();
  in.warmSlip = Vec3(1e-8, 0.0, 0.0);
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"lever"}));
}

// fuzz round 4, item 41 (since round 5 outside the domain)
// A Pi of 1e281 needs an almost all negative pressure (here also a lever of
// 1.5e8 and a K diagonal spanning 8e35): refused, naming one of them.
TEST(FrictionBlock, EllipsoidalRefusesAHugePiOutsideTheDomain) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(1.0, 0.0));
  const double tiny = std::numeric_limits<double>::min();
  const FrictionPatch patch(disk,
                            LinearPressure::fromLoads(disk, {1e-08, 4.4207816532197203e+262, tiny}),
                            14821621760.0, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(tiny, tiny, tiny);
  in.L = tiny;
  in.K << 36917776.0, 4.508515560323756e-225, -9.3386817376370605e-309, 4.508515560323756e-225,
      1.5246092141020473e+20, 123.47506688, -9.3386817376370605e-309, 123.47506688,
      2.0000000000000002e-16;
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); },
                           {"lever", "pressure", "diagonal of K spans"}));
}

// fuzz round 5 (the block's domain)
// K's diagonal spanning more than 1e30 is refused by both laws, naming it; a
// span of 0.99e30 is solved, to the law at its slip (kLawSlack of L set).
TEST(FrictionBlock, RefusesAKDiagonalSpanningMoreThan1e30) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(0.3, -0.2));
  const FrictionPatch patch(disk, LinearPressure::uniform(disk, 1.0), 0.5, 0.0);
  FrictionBlockInput in;
  in.b = Vec3(-8.8212188532448897e-10, 1.790965336840594e-11, -66485.869428073769);
  in.L = 1.7318663946363179e-05;
  in.K << 1.6397902928135056e-14, 2.3559521313631101e-18, 22.498146681802975,
      2.3559521313631101e-18, 9.9999999999999998e-20, 0.087759323871331368, 22.498146681802975,
      0.087759323871331368, 1.0000000000000002e+19;
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    EXPECT_TRUE(
        throwsNaming([&] { solveFrictionBlock(patch, model, in); }, {"diagonal of K spans"}));
  }
  // just inside: K = diag(1, 1, 0.99e30)^(1/2) C diag(...)^(1/2) with C's
  // off-diagonals 0.3 and 0.2
  const Vec3 root(1.0, 1.0, std::sqrt(0.99e30));
  Mat3 C = Mat3::Identity();
  C(0, 2) = C(2, 0) = 0.3;
  C(0, 1) = C(1, 0) = 0.2;
  FrictionBlockInput inside;
  inside.K = root.asDiagonal() * C * root.asDiagonal();
  inside.b = Vec3(1.0, -0.5, 1e31);  // (a free spin slip beyond L K_zz set: slips)
  inside.L = 0.3;
  constexpr double kLawSlack = 1e-6;  // the fuzz target's
  for (Model model : {Model::Exact, Model::Ellipsoidal}) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(patch, model, inside);
    const double set = model == Model::Exact ? 1.0 + disk.maxDistanceFromOrigin() / patch.rho()
                                             : patch.Pi().norm();
    // (a slip long enough for its direction to be resolved, as the fuzz
    // target checks: |s| > 1e-2 of the slip scale |b| + L |K| set)
    ASSERT_FALSE(r.sticking);
    ASSERT_GT(r.slip.norm(), 1e-2 * (inside.b.norm() + inside.L * inside.K.norm() * set));
    EXPECT_LT((r.impulse - inside.L * patch.unitQ(model, r.slip)).norm(),
              kLawSlack * inside.L * set);
  }
}

// fuzz round 5 (the block's domain)
// Hard blocks at levers 1e-5 to 1e5 (spin near the law's turn from force to
// torque, seeded): where the slip's direction is resolved (|s| > 1e-2 of the
// slip scale), the impulse is L q(s^) to kLawSlack of L set.
TEST(FrictionBlock, IsTheLawAtItsSlipAcrossTheLeverDomain) {
  constexpr double kLawSlack = 1e-6;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const std::vector<PatchShape> shapes = {PatchShape::disk(0.5),
                                          PatchShape::disk(0.5, Vec2(0.3, -0.2)),
                                          PatchShape::rectangle(1.0, 0.2)};
  int checked = 0;
  // (the domain's edges 1% inside: rho = max|r| / 1e5 rounds to a lever
  // of 1e5 (1 + 1e-16), refused)
  for (double lever : {1.01e-5, 1e-3, 1.0, 1e3, 0.99e5}) {
    for (int k = 0; k < 60; ++k) {
      const PatchShape& shape = shapes[k % 3];
      const PatchLoads loads = nearestAdmissibleLoads(
          shape, {1.0, 0.3 * uniform(rng), 0.3 * uniform(rng)}, shape.defaultRho());
      const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), 0.5,
                                shape.maxDistanceFromOrigin() / lever);
      Mat3 A;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(i, j) = uniform(rng);
      FrictionBlockInput in;
      in.K = k % 2 ? Mat3(A * A.transpose() + 0.3 * Mat3::Identity()) : Mat3(Mat3::Identity());
      in.L = std::pow(10.0, -4.0 + 3.0 * (1.0 + uniform(rng))) / lever;
      const double spin = std::pow(10.0, -3.0 + 3.0 * (1.0 + uniform(rng))) / lever;
      const double angle = kPi * uniform(rng);
      in.b = Vec3(std::cos(angle), std::sin(angle), uniform(rng) > 0.0 ? spin : -spin);
      for (Model model : {Model::Exact, Model::Ellipsoidal}) {
        const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
        const double set = model == Model::Exact ? 1.0 + lever : patch.Pi().norm();
        const double slipScale = in.b.norm() + in.L * in.K.norm() * set;
        if (r.sticking || !(r.slip.norm() > 1e-2 * slipScale)) continue;
        ++checked;
        EXPECT_LT((r.impulse - in.L * patch.unitQ(model, r.slip)).norm(), kLawSlack * in.L * set)
            << "lever " << lever << ", block " << k << ", " << toString(model);
      }
    }
  }
  EXPECT_GT(checked, 300);  // the checks above say something
}

}  // namespace
}  // namespace patchspin
