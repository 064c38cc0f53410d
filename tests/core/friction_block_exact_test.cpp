// The exact block (friction_block.cpp) where the law turns fastest: tiny patches far
// from O, spinning about a point on or inside the patch, huge mu or K, long
// levers. Each answer is checked against brute-force quadrature of Eq. (16)
// at the returned slip (tests/support/oracle.hpp): impulse = L q(s^) to kLaw
// of L times the limit set's size, and slip = b + K impulse to kSlip. The
// assert preset runs these with Eigen's assertions live (fuzz round 11,
// item 68).
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "error_matchers.hpp"
#include "oracle.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace patchspin {
namespace {

using testing::throwsNaming;

// slip = b + K impulse to the round-off of one 3x3 product
constexpr double kSlip = 1e-14;
// the fuzz target's tolerance on the law at the slip, relative to L times the
// limit set's size
constexpr double kLaw = 1e-6;

void expectSlipIsBPlusKImpulse(const FrictionBlockInput& input, const FrictionBlockResult& r) {
  EXPECT_LT((r.slip - input.b - input.K * r.impulse).norm(),
            kSlip * (input.b.norm() + input.K.norm() * r.impulse.norm()));
}

// The oracle: Q = -mu ∫ p k dA with mu = 1 by brute-force quadrature of
// Eq. (16) at the returned slip, so q = Q / Pz.
Vec3 diskLawByQuadrature(const FrictionPatch& patch, const LinearPressure& p, const Vec3& slip) {
  const PatchShape& disk = patch.shape();
  return patchspin::testing::bruteForceQDisk(disk.centre(), disk.radius(),
                                             patchspin::testing::linearField(p), 1.0, patch.rho(),
                                             slip, 1e-12) /
         patch.Pz();
}

void expectImpulseIsTheLaw(const FrictionBlockInput& input, const FrictionBlockResult& r,
                           const Vec3& q, double setSize) {
  EXPECT_LT((r.impulse - input.L * q).norm(), kLaw * input.L * setSize)
      << "q " << q.transpose() << ", impulse " << r.impulse.transpose();
}

// fuzz round 7, item 56
// A 1e-8 m disk 9,000 diameters from O (rho = 0.5), its ICR at the rim: solved
// about the disk's centre, the law at its slip.
TEST(ExactBlock, TinyDiskFarFromOSpinningAboutItsRimIsTheLaw) {
  const Vec2 centre(-3.7438506778344681e-05, -8.2157417227233455e-05);
  const double radius = 1e-8, rho = 0.5;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p = LinearPressure::fromLoads(
      shape, PatchLoads{1371.8459892853916, 0.11270929465102736, -0.051357058932178852});
  const FrictionPatch patch(shape, p, 1073217536.0, rho);
  FrictionBlockInput input;
  input.b = Vec3(0.5, 0.5, 0.5);
  input.L = 0.5;
  input.K << 1.0, 0.5, 0.5, 0.5, 1.25, 0.75, 0.5, 0.75, 1.25;
  input.warmSlip = Vec3(0.5, -524288.0, -524288.0);
  input.warmGauge = Vec3(14956363776.0, 0.00021257251501083374, -1.1920928955078125e-07);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
  ASSERT_FALSE(r.sticking);
  // (the ICR c = rho (-s_y, s_x) / s_z lies at the disk's rim, 1.1 R from
  // its centre: the hard case, where the law turns fastest)
  const Vec2 icr = rho * Vec2(-r.slip.y(), r.slip.x()) / r.slip.z();
  EXPECT_LT((icr - centre).norm(), 2.0 * radius);
  EXPECT_LT((r.slip - input.b - input.K * r.impulse).norm(),
            kSlip * (input.b.norm() + input.K.norm() * r.impulse.norm()));
  // oracle: Q = -mu ∫ p k dA with mu = 1, so q = Q / Pz
  const Vec3 q = patchspin::testing::bruteForceQDisk(
                     centre, radius, patchspin::testing::linearField(p), 1.0, rho, r.slip, 1e-12) /
                 patch.Pz();
  EXPECT_LT((r.impulse - input.L * q).norm(), kLaw * input.L)
      << "q " << q.transpose() << ", impulse " << r.impulse.transpose();
}

// fuzz round 9, item 64
// The same tiny disk with its ICR inside it: the slip polished relative to
// |s'|, the law at its slip.
TEST(ExactBlock, TinyDiskFarFromOSpinningAboutAPointInsideIsTheLaw) {
  const Vec2 centre(-3.7438506778344681e-05, -8.2157417227233455e-05);
  const double radius = 1e-8, rho = 0.5;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p = LinearPressure::fromLoads(
      shape,
      PatchLoads{1.3513656002999971e+158, 1.1102462453994961e+154, -5.0589732790361525e+153});
  const FrictionPatch patch(shape, p, 1073217536.0, rho);
  FrictionBlockInput input;
  input.b = Vec3(-0.0, 0.5, 0.5);
  input.L = 23.6484375;
  input.K = 0.5 * Mat3::Identity();
  input.warmSlip = Vec3(-524288.0, -524288.0, 10661396480.0);
  input.warmGauge = Vec3(0.0, 1e-08, 0.00021257251501083374);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
  ASSERT_FALSE(r.sticking);
  // (the ICR c = rho (-s_y, s_x) / s_z lies inside the disk: the law turns
  // with the slip's direction about g)
  const Vec2 icr = rho * Vec2(-r.slip.y(), r.slip.x()) / r.slip.z();
  EXPECT_LT((icr - centre).norm(), radius);
  EXPECT_LT((r.slip - input.b - input.K * r.impulse).norm(),
            kSlip * (input.b.norm() + input.K.norm() * r.impulse.norm()));
  // oracle: Q = -mu ∫ p k dA with mu = 1 by brute-force quadrature of
  // Eq. (16) at the returned slip, so q = Q / Pz; kLaw is the fuzz target's
  // tolerance (relative to L times the set's size, ~1 here: lever 1.8e-4)
  const Vec3 q = patchspin::testing::bruteForceQDisk(
                     centre, radius, patchspin::testing::linearField(p), 1.0, rho, r.slip, 1e-12) /
                 patch.Pz();
  EXPECT_LT((r.impulse - input.L * q).norm(), kLaw * input.L)
      << "q " << q.transpose() << ", impulse " << r.impulse.transpose();
}

// fuzz round 11, item 66
// mu = 1e300 overflows the recentred patch's bound, not the unit law the block
// solves: still solved about the disk's centre, the law at its slip.
TEST(ExactBlock, TinyDiskWithAHugeMuIsTheLaw) {
  const Vec2 centre(-5.0173184718005359e-08, 0.00010531768202781677);
  const double radius = 1e-8, rho = 0.5, mu = 1.0000000000000001e+300;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p = LinearPressure::fromLoads(
      shape, PatchLoads{57673047.943524897, -6073.8475422882257, -2.8935592936814216});
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
  expectSlipIsBPlusKImpulse(input, r);
  // (the set's size ~1 here: lever 2.1e-4)
  expectImpulseIsTheLaw(input, r, diskLawByQuadrature(patch, p, r.slip), 1.0);
}

// fuzz round 11, item 67
// A quadrilateral 2,094 m from O (lever 4,190) spinning about a point inside
// it, where the law turns across ~1e-11 rad: the law at its slip, also for a
// tolerance below what double resolves.
TEST(ExactBlock, FarPolygonSpinningAboutAPointInsideIsTheLaw) {
  const PatchShape shape = PatchShape::polygon({Vec2(-0.018852195551757815, -2093.2499999998117),
                                                Vec2(-2.0949095026328575e-05, -2093.7499999995339),
                                                Vec2(0.49997904250000003, -2094.7500000049999),
                                                Vec2(0.49997905250000002, -2093.7500000049999)});
  const double rho = 0.5;
  const LinearPressure p = LinearPressure::fromLoads(
      shape, PatchLoads{0.00011939347811641755, 0.25002100756621692, 3.6343011768632856e-05});
  const FrictionPatch patch(shape, p, 0.0, rho);
  FrictionBlockInput input;
  input.b = Vec3(1664.0, 0.5, -6.8545341491699219e-07);
  input.K << 1.25, 0.75, 0.75, 0.75, 1.25, 0.75, 0.75, 0.75, 1.25;
  input.L = 0.5;
  input.warmSlip = Vec3(5.4110892669614444e-312, 0.5, -0.0);
  input.warmGauge = Vec3(7.5658590503735468e-10, 4.0218728298904003e+180, 0.5);
  // (and with a tolerance below what double resolves, which never met the
  // linearised last step and ended with the iterate's own q: 0.027 of L off
  // the law at the returned slip before the step was finished at the
  // default tolerance's level; 1e-17 already passed)
  for (const double tolerance : {0.0, 1e-18}) {
    SCOPED_TRACE(tolerance);
    input.tolerance = tolerance;
    const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
    ASSERT_FALSE(r.sticking);
    // the ICR, rho (-s_y, s_x) / s_z, is inside the patch
    const Vec2 icr = rho * Vec2(-r.slip.y(), r.slip.x()) / r.slip.z();
    EXPECT_TRUE(shape.contains(icr)) << icr.transpose();
    expectSlipIsBPlusKImpulse(input, r);
    const Vec3 q = patchspin::testing::bruteForceQ(shape, patchspin::testing::linearField(p), 1.0,
                                                   rho, r.slip, 1e-13) /
                   patch.Pz();
    // the set's size (1 + max|r| / rho): the fuzz target's without its factor
    // A max|p| / Pz (2.6 here: min p is -2.8e-12 of the mean, so the target
    // bounds ∫|p| by A max|p|), stricter than the target
    expectImpulseIsTheLaw(input, r, q, 1.0 + shape.maxDistanceFromOrigin() / rho);
  }
}

// fuzz round 11, item 67
// The tiny disk with K of 3.9e146 on its diagonal: the law at its slip.
TEST(ExactBlock, TinyDiskWithAHugeKIsTheLaw) {
  const Vec2 centre(-3.7438506778344681e-05, -8.2157417227233455e-05);
  const double radius = 1e-8, rho = 0.5;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p = LinearPressure::fromLoads(
      shape, PatchLoads{3.1464622713927023e+148, 2.5851270122528471e+144, -1.177964382294434e+144});
  const FrictionPatch patch(shape, p, 1073217536.0, rho);
  FrictionBlockInput input;
  input.b = Vec3(0.5, 0.5, 3.8706602357762659e+146);
  input.K << 3.8706602353384459e+146, 1.0000449977815151, 0.50002250389075753,  //
      1.0000449977815151, 3.8706602353384459e+146, 1.5000000099999999,          //
      0.50002250389075753, 1.5000000099999999, 3.8706602353384459e+146;
  input.L = 0.5;
  input.warmSlip = Vec3(0.5, 4.3910071674220151e+223, 0.0);
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
  ASSERT_FALSE(r.sticking);
  expectSlipIsBPlusKImpulse(input, r);
  expectImpulseIsTheLaw(input, r, diskLawByQuadrature(patch, p, r.slip), 1.0);
}

// fuzz round 11, item 68 (stableNorm of a fixed-size K aborted with assertions on)
// A block in the verified regime (cond(K) max(1, lever, 1 / lever) >= 1e5):
// the law at its slip.
TEST(ExactBlock, VerifiedBlockIsTheLawAtItsSlip) {
  const Vec2 centre(600.0, 0.0);
  const double radius = 0.1, rho = 0.5;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p{1.0 / (M_PI * radius * radius), 0.0, 0.0};  // uniform, Pz = 1 N
  const FrictionPatch patch(shape, p, 0.5, rho);
  FrictionBlockInput input;
  input.b = Vec3(1.0, 0.2, 0.3);
  input.K = Vec3(1.0, 1.0, 0.01).asDiagonal();
  input.L = 0.1;
  const double cond = input.K.norm() * Mat3(input.K.inverse()).norm();
  const double lever = shape.maxDistanceFromOrigin() / rho;
  ASSERT_GE(cond * lever, 1e5);  // the verified regime
  const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
  ASSERT_FALSE(r.sticking);
  expectSlipIsBPlusKImpulse(input, r);
  expectImpulseIsTheLaw(input, r, diskLawByQuadrature(patch, p, r.slip), 1.0 + lever);
}

// A coin-sized disk sliding and spinning (|K| L |dq/ds| / |s| well below 1/2,
// the fixed-point polish's regime), solved cold and then warm-started: at the
// answer itself, one fixed-point step on from a nearby impulse (b + K L q of
// the answer turned by 1e-4: the Bullet adapter's s = b + K lamF), and the
// answer turned by 0.7 and 0.3 of the tolerance across itself (a first
// iterate that meets the stopping rule at once, its q the law at s, not at
// the returned slip). At tolerances from coarse to the default, four slips
// from translation to spin and two with the ICR at the rim, where q turns
// fastest (there a first iterate returned without the polish misses the law
// at its slip by 1.5 times the tolerance, measured at 1e-3, 1e-6, 1e-9; the
// polish is skipped only where |J| |K grad D| / |s| bounds that miss by half
// the tolerance). Asserted: the impulse is the law at its slip by quadrature
// to the tolerance of |q| (the polish's own criterion; kQuadrature for the
// oracle's 1e-12 and the law's round-off), and the slip is the cold one to
// kAgree times the tolerance of the slip scale |b| + L |K| (the stopping
// rule |K grad D| <= tol scale with the potential's Hessian K^-1 to within a
// factor 2 here; measured: 0.005 of it at most).
TEST(ExactBlock, WarmStartedSlipIsTheLawAtItsSlip) {
  const double radius = 0.012;
  const PatchShape coin = PatchShape::disk(radius, Vec2::Zero());
  const LinearPressure p = LinearPressure::fromLoads(coin, PatchLoads{0.02, 4e-5, -2e-5});
  const FrictionPatch patch(coin, p, 0.5, coin.defaultRho());
  ASSERT_GE(minPressure(coin, patch.pressure()), 0.0);
  constexpr double kQuadrature = 1e-11, kAgree = 2.0;
  FrictionBlockInput input;
  input.K << 80.0, 1.0, -2.0, 1.0, 70.0, 0.5, -2.0, 0.5, 150.0;
  input.L = 0.5 * 0.02 / 240.0;
  const double rimIcr = radius / patch.rho();  // |s_xy| / s_z with the ICR at the rim
  for (const Vec3& b : {Vec3(1.2, -0.4, 0.9), Vec3(-0.3, 0.05, 1.4), Vec3(0.8, 0.7, -0.1),
                        Vec3(0.05, -0.02, 1.0), Vec3(rimIcr, 0.0, 1.0), Vec3(0.0, rimIcr, 1.0)}) {
    for (const double tol : {1e-3, 1e-6, 1e-9, 1e-12, 0.0}) {
      SCOPED_TRACE(::testing::Message() << "b " << b.transpose() << ", tol " << tol);
      input.b = b;
      input.tolerance = tol;
      input.warmSlip.setZero();
      const FrictionBlockResult cold = solveFrictionBlock(patch, Model::Exact, input);
      ASSERT_FALSE(cold.sticking);
      const double t = tol > 0.0 ? tol : 1e-14;
      const Vec3 across = cold.slip.unitOrthogonal();
      const Eigen::AngleAxisd nearImpulse(1e-4, Vec3(0.3, -0.5, 0.8).normalized()),
          first(0.7 * t, across), second(0.3 * t, cold.slip.normalized().cross(across));
      for (const Vec3& warm : {cold.slip, Vec3(b + input.K * (nearImpulse * cold.impulse)),
                               Vec3(first * cold.slip), Vec3(second * cold.slip)}) {
        input.warmSlip = warm;
        const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, input);
        ASSERT_FALSE(r.sticking);
        expectSlipIsBPlusKImpulse(input, r);
        const Vec3 q = diskLawByQuadrature(patch, p, r.slip);
        EXPECT_LT((r.impulse / input.L - q).norm(), (t + kQuadrature) * q.norm());
        EXPECT_LT((r.slip - cold.slip).norm(),
                  kAgree * t * (input.b.norm() + input.L * input.K.norm()));
      }
    }
  }
}

// fuzz round 5 (a torque 100 L outside the set)
// A pressure whose terms about O cancel (round-off model 51 > 1e-6) is refused
// by the exact block, naming it; the ellipsoidal block solves it, and a
// 1 m x 1 mm face under a tipped admissible pressure is solved.
TEST(ExactBlock, RefusesALawWithoutDigits) {
  const PatchShape sliver = PatchShape::polygon({{-5.00585889346894e-09, -5.4910742118954658e-09},
                                                 {-3.1943728212127098e-09, -5.4910742300103267e-09},
                                                 {0.49999999680574098, 1.3205255290824883e-09},
                                                 {4.8521548660111215e-10, 6.3205254922877428e-09}});
  const FrictionPatch noisy(
      sliver,
      LinearPressure::fromLoads(
          sliver, {0.32000003110670083, 2.6728782502318121e-10, 0.040000002870676614}),
      1e-8, 0.5);
  // the law is noise: some direction's unit torque exceeded ten times its
  // bound max|r| / rho (measured here before the sixth round; since then the
  // exact law itself refuses this pressure, FrictionBlockIllConditioned.
  // ExactLawRefusesAPressureWithoutDigits)
  ASSERT_GE(minPressure(sliver, noisy.pressure()),
            -1e-6 * noisy.Pz() / sliver.area());  // inside the p >= 0 domain
  FrictionBlockInput in;
  in.b = Vec3(0.5, 0.5, 0.5);
  in.L = 0.5;
  in.K << 29359104.75, 0.50000000080302698, 0.25000000500000003, 0.50000000080302698, 29359104.5,
      5.8030269782466349e-09, 0.25000000500000003, 5.8030269782466349e-09, 29359104.25;
  in.warmSlip = Vec3(12674138112.0, 0.5, 0.5);
  EXPECT_TRUE(throwsNaming([&] { solveFrictionBlock(noisy, Model::Exact, in); }, {"no digits"}));
  EXPECT_NO_THROW(solveFrictionBlock(noisy, Model::Ellipsoidal, in));
  // an ordinary long face, 1 m x 1 mm, with its centre of pressure moved
  // to the end of the kern and beyond (then projected)
  const PatchShape face = PatchShape::rectangle(1.0, 1e-3, Vec2(0.2, 0.0));
  const PatchLoads tipped = nearestAdmissibleLoads(face, {1.0, -0.3e-3, 0.5}, face.defaultRho());
  const FrictionPatch ordinary(face, LinearPressure::fromLoads(face, tipped), 0.5, 0.0);
  FrictionBlockInput slide;
  slide.b = Vec3(1.0, 0.5, 0.25);
  slide.L = 0.5;
  EXPECT_NO_THROW(solveFrictionBlock(ordinary, Model::Exact, slide));
}

// Blocks at E's boundary for the gauge tests below: lambda0 = f L q(u) for a
// random unit u, so whether the block sticks (f <= 1) is known without the
// solver, and u is where E's boundary point along lambda0 lies.
struct BoundaryBlock {
  FrictionBlockInput in;
  Vec3 u;
};
BoundaryBlock boundaryBlock(const FrictionPatch& patch, std::mt19937& rng, double f) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0), eig(0.2, 5.0);
  std::normal_distribution<double> n;
  Mat3 A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) = entry(rng);
  const Mat3 Qm = Eigen::HouseholderQR<Mat3>(A).householderQ();
  BoundaryBlock block;
  block.in.K = Qm * Vec3(eig(rng), eig(rng), eig(rng)).asDiagonal() * Qm.transpose();
  block.in.L = 0.5;
  block.u = Vec3(n(rng), n(rng), n(rng)).normalized();
  block.in.b = -block.in.K * (f * block.in.L * patch.unitQ(Model::Exact, block.u));
  return block;
}

// The law by quadrature of Eq. (16) (tests/support/oracle.hpp), q = Q / Pz
// with mu = 1.
Vec3 lawByQuadrature(const FrictionPatch& patch, const Vec3& w) {
  return patchspin::testing::bruteForceQ(patch.shape(),
                                         patchspin::testing::linearField(patch.pressure()), 1.0,
                                         patch.rho(), w, 1e-12) /
         patch.Pz();
}

std::vector<FrictionPatch> gaugeTestPatches() {
  const PatchShape disk = PatchShape::disk(0.05);
  const PatchShape rect = PatchShape::rectangle(0.08, 0.04, Vec2(0.01, -0.005));
  return {FrictionPatch(disk, LinearPressure::fromLoads(disk, {10.0, 0.06, -0.04}), 0.5),
          FrictionPatch(rect, LinearPressure::fromLoads(rect, {10.0, 0.02, 0.03}), 0.5)};
}

// A gauge iteration started at the antipode -w of E's boundary point q(w)
// along lambda0 (a warm start kept from a visit whose lambda0 has since
// turned over) has the root q(-w) = -q(w) along -lambda0 at hand: the law is
// odd, and the iterate is taken at w at once. Asserted for blocks that stick
// (f < 1, beyond the quick octahedron test): the same decision and impulse
// as the cold start, the boundary point found at the first evaluation
// (iterations 0: without the rule, Newton stayed at the antipode for all
// kMaxIterations), and that point checked against quadrature: the gauge
// value is the law at the gauge slip (kQuadrature: the oracle's 1e-12 and
// the law's round-off), parallel to lambda0 (kParallelTol: the gauge's
// tolerance 1e-14 amplified by its 2x2 solve) and on its side.
TEST(ExactBlock, GaugeStartedAtTheAntipodeIsTheBoundaryPoint) {
  constexpr double kQuadrature = 1e-11, kParallelTol = 1e-10;
  // b + K impulse = 0 for a stick, to the round-off of the stick solve
  constexpr double kStickSolve = 1e-12;
  for (const FrictionPatch& patch : gaugeTestPatches()) {
    std::mt19937 rng(47);
    int located = 0;
    for (int trial = 0; trial < 40; ++trial) {
      const double f = std::uniform_real_distribution<double>(0.9, 0.999)(rng);
      const FrictionBlockInput in = boundaryBlock(patch, rng, f).in;
      const FrictionBlockResult cold = solveFrictionBlock(patch, Model::Exact, in);
      ASSERT_TRUE(cold.sticking) << f;
      if (cold.gaugeSlip.isZero(0.0)) continue;  // the octahedron held it
      ++located;
      FrictionBlockInput warm = in;
      warm.warmGauge = -cold.gaugeSlip;
      const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, warm);
      ASSERT_TRUE(r.sticking);
      EXPECT_EQ(r.iterations, 0);
      EXPECT_LT((in.b + in.K * r.impulse).norm(), kStickSolve * in.b.norm());
      EXPECT_EQ(r.impulse, cold.impulse);
      const Vec3 lambda0 = -in.K.inverse() * in.b;
      const Vec3 w = r.gaugeSlip, q = r.gaugeValue;
      ASSERT_NEAR(w.norm(), 1.0, 1e-15);
      EXPECT_LT((q - lawByQuadrature(patch, w)).norm(), kQuadrature * q.norm());
      EXPECT_LT(q.normalized().cross(lambda0.normalized()).norm(), kParallelTol);
      EXPECT_GT(q.dot(lambda0), 0.0);
    }
    EXPECT_GE(located, 20);
    // and blocks that slip (f > 1, by 0.1 to 1 %), started at the antipode
    // of their boundary point's slip u: the slip (without the rule the
    // trapped iteration left the decision to the candidates and the
    // 128-direction sphere, which missed the narrow cone h < 0 and stuck the
    // first of these blocks), its slip as from u itself to the tolerance
    // (kAgree of the slip scale, as WarmStartedSlipIsTheLawAtItsSlip), and
    // short of the gauge's cap of kMaxIterations = 100, which the trapped
    // iteration spent
    constexpr double kAgree = 2.0, kTol = 1e-14;
    for (int trial = 0; trial < 20; ++trial) {
      const double f = std::uniform_real_distribution<double>(1.001, 1.01)(rng);
      const BoundaryBlock block = boundaryBlock(patch, rng, f);
      FrictionBlockInput antipode = block.in, fromU = block.in;
      antipode.warmGauge = -block.u;
      fromU.warmGauge = block.u;
      const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, antipode),
                                expected = solveFrictionBlock(patch, Model::Exact, fromU);
      ASSERT_FALSE(r.sticking) << f;
      EXPECT_LT(r.iterations, 100);
      const double scale = block.in.b.norm() + block.in.L * block.in.K.norm();
      EXPECT_LT((r.slip - expected.slip).norm(), kAgree * kTol * scale);
    }
  }
}

// A gauge iterate w whose law value separates lambda0 from L E (h(w) =
// lambda0.w - L q(w).w < 0) proves the slip and starts the iteration on D
// there: the block then solves exactly as with w given as the warm-start
// slip (the same certificate and start, the candidates skipped). Asserted
// for blocks that slip (f > 1) and whose ellipsoidal solution proves
// nothing (checked here with the law): started from the gauge direction u
// (its h = (1 - f) L |q(u).u| < 0), the block takes the warm-started
// block's iterations and returns its impulse (without the rule the gauge
// converged first and the candidates chose the start: other iterations);
// the impulse is the law at the slip by quadrature (kQuadrature of |q|, the
// oracle's 1e-12 and the law's round-off, plus the iteration's own
// resolution: it stops at kIterationTol of the slip scale |b| + L |K|, which
// fixes the slip's direction to that over |s|, and the law's Jacobian is
// O(|q|) on these patches), and slip = b + K impulse.
TEST(ExactBlock, GaugeIterateThatSeparatesProvesTheSlip) {
  constexpr double kQuadrature = 1e-11, kIterationTol = 1e-14;
  for (const FrictionPatch& patch : gaugeTestPatches()) {
    std::mt19937 rng(53);
    int gaugeStarted = 0;
    for (int trial = 0; trial < 200 && gaugeStarted < 15; ++trial) {
      const double f = std::uniform_real_distribution<double>(1.001, 1.1)(rng);
      const BoundaryBlock block = boundaryBlock(patch, rng, f);
      const FrictionBlockInput& in = block.in;
      const Vec3 lambda0 = -in.K.inverse() * in.b;
      auto gap = [&](const Vec3& u) {
        return lambda0.dot(u) - in.L * patch.unitQ(Model::Exact, u).dot(u);
      };
      const Vec3 ellipsoidal = solveFrictionBlock(patch, Model::Ellipsoidal, in).slip;
      if (!ellipsoidal.isZero(0.0) && gap(ellipsoidal.normalized()) < 0.0) continue;
      // (scaled to a largest entry of 1: the gauge's start and the warm slip
      // are then the same unit vector to the bit)
      const Vec3 u = block.u / block.u.cwiseAbs().maxCoeff();
      ASSERT_LT(gap(u.normalized()), 0.0);
      ++gaugeStarted;
      FrictionBlockInput viaGauge = in, viaWarmSlip = in;
      viaGauge.warmGauge = u;
      viaWarmSlip.warmSlip = u;
      const FrictionBlockResult r = solveFrictionBlock(patch, Model::Exact, viaGauge);
      const FrictionBlockResult expected = solveFrictionBlock(patch, Model::Exact, viaWarmSlip);
      ASSERT_FALSE(r.sticking) << f;
      EXPECT_EQ(r.iterations, expected.iterations);
      EXPECT_EQ(r.impulse, expected.impulse);
      expectSlipIsBPlusKImpulse(in, r);
      const Vec3 q = lawByQuadrature(patch, r.slip);
      const double scale = in.b.norm() + in.L * in.K.norm();
      EXPECT_LT((r.impulse / in.L - q).norm(),
                (kQuadrature + kIterationTol * scale / r.slip.norm()) * q.norm())
          << f;
    }
    EXPECT_GE(gaugeStarted, 10);
  }
}

}  // namespace
}  // namespace patchspin
