// Seventh fuzz round (issue 6): regression tests for the classes decided in
// it (fuzz/README.md, "Seventh round"). Each was a fuzz finding and fails on
// cb5dd68 (checked); each is checked against an independent computation.
#include <patchspin/analysis.hpp>
#include <patchspin/friction_block.hpp>

#include <gtest/gtest.h>

#include "oracle.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace patchspin;

namespace {

// Largest |F_o| over the axes and the given directions: the field's own scale.
double fieldScaleOf(const FlatBodyModel& model, const std::vector<LimitDirection>& directions) {
  double scale = 0.0;
  for (const Vec3& w : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY()), Vec3(Vec3::UnitZ())})
    scale = std::max(scale, model.limitField(w).norm());
  for (const LimitDirection& d : directions) scale = std::max(scale, model.limitField(d.w).norm());
  return scale;
}

}  // namespace

// 55. (The exact polygon law far from O, refused in the seventh round
// because its Pz, from area moments summed about O, had no digits: since
// the eighth round the moments are summed about the vertex mean and those
// blocks are solved; tests/core/fuzz_round8_test.cpp, item 58.)

// 54. mu = 1.7e-279, g = 4.3e300, a centre of mass 1.7e266 m above O with a
// horizontal force of 0.5 N (fuzz/known_failures of the sixth round): the
// unit-scale normalisation took the external field's exponent from the force
// times the lever |r_c| / max|r| *including z_c* (2^884), although the
// external wrench Q_e = (P_x, P_y, T_z / rho) and M^-1 involve only x_c and
// y_c (z_c enters the pressure, as a tipping couple, not the field). The
// loads were scaled by 2^-883, the friction field came out ~1e-245, B B^T in
// Eq. (111) underflowed, and the direction returned was 1.4e-3 of the field
// off the fixed point. Now the field is solved at unit scale; every
// direction is a fixed point of the field evaluated at the body's own scale
// (limitField, Eq. (98): independent of the solver's scaling), with both
// solvers (the eigenproblem (111) and Newton on the sphere).
TEST(FuzzRound7, LimitsHighCentreOfMassWithTinyMuIsSolvedAtUnitScale) {
  FlatBody body;
  body.shape = PatchShape::disk(0.5, Vec2(0.5, 0.5));
  body.mass = 0.5;
  body.Jz = 57853952.0;
  body.Jxz = 0.5;
  body.Jyz = 0.5;
  body.com = Vec3(6.7815618489184211e-310, 2.2250738585072014e-308, 1.7108663708439404e+266);
  body.mu = 1.707867266264823e-279;
  body.g = 4.2576413334806225e+300;
  body.force = Vec2(0.5, 1.3202896917249277e-192);
  body.torque = Vec3(1.7078672649790534e-279, 9.2708718708331899e-313, 0.0);
  const FlatBodyModel model(body, Model::Ellipsoidal);
  // the fuzz target's slack: the polish reaches 1e-11 of the field
  // (kResidualTol; measured here 2.5e-17, M being diagonal to round-off with
  // x_c, y_c denormal); 1e-6 is the target's limit, far above both
  constexpr double kFixedPoint = 1e-6;
  for (bool sphere : {false, true}) {
    LimitOptions options;
    options.sphereSolver = sphere;
    const LimitAnalysis result = findLimitDirections(model, options);
    ASSERT_FALSE(result.directions.empty()) << (sphere ? "sphere solver" : "(111)");
    const double scale = fieldScaleOf(model, result.directions);
    for (const LimitDirection& d : result.directions) {
      const Vec3 F = model.limitField(d.w);
      EXPECT_NEAR(d.w.norm(), 1.0, 1e-12);
      EXPECT_LT((F - d.w.dot(F) * d.w).norm(), kFixedPoint * scale)
          << (sphere ? "sphere solver" : "(111)") << ", direction " << d.w.transpose();
    }
  }
}

// 56. The exact block of a patch far smaller than rho: a 1e-8 m disk 9,000
// diameters from O with rho = 0.5 (fuzz/known_failures of the sixth round:
// lever max|r| / rho = 1.8e-4, inside the domain, but diameter / rho =
// 4e-8), K well conditioned (unit-diagonal cond 5). The block spins about
// the disk's centre (ICR at its rim), where the law turns across a
// change of w_xy / w_z of diameter / rho: the iteration's stop at 1e-14 of
// the slip scale left the law at the returned slip 8e-5 of the set off the
// impulse (the impulse itself right to 1e-12). Now solved about the disk's
// centre (step.cpp, solveExactRecentred). Checked against the brute-force
// quadrature of Eq. (16) at the returned slip (tests/support/oracle.hpp,
// independent of the core's law): impulse = L q(s^) to kLaw of L (the fuzz
// target's law slack; measured 2e-8, the rounding of s = b + K impulse about
// O: eps |b| rho / (|s_z| R) ~ 4e-8), and s = b + K impulse.
TEST(FuzzRound7, ExactBlockOfATinyDiskFarFromOIsTheLawAtItsSlip) {
  const Vec2 centre(-3.7438506778344681e-05, -8.2157417227233455e-05);
  const double radius = 1e-8, rho = 0.5;
  const PatchShape shape = PatchShape::disk(radius, centre);
  const LinearPressure p =
      LinearPressure::fromLoads(shape, PatchLoads{1371.8459892853916, 0.11270929465102736, -0.051357058932178852});
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
  // slip = b + K impulse to the round-off of one 3x3 product
  constexpr double kSlip = 1e-14;
  EXPECT_LT((r.slip - input.b - input.K * r.impulse).norm(), kSlip * (input.b.norm() + input.K.norm() * r.impulse.norm()));
  // oracle: Q = -mu ∫ p k dA with mu = 1, so q = Q / Pz
  const Vec3 q = patchspin::testing::bruteForceQDisk(centre, radius, patchspin::testing::linearField(p), 1.0, rho, r.slip, 1e-12) / patch.Pz();
  constexpr double kLaw = 1e-6;
  EXPECT_LT((r.impulse - input.L * q).norm(), kLaw * input.L) << "q " << q.transpose() << ", impulse "
                                                               << r.impulse.transpose();
}
