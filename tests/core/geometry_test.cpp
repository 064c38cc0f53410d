// Patch shapes: area moments, rho (11) and the moment table of (36) against
// brute-force quadrature (tests/support/oracle) and closed forms; invalid input.
#include <patchspin/geometry.hpp>

#include "oracle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::bruteForceAreaMoments;
using testing::bruteForceIntegral;
using testing::bruteForceMomentTable;

constexpr double kPi = 3.14159265358979323846;
// Core moments (closed-form edge sums, disk quadrature at kRoundOff) against the
// oracle run at relTol 1e-13: both sides are good to ~1e-14, so 1e-12
// relative (the brief's target) leaves two digits of margin.
constexpr double kMomentRelTol = 1e-12;
// Closed forms for disks (pi R^2, parallel-axis theorem, 2R/3): only round-off
// of a few operations on O(1) numbers.
constexpr double kClosedFormRelTol = 1e-14;
// Vertex positions, areas and distances of O(1) shapes: a few ulps.
constexpr double kRoundOff = 1e-15;
// Accuracy asked of the oracle here (one digit below kMomentRelTol).
constexpr double kOracleRelTol = 1e-13;

// Test shapes: O inside, on the boundary, and outside.
std::vector<PatchShape> testShapes() {
  return {
      PatchShape::disk(0.7),                                   // centred at O
      PatchShape::disk(0.5, Vec2(0.2, -0.1)),                  // O inside, off-centre
      PatchShape::disk(0.3, Vec2(0.9, 0.4)),                   // O outside
      PatchShape::disk(0.4, Vec2(0.4, 0.0)),                   // O on the rim
      PatchShape::rectangle(1.0, 0.4),                         // centred at O
      PatchShape::rectangle(0.8, 0.3, Vec2(0.1, 0.05), 0.6),   // O inside, rotated
      PatchShape::rectangle(0.5, 0.2, Vec2(1.2, -0.7), -0.3),  // O outside
      PatchShape::polygon({{-0.2, -0.3}, {0.6, -0.1}, {0.4, 0.5}, {-0.3, 0.2}}),
      PatchShape::polygon({{0.0, 0.0}, {0.5, 0.1}, {0.2, 0.6}}),  // O at a vertex
      PatchShape::regularPolygon(7, 0.45, Vec2(-0.3, 0.6), 0.2),  // O outside
  };
}

// |a - b| <= tol (|b| + scale): relative where b is large, absolute (at the
// size of a typical entry of that dimension) where b vanishes by symmetry.
::testing::AssertionResult nearRel(double a, double b, double tol, double scale) {
  const double bound = tol * (std::abs(b) + scale);
  if (std::abs(a - b) <= bound) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << a << " vs " << b << " differ by " << std::abs(a - b) << " > " << bound;
}

TEST(AreaMoments, MatchBruteForce) {
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const AreaMoments& m = shape.areaMoments();
    const AreaMoments ref = bruteForceAreaMoments(shape, kOracleRelTol);
    const double A = ref.area;
    const double l = shape.maxDistanceFromOrigin();
    EXPECT_TRUE(nearRel(m.area, ref.area, kMomentRelTol, 0.0));
    EXPECT_TRUE(nearRel(m.first.x(), ref.first.x(), kMomentRelTol, A * l));
    EXPECT_TRUE(nearRel(m.first.y(), ref.first.y(), kMomentRelTol, A * l));
    EXPECT_TRUE(nearRel(m.xx, ref.xx, kMomentRelTol, A * l * l));
    EXPECT_TRUE(nearRel(m.xy, ref.xy, kMomentRelTol, A * l * l));
    EXPECT_TRUE(nearRel(m.yy, ref.yy, kMomentRelTol, A * l * l));
    EXPECT_TRUE(nearRel(shape.area(), A, kMomentRelTol, 0.0));
    EXPECT_TRUE(nearRel(shape.centroid().x(), ref.first.x() / A, kMomentRelTol, l));
    EXPECT_TRUE(nearRel(shape.centroid().y(), ref.first.y() / A, kMomentRelTol, l));
  }
}

// Disk of radius R centred at C: A = pi R^2, S = A C,
// Ixx = A (R^2/4 + Cx^2), Ixy = A Cx Cy, Iyy = A (R^2/4 + Cy^2).
TEST(AreaMoments, DiskClosedForm) {
  const double R = 0.35;
  const Vec2 C(-0.4, 0.25);
  const PatchShape disk = PatchShape::disk(R, C);
  const AreaMoments& m = disk.areaMoments();
  const double A = kPi * R * R;
  EXPECT_TRUE(nearRel(m.area, A, kClosedFormRelTol, 0.0));
  EXPECT_TRUE(nearRel(m.first.x(), A * C.x(), kClosedFormRelTol, 0.0));
  EXPECT_TRUE(nearRel(m.first.y(), A * C.y(), kClosedFormRelTol, 0.0));
  EXPECT_TRUE(nearRel(m.xx, A * (R * R / 4 + C.x() * C.x()), kClosedFormRelTol, 0.0));
  EXPECT_TRUE(nearRel(m.xy, A * C.x() * C.y(), kClosedFormRelTol, 0.0));
  EXPECT_TRUE(nearRel(m.yy, A * (R * R / 4 + C.y() * C.y()), kClosedFormRelTol, 0.0));
}

// G of Eq. (94): [[A, Sx, Sy], [Sx, Ixx, Ixy], [Sy, Ixy, Iyy]].
TEST(AreaMoments, LoadMatrixLayout) {
  const PatchShape shape = PatchShape::rectangle(0.8, 0.3, Vec2(0.1, 0.05), 0.6);
  const AreaMoments& m = shape.areaMoments();
  Mat3 G;
  G << m.area, m.first.x(), m.first.y(), m.first.x(), m.xx, m.xy, m.first.y(), m.xy, m.yy;
  EXPECT_EQ(m.loadMatrix(), G);
}

// rho of Eq. (11), the mean distance from O.
TEST(Rho, MatchesBruteForce) {
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const double ref = bruteForceIntegral(
                           shape, [](const Vec2& p) { return p.norm(); }, kOracleRelTol) /
                       bruteForceAreaMoments(shape, kOracleRelTol).area;
    EXPECT_TRUE(nearRel(shape.defaultRho(), ref, kMomentRelTol, 0.0));
  }
}

// Eq. (47): centred disk, rho = (2/R^2) ∫_0^R s^2 ds = 2R/3.
TEST(Rho, CentredDiskIsTwoThirdsR) {
  for (double R : {1e-3, 0.25, 1.0, 40.0}) {
    EXPECT_TRUE(nearRel(PatchShape::disk(R).defaultRho(), 2.0 * R / 3.0, kClosedFormRelTol, 0.0))
        << "R = " << R;
  }
}

// Centred rectangle a x b: rho = (1/ab) ∫∫ r dA. Closed form: split the
// quarter rectangle [0,a2] x [0,b2] (a2 = a/2, b2 = b/2, d = |(a2, b2)|) along
// its diagonal; in polar coordinates the triangle below it gives
//   (1/3) ∫_0^phi1 (a2 / cos phi)^3 dphi = (a2^3/6) [sec tan + ln(sec + tan)]
//   = a2 b2 d / 6 + (a2^3 / 6) asinh(b2 / a2),
// the other one the same with a2 <-> b2. Checked against the oracle too.
TEST(Rho, CentredRectangleClosedForm) {
  const double a = 1.3, b = 0.45;
  const double a2 = a / 2, b2 = b / 2, d = std::hypot(a2, b2);
  const double quarter =
      a2 * b2 * d / 3 +
      (a2 * a2 * a2 * std::asinh(b2 / a2) + b2 * b2 * b2 * std::asinh(a2 / b2)) / 6;
  const double rho = 4.0 * quarter / (a * b);
  const PatchShape shape = PatchShape::rectangle(a, b);
  // the core sums edge integrals with asinh differences: a few more ulps
  constexpr double kRectangleRhoTol = 1e-13;
  EXPECT_TRUE(nearRel(shape.defaultRho(), rho, kRectangleRhoTol, 0.0));
  const double oracle = bruteForceIntegral(
                            shape, [](const Vec2& p) { return p.norm(); }, kOracleRelTol) /
                        (a * b);
  EXPECT_TRUE(nearRel(oracle, rho, kMomentRelTol, 0.0));
}

// m(f, k) = ∫ f phi_k dA, f in {1, x, y, r, x/r, y/r}, phi in {1, x, y}.
TEST(MomentTable, MatchesBruteForce) {
  for (const PatchShape& shape : testShapes()) {
    SCOPED_TRACE(shape.describe());
    const MomentTable& m = shape.momentTable();
    const MomentTable ref = bruteForceMomentTable(shape, kOracleRelTol);
    const double A = shape.area();
    const double l = shape.maxDistanceFromOrigin();
    // entry (f, k) has the dimension of A * l^(deg f + deg phi_k)
    const int degF[6] = {0, 1, 1, 1, 0, 0};
    for (int row = 0; row < 6; ++row) {
      for (int col = 0; col < 3; ++col) {
        const double scale = A * std::pow(l, degF[row] + (col > 0 ? 1 : 0));
        EXPECT_TRUE(nearRel(m.m(row, col), ref.m(row, col), kMomentRelTol, scale))
            << "row " << row << " col " << col;
      }
    }
  }
}

TEST(Shape, RectangleAndRegularPolygonVertices) {
  const double lx = 0.8, ly = 0.3, angle = 0.6;
  const Vec2 c(0.1, 0.05);
  const PatchShape rect = PatchShape::rectangle(lx, ly, c, angle);
  ASSERT_FALSE(rect.isDisk());
  ASSERT_EQ(rect.vertices().size(), 4u);
  const Eigen::Rotation2Dd rot(angle);
  // every expected corner is a vertex (order: counter-clockwise, any start)
  for (double sx : {-0.5, 0.5}) {
    for (double sy : {-0.5, 0.5}) {
      const Vec2 corner = c + rot * Vec2(sx * lx, sy * ly);
      double best = std::numeric_limits<double>::infinity();
      for (const Vec2& v : rect.vertices()) best = std::min(best, (v - corner).norm());
      EXPECT_LT(best, kRoundOff);
    }
  }
  EXPECT_NEAR(rect.area(), lx * ly, kRoundOff);

  const PatchShape hex = PatchShape::regularPolygon(6, 0.5, Vec2(0.2, -0.3), 0.1);
  ASSERT_EQ(hex.vertices().size(), 6u);
  for (int i = 0; i < 6; ++i) {
    const Vec2 expected =
        Vec2(0.2, -0.3) + 0.5 * Vec2(std::cos(0.1 + i * kPi / 3), std::sin(0.1 + i * kPi / 3));
    EXPECT_LT((hex.vertices()[i] - expected).norm(), kRoundOff) << "vertex " << i;
  }
  // A = (n/2) R^2 sin(2 pi / n)
  EXPECT_NEAR(hex.area(), 3.0 * 0.25 * std::sin(kPi / 3), kRoundOff);
}

TEST(Shape, DistancesAndContains) {
  const PatchShape disk = PatchShape::disk(0.3, Vec2(0.9, 0.4));
  EXPECT_NEAR(disk.maxDistanceFromOrigin(), std::hypot(0.9, 0.4) + 0.3, kRoundOff);
  EXPECT_NEAR(disk.diameter(), 0.6, kRoundOff);
  EXPECT_TRUE(disk.contains(Vec2(0.9, 0.69)));
  EXPECT_FALSE(disk.contains(Vec2(0.9, 0.71)));
  EXPECT_TRUE(disk.contains(Vec2(0.9, 0.71), 0.02));

  const PatchShape rect = PatchShape::rectangle(1.0, 0.4, Vec2(2.0, 0.0));
  EXPECT_NEAR(rect.maxDistanceFromOrigin(), std::hypot(2.5, 0.2), kRoundOff);
  EXPECT_NEAR(rect.diameter(), std::hypot(1.0, 0.4), kRoundOff);
  EXPECT_TRUE(rect.contains(Vec2(2.5, 0.2)));  // closed: corner included
  EXPECT_FALSE(rect.contains(Vec2(2.51, 0.0)));
  EXPECT_TRUE(rect.contains(Vec2(2.51, 0.0), 0.02));
}

TEST(Shape, CollinearVerticesAreRemoved) {
  const PatchShape shape =
      PatchShape::polygon({{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}});
  EXPECT_EQ(shape.vertices().size(), 4u);
  EXPECT_NEAR(shape.area(), 1.0, kRoundOff);
}

// inFrame: P' = R(-angle) (P - n). Moments in the new frame against the
// oracle, and the first moment against the transformation rule
//   S' = R(-angle) (S - A n).
TEST(Shape, InFrameTransformsMoments) {
  const Vec2 n(0.3, -0.2);
  const double angle = 0.7;
  for (const PatchShape& shape :
       {PatchShape::disk(0.5, Vec2(0.2, -0.1)),
        PatchShape::polygon({{-0.2, -0.3}, {0.6, -0.1}, {0.4, 0.5}, {-0.3, 0.2}})}) {
    SCOPED_TRACE(shape.describe());
    const PatchShape moved = shape.inFrame(n, angle);
    const Vec2 expectedFirst =
        Eigen::Rotation2Dd(-angle) * (shape.areaMoments().first - shape.area() * n);
    const double l = moved.maxDistanceFromOrigin();
    EXPECT_TRUE(nearRel(moved.area(), shape.area(), kMomentRelTol, 0.0));
    EXPECT_TRUE(
        nearRel(moved.areaMoments().first.x(), expectedFirst.x(), kMomentRelTol, moved.area() * l));
    EXPECT_TRUE(
        nearRel(moved.areaMoments().first.y(), expectedFirst.y(), kMomentRelTol, moved.area() * l));
    const double rhoRef = bruteForceIntegral(
                              moved, [](const Vec2& p) { return p.norm(); }, kOracleRelTol) /
                          moved.area();
    EXPECT_TRUE(nearRel(moved.defaultRho(), rhoRef, kMomentRelTol, 0.0));
  }
}

// ---- invalid input ---------------------------------------------------------

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Runs `make`, expects patchspin::Error whose message mentions one of `words`.
template <class F>
::testing::AssertionResult throwsNaming(F make, std::vector<std::string> words) {
  try {
    make();
  } catch (const Error& e) {
    const std::string msg = lower(e.what());
    for (const std::string& w : words)
      if (msg.find(w) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "message does not name the problem: " << e.what();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a non-Error exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

TEST(ShapeErrors, InvalidPolygons) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsNaming([] { PatchShape::polygon({}); }, {"3", "vert"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::polygon({{0, 0}, {1, 0}}); }, {"3", "vert"}));
  EXPECT_TRUE(throwsNaming(
      [] {
        PatchShape::polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
      },
      {"clockwise"}));
  // an arrow head: convex hull minus a notch
  EXPECT_TRUE(throwsNaming(
      [] {
        PatchShape::polygon({{0, 0}, {2, 0}, {2, 2}, {1, 0.5}, {0, 2}});
      },
      {"convex"}));
  // a self-intersecting pentagram (turns left everywhere, winds twice)
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i)
    star.emplace_back(std::cos(i * 4 * kPi / 5), std::sin(i * 4 * kPi / 5));
  EXPECT_TRUE(throwsNaming([&] { PatchShape::polygon(star); }, {"convex", "intersect"}));
  EXPECT_TRUE(throwsNaming(
      [] {
        PatchShape::polygon({{0, 0}, {1, 1}, {2, 2}});
      },
      {"area", "collinear", "degenerate"}));
  EXPECT_TRUE(throwsNaming(
      [] {
        PatchShape::polygon({{0, 0}, {1, 0}, {1, 0}, {0, 1}});
      },
      {"repeat", "duplicate", "area"}));
  EXPECT_TRUE(throwsNaming(
      [&] {
        PatchShape::polygon({{0, 0}, {1, nan}, {0, 1}});
      },
      {"finite", "nan"}));
  EXPECT_TRUE(throwsNaming(
      [&] {
        PatchShape::polygon({{0, 0}, {inf, 0}, {0, 1}});
      },
      {"finite", "inf"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::rectangle(0.0, 1.0); },
                           {"lx", "length", "side", "positive", "> 0"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::rectangle(1.0, -2.0); },
                           {"ly", "length", "side", "positive", "> 0"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::regularPolygon(2, 1.0); }, {"3", "n"}));
}

TEST(ShapeErrors, InvalidDisks) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsNaming([] { PatchShape::disk(0.0); }, {"radius"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::disk(-1.0); }, {"radius"}));
  EXPECT_TRUE(throwsNaming([&] { PatchShape::disk(nan); }, {"radius"}));
  EXPECT_TRUE(throwsNaming([&] { PatchShape::disk(inf); }, {"radius"}));
  EXPECT_TRUE(throwsNaming([&] { PatchShape::disk(1.0, Vec2(nan, 0.0)); },
                           {"centre", "center", "finite", "nan"}));
}

TEST(ShapeErrors, WrongKindAccessors) {
  EXPECT_THROW(PatchShape::disk(1.0).vertices(), Error);
  EXPECT_THROW(PatchShape::rectangle(1.0, 1.0).radius(), Error);
  EXPECT_THROW(PatchShape::rectangle(1.0, 1.0).centre(), Error);
}

}  // namespace
}  // namespace patchspin
