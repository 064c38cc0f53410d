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
//    kind at amplitude phi, parameter m; Y_n = [sin^(2n-1) phi cos phi Delta]):
//      W0 = E,  W1 = [(1-m) F - (1-2m) E - m Y1] / (3m),
//      W2 = [2(1-m)(2m+1) F + (8m^2 - 3m - 2) E + m(1 - 4m) Y1 - 3m^2 Y2] / (15 m^2),
//    from d/dphi(sin^(2n-1) cos Delta) = [(2n-1) s^(n-1) - 2n(1+m) s^n
//    + (2n+1) m s^(n+1)] / Delta. F always carries 1 - m (c on the circle: F
//    diverges where Delta = 0, the product -> 0). For m <= kSeriesM (c near
//    the centre or far from the circle) the 1/m^2 would cancel: the binomial
//    series Delta = sum b_k (m s)^k, W_j = sum b_k m^k Q_(j+k),
//    Q_n = ∫ s^n d phi = -[sin^(2n-1) cos]/(2n) + (2n-1)/(2n) Q_(n-1).
// Guarded by exact_arc_region_test.cpp (BoundaryMoments*, and the law's tests).
#pragma once

#include "exact_edge_integrals.hpp"

#include <patchspin/types.hpp>

#include <cmath>

namespace patchspin::internal {

struct BoundaryMoments {
  Vec2 N1 = Vec2::Zero();
  Mat2 M = Mat2::Zero();
  Vec2 N3 = Vec2::Zero();
};

// The segment a -> b (any length), c the ICR; deltaZero: |delta| below it is
// rounding (c on the segment's line).
inline void addSegmentMoments(const Vec2& a, const Vec2& b, const Vec2& c, double deltaZero,
                              BoundaryMoments& acc) {
  const double L = (b - a).norm();
  if (!(L > 0.0)) return;
  const Vec2 e = (b - a) / L;
  const Vec2 n(e.y(), -e.x());
  const Vec2 ra = a - c;
  const double ta = ra.dot(e), tb = ta + L;
  double delta = ra.dot(n);
  const double Ra = ra.norm(), Rb = (b - c).norm();
  const double J1 = L * (ta + tb) / (Ra + Rb);
  double delta2J0 = 0.0;
  if (std::abs(delta) > deltaZero) {
    delta2J0 = delta * delta * asinhDifference(ta, tb, Ra, Rb, J1, delta, L);
  } else {
    delta = 0.0;
  }
  const double T = (ta >= 0.0 || tb <= 0.0) ? L * Rb + ta * J1 : tb * Rb - ta * Ra;
  const double K0 = 0.5 * (T + delta2J0);
  const double K1 = J1 * (Ra * Ra + Ra * Rb + Rb * Rb) / 3.0;
  const double K3 = 0.25 * (tb * Rb * Rb * Rb - ta * Ra * Ra * Ra) + 0.75 * delta * delta * K0;
  acc.N1 += K0 * n;
  acc.M += (K1 * e + (delta * K0) * n) * n.transpose();
  acc.N3 += K3 * n;
}

namespace arc_detail {

// m below this: the series (<= 17 terms for 1e-17); above, the closed form
// loses about 1/m^2 (100 at the switch) to cancellation.
constexpr double kSeriesM = 0.1;

struct W3 {
  double w0 = 0.0, w1 = 0.0, w2 = 0.0;
};

// E(phi | m) for m = 1 (k = 1): E = 2n + sin(phi - n pi), n = round(phi/pi)
// (libstdc++'s ellint_2 rejects k = 1 at phi = pi/2 + n pi).
inline double ellE(double k, double m, double phi) {
  if (m >= 1.0) {
    const double n = std::nearbyint(phi / M_PI);
    return 2.0 * n + std::sin(phi - n * M_PI);
  }
  return std::ellint_2(k, phi);
}

// W_j over [p1, p2] (see the file comment); y_i = sin, c_i = cos, dl_i = Delta
// at the ends.
inline W3 evenIntegrals(double m, double mc, double p1, double p2, double y1, double c1, double dl1,
                        double y2, double c2, double dl2) {
  W3 w;
  if (m <= kSeriesM) {
    // Q_n by its recurrence, b_k = b_(k-1) (k - 3/2) / k
    double Q[3] = {p2 - p1, 0.0, 0.0};
    double s1p = y1 / 1.0, s2p = y2;  // sin^(2n-1) at n = 1
    const double s1 = y1 * y1, s2 = y2 * y2;
    auto nextQ = [&](int n, double prev) {
      const double v = -(s2p * c2 - s1p * c1) / (2.0 * n) + (2.0 * n - 1.0) / (2.0 * n) * prev;
      s1p *= s1, s2p *= s2;
      return v;
    };
    Q[1] = nextQ(1, Q[0]);
    Q[2] = nextQ(2, Q[1]);
    double bm = 1.0;  // b_k m^k
    for (int k = 0; k < 60; ++k) {
      w.w0 += bm * Q[0];
      w.w1 += bm * Q[1];
      w.w2 += bm * Q[2];
      bm *= m * (k + 1 - 1.5) / (k + 1);
      if (std::abs(bm) < 1e-18) break;
      Q[0] = Q[1], Q[1] = Q[2];
      Q[2] = nextQ(k + 3, Q[1]);
    }
    return w;
  }
  const double k = std::sqrt(m);
  const double E = ellE(k, m, p2) - ellE(k, m, p1);
  // (1 - m) F, 0 at m = 1 (F's log divergence times 0)
  const double mcF =
      (mc > 0.0 && m < 1.0) ? mc * (std::ellint_1(k, p2) - std::ellint_1(k, p1)) : 0.0;
  const double Y1 = y2 * c2 * dl2 - y1 * c1 * dl1;
  const double Y2 = y2 * y2 * y2 * c2 * dl2 - y1 * y1 * y1 * c1 * dl1;
  w.w0 = E;
  w.w1 = (mcF - (1.0 - 2.0 * m) * E - m * Y1) / (3.0 * m);
  w.w2 = (2.0 * (2.0 * m + 1.0) * mcF + ((8.0 * m - 3.0) * m - 2.0) * E + m * (1.0 - 4.0 * m) * Y1 -
          3.0 * m * m * Y2) /
         (15.0 * m * m);
  return w;
}

}  // namespace arc_detail

// The arc of the circle (o, a) from t1 to t2 > t1, c the ICR.
inline void addArcMoments(const Vec2& o, double a, double t1, double t2, const Vec2& c,
                          BoundaryMoments& acc) {
  const Vec2 d = o - c;
  const double D = d.norm();
  const double t0 = D > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
  const double th1 = t1 - t0, th2 = t2 - t0;
  // end distances, directly (accurate also when c is on the arc)
  const double x = (o + a * Vec2(std::cos(t2), std::sin(t2)) - c).norm();
  const double y = (o + a * Vec2(std::cos(t1), std::sin(t1)) - c).norm();
  const double u1 = std::cos(th1), u2 = std::cos(th2);
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
  const arc_detail::W3 W = arc_detail::evenIntegrals(m, mc, p1, p2, std::sin(p1), std::cos(p1),
                                                     y / Dp, std::sin(p2), std::cos(p2), x / Dp);
  const double L1 = 2.0 * Dp * W.w0;
  const double C1 = 2.0 * Dp * (W.w0 - 2.0 * W.w1);
  const double C2 = 2.0 * Dp * (W.w0 - 4.0 * W.w1 + 4.0 * W.w2);
  const double V0 = W.w0 - m * W.w1, V1 = W.w1 - m * W.w2;
  const double C3 = 2.0 * Dp * Dp * Dp * (V0 - 2.0 * V1);

  Mat2 rot;
  rot << std::cos(t0), -std::sin(t0), std::sin(t0), std::cos(t0);
  const Vec2 Pe = rot * Vec2(C1, S1);
  Mat2 local;
  local << C2, SC, SC, L1 - C2;
  const Mat2 Pee = rot * local * rot.transpose();
  acc.N1 += a * Pe;
  acc.M += (a * d) * Pe.transpose() + (a * a) * Pee;
  acc.N3 += a * (rot * Vec2(C3, S3));
}

}  // namespace patchspin::internal
