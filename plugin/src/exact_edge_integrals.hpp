// Closed-form edge integrals of the exact model, Eq. (16), over the signed
// triangle (c, edge) for linear pressure basis functions (DESIGN item 3).
// Internal to exact_polygon.cpp; templated on the scalar so that the same
// code gives values (double) and derivatives with respect to the ICR c
// (Dual2, forward mode with two partials).
#pragma once

#include <cmath>

namespace patchspin::internal {

// ---- forward-mode dual number with two partials (d/dc_x, d/dc_y) ----

struct Dual2 {
  double v = 0.0;  // value
  double d0 = 0.0;  // d value / d c_x
  double d1 = 0.0;  // d value / d c_y
  Dual2() = default;
  Dual2(double value) : v(value) {}  // NOLINT: implicit constant
  Dual2(double value, double g0, double g1) : v(value), d0(g0), d1(g1) {}
};

inline Dual2 operator+(const Dual2& a, const Dual2& b) { return {a.v + b.v, a.d0 + b.d0, a.d1 + b.d1}; }
inline Dual2 operator-(const Dual2& a, const Dual2& b) { return {a.v - b.v, a.d0 - b.d0, a.d1 - b.d1}; }
inline Dual2 operator-(const Dual2& a) { return {-a.v, -a.d0, -a.d1}; }
inline Dual2 operator*(const Dual2& a, const Dual2& b) {
  return {a.v * b.v, a.d0 * b.v + a.v * b.d0, a.d1 * b.v + a.v * b.d1};
}
inline Dual2 operator*(double s, const Dual2& a) { return {s * a.v, s * a.d0, s * a.d1}; }
inline Dual2 operator*(const Dual2& a, double s) { return {s * a.v, s * a.d0, s * a.d1}; }
inline Dual2 operator/(const Dual2& a, const Dual2& b) {
  const double q = a.v / b.v;
  return {q, (a.d0 - q * b.d0) / b.v, (a.d1 - q * b.d1) / b.v};
}
inline Dual2 operator/(const Dual2& a, double s) { return {a.v / s, a.d0 / s, a.d1 / s}; }
inline Dual2& operator+=(Dual2& a, const Dual2& b) { return a = a + b; }

inline double valueOf(double x) { return x; }
inline double valueOf(const Dual2& x) { return x.v; }

// chain rule helper: f(a) with f'(a) = slope
inline Dual2 applyChain(const Dual2& a, double f, double slope) {
  return {f, slope * a.d0, slope * a.d1};
}
// |r| is not differentiable at 0; there it only ever multiplies delta = 0
// (c on the edge's line), so any finite slope gives the right total.
inline Dual2 sqrt(const Dual2& a) {
  const double s = std::sqrt(a.v);
  return applyChain(a, s, s > 0.0 ? 0.5 / s : 0.0);
}
inline Dual2 log(const Dual2& a) { return applyChain(a, std::log(a.v), 1.0 / a.v); }
inline Dual2 log1p(const Dual2& a) { return applyChain(a, std::log1p(a.v), 1.0 / (1.0 + a.v)); }

// ---- J0 = asinh(tb / d) - asinh(ta / d), d = |delta| > 0, ta < tb ----
//
// Ra = sqrt(ta^2 + d^2), Rb = sqrt(tb^2 + d^2), L = tb - ta, J1 = Rb - Ra.
// asinh(t / d) = log((t + R) / d), so J0 = log of a ratio, written as
// log1p(positive / positive) without cancellation (one transcendental call):
//   ta >= 0:  J0 = log((tb + Rb) / (ta + Ra)) = log1p((L + J1) / (ta + Ra))
//   tb <= 0:  J0 = log((Ra - ta) / (Rb - tb)) = log1p((L - J1) / (Rb - tb))
//   ta < 0 < tb:  ta + Ra = d^2 / (Ra - ta), so J0 = log1p(N / d^2),
//     N = (tb + Rb)(Ra - ta) - d^2 = tb Ra - ta Rb - ta tb + (Ra Rb - d^2),
//     Ra Rb - d^2 = (ta^2 tb^2 + d^2 (ta^2 + tb^2)) / (Ra Rb + d^2),
//   every term >= 0; if N / d^2 overflows, J0 = log((tb + Rb)(Ra - ta)) - 2 log d.
template <class T>
T asinhDifference(const T& ta, const T& tb, const T& Ra, const T& Rb, const T& J1,
                  const T& delta, double L) {
  using std::log;
  using std::log1p;
  if (valueOf(ta) >= 0.0) return log1p((L + J1) / (ta + Ra));
  if (valueOf(tb) <= 0.0) return log1p((L - J1) / (Rb - tb));
  const T d2 = delta * delta;
  const T ta2 = ta * ta, tb2 = tb * tb, RaRb = Ra * Rb;
  const T N = tb * Ra - ta * Rb - ta * tb + (ta2 * tb2 + d2 * (ta2 + tb2)) / (RaRb + d2);
  if (valueOf(d2) > 0.0 && valueOf(N) < 1e290 * valueOf(d2)) return log1p(N / d2);
  const T d = valueOf(delta) > 0.0 ? delta : -delta;
  return log((tb + Rb) * (Ra - ta)) - 2.0 * log(d);
}

constexpr double kThird = 1.0 / 3.0;

// Per-edge accumulators: force (x, y) and torque times rho for the pressure
// basis (1, x, y) in the frame where c is given.
template <class T>
struct EdgeSums {
  T fx[3], fy[3], tz[3];
};

// ---- signed triangle (c, a, b), polar about c ----
//
// With P = c + s u, u = (cos al, sin al), v = w3/rho perp(P - c):
//   k = sgn(w3) (perp(u), (c.u + s) / rho)          (torque: P x perp(u) = P.u)
// and phi(P) = phi(c) + s q, q = grad(phi).u. The radial integral is
//   int_0^S phi k s ds = phi_c k0 S^2/2 + (phi_c k1 + q k0) S^3/3 + q k1 S^4/4,
//   k0 = sgn (perp(u), c.u/rho),  k1 = sgn (0, 0, 1/rho).
// Along the edge, r(tau) = e(t) - c = tau e + f with e the unit edge direction,
// n = perp(e), f = -delta n the foot vector, delta = cross(a - c, e), and
//   S = R = |r| = sqrt(tau^2 + delta^2),  d al = delta d tau / R^2,  u = r / R,
//   perp(r) = tau n + delta e,  c.r = tau ce - delta cn,  g.r = tau ge - delta gn
// (ce = c.e, cn = c.n, ge = g.e, gn = g.n, g = grad phi). The edge integral is
//   delta int [ phi_c/2 (perp(r), c.r/rho)/R + phi_c (0,0,R/rho)/3
//             + (g.r)(perp(r), c.r/rho)/(3R) + (g.r) R (0,0,1/rho)/4 ] d tau
// in terms of
//   J0 = int 1/R = asinh(tb/d) - asinh(ta/d)    J1 = int tau/R = Rb - Ra
//   J2 = int tau^2/R = (T - d^2 J0)/2           K0 = int R = (T + d^2 J0)/2
//   K1 = int tau R = (Rb^3 - Ra^3)/3,           T = tb Rb - ta Ra.
// Every J0 carries a factor delta (force) or delta^2 in the bracket, so at
// delta = 0 (c on the edge's line) the terms delta J0, delta^2 J0 are 0 with
// zero derivative; the rest of the bracket stays and gives the derivative of
// the sliver triangle's contribution.
// L = |b - a| > 0 and deltaZero are given by the caller.
template <class T>
void addSignedTriangle(double ax, double ay, double bx, double by, double L, const T& cx,
                       const T& cy, const T& Ra, const T& Rb, double deltaZero,
                       EdgeSums<T>& sums) {
  const double Lx = bx - ax, Ly = by - ay;
  const double invL = 1.0 / L;
  const double ex = Lx * invL, ey = Ly * invL;
  const double nx = -ey, ny = ex;
  const T rax = ax - cx, ray = ay - cy;
  const T ta = rax * ex + ray * ey;
  const T tb = ta + L;
  T delta = rax * ey - ray * ex;

  // J1 = Rb - Ra = L (ta + tb) / (Ra + Rb) without cancellation
  const T J1 = L * (ta + tb) / (Ra + Rb);

  // J0 terms; delta below deltaZero (rounding level) counts as c on the line
  T deltaJ0 = 0.0, delta2J0 = 0.0;
  if (std::abs(valueOf(delta)) > deltaZero) {
    deltaJ0 = delta * asinhDifference(ta, tb, Ra, Rb, J1, delta, L);
    delta2J0 = delta * deltaJ0;
  } else {
    delta = T(delta) - valueOf(delta);  // value 0, keep the derivative
  }
  // T = tb Rb - ta Ra = L Rb + ta J1 (all terms one sign when ta, tb are)
  const T Tq = (valueOf(ta) >= 0.0 || valueOf(tb) <= 0.0) ? L * Rb + ta * J1 : tb * Rb - ta * Ra;
  const T J2 = 0.5 * (Tq - delta2J0);
  const T K0 = 0.5 * (Tq + delta2J0);
  const T K1 = J1 * (Ra * Ra + Ra * Rb + Rb * Rb) * kThird;
  const T ce = cx * ex + cy * ey;
  const T cn = cx * nx + cy * ny;

  // basis phi = 1 (phi_c = 1, g = 0)
  //   F_xy = delta (n J1 + e delta J0) / 2
  //   Tz   = delta [ (ce J1 - cn delta J0) / 2 + K0 / 3 ]
  const T halfForceN = 0.5 * J1, halfForceE = 0.5 * deltaJ0;
  const T torque0 = 0.5 * (ce * J1 - cn * deltaJ0) + K0 * kThird;
  sums.fx[0] += delta * (halfForceN * nx + halfForceE * ex);
  sums.fy[0] += delta * (halfForceN * ny + halfForceE * ey);
  sums.tz[0] += delta * torque0;

  // basis phi = x, y (phi_c = c_x or c_y, g = unit x or y)
  //   F_xy = delta [ phi_c (n J1 + e delta J0)/2
  //                + (ge n J2 + delta (ge e - gn n) J1 - gn e delta^2 J0) / 3 ]
  //   Tz   = delta [ phi_c ((ce J1 - cn delta J0)/2 + K0/3)
  //                + (ge ce J2 - delta (ge cn + gn ce) J1 + gn cn delta^2 J0) / 3
  //                + (ge K1 - delta gn K0) / 4 ]
  const T deltaJ1 = delta * J1;
  for (int k = 1; k < 3; ++k) {
    const T& pc = k == 1 ? cx : cy;
    const double ge = k == 1 ? ex : ey;
    const double gn = k == 1 ? nx : ny;
    const T an = (pc * halfForceN) + (ge * J2 - gn * deltaJ1) * kThird;       // along n
    const T ae = (pc * halfForceE) + (ge * deltaJ1 - gn * delta2J0) * kThird;  // along e
    const T tq = pc * torque0 +
                 (ge * (ce * J2) - (ge * cn + gn * ce) * deltaJ1 + gn * (cn * delta2J0)) * kThird +
                 (ge * K1 - gn * (delta * K0)) * 0.25;
    sums.fx[k] += delta * (an * nx + ae * ex);
    sums.fy[k] += delta * (an * ny + ae * ey);
    sums.tz[k] += delta * tq;
  }
}

}  // namespace patchspin::internal
