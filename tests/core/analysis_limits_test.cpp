// Limit directions of a flat body (Sect. 5.5-5.6, 6) against closed forms
// re-derived by hand and against independent numerical computations.
//
// Sign convention (see analysis.hpp): the paper's Eq. (3) gives the pressure
// moments with the opposite sign of the physical moment of the pressure on
// the body. With physical moments the paper's Sect. 6.3 results hold with
// T -> -T (w3 -> -w3 of every direction), and Sect. 6.2's (122), (125) hold
// with w2 -> -w2. Derivations of the expected values are next to each test.
#include <gtest/gtest.h>

#include <algorithm>
#include <closed_forms.hpp>
#include <cmath>
#include <oracle.hpp>
#include <patchspin/analysis.hpp>
#include <patchspin/pressure.hpp>
#include <random>

namespace patchspin {
namespace {

// Round-off of a few 3x3 solves and an eigen-decomposition relative to mu g:
// the closed forms below are exact, so agreement is to ~1e-13.
constexpr double kTol = 1e-10;
// The bound on the residual of (106) for reported directions [rel. to mu g].
constexpr double kResidualTol = 1e-10;

constexpr double kMass = 2.0, kRadius = 0.1, kMu = 0.3, kG = 9.81;
const double kFric = kMu * kMass * kG;  // mu m g [N]

FlatBody thinDisk(double F, double T = 0.0) {
  FlatBody body;
  body.shape = PatchShape::disk(kRadius);
  body.mass = kMass;
  body.Jz = kMass * kRadius * kRadius / 2.0;
  body.mu = kMu;
  body.g = kG;
  body.force = Vec2(F, 0.0);
  body.torque = Vec3(T, 0.0, 0.0);
  return body;
}

const LimitDirection* findNear(const LimitAnalysis& a, const Vec3& w, double tol = 1e-7) {
  for (const LimitDirection& d : a.directions) {
    if ((d.w - w).norm() < tol) return &d;
  }
  return nullptr;
}

int countType(const LimitAnalysis& a, bool attracting, LimitType type) {
  return static_cast<int>(std::count_if(
      a.directions.begin(), a.directions.end(),
      [&](const LimitDirection& d) { return d.attracting == attracting && d.type == type; }));
}

std::vector<double> sortedRe(const LimitDirection& d) {
  std::vector<double> v{d.eigenvalues[0].real(), d.eigenvalues[1].real()};
  std::sort(v.begin(), v.end());
  return v;
}

// ---------------------------------------------------------------- Sect. 6.1

// Eq. (113)-(114): kappa^2 = R^2/2, rho = 2R/3 give M33 = m kappa^2/rho^2 = 9m/8;
// uniform pressure gives Pi = I, so B = -mu g diag(1, 1, 8/9), c = (F/m, 0, 0).
TEST(ThinDisk, MatricesMatchEq113And114) {
  const double F = 0.2 * kFric;
  const FlatBodyModel model(thinDisk(F), Model::Ellipsoidal);
  EXPECT_NEAR(model.rho(), 2.0 * kRadius / 3.0, 1e-15);
  const Mat3 Mexp = kMass * Vec3(1.0, 1.0, 9.0 / 8.0).asDiagonal().toDenseMatrix();
  EXPECT_LT((model.massMatrix() - Mexp).norm(), kTol * kMass);
  const Mat3 Bexp = -kMu * kG * Vec3(1.0, 1.0, 8.0 / 9.0).asDiagonal().toDenseMatrix();
  EXPECT_LT((model.linearB() - Bexp).norm(), kTol * kMu * kG);
  EXPECT_LT((model.linearC() - Vec3(F / kMass, 0.0, 0.0)).norm(), kTol * kMu * kG);
  // the same B from the core's FrictionPatch (Pi of Eq. (40))
  const FrictionPatch patch(PatchShape::disk(kRadius),
                            LinearPressure::uniform(PatchShape::disk(kRadius), kMass * kG), kMu);
  const Mat3 Bcore = -kMu * kMass * kG * model.massMatrix().inverse() * patch.Pi();
  EXPECT_LT((model.linearB() - Bcore).norm(), kTol * kMu * kG);
}

// The paper omits (116). Derived: V*(w) = (I - w w^T)(B w + c); its second
// component is -mu g w2 (1 - ...) - w2 R*, which vanishes on w2 = 0: the circle
// w2 = 0 is invariant. Checked on the field itself.
TEST(ThinDisk, CircleW2ZeroIsInvariant) {
  const FlatBodyModel model(thinDisk(0.3 * kFric), Model::Ellipsoidal);
  for (double th = 0.0; th < 2.0 * M_PI; th += 0.1) {
    const Vec3 w(std::cos(th), 0.0, std::sin(th));
    const Vec3 Fo = model.limitField(w);
    const Vec3 V = Fo - w.dot(Fo) * w;
    EXPECT_NEAR(V.y(), 0.0, kTol * kMu * kG);
    // R*(w) of Eq. (115): F/m w1 - mu g (1 - w3^2 / 9)
    EXPECT_NEAR(w.dot(Fo), 0.3 * kFric / kMass * w.x() - kMu * kG * (1.0 - w.z() * w.z() / 9.0),
                kTol * kMu * kG);
  }
}

// Eq. (118)-(119), derived: on w = (+-1, 0, 0), R* = -mu g +- F/m; the tangent
// Jacobian is diag(-mu g, -8/9 mu g) - R*, i.e. eigenvalues -+F/m and
// mu g/9 -+ F/m. On w3,4 = (9F/(mu m g), 0, +-s), R* = -8/9 mu g; tangent
// eigenvalues -mu g/9 (along w2) and -mu g/9 s^2 (in the circle).
void expectThinDiskDirections(double F, int expectedCount) {
  const FlatBodyModel model(thinDisk(F), Model::Ellipsoidal);
  const LimitAnalysis a = findLimitDirections(model);
  ASSERT_TRUE(a.linear);
  ASSERT_EQ(static_cast<int>(a.directions.size()), expectedCount);
  EXPECT_TRUE(a.continua.empty());
  EXPECT_TRUE(a.indexConsistent);
  EXPECT_FALSE(a.tipping);
  const double mg = kMu * kG, f = F / kMass;
  for (double sign : {1.0, -1.0}) {
    const LimitDirection* d = findNear(a, Vec3(sign, 0.0, 0.0));
    ASSERT_NE(d, nullptr);
    EXPECT_NEAR(d->rdot, -mg + sign * f, kTol * mg);
    std::vector<double> expected{-sign * f, mg / 9.0 - sign * f};
    std::sort(expected.begin(), expected.end());
    const std::vector<double> got = sortedRe(*d);
    EXPECT_NEAR(got[0], expected[0], kTol * mg);
    EXPECT_NEAR(got[1], expected[1], kTol * mg);
  }
  const double w1 = 9.0 * F / kFric;
  if (std::abs(w1) < 1.0) {
    const double s = std::sqrt(1.0 - w1 * w1);
    for (double sign : {1.0, -1.0}) {
      const LimitDirection* d = findNear(a, Vec3(w1, 0.0, sign * s));
      ASSERT_NE(d, nullptr);
      EXPECT_NEAR(d->rdot, -8.0 / 9.0 * mg, kTol * mg);
      const std::vector<double> got = sortedRe(*d);
      std::vector<double> expected{-mg / 9.0, -mg / 9.0 * s * s};
      std::sort(expected.begin(), expected.end());
      EXPECT_NEAR(got[0], expected[0], kTol * mg);
      EXPECT_NEAR(got[1], expected[1], kTol * mg);
      EXPECT_TRUE(d->attracting);
      EXPECT_EQ(d->type, LimitType::Dominant);
    }
  }
  for (const LimitDirection& d : a.directions) EXPECT_LT(d.residual, kResidualTol * mg);
}

TEST(ThinDisk, Case1RepellingIsolatedAndAttractingIsolated) {
  const double F = 1.5 * kFric;
  expectThinDiskDirections(F, 2);
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(thinDisk(F), Model::Ellipsoidal));
  const LimitDirection* w1 = findNear(a, Vec3(1, 0, 0));
  const LimitDirection* w2 = findNear(a, Vec3(-1, 0, 0));
  ASSERT_TRUE(w1 && w2);
  EXPECT_FALSE(w1->attracting);
  EXPECT_EQ(w1->type, LimitType::Isolated);
  EXPECT_TRUE(w2->attracting);
  EXPECT_EQ(w2->type, LimitType::Isolated);
}

TEST(ThinDisk, Case2AttractingDominantAndAttractingIsolated) {
  const double F = 0.5 * kFric;
  expectThinDiskDirections(F, 2);
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(thinDisk(F), Model::Ellipsoidal));
  EXPECT_EQ(findNear(a, Vec3(1, 0, 0))->type, LimitType::Dominant);
  EXPECT_TRUE(findNear(a, Vec3(1, 0, 0))->attracting);
  EXPECT_EQ(findNear(a, Vec3(-1, 0, 0))->type, LimitType::Isolated);
}

TEST(ThinDisk, Case3SaddleIsolatedAndTwoDominant) {
  const double F = 0.05 * kFric;
  expectThinDiskDirections(F, 4);
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(thinDisk(F), Model::Ellipsoidal));
  EXPECT_EQ(findNear(a, Vec3(1, 0, 0))->type, LimitType::Saddle);
  EXPECT_TRUE(findNear(a, Vec3(1, 0, 0))->attracting);
  EXPECT_EQ(countType(a, true, LimitType::Dominant), 2);
  EXPECT_EQ(countType(a, true, LimitType::Isolated), 1);
  // negative force mirrors the picture
  expectThinDiskDirections(-0.05 * kFric, 4);
}

// Bifurcations: pitchfork at |F| = mu m g / 9 (w1 nonhyperbolic), attracting to
// repelling at |F| = mu m g (R* = 0 at w1).
TEST(ThinDisk, BifurcationPoints) {
  const double Fc = kFric / 9.0;
  EXPECT_EQ(findLimitDirections(FlatBodyModel(thinDisk(Fc * (1 - 1e-6)), Model::Ellipsoidal))
                .directions.size(),
            4u);
  EXPECT_EQ(findLimitDirections(FlatBodyModel(thinDisk(Fc * (1 + 1e-6)), Model::Ellipsoidal))
                .directions.size(),
            2u);
  const LimitAnalysis atPitchfork =
      findLimitDirections(FlatBodyModel(thinDisk(Fc), Model::Ellipsoidal));
  EXPECT_EQ(findNear(atPitchfork, Vec3(1, 0, 0))->type, LimitType::Nonhyperbolic);
  const LimitAnalysis atTurn =
      findLimitDirections(FlatBodyModel(thinDisk(kFric), Model::Ellipsoidal));
  EXPECT_NEAR(findNear(atTurn, Vec3(1, 0, 0))->rdot, 0.0, kTol * kMu * kG);
  EXPECT_EQ(findNear(atTurn, Vec3(1, 0, 0))->type, LimitType::Nonhyperbolic);
}

// F = 0, Prop. 3: the circle w3 = 0 (R* = -mu g) is a continuum; the poles
// (pure spin, R* = -8/9 mu g, eigenvalues -mu g/9 twice) are attracting-dominant.
TEST(ThinDisk, ForceFreeContinuumAndPoles) {
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(thinDisk(0.0), Model::Ellipsoidal));
  ASSERT_EQ(a.continua.size(), 1u);
  EXPECT_FALSE(a.continua[0].sphere);
  EXPECT_NEAR(std::abs(a.continua[0].normal.z()), 1.0, kTol);
  EXPECT_NEAR(a.continua[0].offset, 0.0, kTol);
  EXPECT_NEAR(a.continua[0].rdot, -kMu * kG, kTol * kMu * kG);
  EXPECT_TRUE(a.continua[0].attracting);
  ASSERT_EQ(a.directions.size(), 2u);
  for (const LimitDirection& d : a.directions) {
    EXPECT_NEAR(std::abs(d.w.z()), 1.0, kTol);
    EXPECT_NEAR(d.rdot, -8.0 / 9.0 * kMu * kG, kTol * kMu * kG);
    EXPECT_EQ(d.type, LimitType::Dominant);
  }
}

// A pure spin-up torque about z: c = (0, 0, c3) gives the circle
// (R* + mu g)(w1, w2) = 0, w3 = c3 / (R* + 8/9 mu g) = -9 c3 / (mu g): a
// continuum with c != 0, plus two isolated directions on the w3 axis.
TEST(ThinDisk, ContinuumWithSpinTorque) {
  FlatBody body = thinDisk(0.0);
  const double c3 = 0.05 * kMu * kG;  // [m/s^2]
  const FlatBodyModel probe(body, Model::Ellipsoidal);
  body.torque.z() = c3 * probe.massMatrix()(2, 2) * probe.rho();
  const FlatBodyModel model(body, Model::Ellipsoidal);
  const LimitAnalysis a = findLimitDirections(model);
  ASSERT_EQ(a.continua.size(), 1u);
  EXPECT_NEAR(a.continua[0].rdot, -kMu * kG, kTol * kMu * kG);
  EXPECT_NEAR(a.continua[0].centre().z(), -9.0 * c3 / (kMu * kG), 1e-9);
  EXPECT_NEAR(a.continua[0].radius(), std::sqrt(1.0 - std::pow(9.0 * c3 / (kMu * kG), 2)), 1e-9);
  // isolated: w = (0, 0, +-1), R* = -8/9 mu g +- c3
  ASSERT_EQ(a.directions.size(), 2u);
  for (const LimitDirection& d : a.directions) {
    EXPECT_NEAR(std::abs(d.w.z()), 1.0, kTol);
    EXPECT_NEAR(d.rdot, -8.0 / 9.0 * kMu * kG + d.w.z() * c3, kTol * kMu * kG);
  }
}

// ---------------------------------------------------------------- Prop. 2

// Prop. 2: (pi_x - x_c, pi_y - y_c, 0) is an eigenvector of B with eigenvalue
// -mu Pz / m. Independently from statics: at rest the pressure centre
// satisfies (∫y p, -∫x p) + r_c x (0, 0, -m g) + T = 0, so
// pi_x - x_c = T_y / (m g), pi_y - y_c = -T_x / (m g).
TEST(Prop2, EigenvectorFromStatics) {
  FlatBody body;
  body.shape = PatchShape::rectangle(0.3, 0.2, Vec2(0.02, -0.01), 0.3);
  body.mass = 1.5;
  body.Jz = 0.02;
  body.com = Vec3(0.01, 0.015, 0.0);
  body.mu = 0.4;
  body.g = 9.81;
  body.torque = Vec3(0.12, -0.2, 0.0);
  const FlatBodyModel model(body, Model::Ellipsoidal);
  const double mg = body.mass * body.g;
  const Vec3 gamma = Vec3(body.torque.y() / mg, -body.torque.x() / mg, 0.0).normalized();
  const double lambda = -body.mu * body.g;
  EXPECT_LT((model.linearB() * gamma - lambda * gamma).norm(), kTol * body.mu * body.g);
  const LimitAnalysis a = findLimitDirections(model);
  EXPECT_EQ(a.directions.size(), 6u);  // the conjecture after Prop. 2: B has real spectrum here
  for (double sign : {1.0, -1.0}) {
    const LimitDirection* d = findNear(a, sign * gamma, 1e-9);
    ASSERT_NE(d, nullptr);
    EXPECT_NEAR(d->rdot, lambda, kTol * body.mu * body.g);
  }
}

// Prop. 3: no couple, centre of mass over the pressure centre: the circle
// w3 = 0 is a continuum with R* = -mu Pz / m.
TEST(Prop3, OffsetCentreOfMassGivesContinuum) {
  FlatBody body;
  body.shape = PatchShape::regularPolygon(5, 0.1);
  body.mass = 1.0;
  body.Jz = 0.004;
  body.com = Vec3(0.02, -0.01, 0.0);
  body.mu = 0.5;
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(body, Model::Ellipsoidal));
  ASSERT_EQ(a.continua.size(), 1u);
  EXPECT_NEAR(std::abs(a.continua[0].normal.z()), 1.0, 1e-9);
  EXPECT_NEAR(a.continua[0].rdot, -body.mu * body.g, kTol * body.mu * body.g);
  EXPECT_EQ(a.directions.size(), 2u);
}

// ---------------------------------------------------------------- Sect. 6.3

// Physical torque T about x (zeta = T/(m g R)): p0 = m g/(pi R^2),
// c_y = -4T/(pi R^4), so Pi = [[1,0,4 zeta/3],[0,1,0],[3 zeta/2,0,1]] and
// B = -mu g [[1,0,4 zeta/3],[0,1,0],[4 zeta/3,0,8/9]] (the paper's (128) has a
// stray mu and, by Eq. (3)'s sign, -zeta). With xi = F/(mu m g), s = R*/(mu g):
//   (s+1) w1 + 4 zeta/3 w3 = xi,  (s+1) w2 = 0,  (s+8/9) w3 + 4 zeta/3 w1 = 0.
// Off the circle (s = -1): w5,6 = (xi/(16 zeta^2), +-.., 3 xi/(4 zeta)), real for
//   |xi| < 16 zeta^2 / sqrt(1 + 144 zeta^2)                    (F_crit^4/6)
// On the circle, eliminating s and w1 (w1 w3 = 9 xi w3 + 12 zeta - 24 zeta w3^2):
//   (576 z^2+1) w3^4 - 432 xi z w3^3 + (81 xi^2 - 576 z^2 - 1) w3^2 + 216 xi z w3 + 144 z^2 = 0
// (the paper's (130) with z -> -z). R* = 0 on the circle gives w3 = -3 zeta w1/2,
//   xi = (1 - 2 zeta^2) / sqrt(1 + 9 zeta^2 / 4)                 (F_crit^2/2)
// (the paper's "1 - 2 zeta^2" drops the normalisation of w).
double quartic(double w3, double xi, double z) {
  return (576 * z * z + 1) * std::pow(w3, 4) - 432 * xi * z * std::pow(w3, 3) +
         (81 * xi * xi - 576 * z * z - 1) * w3 * w3 + 216 * xi * z * w3 + 144 * z * z;
}
double quarticDw(double w3, double xi, double z) {
  return 4 * (576 * z * z + 1) * std::pow(w3, 3) - 3 * 432 * xi * z * w3 * w3 +
         2 * (81 * xi * xi - 576 * z * z - 1) * w3 + 216 * xi * z;
}

// F_crit^2/4: the quartic's double root, by Newton on (w3, xi) for q = q' = 0
// (started from a scan of q's minimum), independent of the limit solver.
double criticalXi24(double z) {
  double best = 1e300, w3 = 0.0, xi = 0.0;
  for (double x = 0.05; x < 1.0; x += 0.001) {
    for (double w = -0.999; w < 0.999; w += 0.002) {
      const double q = std::abs(quartic(w, x, z)) + std::abs(quarticDw(w, x, z));
      if (q < best) best = q, w3 = w, xi = x;
    }
  }
  for (int it = 0; it < 50; ++it) {
    const double h = 1e-7;
    const double f1 = quartic(w3, xi, z), f2 = quarticDw(w3, xi, z);
    const double a = (quartic(w3 + h, xi, z) - quartic(w3 - h, xi, z)) / (2 * h);
    const double b = (quartic(w3, xi + h, z) - quartic(w3, xi - h, z)) / (2 * h);
    const double c = (quarticDw(w3 + h, xi, z) - quarticDw(w3 - h, xi, z)) / (2 * h);
    const double d = (quarticDw(w3, xi + h, z) - quarticDw(w3, xi - h, z)) / (2 * h);
    const double det = a * d - b * c;
    w3 -= (d * f1 - b * f2) / det;
    xi -= (-c * f1 + a * f2) / det;
  }
  return xi;
}

LimitAnalysis torqueCase(double xi, double zeta) {
  return findLimitDirections(
      FlatBodyModel(thinDisk(xi * kFric, zeta * kMass * kG * kRadius), Model::Ellipsoidal));
}

TEST(ThinDiskTorque, CriticalForcesOrdered) {
  const double z = 0.2;
  const double xi46 = 16 * z * z / std::sqrt(1 + 144 * z * z);
  const double xi24 = criticalXi24(z);
  const double xi22 = (1 - 2 * z * z) / std::sqrt(1 + 9 * z * z / 4);
  EXPECT_LT(xi46, xi24);
  EXPECT_LT(xi24, xi22);
  // count changes exactly at the critical forces (relative offset 1e-4)
  constexpr double kOff = 1e-4;
  EXPECT_EQ(torqueCase(xi46 * (1 - kOff), z).directions.size(), 6u);
  EXPECT_EQ(torqueCase(xi46 * (1 + kOff), z).directions.size(), 4u);
  EXPECT_EQ(torqueCase(xi24 * (1 - kOff), z).directions.size(), 4u);
  EXPECT_EQ(torqueCase(xi24 * (1 + kOff), z).directions.size(), 2u);
}

TEST(ThinDiskTorque, AllFourCases) {
  const double z = 0.2;
  const double xi46 = 16 * z * z / std::sqrt(1 + 144 * z * z);
  const double xi24 = criticalXi24(z);
  const double xi22 = (1 - 2 * z * z) / std::sqrt(1 + 9 * z * z / 4);
  // Case 4: six directions; w5,6 of (132) (physical sign) are attracting saddles
  {
    const double xi = 0.5 * xi46;
    const LimitAnalysis a = torqueCase(xi, z);
    ASSERT_EQ(a.directions.size(), 6u);
    EXPECT_FALSE(a.tipping);
    const double w1 = xi / (16 * z * z), w3 = 3 * xi / (4 * z);
    const double w2 = std::sqrt(1 - w1 * w1 - w3 * w3);
    for (double sign : {1.0, -1.0}) {
      const LimitDirection* d = findNear(a, Vec3(w1, sign * w2, w3), 1e-9);
      ASSERT_NE(d, nullptr);
      EXPECT_NEAR(d->rdot, -kMu * kG, kTol * kMu * kG);
      EXPECT_TRUE(d->attracting);
      EXPECT_EQ(d->type, LimitType::Saddle);
    }
    EXPECT_EQ(countType(a, true, LimitType::Isolated), 2);
    EXPECT_EQ(countType(a, true, LimitType::Dominant), 2);
    EXPECT_EQ(countType(a, true, LimitType::Saddle), 2);
    for (const LimitDirection& d : a.directions) {
      if (std::abs(d.w.y()) < 1e-9) {
        EXPECT_NEAR(quartic(d.w.z(), xi, z), 0.0, 1e-9);
      }
    }
  }
  // Case 3: four on the circle: one saddle, one isolated, two dominant
  {
    const double xi = 0.5 * (xi46 + xi24);
    const LimitAnalysis a = torqueCase(xi, z);
    ASSERT_EQ(a.directions.size(), 4u);
    EXPECT_EQ(countType(a, true, LimitType::Dominant), 2);
    EXPECT_EQ(countType(a, true, LimitType::Saddle), 1);
    EXPECT_EQ(countType(a, true, LimitType::Isolated), 1);
    for (const LimitDirection& d : a.directions) {
      EXPECT_NEAR(d.w.y(), 0.0, 1e-9);
      EXPECT_NEAR(quartic(d.w.z(), xi, z), 0.0, 1e-9);
    }
  }
  // Case 2: attracting-dominant + attracting-isolated
  {
    const LimitAnalysis a = torqueCase(0.5 * (xi24 + xi22), z);
    ASSERT_EQ(a.directions.size(), 2u);
    EXPECT_EQ(countType(a, true, LimitType::Dominant), 1);
    EXPECT_EQ(countType(a, true, LimitType::Isolated), 1);
  }
  // Case 1: repelling-isolated + attracting-isolated
  {
    const LimitAnalysis a = torqueCase(1.2 * xi22, z);
    ASSERT_EQ(a.directions.size(), 2u);
    EXPECT_EQ(countType(a, false, LimitType::Isolated), 1);
    EXPECT_EQ(countType(a, true, LimitType::Isolated), 1);
  }
}

// F_crit^2/2: at xi22 the direction w = (1, 0, -3 zeta/2)/|.| has R* = 0.
TEST(ThinDiskTorque, AttractingTurnsRepellingAtVerifiedCriticalForce) {
  const double z = 0.2;
  const double xi22 = (1 - 2 * z * z) / std::sqrt(1 + 9 * z * z / 4);
  const Vec3 w = Vec3(1.0, 0.0, -1.5 * z).normalized();
  const LimitAnalysis at = torqueCase(xi22, z);
  const LimitDirection* d = findNear(at, w, 1e-9);
  ASSERT_NE(d, nullptr);
  EXPECT_NEAR(d->rdot, 0.0, kTol * kMu * kG);
  // the paper's 1 - 2 zeta^2 is beyond it: there this direction already repels
  const LimitAnalysis paper = torqueCase(1 - 2 * z * z, z);
  int repelling = 0;
  for (const LimitDirection& e : paper.directions) repelling += e.attracting ? 0 : 1;
  EXPECT_EQ(repelling, 1);
}

// Validity of the linear pressure (end of Sect. 6.3): p >= 0 iff |zeta| <= 1/4.
TEST(ThinDiskTorque, TippingBeyondQuarter) {
  EXPECT_FALSE(torqueCase(0.1, 0.249).tipping);
  EXPECT_TRUE(torqueCase(0.1, 0.251).tipping);
}

// ---------------------------------------------------------------- Sect. 6.2

// Thick disk (centre of mass at height h, eta = mu h / R): N != 0, Pi(w).
// Derived with physical moments: a = c_x R/p0, b = c_y R/p0,
//   a = 12 eta (3 w1 - 4 eta w2 w3) / D,  b = 12 eta (3 w2 + 4 eta w1 w3) / D,
//   D = 9 + 16 eta^2 w3^2 (the paper's (122): w2 -> -w2), and
//   R* = -8/9 mu g + mu g 16 eta^2 (1 - w3^2) / D                       (124)
//   w1 = (1 - w3^2) K / (9 D xi),  w2 = -12 eta w3 (1 - w3^2) / (D xi),
//   K = 9 + 144 eta^2 - 272 eta^2 w3^2                         ((125), w2 -> -w2)
// and w1 -> 1 as w3 -> 0 gives F_crit = mu m g (1 + 16 eta^2) / 9     (127).
FlatBody thickDisk(double F, double eta) {
  FlatBody body = thinDisk(F);
  body.com.z() = eta * kRadius / kMu;
  return body;
}

TEST(ThickDisk, PressureLeansForward) {
  // sliding along +x the friction at the base pitches the front (+x) down:
  // physically c_x > 0; and a = 12 eta * 3 / 9 = 4 eta at w = (1, 0, 0)
  const double eta = 0.2;
  const FlatBodyModel model(thickDisk(0.0, eta), Model::Ellipsoidal);
  const ContactState c = model.contact(Vec3::UnitX(), 0.0, model.bodyLoads());
  EXPECT_GT(c.pressure[1], 0.0);
  EXPECT_NEAR(c.pressure[1] * kRadius / c.pressure[0], 4 * eta, 1e-12);
  EXPECT_NEAR(c.pressure[2], 0.0, 1e-9 * c.pressure[0] / kRadius);
  // general w: compare with the closed form above
  const Vec3 w = Vec3(0.3, -0.5, 0.7).normalized();
  const ContactState cw = model.contact(w, 0.0, model.bodyLoads());
  const double D = 9 + 16 * eta * eta * w.z() * w.z();
  EXPECT_NEAR(cw.pressure[1] * kRadius / cw.pressure[0],
              12 * eta * (3 * w.x() - 4 * eta * w.y() * w.z()) / D, 1e-12);
  EXPECT_NEAR(cw.pressure[2] * kRadius / cw.pressure[0],
              12 * eta * (3 * w.y() + 4 * eta * w.x() * w.z()) / D, 1e-12);
}

TEST(ThickDisk, NontrivialDirectionsMatchDerivation) {
  const double eta = 0.2;
  const double xi = 0.08;
  const FlatBodyModel model(thickDisk(xi * kFric, eta), Model::Ellipsoidal);
  const LimitAnalysis a = findLimitDirections(model);
  EXPECT_FALSE(a.linear);
  ASSERT_EQ(a.directions.size(), 4u);
  EXPECT_TRUE(a.indexConsistent);
  int nontrivial = 0;
  for (const LimitDirection& d : a.directions) {
    const double w3 = d.w.z();
    if (std::abs(w3) < 1e-9) continue;
    ++nontrivial;
    const double D = 9 + 16 * eta * eta * w3 * w3;
    const double K = 9 + 144 * eta * eta - 272 * eta * eta * w3 * w3;
    EXPECT_NEAR(d.rdot, -8.0 / 9.0 * kMu * kG + kMu * kG * 16 * eta * eta * (1 - w3 * w3) / D,
                1e-9);
    EXPECT_NEAR(d.w.x(), (1 - w3 * w3) * K / (9 * D * xi), 1e-9);
    EXPECT_NEAR(d.w.y(), -12 * eta * w3 * (1 - w3 * w3) / (D * xi), 1e-9);
    EXPECT_TRUE(d.attracting);
    EXPECT_EQ(d.type, LimitType::Dominant);
  }
  EXPECT_EQ(nontrivial, 2);
}

TEST(ThickDisk, CriticalForceEq127) {
  for (double eta : {0.1, 0.2}) {
    const double Fc = kFric * (1 + 16 * eta * eta) / 9.0;
    const LimitAnalysis below =
        findLimitDirections(FlatBodyModel(thickDisk(0.97 * Fc, eta), Model::Ellipsoidal));
    const LimitAnalysis above =
        findLimitDirections(FlatBodyModel(thickDisk(1.03 * Fc, eta), Model::Ellipsoidal));
    EXPECT_EQ(below.directions.size(), 4u) << eta;
    EXPECT_EQ(above.directions.size(), 2u) << eta;
    // at Fc the pitchfork: w = (1, 0, 0) is nonhyperbolic (an eigenvalue crosses 0)
    const LimitDirection at =
        classifyDirection(FlatBodyModel(thickDisk(Fc, eta), Model::Ellipsoidal), Vec3::UnitX());
    EXPECT_NEAR(std::min(std::abs(at.eigenvalues[0]), std::abs(at.eigenvalues[1])), 0.0, 1e-9);
  }
}

// End of Sect. 6.2: p >= 0 in every direction iff 160 eta^2 w3^2 - 144 eta^2 + 9 >= 0;
// at w = (1, 0, 0) (a limit direction) this needs eta <= 1/4.
TEST(ThickDisk, TippingBeyondQuarter) {
  EXPECT_FALSE(
      findLimitDirections(FlatBodyModel(thickDisk(0.5 * kFric, 0.24), Model::Ellipsoidal)).tipping);
  EXPECT_TRUE(
      findLimitDirections(FlatBodyModel(thickDisk(0.5 * kFric, 0.26), Model::Ellipsoidal)).tipping);
}

// ---------------------------------------------------------------- properties

// Random flat bodies and loads (fixed seed): 2, 4 or 6 directions (Prop. 6,
// generic), each solving (106) to 1e-10, Poincare-Hopf index sum 2, and the
// same set as the independent sphere solver (Newton from a seed grid).
TEST(Properties, RandomLinearBodies) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    FlatBody body;
    const double L = 0.1;
    if (trial % 2 == 0) {
      body.shape = PatchShape::disk(L, Vec2(0.3 * L * u(rng), 0.3 * L * u(rng)));
    } else {
      body.shape = PatchShape::rectangle(L * (1.2 + 0.5 * u(rng)), L * (0.8 + 0.3 * u(rng)),
                                         Vec2(0.2 * L * u(rng), 0.2 * L * u(rng)), u(rng));
    }
    body.mass = 1.0 + 0.5 * u(rng);
    body.Jz = body.mass * L * L * (0.4 + 0.2 * u(rng));
    body.com = Vec3(0.2 * L * u(rng), 0.2 * L * u(rng), 0.0);
    body.mu = 0.4 + 0.2 * u(rng);
    const double fr = body.mu * body.mass * body.g;
    body.force = Vec2(0.5 * fr * u(rng), 0.5 * fr * u(rng));
    body.torque = Vec3(0.02 * fr * L * u(rng), 0.02 * fr * L * u(rng), 0.1 * fr * L * u(rng));
    const FlatBodyModel model(body, Model::Ellipsoidal);
    const LimitAnalysis a = findLimitDirections(model);
    ASSERT_TRUE(a.linear);
    const std::size_t n = a.directions.size();
    EXPECT_TRUE(n == 2 || n == 4 || n == 6) << "trial " << trial << ": " << n;
    EXPECT_TRUE(a.indexConsistent) << trial;
    const Mat3 B = model.linearB();
    const Vec3 c = model.linearC();
    for (const LimitDirection& d : a.directions) {
      EXPECT_LT(((d.rdot * Mat3::Identity() - B) * d.w - c).norm(),
                kResidualTol * body.mu * body.g);
      EXPECT_NEAR(d.w.norm(), 1.0, 1e-14);
    }
    LimitOptions sphere;
    sphere.sphereSolver = true;
    sphere.seeds = 300;
    const LimitAnalysis b = findLimitDirections(model, sphere);
    EXPECT_EQ(b.directions.size(), n) << trial;
    for (const LimitDirection& d : b.directions)
      EXPECT_NE(findNear(a, d.w, 1e-7), nullptr) << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 40);
}

// ---------------------------------------------------------------- exact law

// Thin disk, exact law (16). Near w = (1, 0, 0) with small spin, the local slip
// direction is (1, omega x / u) to first order, so T_z = -mu p0 (omega/u) ∫x^2
// = -mu Pz (R^2/4)(omega/u), i.e. dQ3/dw3 = -mu Pz R^2/(4 rho^2) = -9/16 mu Pz
// (ellipsoidal: -mu Pz). With M33 = 9m/8 the tangent eigenvalue along w3 is
// -mu g/2 - R* = mu g/2 - F/m: the exact-law critical force is mu m g / 2,
// not the ellipsoidal mu m g / 9.
TEST(ExactThinDisk, CriticalForceIsHalfMuMg) {
  const double F1 = 0.3 * kFric, F2 = 0.7 * kFric;
  auto lambdaW3 = [](double F) {
    const LimitDirection d =
        classifyDirection(FlatBodyModel(thinDisk(F), Model::Exact), Vec3::UnitX());
    return d.eigenvalues[1].real();  // the larger one: mu g/2 - F/m
  };
  const double l1 = lambdaW3(F1), l2 = lambdaW3(F2);
  const double Fzero = F1 - l1 * (F2 - F1) / (l2 - l1);  // linear in F
  // 1e-8: the exact law's Jacobian is accurate to ~1e-10 relative
  EXPECT_NEAR(Fzero / kFric, 0.5, 1e-8);
  EXPECT_NEAR(l1, kMu * kG / 2 - F1 / kMass, 1e-8 * kMu * kG);
  // the global solver sees the count change at 0.5 mu m g (within 0.2 %),
  // and the nontrivial pair is born there in a supercritical pitchfork:
  // w3^2 ~ (F_crit - F), so w3^2 at 1 % and 0.1 % below differ by 10 (the
  // next order, O(F_crit - F), allows the 5 %)
  LimitOptions opt;
  opt.seeds = 200;
  auto spin = [&](double xi) {
    const LimitAnalysis a =
        findLimitDirections(FlatBodyModel(thinDisk(xi * kFric), Model::Exact), opt);
    EXPECT_TRUE(a.indexConsistent) << xi;
    double w3 = 0.0;
    for (const LimitDirection& d : a.directions) w3 = std::max(w3, d.w.z());
    return std::make_pair(a.directions.size(), w3);
  };
  const auto far = spin(0.49), near = spin(0.499), above = spin(0.501);
  EXPECT_EQ(far.first, 4u);
  EXPECT_EQ(near.first, 4u);
  EXPECT_EQ(above.first, 2u);
  EXPECT_NEAR(std::pow(far.second / near.second, 2), 10.0, 0.5);
}

// Farkas et al. (2003): the free uniform disk stops with v/(R omega) = 0.6530.
// Independently from the elliptic closed forms (52)-(53): on w2 = 0,
// F_o = -mu g (P(eps), 0, 8/9 T(eps)) must be parallel to w with
// w1/w3 = (R/rho) eps = 1.5 eps, i.e. P(eps) = 4/3 eps T(eps).
TEST(ExactThinDisk, ForceFreeContinuaGiveFarkasRatio) {
  double lo = 0.3, hi = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double f =
        testing::uniformDiskForce(mid) - 4.0 / 3.0 * mid * testing::uniformDiskTorque(mid);
    const double flo =
        testing::uniformDiskForce(lo) - 4.0 / 3.0 * lo * testing::uniformDiskTorque(lo);
    ((f > 0) == (flo > 0) ? lo : hi) = mid;
  }
  const double epsClosed = 0.5 * (lo + hi);
  EXPECT_NEAR(epsClosed, 0.6530, 5e-5);  // published to four digits
  LimitOptions opt;
  opt.seeds = 200;
  const LimitAnalysis a = findLimitDirections(FlatBodyModel(thinDisk(0.0), Model::Exact), opt);
  // circles: w3 = 0 (pure translation) and w3 = +-1/sqrt(1 + (1.5 eps)^2)
  ASSERT_EQ(a.continua.size(), 3u);
  const double w3 = 1.0 / std::sqrt(1.0 + std::pow(1.5 * epsClosed, 2));
  int found = 0;
  for (const LimitContinuum& c : a.continua) {
    EXPECT_NEAR(std::abs(c.normal.z()), 1.0, 1e-8);
    const double z = c.offset * c.normal.z();
    if (std::abs(std::abs(z) - w3) < 1e-8) ++found;
  }
  EXPECT_EQ(found, 2);
  // the poles (pure spin) are isolated directions
  EXPECT_EQ(a.directions.size(), 2u);
}

}  // namespace
}  // namespace patchspin
