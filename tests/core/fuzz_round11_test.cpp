// Eleventh fuzz round (issue 6): regression test for the class decided in it
// (fuzz/README.md, "Eleventh round", item 66): the exact block of a tiny
// patch far from O, recentred about its centre (item 56), fell back to O
// when the recentred patch's scale check overflowed for a huge mu, although
// the block solves the unit law, which mu does not enter.
//
// The oracle is brute-force quadrature of Eq. (16) at the returned slip
// (tests/support/oracle.hpp), as in item 64's test. (Checked: with
// ea75cc2's step.cpp, main's before this round, linked ahead of the core,
// the test fails: the impulse is 2.7e-5 of L off the law; on the final core
// it passes, 1.2e-9 of L.)
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/step.hpp>

#include <gtest/gtest.h>

#include "oracle.hpp"

#include <cmath>

using namespace patchspin;

namespace {

// 66, the tenth round's open input
// (step_exact_tiny_disk_far_from_O_icr_at_its_centre_law_1.4e-5_off.bin): a
// 1e-8 m disk 1.05e-4 m (5,300 diameters) from O, rho = 0.5, mu = 1e300,
// slipping with its ICR inside the disk, 0.30 R from its centre. The
// patch's bound mu A max|p| (1 + max|r| / rho) is 1.2e308 about O, but
// 2.9e308 about the disk's centre (max|r'| / rho' = 1.5), so the recentred
// patch was refused and the block was solved about O, where the iteration's
// stop at 1e-14 of the slip scale fixes the ICR only to ~1e-6 R.
TEST(FuzzRound11, ExactBlockOfATinyDiskWithAHugeMuIsTheLawAtItsSlip) {
  const Vec2 centre(-5.0173184718005359e-08, 0.00010531768202781677);
  const double radius = 1e-8, rho = 0.5, mu = 1.0000000000000001e+300;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p =
      LinearPressure::fromLoads(shape, PatchLoads{57673047.943524897, -6073.8475422882257, -2.8935592936814216});
  const FrictionPatch patch(shape, p, mu, rho);
  // (the recentred patch with the same mu is out of range: what sent the
  // block back to O)
  const PatchShape local = shape.inFrame(centre, 0.0);
  const LinearPressure localPressure{p.p0 + p.cx * centre.x() + p.cy * centre.y(), p.cx, p.cy};
  EXPECT_THROW(FrictionPatch(local, localPressure, mu), Error);

  FrictionBlockInput input;
  input.b = Vec3(-7.3046066972892731e-09, 5.5010787036735564e-09, 0.5);
  input.K << 1.25, 0.75, 0.75, 0.75, 1.25, 0.75, 0.75, 0.75, 1.25;
  input.L = 0.5;
  input.warmSlip = Vec3(0.5, 0.5, 0.5);
  input.warmGauge = Vec3(-1.0, 0.5, 3.7838664024170652e+146);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
  ASSERT_FALSE(r.sticking);
  // (the ICR c = rho (-s_y, s_x) / s_z lies inside the disk, 0.30 R from
  // its centre: the law turns with the slip's direction about the centre)
  const Vec2 icr = rho * Vec2(-r.slip.y(), r.slip.x()) / r.slip.z();
  EXPECT_LT((icr - centre).norm(), radius);
  // slip = b + K impulse to the round-off of one 3x3 product
  constexpr double kSlip = 1e-14;
  EXPECT_LT((r.slip - input.b - input.K * r.impulse).norm(),
            kSlip * (input.b.norm() + input.K.norm() * r.impulse.norm()));
  // oracle: Q = -mu ∫ p k dA with mu = 1 by brute-force quadrature of
  // Eq. (16) at the returned slip, so q = Q / Pz; kLaw is the fuzz target's
  // tolerance (relative to L times the set's size, ~1 here: lever 2.1e-4)
  const Vec3 q = patchspin::testing::bruteForceQDisk(centre, radius, patchspin::testing::linearField(p), 1.0, rho,
                                                     r.slip, 1e-12) /
                 patch.Pz();
  constexpr double kLaw = 1e-6;
  EXPECT_LT((r.impulse - input.L * q).norm(), kLaw * input.L)
      << "q " << q.transpose() << ", impulse " << r.impulse.transpose();
}

}  // namespace
