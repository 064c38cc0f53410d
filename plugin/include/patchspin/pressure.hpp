// Normal pressure on a patch and the loads it carries, Eq. (2)-(3), (69), (94).
// Units: pressure [Pa = N/m^2], gradients [N/m^3], force [N], torque [N m].
#pragma once

#include <patchspin/geometry.hpp>

namespace patchspin {

// Normal load of a patch about O: Pz = ∫p dA (2), Tx = -∫y p dA, Ty = ∫x p dA (3).
struct PatchLoads {
  double Pz = 0.0;  // [N]
  double Tx = 0.0;  // [N m]
  double Ty = 0.0;  // [N m]
  Vec3 asVector() const { return Vec3(Pz, Tx, Ty); }
};

// Linear pressure p(x, y) = p0 + cx x + cy y, Eq. (69).
struct LinearPressure {
  double p0 = 0.0;  // [Pa]
  double cx = 0.0;  // [Pa/m]
  double cy = 0.0;  // [Pa/m]

  double at(const Vec2& point) const { return p0 + cx * point.x() + cy * point.y(); }
  Vec3 coefficients() const { return Vec3(p0, cx, cy); }

  // The linear pressure that carries `loads`, Eq. (94): solves
  // [Pz, Ty, -Tx] = G (p0, cx, cy). Throws Error on non-finite loads.
  static LinearPressure fromLoads(const PatchShape& shape, const PatchLoads& loads);
  // Uniform pressure p = Pz / A.
  static LinearPressure uniform(const PatchShape& shape, double Pz);
};

// Loads carried by a linear pressure (inverse of fromLoads).
PatchLoads loadsOf(const PatchShape& shape, const LinearPressure& pressure);

// Smallest pressure on the closed patch (at a vertex for polygons; at
// p(C) - R |grad p| for a disk of centre C and radius R). Throws Error if
// the pressure is not finite on the patch.
double minPressure(const PatchShape& shape, const LinearPressure& pressure);

// True if the linear pressure carrying `loads` is >= 0 everywhere on the patch
// (DESIGN item 2). `relTol` is relative to the mean pressure Pz / A.
bool isAdmissible(const PatchShape& shape, const PatchLoads& loads, double relTol = 1e-12);

// The admissible load nearest to `loads` in the metric
//   |(dPz, dTx / rho, dTy / rho)|,
// i.e. Euclidean once torques are divided by the patch length scale rho [m]
// (pass shape.defaultRho() when in doubt; Error for a rho more than 1e12
// times off Eq. (11) either way, or results that overflow). Loads with
// Pz <= 0 map to zero (the contact carries nothing). Admissible loads are
// returned unchanged.
PatchLoads nearestAdmissibleLoads(const PatchShape& shape, const PatchLoads& loads, double rho);

// The pressure averages of Eq. (36) for pressure p on the patch (Pz > 0):
struct PiMoments {
  double Pz = 0.0;     // ∫ p dA                     [N]
  double pi_x = 0.0;   // ∫ p x dA / Pz               [m]
  double pi_y = 0.0;   // ∫ p y dA / Pz               [m]
  double pi_x0 = 0.0;  // ∫ p x/r dA / Pz             [-]
  double pi_y0 = 0.0;  // ∫ p y/r dA / Pz             [-]
  double pi_xy = 0.0;  // ∫ p r dA / Pz               [m]
};

// Eq. (36) from the shape's moment table: a few dozen flops (DESIGN item 1).
// Throws Error if Pz <= 0.
PiMoments piMoments(const PatchShape& shape, const LinearPressure& pressure);

// Pi of Eq. (40) (without the factor -mu Pz):
//   Pi = [[1, 0, -pi_y0], [0, 1, pi_x0], [-pi_y/rho, pi_x/rho, pi_xy/rho]].
Mat3 ellipsoidalPi(const PiMoments& moments, double rho);

// Hertz (parabolic) pressure of Eq. (57) on a disk of radius R centred at C:
//   p = 3 Pz / (2 pi R^2) sqrt(1 - |P - C|^2 / R^2).
struct HertzPressure {
  double Pz = 0.0;  // [N]
};

// Eq. (36) for the Hertz pressure (57) on a disk (Error for polygons).
PiMoments piMomentsHertz(const PatchShape& disk, const HertzPressure& pressure);

}  // namespace patchspin
