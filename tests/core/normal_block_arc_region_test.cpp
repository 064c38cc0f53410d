// The normal block's patch geometry on arc regions: the nearest patch point
// and the inner radius against dense boundary samples, and the clamp's
// single contact point on an arc.
#include <patchspin/parts/normal_block.hpp>
#include <patchspin/parts/patch_blocks.hpp>

#include "arc_region_quadrature.hpp"
#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace patchspin::parts {
namespace {

using patchspin::testing::exact_arc::Region;

Region coinOverEdge() {
  // a coin of radius 2 cm over a box edge at 0.5 R, about its centroid
  const std::vector<Vec2> box = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1),
                                 Vec2(-0.1, 0.1)};
  Region r = diskPolygonIntersection(Vec2(0.09, 0.03), 0.02, box);
  const AreaMoments m = areaMomentsOf(r);
  const Vec2 g = m.first / m.area;
  for (BoundaryPiece& p : r) p.a -= g, p.b -= g, p.centre -= g;
  return r;
}

// 20000 samples per piece, spacing h < 0.02 m * 2 pi / 20000: no sample is
// nearer than the true nearest point (to 1e-12 m) and one is within h / 2
// of it (triangle inequality)
TEST(NormalBlockArcRegion, NearestPointAndInnerRadius) {
  for (const Region& region : {coinOverEdge(), diskDiskIntersection(Vec2(-0.0125, -0.005), 0.02,
                                                                    Vec2(0.0125, 0.005), 0.02)}) {
    const PatchShape shape = PatchShape::arcRegion(region);
    const std::vector<Vec2> pts = patchspin::testing::exact_arc::boundarySamples(region, 20000);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.04, 0.04);
    for (int i = 0; i < 200; ++i) {
      const Vec2 p(u(rng), u(rng));
      const Vec2 q = nearestPointOn(shape, p);
      if (patchspin::testing::arc_region::insideByChords(region, p)) {
        EXPECT_EQ(q, p);
        continue;
      }
      double best = INFINITY;
      for (const Vec2& s : pts) best = std::min(best, (s - p).norm());
      const double h = 0.02 * 2.0 * M_PI / 20000.0;
      EXPECT_GE(best, (q - p).norm() - 1e-12);
      EXPECT_LE(best, (q - p).norm() + h / 2.0);
      EXPECT_TRUE(shape.contains(q, 1e-12));
    }
    // the inner radius about O (inside both regions): the distance to the
    // nearest boundary sample (these regions are a disk ∩ half-planes)
    double inner = INFINITY;
    for (const Vec2& s : pts) inner = std::min(inner, s.norm());
    EXPECT_NEAR(std::sqrt(innerRadiusSquared(shape)), inner, 1e-9);
  }
}

// A centre of pressure beyond the arc: the clamp acts through one point, the
// radial nearest point of the arc, pushing (or not at all).
TEST(NormalBlockArcRegion, ClampOnAnArcActsAtItsNearestPoint) {
  const Region region = coinOverEdge();
  const PatchShape shape = PatchShape::arcRegion(region);
  const PatchOutlineSummary outline = summarizeOutline(shape);
  std::mt19937 rng(13);
  int clamped = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const PatchBody a = testing::randomBody(rng), ground;
    const Mat3 F = testing::randomRotation(rng);
    PatchBlocks k;
    ASSERT_TRUE(makePatchBlocks(patchEffectiveMass(a, ground, F, 0.03), k));
    // a cop at 1.5 R from the coin's centre on the arc's side (x < edge)
    const BoundaryPiece* arc = nullptr;
    for (const BoundaryPiece& p : shape.boundary())
      if (p.kind == BoundaryPiece::Kind::Arc) arc = &p;
    ASSERT_NE(arc, nullptr);
    const double t = 0.5 * (arc->angle0 + arc->angle1) + 0.3 * std::sin(trial);
    const Vec2 cop = arc->centre + 1.5 * arc->radius * Vec2(std::cos(t), std::sin(t));
    NormalImpulse out;
    clampNormalImpulse(k.Winv, Vec3(1.0, cop.y(), -cop.x()), Vec3(0.1, 0.0, 0.0), cop, outline,
                       shape, out);
    if (!(out.lamN[0] > 0.0)) continue;
    ++clamped;
    const Vec2 at(-out.lamN[2] / out.lamN[0], out.lamN[1] / out.lamN[0]);
    const Vec2 expected = arc->centre + arc->radius * Vec2(std::cos(t), std::sin(t));
    EXPECT_LT((at - expected).norm(), 1e-12) << trial;
    EXPECT_TRUE(out.tipping);
  }
  EXPECT_GT(clamped, 50);
}

}  // namespace
}  // namespace patchspin::parts
