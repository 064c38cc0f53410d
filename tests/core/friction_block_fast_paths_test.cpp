// The friction block's shortcuts for speed (issue 6) decide as the checks
// they stand in front of: the ellipsoidal block's positive definiteness test
// accepts a K without factoring it when its off-diagonals are small
// (A_ij^2 <= 0.2 A_ii A_jj); every other K goes to the Cholesky
// factorisation. Checked against Eigen's own LLT of K's symmetric part (the
// factorisation the block documents as its decision).
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <string>

using namespace patchspin;

namespace {

// Eigen's decision: K's symmetric part has a Cholesky factor with a positive
// diagonal and finite entries.
bool llTAccepts(const Mat3& K) {
  const Mat3 A = 0.5 * (K + K.transpose());
  const Eigen::LLT<Mat3> llt(A);
  return llt.info() == Eigen::Success && A.diagonal().minCoeff() > 0.0 &&
         llt.matrixLLT().allFinite();
}

// Whether the ellipsoidal block refuses K as not positive definite.
bool blockRefusesAsIndefinite(const FrictionPatch& patch, const Mat3& K) {
  FrictionBlockInput in;
  in.K = K;
  in.b = Vec3(0.3, -0.2, 0.1);
  in.L = 0.5;
  try {
    solveFrictionBlock(patch, Model::Ellipsoidal, in);
  } catch (const Error& e) {
    return std::string(e.what()).find("not positive definite") != std::string::npos;
  }
  return false;
}

}  // namespace

// K = D^1/2 C D^1/2 over a grid of unit-diagonal C with off-diagonals in
// [-0.6, 0.6] (the shortcut's bound is |c| <= sqrt(0.2) = 0.447; beyond it
// are indefinite and exactly singular C, e.g. all three -0.5) and diagonals
// D spanning 1e-3 to 1e3: the block refuses exactly the K that LLT refuses.
TEST(FrictionBlockFastPaths, EllipsoidalPositiveDefinitenessShortcutDecidesAsTheFactorisation) {
  const PatchShape disk = PatchShape::disk(0.05);
  const FrictionPatch patch(disk, LinearPressure::uniform(disk, 1.0), 0.3);
  constexpr int kSteps = 13;  // c = -0.6, -0.5, ..., 0.6
  const double diagonals[3][3] = {{1.0, 1.0, 1.0}, {1e-3, 1.0, 1e3}, {2.5e2, 4e-2, 7.0}};
  int accepted = 0, refused = 0, shortcutRegion = 0;
  for (const auto& dg : diagonals) {
    const Vec3 s(std::sqrt(dg[0]), std::sqrt(dg[1]), std::sqrt(dg[2]));
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; j < kSteps; ++j)
        for (int k = 0; k < kSteps; ++k) {
          const double c01 = -0.6 + 0.1 * i, c02 = -0.6 + 0.1 * j, c12 = -0.6 + 0.1 * k;
          Mat3 C;
          C << 1.0, c01, c02, c01, 1.0, c12, c02, c12, 1.0;
          const Mat3 K = s.asDiagonal() * C * s.asDiagonal();
          const bool llt = llTAccepts(K);
          EXPECT_EQ(blockRefusesAsIndefinite(patch, K), !llt)
              << "c = (" << c01 << ", " << c02 << ", " << c12 << "), diagonal " << dg[0] << " "
              << dg[1] << " " << dg[2];
          (llt ? accepted : refused) += 1;
          if (std::abs(c01) <= 0.44 && std::abs(c02) <= 0.44 && std::abs(c12) <= 0.44)
            ++shortcutRegion;
        }
  }
  // both decisions and the shortcut's region are exercised
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
  EXPECT_GT(shortcutRegion, 0);
}
