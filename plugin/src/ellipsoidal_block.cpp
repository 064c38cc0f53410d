// The ellipsoidal friction block, q(w) = -Pi w, Eq. (41) (friction_block.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "friction_block_solvers.hpp"
#include "spd3.hpp"

namespace patchspin::internal {

namespace {
// The root brackets bisect at the geometric mean while hi / lo exceeds this
// (a bracket spanning orders of magnitude), else at the arithmetic mean.
constexpr double kGeometricBisection = 4.0;
}  // namespace

// Ellipsoidal law q(w) = -Pi w. With A = L K Pi the slip s = b - A w must
// equal r w: w = (r I + A)^-1 b with |w| = 1, a scalar root in r > 0.
// No matrix is factorised: by Cayley-Hamilton, for the 3x3 A with
//   t = tr A,  m = (t^2 - tr A^2) / 2 = tr adj A,  d = det A,  adj A = A^2 - t A + m I,
//   (r I + A)^-1 = (r^2 I + r (t I - A) + adj A) / p(r),
//   p(r) = r^3 + t r^2 + m r + d,
// so w(r) = N(r) / p(r) with N(r) = r^2 b + r (t b - A b) + adj(A) b: three
// vectors and four numbers, then every trial r costs a few dozen flops.
// A is similar to L Pi^1/2 K Pi^1/2 (SPD), so its eigenvalues are positive and
// p(r) > 0 for r >= 0.
// Stick iff |A^-1 b| = |N(0)| / d <= 1.
// Slip: f(r) = p(r) / |N(r)| - 1 = 0. f(0) < 0 and f grows without bound; for
// A = a I, f = (r + a) / |b| - 1 is linear (Newton exact in one step), and
// near-isotropic blocks, the common case, converge in two or three steps;
// the bracket [lo, hi] with hi = |b| + |A|_F (where |w| < 1) safeguards.
FrictionBlockResult solveEllipsoidal(const Mat3& Pi, const FrictionBlockInput& in) {
  FrictionBlockResult out;
  const double tol = in.tolerance > 0.0 ? in.tolerance : kRelativeTolerance;
  const Mat3 A = in.L * (in.K * Pi);
  const double t = A.trace();
  // adj A by cofactors, m = tr adj A (sum of the principal 2x2 minors) and
  // t I - A with its diagonal summed from the other two: each entry a
  // difference of at most two products, not the forms above, which cancel to
  // the scale of |A|^2 (FrictionBlock.EllipsoidalRefusesALongLever)
  Mat3 adj;
  adj(0, 0) = A(1, 1) * A(2, 2) - A(1, 2) * A(2, 1);
  adj(0, 1) = A(0, 2) * A(2, 1) - A(0, 1) * A(2, 2);
  adj(0, 2) = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  adj(1, 0) = A(1, 2) * A(2, 0) - A(1, 0) * A(2, 2);
  adj(1, 1) = A(0, 0) * A(2, 2) - A(0, 2) * A(2, 0);
  adj(1, 2) = A(0, 2) * A(1, 0) - A(0, 0) * A(1, 2);
  adj(2, 0) = A(1, 0) * A(2, 1) - A(1, 1) * A(2, 0);
  adj(2, 1) = A(0, 1) * A(2, 0) - A(0, 0) * A(2, 1);
  adj(2, 2) = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  const double m = adj.trace();
  const double d = A.row(0).dot(adj.col(0));
  Mat3 tMinusA = -A;
  tMinusA(0, 0) = A(1, 1) + A(2, 2);
  tMinusA(1, 1) = A(0, 0) + A(2, 2);
  tMinusA(2, 2) = A(0, 0) + A(1, 1);
  const Vec3 n2 = in.b;
  const Vec3 n1 = tMinusA * in.b;
  const Vec3 n0 = adj * in.b;
  const double bNorm = in.b.norm(), aNorm = A.norm();
  const double scale = bNorm + aNorm;
  // L K Pi beyond double's range is refused before the iteration runs on inf
  // (FrictionBlockScale.FarFromUnitScaleIsTheLaw)
  if (!std::isfinite(scale) || !std::isfinite(m) || !std::isfinite(d) || !n0.allFinite() ||
      !n1.allFinite()) {
    throw Error("friction block out of range: L K Pi overflows double (K, b or L too large)");
  }
  // stick iff lambda0 = -K^-1 b = -L Pi w0 has |w0| <= 1, by solves with K
  // and Pi themselves (backward stable); a well-conditioned A, |A| |A^-1| =
  // |A| |adj A| / d below kAdjugateCondition, keeps the cheaper adjugate
  // test, whose error ~cond(A) eps is far inside the Newton tolerance
  // (FrictionBlockConditioning.EllipsoidalWithAnIllConditionedKStaysInTheSet)
  constexpr double kAdjugateCondition = 1e8;
  const bool wellConditioned = d > 0.0 && aNorm * adj.norm() < kAdjugateCondition * d;
  bool stick = false;
  Vec3 lambda0;
  // (|adj(A) b| without underflowing squares:
  // FrictionBlockScale.EllipsoidalWithATinyLDoesNotStick)
  const double n0Norm = rangeSafeNorm(n0);
  bool pivoted = !wellConditioned;
  if (wellConditioned) {
    stick = n0Norm <= d;
    // a stick's impulse -K^-1 b by a solve with K itself, so b + K lambda = 0
    // to round-off of |K| |lambda|
    // (FrictionBlockConditioning.StickWithAnIllConditionedKStopsTheSlip); where it and the
    // adjugate's -L Pi A^-1 b differ by more than kStickAgreement, d (a cubic in A's entries) may
    // be noise and the stick is decided again below
    // (FrictionBlockIllConditioned.EllipsoidalStickNeverLeavesTheLimitSet)
    constexpr double kStickAgreement = 1e-4;
    if (stick) {
      lambda0 =
          stickSolve(in.K, requirePositiveDefiniteFactor(0.5 * (in.K + in.K.transpose())), in.b);
      if (!lambda0.allFinite())
        lambda0 = -in.L * (Pi * (n0 / d));
      else if (!(rangeSafeNorm(lambda0 + in.L * (Pi * (n0 / d))) <=
                 kStickAgreement * rangeSafeNorm(lambda0)))
        pivoted = true;
    }
  }
  if (pivoted) {
    // (an ill-conditioned A only: a numerically singular K is refused here as
    // in the exact block; FrictionBlockConditioning.NumericallySingularKIsRefusedOrTheLaw)
    const Mat3 Ksym = 0.5 * (in.K + in.K.transpose());
    requireNotNumericallySingular(Ksym);
    lambda0 = stickSolve(in.K, requirePositiveDefiniteFactor(Ksym), in.b);
    const Vec3 w0 = -Pi.partialPivLu().solve(lambda0) / in.L;
    stick = lambda0.allFinite() && w0.allFinite() ? w0.norm() <= 1.0 : d > 0.0 && n0Norm <= d;
  }
  if (stick) {
    out.sticking = true;
    out.impulse = requireStopsTheSlip(in.K, in.b, lambda0);
    out.slip.setZero();
    return out;
  }
  auto f = [&](double r, double& df, Vec3& N) {
    N = (r * n2 + n1) * r + n0;
    const Vec3 dN = 2.0 * r * n2 + n1;
    const double p = ((r + t) * r + m) * r + d;
    const double dp = (3.0 * r + 2.0 * t) * r + m;
    const double nN = N.norm();
    df = (dp * nN - p * N.dot(dN) / nN) / (nN * nN);
    return p / nN - 1.0;
  };
  // r w = b - A w with |w| = 1 brackets the root by |b| -+ |A|_F
  // (FrictionBlockScale.FarFromUnitScaleIsTheLaw: a stale warm start)
  double lo = std::max(0.0, bNorm - aNorm), hi = scale;
  double r = std::max(lo, bNorm - t / 3.0);  // isotropic estimate
  if (in.warmSlip.norm() > lo && in.warmSlip.norm() < hi) r = in.warmSlip.norm();
  Vec3 N = in.b;
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it + 1;
    double df = 0.0;
    const double fr = f(r, df, N);
    if (fr < 0.0)
      lo = r;
    else
      hi = r;
    // f is relative (p / |N| - 1); the root r itself sets the scale of the
    // bracket and of the step, not |b| + |A| >> r for a long lever
    // (FrictionBlock.IsTheLawAtItsSlipAcrossTheLeverDomain)
    if (std::abs(fr) <= tol || hi - lo <= tol * hi) break;
    // safeguard: bisect, geometrically while the bracket spans orders of
    // magnitude (FrictionBlockScale.FarFromUnitScaleIsTheLaw: a stale warm start)
    const double mid =
        lo > 0.0 && hi > kGeometricBisection * lo ? std::sqrt(lo) * std::sqrt(hi) : 0.5 * (lo + hi);
    double next = df > 0.0 ? r - fr / df : mid;
    if (!(next > lo && next < hi)) next = mid;
    if (std::abs(next - r) <= tol * next) {
      r = next;
      N = (r * n2 + n1) * r + n0;  // (only N(r) is used from here on)
      break;
    }
    r = next;
  }
  Vec3 w = N.normalized();
  out.impulse = -in.L * (Pi * w);
  out.slip = in.b + in.K * out.impulse;
  // Backward error: the impulse -L Pi w with |w| = 1 is the exact solution
  // of the block with b - e, e = s - (s.w) w, if s.w >= 0. A root r off by
  // the tolerance leaves |e| ~ tol |A| (w = N / |N| is the normalised
  // (rI + A)^-1 b); past kBackwardErrorUlps that (kMinBackwardError for the
  // default tolerance) the Cayley-Hamilton sums, which hold det A and adj A,
  // have cancelled to noise (a K near singular), and the root is found again
  // with (rI + A)^-1 b by pivoted solves (backward stable, whatever A's
  // conditioning). Guarded by
  // FrictionBlockIllConditioned.EllipsoidalBlockWithANearSingularKIsTheLongDoubleSolution.
  constexpr double kBackwardErrorUlps = 100.0, kMinBackwardError = 1e-10;
  const double backwardTol = std::max(kBackwardErrorUlps * tol, kMinBackwardError) * scale;
  auto backwardError = [&] {
    const double along = out.slip.dot(w);
    return rangeSafeNorm(out.slip - std::max(along, 0.0) * w);
  };
  // The re-solves: phi(r) = 1 / |v| - 1, v = (rI + A)^-1 b, increasing in
  // r like f; phi' = v.(rI + A)^-1 v / |v|^3; bracketed and safeguarded as
  // above. First by pivoted LU of rI + A itself; where that misses too, by
  // the same root on the impulse's side (below), where K's diagonal scaling
  // applies; a block that misses even so is refused.
  if (!(backwardError() <= backwardTol)) {
    // (rI + A)^-1 x = Pi^-1 M(r)^-1 x / L with M(r) = K + (r / L) Pi^-1:
    // lambda = -L Pi w solves M(r) lambda = -b. M(r) is K plus a moderate
    // term, so scaled by D^-1 on both sides (D^2 its diagonal, at least K's)
    // it has K's unit-diagonal conditioning, not the spread of K's diagonal
    // that the plain rI + A carries. Only where the plain re-solve misses.
    // Guarded by
    // FrictionBlockConditioning.EllipsoidalWithANearSingularWideDiagonalKMatches50Digits.
    const Mat3 Pinv = Pi.inverse();
    for (const bool onImpulseSide : {false, true}) {
      if (onImpulseSide && !Pinv.allFinite()) break;
      double plo = std::max(0.0, bNorm - aNorm), phi = scale;
      double pr = std::max(plo, bNorm - t / 3.0);
      Vec3 v = in.b;
      for (int it = 0; it < kMaxIterations; ++it) {
        ++out.iterations;
        double g = 0.0, dg = 0.0;
        if (!onImpulseSide) {
          const Eigen::PartialPivLU<Mat3> lu(pr * Mat3::Identity() + A);
          v = lu.solve(in.b);
          const double vn = v.norm();
          g = 1.0 / vn - 1.0;
          dg = v.dot(lu.solve(v)) / (vn * vn * vn);
        } else {
          const Mat3 M = in.K + (pr / in.L) * Pinv;
          const Vec3 dInv =
              M.diagonal().cwiseAbs().cwiseMax(in.K.diagonal()).cwiseSqrt().cwiseInverse();
          const Eigen::PartialPivLU<Mat3> lu(dInv.asDiagonal() * M * dInv.asDiagonal());
          auto shiftedSolve = [&](const Vec3& x) {
            return Vec3(Pinv * Vec3(dInv.asDiagonal() * lu.solve(Vec3(dInv.asDiagonal() * x))) /
                        in.L);
          };
          v = shiftedSolve(in.b);
          const double vn = v.norm();
          g = 1.0 / vn - 1.0;
          dg = v.dot(shiftedSolve(v)) / (vn * vn * vn);
        }
        if (!std::isfinite(g) || g < 0.0)
          plo = pr;
        else
          phi = pr;
        if (std::abs(g) <= tol || phi - plo <= tol * phi) break;
        const double mid = plo > 0.0 && phi > kGeometricBisection * plo
                               ? std::sqrt(plo) * std::sqrt(phi)
                               : 0.5 * (plo + phi);
        double next = dg > 0.0 && std::isfinite(g) ? pr - g / dg : mid;
        if (!(next > plo && next < phi)) next = mid;
        pr = next;
      }
      w = v.normalized();
      out.impulse = -in.L * (Pi * w);
      out.slip = in.b + in.K * out.impulse;
      // |v| itself carries cond(rI + A) eps relative error (a backward stable
      // solve pins v's residual, not its norm), so the root only makes |v| = 1
      // to that noise, and w = v / |v| leaves e ~ that noise times |A v|.
      // Newton on the residual F(w, r) = b - L K Pi w - r w with w on the
      // sphere, whose bordered Jacobian [A + rI, w; w^T, 0] is regular where
      // A + rI is singular along the slip, brings e to the round-off of the
      // residual
      // (FrictionBlockIllConditioned.EllipsoidalBlockWithANearSingularKIsTheLongDoubleSolution).
      double rr = std::max(out.slip.dot(w), 0.0);
      // (quadratic convergence: a few steps reach kPolishTarget of the
      // backward tolerance, well inside it, or stop improving)
      constexpr int kMaxPolishSteps = 4;
      constexpr double kPolishTarget = 1e-3;
      for (int k = 0; k < kMaxPolishSteps && !(backwardError() <= kPolishTarget * backwardTol);
           ++k) {
        Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
        M.topLeftCorner<3, 3>() = A + rr * Mat3::Identity();
        M.block<3, 1>(0, 3) = w;
        M.block<1, 3>(3, 0) = w.transpose();
        Eigen::Vector4d rhs;
        rhs << out.slip - rr * w, 0.0;
        const Eigen::Vector4d delta = M.fullPivLu().solve(rhs);
        if (!delta.allFinite()) break;
        const Vec3 wNew = (w + delta.head<3>()).normalized();
        const Vec3 impulseNew = -in.L * (Pi * wNew);
        const Vec3 slipNew = in.b + in.K * impulseNew;
        const double eNew = rangeSafeNorm(slipNew - std::max(slipNew.dot(wNew), 0.0) * wNew);
        if (!(eNew < backwardError())) break;
        w = wNew, out.impulse = impulseNew, out.slip = slipNew, rr = std::max(rr + delta(3), 0.0);
      }
      if (backwardError() <= backwardTol) break;
    }
    // (a block that misses it even so is singular to round-off)
    if (!(backwardError() <= backwardTol))
      throw Error(
          "friction block matrix K is numerically singular (the ellipsoidal slip misses its law "
          "by " +
          internal::formatDouble(backwardError()) + " against a slip scale " +
          internal::formatDouble(scale) + ")");
  }
  return out;
}

}  // namespace patchspin::internal
