// Tests of the normal block part (parts/normal_block.hpp): a velocity solve
// against a brute-force LCP of point contacts at the patch's corners, the
// nearest point and inner radius against brute force, the position solve
// and the targets.
#include <patchspin/parts/normal_block.hpp>
#include <patchspin/parts/patch_blocks.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <optional>

namespace patchspin::parts {
namespace {

// 3x3 and 4x4 solves of O(1-100) numbers.
constexpr double kSolveTol = 1e-9;

using Vec4 = Eigen::Vector4d;
using Mat34 = Eigen::Matrix<double, 3, 4>;

// Point contacts at the rectangle's corners: a normal impulse p_i at (x, y)
// is the generalised impulse (p, y p, -x p) of the normal DOFs, and the
// normal velocity there is c0 + y c1 - x c2 (S5).
Mat34 cornerRows(const PatchShape& rect) {
  Mat34 G;
  for (int i = 0; i < 4; ++i) {
    const Vec2 v = rect.vertices()[std::size_t(i)];
    G.col(i) = Vec3(1.0, v.y(), -v.x());
  }
  return G;
}

// The LCP of the four corner points with the normal block's effective mass
// W: p >= 0, point velocities g = G^T (c + W G p) >= 0, p.g = 0, solved by
// trying every active set (16). Returns the generalised impulse G p of the
// solution with all four points active if one exists (the wrench is unique
// though p is not).
std::optional<Vec3> allCornersActive(const Mat3& W, const Vec3& c, const Mat34& G) {
  // G p = -W^-1 c has a solution p >= 0 iff the wrench's centre of pressure
  // lies in the corners' convex hull: search p >= 0 by brute force over the
  // 4 choices of a vertex left at zero (a 3x3 solve each), plus the interior
  // minimum-norm solution
  const Vec3 target = -W.inverse() * c;
  for (int drop = 0; drop < 4; ++drop) {
    Mat3 Gs;
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != drop) Gs.col(k++) = G.col(j);
    const Vec3 ps = Gs.fullPivLu().solve(target);
    if ((Gs * ps - target).norm() <= kSolveTol * (1.0 + target.norm()) &&
        ps.minCoeff() >= -kSolveTol * target[0])
      return target;
  }
  return std::nullopt;
}

// Brute-force LCP over all 16 active sets: true if some solution lifts a
// corner (separating velocity > 0 there, zero impulse).
bool someSolutionLiftsACorner(const Mat3& W, const Vec3& c, const Mat34& G) {
  const Eigen::Matrix4d A = G.transpose() * W * G;
  const Vec4 g0 = G.transpose() * c;
  for (int mask = 1; mask < 15; ++mask) {  // proper, non-empty active sets
    Eigen::Matrix4d As = Eigen::Matrix4d::Identity();
    Vec4 rhs = Vec4::Zero();
    for (int i = 0; i < 4; ++i)
      if (mask & (1 << i)) {
        for (int j = 0; j < 4; ++j) As(i, j) = (mask & (1 << j)) ? A(i, j) : 0.0;
        rhs[i] = -g0[i];
      }
    const Vec4 p = As.completeOrthogonalDecomposition().solve(rhs);
    if ((As * p - rhs).norm() > kSolveTol) continue;
    const Vec4 g = g0 + A * p;
    bool ok = true, lifted = false;
    for (int i = 0; i < 4; ++i) {
      if (mask & (1 << i))
        ok = ok && p[i] >= -kSolveTol;
      else {
        ok = ok && g[i] >= -kSolveTol;
        lifted = lifted || g[i] > kSolveTol;
      }
    }
    if (ok && lifted) return true;
  }
  return false;
}

// A box face resting on the ground, pressed and tilted by random velocities:
// where the block holds its face (interior) its impulse is the corner LCP's
// all-contacts wrench, and where it does not, the LCP lifts a corner.
TEST(NormalBlock, AgreesWithTheCornerContactLcp) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const PatchShape rect = PatchShape::rectangle(0.08, 0.05);
  const PatchOutlineSummary outline = summarizeOutline(rect);
  const Mat34 G = cornerRows(rect);
  int interior = 0, tipping = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const PatchBody a = testing::randomBody(rng), ground;
    const Mat3 F = testing::randomRotation(rng);
    PatchBlocks k;
    ASSERT_TRUE(makePatchBlocks(patchEffectiveMass(a, ground, F, 0.03), k));
    const Mat3 W = k.Winv.inverse();
    // approaching at 0.1 m/s, tilting at up to 0.5 rad/s
    const Vec3 c(-0.1, 0.5 * u(rng), 0.5 * u(rng));
    const NormalImpulse n =
        solveNormalVelocity(k.Winv, Vec3::Zero(), c, Vec3::Zero(), outline, rect);
    const std::optional<Vec3> lcp = allCornersActive(W, c, G);
    EXPECT_EQ(n.interior, lcp.has_value()) << "trial " << trial;
    if (n.interior && lcp) {
      ++interior;
      EXPECT_LT((n.lamN - *lcp).norm(), kSolveTol * lcp->norm());
      // the face is held: no normal velocity, no tilt
      EXPECT_LT((c + W * n.lamN).norm(), kSolveTol * c.norm());
    } else if (!n.interior) {
      ++tipping;
      EXPECT_TRUE(someSolutionLiftsACorner(W, c, G)) << "trial " << trial;
      // the clamped impulse's centre of pressure is on the patch's
      // boundary (no impulse at all where y_z <= 0), and it is the LCP's
      // impulse at its active corners: their normal velocity stopped, each
      // pushing (the corners it acts through: the ends of the edge it lies
      // on, or the corner it is at)
      if (n.lamN[0] > 0.0) {
        const Vec2 cop(-n.lamN[2] / n.lamN[0], n.lamN[1] / n.lamN[0]);
        EXPECT_LE((nearestPointOn(rect, cop) - cop).norm(), 1e-12);
        const Vec4 g = G.transpose() * (c + W * n.lamN);  // corners' normal velocity
        // active corners: the one cop is at, else the two ends of its edge
        std::vector<int> active;
        for (int i = 0; i < 4; ++i)
          if ((cop - rect.vertices()[std::size_t(i)]).norm() <= 1e-9) active = {i};
        for (int i = 0; i < 4 && active.empty(); ++i) {
          const Vec2 p1 = rect.vertices()[std::size_t(i)];
          const Vec2 e = rect.vertices()[std::size_t((i + 1) % 4)] - p1;
          const double t = (cop - p1).dot(e) / e.squaredNorm();
          if (t > 0.0 && t < 1.0 && (cop - p1 - t * e).norm() <= 1e-9) active = {i, (i + 1) % 4};
        }
        for (const int i : active)
          EXPECT_LT(std::abs(g[i]), kSolveTol * c.norm()) << "trial " << trial << " corner " << i;
        EXPECT_FALSE(active.empty()) << "trial " << trial;
      } else {
        EXPECT_EQ(n.lamN, Vec3::Zero());
      }
    }
  }
  // both branches exercised
  EXPECT_GT(interior, 40);
  EXPECT_GT(tipping, 40);
}

TEST(NormalBlock, SeparatingBodiesGetNoImpulse) {
  const PatchShape disk = PatchShape::disk(0.05);
  const NormalImpulse n = solveNormalVelocity(Mat3::Identity(), Vec3::Zero(), Vec3(0.1, 0.0, 0.0),
                                              Vec3::Zero(), summarizeOutline(disk), disk);
  EXPECT_EQ(n.lamN, Vec3::Zero());
  EXPECT_FALSE(n.interior);
  EXPECT_FALSE(n.tipping);
}

// Against a brute-force search over a fine sampling of the boundary.
TEST(NormalBlock, NearestPointOnThePatchIsTheClosestBoundaryPoint) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  const PatchShape shapes[] = {PatchShape::disk(0.05, Vec2(0.01, 0.0)),
                               PatchShape::rectangle(0.1, 0.04),
                               PatchShape::regularPolygon(7, 0.06)};
  for (const PatchShape& shape : shapes)
    for (int trial = 0; trial < 100; ++trial) {
      const Vec2 p(u(rng), u(rng));
      const Vec2 q = nearestPointOn(shape, p);
      if (shape.contains(p)) {
        EXPECT_EQ(q, p);
        continue;
      }
      double best = INFINITY;
      const int n = shape.isDisk() ? 1 : int(shape.vertices().size());
      for (int e = 0; e < n; ++e)
        for (int s = 0; s <= 20000; ++s) {
          const double t = s / 20000.0;
          Vec2 b;
          if (shape.isDisk()) {
            b = shape.centre() +
                shape.radius() * Vec2(std::cos(2 * M_PI * t), std::sin(2 * M_PI * t));
          } else {
            const auto& v = shape.vertices();
            b = v[std::size_t(e)] + t * (v[std::size_t((e + 1) % n)] - v[std::size_t(e)]);
          }
          best = std::min(best, (b - p).norm());
        }
      // the sampling's spacing bounds how far its best can be from the true one
      EXPECT_NEAR((q - p).norm(), best, 2e-5);
    }
}

TEST(NormalBlock, InnerRadiusIsTheDistanceToTheNearestEdge) {
  const PatchShape rect = PatchShape::rectangle(0.1, 0.04);
  EXPECT_NEAR(std::sqrt(innerRadiusSquared(rect)), 0.02, 1e-10);
  EXPECT_EQ(innerRadiusSquared(PatchShape::disk(0.05)), 0.0);
  // O outside the patch: 0
  EXPECT_EQ(innerRadiusSquared(PatchShape::rectangle(0.1, 0.04, Vec2(0.2, 0.0))), 0.0);
}

TEST(NormalBlock, PositionSolvePushesOnlyApart) {
  const Mat3 Winv = Mat3::Identity() * 2.0;
  // approaching the target: a push
  const Vec3 push =
      solveNormalPosition(Winv, Vec3::Zero(), Vec3(0.0, 0.1, 0.0), Vec3(0.05, 0.0, 0.0));
  EXPECT_NEAR(push[0], 0.1, 1e-15);
  EXPECT_NEAR(push[1], -0.2, 1e-15);
  // already moving apart faster than the target: nothing, not a pull
  EXPECT_EQ(solveNormalPosition(Winv, Vec3::Zero(), Vec3(0.1, 0.1, 0.0), Vec3(0.05, 0.0, 0.0)),
            Vec3::Zero());
}

// A gap closes in one step at most, and no deeper than the low side's sink
// allowance; penetration is corrected by erp (split) or erp2 (Baumgarte).
TEST(NormalBlock, TargetsCloseAGapAndCorrectPenetration) {
  const double dt = 0.01, size = 0.05;
  const Vec3 tilt(0.0, 0.002, -0.001);
  NormalTargets t = normalTargets(0.001, 0.0005, tilt, size, dt, true, 0.2, 0.8, 0.0);
  EXPECT_DOUBLE_EQ(t.velocity[0], -(0.0005 + kLowSideSinkRelTol * size) / dt);
  EXPECT_EQ(t.push, Vec3(tilt * 0.2 / dt));
  t = normalTargets(0.001, 0.002, tilt, size, dt, false, 0.2, 0.8, 0.0);
  EXPECT_DOUBLE_EQ(t.velocity[0], -0.001 / dt);  // at most the gap
  EXPECT_EQ(t.push, Vec3::Zero());
  t = normalTargets(-0.001, -0.001, tilt, size, dt, true, 0.2, 0.8, 0.0);
  EXPECT_EQ(t.velocity, Vec3::Zero());
  EXPECT_EQ(t.push, Vec3((Vec3(0.001, 0.0, 0.0) + tilt) * 0.2 / dt));
  t = normalTargets(-0.001, -0.001, tilt, size, dt, false, 0.2, 0.8, 0.0);
  EXPECT_EQ(t.velocity, Vec3((Vec3(0.001, 0.0, 0.0) + tilt) * 0.8 / dt));
}

// A soft patch (S24): its sink is corrected in the normal velocity target
// with the contact's own ERP (Bullet's soft rows), with nothing pushed
// along the normal; its tilt, and a gap, as on a hard patch (normalTargets).
TEST(NormalBlock, SoftTargetsPutTheSinkInTheVelocityAndTheTiltAsHard) {
  const double dt = 0.01, size = 0.05, softErp = 0.3, bounce = 0.4;
  const Vec3 tilt(0.0, 0.002, -0.001);
  for (const double gap : {0.001, -0.001})
    for (const bool split : {true, false}) {
      const NormalTargets hard = normalTargets(gap, gap, tilt, size, dt, split, 0.2, 0.8, 0.0);
      const NormalTargets t =
          softNormalTargets(gap, gap, tilt, size, dt, split, 0.2, 0.8, softErp, bounce);
      if (gap > 0.0)
        EXPECT_DOUBLE_EQ(t.velocity[0], hard.velocity[0] + bounce);
      else
        EXPECT_DOUBLE_EQ(t.velocity[0], -gap * softErp / dt + bounce);
      EXPECT_EQ(t.velocity.tail<2>(), hard.velocity.tail<2>());
      EXPECT_EQ(t.push.tail<2>(), hard.push.tail<2>());
      EXPECT_EQ(t.push[0], 0.0);
    }
}

// Bullet's contact CFM per point, spread over a full manifold: a quarter.
TEST(NormalBlock, SoftPatchComplianceIsAFullManifoldInParallel) {
  EXPECT_EQ(kSoftContactPoints, 4);
  EXPECT_DOUBLE_EQ(patchCompliance(2.0), 0.5);
}

// The bounce is added to the normal velocity target (split impulse or not,
// across a gap or not), never to the tilt rates.
TEST(NormalBlock, BounceAddsToTheNormalTargetOnly) {
  const double dt = 0.01, size = 0.05, bounce = 0.7;
  const Vec3 tilt(0.0, 0.002, -0.001);
  for (const double gap : {0.001, -0.001})
    for (const bool split : {true, false}) {
      const NormalTargets plain = normalTargets(gap, gap, tilt, size, dt, split, 0.2, 0.8, 0.0);
      const NormalTargets t = normalTargets(gap, gap, tilt, size, dt, split, 0.2, 0.8, bounce);
      EXPECT_DOUBLE_EQ(t.velocity[0], plain.velocity[0] + bounce);
      EXPECT_EQ(t.velocity.tail<2>(), plain.velocity.tail<2>());
      EXPECT_EQ(t.push, plain.push);
    }
}

// Bullet's restitution curve: e times the closing speed, none below the
// velocity threshold, none for a separating contact or a negative e.
TEST(NormalBlock, RestitutionFollowsBulletsCurve) {
  EXPECT_DOUBLE_EQ(restitutionVelocity(-2.0, 0.5, 0.2), 1.0);
  EXPECT_DOUBLE_EQ(restitutionVelocity(-0.2, 0.5, 0.2), 0.1);  // at the threshold
  EXPECT_EQ(restitutionVelocity(-0.19, 0.5, 0.2), 0.0);
  EXPECT_EQ(restitutionVelocity(1.0, 0.5, 0.2), 0.0);    // separating
  EXPECT_EQ(restitutionVelocity(-1.0, -0.5, 0.2), 0.0);  // negative coefficient
  EXPECT_EQ(restitutionVelocity(-1.0, 0.0, 0.2), 0.0);
}

// Touching: this step's bounce (or the one owed, if larger). Across a gap
// that closes in this step (1 cm at 1 m/s in 0.01 s): none now, the bounce
// owed to the next step; a gap that stays open: nothing.
TEST(NormalBlock, ABounceAcrossAGapComesTheStepAfterTheLanding) {
  const double dt = 0.01, e = 0.5, th = 0.2;
  Bounce b = restitutionBounce(-1.0, -0.001, dt, e, th, 0.0);
  EXPECT_DOUBLE_EQ(b.now, 0.5);
  EXPECT_EQ(b.next, 0.0);
  b = restitutionBounce(-1.0, 0.01, dt, e, th, 0.0);  // lands in this step
  EXPECT_EQ(b.now, 0.0);
  EXPECT_DOUBLE_EQ(b.next, 0.5);
  b = restitutionBounce(-0.99, 0.01, dt, e, th, 0.0);  // does not reach the face
  EXPECT_EQ(b.now, 0.0);
  EXPECT_EQ(b.next, 0.0);
  b = restitutionBounce(-0.1, 0.0, dt, e, th, 0.5);  // the step after the landing
  EXPECT_DOUBLE_EQ(b.now, 0.5);
  b = restitutionBounce(-0.1, 1e-7, dt, e, th, 0.5);  // a hair above the face
  EXPECT_DOUBLE_EQ(b.now, 0.5);
  b = restitutionBounce(-2.0, 0.0, dt, e, th, 0.5);  // a harder hit now: its own bounce
  EXPECT_DOUBLE_EQ(b.now, 1.0);
}

}  // namespace
}  // namespace patchspin::parts
