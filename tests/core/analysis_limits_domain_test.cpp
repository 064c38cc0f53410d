// The limit-direction solver's domain in the body (sixth fuzz round, issue
// 6): a centre of mass far from O in radii of gyration makes the mass matrix
// (91) numerically singular. Fuzz finding, failing on e4caa91 (checked),
// and the control checked against the limit field itself (Eq. (98): a
// limit direction is a unit fixed point of the field's direction).
#include <patchspin/analysis.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace patchspin;

// 53. A 0.5 kg body with Jz = 0.5 kg m^2 (radius of gyration 1 m) whose
// centre of mass lies 1.35e8 m from O, mu = g = 2e-81: M = W^T diag(m, m,
// Jz) W has a unit-diagonal condition of ~4 (1 + m |r_c|^2 / Jz) = 7e16, its
// inverse no digits, and the directions returned were 1.5e-3 of the field
// off the fixed point. Now refused (more than 1e5 radii of gyration); a body
// with its centre of mass 1e3 radii away is solved, and its directions are
// fixed points of the field to kFixedPoint.
TEST(LimitsDomain, RefusesACentreOfMassFarBeyondTheRadiusOfGyration) {
  FlatBody far;
  far.shape = PatchShape::disk(0.5, Vec2(0.5, 0.5));
  far.mass = 0.5;
  far.Jz = 0.5;
  far.com = Vec3(-134742016.0, 2.0458501687594335e-81, 2.0546950501119882e-81);
  far.mu = 2.0546950501119882e-81;
  far.g = 2.0546950501119882e-81;
  far.force = Vec2(2.0546950501119882e-81, 1.0012491512498406e-312);
  const FlatBodyModel farModel(far, Model::Ellipsoidal);
  try {
    findLimitDirections(farModel, LimitOptions{});
    ADD_FAILURE() << "a centre of mass 1.35e8 radii of gyration from O was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mass matrix"), std::string::npos) << e.what();
  }

  FlatBody near = far;
  near.com = Vec3(-1e3, 0.0, 0.2);
  near.mu = 0.3;
  near.g = 9.81;
  near.force = Vec2(0.5, 0.0);
  const FlatBodyModel nearModel(near, Model::Ellipsoidal);
  const LimitAnalysis result = findLimitDirections(nearModel, LimitOptions{});
  ASSERT_FALSE(result.directions.empty());
  // the field's own scale: its largest value over the directions found and
  // the axes; kFixedPoint: M's condition here is ~4e6, so the field carries
  // ~4e6 eps relative error; 1e-6 leaves 1e3 of room (the fuzz target's slack)
  double scale = 0.0;
  for (const Vec3& w : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY()), Vec3(Vec3::UnitZ())})
    scale = std::max(scale, nearModel.limitField(w).norm());
  for (const LimitDirection& d : result.directions)
    scale = std::max(scale, nearModel.limitField(d.w).norm());
  constexpr double kFixedPoint = 1e-6;
  for (const LimitDirection& d : result.directions) {
    const Vec3 F = nearModel.limitField(d.w);
    EXPECT_NEAR(d.w.norm(), 1.0, 1e-12);
    EXPECT_LT((F - d.w.dot(F) * d.w).norm(), kFixedPoint * scale);
  }
}
