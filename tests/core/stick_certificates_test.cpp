// Tests of the exact law's stick certificates (parts/stick_certificates.hpp):
// a certificate never sticks a block that the full block solver
// (solveFrictionBlock) says slips, and it does certify many sticks near the
// limit set's boundary (not a vacuous test).
#include <patchspin/friction_block.hpp>
#include <patchspin/parts/stick_certificates.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <random>

namespace patchspin::parts {
namespace {

Mat3 randomSpd(std::mt19937& rng) {
  const Mat3 R = testing::randomRotation(rng);
  std::uniform_real_distribution<double> e(0.5, 5.0);
  return R * Vec3(e(rng), e(rng), e(rng)).asDiagonal() * R.transpose();
}

void checkPatch(const FrictionPatch& law, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> scale(0.3, 1.5);
  const Mat3 piInv = law.Pi().inverse();
  int certified = 0, sticks = 0;
  StickCertificates certs;
  for (int trial = 0; trial < 600; ++trial) {
    // lambda0 = -K^-1 b of a block near its friction limit L = 1 (the
    // interesting range: inside, on and just beyond E's boundary)
    const Mat3 K = randomSpd(rng);
    const Vec3 dir = Vec3(n(rng), n(rng), n(rng)).normalized();
    const Vec3 boundary = law.unitQ(Model::Exact, -dir);  // a point of E's boundary
    const Vec3 lambda0 =
        scale(rng) * boundary.norm() * Vec3(n(rng), n(rng), n(rng)).normalized() * 0.2 +
        scale(rng) * boundary;
    FrictionBlockInput in;
    in.K = K;
    in.b = -K * lambda0;
    in.L = 1.0;
    const FrictionBlockResult solved = solveFrictionBlock(law, Model::Exact, in);
    sticks += solved.sticking;
    // the certificates' state carries over between trials, as between visits
    bool refine = true;
    if (trial % 7 == 0) certs.invalidate();
    if (exactHullSticks(certs, piInv, /*sticking=*/true, law, lambda0, 1.0, refine)) {
      ++certified;
      EXPECT_TRUE(solved.sticking) << "certified a slipping block, trial " << trial;
    }
  }
  // the certificates prove a good part of the sticks (measured ~40 % here)
  EXPECT_GT(certified, sticks / 5);
  EXPECT_GT(sticks, 100);
}

TEST(StickCertificates, NeverStickABlockTheSolverSaysSlipsOnADisk) {
  const PatchShape disk = PatchShape::disk(0.05);
  checkPatch(FrictionPatch(disk, LinearPressure::fromLoads(disk, {10.0, 0.06, -0.04}), 0.5), 51);
}

TEST(StickCertificates, NeverStickABlockTheSolverSaysSlipsOnARectangle) {
  const PatchShape rect = PatchShape::rectangle(0.08, 0.04, Vec2(0.01, -0.005));
  checkPatch(FrictionPatch(rect, LinearPressure::fromLoads(rect, {10.0, 0.02, 0.03}), 0.5), 52);
}

TEST(StickCertificates, KeepTheSolversBoundaryPointOfAStick) {
  StickCertificates certs;
  keepGaugePoint(certs, Vec3(0.0, 0.0, 1.0), Vec3(0.0, 0.0, -0.5), true);
  EXPECT_TRUE(certs.hullValid);
  EXPECT_EQ(certs.hullDirection, Vec3(0.0, 0.0, -1.0));
  EXPECT_EQ(certs.gaugeSlip, Vec3(0.0, 0.0, 1.0));
  StickCertificates slip;
  keepGaugePoint(slip, Vec3(0.0, 1.0, 0.0), Vec3(0.0, -0.5, 0.0), false);
  EXPECT_FALSE(slip.hullValid);
  EXPECT_EQ(slip.gaugeSlip, Vec3(0.0, 1.0, 0.0));
}

}  // namespace
}  // namespace patchspin::parts
