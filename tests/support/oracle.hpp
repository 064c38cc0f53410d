// Brute-force oracles for the tests: nested adaptive Gauss-Kronrod quadrature
// of the friction integrals (16) and of the pressure moments (36), written
// independently of the core's exact model (no polar sums about the ICR, no
// elliptic integrals). Slow but simple; used to check the fast code.
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>

#include <functional>
#include <vector>

namespace patchspin::testing {

using ScalarField = std::function<double(const Vec2&)>;

// Work done by one oracle call (for timing and for detecting a capped run).
struct QuadratureReport {
  double errorEstimate = 0.0;  // sum of |K15 - G7| over all panels (outer level)
  long evaluations = 0;        // integrand evaluations, all levels
  bool capped = false;         // a panel budget was exhausted before relTol was met
};

// Unit friction kernel of Eq. (16) at patch point (x, y) for slip direction w:
//   v = (w1 - w3 y / rho, w2 + w3 x / rho)                              (1)
//   k = (v_x, v_y, (x v_y - y v_x) / rho) / |v|,     k = 0 where v = 0.
Vec3 frictionKernel(const Vec3& w, double rho, const Vec2& point);

// Instantaneous centre of rotation c = rho (-w2, w1) / w3; false if w3 = 0.
bool instantaneousCentre(const Vec3& w, double rho, Vec2& centre);

// Q = (Px, Py, Tz / rho) of Eq. (16)-(17):  Q = -mu ∫_A p(x,y) k(w; x,y) dA.
// Nested adaptive G7-K15 quadrature, split at the ICR so that the kernel's
// discontinuity lies on panel boundaries. Polygons: x outer (split at the
// vertices' x and c_x), y inner between the lower and upper chains (split at
// c_y). Disks: polar about the centre with radius s = R sin t (smooth also for
// the Hertz pressure's sqrt edge), angle outer (starting at the ICR's angle),
// t inner (split at the ICR). relTol is relative to ∫ |p k| dA; inner
// integrals stop at an absolute floor of 1e-3 relTol ∫|p k| dA / (outer
// width), so all of them together cost at most 1e-3 relTol.
// Measured (2 shared cores): 15-45 ms per call with the ICR inside the
// patch (~0.4 M kernel evaluations), < 1 ms with the ICR outside.
Vec3 bruteForceQ(const PatchShape& shape, const ScalarField& pressure, double mu, double rho,
                 const Vec3& w, double relTol = 1e-12, QuadratureReport* report = nullptr);

// ∫_A f dA by the same scheme, split at O = (0, 0) (where r, x/r, y/r of
// Eq. (11) and (36) are not smooth). relTol is relative to ∫ |f| dA.
double bruteForceIntegral(const PatchShape& shape, const ScalarField& f, double relTol = 1e-12,
                          QuadratureReport* report = nullptr);

// The same for a shape given by its parts (used before a PatchShape exists).
Vec3 bruteForceQPolygon(const std::vector<Vec2>& vertices, const ScalarField& pressure, double mu,
                        double rho, const Vec3& w, double relTol = 1e-12,
                        QuadratureReport* report = nullptr);
Vec3 bruteForceQDisk(const Vec2& centre, double radius, const ScalarField& pressure, double mu,
                     double rho, const Vec3& w, double relTol = 1e-12,
                     QuadratureReport* report = nullptr);
double bruteForceIntegralPolygon(const std::vector<Vec2>& vertices, const ScalarField& f,
                                 double relTol = 1e-12, QuadratureReport* report = nullptr);
double bruteForceIntegralDisk(const Vec2& centre, double radius, const ScalarField& f,
                              double relTol = 1e-12, QuadratureReport* report = nullptr);

// Line contact on the segment y = 0, x in [x0, x1], with uniform load density
// Pz / (x1 - x0): the delta -> 0 limit of (16) for a thin strip (Sect. 4.5.4),
//   Q = -mu (Pz / (x1 - x0)) ∫ k(w; x, 0) dx,
// one-dimensional adaptive quadrature split at the ICR's x.
Vec3 bruteForceLineQ(double x0, double x1, double Pz, double mu, double rho, const Vec3& w,
                     double relTol = 1e-12);

// Area moments, moment table and the averages (36) by brute force.
AreaMoments bruteForceAreaMoments(const PatchShape& shape, double relTol = 1e-13);
MomentTable bruteForceMomentTable(const PatchShape& shape, double relTol = 1e-13);
PiMoments bruteForcePiMoments(const PatchShape& shape, const ScalarField& pressure,
                              double relTol = 1e-13);

// Pressure fields as ScalarField.
ScalarField linearField(const LinearPressure& pressure);
// Hertz pressure (57) with total load Pz on a disk of radius R centred at C.
ScalarField hertzField(const Vec2& centre, double radius, double Pz);

// Mean distance from its centre of the rectangle [-a, a] x [-b, b] [m], by
// the midpoint rule on 2k x k cells, k = 400 (relative error ~1e-6: the
// integrand is smooth except at the centre): mu N times it is the twist a
// flat pad under uniform pressure holds, and it checks the closed form the
// scenes use (MultiBodyField.MeanDistanceOfRectangleMatchesQuadrature).
double rectangleMeanDistance(double a, double b);

}  // namespace patchspin::testing
