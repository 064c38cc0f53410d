// The thick disk of issue 34 and its fast dynamics, derived here from
// Newton-Euler independently of the library, with the exact law (16) by
// brute-force quadrature (tests/support/oracle.hpp): the oracle of
// limit_cycles_test.cpp and cycle_bifurcation_test.cpp.
//
// Thick disk of issue 34: R = 1 m, centre of mass at (0, 0, h), h = 0.4 m,
// m = 1 kg, Jz = 0.5 kg m^2, mu = 0.5, g = 9.81, force F along x, rho =
// 2R/3 given explicitly (so nothing here depends on Eq. (11)). At r -> 0
// (omega -> 0, psi frozen), with Q = (P_x, P_y, T_z / rho) = -mu ∫ p k dA:
//   C moves with O (it lies on O's vertical):  m u' = (P_x + F, P_y)
//   spin about the vertical through O and C:   (rho omega)' = rho^2 Q3 / Jz
//   no rotation about x, y: moments about C of the pressure and of the
//   friction at depth h cancel, ∫ x p = -h P_x, ∫ y p = -h P_y; with p =
//   p0 + cx x + cy y on the disk: p0 = m g / (pi R^2), (cx, cy) = -a (P_x,
//   P_y), a = 4 h / (pi R^4) (a body sliding along +x presses its front).
// Q is linear in (p0, cx, cy): Q = mu (p0 K1 + cx Kx + cy Ky), Kf = -∫ f k
// dA; the 2x2 system (I + mu a [Kx Ky]) (P_x, P_y) = mu p0 K1 gives P.
// Then F_o = ((Q1 + F) / m, Q2 / m, rho^2 Q3 / Jz), w' = F_o - (w.F_o) w,
// (ln r)' = w.F_o, Eq. (27), (103)-(104).
#pragma once

#include <cmath>
#include <oracle.hpp>
#include <patchspin/analysis.hpp>

namespace patchspin::thick_disk {

constexpr double kR = 1.0, kH = 0.4, kMass = 1.0, kJz = 0.5, kMu = 0.5, kG = 9.81;
constexpr double kRho = 2.0 * kR / 3.0;

inline FlatBody thickDisk(double F) {
  FlatBody body;
  body.shape = PatchShape::disk(kR);
  body.mass = kMass;
  body.Jz = kJz;
  body.com = Vec3(0.0, 0.0, kH);
  body.mu = kMu;
  body.g = kG;
  body.force = Vec2(F, 0.0);
  body.rho = kRho;
  return body;
}

// F_o(w) of the thick disk by brute-force quadrature (derivation above).
// relTol 1e-6 of the quadrature (the default): F_o to ~1e-6 relative, which moves the
// cycle by ~1e-6 (it attracts at rates ~1 m/s^2 against |F_o| ~ 5 m/s^2),
// far below the tolerances of the tests that use it.
inline Vec3 oracleField(const Vec3& w, double F, double quadTol = 1e-6) {
  const Vec2 centre = Vec2::Zero();
  const Vec3 K1 = testing::bruteForceQDisk(
      centre, kR, [](const Vec2&) { return 1.0; }, 1.0, kRho, w, quadTol);
  const Vec3 Kx = testing::bruteForceQDisk(
      centre, kR, [](const Vec2& p) { return p.x(); }, 1.0, kRho, w, quadTol);
  const Vec3 Ky = testing::bruteForceQDisk(
      centre, kR, [](const Vec2& p) { return p.y(); }, 1.0, kRho, w, quadTol);
  const double p0 = kMass * kG / (M_PI * kR * kR);
  const double a = 4.0 * kH / (M_PI * std::pow(kR, 4));
  Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
  A.col(0) += kMu * a * Kx.head<2>();
  A.col(1) += kMu * a * Ky.head<2>();
  const Vec2 P = A.lu().solve(kMu * p0 * K1.head<2>());
  const Vec3 Q = kMu * (p0 * K1 - a * P.x() * Kx - a * P.y() * Ky);
  return Vec3((Q.x() + F) / kMass, Q.y() / kMass, kRho * kRho * Q.z() / kJz);
}

// V* = F_o - (w . F_o) w of the oracle at the unit vector along w.
inline Vec3 oracleV(const Vec3& w, double F, double quadTol = 1e-6) {
  const Vec3 x = w.normalized();
  const Vec3 f = oracleField(x, F, quadTol);
  return f - x.dot(f) * x;
}

}  // namespace patchspin::thick_disk
