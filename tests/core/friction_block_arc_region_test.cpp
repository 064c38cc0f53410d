// The friction block (solveFrictionBlock) on an arc-region patch, both laws:
// its answer is the law (slip: lambda = L q(s / |s|) with s = b + K lambda;
// stick: s = 0 and lambda = -K^-1 b), and the 256-gon of the same cut disk
// gives nearly the same impulse (the n-gon's model difference, ~1e-5 here).
#include <patchspin/friction_block.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "clip_polygon.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace patchspin {
namespace {

std::vector<Vec2> clipToBox(const std::vector<Vec2>& subject, double half) {
  return testing::clipPolygon(
      subject, {Vec2(-half, -half), Vec2(half, -half), Vec2(half, half), Vec2(-half, half)});
}

// slip: lambda = L q(s) to 1e-8 of L (the block's documented 1e-6 of the set
// at worst; ~1e-12 for these well-conditioned K); stick: s = 0
TEST(FrictionBlockArcRegion, AnswerIsTheLawAndNearTheFinePolygon) {
  const double R = 0.02;
  const Vec2 c(0.1 - 0.5 * R, 0.03);
  const PatchShape region = PatchShape::arcRegion(diskPolygonIntersection(
      c, R, {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)}));
  const Vec2 g = region.centroid();
  const PatchShape shape = region.inFrame(g, 0.0);
  std::vector<Vec2> ngon;
  for (int i = 0; i < 256; ++i) {
    const double t = 2.0 * M_PI * (i + 0.5) / 256;
    ngon.push_back(c + R * Vec2(std::cos(t), std::sin(t)));
  }
  const PatchShape poly = PatchShape::polygon(clipToBox(ngon, 0.1)).inFrame(g, 0.0);
  const PatchLoads loads{10.0, 0.01, -0.02};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int slips = 0;
  for (const Model model : {Model::Exact, Model::Ellipsoidal}) {
    const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), 0.5);
    const FrictionPatch fine(poly, LinearPressure::fromLoads(poly, loads), 0.5, patch.rho());
    for (int trial = 0; trial < 40; ++trial) {
      FrictionBlockInput in;
      Mat3 A = Mat3::Identity() + 0.3 * Mat3::NullaryExpr([&] { return u(rng); });
      in.K = A * A.transpose();
      in.b = Vec3(u(rng), u(rng), u(rng));
      in.L = 0.5 * (1.0 + u(rng));
      const FrictionBlockResult r = solveFrictionBlock(patch, model, in);
      const Vec3 s = in.b + in.K * r.impulse;
      if (r.sticking) {
        EXPECT_LT(s.norm(), 1e-10 * (in.b.norm() + in.K.norm() * r.impulse.norm()));
      } else {
        ++slips;
        const Vec3 law = in.L * patch.unitQ(model, s);
        EXPECT_LT((r.impulse - law).norm(), 1e-8 * in.L) << trial;
      }
      const FrictionBlockResult rf = solveFrictionBlock(fine, model, in);
      EXPECT_LT((r.impulse - rf.impulse).norm(), 1e-3 * in.L) << trial;
    }
  }
  EXPECT_GT(slips, 20);
}

}  // namespace
}  // namespace patchspin
