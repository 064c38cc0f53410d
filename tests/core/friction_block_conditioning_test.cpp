// The friction block with an ill-conditioned, badly scaled or numerically
// singular K (friction_block.cpp): a K singular to round-off is refused by name, and
// every answer is either inside the limit set with slip = b + K impulse, the
// law at its own slip to what double resolves there, a stick with
// b + K lambda = 0 to round-off, or the block solved in 50 digits.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "error_matchers.hpp"
#include "fuzz_inputs.hpp"
#include "oracle.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::throwsNaming;

// ---- 50 significant digits, for the ellipsoidal block (item 57) ----------
using Big = boost::multiprecision::cpp_bin_float_50;
using BigVec = std::array<Big, 3>;
using BigMat = std::array<BigVec, 3>;

BigMat toBig(const Mat3& m) {
  BigMat out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = Big(m(i, j));
  return out;
}
BigVec toBig(const Vec3& v) {
  return {Big(v[0]), Big(v[1]), Big(v[2])};
}
BigMat times(const BigMat& a, const BigMat& b) {
  BigMat out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return out;
}
BigVec times(const BigMat& a, const BigVec& v) {
  BigVec out;
  for (int i = 0; i < 3; ++i) out[i] = a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2];
  return out;
}
Big det(const BigMat& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}
// a^-1 v by Cramer's rule: with 50 digits, a condition number of 1e36
// (rI + L K Pi below) leaves 14
BigVec solve(const BigMat& a, const BigVec& v) {
  const Big d = det(a);
  BigVec out;
  for (int k = 0; k < 3; ++k) {
    BigMat ak = a;
    for (int i = 0; i < 3; ++i) ak[i][k] = v[i];
    out[k] = det(ak) / d;
  }
  return out;
}
Big norm(const BigVec& v) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// The ellipsoidal block of friction_block.hpp in its first form, (rI + A) w = b with
// A = L K Pi and |w| = 1, solved by bisection in r (no Newton, no
// reformulation, no scaling) in 50 digits; the impulse -L Pi w. Stick iff
// |A^-1 b| <= 1 (then the impulse is -K^-1 b).
struct BigBlock {
  bool sticking = false;
  Vec3 impulse = Vec3::Zero();
};
BigBlock solveEllipsoidalBig(const Mat3& Pi, const Mat3& K, const Vec3& b, double L) {
  const BigMat P = toBig(Pi), Kb = toBig(K);
  const BigVec bb = toBig(b);
  BigMat A = times(Kb, P);
  for (auto& row : A)
    for (Big& x : row) x *= Big(L);
  BigBlock out;
  auto wOf = [&](const Big& r) {
    BigMat M = A;
    for (int i = 0; i < 3; ++i) M[i][i] += r;
    return solve(M, bb);
  };
  if (norm(wOf(Big(0))) <= 1) {
    out.sticking = true;
    const BigVec lambda = solve(Kb, bb);
    out.impulse = -Vec3(double(lambda[0]), double(lambda[1]), double(lambda[2]));
    return out;
  }
  // |w(r)| decreases from |A^-1 b| > 1 to below 1 at r = |b| + |A|_F:
  // bisection, geometric over the decades, then plain
  Big aNorm = 0;
  for (const auto& row : A)
    for (const Big& x : row) aNorm += x * x;
  Big hi = norm(bb) + sqrt(aNorm), lo = hi * Big(1e-200);
  EXPECT_GT(norm(wOf(lo)), 1) << "the bracket's lower end is past the root";
  for (int it = 0; it < 2000 && hi - lo > hi * Big(1e-40); ++it) {
    const Big mid = hi > 4 * lo ? sqrt(lo * hi) : (lo + hi) / 2;
    (norm(wOf(mid)) > 1 ? lo : hi) = mid;
  }
  BigVec w = wOf(lo);
  const Big n = norm(w);
  for (Big& x : w) x /= n;
  const BigVec piW = times(P, w);
  out.impulse = -L * Vec3(double(piW[0]), double(piW[1]), double(piW[2]));
  return out;
}

// fuzz round 2, item 19
// K with entries 0.5 to 9.5e19: the impulse is inside |lambda| <= L |Pi|_F
// and slip = b + K impulse to kSlipSlack of the products.
TEST(FrictionBlockConditioning, EllipsoidalWithAnIllConditionedKStaysInTheSet) {
  const FrictionPatch patch = patchspin::testing::fuzzDodecagonPatch();
  FrictionBlockInput in;
  in.b = Vec3(0.5, 0.5, 0.5);
  in.L = 0.5;
  in.K << 0.5, 0.5, 4860674048.0, 0.5, 0.75, 4860674048.0, 4860674048.0, 4860674048.0,
      9.4504608803602825e+19;
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Ellipsoidal, in);
  // the ellipsoidal set: |lambda| <= L |Pi|_F, to round-off (1e-12)
  constexpr double kRoundOff = 1e-12;
  EXPECT_LE(r.impulse.norm(), in.L * patch.Pi().norm() * (1.0 + kRoundOff));
  // slip = b + K impulse to round-off of the products (1e-9 of the scale,
  // the fuzz target's kBoundSlack: a backward-stable solve meets it)
  constexpr double kSlipSlack = 1e-9;
  EXPECT_LE((r.slip - in.b - in.K * r.impulse).norm(),
            kSlipSlack * (in.b.norm() + in.K.norm() * r.impulse.norm()));
}

// fuzz round 3, items 21 and 29
// K with cond ~1e34 at unit diagonal: an Error naming the singular K (or
// K's diagonal span), or the law at its own slip (unitQ) to kLawTol.
TEST(FrictionBlockConditioning, NumericallySingularKIsRefusedOrTheLaw) {
  const PatchShape shape = PatchShape::polygon({{2e-08, 1.00000001e-08},
                                                {1.9766205535603823e-08, 1.2149704499772297e-08},
                                                {1.9075754154720659e-08, 1.4198891106360189e-08},
                                                {1.7960930596539016e-08, 1.6051742231546959e-08},
                                                {1.6473862771602071e-08, 1.7621620616014996e-08},
                                                {1.4684084318646699e-08, 1.8835120491301074e-08},
                                                {1.2675283288937209e-08, 1.9635499951945065e-08},
                                                {1.0541388986000835e-08, 1.9985334143925129e-08},
                                                {8.382179935789701e-09, 1.9868265209237061e-08},
                                                {6.2986183537031865e-09, 1.9289767161154098e-08},
                                                {4.3881292636072782e-09, 1.8276889925450199e-08},
                                                {2.7400450119987498e-09, 1.6876994515934688e-08},
                                                {1.4314281867687222e-09, 1.51555384860845e-08},
                                                {5.2346825624182251e-10, 1.3193015206594482e-08},
                                                {5.8620417644502455e-11, 1.1081190084825624e-08},
                                                {5.8620439268305649e-11, 8.9188097163467921e-09},
                                                {5.2346832010212787e-10, 6.806984603874884e-09},
                                                {1.4314282898794938e-09, 4.8444613425440653e-09},
                                                {2.7400451495386354e-09, 3.1230053388662202e-09},
                                                {4.3881294291450745e-09, 1.7231099623123909e-09},
                                                {6.2986185394985276e-09, 7.102327648182723e-10},
                                                {8.3821801331550051e-09, 1.3173475840654039e-10},
                                                {1.0541389185707508e-08, 1.4665866902652304e-11},
                                                {1.26752834816472e-08, 3.6450010156060337e-10},
                                                {1.4684084495349107e-08, 1.1648796023806164e-09},
                                                {1.6473862924034484e-08, 2.3783795134622653e-09},
                                                {1.7960930717573863e-08, 3.9482579276716577e-09},
                                                {1.9075754238698476e-08, 5.8011090751548926e-09},
                                                {1.9766205578597912e-08, 7.8502956955518106e-09}});
  const FrictionPatch patch(
      shape,
      LinearPressure::fromLoads(
          shape, {0.09269204466265292, -7.5064762499732558e-10, 1.0766479339077318e-09}),
      1e-8, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 1e-8;
  in.K << 3.0000000000000004e-16, 13.305774080000001, 2.0691215973347427e-16, 13.305774080000001,
      1.7704362386799985e+18, 0.91971635818481468, 2.0691215973347427e-16, 0.91971635818481468,
      2.0047777952181065e-16;
  // the law's round-off at this ordinary pressure (p > 0, a 2e-8 m 29-gon):
  // ~1e-14 of L times the set's size; 1e-6 as the fuzz target checks it
  constexpr double kLawTol = 1e-6;
  try {
    const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
    ASSERT_FALSE(r.sticking);
    const double setSize = 1.0 + shape.maxDistanceFromOrigin() / patch.rho();
    EXPECT_LT((r.impulse - in.L * patch.unitQ(Model::Exact, r.slip)).norm(),
              kLawTol * in.L * setSize);
  } catch (const Error& e) {
    // (fifth round: this K's diagonal spans 6e33, refused as out of range
    // before its condition is looked at)
    const std::string what = e.what();
    EXPECT_TRUE(what.find("singular") != std::string::npos ||
                what.find("diagonal of K spans") != std::string::npos)
        << what;
  }

  // the ellipsoidal block with K of entries 3e-16 to 9.9e19, whose y-z block
  // is singular once scaled to a unit diagonal (K_yz^2 = K_yy K_zz to 1e-10):
  // it slipped at (1e-8, 1.6e14, 1.4e19), driven by the impulse, 1.07 of
  // L |Pi| off the law q = -Pi s^ (found by fuzzing). Now an Error, or the law.
  const PatchShape disk = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  const FrictionPatch small(
      disk,
      LinearPressure::fromLoads(
          disk, {0.082551611533770858, -6.680727410960975e-10, 9.5894732401865139e-10}),
      1e-8, 1e-8);
  FrictionBlockInput ell;
  ell.b = Vec3(1e-8, 1e-8, 0.5);
  ell.L = 0.5;
  ell.warmSlip = Vec3(14936440832.0, -795.125, -0.38824462890625);
  ell.K << 3.2204460492503131e-16, 5.0000000000000001e-09, 2.2204460492503131e-24,
      5.0000000000000001e-09, 12713013504.25, 1119806363271168.0, 2.2204460492503131e-24,
      1119806363271168.0, 9.8636431938662957e+19;
  try {
    const FrictionBlockResult r = solveFrictionBlock(small, Model::Ellipsoidal, ell);
    ASSERT_FALSE(r.sticking);
    EXPECT_LT((r.impulse - ell.L * small.unitQ(Model::Ellipsoidal, r.slip)).norm(),
              kLawTol * ell.L * small.Pi().norm());
  } catch (const Error& e) {
    // (fifth round: this K's diagonal spans 3e35, refused as out of range)
    const std::string what = e.what();
    EXPECT_TRUE(what.find("singular") != std::string::npos ||
                what.find("diagonal of K spans") != std::string::npos)
        << what;
  }
}

// fuzz round 3, items 22 and 24
// A diagonal K spanning 6.6e138 is refused, naming its diagonal; spanning
// 6.6e28 it is the law at its slip to the slip's resolution (kResolutionUlps
// eps |K| L set / |s|); K_zz = 1.3e-306 gives the law or an Error.
TEST(FrictionBlockConditioning, ExactWithABadlyScaledKIsTheLawToItsResolution) {
  const PatchShape disk = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(
          disk, {0.082551611533770858, -6.680727410960975e-10, 9.5894732401865139e-10}),
      0.5, 1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 0.5);
  in.L = 0.5;
  in.K = Vec3(9701425152.0, 14943780864.0, 2.2739476699754749e-129).asDiagonal();
  in.warmSlip = Vec3(0.0, -0.0, 0.5);
  EXPECT_TRUE(
      throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"diagonal of K spans"}));
  in.K(2, 2) = 2.2739476699754749e-19;
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
  ASSERT_FALSE(r.sticking);
  const double set = 1.0 + disk.maxDistanceFromOrigin() / patch.rho();
  // a few ulps per term of the 3x3 products, times |J| <= set
  constexpr double kResolutionUlps = 64.0;
  const double resolution = kResolutionUlps * std::numeric_limits<double>::epsilon() * in.K.norm() *
                            in.L * set / r.slip.norm();
  ASSERT_LT(resolution, 1e-2);  // the check below still means something
  EXPECT_LT((r.impulse - in.L * patch.unitQ(Model::Exact, r.slip)).norm(), resolution * in.L * set);

  // K_zz = 1.3e-306 (a diagonal spanning 1e316): the slip's round-off along
  // z, weighed by K^-1 = 7.5e305, swamped every trial's potential, and the
  // block slipped at (-7.2e8, -3.1e8, 1e-8), 0.59 of the set off the law
  // there. Now an Error (K^-1 out of double's useful range), or the law.
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.K(2, 2) = 1.3350831721133898e-306;
  in.warmSlip.setZero();
  try {
    const FrictionBlockResult far = solveFrictionBlock(patch, Model::Exact, in);
    ASSERT_FALSE(far.sticking);
    const double farResolution = kResolutionUlps * std::numeric_limits<double>::epsilon() *
                                 in.K.norm() * in.L * set / far.slip.norm();
    EXPECT_LT((far.impulse - in.L * patch.unitQ(Model::Exact, far.slip)).norm(),
              farResolution * in.L * set);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

// fuzz round 4, item 40
// Sticks with an ill-conditioned K return lambda = -K^-1 b from a pivoted
// solve: b + K lambda is round-off of |K| |lambda| (kResidualTol).
TEST(FrictionBlockConditioning, StickWithAnIllConditionedKStopsTheSlip) {
  // backward-stable 3x3 solves: a few ulps of |K| |lambda| (and of |b|)
  constexpr double kResidualTol = 1e-13;
  auto checkStick = [&](const FrictionPatch& patch, Model model, const FrictionBlockInput& in) {
    SCOPED_TRACE(toString(model));
    const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
    if (r.sticking) {
      EXPECT_LT((in.b + in.K * r.impulse).norm(),
                kResidualTol * (in.b.norm() + in.K.norm() * r.impulse.norm()));
    } else {
      // a slip is the law at its slip
      const Vec3 q = patch.unitQ(model, r.slip);
      EXPECT_LT((r.impulse / in.L - q).norm(), 1e-6 * q.norm());
    }
    return r.sticking;
  };
  const PatchShape sliver = PatchShape::polygon({{7.500000000000001e-09, -0.24999999000000006},
                                                 {1.7500000000000001e-08, -0.24999998999999995},
                                                 {1.2500000000000003e-08, 0.25000001000000005},
                                                 {2.5000000000000001e-09, 0.25000000999999994}});
  const FrictionPatch thin(
      sliver,
      LinearPressure::fromLoads(
          sliver, {7.566666666666056e-07, -7.566666647221408e-15, 8.8277777777770622e-15}),
      0.5, -1.0);
  FrictionBlockInput a;
  a.b = Vec3(1e-08, 1e-08, 1e-08);
  a.L = 0.5;
  a.K = Mat3::Constant(19822410.75);
  a.K.diagonal().setConstant(19824981.25);
  a.warmSlip = Vec3(-13578.5, 1e-08, 1e-08);
  EXPECT_TRUE(checkStick(thin, Model::Ellipsoidal, a));

  const PatchShape speck = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  const FrictionPatch heavy(
      speck,
      LinearPressure::fromLoads(
          speck, {2.2967985926923795e+81, -2.1002768830563735e+73, 2.8363210237402899e+73}),
      1.0, 1e-8);
  FrictionBlockInput e;
  e.b = Vec3(1e-08, 1e-08, 1e-08);
  e.L = 1e-8;
  e.K << 2273843767050240.0, 2273843734555192.0, 2273843734555192.0, 2273843734555192.0,
      3410765633716224.0, 3410765599997952.0, 2273843734555192.0, 3410765599997952.0,
      3410765633716224.0;
  e.warmSlip = Vec3(-33718272.0, -33718272.0, -311623680.0);
  EXPECT_TRUE(checkStick(heavy, Model::Exact, e));

  const PatchShape disk = PatchShape::disk(0.5, Vec2(1e-8, 1e-8));
  const FrictionPatch tipped(
      disk,
      LinearPressure::fromLoads(disk, {1.0000000000000001e+300, 1e-08, 7.8861841068295186e+146}),
      0.00021254271268844604, 0.5);
  FrictionBlockInput z;
  z.b = Vec3(0.5, 0.5, 0.5);
  z.L = 0.5;
  z.K = Mat3::Constant(0.75);
  z.K.diagonal().setConstant(0.75000001000000005);
  z.warmSlip = Vec3(0.5, 0.5, 0.5);
  for (Model model : {Model::Exact, Model::Ellipsoidal}) checkStick(tipped, model, z);
}

// fuzz round 5, item 43
// A K singular to round-off whose leading minors pass: the ellipsoidal block
// refuses it as singular; the exact block refuses it or stops the slip to
// kResidual.
TEST(FrictionBlockConditioning, StickRefusesAKSingularToRoundOff) {
  const PatchShape triangle = PatchShape::polygon({{-74743808.000000015, 119242751.99999999},
                                                   {0.49999999000000001, -74743808.000000015},
                                                   {0.0, 116387839.99999999}});
  const FrictionPatch patch(
      triangle,
      LinearPressure::fromLoads(
          triangle, {8.2967671213372529e-09, -0.17867705275273596, -0.15503299011029428}),
      1e-8, 0.0);
  FrictionBlockInput in;
  in.b = Vec3(0.0, 0.5, 0.5);
  in.L = 1e-8;
  in.K << 2.196804715965055e+20, -7770798429306880.0, 1.5980646969869599e+20, -7770798429306880.0,
      274877906948.37549, -5652864156303360.0, 1.5980646969869599e+20, -5652864156303360.0,
      1.162511513743786e+20;
  EXPECT_TRUE(
      throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); }, {"singular"}));
  // the exact block: refused as well, or a stick that stops the slip
  constexpr double kResidual = 1e-10;
  try {
    const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
    if (r.sticking) {
      EXPECT_LE((in.b + in.K * r.impulse).norm(),
                kResidual * (in.b.norm() + in.K.norm() * r.impulse.norm()));
    }
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

// fuzz round 5, item 44
// K singular to round-off in two 2x2 minors is refused as singular; K =
// 3 (1 1^T) + 1e-8 I (cond 9e8) keeps its stick with b + K lambda = 0.
TEST(FrictionBlockConditioning, ExactStickRefusesCofactorsWithoutDigits) {
  const PatchShape quad = PatchShape::polygon({{-6.7766371900790209e-09, -9.9999999322336289e-09},
                                               {-1.0000000000000001e-16, -1e-08},
                                               {0.038782114750976461, 0.4999999896121789},
                                               {4.9999999000000001e-09, 0.49999999000000001}});
  const FrictionPatch patch(
      quad,
      LinearPressure::fromLoads(quad,
                                {851722772.11537802, -212930647.22235772, 8257900.7497947859}),
      1e-8, 0.5);
  FrictionBlockInput in;
  in.b = Vec3(-281018368.0, 0.5, 0.5);
  in.L = 1e-8;
  in.warmSlip = Vec3(2.2204460492503131e-16, 0.0, 0.0);
  in.K << 2.2269023871737371e+20, 7461404672.0, 3.9979872811923538e+18, 7461404672.0,
      0.25000000000000011, 133955584.0, 3.9979872811923538e+18, 133955584.0, 71776393939124224.0;
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(patch, Model::Exact, in); }, {"singular"}));

  const PatchShape disk = PatchShape::disk(0.5);
  const FrictionPatch uniform(disk, LinearPressure::uniform(disk, 1.0), 0.5, 0.0);
  FrictionBlockInput inside;
  inside.b = Vec3(1.0, 1.0, 1.0);
  inside.L = 1.0;
  inside.K = 3.0 * Mat3::Ones() + 1e-8 * Mat3::Identity();
  const FrictionBlockResult r = solveFrictionBlock(uniform, Model::Exact, inside);
  // -K^-1 b = -b / 9 is well inside L E (force 0.16 of L): a stick
  ASSERT_TRUE(r.sticking);
  constexpr double kResidual = 1e-12;  // a backward-stable solve: a few ulps
  EXPECT_LT((inside.b + inside.K * r.impulse).norm(),
            kResidual * (inside.b.norm() + inside.K.norm() * r.impulse.norm()));
}

// fuzz round 8, item 57
// K with unit-diagonal condition 1.9e9 and a diagonal spanning 1.2e27 and
// 2.1e27: the stick decision and the impulse (to kImpulse of L |Pi|) match the
// block solved in its first form in 50 digits, and the slip b + K impulse is
// along w = -Pi^-1 impulse / L to kBackward (friction_block.hpp's 1e-10).
TEST(FrictionBlockConditioning, EllipsoidalWithANearSingularWideDiagonalKMatches50Digits) {
  struct Case {
    PatchLoads loads;
    Mat3 K;
    Vec3 warm;
  };
  std::vector<Case> cases(2);
  cases[0].loads = {1.4899643344710497e+236, -1.4991057232768605e+228, 1.8623432307385959e+228};
  cases[0].K << 1.8994705936215963e-07, 6459695.0000000065, 4.3582916259794539e-12,  //
      6459695.0000000065, 2.196804715965055e+20, 2579234964.2162175,                 //
      4.3582916259794539e-12, 2579234964.2162175, 2.6609808944266215e+19;
  cases[0].warm = Vec3(7113015296.0, 0.0, 1.5627709092286829e-312);
  cases[1].loads = {8.3943422731309656e+234, -8.4458441411370788e+226, 1.0492295786676125e+227};
  cases[1].K << 1.0575695363890247e-07, 4820035.0, 3.2520294189453125e-12,  //
      4820035.0, 2.196804715965055e+20, -63903.268157400002,                //
      3.2520294189453125e-12, -63903.268157400002, 1410963865600.0;
  cases[1].warm = Vec3(0.5, 1e-8, 1e-8);
  const PatchShape disk = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  // kImpulse: far above the measured 8e-16, far below the fuzz target's
  // law slack of 1e-6 of L |Pi|
  constexpr double kImpulse = 1e-10, kBackward = 1e-10;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, cases[c].loads), 1e-8, 1e-8);
    FrictionBlockInput in;
    in.b = Vec3(0.0, 4.9406564584124654e-324, 0.5);
    in.L = 1e-8;
    in.K = cases[c].K;
    in.warmSlip = cases[c].warm;
    FrictionBlockResult r;
    ASSERT_NO_THROW(r = solveFrictionBlock(patch, Model::Ellipsoidal, in)) << "case " << c;
    const Mat3& Pi = patch.Pi();
    const BigBlock ref = solveEllipsoidalBig(Pi, in.K, in.b, in.L);
    ASSERT_FALSE(ref.sticking) << "case " << c;
    EXPECT_FALSE(r.sticking) << "case " << c;
    const double setSize = in.L * Pi.norm();
    EXPECT_LT((r.impulse - ref.impulse).norm(), kImpulse * setSize)
        << "case " << c << ": impulse " << r.impulse.transpose() << ", 50 digits "
        << ref.impulse.transpose();
    // the backward error of the returned impulse, in 50 digits
    const BigVec lambda = toBig(r.impulse);
    const BigVec w0 = solve(toBig(Pi), lambda);
    BigVec w = {-w0[0] / in.L, -w0[1] / in.L, -w0[2] / in.L};
    const double wNorm = double(norm(w));
    // (|w| = 1 to the rounding of -L Pi w and of its inverse: Pi is well
    // conditioned)
    EXPECT_NEAR(wNorm, 1.0, 1e-12) << "case " << c;
    for (Big& x : w) x /= Big(wNorm);
    const BigVec kl = times(toBig(in.K), lambda);
    const BigVec b = toBig(in.b);
    const BigVec s = {b[0] + kl[0], b[1] + kl[1], b[2] + kl[2]};
    const Big along = s[0] * w[0] + s[1] * w[1] + s[2] * w[2];
    const BigVec e = {s[0] - along * w[0], s[1] - along * w[1], s[2] - along * w[2]};
    const double scale = in.b.norm() + (in.L * (in.K * Pi)).norm();
    EXPECT_LT(double(norm(e)), kBackward * scale) << "case " << c;
    EXPECT_GT(double(along), -kBackward * scale) << "case " << c;
  }
}

}  // namespace
}  // namespace patchspin
