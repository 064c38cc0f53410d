// Tests of the implicit friction block (friction_block.hpp, DESIGN item 4), each against
// a computation that does not use the solver: closed forms for isotropic
// cases, the defining relations, the projection optimality inequality of the
// maximum-dissipation law, and the energy balance.
#include <patchspin/friction_block.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace patchspin {
namespace {

// Round-off of a few 3x3 solves on O(1) numbers, amplified by at most ~100.
constexpr double kSolveTol = 1e-12;

Mat3 randomSpd(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(lo, hi);
  Mat3 A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) = u(rng);
  const Eigen::HouseholderQR<Mat3> qr(A);
  const Mat3 Qm = qr.householderQ();
  return Qm * Vec3(e(rng), e(rng), e(rng)).asDiagonal() * Qm.transpose();
}

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Vec3(n(rng), n(rng), n(rng)).normalized();
}

FrictionPatch tiltedDisk() {
  const PatchShape disk = PatchShape::disk(0.05);
  return FrictionPatch(disk, LinearPressure::fromLoads(disk, {10.0, 0.06, -0.04}), 0.5);
}

FrictionPatch tiltedRectangle() {
  const PatchShape rect = PatchShape::rectangle(0.08, 0.04, Vec2(0.01, -0.005));
  return FrictionPatch(rect, LinearPressure::fromLoads(rect, {10.0, 0.02, 0.03}), 0.5);
}

// Isotropic case (Pi = I, K = k I): closed form. Slip s = b (1 - k L / |b|) if
// |b| > k L, else stick with lambda = -b / k.
TEST(FrictionBlockTest, EllipsoidalIsotropicMatchesClosedForm) {
  const PatchShape disk = PatchShape::disk(0.05);
  const FrictionPatch patch(disk, LinearPressure::uniform(disk, 10.0), 0.5);
  ASSERT_LT((patch.Pi() - Mat3::Identity()).norm(), 1e-12);  // Sect. 4.5.2
  const double k = 2.0, L = 0.3;
  FrictionBlockInput in;
  in.K = k * Mat3::Identity();
  in.L = L;
  in.b = Vec3(1.0, -0.5, 0.7);
  const auto slip = solveFrictionBlock(patch, Model::Ellipsoidal, in);
  EXPECT_FALSE(slip.sticking);
  EXPECT_LT((slip.slip - in.b * (1.0 - k * L / in.b.norm())).norm(), kSolveTol);
  in.b = Vec3(0.2, -0.1, 0.3);  // |b| = 0.374 < k L = 0.6
  const auto stick = solveFrictionBlock(patch, Model::Ellipsoidal, in);
  EXPECT_TRUE(stick.sticking);
  EXPECT_EQ(stick.slip.norm(), 0.0);
  EXPECT_LT((stick.impulse + in.b / k).norm(), kSolveTol);
}

// General ellipsoidal blocks satisfy the defining relations:
//   slip: s = b + K lambda, lambda = -L Pi s/|s|;  stick: lambda = -K^-1 b
//   inside the ellipsoid, |(L Pi)^-1 lambda| <= 1.
TEST(FrictionBlockTest, EllipsoidalSatisfiesDefiningRelations) {
  std::mt19937 rng(7);
  const FrictionPatch patch = tiltedDisk();
  int slips = 0, sticks = 0;
  for (int trial = 0; trial < 200; ++trial) {
    FrictionBlockInput in;
    in.K = randomSpd(rng, 0.2, 5.0);
    in.L = 0.5;
    in.b = randomUnit(rng) * std::uniform_real_distribution<double>(0.01, 6.0)(rng);
    const auto res = solveFrictionBlock(patch, Model::Ellipsoidal, in);
    const Vec3 lambdaInEllipsoid = (in.L * patch.Pi()).inverse() * res.impulse;
    if (res.sticking) {
      ++sticks;
      EXPECT_LT((in.K * res.impulse + in.b).norm(), kSolveTol * in.b.norm());
      EXPECT_LE(lambdaInEllipsoid.norm(), 1.0 + kSolveTol);
    } else {
      ++slips;
      EXPECT_LT((res.slip - in.b - in.K * res.impulse).norm(), kSolveTol * in.b.norm());
      const Vec3 w = res.slip.normalized();
      EXPECT_LT((res.impulse + in.L * patch.Pi() * w).norm(), kSolveTol);
      // and stick was correctly refused: -K^-1 b lies outside the ellipsoid
      EXPECT_GT(((in.L * patch.Pi()).inverse() * (-in.K.inverse() * in.b)).norm(), 1.0);
    }
  }
  EXPECT_GT(slips, 20);
  EXPECT_GT(sticks, 20);
}

// Exact law: the impulse is the K-metric projection of lambda0 = -K^-1 b onto
// L E. Optimality is checked against sampled points L q(w') of the limit
// surface (and the origin): none may be K-closer to lambda0.
void checkExactProjection(const FrictionPatch& patch, std::uint32_t seed) {
  std::mt19937 rng(seed);
  // sampled limit surface, shared by all trials
  std::vector<Vec3> surface;
  for (int i = 0; i < 2000; ++i) surface.push_back(patch.unitQ(Model::Exact, randomUnit(rng)));
  int slips = 0, sticks = 0;
  for (int trial = 0; trial < 60; ++trial) {
    FrictionBlockInput in;
    in.K = randomSpd(rng, 0.2, 5.0);
    in.L = 0.5;
    in.b = randomUnit(rng) * std::uniform_real_distribution<double>(0.01, 5.0)(rng);
    const auto res = solveFrictionBlock(patch, Model::Exact, in);
    const Mat3 Kinv = in.K.inverse();
    const Vec3 lambda0 = -Kinv * in.b;
    auto kdist = [&](const Vec3& l) { return (l - lambda0).dot(in.K * (l - lambda0)); };
    // relative slack: the solver converges to ~1e-14; sampled points are exact
    const double slack = 1e-10 * (1.0 + kdist(Vec3::Zero()));
    if (res.sticking) {
      ++sticks;
      EXPECT_EQ(res.slip.norm(), 0.0);
      EXPECT_LT((res.impulse - lambda0).norm(), kSolveTol * (1.0 + lambda0.norm()));
      // lambda0 inside L E: support inequality lambda0.d >= L q(d).d on samples
      for (int i = 0; i < 200; ++i) {
        const Vec3 d = randomUnit(rng);
        EXPECT_GE(lambda0.dot(d), in.L * patch.unitQ(Model::Exact, d).dot(d) - 1e-12);
      }
    } else {
      ++slips;
      EXPECT_LT((res.slip - in.b - in.K * res.impulse).norm(), kSolveTol * (1.0 + in.b.norm()));
      // impulse on the limit surface with the slip's direction as its normal
      const Vec3 w = res.slip.normalized();
      EXPECT_LT((res.impulse - in.L * patch.unitQ(Model::Exact, w)).norm(), 1e-10);
      const double best = kdist(res.impulse);
      for (const Vec3& q : surface) EXPECT_GE(kdist(in.L * q), best - slack);
      // friction dissipates: lambda . s <= 0
      EXPECT_LE(res.impulse.dot(res.slip), 0.0);
    }
  }
  EXPECT_GT(slips, 5);
  EXPECT_GT(sticks, 5);
}

TEST(FrictionBlockTest, ExactIsKProjectionOntoLimitSetDisk) {
  checkExactProjection(tiltedDisk(), 11);
}
TEST(FrictionBlockTest, ExactIsKProjectionOntoLimitSetRectangle) {
  checkExactProjection(tiltedRectangle(), 12);
}

// Friction never adds energy: with E(x) = 1/2 x^T K^-1 x, E(s) <= E(b).
TEST(FrictionBlockTest, NeverAddsEnergy) {
  std::mt19937 rng(3);
  for (const Model model : {Model::Ellipsoidal, Model::Exact}) {
    const FrictionPatch patch = tiltedRectangle();
    for (int trial = 0; trial < 100; ++trial) {
      FrictionBlockInput in;
      in.K = randomSpd(rng, 0.2, 5.0);
      in.L = std::uniform_real_distribution<double>(0.0, 2.0)(rng);
      in.b = randomUnit(rng) * std::uniform_real_distribution<double>(0.0, 5.0)(rng);
      const auto res = solveFrictionBlock(patch, model, in);
      const Mat3 Kinv = in.K.inverse();
      EXPECT_LE(res.slip.dot(Kinv * res.slip), in.b.dot(Kinv * in.b) * (1.0 + 1e-12))
          << toString(model);
    }
  }
}

// The exact law's limit set contains the octahedron conv{+-Pi e_i}: the
// law at the fitting motions equals the ellipsoid's, q(e_i) = -Pi e_i (checked
// here against the exact law itself), so impulses L Pi c with |c|_1 <= 1 lie
// in L E and the block sticks with lambda = -K^-1 b; just outside the
// octahedron along a vertex (c = 1.05 e_i) it must slip (a vertex of the
// octahedron is on the boundary of E, so the point beyond it is outside).
TEST(FrictionBlockTest, ExactSticksInsideTheFittingOctahedron) {
  const FrictionPatch patch = tiltedRectangle();
  for (int i = 0; i < 3; ++i) {
    const Vec3 q = patch.unitQ(Model::Exact, Vec3::Unit(i));
    EXPECT_LT((q + patch.Pi().col(i)).norm(), 1e-10) << "fitting motion " << i;
  }
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    FrictionBlockInput in;
    in.K = randomSpd(rng, 0.2, 5.0);
    in.L = 0.7;
    Vec3 c(u(rng), u(rng), u(rng));
    c *= 0.999 * std::abs(u(rng)) / c.lpNorm<1>();
    const Vec3 lambda = in.L * (patch.Pi() * c);
    in.b = -in.K * lambda;
    const auto res = solveFrictionBlock(patch, Model::Exact, in);
    EXPECT_TRUE(res.sticking);
    EXPECT_LT((res.impulse - lambda).norm(), kSolveTol * lambda.norm() + 1e-15);
  }
  for (int i = 0; i < 3; ++i) {
    FrictionBlockInput in;
    in.K = Mat3::Identity();
    in.L = 0.7;
    in.b = -in.K * (1.05 * in.L * patch.Pi().col(i));
    EXPECT_FALSE(solveFrictionBlock(patch, Model::Exact, in).sticking) << "beyond vertex " << i;
  }
}

// The exact law's limit set E also contains the bicone over the
// translation ellipse: a pure translation u (|u| = 1) gives the uniform
// force -u and the torque of that force at the centre of pressure, linear in
// u, so q((u, 0)) = -Pi (u, 0) for every u (the fitting motions e1, e2 are
// two of them); with +-q(e3) = -+Pi e3 and E convex,
//   Pi z in E for |(z1, z2)| + |z3| <= 1
// (the PatchFrictionSolver's quick stick test). Checked independently of
// that argument by the support inequality of E: lambda in E iff
// w . lambda >= w . q(w) for every unit w (q(w) minimises q . w over E),
// over 2000 random w and points on the bicone's boundary; kSupportTol is the
// exact law's own accuracy (1e-10 of mu Pz, unit here) with a margin.
TEST(FrictionBlockTest, ExactLimitSetContainsTheTranslationBicone) {
  constexpr double kSupportTol = 1e-9;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const PatchShape disk = PatchShape::disk(0.05);
  const FrictionPatch patches[] = {
      tiltedRectangle(),
      FrictionPatch(disk, LinearPressure::fromLoads(disk, {10.0, -0.05, 0.08}), 0.5)};
  for (const FrictionPatch& patch : patches) {
    for (int k = 0; k < 16; ++k) {  // translations: the ellipse itself
      const double a = 2.0 * M_PI * k / 16;
      const Vec3 w(std::cos(a), std::sin(a), 0.0);
      EXPECT_LT((patch.unitQ(Model::Exact, w) + patch.Pi() * w).norm(), 1e-10) << k;
    }
    std::vector<Vec3> ws, qs;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 w = randomUnit(rng);
      ws.push_back(w);
      qs.push_back(patch.unitQ(Model::Exact, w));
    }
    double worst = -1e300;
    for (int trial = 0; trial < 200; ++trial) {
      const double t = std::abs(u(rng)), phi = M_PI * u(rng);
      const double sign = u(rng) < 0 ? -1.0 : 1.0;
      const Vec3 z((1.0 - t) * std::cos(phi), (1.0 - t) * std::sin(phi),
                   sign * t);  // on the boundary
      const Vec3 lambda = patch.Pi() * z;
      for (size_t i = 0; i < ws.size(); ++i)
        worst = std::max(worst, ws[i].dot(qs[i]) - ws[i].dot(lambda));
    }
    EXPECT_LE(worst, kSupportTol);
    // and the bicone is not all of E: beyond its vertex Pi e3 the point is out
    const Vec3 beyond = 1.05 * patch.Pi().col(2);
    double gap = -1e300;
    for (size_t i = 0; i < ws.size(); ++i)
      gap = std::max(gap, ws[i].dot(qs[i]) - ws[i].dot(beyond));
    EXPECT_GT(gap, 0.0);
  }
}

// A coarser stopping tolerance (what the single-precision Bullet layer asks
// for) moves the solution by at most ~cond(K) x tolerance of the slip scale:
// compared with the default (1e-14) solve of the same block. K here has
// eigenvalues in [0.2, 5] (cond <= 25), so 1e-9 -> 25e-9 of |b| + L|K|; the
// bound 1e-7 leaves a factor 4 for the Newton iterations' last step.
TEST(FrictionBlockTest, CoarserToleranceStaysClose) {
  constexpr double kCoarse = 1e-9;
  constexpr double kBound = 1e-7;
  std::mt19937 rng(21);
  for (const Model model : {Model::Ellipsoidal, Model::Exact}) {
    const FrictionPatch patch = tiltedRectangle();
    for (int trial = 0; trial < 60; ++trial) {
      FrictionBlockInput in;
      in.K = randomSpd(rng, 0.2, 5.0);
      in.L = std::uniform_real_distribution<double>(0.1, 2.0)(rng);
      in.b = randomUnit(rng) * std::uniform_real_distribution<double>(0.01, 5.0)(rng);
      const auto fine = solveFrictionBlock(patch, model, in);
      in.tolerance = kCoarse;
      const auto coarse = solveFrictionBlock(patch, model, in);
      const double scale = in.b.norm() + in.L * in.K.norm();
      EXPECT_EQ(coarse.sticking, fine.sticking) << toString(model);
      EXPECT_LT((coarse.slip - fine.slip).norm(), kBound * scale) << toString(model);
    }
  }
}

// The exact block's stick test locates the limit set's boundary along
// lambda0 = -K^-1 b and returns it (gaugeSlip w, gaugeValue q): q must be the
// law at w, parallel to lambda0, and the maximum-dissipation point of E for
// w (q.w <= q(u).w for every sampled law value q(u): E's support, computed
// without the solver). The blocks are built near the boundary: lambda0 = f L
// q(u) for a random u, so the block sticks iff f <= 1 (q(u) is on the
// boundary: f is known without the solver). Started there again (warmGauge,
// as a caller does in its next solver iteration), or from a direction turned
// by kTurn, the block must decide and return the same, and a converged start
// must cost at most one Newton step.
TEST(FrictionBlockTest, ExactGaugeIsTheBoundaryPointAndWarmStartsTheStickTest) {
  // the law's round-off (~1e-13 of |q|) against sampled exact values
  constexpr double kSupportSlack = 1e-12;
  // the gauge's own tolerance (1e-14 relative), amplified by the 2x2 solve
  constexpr double kParallelTol = 1e-10;
  constexpr double kTurn = 0.05;  // rad: a warm start from a neighbouring visit
  // the value and the Jacobian evaluations of the law (the polygon's Jacobian
  // is a boundary integral over the same closed forms) agree to
  // its accuracy, ~1e-13 relative
  constexpr double kLawTol = 1e-13;
  for (const FrictionPatch& patch : {tiltedRectangle(), tiltedDisk()}) {
    std::mt19937 rng(31);
    std::vector<Vec3> surface;
    for (int i = 0; i < 2000; ++i) surface.push_back(patch.unitQ(Model::Exact, randomUnit(rng)));
    int located = 0, sticks = 0;
    for (int trial = 0; trial < 200; ++trial) {
      FrictionBlockInput in;
      in.K = randomSpd(rng, 0.2, 5.0);
      in.L = 0.5;
      const double f = std::uniform_real_distribution<double>(0.95, 1.05)(rng);
      in.b = -in.K * (f * in.L * patch.unitQ(Model::Exact, randomUnit(rng)));
      const FrictionBlockResult cold = solveFrictionBlock(patch, Model::Exact, in);
      // (1e-9: the decision's own resolution, far above its tolerance)
      if (std::abs(f - 1.0) > 1e-9) {
        EXPECT_EQ(cold.sticking, f < 1.0) << f;
      }
      if (cold.gaugeSlip.isZero(0.0)) continue;
      ++located;
      sticks += cold.sticking;
      const Vec3 w = cold.gaugeSlip, q = cold.gaugeValue;
      EXPECT_NEAR(w.norm(), 1.0, 1e-15);
      EXPECT_LT((q - patch.unitQ(Model::Exact, w)).norm(), kLawTol * q.norm());
      const Vec3 lambda0 = -in.K.inverse() * in.b;
      EXPECT_LT(q.normalized().cross(lambda0.normalized()).norm(), kParallelTol);
      EXPECT_GT(q.dot(lambda0), 0.0);
      for (const Vec3& p : surface) EXPECT_LE(q.dot(w), p.dot(w) + kSupportSlack * q.norm());

      for (const bool turned : {false, true}) {
        FrictionBlockInput warm = in;
        warm.warmGauge = turned ? Vec3(w + kTurn * w.unitOrthogonal()).normalized() : w;
        const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, warm);
        EXPECT_EQ(r.sticking, cold.sticking) << turned;
        EXPECT_LT((r.impulse - cold.impulse).norm(), kSolveTol * (1.0 + cold.impulse.norm()))
            << turned;
        // (one step at most: the start is renormalised, and a residual at
        // the tolerance may then be an ulp above it)
        if (!turned && cold.sticking) {
          EXPECT_LE(r.iterations, 1);
        }
      }
    }
    EXPECT_GE(located, 50);
    EXPECT_GE(sticks, 20);
  }
}

TEST(FrictionBlockTest, RejectsBadInput) {
  const FrictionPatch patch = tiltedDisk();
  FrictionBlockInput in;
  in.L = -1.0;
  EXPECT_THROW(solveFrictionBlock(patch, Model::Ellipsoidal, in), Error);
  in.L = 1.0;
  in.b = Vec3(NAN, 0.0, 0.0);
  EXPECT_THROW(solveFrictionBlock(patch, Model::Exact, in), Error);
  in.b = Vec3(1.0, 0.0, 0.0);
  in.K = -Mat3::Identity();
  EXPECT_THROW(solveFrictionBlock(patch, Model::Exact, in), Error);
  in.K = Mat3::Identity();
  for (const double tol : {-1e-9, 1.0, double(NAN)}) {
    in.tolerance = tol;
    EXPECT_THROW(solveFrictionBlock(patch, Model::Ellipsoidal, in), Error) << tol;
  }
}

}  // namespace
}  // namespace patchspin
