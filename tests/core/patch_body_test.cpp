// Tests of the patch body part (parts/patch_body.hpp) against dense linear
// algebra: J M^-1 J^T with the rows of patchBodyRows and a block-diagonal
// M^-1, and the velocity change M^-1 J^T lambda of an impulse.
#include <patchspin/parts/patch_body.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <random>

namespace patchspin::parts {
namespace {

// A handful of 6x6 products and sums of O(1-100) numbers: round-off ~1e-14
// relative, with room for the spread of the inertia's eigenvalues.
constexpr double kDenseTol = 1e-12;

using Mat66 = Eigen::Matrix<double, 6, 6>;

using testing::inverseMass;
using testing::randomRotation;

PatchBody randomBody(std::mt19937& rng, bool isotropic) {
  return testing::randomBody(rng, !isotropic);
}

double relativeError(const Mat66& a, const Mat66& b) {
  return (a - b).norm() / b.norm();
}

TEST(PatchBody, EffectiveMassIsTheDenseProductOfItsRows) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const PatchBody a = randomBody(rng, trial % 3 != 0), b = randomBody(rng, true);
    const Mat3 F = randomRotation(rng);
    const double rho = 0.02 + 0.001 * trial;
    const Mat66 Ja = patchBodyRows(a, F, rho), Jb = patchBodyRows(b, F, rho);
    const Mat66 dense = Ja * inverseMass(a) * Ja.transpose() + Jb * inverseMass(b) * Jb.transpose();
    EXPECT_LT(relativeError(patchEffectiveMass(a, F, rho), Ja * inverseMass(a) * Ja.transpose()),
              kDenseTol);
    EXPECT_LT(relativeError(patchEffectiveMass(a, b, F, rho), dense), kDenseTol);
  }
}

TEST(PatchBody, AStaticBodyAddsNothing) {
  std::mt19937 rng(8);
  const PatchBody a = randomBody(rng, true), ground;
  const Mat3 F = randomRotation(rng);
  EXPECT_EQ(patchEffectiveMass(a, ground, F, 0.03), patchEffectiveMass(a, F, 0.03));
  EXPECT_EQ(patchEffectiveMass(ground, a, F, 0.03), patchEffectiveMass(a, F, 0.03));
}

// c = J_a [va; wa] - J_b [vb; wb], with the DOFs' meaning (S1) checked
// directly: the normal velocity of O, the tilt rates and rho times the spin.
TEST(PatchBody, VelocityIsTheRowsTimesTheBodyVelocities) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const PatchBody a = randomBody(rng, true), b = randomBody(rng, true);
    const Mat3 F = randomRotation(rng);
    const double rho = 0.04;
    const Vec3 va(u(rng), u(rng), u(rng)), wa(u(rng), u(rng), u(rng)), vb(u(rng), u(rng), u(rng)),
        wb(u(rng), u(rng), u(rng));
    Eigen::Matrix<double, 6, 1> qa, qb;
    qa << va, wa;
    qb << vb, wb;
    const Vec6 dense = patchBodyRows(a, F, rho) * qa - patchBodyRows(b, F, rho) * qb;
    const Vec6 c = patchVelocity(a, va, wa, b, vb, wb, F, rho);
    EXPECT_LT((c - dense).norm(), kDenseTol * dense.norm());
    const Vec3 u0 = (va + wa.cross(a.r)) - (vb + wb.cross(b.r)), w = wa - wb;
    EXPECT_NEAR(c[0], F.col(2).dot(u0), kDenseTol);
    EXPECT_NEAR(c[3], F.col(0).dot(u0), kDenseTol);
    EXPECT_NEAR(c[4], F.col(1).dot(u0), kDenseTol);
    EXPECT_NEAR(c[1], F.col(0).dot(w), kDenseTol);
    EXPECT_NEAR(c[5], rho * F.col(2).dot(w), kDenseTol);
  }
}

// An impulse changes the bodies' velocities by M^-1 J^T lambda (A) and
// -M^-1 J^T lambda (B), and so the DOF velocities by K6 lambda.
TEST(PatchBody, ImpulseChangesVelocitiesByTheInverseMassTimesTheRows) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const PatchBody a = randomBody(rng, trial % 2 == 0), b = randomBody(rng, true);
    const Mat3 F = randomRotation(rng);
    const double rho = 0.05;
    Vec6 lam;
    for (int i = 0; i < 6; ++i) lam[i] = u(rng);
    Eigen::Matrix<double, 6, 1> dq[2];
    applyPatchImpulse(a, b, F, rho, lam,
                      [&](int side, const Vec3& dv, const Vec3& dw) { dq[side] << dv, dw; });
    const Eigen::Matrix<double, 6, 1> ea =
        inverseMass(a) * patchBodyRows(a, F, rho).transpose() * lam;
    const Eigen::Matrix<double, 6, 1> eb =
        -inverseMass(b) * patchBodyRows(b, F, rho).transpose() * lam;
    EXPECT_LT((dq[0] - ea).norm(), kDenseTol * ea.norm());
    EXPECT_LT((dq[1] - eb).norm(), kDenseTol * eb.norm());
    const Vec6 dc = patchVelocity(a, dq[0].head<3>(), dq[0].tail<3>(), b, dq[1].head<3>(),
                                  dq[1].tail<3>(), F, rho);
    const Vec6 expected = patchEffectiveMass(a, b, F, rho) * lam;
    EXPECT_LT((dc - expected).norm(), kDenseTol * expected.norm());
  }
}

}  // namespace
}  // namespace patchspin::parts
