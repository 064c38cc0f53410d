// Seventh fuzz round (issue 6): regression tests for the classes decided in
// it (fuzz/README.md, "Seventh round"). Each was a fuzz finding and fails on
// cb5dd68 (checked); each is checked against an independent computation.
#include <patchspin/analysis.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
