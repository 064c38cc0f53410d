// The exact law's basis F (and dF/dw) on a region whose ICR is far (or at
// infinity) from Green's theorem: one boundary integral instead of an area
// rule (exact_arc_region.cpp's far branch). Internal to exact_arc_region.cpp.
//
// Complex notation in the frame about g: z = x + i y, omega = w'1 + i w'2,
// beta = w'3 / rho. Eq. (1): v = omega + i beta z = omega (1 - lambda z),
// lambda = -i beta / omega (|lambda z| <= 1 / kappa < 1: the ICR is
// z = 1 / lambda). With h = (1 - lambda z)^(1/2) (principal; Re > 0) and
// conj(h) = (1 - conj(lambda) conj(z))^(1/2), |1 - lambda z| = h conj(h), so
//   u = v/|v| = om (h / conj(h)),          om = omega / |omega|
//   1/|v|     = (1/|omega|) h^-1 conj(h)^-1
//   u^2/|v|   = (om^2/|omega|) h conj(h)^-3,
// each a holomorphic times an antiholomorphic function. For f(z) g(conj z),
// Green's theorem (∫_A dPhi/d conj(z) dA = (1/2i) ∮ Phi dz) gives
//   ∫_A z^a zb^b f(z) g(zb) dA = (1/2i) ∮ z^a f(z) zb^(b+1) G_b(lambdab zb) dz,
// zb = conj(z), with G_b(tau) = ∫_0^1 s^b g-shape(tau s) ds; for the three
// kernels (sigma = sqrt(1 - tau) = conj(h), q = 1/(1 + sigma); from
// tau = (1 - sigma)(1 + sigma), free of the cancellation of the 1/tau forms):
//   J_b = ∫ s^b (1 - tau s)^(-1/2):  J0 = 2q,  J1 = (2/3)(2 + sigma) q^2,
//         J2 = (2/15)(3 sigma^2 + 9 sigma + 8) q^3
//   M_a = ∫ s^a (1 - tau s)^(1/2):   M0 = (2/3)(1 + sigma + sigma^2) q,
//         M1 = (2/15)(3 sigma^3 + 6 sigma^2 + 4 sigma + 2) q^2
// (for conj(u^2/|v|) the antiholomorphic factor is conj(h), so M_a).
// The integrals needed (I: the kernel h/conj(h); K1: 1/(h conj h); K2c:
// conj of ∫ z^a zb^b h conj(h)^-3, i.e. ∫ z^b h^-3 zb^a conj(h)):
//   I(a, b)   for (0,0) (1,0) (0,1) (1,1) (0,2)            F
//   K1(a, b)  for (0,0) (1,0) (1,1) (2,0) (2,1)            dF (K1 is real-kernelled)
//   K2c(a, b) for a = 0: b = 0..3; a = 1: b = 0..2          dF
// The boundary integrand is analytic near the boundary (the only
// singularity is the ICR), so Gauss-Legendre converges on each piece as the
// area rule did in its radial direction. At lambda = 0 (translation) every
// G_b is 1/(b+1) and the integrals are the area moments.
//
// Assembly (phi = 1, x = (z + zb)/2, y = (z - zb)/(2i)):
//   force_phi = om ∫ phi h/conj(h),  torque_phi = Im(om ∫ phi zb h/conj(h)) / rho
// and, m = (perp u, (P.u)/rho), dF[phi] = ∫ phi m m^T / |v|:
//   m0^2 = (1 - Re u^2)/2, m1^2 = (1 + Re u^2)/2, m0 m1 = -Im(u^2)/2,
//   (m0 + i m1) m2 = i (zb u^2 + z) / (2 rho),  m2^2 = (Re(zb^2 u^2) + |z|^2)/(2 rho^2).
// Guarded by exact_arc_region_test.cpp (FarBranchMatchesOracleAcrossKappa).
#pragma once

#include <patchspin/internal/exact.hpp>

#include <array>
#include <cmath>

namespace patchspin::internal {

// Minimal complex arithmetic (std::complex's multiplication checks for NaN
// and its division calls a library routine on every use).
struct Cx {
  double re = 0.0, im = 0.0;
};
inline Cx operator+(Cx a, Cx b) {
  return {a.re + b.re, a.im + b.im};
}
inline Cx operator*(Cx a, Cx b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
inline Cx operator*(double s, Cx a) {
  return {s * a.re, s * a.im};
}
inline Cx& operator+=(Cx& a, Cx b) {
  return a = a + b;
}
inline Cx conj(Cx a) {
  return {a.re, -a.im};
}

// The boundary sums of the far rule.
struct FarGreenSums {
  std::array<Cx, 5> I{};    // (0,0) (1,0) (0,1) (1,1) (0,2)
  std::array<Cx, 5> K1{};   // (0,0) (1,0) (1,1) (2,0) (2,1)
  std::array<Cx, 7> K2c{};  // a = 0: b = 0..3, a = 1: b = 0..2
};

// One boundary node z (g-frame) with W = weight * dz/dparam / (2i).
template <bool kJacobian>
inline void addFarGreenNode(Cx z, Cx W, Cx lambda, FarGreenSums& s) {
  const Cx zb = conj(z);
  // h = sqrt(1 - lambda z), Re(1 - lambda z) >= 1 - 1/kappa > 0
  const Cx t = lambda * z;
  const double wr = 1.0 - t.re, wi = -t.im;
  const double wAbs = std::sqrt(wr * wr + wi * wi);  // |1 - lambda z| = |h|^2
  const double hr = std::sqrt(0.5 * (wAbs + wr));
  const Cx h{hr, 0.5 * wi / hr};
  const Cx sig = conj(h);
  const double pr = 1.0 + sig.re, pi = sig.im;
  const double pInv = 1.0 / (pr * pr + pi * pi);
  const Cx q{pr * pInv, -pi * pInv};  // 1 / (1 + sigma)
  const Cx q2 = q * q;
  const Cx sig2 = sig * sig;
  const Cx J0 = 2.0 * q;
  const Cx J1 = (2.0 / 3.0) * (Cx{2.0 + sig.re, sig.im} * q2);
  const Cx J2 = (2.0 / 15.0) *
                (Cx{3.0 * sig2.re + 9.0 * sig.re + 8.0, 3.0 * sig2.im + 9.0 * sig.im} * (q2 * q));
  const Cx Wzb = W * zb;
  const Cx e = Wzb * h, eZb = e * zb;
  const Cx eJ0 = e * J0, eJ1 = eZb * J1;
  s.I[0] += eJ0;
  s.I[1] += z * eJ0;
  s.I[2] += eJ1;
  s.I[3] += z * eJ1;
  s.I[4] += (eZb * zb) * J2;
  if constexpr (kJacobian) {
    // h^-1 = sigma / |h|^2, h^-3 = sigma^3 / |h|^6
    const double inv = 1.0 / wAbs, inv3 = inv * inv * inv;
    const Cx z2 = z * z;
    const Cx f = inv * (Wzb * sig);
    const Cx fJ0 = f * J0, fJ1 = (f * zb) * J1;
    s.K1[0] += fJ0;
    s.K1[1] += z * fJ0;
    s.K1[2] += z * fJ1;
    s.K1[3] += z2 * fJ0;
    s.K1[4] += z2 * fJ1;
    const Cx sig3 = sig2 * sig;
    const Cx M0 = (2.0 / 3.0) * (Cx{1.0 + sig.re + sig2.re, sig.im + sig2.im} * q);
    const Cx M1 = (2.0 / 15.0) * (Cx{3.0 * sig3.re + 6.0 * sig2.re + 4.0 * sig.re + 2.0,
                                     3.0 * sig3.im + 6.0 * sig2.im + 4.0 * sig.im} *
                                  q2);
    const Cx p = inv3 * (Wzb * sig3);
    const Cx pM0 = p * M0, pM1 = (p * zb) * M1;
    s.K2c[0] += pM0;
    s.K2c[1] += z * pM0;
    s.K2c[2] += z2 * pM0;
    s.K2c[3] += (z2 * z) * pM0;
    s.K2c[4] += pM1;
    s.K2c[5] += z * pM1;
    s.K2c[6] += z2 * pM1;
  }
}

// F' and dF' (g-frame) from the sums; w' = (omega, beta rho) with omega != 0.
inline void farGreenBasis(const FarGreenSums& s, const Vec3& wl, double rho, bool wantJacobian,
                          ExactBasis& out) {
  const double omAbs = std::hypot(wl.x(), wl.y());
  const Cx om{wl.x() / omAbs, wl.y() / omAbs};
  const double invRho = 1.0 / rho;
  // ∫ phi X for phi = 1, x, y from ∫ X, ∫ z X, ∫ zb X
  auto phiSplit = [](Cx one, Cx withZ, Cx withZb) -> std::array<Cx, 3> {
    return {one, 0.5 * (withZ + withZb),
            Cx{0.5 * (withZ.im - withZb.im), -0.5 * (withZ.re - withZb.re)}};
  };
  const std::array<Cx, 3> force = phiSplit(s.I[0], s.I[1], s.I[2]);
  const std::array<Cx, 3> lever = phiSplit(s.I[2], s.I[3], s.I[4]);  // ∫ phi zb h/conj(h)
  for (int k = 0; k < 3; ++k) {
    const Cx f = om * force[k], l = om * lever[k];
    out.F.col(k) = Vec3(f.re, f.im, l.im * invRho);
  }
  if (!wantJacobian) return;
  auto c = [](Cx a) { return conj(a); };
  // K1 family (real kernel): ∫ zb X = conj(∫ z X), ∫ z zb^2 X = conj(∫ z^2 zb X)
  const std::array<Cx, 3> A = phiSplit(s.K1[0], s.K1[1], c(s.K1[1]));
  const std::array<Cx, 3> D = phiSplit(s.K1[1], s.K1[3], s.K1[2]);
  const std::array<Cx, 3> G = phiSplit(s.K1[2], s.K1[4], c(s.K1[4]));
  // K2(a, b) = conj(K2c(a, b))
  auto K2 = [&](int a, int b) { return c(s.K2c[a == 0 ? b : 4 + b]); };
  const std::array<Cx, 3> B = phiSplit(K2(0, 0), K2(1, 0), K2(0, 1));
  const std::array<Cx, 3> C = phiSplit(K2(0, 1), K2(1, 1), K2(0, 2));
  const std::array<Cx, 3> E = phiSplit(K2(0, 2), K2(1, 2), K2(0, 3));
  const double invOm = 1.0 / omAbs;
  const Cx om2 = invOm * (om * om);
  for (int k = 0; k < 3; ++k) {
    const double a = invOm * A[k].re, g = invOm * G[k].re;
    const Cx b = om2 * B[k], e = om2 * E[k];
    const Cx cd = om2 * C[k] + invOm * D[k];  // ∫ phi (zb u^2 + z) / |v|
    Mat3& d = out.dF[k];
    d(0, 0) = 0.5 * (a - b.re);
    d(1, 1) = 0.5 * (a + b.re);
    d(0, 1) = d(1, 0) = -0.5 * b.im;
    d(0, 2) = d(2, 0) = -0.5 * invRho * cd.im;
    d(1, 2) = d(2, 1) = 0.5 * invRho * cd.re;
    d(2, 2) = 0.5 * invRho * invRho * (e.re + g);
  }
}

}  // namespace patchspin::internal
