// What the exact law's region evaluations share (exact_polygon.cpp,
// exact_arc_region.cpp): the frame centred at a point g of the region, the
// far branch's area rule (its order and one node's kernel), and the way back
// from g's frame to O's.
//
// Frame: P' = P - g, w' = S w with S = [[1, 0, -gy/rho], [0, 1, gx/rho],
// [0, 0, 1]] (Eq. (1) about g); F is homogeneous of degree 0 in w, so w is
// first scaled to max |w_i| = 1 (the squares below stay finite for any
// finite w) and dF scales by 1 / wScale. The ICR c' = rho (-w'2, w'1) / w'3
// lies kappa region radii from g, kappa^2 written without dividing by w'3.
#pragma once

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "gauss_tables.hpp"

namespace patchspin::internal {

struct RegionFrame {
  Mat3 S = Mat3::Identity();
  double wScale = 1.0;
  Vec3 wl = Vec3::Zero();  // w' = S w / wScale
  double planarSq = 0.0;   // rho^2 |w'_xy|^2
  double w3Sq = 0.0;       // w'_3^2
  RegionFrame() = default;
  RegionFrame(const Vec2& g, double rho, const Vec3& w) {
    S(0, 2) = -g.y() / rho;
    S(1, 2) = g.x() / rho;
    wScale = w.cwiseAbs().maxCoeff();
    wl = S * (w / wScale);
    planarSq = rho * rho * (wl.x() * wl.x() + wl.y() * wl.y());
    w3Sq = wl.z() * wl.z();
  }
  // the ICR beyond farRatio region radii (radiusSq: the radius squared), or
  // pure translation
  bool far(double farRatio, double radiusSq) const {
    return planarSq > farRatio * farRatio * radiusSq * w3Sq;
  }
  double kappaSq(double radiusSq) const {
    return w3Sq > 0.0 ? planarSq / (radiusSq * w3Sq) : INFINITY;
  }
};

// Order n of the far rule for ICR distance ratio kappa (kappa^2 given; +inf
// for translation). Gauss-Legendre on an interval of half-length h with the
// nearest singularity at distance D converges like beta^(-2n), beta = K +
// sqrt(K^2-1), K = D/h, for an analytic integrand; ours is a polynomial of
// degree 3 (pressure basis x lever arm x the map's Jacobian) times the
// analytic v/|v|, which costs three orders of beta: error ~ C beta^(3 - 2n)
// (measured: n = 2 gives ~1e-3/kappa, n = 3 ~kappa^-3); the Jacobian's
// integrand has degree 4, one more. A fan piece spans at most 2 region radii
// and c is at least (kappa - 1) of them from it, so K >= kappa - 1
// (conservative). With kErrorConstant = 1 the measured errors stay below
// 0.02 tol for tol in [1e-13, 1e-4] over kappa in [8, 1e7] (the polygon's
// tolerance test: against the default accuracy).
inline int farOrder(double kappaSq, double tol, bool jacobian) {
  constexpr double kErrorConstant = 1.0;
  // the Jacobian's integrand m m^T phi det has one more polynomial degree
  const double degree = jacobian ? 4.0 : 3.0;
  const int minOrder = jacobian ? 3 : 2;         // exact for that degree (2n - 1 >= degree)
  if (!std::isfinite(kappaSq)) return minOrder;  // pure translation: v/|v| constant
  const double K = std::sqrt(kappaSq) - 1.0;
  const double beta = K + std::sqrt(K * K - 1.0);
  const double n = 0.5 * degree + 0.5 * std::log(kErrorConstant / tol) / std::log(beta);
  return std::clamp(static_cast<int>(std::ceil(n)), minOrder, kGaussMaxOrder);
}

// One node P (g-frame) of the area rule with weighted functions phi (wt
// phi_k(P)): Eq. (1) and the kernel
//   v = M w',  M = [[1, 0, -y/rho], [0, 1, x/rho]],  k = M^T v/|v|
//   dk/dw' = M^T (I - vv^T/|v|^2) M / |v| = m m^T / |v|,  m = M^T perp(v)/|v|,
// added as F += k phi^T and dF[c] += phi_c m m^T / |v|.
template <bool kJacobian, int M>
inline void addKernelNode(const Vec2& P, const Eigen::Matrix<double, M, 1>& phi, const Vec3& w,
                          double invRho, Eigen::Matrix<double, 3, M>& F, Mat3* dF) {
  const double vx = w.x() - w.z() * P.y() * invRho, vy = w.y() + w.z() * P.x() * invRho;
  const double invV = 1.0 / std::sqrt(vx * vx + vy * vy);
  const double ux = vx * invV, uy = vy * invV;
  const Vec3 k(ux, uy, (P.x() * uy - P.y() * ux) * invRho);
  F.noalias() += k * phi.transpose();
  if constexpr (kJacobian) {
    const Vec3 m(-uy, ux, (P.x() * ux + P.y() * uy) * invRho);
    const Mat3 mm = (invV * m) * m.transpose();
    for (int c = 0; c < M; ++c) dF[c].noalias() += phi[c] * mm;
  }
}

// The basis back at O from g's frame (Fl, dFl): phi = (1, gx + x', gy + y'),
// torque about O = T k', T = S^T:
//   F.col(0) = T F'.col(0),  F.col(1) = T (gx F'.col(0) + F'.col(1)), ...
//   dF[k] = T dF'[k] S / wScale   (chain rule through w' = S w / wScale)
inline void basisAtO(const Mat3& Fl, const std::array<Mat3, 3>& dFl, const Vec2& g,
                     const RegionFrame& frame, bool wantJacobian, ExactBasis& out) {
  const Mat3 T = frame.S.transpose();
  Mat3 Fm = Fl;
  Fm.col(1) += g.x() * Fl.col(0);
  Fm.col(2) += g.y() * Fl.col(0);
  out.F.noalias() = T * Fm;
  if (wantJacobian) {
    const Mat3 d0 = dFl[0];
    const Mat3 d1 = dFl[1] + g.x() * d0;
    const Mat3 d2 = dFl[2] + g.y() * d0;
    const Mat3 Sw = frame.S / frame.wScale;
    out.dF[0].noalias() = T * d0 * Sw;
    out.dF[1].noalias() = T * d1 * Sw;
    out.dF[2].noalias() = T * d2 * Sw;
  } else {
    for (Mat3& m : out.dF) m.setZero();
  }
}

}  // namespace patchspin::internal
