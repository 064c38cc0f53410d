// 3x3 symmetric positive definite kit of the friction block: Cholesky factor,
// solves, inverse, singularity and positive definiteness tests, range-safe norms.
// Private to patchspin::core (not installed).
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <patchspin/types.hpp>

namespace patchspin::internal {

// K scaled to a unit diagonal must have a condition number below this: K^-1
// then carries eps cond ~ 2e-6 relative error at most, the resolution to which
// the blocks' answers are checked. The scaled cond is at most 3 times the plain
// |K| |K^-1| (van der Sluis), so callers may test that first.
// Guarded by FrictionBlockConditioning.NumericallySingularKIsRefusedOrTheLaw.
constexpr double kSingularCondition = 1e10;

inline double stableNormOf(const Mat3& m) {
  return stableMatrixNorm(m);
}
inline double stableNormOf(const Vec3& v) {
  return v.stableNorm();
}

// |v| as sqrt(v.squaredNorm()) where that sum of squares is a normal, finite
// double (then within a few ulps of the exact norm), Eigen's stableNorm (no
// under- or overflow) only outside that range; the zero vector is 0.
template <typename Derived>
double rangeSafeNorm(const Eigen::MatrixBase<Derived>& v) {
  const double s = v.squaredNorm();
  if (s >= std::numeric_limits<double>::min() && s <= std::numeric_limits<double>::max())
    return std::sqrt(s);
  if (v.isZero(0.0)) return 0.0;
  return stableNormOf(v.eval());
}

// Cholesky factor of the symmetric Ksym (Eigen's LLT decision: the same
// pivots in the same order); throws Error unless it succeeds with a positive
// diagonal and a finite factor. Accurate to the condition number of Ksym
// scaled to a unit diagonal, whatever the diagonal's spread.
// Guarded by FrictionBlockConditioning.ExactStickRefusesCofactorsWithoutDigits and
// FrictionBlockIllConditioned.ExactBlockAcceptsAPositiveDefiniteKWhoseDeterminantHasNoDigits.
Eigen::LLT<Mat3> requirePositiveDefiniteFactor(const Mat3& Ksym);

// x = K^-1 b by forward and back substitution on llt's factor L, L L^T = K.
Vec3 choleskySolve(const Eigen::LLT<Mat3>& llt, const Vec3& b);

// K^-1 from llt, symmetrised.
Mat3 inverseOf(const Eigen::LLT<Mat3>& llt);

// Throws Error ("numerically singular") unless Ksym scaled to a unit diagonal
// has a Frobenius condition number below kSingularCondition; Kinv = Ksym^-1.
void requireNotNumericallySingular(const Mat3& Ksym, const Mat3& Kinv);
void requireNotNumericallySingular(const Mat3& Ksym);

// Throws Error unless K's symmetric part is positive definite (the decision of
// requirePositiveDefiniteFactor, without the factor on the common path).
// Guarded by
// FrictionBlockFastPaths.EllipsoidalPositiveDefinitenessShortcutDecidesAsTheFactorisation.
void requirePositiveDefinite(const Mat3& K);

// A stick's impulse lambda = -K^-1 b from the Cholesky factor of K's symmetric
// part, refined once with K itself (K may be asymmetric to 1e-10); Cholesky,
// unlike partial pivoting, is invariant under K's diagonal scaling.
// Guarded by FrictionBlockIllConditioned.ExactStickWithABadlyScaledKIsMinusKInverseB.
Vec3 stickSolve(const Mat3& K, const Eigen::LLT<Mat3>& llt, const Vec3& b);

// Returns lambda if it stops the slip, |b + K lambda| <= kStickResidual
// (|b| + |K| |lambda|); otherwise throws Error (K numerically singular).
// Guarded by FrictionBlockConditioning.StickRefusesAKSingularToRoundOff.
Vec3 requireStopsTheSlip(const Mat3& K, const Vec3& b, const Vec3& lambda);

}  // namespace patchspin::internal
