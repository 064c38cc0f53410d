// Tests of the pivot rows part (parts/pivot_rows.hpp): the pivot points of a
// clamped centre of pressure, the pushing test, the sticking pivot solve
// (velocities checked after the impulse, not by its formula) and the fold
// of a held patch's general rows (its rows' velocities unchanged, and
// foldHeldDofs for unit rows).
#include <patchspin/parts/pivot_rows.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace patchspin::parts {
namespace {

// products of 6x6 matrices with entries ~1 and conditions ~1e2: 1e-10
constexpr double kTol = 1e-10;

Mat6 randomSpd(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat6 B;
  for (int i = 0; i < 36; ++i) B(i / 6, i % 6) = u(rng);
  return B * B.transpose() + 0.5 * Mat6::Identity();
}

Vec6 randomVec6(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec6 v;
  for (int i = 0; i < 6; ++i) v[i] = u(rng);
  return v;
}

PatchShape box() {  // 0.04 x 0.1, as the light box's foot
  return PatchShape::polygon({{-0.02, -0.05}, {0.02, -0.05}, {0.02, 0.05}, {-0.02, 0.05}});
}

TEST(PivotRows, TakesTheCornersOfTheEdgeBeyondWhichTheCentreOfPressureLies) {
  // cop (0.03, 0.01): beyond the edge x = 0.02, inside its extent
  PivotRows r = pivotRowsOf(box(), Vec3(2.0, 2.0 * 0.01, -2.0 * 0.03));
  ASSERT_EQ(r.n, 2);
  EXPECT_EQ(r.a[0], pivotRow(Vec2(0.02, -0.05)));
  EXPECT_EQ(r.a[1], pivotRow(Vec2(0.02, 0.05)));
  // cop (0.03, 0.07): beyond the corner (0.02, 0.05) alone
  r = pivotRowsOf(box(), Vec3(1.0, 0.07, -0.03));
  ASSERT_EQ(r.n, 1);
  EXPECT_EQ(r.a[0], pivotRow(Vec2(0.02, 0.05)));
  // a normal impulse that does not push has no pivots
  EXPECT_EQ(pivotRowsOf(box(), Vec3(0.0, 0.0, 0.0)).n, 0);
  EXPECT_EQ(pivotRowsOf(box(), Vec3(-1.0, 0.0, 0.03)).n, 0);
}

// A disk of radius 1 cut by the line x = 0.5 (an arc region): a centre of
// pressure beyond the chord, inside its extent, pivots on the chord's ends
// (0.5, +-sqrt(3)/2); beyond the arc, on the circle's point radially out
// (as clampNormalImpulse takes them). Closed forms: the chord's ends and
// the radial point, to 1e-12.
TEST(PivotRows, ACutDiskPivotsOnItsChordsEndsOrARimPoint) {
  const PatchShape cut = PatchShape::arcRegion(diskPolygonIntersection(
      Vec2::Zero(), 1.0, {{-2.0, -2.0}, {0.5, -2.0}, {0.5, 2.0}, {-2.0, 2.0}}));
  ASSERT_EQ(cut.kind(), PatchShape::Kind::ArcRegion);
  const double h = std::sqrt(3.0) / 2.0;
  PivotRows r = pivotRowsOf(cut, Vec3(1.0, 0.1, -0.7));  // cop (0.7, 0.1)
  ASSERT_EQ(r.n, 2);
  for (const Vec3& a : {r.a[0], r.a[1]}) {
    EXPECT_NEAR(a[2], -0.5, 1e-12);         // x = 0.5
    EXPECT_NEAR(std::abs(a[1]), h, 1e-12);  // y = +-sqrt(3)/2
  }
  EXPECT_NEAR(r.a[0][1] + r.a[1][1], 0.0, 1e-12);
  const Vec2 out(-1.2, 0.9);  // beyond the arc: the rim point along it
  r = pivotRowsOf(cut, Vec3(1.0, out.y(), -out.x()));
  ASSERT_EQ(r.n, 1);
  const Vec2 rim = out.normalized();
  EXPECT_NEAR(r.a[0][1], rim.y(), 1e-12);
  EXPECT_NEAR(-r.a[0][2], rim.x(), 1e-12);
}

TEST(PivotRows, PushWhenEveryPivotImpulseIsNonNegative) {
  PivotRows r;
  r.n = 2;
  r.a[0] = pivotRow(Vec2(0.02, -0.05));
  r.a[1] = pivotRow(Vec2(0.02, 0.05));
  EXPECT_TRUE(pivotsPush(r, 2.0 * r.a[0] + 3.0 * r.a[1]));
  EXPECT_TRUE(pivotsPush(r, 2.0 * r.a[0]));
  EXPECT_FALSE(pivotsPush(r, 2.0 * r.a[0] - 0.1 * r.a[1]));
  r.n = 1;
  EXPECT_TRUE(pivotsPush(r, 0.5 * r.a[0]));
  EXPECT_FALSE(pivotsPush(r, -0.5 * r.a[0]));
}

// After d: the pivots' normal velocities are at their targets, the
// friction DOFs at rest, and the normal impulse is the pivots' alone.
TEST(PivotRows, StickingPivotSolveStopsThePivotsAndTheSlip) {
  std::mt19937 rng(7);
  int solved = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Mat6 K6 = randomSpd(rng);
    PivotRows r;
    r.n = 1 + trial % 2;
    r.a[0] = pivotRow(Vec2(0.5, -0.7));
    r.a[1] = pivotRow(Vec2(0.5, 0.7));
    const Vec6 c = randomVec6(rng);
    const Vec3 target = Vec3(randomVec6(rng).head<3>()) * 0.1;
    Vec6 res;
    res << target - c.head<3>(), -c.tail<3>();
    const Vec3 lamN = randomVec6(rng).head<3>();
    Vec6 d;
    if (!solvePivotsWithFriction(K6, r, lamN, res, d)) continue;
    ++solved;
    const Vec6 after = c + K6 * d;
    for (int k = 0; k < r.n; ++k)
      EXPECT_NEAR(r.a[k].dot(after.head<3>()), r.a[k].dot(target), kTol) << trial;
    EXPECT_LT(after.tail<3>().norm(), kTol) << trial;
    EXPECT_TRUE(pivotsPush(r, lamN + d.head<3>())) << trial;
    // in the pivots' span: no component off it
    Eigen::Matrix<double, 3, Eigen::Dynamic> A(3, r.n);
    for (int k = 0; k < r.n; ++k) A.col(k) = r.a[k];
    const Vec3 lam = lamN + d.head<3>();
    const Eigen::VectorXd z = A.colPivHouseholderQr().solve(lam);
    EXPECT_LT((A * z - lam).norm(), kTol) << trial;
  }
  // about half of the random residuals need a pulling pivot: refused
  EXPECT_GT(solved, 20);
  EXPECT_LT(solved, 190);
}

// The held patch's rows H do not move when this patch takes d and the held
// one gain d: H (C^T d + Kh gain d) = 0, and this patch's velocity changes by
// the folded K d = K d + C gain d.
TEST(PivotRows, FoldOfHeldRowsKeepsThoseRowsStill) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Mat6 K = randomSpd(rng), Kh = randomSpd(rng);
    Mat6 C;
    for (int i = 0; i < 6; ++i) C.col(i) = 0.3 * randomVec6(rng);
    Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6> H =
        Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6>::Zero(5, 6);
    H.block<1, 3>(0, 0) = pivotRow(Vec2(0.2, -0.5)).transpose();
    H.block<1, 3>(1, 0) = pivotRow(Vec2(0.2, 0.5)).transpose();
    H.block<3, 3>(2, 3).setIdentity();
    HeldBlocks h;
    foldHeldRows(K, Kh, C, H, h);
    ASSERT_TRUE(h.valid) << trial;
    const Vec6 d = randomVec6(rng);
    const Vec6 ds = h.gain * d;
    EXPECT_LT((H * (C.transpose() * d + Kh * ds)).norm(), kTol) << trial;
    const Vec6 dv = K * d + C * ds;  // this patch's velocity change
    Mat6 Kf;
    Kf << h.Winv.inverse(), h.Knf, h.Knf.transpose(), h.Kff;
    EXPECT_LT((Kf * d - dv).norm(), kTol * (1.0 + dv.norm())) << trial;
    // unit rows: foldHeldDofs
    HeldBlocks unit, ref;
    foldHeldRows(K, Kh, C, Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6>::Identity(3, 6), unit);
    foldHeldDofs<3>(K, Kh, C.leftCols<3>(), ref);
    ASSERT_TRUE(unit.valid && ref.valid);
    EXPECT_LT((unit.Winv - ref.Winv).norm(), kTol * ref.Winv.norm());
    EXPECT_LT((unit.gain - ref.gain).norm(), kTol * (1.0 + ref.gain.norm()));
  }
}

}  // namespace
}  // namespace patchspin::parts
