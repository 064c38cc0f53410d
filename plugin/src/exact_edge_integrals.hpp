// Closed-form edge integrals of the exact model, Eq. (16), over the signed
// triangle (c, edge) for linear pressure basis functions (DESIGN item 3), and
// the edge's part of their derivative with respect to the ICR c (a boundary
// integral over the same closed forms, see addSignedTriangle).
// Internal to exact_polygon.cpp.
#pragma once

#include <cmath>

namespace patchspin::internal {

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
inline double asinhDifference(double ta, double tb, double Ra, double Rb, double J1, double delta,
                              double L) {
  if (ta >= 0.0) return std::log1p((L + J1) / (ta + Ra));
  if (tb <= 0.0) return std::log1p((L - J1) / (Rb - tb));
  const double d2 = delta * delta;
  const double ta2 = ta * ta, tb2 = tb * tb, RaRb = Ra * Rb;
  const double N = tb * Ra - ta * Rb - ta * tb + (ta2 * tb2 + d2 * (ta2 + tb2)) / (RaRb + d2);
  if (d2 > 0.0 && N < 1e290 * d2) return std::log1p(N / d2);
  return std::log((tb + Rb) * (Ra - ta)) - 2.0 * std::log(std::abs(delta));
}

constexpr double kThird = 1.0 / 3.0;

// Linear functions phi integrated at once: column 0 is phi = 1, columns
// 1..E-1 are phi_k(P) = pc[k] + g[k].(P - c) (pc = phi_k(c), g = grad phi_k
// = (gx, gy)), all in the frame where c is given. The pressure basis
// (1, x, y) is E = 3 with pc = (c_x, c_y), g the unit vectors; one linear
// pressure is E = 2.
template <int E>
struct LinearFunctions {
  double pc[E], gx[E], gy[E];  // entries 0 unused (phi = 1)
};

// Per-edge accumulators: force (x, y) and torque times rho per function.
template <int E>
struct EdgeSums {
  double fx[E], fy[E], tz[E];
};

// Boundary part of d(EdgeSums)/dc: [k][j] = d/dc_j of function k's sums.
template <int E>
struct EdgeSumsGradient {
  double fx[E][2], fy[E][2], tz[E][2];
};

// ---- signed triangle (c, a, b), polar about c ----
//
// The integrals along an edge from c's point of view (the notation below):
// tau from ta to tb = ta + L, R = sqrt(tau^2 + delta^2), Ra = R(ta),
// Rb = R(tb); delta below deltaZero (rounding level) counts as c on the
// edge's line and is returned as 0, and so are delta J0, delta^2 J0. Shared
// by the polygon's edges (addSignedTriangle) and the segments of regions
// with arcs (exact_boundary_moments.hpp).
struct EdgeIntegrals {
  double delta = 0.0;
  double J1 = 0.0, deltaJ0 = 0.0, delta2J0 = 0.0, T = 0.0, J2 = 0.0, K0 = 0.0, K1 = 0.0;
};
inline EdgeIntegrals edgeIntegrals(double ta, double L, double Ra, double Rb, double delta,
                                   double deltaZero) {
  EdgeIntegrals r;
  const double tb = ta + L;
  // J1 = Rb - Ra = L (ta + tb) / (Ra + Rb) without cancellation
  r.J1 = L * (ta + tb) / (Ra + Rb);
  if (std::abs(delta) > deltaZero) {
    r.delta = delta;
    r.deltaJ0 = delta * asinhDifference(ta, tb, Ra, Rb, r.J1, delta, L);
    r.delta2J0 = delta * r.deltaJ0;
  }
  // T = tb Rb - ta Ra = L Rb + ta J1 (all terms one sign when ta, tb are)
  r.T = (ta >= 0.0 || tb <= 0.0) ? L * Rb + ta * r.J1 : tb * Rb - ta * Ra;
  r.J2 = 0.5 * (r.T - r.delta2J0);
  r.K0 = 0.5 * (r.T + r.delta2J0);
  r.K1 = r.J1 * (Ra * Ra + Ra * Rb + Rb * Rb) * kThird;
  return r;
}

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
// delta = 0 (c on the edge's line) the terms delta J0, delta^2 J0 are 0.
//
// Derivative in c (`gradient` not null). With the kernel kappa(c; P) =
// (perp(u), P.u) (k without sgn(w3) and 1/rho) and G = int_A phi kappa dA,
// substituting r = P - c gives an integral over A - c of phi(c + r)
// kappa(r, c + r), whose domain moves with -c and whose integrand depends
// on c through phi and through the torque's P.u only:
//   dG/dc_j = sum_edges n_j int_edge phi kappa d tau           (A - c moves)
//           + (d phi/dc_j) int_A kappa dA                      (phi(c + r))
//           + (0, 0, int_A phi u_j dA)                         (P.u = c.u + R)
// (n = perp(e) is the inward normal of a counter-clockwise edge). The last
// term is G's own force: perp(u) = (-u_y, u_x), so int phi u = (G_y, -G_x);
// the middle one is the phi = 1 column for phi = x, y. Both are added by the
// caller; here the edge term (for functions firstGradient..E-1: the law of
// one pressure needs it for that pressure only), with phi = A0 + A1 tau (A0 = phi_c - delta gn,
// A1 = ge), kappa = ((tau n + delta e) / R, (tau ce - delta cn + R^2) / R):
//   force   n (A0 J1 + A1 J2) + e (A0 delta J0 + A1 delta J1)
//   torque  ce (A0 J1 + A1 J2) - cn (A0 delta J0 + A1 delta J1) + A0 K0 + A1 K1
// Its integrand is bounded (|kappa| <= 1 + |P|), so the formula holds for c
// on the edge or a vertex too (there delta J0 = 0).
// L = |b - a| > 0 and deltaZero are given by the caller.
template <int E>
void addSignedTriangle(double ax, double ay, double bx, double by, double L, double cx, double cy,
                       double Ra, double Rb, double deltaZero, const LinearFunctions<E>& phi,
                       EdgeSums<E>& sums, EdgeSumsGradient<E>* gradient, int firstGradient) {
  const double Lx = bx - ax, Ly = by - ay;
  const double invL = 1.0 / L;
  const double ex = Lx * invL, ey = Ly * invL;
  const double nx = -ey, ny = ex;
  const double rax = ax - cx, ray = ay - cy;
  const double ta = rax * ex + ray * ey;
  const EdgeIntegrals ei = edgeIntegrals(ta, L, Ra, Rb, rax * ey - ray * ex, deltaZero);
  const double delta = ei.delta, J1 = ei.J1, deltaJ0 = ei.deltaJ0, delta2J0 = ei.delta2J0,
               J2 = ei.J2, K0 = ei.K0, K1 = ei.K1;
  const double ce = cx * ex + cy * ey;
  const double cn = cx * nx + cy * ny;

  // phi = 1 (phi_c = 1, g = 0)
  //   F_xy = delta (n J1 + e delta J0) / 2
  //   Tz   = delta [ (ce J1 - cn delta J0) / 2 + K0 / 3 ]
  const double halfForceN = 0.5 * J1, halfForceE = 0.5 * deltaJ0;
  const double torque0 = 0.5 * (ce * J1 - cn * deltaJ0) + K0 * kThird;
  sums.fx[0] += delta * (halfForceN * nx + halfForceE * ex);
  sums.fy[0] += delta * (halfForceN * ny + halfForceE * ey);
  sums.tz[0] += delta * torque0;

  // linear phi (phi_c, g)
  //   F_xy = delta [ phi_c (n J1 + e delta J0)/2
  //                + (ge n J2 + delta (ge e - gn n) J1 - gn e delta^2 J0) / 3 ]
  //   Tz   = delta [ phi_c ((ce J1 - cn delta J0)/2 + K0/3)
  //                + (ge ce J2 - delta (ge cn + gn ce) J1 + gn cn delta^2 J0) / 3
  //                + (ge K1 - delta gn K0) / 4 ]
  const double deltaJ1 = delta * J1;
  double ge[E], gn[E];
  ge[0] = gn[0] = 0.0;
  for (int k = 1; k < E; ++k) {
    ge[k] = phi.gx[k] * ex + phi.gy[k] * ey;
    gn[k] = phi.gx[k] * nx + phi.gy[k] * ny;
    const double pc = phi.pc[k];
    const double an = (pc * halfForceN) + (ge[k] * J2 - gn[k] * deltaJ1) * kThird;        // along n
    const double ae = (pc * halfForceE) + (ge[k] * deltaJ1 - gn[k] * delta2J0) * kThird;  // along e
    const double tq =
        pc * torque0 +
        (ge[k] * (ce * J2) - (ge[k] * cn + gn[k] * ce) * deltaJ1 + gn[k] * (cn * delta2J0)) *
            kThird +
        (ge[k] * K1 - gn[k] * (delta * K0)) * 0.25;
    sums.fx[k] += delta * (an * nx + ae * ex);
    sums.fy[k] += delta * (an * ny + ae * ey);
    sums.tz[k] += delta * tq;
  }

  if (gradient == nullptr) return;
  // edge term of dG/dc (see above): A0 = phi_c - delta gn, A1 = ge
  for (int k = firstGradient; k < E; ++k) {
    const double A0 = k == 0 ? 1.0 : phi.pc[k] - delta * gn[k];
    const double alongN = A0 * J1 + ge[k] * J2;
    const double alongE = A0 * deltaJ0 + ge[k] * deltaJ1;
    const double fx = alongN * nx + alongE * ex;
    const double fy = alongN * ny + alongE * ey;
    const double tz = ce * alongN - cn * alongE + A0 * K0 + ge[k] * K1;
    gradient->fx[k][0] += nx * fx, gradient->fx[k][1] += ny * fx;
    gradient->fy[k][0] += nx * fy, gradient->fy[k][1] += ny * fy;
    gradient->tz[k][0] += nx * tz, gradient->tz[k][1] += ny * tz;
  }
}

}  // namespace patchspin::internal
