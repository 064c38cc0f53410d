// Linear pressure and loads, Eq. (94); admissible loads (p >= 0); the
// averages (36) and Pi (40); the Hertz pressure (57). Independent references:
// brute-force quadrature (tests/support/oracle) and hand derivations.
#include <patchspin/pressure.hpp>

#include "oracle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace patchspin {
namespace {

using testing::bruteForceAreaMoments;
using testing::bruteForceIntegral;
using testing::bruteForcePiMoments;
using testing::hertzField;
using testing::linearField;

constexpr double kPi = 3.14159265358979323846;
// Oracle quadrature runs at relTol 1e-13; the core's moments are closed forms
// or 1e-15 quadrature. 1e-12 relative is the brief's target with margin.
constexpr double kIntegralRelTol = 1e-12;
// Solving Eq. (94) forward (loads -> coefficients) loses up to cond(G) digits;
// the shapes below have a scaled condition number < kMaxCondition (asserted),
// so 1e-13 * kMaxCondition bounds the forward error.
constexpr double kMaxCondition = 1e3;
constexpr double kForwardRelTol = 1e-13 * kMaxCondition;
// nearestAdmissibleLoads: the projection is a small optimisation (vertex
// enumeration for polygons, a 1-D search for disks); 1e-9 relative is far
// below anything a solver would notice and far above round-off.
constexpr double kProjectionRelTol = 1e-9;
// Accuracy asked of the oracle (one digit below kIntegralRelTol).
constexpr double kOracleRelTol = 1e-13;
// A few ulps of O(1) quantities (a handful of flops).
constexpr double kRoundOff = 1e-14;

std::vector<PatchShape> testShapes() {
  return {
      PatchShape::disk(0.7),
      PatchShape::disk(0.5, Vec2(0.2, -0.1)),
      PatchShape::disk(0.3, Vec2(0.9, 0.4)),  // O outside
      PatchShape::rectangle(1.0, 0.4),
      PatchShape::rectangle(0.8, 0.3, Vec2(0.1, 0.05), 0.6),
      PatchShape::rectangle(0.5, 0.2, Vec2(0.6, -0.4), -0.3),  // O outside
      PatchShape::polygon({{-0.2, -0.3}, {0.6, -0.1}, {0.4, 0.5}, {-0.3, 0.2}}),
      PatchShape::regularPolygon(7, 0.45, Vec2(-0.3, 0.5), 0.2),  // O outside
  };
}

// Loads of a pressure field by brute force, Eq. (2)-(3):
//   Pz = ∫p dA, Tx = -∫y p dA, Ty = ∫x p dA.
PatchLoads bruteForceLoads(const PatchShape& shape, const testing::ScalarField& p) {
  PatchLoads l;
  l.Pz = bruteForceIntegral(shape, p, kOracleRelTol);
  l.Tx = -bruteForceIntegral(
      shape, [&](const Vec2& q) { return q.y() * p(q); }, kOracleRelTol);
  l.Ty = bruteForceIntegral(
      shape, [&](const Vec2& q) { return q.x() * p(q); }, kOracleRelTol);
  return l;
}

// Smallest value of a linear pressure on the shape, computed here directly:
// at a vertex for polygons, p(C) - R |grad p| for a disk.
double directMinPressure(const PatchShape& shape, const LinearPressure& p) {
  if (shape.isDisk()) return p.at(shape.centre()) - shape.radius() * std::hypot(p.cx, p.cy);
  double m = std::numeric_limits<double>::infinity();
  for (const Vec2& v : shape.vertices()) m = std::min(m, p.at(v));
  return m;
}

// Random pressure with mean ~1 Pa, gradients up to ~1/l.
LinearPressure randomPressure(const PatchShape& shape, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double l = shape.diameter();
  return LinearPressure{1.0 + 0.3 * u(rng), u(rng) / l, u(rng) / l};
}

Vec3 scaled(const PatchLoads& l, double rho) {
  return Vec3(l.Pz, l.Tx / rho, l.Ty / rho);
}

// ---- Eq. (94) ----------------------------------------------------------------

TEST(Loads, LoadsOfMatchesBruteForce) {
  std::mt19937 rng(1);
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const LinearPressure p = randomPressure(shape, rng);
    const PatchLoads ref = bruteForceLoads(shape, linearField(p));
    const PatchLoads got = loadsOf(shape, p);
    const double l = shape.maxDistanceFromOrigin();
    const double scale = std::abs(ref.Pz);
    EXPECT_NEAR(got.Pz, ref.Pz, kIntegralRelTol * scale);
    EXPECT_NEAR(got.Tx, ref.Tx, kIntegralRelTol * scale * l);
    EXPECT_NEAR(got.Ty, ref.Ty, kIntegralRelTol * scale * l);
  }
}

TEST(Loads, FromLoadsRecoversPressure) {
  std::mt19937 rng(2);
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    // conditioning of G in units (1, l, l), which the tolerance relies on
    const double l = shape.maxDistanceFromOrigin();
    const Eigen::DiagonalMatrix<double, 3> D(1.0, l, l);
    const Mat3 Gs = D.inverse() * shape.areaMoments().loadMatrix() * D.inverse();
    const Vec3 sv = Eigen::JacobiSVD<Mat3>(Gs).singularValues();
    const double cond = sv(0) / sv(2);
    ASSERT_LT(cond, kMaxCondition);

    const LinearPressure p = randomPressure(shape, rng);
    const LinearPressure got =
        LinearPressure::fromLoads(shape, bruteForceLoads(shape, linearField(p)));
    const double pScale = std::abs(p.p0) + l * std::hypot(p.cx, p.cy);
    EXPECT_NEAR(got.p0, p.p0, kForwardRelTol * pScale);
    EXPECT_NEAR(got.cx, p.cx, kForwardRelTol * pScale / l);
    EXPECT_NEAR(got.cy, p.cy, kForwardRelTol * pScale / l);
    // and back: loadsOf o fromLoads = identity (backward-stable solve)
    const PatchLoads loads{2.0, 0.1 * l, -0.05 * l};
    const PatchLoads back = loadsOf(shape, LinearPressure::fromLoads(shape, loads));
    EXPECT_NEAR(back.Pz, loads.Pz, kForwardRelTol * loads.Pz);
    EXPECT_NEAR(back.Tx, loads.Tx, kForwardRelTol * loads.Pz * l);
    EXPECT_NEAR(back.Ty, loads.Ty, kForwardRelTol * loads.Pz * l);
  }
}

TEST(Loads, UniformPressure) {
  for (const PatchShape& shape : testShapes()) {
    const LinearPressure p = LinearPressure::uniform(shape, 3.0);
    EXPECT_NEAR(p.p0, 3.0 / shape.area(), kRoundOff * p.p0);
    EXPECT_EQ(p.cx, 0.0);
    EXPECT_EQ(p.cy, 0.0);
  }
}

TEST(Loads, NonFiniteLoadsThrow) {
  const PatchShape shape = PatchShape::disk(1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LinearPressure::fromLoads(shape, PatchLoads{nan, 0.0, 0.0}), Error);
  EXPECT_THROW(LinearPressure::fromLoads(shape, PatchLoads{1.0, 0.0, HUGE_VAL}), Error);
}

// ---- minimum pressure and admissibility --------------------------------------

TEST(Admissible, MinPressure) {
  std::mt19937 rng(3);
  // a dense rim / vertex sample may not go below the reported minimum; on the
  // disk the sample's own minimum is within |grad p| R (1 - cos(pi / n)).
  constexpr int kRimSamples = 3600;
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const LinearPressure p = randomPressure(shape, rng);
    const double got = minPressure(shape, p);
    EXPECT_NEAR(got, directMinPressure(shape, p), kRoundOff);
    if (shape.isDisk()) {
      double sampled = std::numeric_limits<double>::infinity();
      for (int i = 0; i < kRimSamples; ++i) {
        const double a = 2 * kPi * i / kRimSamples;
        sampled = std::min(sampled,
                           p.at(shape.centre() + shape.radius() * Vec2(std::cos(a), std::sin(a))));
      }
      const double gap =
          std::hypot(p.cx, p.cy) * shape.radius() * (1 - std::cos(kPi / kRimSamples));
      EXPECT_GE(sampled, got - kRoundOff);
      EXPECT_LE(sampled, got + gap + kRoundOff);
    }
  }
}

// DESIGN item 2: for a disk of radius R centred at O the admissible loads are
// the cone sqrt(Tx^2 + Ty^2) <= Pz R / 4. Derivation: p = p0 + c.(x, y) has
// min p0 - R|c|; Pz = p0 pi R^2, (Ty, -Tx) = c pi R^4 / 4, so
// p >= 0 <=> |c| R <= p0 <=> |T| = |c| pi R^4/4 <= p0 pi R^2 R / 4 = Pz R / 4.
TEST(Admissible, CentredDiskCone) {
  const double R = 0.6;
  const PatchShape disk = PatchShape::disk(R);
  // check the claim by brute force: a pressure touching zero has |T| = Pz R/4
  for (double dir : {0.0, 1.0, 2.5, 4.0}) {
    const LinearPressure p{1.0, std::cos(dir) / R, std::sin(dir) / R};  // min = 0
    const PatchLoads l = bruteForceLoads(disk, linearField(p));
    EXPECT_NEAR(std::hypot(l.Tx, l.Ty), l.Pz * R / 4.0, kIntegralRelTol * l.Pz * R);
  }
  // and the core's predicate on both sides of the cone (margin 1e-9 >> relTol)
  for (double dir : {0.3, 2.0, -1.2}) {
    for (double Pz : {0.01, 1.0, 250.0}) {
      const double t = Pz * R / 4.0;
      const PatchLoads inside{Pz, (1 - 1e-9) * t * std::cos(dir), (1 - 1e-9) * t * std::sin(dir)};
      const PatchLoads outside{Pz, (1 + 1e-9) * t * std::cos(dir), (1 + 1e-9) * t * std::sin(dir)};
      EXPECT_TRUE(isAdmissible(disk, inside));
      EXPECT_FALSE(isAdmissible(disk, outside));
    }
  }
  EXPECT_FALSE(isAdmissible(disk, PatchLoads{-1.0, 0.0, 0.0}));
}

// Polygons and off-centre disks: build pressures with a known minimum, get
// their loads by brute force, ask the core.
TEST(Admissible, AgreesWithKnownPressures) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    for (int k = 0; k < 4; ++k) {
      LinearPressure p = randomPressure(shape, rng);
      // shift p0 so that min p = 0, then by +-0.05 of the mean pressure
      // p(centroid) (> 0 once min p = 0): well clear of relTol
      const double target = (k % 2 == 0 ? 0.05 : -0.05);
      p.p0 -= directMinPressure(shape, p);
      p.p0 += target * p.at(shape.centroid());
      const PatchLoads l = bruteForceLoads(shape, linearField(p));
      ASSERT_GT(l.Pz, 0.0);
      EXPECT_EQ(isAdmissible(shape, l), target > 0) << "min p = " << directMinPressure(shape, p);
    }
  }
}

// relTol is relative to the mean pressure Pz / A.
TEST(Admissible, RelativeTolerance) {
  const PatchShape shape = PatchShape::rectangle(1.0, 0.5);
  const double mean = 2.0;
  // p = mean + c x with min at x = -1/2: p(-1/2) = mean - c / 2 = -eps * mean
  for (double eps : {1e-14, 1e-10}) {
    const LinearPressure p{mean, 2.0 * mean * (1.0 + eps), 0.0};
    const PatchLoads l = loadsOf(shape, p);
    EXPECT_EQ(isAdmissible(shape, l), eps < 1e-12) << "eps = " << eps;
    EXPECT_TRUE(isAdmissible(shape, l, 1e-9));
  }
}

// ---- nearest admissible loads ------------------------------------------------

TEST(NearestAdmissible, IsTheProjection) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int kTrials = 12;
  constexpr int kSamples = 400;
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const double l = shape.maxDistanceFromOrigin();
    // admissible samples: pressures >= 0 (half of them touching zero), loads
    // from brute-force area moments (independent of the core's G)
    const Mat3 G = bruteForceAreaMoments(shape).loadMatrix();
    std::vector<PatchLoads> admissible;
    for (int s = 0; s < kSamples; ++s) {
      LinearPressure p{0.0, 3.0 * u(rng) / l, 3.0 * u(rng) / l};
      p.p0 = -directMinPressure(shape, p) + (s % 2 == 0 ? 0.0 : std::abs(u(rng)));
      const Vec3 rhs = G * p.coefficients();  // (Pz, Ty, -Tx)
      admissible.push_back(PatchLoads{rhs[0], -rhs[2], rhs[1]});
    }
    int projected = 0;
    for (double rho : {shape.defaultRho(), 0.1 * l}) {
      for (int t = 0; t < kTrials; ++t) {
        const PatchLoads x{std::abs(u(rng)) + 0.1, 0.5 * l * u(rng), 0.5 * l * u(rng)};
        const PatchLoads r = nearestAdmissibleLoads(shape, x, rho);
        if (isAdmissible(shape, x)) {
          EXPECT_EQ(r.Pz, x.Pz);
          EXPECT_EQ(r.Tx, x.Tx);
          EXPECT_EQ(r.Ty, x.Ty);
          continue;
        }
        ++projected;
        EXPECT_TRUE(isAdmissible(shape, r, kProjectionRelTol));
        const Vec3 xs = scaled(x, rho), rs = scaled(r, rho);
        const double d = (xs - rs).norm();
        for (const PatchLoads& s : admissible) {
          const Vec3 ss = scaled(s, rho);
          // nearest: no sample is closer
          EXPECT_LE(d, (xs - ss).norm() * (1 + kProjectionRelTol) + kRoundOff)
              << "sample closer than the returned load";
          // projection onto a convex cone: (x - r).(s - r) <= 0
          EXPECT_LE((xs - rs).dot(ss - rs), kProjectionRelTol * d * (ss - rs).norm() + kRoundOff);
        }
      }
    }
    // not vacuous: most trial loads lie outside the admissible cone
    EXPECT_GT(projected, kTrials);
  }
}

// Documented in pressure.hpp: "Loads with Pz <= 0 map to zero (the contact
// carries nothing)". Note this is a contract, not the Euclidean projection:
// for Pz < 0 with a large torque the nearest cone point is not 0.
TEST(NearestAdmissible, NonPositiveNormalForceMapsToZero) {
  const PatchShape shape = PatchShape::rectangle(1.0, 0.5);
  for (const PatchLoads& x :
       {PatchLoads{0.0, 0.1, 0.0}, PatchLoads{-2.0, 0.0, 0.0}, PatchLoads{-1.0, 0.3, -0.2}}) {
    const PatchLoads r = nearestAdmissibleLoads(shape, x, shape.defaultRho());
    EXPECT_EQ(r.Pz, 0.0);
    EXPECT_EQ(r.Tx, 0.0);
    EXPECT_EQ(r.Ty, 0.0);
  }
}

// ---- Eq. (36), (40) ------------------------------------------------------------

void expectPiMomentsNear(const PiMoments& got, const PiMoments& ref, double l) {
  EXPECT_NEAR(got.Pz, ref.Pz, kIntegralRelTol * std::abs(ref.Pz));
  // lengths relative to the patch size l, ratios relative to 1
  EXPECT_NEAR(got.pi_x, ref.pi_x, kIntegralRelTol * (std::abs(ref.pi_x) + l));
  EXPECT_NEAR(got.pi_y, ref.pi_y, kIntegralRelTol * (std::abs(ref.pi_y) + l));
  EXPECT_NEAR(got.pi_xy, ref.pi_xy, kIntegralRelTol * (std::abs(ref.pi_xy) + l));
  EXPECT_NEAR(got.pi_x0, ref.pi_x0, kIntegralRelTol * (std::abs(ref.pi_x0) + 1));
  EXPECT_NEAR(got.pi_y0, ref.pi_y0, kIntegralRelTol * (std::abs(ref.pi_y0) + 1));
}

TEST(PiMoments, LinearPressureMatchesBruteForce) {
  std::mt19937 rng(6);
  std::vector<PatchShape> shapes = testShapes();
  shapes.push_back(PatchShape::polygon({{0.0, 0.0}, {0.5, 0.1}, {0.2, 0.6}}));  // O at a vertex
  shapes.push_back(PatchShape::rectangle(1.0, 0.5, Vec2(0.5, 0.0)));            // O on an edge
  shapes.push_back(PatchShape::disk(0.4, Vec2(0.0, 0.4)));                      // O on the rim
  for (const PatchShape& shape : shapes) {
    SCOPED_TRACE(shape.describe());
    const LinearPressure p = randomPressure(shape, rng);
    expectPiMomentsNear(piMoments(shape, p), bruteForcePiMoments(shape, linearField(p)),
                        shape.maxDistanceFromOrigin());
  }
}

// Eq. (40): Pi = [[1, 0, -pi_y0], [0, 1, pi_x0], [-pi_y/rho, pi_x/rho, pi_xy/rho]].
TEST(PiMoments, EllipsoidalPiLayout) {
  PiMoments m;
  m.Pz = 2.0;
  m.pi_x = 0.1;
  m.pi_y = -0.2;
  m.pi_x0 = 0.3;
  m.pi_y0 = -0.4;
  m.pi_xy = 0.5;
  const double rho = 0.7;
  Mat3 expected;
  expected << 1, 0, 0.4, 0, 1, 0.3, 0.2 / rho, 0.1 / rho, 0.5 / rho;
  EXPECT_TRUE(ellipsoidalPi(m, rho).isApprox(expected, kRoundOff));
}

TEST(PiMoments, HertzMatchesBruteForce) {
  for (const PatchShape& disk :
       {PatchShape::disk(0.7), PatchShape::disk(0.5, Vec2(0.2, -0.1)),
        PatchShape::disk(0.3, Vec2(0.9, 0.4)), PatchShape::disk(0.4, Vec2(-0.4, 0.0))}) {
    SCOPED_TRACE(disk.describe());
    const double Pz = 4.0;
    const PiMoments ref = bruteForcePiMoments(disk, hertzField(disk.centre(), disk.radius(), Pz));
    expectPiMomentsNear(piMomentsHertz(disk, HertzPressure{Pz}), ref, disk.maxDistanceFromOrigin());
  }
}

TEST(PiMoments, Errors) {
  const PatchShape disk = PatchShape::disk(0.5);
  EXPECT_THROW(piMoments(disk, LinearPressure{-1.0, 0.0, 0.0}), Error);
  EXPECT_THROW(piMoments(disk, LinearPressure{0.0, 1.0, 0.0}), Error);  // Pz = 0
  EXPECT_THROW(piMomentsHertz(PatchShape::rectangle(1.0, 1.0), HertzPressure{1.0}), Error);
  EXPECT_THROW(piMomentsHertz(disk, HertzPressure{0.0}), Error);
  EXPECT_THROW(piMomentsHertz(disk, HertzPressure{std::nan("")}), Error);
}

}  // namespace
}  // namespace patchspin
