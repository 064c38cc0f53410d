// Boundary moments about the ICR c of a region bounded by segments and
// circular arcs, from which the exact model, Eq. (16), follows in closed form
// (exact_arc_region.cpp). Internal to exact_arc_region.cpp.
//
// With r = P - c, rho_c = |r| and the outward normal n, summed over the
// boundary pieces (the region's boundary is closed, counter-clockwise):
//   N1 = ∮ rho_c n ds,   M = ∮ rho_c r n^T ds,   N3 = ∮ rho_c^3 n ds.
//
// Segment a -> b: e = (b - a)/L, n = (e_y, -e_x), r = tau e + delta n with
// delta = (a - c).n, tau in [ta, tb], R = sqrt(tau^2 + delta^2):
//   N1 = n K0,  M = (e K1 + delta n K0) n^T,  N3 = n K3,
//   K0 = ∫R = (T + delta^2 J0)/2, K1 = ∫tau R = (Rb^3 - Ra^3)/3,
//   K3 = ∫R^3 = [tau R^3]/4 + 3 delta^2 K0/4   (d(tau R^3) = 4R^3 - 3 delta^2 R),
// with T, J0 as in exact_edge_integrals.hpp.
//
// Arc x = o + a e(t), t in [t1, t2], n = e(t), ds = a dt, d = o - c = D e(t0),
// theta = t - t0: rho_c^2 = A + B cos(theta), A = D^2 + a^2, B = 2 a D, and
//   ∫rho e dt = Rot(t0) (C1, S1),  ∫rho e e^T dt = Rot [[C2, SC], [SC, L1 - C2]] Rot^T,
//   ∫rho^3 e dt = Rot (C3, S3);  N1 = a ∫rho e,  M = a d ∫rho e^T + a^2 ∫rho e e^T,
//   N3 = a ∫rho^3 e,
// where L1, C1, C2, C3 = ∫ rho {1, cos, cos^2}, ∫ rho^3 cos (d theta) and
// S1, SC, S3 = ∫ rho {sin, sin cos}, ∫ rho^3 sin.
//  * odd in sin (u = cos theta, x = rho(t2), y = rho(t1), no division by B):
//      S1 = -(2/3) (u2 - u1) (x^2 + x y + y^2) / (x + y)
//      S3 = -(2/5) (u2 - u1) (x^4 + x^3 y + x^2 y^2 + x y^3 + y^4) / (x + y)
//      SC = 2 (u1 - u2) [u1 (2x^3 + 4x^2 y + 6x y^2 + 3y^3)
//                        + u2 (3x^3 + 6x^2 y + 4x y^2 + 2y^3)] / (15 (x + y)^2)
//  * even: phi = theta/2, s = sin^2 phi, rho = (D + a) Delta, Delta = sqrt(1 - m s),
//    m = 4aD/(D + a)^2, 1 - m = ((D - a)/(D + a))^2, W_j = ∫ s^j Delta d phi:
//      L1 = 2(D+a) W0,  C1 = 2(D+a)(W0 - 2W1),  C2 = 2(D+a)(W0 - 4W1 + 4W2),
//      C3 = 2(D+a)^3 (V0 - 2V1),  V_j = ∫ s^j Delta^3 = W_j - m W_{j+1}.
//    Closed form (F, E incomplete elliptic integrals of the first and second
//    kind at amplitude phi, parameter m: Carlson's R_F, R_D from 1 - m
//    (elliptic.hpp; std::ellint_1's k = sqrt(m) rounds to 1 within 1e-8 of
//    the circle, and dF lost 1e-8 there; std::ellint_2 cost 220 ns a call);
//    Y_n = [sin^(2n-1) phi cos phi Delta]):
//      W0 = E,  W1 = [(1-m) F - (1-2m) E - m Y1] / (3m),
//      W2 = [2(1-m)(2m+1) F + (8m^2 - 3m - 2) E + m(1 - 4m) Y1 - 3m^2 Y2] / (15 m^2),
//    from d/dphi(sin^(2n-1) cos Delta) = [(2n-1) s^(n-1) - 2n(1+m) s^n
//    + (2n+1) m s^(n+1)] / Delta. F always carries 1 - m (c on the circle: F
//    diverges where Delta = 0, the product -> 0). For m <= kSeriesM (c near
//    the centre or far from the circle) the 1/m^2 would cancel: the binomial
//    series Delta = sum b_k (m s)^k, W_j = sum b_k m^k Q_(j+k),
//    Q_n = ∫ s^n d phi = -[sin^(2n-1) cos]/(2n) + (2n-1)/(2n) Q_(n-1).
//
// Their derivatives in c (for dF/dw) need two more moments with bounded
// integrands, u = r / rho_c:
//   Q = ∮ u n^T ds,   U[k] = ∮ (r r^T / rho_c) n_k ds,
// since d rho_c / dc = -u: dN1/dc_j = -Q(j, :), dM/dc_j = -U[.](., j) - e_j N1^T,
// dN3/dc_j = -3 M(j, :). Segment: Q = (e J1 + delta n J0) n^T,
// U[k] = (J2 e e^T + delta J1 (e n^T + n e^T) + delta^2 J0 n n^T) n_k.
// Arc (local frame, r = (D + a cos, a sin), e = (cos, sin)): integrals
// c_k = ∫ cos^k / rho and o_k = ∫ sin cos^k / rho (d theta):
//   o_k = -∫ u^k (A + Bu)^(-1/2) du:  o0 = -2 (u2 - u1)/(x + y),
//     o1 = 2 (u1 - u2)(2u1 x + u1 y + u2 x + 2u2 y) / (3 (x + y)^2),
//     o2 = 2 (u1 - u2)(8u1^2 x^2 + 9u1^2 xy + 3u1^2 y^2 + 4u1u2 x^2 + 12u1u2 xy
//          + 4u1u2 y^2 + 3u2^2 x^2 + 9u2^2 xy + 8u2^2 y^2) / (15 (x + y)^3)  (sympy);
//   c_k = 2/(D + a) ∫ (1 - 2s)^k / Delta d phi from I_n = ∫ s^n / Delta:
//     I0 = F, I1 = (F - E)/m, (2n+1) m I_(n+1) = Y_n - (2n-1) I_(n-1) + 2n (1+m) I_n,
//   or the series 1/Delta = sum c_k (m s)^k, c_k = c_(k-1) (k - 1/2)/k, for m <= kSeriesM.
// F's coefficient is tracked apart: the integrands are bounded, so it is
// (1 - m) times a bounded factor and dropped where m = 1 (F infinite).
// Guarded by exact_arc_region_test.cpp (the law's and the Jacobian's tests).
#pragma once

#include "elliptic.hpp"
#include "exact_edge_integrals.hpp"

#include <patchspin/types.hpp>

#include <cmath>

namespace patchspin::internal {

struct BoundaryMoments {
  Vec2 N1 = Vec2::Zero();
  Mat2 M = Mat2::Zero();
  Vec2 N3 = Vec2::Zero();
  // for the derivative in c only (withGradient)
  Mat2 Q = Mat2::Zero();
  Mat2 U[2] = {Mat2::Zero(), Mat2::Zero()};
};

// The segment a -> b (any length), c the ICR; deltaZero: |delta| below it is
// rounding (c on the segment's line).
inline void addSegmentMoments(const Vec2& a, const Vec2& b, const Vec2& c, double deltaZero,
                              bool withGradient, BoundaryMoments& acc) {
  const double L = (b - a).norm();
  if (!(L > 0.0)) return;
  const Vec2 e = (b - a) / L;
  const Vec2 n(e.y(), -e.x());
  const Vec2 ra = a - c;
  const double ta = ra.dot(e), tb = ta + L;
  const double Ra = ra.norm(), Rb = (b - c).norm();
  const EdgeIntegrals ei = edgeIntegrals(ta, L, Ra, Rb, ra.dot(n), deltaZero);
  const double delta = ei.delta, J1 = ei.J1, deltaJ0 = ei.deltaJ0, delta2J0 = ei.delta2J0,
               K0 = ei.K0, K1 = ei.K1;
  const double K3 = 0.25 * (tb * Rb * Rb * Rb - ta * Ra * Ra * Ra) + 0.75 * delta * delta * K0;
  acc.N1 += K0 * n;
  acc.M += (K1 * e + (delta * K0) * n) * n.transpose();
  acc.N3 += K3 * n;
  if (!withGradient) return;
  const double J2 = ei.J2;
  acc.Q += (J1 * e + deltaJ0 * n) * n.transpose();
  const Mat2 en = e * n.transpose();
  const Mat2 rr =
      J2 * e * e.transpose() + (delta * J1) * (en + en.transpose()) + delta2J0 * n * n.transpose();
  acc.U[0] += n.x() * rr;
  acc.U[1] += n.y() * rr;
}

namespace arc_detail {

// m below this: the series (<= 17 terms for 1e-17); above, the closed form
// loses about 1/m^2 (100 at the switch) to cancellation.
constexpr double kSeriesM = 0.1;

struct W3 {
  double w0 = 0.0, w1 = 0.0, w2 = 0.0;
};

// E(phi | 1) = 2n + sin(phi - n pi), n = round(phi / pi) (m = 1: Delta = |cos|).
inline double ellE(double phi) {
  const double n = std::nearbyint(phi / M_PI);
  return 2.0 * n + std::sin(phi - n * M_PI);
}

// The arc's ends in phi: amplitude p, sin y, cos c, Delta dl.
struct Ends {
  double p1, y1, c1, dl1, p2, y2, c2, dl2;
};

// What the closed forms share: E, F over [p1, p2] (haveF false at m = 1,
// where F may be infinite) and the boundary terms Y1, Y2.
struct Elliptic {
  double E = 0.0, F = 0.0, Y1 = 0.0, Y2 = 0.0;
  bool haveF = false;
};

// Q_n = ∫ sin^(2n) phi, n = 0..count-1, by the recurrence (file comment).
inline void sinePowerIntegrals(const Ends& e, int count, double* Q) {
  double s1p = e.y1, s2p = e.y2;  // sin^(2n-1) at n = 1
  const double s1 = e.y1 * e.y1, s2 = e.y2 * e.y2;
  Q[0] = e.p2 - e.p1;
  for (int n = 1; n < count; ++n) {
    Q[n] = -(s2p * e.c2 - s1p * e.c1) / (2.0 * n) + (2.0 * n - 1.0) / (2.0 * n) * Q[n - 1];
    s1p *= s1, s2p *= s2;
  }
}

// Terms of the series in m stop below this (coefficients <= 1, |Q_n| <= |dphi|).
constexpr double kSeriesStop = 1e-18;
constexpr int kSeriesTerms = 40;  // m <= 0.1 needs <= 18

// W_j over [p1, p2] (see the file comment); fills ell on the closed-form side.
inline W3 evenIntegrals(double m, double mc, const Ends& e, Elliptic& ell) {
  W3 w;
  if (m <= kSeriesM) {
    double Q[kSeriesTerms + 3];
    sinePowerIntegrals(e, kSeriesTerms + 3, Q);
    double bm = 1.0;  // b_k m^k, b_k = b_(k-1) (k - 3/2) / k
    for (int k = 0; k < kSeriesTerms && std::abs(bm) >= kSeriesStop; ++k) {
      w.w0 += bm * Q[k];
      w.w1 += bm * Q[k + 1];
      w.w2 += bm * Q[k + 2];
      bm *= m * (k + 1 - 1.5) / (k + 1);
    }
    return w;
  }
  ell.haveF = mc > 0.0;
  if (ell.haveF) {
    const EllipticFE d = ellipticFEDifference(e.p1, e.y1, e.c1, e.p2, e.y2, e.c2, m, mc);
    ell.F = d.F;
    ell.E = d.E;
  } else {
    ell.E = ellE(e.p2) - ellE(e.p1);
  }
  // (1 - m) F, 0 at m = 1 (F's log divergence times 0)
  const double mcF = ell.haveF ? mc * ell.F : 0.0;
  ell.Y1 = e.y2 * e.c2 * e.dl2 - e.y1 * e.c1 * e.dl1;
  ell.Y2 = e.y2 * e.y2 * e.y2 * e.c2 * e.dl2 - e.y1 * e.y1 * e.y1 * e.c1 * e.dl1;
  const double E = ell.E, Y1 = ell.Y1, Y2 = ell.Y2;
  w.w0 = E;
  w.w1 = (mcF - (1.0 - 2.0 * m) * E - m * Y1) / (3.0 * m);
  w.w2 = (2.0 * (2.0 * m + 1.0) * mcF + ((8.0 * m - 3.0) * m - 2.0) * E + m * (1.0 - 4.0 * m) * Y1 -
          3.0 * m * m * Y2) /
         (15.0 * m * m);
  return w;
}

// f F + r: F's coefficient kept apart (see the file comment).
struct WithF {
  double f = 0.0, r = 0.0;
};
inline WithF operator+(WithF a, WithF b) {
  return {a.f + b.f, a.r + b.r};
}
inline WithF operator-(WithF a, WithF b) {
  return {a.f - b.f, a.r - b.r};
}
inline WithF operator*(double s, WithF a) {
  return {s * a.f, s * a.r};
}

// I_n = ∫ s^n / Delta d phi, n = 0..3.
inline void inverseIntegrals(double m, const Ends& e, const Elliptic& ell, WithF* I) {
  if (m <= kSeriesM) {
    double Q[kSeriesTerms + 4];
    sinePowerIntegrals(e, kSeriesTerms + 4, Q);
    double r[4] = {0.0, 0.0, 0.0, 0.0};
    double cm = 1.0;  // c_k m^k, c_k = c_(k-1) (k - 1/2) / k
    for (int k = 0; k < kSeriesTerms && std::abs(cm) >= kSeriesStop; ++k) {
      for (int n = 0; n < 4; ++n) r[n] += cm * Q[k + n];
      cm *= m * (k + 1 - 0.5) / (k + 1);
    }
    for (int n = 0; n < 4; ++n) I[n] = {0.0, r[n]};
    return;
  }
  I[0] = {1.0, 0.0};
  I[1] = {1.0 / m, -ell.E / m};
  I[2] = (1.0 / (3.0 * m)) * (WithF{0.0, ell.Y1} - I[0] + 2.0 * (1.0 + m) * I[1]);
  I[3] = (1.0 / (5.0 * m)) * (WithF{0.0, ell.Y2} - 3.0 * I[1] + 4.0 * (1.0 + m) * I[2]);
}

}  // namespace arc_detail

// The arc of the circle (o, a) from t1 to t2 > t1, c the ICR.
inline void addArcMoments(const Vec2& o, double a, double t1, double t2, const Vec2& c,
                          bool withGradient, BoundaryMoments& acc) {
  const Vec2 d = o - c;
  const double D = d.norm();
  const double t0 = D > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
  const Vec2 dHat = D > 0.0 ? Vec2(d / D) : Vec2(1.0, 0.0);  // (cos t0, sin t0)
  const double th1 = t1 - t0, th2 = t2 - t0;
  // end distances, directly (accurate also when c is on the arc)
  const Vec2 e1(std::cos(t1), std::sin(t1)), e2(std::cos(t2), std::sin(t2));
  const double x = (o + a * e2 - c).norm();
  const double y = (o + a * e1 - c).norm();
  const double u1 = e1.dot(dHat), u2 = e2.dot(dHat);  // cos theta at the ends
  const double du = -2.0 * std::sin(0.5 * (th1 + th2)) * std::sin(0.5 * (th2 - th1));  // u2 - u1
  const double xy = x + y;
  const double S1 = -(2.0 / 3.0) * du * (x * x + x * y + y * y) / xy;
  const double x2 = x * x, y2 = y * y;
  const double S3 = -0.4 * du * (x2 * x2 + x2 * x * y + x2 * y2 + x * y2 * y + y2 * y2) / xy;
  const double SC = 2.0 * (-du) *
                    (u1 * (2 * x2 * x + 4 * x2 * y + 6 * x * y2 + 3 * y2 * y) +
                     u2 * (3 * x2 * x + 6 * x2 * y + 4 * x * y2 + 2 * y2 * y)) /
                    (15.0 * xy * xy);

  const double Dp = D + a;
  const double m = 4.0 * a * D / (Dp * Dp);
  const double r = (D - a) / Dp;
  const double mc = r * r;
  const double p1 = 0.5 * th1, p2 = 0.5 * th2;
  const arc_detail::Ends ends{p1, std::sin(p1), std::cos(p1), y / Dp,
                              p2, std::sin(p2), std::cos(p2), x / Dp};
  arc_detail::Elliptic ell;
  const arc_detail::W3 W = arc_detail::evenIntegrals(m, mc, ends, ell);
  const double L1 = 2.0 * Dp * W.w0;
  const double C1 = 2.0 * Dp * (W.w0 - 2.0 * W.w1);
  const double C2 = 2.0 * Dp * (W.w0 - 4.0 * W.w1 + 4.0 * W.w2);
  const double V0 = W.w0 - m * W.w1, V1 = W.w1 - m * W.w2;
  const double C3 = 2.0 * Dp * Dp * Dp * (V0 - 2.0 * V1);

  Mat2 rot;
  rot << dHat.x(), -dHat.y(), dHat.y(), dHat.x();
  const Vec2 Pe = rot * Vec2(C1, S1);
  Mat2 local;
  local << C2, SC, SC, L1 - C2;
  const Mat2 Pee = rot * local * rot.transpose();
  acc.N1 += a * Pe;
  acc.M += (a * d) * Pe.transpose() + (a * a) * Pee;
  acc.N3 += a * (rot * Vec2(C3, S3));
  if (!withGradient) return;

  // c_k = ∫ cos^k / rho, o_k = ∫ sin cos^k / rho (file comment)
  using arc_detail::WithF;
  WithF I[4];
  arc_detail::inverseIntegrals(m, ends, ell, I);
  const double h = 2.0 / Dp;
  const WithF c0 = h * I[0], c1 = h * (I[0] - 2.0 * I[1]);
  const WithF c2 = h * (I[0] - 4.0 * I[1] + 4.0 * I[2]);
  const WithF c3 = h * (I[0] - 6.0 * I[1] + 12.0 * I[2] - 8.0 * I[3]);
  const double o0 = -2.0 * du / xy;
  const double o1 = 2.0 * (-du) * (2 * u1 * x + u1 * y + u2 * x + 2 * u2 * y) / (3.0 * xy * xy);
  const double o2 =
      2.0 * (-du) *
      (u1 * u1 * (8 * x2 + 9 * x * y + 3 * y2) + u1 * u2 * (4 * x2 + 12 * x * y + 4 * y2) +
       u2 * u2 * (3 * x2 + 9 * x * y + 8 * y2)) /
      (15.0 * xy * xy * xy);
  auto value = [&](WithF v, double odd) { return (ell.haveF ? v.f * ell.F : 0.0) + v.r + odd; };
  const WithF none{};
  // local Q = a ∫ (r / rho) e^T (a of ds included), U[k] = ∫ (r r^T / rho) e_k (times a below)
  Mat2 Ql;
  Ql << a * value(D * c1 + a * c2, 0.0), a * (D * o0 + a * o1), a * a * o1,
      a * a * value(c0 - c2, 0.0);
  Mat2 Ul[2];
  const double cross0 = a * (D * o1 + a * o2);
  Ul[0] << value(D * D * c1 + 2.0 * a * D * c2 + a * a * c3, 0.0), cross0, cross0,
      a * a * value(c1 - c3, 0.0);
  const double cross1 = a * value(D * (c0 - c2) + a * (c1 - c3), 0.0);
  Ul[1] << value(none, D * D * o0 + 2.0 * a * D * o1 + a * a * o2), cross1, cross1,
      a * a * (o0 - o2);
  acc.Q += rot * Ql * rot.transpose();
  const Mat2 U0 = rot * Ul[0] * rot.transpose(), U1 = rot * Ul[1] * rot.transpose();
  acc.U[0] += a * (rot(0, 0) * U0 + rot(0, 1) * U1);
  acc.U[1] += a * (rot(1, 0) * U0 + rot(1, 1) * U1);
}

}  // namespace patchspin::internal
