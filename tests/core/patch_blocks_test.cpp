// Tests of the effective-mass blocks (parts/patch_blocks.hpp) against dense
// linear algebra: Ks is the inverse of the friction block of K6^-1 (the
// friction block's response with the normal block held), G = W^-1 Knf.
#include <patchspin/parts/patch_blocks.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

namespace patchspin::parts {
namespace {

// 6x6 inverses of matrices with condition numbers up to ~1e4: ~1e-12.
constexpr double kInverseTol = 1e-10;

TEST(PatchBlocks, FrictionBlockIsTheSchurComplementOfTheNormalBlock) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 200; ++trial) {
    const PatchBody a = testing::randomBody(rng), b = testing::randomBody(rng);
    const Mat3 F = testing::randomRotation(rng);
    const Mat6 K6 = patchEffectiveMass(a, b, F, 0.03);
    PatchBlocks k;
    ASSERT_TRUE(makePatchBlocks(K6, k));
    const Mat3 KsDense = Mat6(K6.inverse()).bottomRightCorner<3, 3>().inverse();
    EXPECT_LT((k.Ks - KsDense).norm(), kInverseTol * KsDense.norm());
    EXPECT_LT((k.KsInv * k.Ks - Mat3::Identity()).norm(), kInverseTol);
    EXPECT_LT((k.Winv * K6.topLeftCorner<3, 3>() - Mat3::Identity()).norm(), kInverseTol);
    EXPECT_LT((K6.topLeftCorner<3, 3>() * k.G - K6.topRightCorner<3, 3>()).norm(),
              kInverseTol * K6.norm());
    EXPECT_EQ(k.Kff, Mat3(K6.bottomRightCorner<3, 3>()));
  }
}

// A body whose rotation is locked has no tilt mobility: W is singular.
TEST(PatchBlocks, RefusesABodyWithLockedRotation) {
  std::mt19937 rng(22);
  PatchBody a = testing::randomBody(rng);
  a.invI.setZero();
  PatchBlocks k;
  EXPECT_FALSE(makePatchBlocks(patchEffectiveMass(a, Mat3::Identity(), 0.03), k));
}

// Spin about the normal locked (an angular factor (1, 1, 0)): the friction
// block's spin DOF has no effective mass.
TEST(PatchBlocks, RefusesAFrictionBlockWithoutSpinMobility) {
  std::mt19937 rng(23);
  PatchBody a = testing::randomBody(rng);
  a.r = Vec3(0.0, 0.0, -0.02);
  const Vec3 factor(1.0, 1.0, 0.0);
  a.invI = factor.asDiagonal() * a.invI * factor.asDiagonal();
  PatchBlocks k;
  EXPECT_FALSE(makePatchBlocks(patchEffectiveMass(a, Mat3::Identity(), 0.03), k));
}

}  // namespace
}  // namespace patchspin::parts
