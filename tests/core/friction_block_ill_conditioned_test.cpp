// The friction block with an ill-conditioned K (sixth fuzz round, issue 6):
// K near singular below the refusal threshold, K badly scaled, and the
// exact law's digits. Each test is a fuzz finding that failed on e4caa91
// (checked), each checked against an independent computation: a long
// double reference solve, K's eigenvalues in closed form, the law at the
// returned slip (unitQ), or the limit set's closed-form bounds.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fuzz_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

using namespace patchspin;

namespace {

using Mat3l = Eigen::Matrix<long double, 3, 3>;
using Vec3l = Eigen::Matrix<long double, 3, 1>;

// The ellipsoidal block in long double (64-bit mantissa, eps 5.4e-20):
// stick iff |A^-1 b| <= 1 (A = L K Pi), else the root r of |(rI + A)^-1 b| = 1
// by 200 bisections, w = (rI + A)^-1 b / |.|, impulse -L Pi w. Full pivoting
// throughout; at cond 1e9 it keeps ~1e-10 relative, far below the checks.
Vec3l ellipsoidalReference(const Mat3& Pi, const Mat3& K, const Vec3& b, double L, bool& stick) {
  const Mat3l A = (long double)L * (K.cast<long double>() * Pi.cast<long double>());
  const Vec3l bl = b.cast<long double>();
  stick = A.fullPivLu().solve(bl).norm() <= 1.0L;
  if (stick) return -K.cast<long double>().fullPivLu().solve(bl);
  long double lo = 0.0L, hi = bl.norm() + A.norm();
  for (int i = 0; i < 200; ++i) {
    const long double r = 0.5L * (lo + hi);
    if ((r * Mat3l::Identity() + A).fullPivLu().solve(bl).norm() > 1.0L)
      lo = r;
    else
      hi = r;
  }
  const Vec3l w = (lo * Mat3l::Identity() + A).fullPivLu().solve(bl).normalized();
  return -(long double)L * (Pi.cast<long double>() * w);
}

}  // namespace

// 47. The ellipsoidal block with K = 0.75 1 1^T + 1e-8 I (unit-diagonal cond
// 2.3e8, inside the 1e10 refusal): its Cayley-Hamilton sums hold det A and
// adj A, which cancel to noise for a K this near singular, and it slipped
// with |s| = 0.19 where the true slip is 1.1e-9: the impulse 1.28 of
// L |Pi| off the law at its slip. Now a slip verifies its backward error
// and falls back to pivoted solves and a bordered Newton step.
TEST(FrictionBlockIllConditioned, EllipsoidalBlockWithANearSingularKIsTheLongDoubleSolution) {
  const PatchShape disk = PatchShape::disk(0.5, Vec2(0.5, 0.5));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(disk,
                                {0.35832579507494172, -0.13866373869824342, 0.1982947328961451}),
      0.5, 0.5);
  FrictionBlockInput in;
  in.b = Vec3(0.5, 0.5, 0.5);
  in.L = 0.5;
  in.K = 0.75 * Mat3::Ones();
  in.K.diagonal().setConstant(0.75000001000000005);
  in.warmSlip = Vec3(1e-8, 1e-8, 1e-8);
  in.warmGauge = Vec3(0.5, -0.00012291967868804932, 5.2658841013908386e-05);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Ellipsoidal, in);
  bool stick = true;
  const Vec3l ref = ellipsoidalReference(patch.Pi(), in.K, in.b, in.L, stick);
  ASSERT_FALSE(stick);
  ASSERT_FALSE(r.sticking);
  // forward error: the block's answer is determined to ~cond(K) eps = 2.3e8
  // x 1.1e-16 = 2.6e-8 of L |Pi| (measured 2e-8); kForward leaves 40 times that
  constexpr double kForward = 1e-6;
  const double set = in.L * patch.Pi().norm();
  EXPECT_LT((r.impulse.cast<long double>() - ref).norm(), kForward * set);
  // backward error: the impulse -L Pi w (|w| = 1, w = -Pi^-1 impulse / L)
  // with the slip along w is the block's exact solution for b moved by e =
  // s - (s.w) w; a backward-stable answer has |e| at a few eps of the
  // slip scale |b| + |K| |impulse| (kBackward: 1e4 ulps of room)
  constexpr double kBackward = 1e-12;
  const Vec3 w = -patch.Pi().fullPivLu().solve(r.impulse) / in.L;
  EXPECT_NEAR(w.norm(), 1.0, kBackward * 1e3);  // on the set's boundary, to the solve's round-off
  const Vec3 s = in.b + in.K * r.impulse;
  const Vec3 u = w.normalized();
  EXPECT_LT((s - std::max(0.0, s.dot(u)) * u).norm(),
            kBackward * (in.b.norm() + in.K.norm() * r.impulse.norm()));
}

// 48. The ellipsoidal block with K of entries 1.6e20 whose unit-diagonal
// form is indefinite at round-off (off-diagonal 1 - 1e-16): its adjugate
// stick test, on a noise determinant, stuck with -K^-1 b from a pivoted
// solve, an impulse 12.2 against L |Pi|_F = 1.27, outside the limit set.
// Now K is factored by Cholesky and the stick is decided with the impulse it
// returns: refused (Cholesky fails), or an impulse inside L E.
TEST(FrictionBlockIllConditioned, EllipsoidalStickNeverLeavesTheLimitSet) {
  const FrictionPatch patch = patchspin::testing::fuzzDodecagonPatch();
  FrictionBlockInput in;
  in.b = Vec3(0.5, 4.9406564584124654e-324, 0.5);
  in.L = 0.5;
  in.K << 1.6042121049807625e+20, 1.6042121049807598e+20, 1.2409103239413655e+20,
      1.6042121049807598e+20, 1.6042121077295415e+20, 1.2409103239413629e+20,
      1.2409103239413655e+20, 1.2409103239413629e+20, 9.5988456095257461e+19;
  try {
    const FrictionBlockResult r = solveFrictionBlock(patch, Model::Ellipsoidal, in);
    // inside L E = {-L Pi w : |w| <= 1}: |Pi^-1 impulse| <= L, solved here by
    // full pivoting (kInside: that solve's round-off, Pi is well conditioned)
    constexpr double kInside = 1e-9;
    EXPECT_LE(patch.Pi().fullPivLu().solve(r.impulse).norm(), in.L * (1.0 + kInside));
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("positive definite") != std::string::npos ||
                what.find("singular") != std::string::npos)
        << what;
  }
}

// 49. K = a 1 1^T + delta I with a = 1.7e16 and delta = 7.5e7 (unit-diagonal
// cond 6.7e8): positive definite, its eigenvalues delta, delta and 3a + delta,
// but its computed determinant, a difference of terms 1e16 times larger than
// itself, came out negative and the exact block refused K as "not positive
// definite" (Sylvester). Now Cholesky decides, and the block solves it.
// (The fuzz input's loads, (0.48028985921748324, -4.7571832537536188e-09,
// 0.2401449302752777), put the centre of pressure 1.4e-9 m off the centre
// line of this 1e-8 m x 0.5 m sliver 0.5 m from O. Until the eighth round
// fromLoads turned them into a nearly uniform pressure, its cofactor G^-1
// about O having no digits there; now it returns the steep tilt they imply
// (min p 0.17 of the mean), whose terms about O, 4e7 times Pz on a sliver
// with diameter^2 / A = 5e7, the exact block rightly refuses as a law
// without digits (fuzz/README.md, item 59). This test is about K: it keeps
// the uniform pressure of the same Pz.)
TEST(FrictionBlockIllConditioned, ExactBlockAcceptsAPositiveDefiniteKWhoseDeterminantHasNoDigits) {
  const PatchShape quad = PatchShape::polygon({{0.49999999749999996, -0.24999999000000006},
                                               {0.50000000749999995, -0.24999998999999995},
                                               {0.50000000249999998, 0.25000001000000005},
                                               {0.49999999249999999, 0.25000000999999994}});
  const FrictionPatch patch(quad, LinearPressure::uniform(quad, 0.48028985921748324), 1e-8, 0.5);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 1e-8);
  in.L = 1e-8;
  const double a = 16759910503022592.0, diag = 16759910577766400.0;
  in.K = a * Mat3::Ones();
  in.K.diagonal().setConstant(diag);
  in.warmSlip = Vec3(-74743808.0, -74743808.0, 1e-8);
  in.warmGauge = Vec3(255.10698178609888, 1e-8, 0.5);
  // the closed form: eigenvalues diag - a (twice) and diag + 2a, all > 0
  ASSERT_GT(diag - a, 0.0);
  ASSERT_LT(in.K.determinant(), 0.0);  // the cancelled determinant that misled Sylvester's test
  FrictionBlockResult r;
  ASSERT_NO_THROW(r = solveFrictionBlock(patch, Model::Exact, in));
  // the answer is the block's: a stick stops the slip to a backward-stable
  // solve's round-off (kResidual: a few ulps with 1e4 of room), a slip is the
  // law at its slip (kLaw: the fuzz target's 1e-6 of L |q|)
  constexpr double kResidual = 1e-12, kLaw = 1e-6;
  if (r.sticking) {
    EXPECT_LT((in.b + in.K * r.impulse).norm(),
              kResidual * (in.b.norm() + in.K.norm() * r.impulse.norm()));
  } else {
    const Vec3 q = patch.unitQ(Model::Exact, r.slip);
    EXPECT_LT((r.impulse - in.L * q).norm(), kLaw * in.L * q.norm());
  }
}

// 50. An exact stick with a badly scaled K (K_zz = 2e12 against K_xx =
// 1.5e-6, K_xz = -0.014, well conditioned once scaled to a unit diagonal):
// the stick impulse came from a partially pivoted LU, which pivoted on the z
// row and returned a force of 1.65e-8 where -K^-1 b has 5.8e-12: a stick
// 1.65 times outside L E. Now -K^-1 b comes from K's Cholesky factor
// (invariant under the diagonal's scaling): checked against a long double
// solve and against the limit set's force bound L ∫|p| / Pz (p >= 0: L).
TEST(FrictionBlockIllConditioned, ExactStickWithABadlyScaledKIsMinusKInverseB) {
  const PatchShape disk =
      PatchShape::disk(1e-8, Vec2(6.532982249993248e-06, -0.00010626135640955286));
  const FrictionPatch patch(
      disk,
      LinearPressure::fromLoads(disk,
                                {144.15450598324392, 0.015318042281755031, 0.00094211904546359279}),
      1e-8, 1e-8);
  ASSERT_GE(minPressure(disk, patch.pressure()), 0.0);
  FrictionBlockInput in;
  in.b = Vec3(1e-08, 1e-08, -1413632.0);
  in.L = 1e-8;
  in.warmSlip = Vec3(1e-08, 0.0012142658233642578, 0.5);
  in.warmGauge = Vec3(1e-08, -0.0018873810768127441, 2.4080276489257812e-05);
  in.K << 1.484441489990479e-06, 5.012142758233643e-09, -0.014136319987857242,
      5.012142758233643e-09, 0.25000001000000022, -0.014136314999999901, -0.014136319987857242,
      -0.014136314999999899, 1998355431424.0;
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
  const Mat3l Kl = in.K.cast<long double>();
  const Vec3l ref = -Kl.fullPivLu().solve(in.b.cast<long double>());
  // the force of -K^-1 b, 5.8e-12, is far inside L = 1e-8: a stick
  ASSERT_LT(std::hypot(double(ref.x()), double(ref.y())), 1e-2 * in.L);
  ASSERT_TRUE(r.sticking);
  // row by row (the force is 1e5 times smaller than the torque, so a
  // normwise comparison would not see it): K_ii times the error against the
  // terms of row i, |b_i| + sum_j |K_ij| |lambda_j|, whose rounding bounds
  // what any double solve can resolve (row x cancels 1e-8 against 1e-8 to
  // 8.6e-18: lambda_x itself is known to ~1e-7); kRow is a few eps with
  // 1e4 of room (the old pivoted LU: 0.8 in row x)
  constexpr double kRow = 1e-12;
  for (int i = 0; i < 3; ++i) {
    const double terms =
        std::abs(in.b[i]) + in.K.row(i).cwiseAbs().dot(ref.cast<double>().cwiseAbs());
    EXPECT_LE(in.K(i, i) * std::abs(r.impulse[i] - double(ref[i])), kRow * terms) << "row " << i;
  }
  EXPECT_LE(std::hypot(r.impulse.x(), r.impulse.y()), in.L);
}

// 51. The exact block with K near singular (K = 0.75 v v^T + 1e-8 I-like,
// unit-diagonal cond 4.5e8 and 2e8) or with a diagonal spanning 1.3e18 and b
// off the rows' scale: its slip potential weighs the slip by K^-1, its
// Newton iteration stopped far from the solution, and the impulse was 0.57,
// 0.9 and 1.6 of the set off the law at its own slip. Now, for K's plain
// condition (times the lever's distance from 1) at or above 1e5, a slip is
// verified against the law at its slip and the block is refused otherwise:
// solved and the law, or refused naming the cause. Checked against unitQ at
// the returned slip.
TEST(FrictionBlockIllConditioned, ExactBlockWithAnIllConditionedKIsTheLawOrRefused) {
  struct Case {
    PatchShape shape;
    PatchLoads loads;
    double mu, rho;
    Vec3 b;
    double L;
    Mat3 K;
    Vec3 warm, gauge;
  };
  std::vector<Case> cases;
  {
    const PatchShape tri = PatchShape::polygon({{-1.0000061035356431, -0.99999700822522808},
                                                {0.0, 0.0},
                                                {-1.0000015558804356, 4.5476552074754882e-06}});
    Mat3 K;
    K << 0.75000001000000005, 0.75, 1.5, 0.75, 0.75000001000000005, 1.5, 1.5, 1.5,
        3.0000000099999999;
    cases.push_back({tri,
                     {0.38823364427948265, 0.19411579999774151, -0.29117656901983768},
                     8.0390256600414691e+230,
                     0.5,
                     Vec3(1e-8, 1.0, 0.5),
                     0.5,
                     K,
                     Vec3(1e-8, 1.0, 1.0),
                     Vec3(1.0, 1.0, 1.0)});
  }
  {
    const PatchShape disk = PatchShape::disk(0.310272216796875, Vec2(1e-8, 1e-8));
    Mat3 Kd = 0.75 * Mat3::Ones();
    Kd.diagonal().setConstant(0.7500000109857865);
    cases.push_back({disk,
                     {1.5622408520355839, 0.08568717391978023, 0.085687201644241387},
                     0.5,
                     0.5,
                     Vec3(0.5, 0.5, 0.5),
                     0.5,
                     Kd,
                     Vec3(14947450880.0, 37748736.0, 0.0),
                     Vec3::Zero()});
  }
  {
    const PatchShape disk = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
    Mat3 K;
    K << 1.00000001e-08, 5.0000000000000001e-09, 1.0000000000000001e-16, 5.0000000000000001e-09,
        12787086400.25, 0.0011308050000000999, 1.0000000000000001e-16, 0.0011308050000000999,
        1.00000003e-08;
    cases.push_back({disk,
                     {1.5176555785887907e+236, -1.5269668616820956e+228, 1.8969552008645201e+228},
                     1e-8,
                     1e-8,
                     Vec3(0.5, 1e-8, 0.5),
                     0.5,
                     K,
                     Vec3(1e-8, 0.5, 0.0),
                     Vec3::Zero()});
  }
  // kLaw: the fuzz target's tolerance, 1e-6 of the law's size
  constexpr double kLaw = 1e-6;
  for (const Case& c : cases) {
    const FrictionPatch patch(c.shape, LinearPressure::fromLoads(c.shape, c.loads), c.mu, c.rho);
    FrictionBlockInput in;
    in.b = c.b, in.L = c.L, in.K = c.K, in.warmSlip = c.warm, in.warmGauge = c.gauge;
    try {
      const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, in);
      if (r.sticking) continue;  // (none of these sticks; a stick verifies b + K lambda = 0 itself)
      const Vec3 q = patch.unitQ(Model::Exact, r.slip);
      EXPECT_LT((r.impulse - in.L * q).norm(), kLaw * in.L * q.norm()) << "K(0, 0) = " << c.K(0, 0);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot resolve"), std::string::npos) << e.what();
    }
  }
}

// 52. The exact law on a pressure whose terms about O cancel (a 1e-8 m x
// 0.5 m sliver, cy = -2.75e16 against Pz = 0.32): FrictionPatch accepted it
// and its unit torque exceeded its bound max|r| / rho more than ten times
// (measured in ExactBlockRefusesALawWithoutDigits before this round). Now
// the exact law refuses a pressure whose round-off model reaches 1e-6 of Pz
// (as the exact block does). Every evaluation is refused or inside the
// bounds of the law (p >= 0 here: unit force <= 1, unit torque <= max|r| /
// rho, closed forms); an ordinary 1 m x 1 mm face at the end of its kern
// (model 1.4e-10) evaluates, inside its bounds.
TEST(FrictionBlockIllConditioned, ExactLawRefusesAPressureWithoutDigits) {
  const PatchShape sliver = PatchShape::polygon({{-5.00585889346894e-09, -5.4910742118954658e-09},
                                                 {-3.1943728212127098e-09, -5.4910742300103267e-09},
                                                 {0.49999999680574098, 1.3205255290824883e-09},
                                                 {4.8521548660111215e-10, 6.3205254922877428e-09}});
  const FrictionPatch noisy(
      sliver,
      LinearPressure::fromLoads(
          sliver, {0.32000003110670083, 2.6728782502318121e-10, 0.040000002870676614}),
      1e-8, 0.5);
  const PatchShape face = PatchShape::rectangle(1.0, 1e-3, Vec2(0.2, 0.0));
  const PatchLoads tipped = nearestAdmissibleLoads(face, {1.0, -0.3e-3, 0.5}, face.defaultRho());
  const FrictionPatch ordinary(face, LinearPressure::fromLoads(face, tipped), 0.5, 0.0);
  // kBound: the law's round-off on an ordinary patch, ~1e-13, with room
  constexpr double kBound = 1e-9;
  int refused = 0;
  for (const FrictionPatch* patch : {&noisy, &ordinary}) {
    ASSERT_GE(minPressure(patch->shape(), patch->pressure()),
              -1e-6 * patch->Pz() / patch->shape().area());
    const double torqueBound = patch->shape().maxDistanceFromOrigin() / patch->rho();
    for (int i = 0; i < 200; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / 200.0, rxy = std::sqrt(1.0 - z * z),
                   phi = 2.39996322972865332 * i;
      const Vec3 w(rxy * std::cos(phi), rxy * std::sin(phi), z);
      try {
        const Vec3 q = patch->unitQ(Model::Exact, w);
        EXPECT_LE(std::hypot(q.x(), q.y()), 1.0 + kBound);
        EXPECT_LE(std::abs(q.z()), torqueBound * (1.0 + kBound));
      } catch (const Error& e) {
        ++refused;
        EXPECT_EQ(patch, &noisy) << e.what();
        EXPECT_NE(std::string(e.what()).find("no digits"), std::string::npos) << e.what();
      }
    }
  }
  EXPECT_EQ(refused, 200);
}
