// The paper's reference formulas (Sect. 4.5) as functions, each re-derived and
// checked numerically in tests/core/closed_forms_test.cpp. Where the paper
// misprints, the function implements the verified formula and says so.
#pragma once

#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>

namespace patchspin::testing {

// Complete elliptic integrals in the PARAMETER m = k^2 used by the paper
// (Abramowitz-Stegun 17.2): K(m) = std::comp_ellint_1(sqrt(m)), likewise E.
// The standard library takes the MODULUS k.
double ellipticK(double m);
double ellipticE(double m);

// Slip ratio of a disk, Eq. (50): eps = |u| / (R |omega_z|) = (rho / R) |w_xy| / |w3|.
// +infinity for w3 = 0.
double diskSlipRatio(const Vec3& w, double R, double rho);

// Uniform pressure on a disk centred at O, Eq. (52)-(53) (Weidman-Malhotra):
// dimensionless force P_eps and torque T_eps of Eq. (46), (51).
double uniformDiskForce(double eps);
double uniformDiskTorque(double eps);

// Hertz pressure (57) on a disk centred at O, Eq. (58)-(59) (Leine-Glocker).
double hertzDiskForce(double eps);
double hertzDiskTorque(double eps);
// pi_xy of Eq. (48) for the two pressures: 2R/3 (uniform), 3 pi R / 16 (Hertz;
// the paper's "3 pi r / 16" below (57) means the disk radius R).
double uniformDiskPiXY(double R);
double hertzDiskPiXY(double R);

// Q = (Px, Py, Tz / rho) of a disk centred at O from the dimensionless
// functions, Eq. (46): P = -mu Pz P_eps(eps) w_xy / |w_xy|,
// Tz = -mu Pz pi_xy sign(w3) T_eps(eps). (The paper's (51) drops sign(w3).)
Vec3 uniformDiskQ(double R, double mu, double Pz, double rho, const Vec3& w);
Vec3 hertzDiskQ(double R, double mu, double Pz, double rho, const Vec3& w);

// Thin strip (line contact) of length L along x centred at O, uniform load,
// rho = L/4 (64), slip w = (cos theta cos phi, cos theta sin phi, sin theta),
// gamma = 2 tan theta, theta in [0, pi/2). Eq. (62) phi = 0 and (63) phi = pi/2:
//   |(Px, Py)| = mu Pz P,   |Tz| = mu Pz (L/4) T                          (61)
double thinStripForceAlong(double gamma);    // (62): asinh(g)/g
double thinStripTorqueAlong(double gamma);   // (62): sqrt(1 + 1/g^2) - asinh(g)/g^2
double thinStripForceAcross(double gamma);   // (63): 1 or 1/g
double thinStripTorqueAcross(double gamma);  // (63): 0 or 1 - 1/g^2
// The corresponding Q (signs from (16)): phi = 0 gives Q = -mu Pz (P, 0, T),
// phi = pi/2 gives Q = -mu Pz (0, P, T).
Vec3 thinStripQAlong(double mu, double Pz, double theta);
Vec3 thinStripQAcross(double mu, double Pz, double theta);

// Reduction of the slip state to a new reference point O' = O + d (same axes,
// same rho), Eq. (66) generalised:  w' = W w,  Q = W^T Q',
//   W = [[1, 0, -dy/rho], [0, 1, dx/rho], [0, 0, 1]].
Mat3 referencePointMap(const Vec2& d, double rho);

// Pi' of the thin strip (line limit, uniform load, rho = L/4) about the point
// O' = (a L, 0), |a| <= 1/2:  x' in [(-1/2 - a) L, (1/2 - a) L] and
//   pi_x = -a L, pi_x0 = -2a, pi_xy = (1/4 + a^2) L, pi_y = pi_y0 = 0, so
//   Pi' = [[1, 0, 0], [0, 1, -2a], [0, -4a, 1 + 4a^2]].     (68) for a = 1/8
Mat3 thinStripPi(double a);

// Disk of radius R centred at O, p = p0 + cx x + cy y, Eq. (72) and, with
// rho = 2R/3 (47), Eq. (73).
PiMoments linearDiskPiMoments(double R, double p0, double cx, double cy);
Mat3 linearDiskPi(double R, double p0, double cx, double cy);

}  // namespace patchspin::testing
