// Tests of the stack hold part (parts/stack_hold.hpp): the folded blocks of
// a stacked patch are those of the dense Schur complement of the two
// patches' 12 x 12 effective mass, K_P - K_PS K_S^-1 K_SP, built from the
// rows of each body (J M^-1 J^T), and the support's gain is -K_S^-1 K_SP.
#include <patchspin/parts/stack_hold.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

namespace patchspin::parts {
namespace {

// 12x12 products and a 6x6 inverse with condition numbers up to ~1e4.
constexpr double kSchurTol = 1e-9;

using Mat12 = Eigen::Matrix<double, 12, 12>;

// A body U on a body L on the ground: patch 0 (U on L) and patch 1 (L on
// the static ground); body ids U = 0, L = 1, ground = 2.
struct Stack {
  PatchBody upper, lower, ground;
  Mat3 F0, F1;
  double rho0 = 0.03, rho1 = 0.05;
};

Stack randomStack(std::mt19937& rng) {
  Stack s;
  s.upper = testing::randomBody(rng);
  s.lower = testing::randomBody(rng);
  s.F0 = testing::randomRotation(rng);
  s.F1 = testing::randomRotation(rng);
  return s;
}

// The dense effective mass of the 12 DOFs: rows of patch 0 act on U and
// (minus) L, rows of patch 1 on L; the lower body's lever differs per patch.
Mat12 denseK(const Stack& s, const PatchBody& lowerAsB) {
  Eigen::Matrix<double, 12, 12> J = Eigen::Matrix<double, 12, 12>::Zero();  // columns: U (6), L (6)
  J.block<6, 6>(0, 0) = patchBodyRows(s.upper, s.F0, s.rho0);
  J.block<6, 6>(0, 6) = -patchBodyRows(lowerAsB, s.F0, s.rho0);
  J.block<6, 6>(6, 6) = patchBodyRows(s.lower, s.F1, s.rho1);
  Mat12 Minv = Mat12::Zero();
  Minv.block<6, 6>(0, 0) = testing::inverseMass(s.upper);
  Minv.block<6, 6>(6, 6) = testing::inverseMass(s.lower);
  return J * Minv * J.transpose();
}

TEST(StackHold, FoldsTheSupportByTheDenseSchurComplement) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 50; ++trial) {
    Stack s = randomStack(rng);
    // the lower body seen from patch 0: same mass and inertia, its own lever
    PatchBody lowerAsB = s.lower;
    lowerAsB.r = s.lower.r + Vec3(0.0, 0.0, 0.04);
    const std::vector<StackPatchView> views = {{0, 1, &s.upper, &lowerAsB, &s.F0, s.rho0},
                                               {1, 2, &s.lower, &s.ground, &s.F1, s.rho1}};
    std::vector<StackLinks> links;
    std::vector<StackHold> holds;
    linkStackedPatches(views, 3, std::vector<char>(3, 0), links, holds);
    ASSERT_EQ(links[0].support, 1);
    ASSERT_EQ(links[1].load, 0);
    const StackHold& held = holds[std::size_t(links[0].hold)];
    ASSERT_TRUE(held.all.valid);
    const Mat12 K = denseK(s, lowerAsB);
    const Mat6 Kpp = K.topLeftCorner<6, 6>(), Kps = K.topRightCorner<6, 6>(),
               Kss = K.bottomRightCorner<6, 6>();
    const Mat6 schur = Kpp - Kps * Kss.inverse() * Kps.transpose();
    PatchBlocks expected;
    ASSERT_TRUE(makePatchBlocks(schur, expected));
    EXPECT_LT((held.all.Ks - expected.Ks).norm(), kSchurTol * expected.Ks.norm());
    EXPECT_LT((held.all.Winv - expected.Winv).norm(), kSchurTol * expected.Winv.norm());
    const Mat6 gain = -Kss.inverse() * Kps.transpose();
    EXPECT_LT((held.all.gain - gain).norm(), kSchurTol * gain.norm());
    // the support's normal block alone held: the Schur complement over DOFs 0-2
    const Mat3 Kn = Kss.topLeftCorner<3, 3>();
    const Mat6 schurN = Kpp - Kps.leftCols<3>() * Kn.inverse() * Kps.leftCols<3>().transpose();
    ASSERT_TRUE(held.normal.valid);
    ASSERT_TRUE(makePatchBlocks(schurN, expected));
    EXPECT_LT((held.normal.Ks - expected.Ks).norm(), kSchurTol * expected.Ks.norm());
  }
}

// The lower body in another row (a point contact or a joint): no hold, the
// support's share would not be projected onto its limits.
TEST(StackHold, LeavesALowerBodyInOtherRowsAlone) {
  std::mt19937 rng(32);
  Stack s = randomStack(rng);
  const std::vector<StackPatchView> views = {{0, 1, &s.upper, &s.lower, &s.F0, s.rho0},
                                             {1, 2, &s.lower, &s.ground, &s.F1, s.rho1}};
  std::vector<StackLinks> links;
  std::vector<StackHold> holds;
  linkStackedPatches(views, 3, {0, 1, 0}, links, holds);
  EXPECT_EQ(links[0].support, -1);
  EXPECT_TRUE(holds.empty());
}

// Two patches on the same lower body: not a simple stack.
TEST(StackHold, LeavesABodyCarryingTwoPatchesAlone) {
  std::mt19937 rng(33);
  Stack s = randomStack(rng);
  PatchBody third = testing::randomBody(rng);
  const std::vector<StackPatchView> views = {{0, 1, &s.upper, &s.lower, &s.F0, s.rho0},
                                             {3, 1, &third, &s.lower, &s.F0, s.rho0},
                                             {1, 2, &s.lower, &s.ground, &s.F1, s.rho1}};
  std::vector<StackLinks> links;
  std::vector<StackHold> holds;
  linkStackedPatches(views, 4, std::vector<char>(4, 0), links, holds);
  EXPECT_EQ(links[0].support, -1);
  EXPECT_EQ(links[1].support, -1);
}

}  // namespace
}  // namespace patchspin::parts
