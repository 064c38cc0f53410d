// The 3x3 SPD kit of the friction block (spd3.hpp).
#include "spd3.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace patchspin::internal {

void requireNotNumericallySingular(const Mat3& Ksym, const Mat3& Kinv) {
  const Vec3 d = Ksym.diagonal().cwiseAbs().cwiseSqrt();
  const Mat3 scaledK = d.cwiseInverse().asDiagonal() * Ksym * d.cwiseInverse().asDiagonal();
  const Mat3 scaledKinv = d.asDiagonal() * Kinv * d.asDiagonal();
  const double cond = scaledK.norm() * scaledKinv.norm();
  if (!(cond < kSingularCondition))
    throw Error("friction block matrix K is numerically singular (condition number " +
                internal::formatDouble(cond) + " after scaling to a unit diagonal)");
}

// Eigen's LLT with its unblocked lower factorisation written out for the 3x3
// case: the same operations in the same order, failing at the first pivot
// <= 0 as Eigen does, the L1 norm for rcond() as its compute() takes it.
// (Eigen's dynamic-size blocks cost ~320 instructions per factorisation.)
namespace {
struct Llt3 : Eigen::LLT<Mat3> {
  explicit Llt3(const Mat3& a) {
    m_matrix = a;
    // (|lower part of column c| + |row c left of it|, summed as Eigen sums them)
    const Mat3 b = a.cwiseAbs();
    const double sums[3] = {(b(0, 0) + b(1, 0)) + b(2, 0) + 0.0, (b(1, 1) + b(2, 1)) + b(1, 0),
                            b(2, 2) + (b(2, 0) + b(2, 1))};
    m_l1_norm = 0.0;
    for (const double sum : sums)
      if (sum > m_l1_norm) m_l1_norm = sum;
    m_isInitialized = true;
    m_info = factor() ? Eigen::Success : Eigen::NumericalIssue;
  }
  // Eigen's llt_inplace::unblocked: per column k, x = a_kk - |L_k,0:k|^2,
  // stop if x <= 0, l_kk = sqrt(x), then the column below minus L_k+1:,0:k
  // L_k,0:k^T, divided by l_kk
  bool factor() {
    Mat3& m = m_matrix;
    double x = m(0, 0);
    if (x <= 0.0) return false;
    m(0, 0) = x = std::sqrt(x);
    m(1, 0) /= x;
    m(2, 0) /= x;
    x = m(1, 1) - m(1, 0) * m(1, 0);
    if (x <= 0.0) return false;
    m(1, 1) = x = std::sqrt(x);
    m(2, 1) -= m(2, 0) * m(1, 0);
    m(2, 1) /= x;
    x = m(2, 2) - (m(2, 0) * m(2, 0) + m(2, 1) * m(2, 1));
    if (x <= 0.0) return false;
    m(2, 2) = std::sqrt(x);
    return true;
  }
};
}  // namespace

Eigen::LLT<Mat3> requirePositiveDefiniteFactor(const Mat3& Ksym) {
  const Llt3 llt(Ksym);
  if (!(llt.info() == Eigen::Success && Ksym.diagonal().minCoeff() > 0.0 &&
        llt.matrixLLT().allFinite()))
    throw Error(
        "friction block matrix K is not positive definite (or singular to round-off: its Cholesky "
        "factorisation fails)");
  return llt;
}
// (Eigen's solve() goes through dynamic-size triangular blocks, ~2000
// instructions for K^-1, where the substitutions are ~60 flops.)
Vec3 choleskySolve(const Eigen::LLT<Mat3>& llt, const Vec3& b) {
  const Mat3& L = llt.matrixLLT();  // lower triangle
  const double y0 = b[0] / L(0, 0);
  const double y1 = (b[1] - L(1, 0) * y0) / L(1, 1);
  const double y2 = (b[2] - L(2, 0) * y0 - L(2, 1) * y1) / L(2, 2);
  const double x2 = y2 / L(2, 2);
  const double x1 = (y1 - L(2, 1) * x2) / L(1, 1);
  const double x0 = (y0 - (L(1, 0) * x1 + L(2, 0) * x2)) / L(0, 0);
  return Vec3(x0, x1, x2);
}
Mat3 inverseOf(const Eigen::LLT<Mat3>& llt) {
  Mat3 inv;
  for (int k = 0; k < 3; ++k) inv.col(k) = choleskySolve(llt, Vec3::Unit(k));
  return 0.5 * (inv + inv.transpose());
}
void requireNotNumericallySingular(const Mat3& Ksym) {
  requireNotNumericallySingular(Ksym, inverseOf(requirePositiveDefiniteFactor(Ksym)));
}

Vec3 stickSolve(const Mat3& K, const Eigen::LLT<Mat3>& llt, const Vec3& b) {
  const Vec3 lambda = -choleskySolve(llt, b);
  const Vec3 refined = lambda - choleskySolve(llt, b + K * lambda);
  return refined.allFinite() ? refined : lambda;
}

// 1e-10: a backward-stable solve meets it by a factor 1e5.
constexpr double kStickResidual = 1e-10;
Vec3 requireStopsTheSlip(const Mat3& K, const Vec3& b, const Vec3& lambda) {
  const double residual = rangeSafeNorm(b + K * lambda);
  if (!(residual <= kStickResidual * (rangeSafeNorm(b) + rangeSafeNorm(K) * rangeSafeNorm(lambda))))
    throw Error("friction block matrix K is numerically singular (a stick leaves b + K lambda = " +
                internal::formatDouble(residual) +
                " against |b| = " + internal::formatDouble(b.stableNorm()) + ")");
  return lambda;
}

// First a sufficient test without square roots or divisions (the
// factorisation is a chain of three of each): finite entries, a positive
// diagonal and every off-diagonal A_ij^2 <= kDominant A_ii A_jj. The
// factorisation then succeeds in floating point with room to spare:
//   l10^2 = A10^2 / A00 <= 0.2 A11,  so  x1 >= 0.8 A11;
//   |l21| <= (|A21| + |l20| |l10|) / sqrt(x1)  gives  l21^2 <= (sqrt 0.2 + 0.2)^2 / 0.8 A22 = 0.53
//   A22, l20^2 <= 0.2 A22,  so  x2 >= 0.27 A22 > 0,  every l finite;
// round-off moves these bounds by a few eps, not by 0.27. So the fast test
// accepts only what the factorisation accepts, and everything else goes to
// the factorisation (the Bullet integration's blocks pass it: their
// off-diagonals are small).
void requirePositiveDefinite(const Mat3& K) {
  const Mat3 A = 0.5 * (K + K.transpose());
  {
    constexpr double kDominant = 0.2, kMin = std::numeric_limits<double>::min();
    const double a00 = A(0, 0), a11 = A(1, 1), a22 = A(2, 2);
    const double p01 = kDominant * (a00 * a11), p02 = kDominant * (a00 * a22),
                 p12 = kDominant * (a11 * a22);
    // (normal, finite diagonals and bounds: a square that underflows then
    // lies below its bound in exact arithmetic too, and the factorisation's
    // own underflows are far below 0.27 A22; finite bounds imply finite
    // diagonals, and an infinite or NaN off-diagonal fails its comparison)
    if (a00 >= kMin && a11 >= kMin && a22 >= kMin && p01 >= kMin && p02 >= kMin && p12 >= kMin &&
        std::isfinite(p01) && std::isfinite(p02) && std::isfinite(p12) &&
        A(1, 0) * A(1, 0) <= p01 && A(2, 0) * A(2, 0) <= p02 && A(2, 1) * A(2, 1) <= p12)
      return;
  }
  const double x0 = A(0, 0);
  bool ok = x0 > 0.0;
  if (ok) {
    const double l00 = std::sqrt(x0);
    const double l10 = A(1, 0) / l00, l20 = A(2, 0) / l00;
    const double x1 = A(1, 1) - l10 * l10;
    ok = x1 > 0.0;
    if (ok) {
      const double l11 = std::sqrt(x1);
      const double l21 = (A(2, 1) - l20 * l10) / l11;
      const double x2 = A(2, 2) - (l20 * l20 + l21 * l21);
      ok = x2 > 0.0 && std::isfinite(l10) && std::isfinite(l20) && std::isfinite(l21) &&
           std::isfinite(std::sqrt(x2));
    }
  }
  if (!(ok && A.diagonal().minCoeff() > 0.0)) requirePositiveDefiniteFactor(A);  // throws
}

}  // namespace patchspin::internal
