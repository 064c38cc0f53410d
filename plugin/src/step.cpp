// The implicit 3-DOF friction block (DESIGN item 4); see step.hpp.
#include <patchspin/step.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace patchspin {

namespace {

// Newton iterations stop when the residual is below this fraction of the
// problem's own slip scale |b| + L |K|: ~100 ulps, well below any physical
// effect yet reachable in double precision.
constexpr double kRelativeTolerance = 1e-14;
constexpr int kMaxIterations = 100;

// |v| as sqrt(v.squaredNorm()) where that sum of squares is a normal, finite
// double (then within a few ulps of the exact norm: n + 1 roundings of the
// squares and the sum, halved by the sqrt), Eigen's stableNorm (scaled, no
// under- or overflow) only outside that range; the zero vector is 0. The
// plain form saves stableNorm's blockwise scaling and divisions on every
// block, which the time profile showed. A matrix's (Frobenius) norm goes
// through internal::stableMatrixNorm (Eigen's stableNorm of a fixed-size
// matrix aborts without NDEBUG).
double stableNormOf(const Mat3& m) { return internal::stableMatrixNorm(m); }
double stableNormOf(const Vec3& v) { return v.stableNorm(); }
template <typename Derived>
double rangeSafeNorm(const Eigen::MatrixBase<Derived>& v) {
  const double s = v.squaredNorm();
  if (s >= std::numeric_limits<double>::min() && s <= std::numeric_limits<double>::max()) return std::sqrt(s);
  if (v.isZero(0.0)) return 0.0;
  return stableNormOf(v.eval());
}

void validate(const FrictionBlockInput& in) {
  // (the finiteness tests inline, the calls that build the message only
  // where one fails: five calls cost ~2.5 % of a block solve)
  if (!in.b.allFinite()) internal::requireFinite(in.b, "friction block free slip b");
  if (!in.warmSlip.allFinite()) internal::requireFinite(in.warmSlip, "friction block warm-start slip");
  if (!in.warmGauge.allFinite()) internal::requireFinite(in.warmGauge, "friction block warm-start gauge slip");
  if (!in.K.allFinite()) throw Error("friction block matrix K must be finite");
  // K symmetric (SPD, as documented), to kSymmetryTol of its largest entry:
  // both blocks work with its symmetric part, so an asymmetric K stuck with
  // lambda = -Ksym^-1 b where b + K lambda != 0 (found by fuzzing: K_xy =
  // 2.1e-4 against K_yx = 0.5). 1e-10 leaves room for a K assembled in
  // floating point (a few ulps of asymmetry) and keeps the stick residual
  // of the asymmetric part, |K - K^T| |lambda| / 2, at 1e-10 of |K| |lambda|.
  constexpr double kSymmetryTol = 1e-10;
  if (!((in.K - in.K.transpose()).cwiseAbs().maxCoeff() <= kSymmetryTol * in.K.cwiseAbs().maxCoeff()))
    throw Error("friction block matrix K must be symmetric (positive definite)");
  // K's diagonal spanning at most kMaxDiagonalSpan: beyond ~1e36 both blocks
  // lose every digit (measured: 1000 blocks per two decades, K = D^1/2 C
  // D^1/2 with C unit-diagonal and well conditioned, b at each row's own
  // scale; the law at the slip to 1e-14 up to a span of 1e34, then 0.8 to
  // 1.2 of the set off it from 1e36 on, both laws; the fuzz target found
  // such errors from 2e82). K's diagonal holds the slip mobilities of the
  // force rows (1/m and r^2/I terms) and of the spin row (rho^2/I terms) of
  // the same two bodies, so its span is a ratio of lengths squared: within
  // the lever domain (step.hpp) it stays below ~1e20 even for a body 1e5
  // times larger than its patch. 1e30 leaves a margin of 1e6 below the
  // measured onset. (Non-positive diagonals are left to the positive
  // definiteness checks.)
  constexpr double kMaxDiagonalSpan = 1e30;
  const Vec3 kd = in.K.diagonal();
  if (kd.minCoeff() > 0.0 && !(kd.maxCoeff() <= kMaxDiagonalSpan * kd.minCoeff()))
    throw Error("friction block out of range: the diagonal of K spans more than 1e30 (" +
                internal::formatDouble(kd.minCoeff()) + " to " + internal::formatDouble(kd.maxCoeff()) + ")");
  if (!std::isfinite(in.L)) internal::requireFinite(in.L, "friction block bound L");
  if (in.L < 0.0) throw Error("friction block bound L must be >= 0: got " + internal::formatDouble(in.L));
  if (!std::isfinite(in.tolerance)) internal::requireFinite(in.tolerance, "friction block tolerance");
  if (in.tolerance < 0.0 || in.tolerance >= 1.0)
    throw Error("friction block tolerance must lie in [0, 1): got " + internal::formatDouble(in.tolerance));
}

// K (symmetric, positive diagonal) scaled to a unit diagonal must have a
// condition number below kSingularCondition: K^-1 then carries eps cond ~
// 2e-6 relative error at most, the resolution to which the blocks' answers
// are checked (the cofactor inverse is invariant under that scaling, so this
// is its error bound; found by fuzzing: at a scaled cond of 3.3e11 the
// ellipsoidal block was 1.07 of L |Pi| off the law, and at ~1e34 the exact
// one 0.9 of L |q|). The scaled cond is at most 3 times the plain
// |K| |K^-1| (van der Sluis), so callers test that first.
constexpr double kSingularCondition = 1e10;
void requireNotNumericallySingular(const Mat3& Ksym, const Mat3& Kinv) {
  const Vec3 d = Ksym.diagonal().cwiseAbs().cwiseSqrt();
  const Mat3 scaledK = d.cwiseInverse().asDiagonal() * Ksym * d.cwiseInverse().asDiagonal();
  const Mat3 scaledKinv = d.asDiagonal() * Kinv * d.asDiagonal();
  const double cond = scaledK.norm() * scaledKinv.norm();
  if (!(cond < kSingularCondition))
    throw Error("friction block matrix K is numerically singular (condition number " +
                internal::formatDouble(cond) + " after scaling to a unit diagonal)");
}

// K's symmetric part factored by Cholesky (LLT): the positive definiteness
// test and K^-1 of both blocks. Cholesky succeeds, and its solves are
// accurate, to the condition number of K scaled to a unit diagonal (van der
// Sluis, Demmel), whatever the diagonal's spread. The leading minors
// (Sylvester) and the cofactor inverse are not: their products cancel at
// eps |K|^2 and eps |K|^3 (found by fuzzing: K = a 1 1^T + delta I with a =
// 1.7e16 and delta = 7.5e7, unit-diagonal cond 6.7e8, whose computed
// determinant came out negative: refused as not positive definite).
//
// The factor is Eigen's LLT with its unblocked lower factorisation written
// out for the 3x3 case (the same operations in the same order, failing at
// the first pivot <= 0 as Eigen does, the L1 norm for rcond() as its
// compute() takes it): through Eigen's dynamic-size blocks it cost ~320
// instructions on every exact block solve and every stick.
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
Eigen::LLT<Mat3> requirePositiveDefiniteFactor(const Mat3& Ksym) {
  const Llt3 llt(Ksym);
  if (!(llt.info() == Eigen::Success && Ksym.diagonal().minCoeff() > 0.0 &&
        llt.matrixLLT().allFinite()))
    throw Error(
        "friction block matrix K is not positive definite (or singular to round-off: its Cholesky "
        "factorisation fails)");
  return llt;
}
// Solves with the 3x3 factor written out (forward and back substitution
// on L = llt.matrixL(), L L^T = K): Eigen's solve() goes through
// dynamic-size triangular blocks, ~2000 instructions for K^-1 on every
// exact block solve, where the substitutions are ~60 flops.
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

// -K^-1 b, a stick's impulse: by K's Cholesky factor, then one step of
// refinement with K itself (its symmetric part was factored; K may be
// asymmetric to 1e-10). Partial pivoting is not invariant under K's
// diagonal scaling: with K = diag-heavy (K_zz = 2e12 against K_xx = 1.5e-6
// and K_xz = -0.014) it pivoted on the z row, and the solve returned a
// force of 1.6e-8 where -K^-1 b has 5.8e-12 (found by fuzzing: a stick 1.65
// times outside L E).
Vec3 stickSolve(const Mat3& K, const Eigen::LLT<Mat3>& llt, const Vec3& b) {
  const Vec3 lambda = -choleskySolve(llt, b);
  const Vec3 refined = lambda - choleskySolve(llt, b + K * lambda);
  return refined.allFinite() ? refined : lambda;
}

// A stick's impulse must stop the slip, b + K lambda = 0, to the round-off
// of a backward-stable solve (a few eps of |b| + |K| |lambda|; kStickResidual
// leaves 1e5 of room). A K that passed the cheaper singularity tests but is
// singular to round-off misses it by far (found by fuzzing: K with entries
// 1.6e20 to 2.2e20 whose unit-diagonal form has an off-diagonal 1 - 1e-16,
// positive leading minors by round-off: the ellipsoidal block stuck with
// b + K lambda = 0.7 against |b| = 0.7): refused as numerically singular.
constexpr double kStickResidual = 1e-10;
Vec3 requireStopsTheSlip(const Mat3& K, const Vec3& b, const Vec3& lambda) {
  const double residual = rangeSafeNorm(b + K * lambda);
  if (!(residual <= kStickResidual * (rangeSafeNorm(b) + rangeSafeNorm(K) * rangeSafeNorm(lambda))))
    throw Error("friction block matrix K is numerically singular (a stick leaves b + K lambda = " +
                internal::formatDouble(residual) + " against |b| = " + internal::formatDouble(b.stableNorm()) + ")");
  return lambda;
}

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
  // difference of at most two products. The forms above, (t^2 - tr A^2) / 2
  // and A^2 b - t A b, cancel to the scale of |A|^2: with an ill-scaled block
  // (eigenvalues 1e-16 to 1e7: a long lever, fuzz finding) they lost every
  // digit of m and adj(A) b, and the root was far off
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
  // |A|^2 beyond double's range (the old form squared A and overflowed to a
  // NaN impulse, refused): refuse it here, before the iteration runs on inf
  if (!std::isfinite(scale) || !std::isfinite(m) || !std::isfinite(d) || !n0.allFinite() ||
      !n1.allFinite()) {
    throw Error("friction block out of range: L K Pi overflows double (K, b or L too large)");
  }
  // stick iff lambda0 = -K^-1 b = -L Pi w0 has |w0| <= 1, by pivoted solves
  // with K and Pi themselves (backward stable): adj(A) b / d decided wrongly
  // and left b + K lambda at 1e6 times round-off for an ill-conditioned K
  // (entries 0.5 to 9e19; found by fuzzing). A well-conditioned A,
  // |A| |A^-1| = |A| |adj A| / d below kAdjugateCondition, keeps the
  // adjugate test (two 3x3 LU solves cost as much as the rest of a slipping
  // solve): its error is ~cond(A) eps relative, far inside the Newton
  // tolerance.
  constexpr double kAdjugateCondition = 1e8;
  const bool wellConditioned = d > 0.0 && aNorm * adj.norm() < kAdjugateCondition * d;
  bool stick = false;
  Vec3 lambda0;
  // (|adj(A) b| without squares: at unit scale with a tiny L, adj A ~ 1e-196
  // and |n0|^2 underflowed to 0 <= d, a false stick with lambda = -K^-1 b
  // 1e90 times outside the set; found by fuzzing, b = 1e74 against L = 1e-8)
  const double n0Norm = rangeSafeNorm(n0);
  bool pivoted = !wellConditioned;
  if (wellConditioned) {
    stick = n0Norm <= d;
    // the impulse -K^-1 b by a pivoted solve with K itself (backward
    // stable: b + K lambda = 0 to round-off of |K| |lambda|); -L Pi A^-1 b
    // from the adjugate left b + K lambda at cond(A) eps, 1e-8 of the scale
    // for a K with eigenvalues 5.9e7 and 2.6e3 (found by fuzzing). Sticks
    // only.
    // (where the two differ by more than kStickAgreement, the stick is
    // decided again by pivoted solves below: d is a cancelled cubic in A's
    // entries, and for a K singular to round-off it is noise while the
    // condition test on it still passes; found by fuzzing, K with entries
    // 1.6e20 whose unit-diagonal form is indefinite at round-off stuck with
    // an impulse 9.6 times outside L |Pi|)
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
    // (an ill-conditioned A only: a numerically singular K, as the exact
    // block refuses it, has no digits in this answer either; found by
    // fuzzing: K with entries 3e-16 to 9.9e19 whose y-z block is singular
    // once scaled to a unit diagonal returned a slip of 1.4e19 driven by the
    // impulse, 1.07 of L |Pi| off the law)
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
  // r w = b - A w with |w| = 1 brackets the root by |b| -+ |A|_F (the lower
  // end found by fuzzing: from a stale warm start 1e-88 times the root,
  // |N(r)| underflowed and f(r) = inf moved the upper end below the root)
  double lo = std::max(0.0, bNorm - aNorm), hi = scale;
  double r = std::max(lo, bNorm - t / 3.0);  // isotropic estimate
  if (in.warmSlip.norm() > lo && in.warmSlip.norm() < hi) r = in.warmSlip.norm();
  Vec3 N = in.b;
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it + 1;
    double df = 0.0;
    const double fr = f(r, df, N);
    if (fr < 0.0) lo = r; else hi = r;
    // f is relative (p / |N| - 1); the root r itself sets the scale of the
    // bracket and of the step (relative to |b| + |A| a long lever, |A| >> r,
    // stopped far from the root: found by fuzzing)
    if (std::abs(fr) <= tol || hi - lo <= tol * hi) break;
    // safeguard: bisect, geometrically while the bracket spans orders of
    // magnitude (found by fuzzing: a stale warm start 1e-88 times the root,
    // where |N(r)| underflowed and 100 linear bisections did not reach it)
    const double mid = lo > 0.0 && hi > 4.0 * lo ? std::sqrt(lo) * std::sqrt(hi) : 0.5 * (lo + hi);
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
  // default tolerance) the Cayley-Hamilton sums have no digits: p(r) and
  // N(r) hold det A and adj A, cubic and quadratic in A's entries, which
  // cancel to noise for a K near singular (found by fuzzing: K = 0.75 1 1^T
  // + 1e-8 I, unit-diagonal cond 2.3e8, slipped with |s| = 0.19 where the
  // true slip is 1.1e-9: the impulse 1.28 of L |Pi| off the law at its
  // slip). There the root is found again with (rI + A)^-1 b by pivoted
  // solves (backward stable, whatever A's conditioning).
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
    // that the plain rI + A carries (found by fuzzing: K with a diagonal
    // spanning 1.2e27 and a unit-diagonal condition of 1.9e9, whose pivoted
    // rI + A left the slip 4.3e-7 of the slip scale off its law, eps times
    // that condition; this form: 2.5e-17 of it, the impulse within 6e-17 of
    // L |Pi| of the block solved in 50 digits). Only where the plain
    // re-solve misses: blocks it solves are unchanged.
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
          const Vec3 dInv = M.diagonal().cwiseAbs().cwiseMax(in.K.diagonal()).cwiseSqrt().cwiseInverse();
          const Eigen::PartialPivLU<Mat3> lu(dInv.asDiagonal() * M * dInv.asDiagonal());
          auto shiftedSolve = [&](const Vec3& x) {
            return Vec3(Pinv * Vec3(dInv.asDiagonal() * lu.solve(Vec3(dInv.asDiagonal() * x))) / in.L);
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
        const double mid =
            plo > 0.0 && phi > 4.0 * plo ? std::sqrt(plo) * std::sqrt(phi) : 0.5 * (plo + phi);
        double next = dg > 0.0 && std::isfinite(g) ? pr - g / dg : mid;
        if (!(next > plo && next < phi)) next = mid;
        pr = next;
      }
      w = v.normalized();
      out.impulse = -in.L * (Pi * w);
      out.slip = in.b + in.K * out.impulse;
      // |v| itself carries cond(rI + A) eps relative error (a backward stable
      // solve pins v's residual, not its norm), so the root only makes |v| = 1
      // to that noise, and w = v / |v| leaves e ~ that noise times |A v|
      // (found: 1.1e-9 for a slip of 1.1e-9 at cond 2e8). Newton on the
      // residual F(w, r) = b - L K Pi w - r w with w on the sphere, whose
      // bordered Jacobian [A + rI, w; w^T, 0] is regular where A + rI is
      // singular along the slip, brings e to the round-off of the residual.
      double rr = std::max(out.slip.dot(w), 0.0);
      for (int k = 0; k < 4 && !(backwardError() <= 1e-3 * backwardTol); ++k) {
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

// Exact law: maximum dissipation, q(w) = argmin_{q in E} q.w. The block is
// the minimum over the slip s of the convex potential
//   D(s) = 1/2 (s - b)^T K^-1 (s - b) + L g(s),   g(s) = -q(s^) . s,
//   grad D = K^-1 (s - b) - L q(s^),   Hess D = K^-1 - L J / |s|,
// J = dq/dw at s^ (tangential). s = 0 (stick) iff -K^-1 b lies in L E; that
// is tested first through the gauge of E along lambda0 = -K^-1 b: find w with
// q(w) parallel to lambda0 (Newton on the sphere, started from the
// ellipsoidal inverse), then stick iff |lambda0| <= L |q(w)|.
// (plainCondition: |K|_F |K^-1|_F of K's symmetric part, for
// requireVerifiedExactSlip; set before any slip is returned)
FrictionBlockResult solveExact(const FrictionPatch& patch, const FrictionBlockInput& in,
                               double* plainCondition) {
  FrictionBlockResult out;
  const double tol = in.tolerance > 0.0 ? in.tolerance : kRelativeTolerance;
  // positive definite by Cholesky, then the inverse from that factor (see
  // requirePositiveDefiniteFactor)
  const Mat3 Ksym = 0.5 * (in.K + in.K.transpose());
  const Eigen::LLT<Mat3> kLlt = requirePositiveDefiniteFactor(Ksym);
  const double det = kLlt.matrixLLT().diagonal().prod() * kLlt.matrixLLT().diagonal().prod();
  // a diagonal spanning more than kMaxDiagonalSpread is out of this
  // solver's range: its slip potential weighs the slip's round-off along the
  // soft directions by K^-1 up to 1e300 (found by fuzzing: K = diag(1e10,
  // 1.5e10, 1.3e-306), where every trial's potential and gradient came out
  // 1e258 or inf and the block returned a slip of 7e8 driven by the impulse
  // itself). A unit-scaled K within it has |K|, |K^-1| < 1e200.
  constexpr double kMaxDiagonalSpread = 1e200;
  if (!(Ksym.diagonal().maxCoeff() < kMaxDiagonalSpread * Ksym.diagonal().minCoeff()))
    throw Error("friction block out of range: the diagonal of K spans more than 1e200 (" +
                internal::formatDouble(Ksym.diagonal().minCoeff()) + " to " +
                internal::formatDouble(Ksym.diagonal().maxCoeff()) + ")");
  const Mat3 Kinv = inverseOf(kLlt);
  // (found by fuzzing: entries of 1e148 with K_xx = 6e17, det(K) = inf and
  // K^-1 = 0, so K^-1 b = 0 and the block stuck with a zero impulse)
  if (!std::isfinite(det) || !Kinv.allFinite())
    throw Error("friction block out of range: det K overflows double (" + internal::formatDouble(det) + ")");
  // numerically singular K: the slip potential below needs K^-1 (found by
  // fuzzing: K = A A^T + d I with cond ~1e34 gave a slip along its largest
  // eigenvector driven by the impulse itself, off the law by 0.9 of L |q|);
  // the common path pays one product of two norms
  const double cond = Ksym.norm() * Kinv.norm();
  *plainCondition = cond;
  if (!(cond < kSingularCondition / 3.0)) requireNotNumericallySingular(Ksym, Kinv);
  // lambda0 = -K^-1 b by the Cholesky factor (stickSolve): the stick is
  // decided with the impulse it returns (the cofactor inverse cancelled to
  // K^-1 b = 0 for K = 0.75 (1 1^T) + 1e-8 I, and had no digits for a K
  // singular to round-off in two 2x2 minors, where a stick decided with it
  // returned a pivoted solve's force of 4.6e15 against L = 1e-8; both found
  // by fuzzing). A stick verifies b + K lambda = 0 (requireStopsTheSlip).
  const Vec3 lambda0 = stickSolve(in.K, kLlt, in.b);
  auto stickImpulse = [&] { return requireStopsTheSlip(in.K, in.b, lambda0); };
  const double lambda0Norm = lambda0.norm();
  if (lambda0Norm == 0.0) {
    out.sticking = true;
    return out;
  }

  // quick stick: the ellipsoidal Pi matches the exact law at the three
  // fitting motions, q(e_i) = -Pi e_i (Eq. (37)-(39)), and the law is odd, so
  // the convex limit set E contains the octahedron conv{+-Pi e_i}: lambda0
  // inside L times it, |Pi^-1 lambda0|_1 <= L, sticks without the gauge test
  // (a body at rest in a pile, the common case there)
  {
    const Mat3 Pinv = patch.Pi().inverse();
    const Vec3 c = Pinv * lambda0;
    if (c.allFinite() && c.lpNorm<1>() <= in.L) {
      out.sticking = true;
      out.impulse = stickImpulse();
      out.slip.setZero();
      return out;
    }
  }

  // support gap of lambda0 against L E along u (see the slip branch below);
  // h(u) < 0 for some u proves lambda0 outside L E: the block slips
  const Vec3 Kinvb = Kinv * in.b;
  auto gap = [&](const Vec3& u, Vec3& qu, Mat3* ju) {
    qu = patch.unitQ(Model::Exact, u, ju);
    return -u.dot(Kinvb) - in.L * qu.dot(u);
  };
  // cheap certificates first, one evaluation of the law each: the
  // warm-start slip, else the ellipsoidal solution. A block that keeps
  // slipping, the common case inside solver iterations, then skips the
  // gauge test below, and its evaluation (with the Jacobian) also starts
  // the Newton iteration.
  Vec3 bestU = in.b.normalized(), bestQ = Vec3::Zero();
  Mat3 bestJ = Mat3::Zero();
  bool bestHasJ = false;
  double bestScore = 0.0, bestH = 0.0;  // most negative h / |u|_{K^-1}, its h
  auto scoreCandidate = [&](const Vec3& u, bool withJ) {
    Vec3 qu;
    Mat3 ju;
    const double h = gap(u, qu, withJ ? &ju : nullptr);
    const double score = h / std::sqrt(u.dot(Kinv * u));
    if (score < bestScore) {
      bestScore = score, bestU = u, bestQ = qu, bestH = h, bestHasJ = withJ;
      if (withJ) bestJ = ju;
    }
  };
  if (in.warmSlip.norm() > 0.0) scoreCandidate(in.warmSlip.normalized(), true);
  if (!(bestScore < 0.0)) {
    // (only a candidate: where L K Pi overflows, the ellipsoidal solve's
    // refusal is not the exact block's; found by fuzzing: a couple of 6e228
    // on a 0.5 m disk, whose exact law is still in range)
    Vec3 ellipsoidalSlip = Vec3::Zero();
    try {
      ellipsoidalSlip = solveEllipsoidal(patch.Pi(), in).slip;
    } catch (const Error&) {
    }
    if (ellipsoidalSlip.norm() > 0.0 && ellipsoidalSlip.allFinite()) scoreCandidate(ellipsoidalSlip.normalized(), true);
  }
  const bool slipProven = bestScore < 0.0;

  // gauge of E along lambda0: residual = component of q(w) across lambda0
  const Vec3 l = lambda0 / lambda0Norm;
  Vec3 e1 = l.unitOrthogonal();
  Vec3 e2 = l.cross(e1);
  Vec3 w = -l;
  if (!slipProven) {
    // from the caller's previous boundary point (inside solver iterations
    // lambda0 turns little between visits), else the ellipsoidal estimate
    // (scaled by its largest entry: only its direction counts, and its norm
    // may under- or overflow)
    const double warmMax = in.warmGauge.cwiseAbs().maxCoeff();
    if (warmMax > 0.0) {
      w = in.warmGauge / warmMax;
    } else {
      w = -(patch.Pi().fullPivLu().solve(l));  // ellipsoidal: q = -Pi w
    }
    if (!(w.norm() > 0.0) || !w.allFinite()) w = -l;
    w.normalize();
  }
  Vec3 q;
  Mat3 J;
  bool gaugeFound = false;
  // The law's own round-off is ~1e-14 (rms) to ~5e-13 (worst) of |q| (second
  // differences of q along w, measured on the step tests' patches), so a
  // residual near the tolerance can be noise: once it grows back from an
  // iterate already below kGaugeNoise |q|, the Newton steps only move w
  // within that noise, and the smaller of the two is the boundary point
  // (its q off lambda0 by that residual: the stick decision, |lambda0|
  // against L |q(w)|, moves by its square). (Found by a warm start at the
  // converged gauge point that, renormalised, sat 1.06e-14 off and took four
  // steps of 5e-14 rad, residuals 1.1e-14 to 2.1e-14.)
  constexpr double kGaugeNoise = 1e-12;
  Vec3 prevW = w, prevQ = Vec3::Zero();
  double prevRes = INFINITY;
  for (int it = 0; it < kMaxIterations && !slipProven; ++it) {
    q = patch.unitQ(Model::Exact, w, &J);
    const Eigen::Vector2d res(e1.dot(q), e2.dot(q));
    if (res.norm() <= tol * q.norm() && q.dot(l) > 0.0) {
      gaugeFound = true;
      out.gaugeSlip = w, out.gaugeValue = q;
      break;
    }
    if (res.norm() >= prevRes && prevRes <= kGaugeNoise * prevQ.norm() && prevQ.dot(l) > 0.0) {
      gaugeFound = true;
      w = prevW, q = prevQ;
      out.gaugeSlip = w, out.gaugeValue = q;
      break;
    }
    prevW = w, prevQ = q, prevRes = res.norm();
    // tangent basis at w and the 2x2 Newton system
    const Vec3 t1 = w.unitOrthogonal(), t2 = w.cross(t1);
    Eigen::Matrix2d Jr;
    Jr << e1.dot(J * t1), e1.dot(J * t2), e2.dot(J * t1), e2.dot(J * t2);
    Eigen::Vector2d step = -Jr.fullPivLu().solve(res);
    if (!step.allFinite()) step = -res / (q.norm() + 1e-300);
    // damp: at most a quarter turn per iteration
    const double len = step.norm();
    if (len > 0.5) step *= 0.5 / len;
    w = (w + step[0] * t1 + step[1] * t2).normalized();
    out.iterations = it + 1;
  }
  // (only where the iteration found q(w) along lambda0: found by fuzzing, a
  // long lever (max|r| / rho = 5e7) kept it from converging, and the last
  // q(w), mostly torque, made a force 2.8 L look inside L E; otherwise the
  // slip branch below decides, with its own stick fallback)
  if (!slipProven && gaugeFound && lambda0Norm <= in.L * q.norm()) {
    out.sticking = true;
    out.impulse = stickImpulse();
    out.slip.setZero();
    return out;
  }

  // slip. Along the ray s = r u, D is a quadratic in r, minimal at
  //   r*(u) = -h(u) / (u^T K^-1 u),   h(u) = lambda0.u - L q(u).u
  // (h is the support gap of lambda0 against L E), and D(r* u) = D(0) -
  // h(u)^2 / (2 u^T K^-1 u). So the slip lies in the cone h < 0, where D
  // restricted to radially optimal points is smooth. Start from the best of a
  // few candidate directions (warm start, ellipsoidal solution, b, the gauge
  // direction, and a coarse sphere if none has h < 0), then damped Newton on
  // D with every trial moved to r* on its ray; trials outside the cone are
  // rejected, which keeps the iterates off the kink of D at s = 0.
  if (!slipProven) {
    scoreCandidate(in.b.normalized(), false);
    scoreCandidate(w, false);
    // -lambda0 = K^-1 b: its gap is L h_E(l) - |lambda0|, the plain gauge
    // test along lambda0 (found by fuzzing: with a long lever the support of
    // E is ~1e8 in every direction with a torque part, so b and the sphere
    // samples all had positive gaps while a force of 2.8 L was outside)
    scoreCandidate(-l, false);
    // and its force and its torque part alone: E's extent along torque and
    // along force differ by the lever max|r| / rho, so with a long (short)
    // lever a direction with any torque (force) part has a huge support and
    // the separating directions lie in the force plane (on the torque axis)
    // (found by fuzzing: lever 5e7, lambda0 = (-1, -1, -1) stuck at L = 0.5)
    const Vec3 forcePart(-l.x(), -l.y(), 0.0), torquePart(0.0, 0.0, -l.z());
    if (forcePart.norm() > 0.0) scoreCandidate(forcePart.normalized(), false);
    if (torquePart.norm() > 0.0) scoreCandidate(torquePart.normalized(), false);
  }
  if (!(bestScore < 0.0)) {
    // golden-angle (Fibonacci) sphere, deterministic
    std::vector<Vec3> sphere;
    constexpr int kSphereSamples = 128;
    for (int i = 0; i < kSphereSamples; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / kSphereSamples;
      const double rxy = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = 2.39996322972865332 * i;
      sphere.emplace_back(rxy * std::cos(phi), rxy * std::sin(phi), z);
    }
    for (const Vec3& u : sphere) scoreCandidate(u, false);
  }
  if (!(bestScore < 0.0)) {
    // no direction with a support gap: lambda0 is inside L E after all
    out.sticking = true;
    out.impulse = stickImpulse();
    out.slip.setZero();
    return out;
  }
  auto radialOptimum = [&](const Vec3& x, Vec3& qx, Mat3& jx, bool& inCone) {
    const Vec3 u = x.normalized();
    const double h = gap(u, qx, &jx);
    inCone = h < 0.0;
    return Vec3((-h / u.dot(Kinv * u)) * u);
  };
  auto potential = [&](const Vec3& x, const Vec3& qx) {
    const Vec3 d = x - in.b;
    return 0.5 * d.dot(Kinv * d) - in.L * qx.dot(x);
  };
  bool inCone = true;
  // start at the radial optimum of the best candidate (evaluated already if
  // it came with its Jacobian)
  Vec3 s;
  if (bestHasJ) {
    q = bestQ, J = bestJ;
    s = (-bestH / bestU.dot(Kinv * bestU)) * bestU;
  } else {
    s = radialOptimum(bestU, q, J, inCone);
  }
  double D = potential(s, q);
  Vec3 grad = Kinv * (s - in.b) - in.L * q;
  const double scale = in.b.norm() + in.L * in.K.norm();
  // D is O(|b|^2 / |K|); its decrease is invisible below this round-off level,
  // where the Newton steps are judged by the gradient instead
  const double roundOffD = 1e-13 * (std::abs(D) + in.b.dot(Kinvb));
  // With a badly scaled K (diagonal entries kBadlyScaledK apart) that level
  // is wrong: b's part along K's stiff directions dominates b^T K^-1 b while
  // the slip there equals b's to round-off and adds nothing to D (found by
  // fuzzing: K = diag(1e10, 1.5e10, 2e-129), b_z = 0.5, b^T K^-1 b = 1e128,
  // so every trial counted as flat and the iterates wandered off to a slip
  // of 6e9 driven by the impulse itself). There the round-off of each
  // evaluation is taken from its own terms.
  constexpr double kBadlyScaledK = 1e8;
  const double kDiagMax = Ksym.diagonal().maxCoeff(), kDiagMin = Ksym.diagonal().minCoeff();
  const bool badlyScaledK = !(kDiagMax < kBadlyScaledK * kDiagMin);
  const Mat3 absKinv = badlyScaledK ? Mat3(Kinv.cwiseAbs()) : Mat3::Zero();
  auto roundOffAt = [&](const Vec3& x, const Vec3& qx) {
    if (!badlyScaledK) return 0.5 * roundOffD;
    const Vec3 d = (x - in.b).cwiseAbs();
    return 1e-13 * (d.dot(absKinv * d) + in.L * qx.cwiseAbs().dot(x.cwiseAbs()));
  };
  for (int it = 0; it < kMaxIterations; ++it) {
    ++out.iterations;
    // converged: the slip b + K L q(s^) equals s to ~1e-14 of the slip scale
    if ((in.K * grad).norm() <= tol * scale) break;
    const Mat3 H = Kinv - (in.L / s.norm()) * 0.5 * (J + J.transpose());
    Vec3 dir = -(H.inverse() * grad);  // 3x3: cofactors; non-descent caught below
    const bool newton = dir.allFinite() && dir.dot(grad) < 0.0;
    // The last Newton step taken with q linearised (below), where it is in
    // the quadratic regime of `level`: |dir| <= sqrt(level) |s| and |J du|
    // <= sqrt(level) |q|.
    auto linearisedStep = [&](double level) {
      if (!newton || !(dir.norm() <= std::sqrt(level) * s.norm())) return false;
      const Vec3 u = s.normalized();
      const Vec3 du = (dir - u * u.dot(dir)) / s.norm();
      const Vec3 dq = J * du;
      if (!(dq.norm() <= std::sqrt(level) * q.norm())) return false;
      q += dq;
      ++out.iterations;
      return true;
    };
    if (!newton) {
      dir = -in.K * grad;  // fall back to descent
    } else if (dir.norm() <= std::sqrt(tol) * s.norm()) {
      // last Newton step: the residual after it is O((|dir| / |s|)^2) <= tol
      // of the slip scale (quadratic convergence), so take it without a new
      // evaluation of the law, with q linearised along the sphere:
      //   q(u + du) = q(u) + J du + O(|du|^2)
      // Only while J du is itself small: with a long lever (max|r| / rho ~
      // 1e7) J is huge and the linearised q left the limit set (found by
      // fuzzing: |impulse_xy| = 1.28 L); then the step is taken in full below.
      // du to first order, the step's part across s over |s|: the difference
      // of the two unit vectors loses its digits once |dir| / |s| nears eps,
      // and with a long lever the law turns across angles of ~1e-11, |J| up to
      // ~1e11 (found by fuzzing: a 1.6 m polygon 2,094 m from O, |dir| / |s|
      // = 1.7e-16, where the difference was one ulp of s^ and J times it
      // moved q by 2.3e-9 the wrong way: the slip b + K L q then sat 1e-9
      // off the iterate, and the law there 0.029 off q).
      if (linearisedStep(tol)) break;
    }
    // backtracking: sufficient decrease of D, or (at round-off level of D) of |grad D|
    // (down to t = 2^-kMaxHalvings: with a badly scaled K the descent
    // fallback -K grad can be 1e18 times too long along K's stiff direction;
    // found by fuzzing: K_zz = 7.4e9 against |s| = 1e-8 and a lever of 5e7,
    // where 60 halvings rejected every trial and the block returned the warm
    // start's q, 1.3 of the set off the law at its slip. Costs evaluations
    // only when trials keep failing.)
    constexpr int kMaxHalvings = 200;
    double t = 1.0;
    bool accepted = false;
    for (int k = 0; k < kMaxHalvings && !accepted; ++k, t *= 0.5) {
      Vec3 sNew = s + t * dir;
      if (!(sNew.norm() > 0.0)) continue;
      Vec3 qNew;
      Mat3 jNew;
      // (a trial where the law's Jacobian leaves double's range, with a
      // pressure near overflow, is rejected like one outside the cone)
      try {
        sNew = radialOptimum(sNew, qNew, jNew, inCone);
      } catch (const Error&) {
        continue;
      }
      if (!inCone) continue;
      // a trial that leaves s where it is (t |dir| below its ulps, or the
      // radial optimum rounding back to s) cannot make progress, nor can
      // shorter ones: accepting it only repeats the iteration (found by
      // fuzzing: the last 93 of 100 iterations on one slip, each accepting
      // t = 2^-22, where the decrease test's D + 1e-4 t grad.dir rounded to D)
      if (sNew == s) break;
      const double DNew = potential(sNew, qNew);
      const Vec3 gradNew = Kinv * (sNew - in.b) - in.L * qNew;
      const bool decrease = DNew <= D + 1e-4 * t * grad.dot(dir);
      const bool flatButBetter = DNew <= D + roundOffAt(s, q) + roundOffAt(sNew, qNew) && gradNew.norm() < grad.norm();
      if (decrease || flatButBetter) {
        s = sNew, q = qNew, J = jNew, D = DNew, grad = gradNew;
        accepted = true;
      }
    }
    if (!accepted) {
      // no further progress possible in double precision. A tolerance below
      // what double resolves (the caller's, e.g. 1e-18) never met the
      // shortcut above, and the iterate's own q then is the law at s, not at
      // the returned slip b + K L q, which sits the residual off s: with a
      // long lever the law there differs (found: item 67's far polygon with
      // tolerance 1e-18 returned an impulse 0.027 of L off the law at its
      // slip, while 1e-17 and the default passed). So the step is finished
      // as the shortcut would at the default tolerance, where it qualifies.
      linearisedStep(std::max(tol, kRelativeTolerance));
      break;
    }
  }
  // consistency with the returned slip: where the map s -> b + K L q(s^)
  // contracts (|K| L |dq/ds| < 1/2: the slip hardly depends on the impulse),
  // fixed-point steps make the impulse the law at the returned slip's
  // direction (found by fuzzing: |b| = 8e230 met the convergence test,
  // relative to |b|, at once, with q still at the warm start's direction)
  // (J: the law's Jacobian on the unit sphere at the last iterate, so
  // |dq/ds| = |J| / |s|.) The result is kept only if it does not raise the
  // potential D (found by fuzzing: with a pressure far from admissible, J
  // misjudged the contraction and the steps gained energy)
  Vec3 qPolished = q;
  for (int k = 0; k < 8; ++k) {
    const Vec3 sOut = in.b + in.K * (in.L * qPolished);
    if (!(sOut.norm() > 0.0) || !sOut.allFinite()) break;
    if (!(in.K.norm() * in.L * J.norm() < 0.5 * sOut.norm())) break;
    const Vec3 qOut = patch.unitQ(Model::Exact, sOut);
    const bool settled = (qOut - qPolished).norm() <= tol * qPolished.norm();
    qPolished = qOut;
    if (settled) break;
  }
  if (!(qPolished == q)) {
    const Vec3 sPolished = in.b + in.K * (in.L * qPolished);
    if (potential(sPolished, qPolished) <= D + roundOffAt(s, q) + roundOffAt(sPolished, qPolished)) q = qPolished;
  }
  out.impulse = in.L * q;
  out.slip = in.b + in.K * out.impulse;
  return out;
}

}  // namespace

namespace {
// Found by fuzzing: K = diag(1e300, 1e-8, 1e-8) (SPD, but its products
// overflow) gave a NaN impulse; such blocks are out of double's range.
FrictionBlockResult requireFiniteResult(const FrictionBlockResult& r) {
  if (!r.impulse.allFinite() || !r.slip.allFinite())
    throw Error("friction block out of range: the impulse overflows double (K, b or L too large)");
  return r;
}
}  // namespace

namespace {
// K positive definite: its symmetric part has a Cholesky factor, as the
// exact path checks.
// The decision is Eigen's LLT's (its unblocked lower factorisation: the
// same pivots in the same order of operations, success iff each pivot is
// > 0), written out for the 3x3 case, where Eigen's dynamic-size blocks
// cost ~10 times the arithmetic on every block solve; the factor itself is
// only needed by the stick paths, which call requirePositiveDefiniteFactor.
//
// First a sufficient test without square roots or divisions (the
// factorisation is a chain of three of each, ~90 cycles of latency on every
// ellipsoidal block solve): finite entries, a positive diagonal and every
// off-diagonal A_ij^2 <= kDominant A_ii A_jj. The factorisation then
// succeeds in floating point with room to spare: l10^2 = A10^2 / A00 <=
// 0.2 A11, so x1 >= 0.8 A11; |l21| <= (|A21| + |l20| |l10|) / sqrt(x1) gives
// l21^2 <= (sqrt 0.2 + 0.2)^2 / 0.8 A22 = 0.53 A22 and l20^2 <= 0.2 A22, so
// x2 >= 0.27 A22 > 0, every l finite; round-off moves these bounds by a few
// eps, not by 0.27. So the fast test accepts only what the factorisation
// accepts, and everything else goes to the factorisation (the Bullet
// integration's blocks pass it: their off-diagonals are small).
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
    if (a00 >= kMin && a11 >= kMin && a22 >= kMin && p01 >= kMin &&
        p02 >= kMin && p12 >= kMin && std::isfinite(p01) && std::isfinite(p02) &&
        std::isfinite(p12) && A(1, 0) * A(1, 0) <= p01 && A(2, 0) * A(2, 0) <= p02 &&
        A(2, 1) * A(2, 1) <= p12)
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

// The exact block with an ill-conditioned K verifies that a slip is the
// law at its own slip direction, impulse = L q(s^), s = b + K impulse (a
// residual: the returned state is then the exact solution of the block to
// the law's round-off) and refuses the block otherwise. The slip potential
// weighs the slip by K^-1, so its Newton iteration works at K's plain
// condition number, not at its unit-diagonal one; beyond ~1e8 its descent
// tests are round-off and it can stop far from the solution (found by
// fuzzing, both with a K near singular, e.g. K = 0.75 1 1^T + 1.1e-8 I, and
// with a wide diagonal and b off the rows' scale, e.g. K_xx = 8.4e12
// against K_yy = K_zz = 1e-8 and b ~ 1e-8: slips driven by the impulse,
// 0.5 to 1.1 of the set off the law). kVerifyCondition = 1e5 (|K|_F |K^-1|_F,
// at least the 2-norm condition) lies below every such finding (the lowest:
// 1.2e8; this round's session found 2.6e-6 at 3.8e6 with the lever factor
// below) and above what the Bullet integration feeds the block (measured:
// |K|_F |K^-1|_F at most 7.2e3, unit-diagonal condition ~10, diagonal span
// ~6e3, levers ~1 to 3); the check costs one evaluation of the law there
// and nothing below it. The direction of s is checked where it is resolved
// (|s| above kResolvedSlip of the block's slip scale: the Newton tolerance
// leaves 1e-14 of it, magnified by the law's sensitivity, up to 1e5 at the
// lever domain's ends; as the fuzz target checks it), to kVerifyLaw of the
// set's size (the target's tolerance), and the
// slip's kinetic energy may not grow (s^T K^-1 s <= b^T K^-1 b, maximum
// dissipation; to kVerifyEnergy, wherever s is resolved or not: found by
// fuzzing, a K spanning 5.6e25 with a lever of 1e4 returned a slip of
// 1e-9 of the scale with 2e4 times the energy of b).
constexpr double kVerifyCondition = 1e5, kVerifyLaw = 1e-6, kResolvedSlip = 1e-2,
                 kVerifyEnergy = 1e-10;
FrictionBlockResult requireVerifiedExactSlip(const FrictionPatch& patch,
                                             const FrictionBlockInput& in,
                                             const FrictionBlockResult& r, double cond) {
  if (r.sticking || in.L == 0.0) return r;
  // (times the lever's distance from 1: the law turns from force to torque
  // across |w_z| / |w_xy| ~ 1 / lever, so the iteration's round-off reaches
  // the law magnified by it; found by fuzzing: cond 3e6 with a lever of
  // 1.06e4 left the law 1.2e-5 off)
  const double lever = patch.shape().maxDistanceFromOrigin() / patch.rho();
  if (cond * std::max({1.0, lever, 1.0 / lever}) < kVerifyCondition) return r;
  const Eigen::LLT<Mat3> llt = requirePositiveDefiniteFactor(0.5 * (in.K + in.K.transpose()));
  const double energyBefore = in.b.dot(llt.solve(in.b)),
               energyAfter = r.slip.dot(llt.solve(r.slip));
  if (!(energyAfter <= energyBefore * (1.0 + kVerifyEnergy)))
    throw Error("friction block: the exact block cannot resolve this K (condition number " +
                internal::formatDouble(cond) + "): its slip gains kinetic energy (" +
                internal::formatDouble(energyBefore) + " -> " +
                internal::formatDouble(energyAfter) + ")");
  const Vec3 q = patch.unitQ(Model::Exact, r.slip);
  // (the set's size and the slip scale as the fuzz target measures them:
  // force up to ∫|p| / Pz ~ 1 (p >= 0), torque up to that times the lever;
  // relative to |q| alone a long lever's translation, |q| ~ 1 in a set of
  // size 1e5, was held to 1e-12 of the set, below what the iteration
  // resolves there)
  const double lawSize = 1.0 + lever;
  const double scale = in.b.stableNorm() + in.L * internal::stableMatrixNorm(in.K) * lawSize;
  const double miss = (r.impulse / in.L - q).stableNorm();
  if (!(r.slip.stableNorm() > kResolvedSlip * scale) || miss <= kVerifyLaw * lawSize) return r;
  throw Error("friction block: the exact block cannot resolve this K (condition number " +
              internal::formatDouble(cond) + "): its impulse misses the law at its slip by " +
              internal::formatDouble(miss / lawSize) + " of the law's size");
}

// The exact block of a patch much smaller than rho, solved in the frame of
// the patch's own centre g with rho' of Eq. (11) about g. The law turns as
// the ICR crosses the patch, across a change of w_xy / w_z of ~diameter /
// rho, so in O's coordinates the iteration's round-off (1e-14 of the slip
// scale) reaches the law magnified by rho / diameter, whatever
// max|r| / rho is (found by fuzzing: a 1e-8 m disk 9,000 diameters from O
// with rho = 0.5, lever max|r| / rho 1.8e-4 but diameter / rho 4e-8: the
// impulse was right to 1e-12 and the law at the returned slip 8e-5 of the
// set's size off it, the ICR at the disk's rim; scaling the spin
// coordinate alone changed nothing; recentred: 2e-8, by brute-force
// quadrature). About g the law resolves at unit scale. Slip and impulse
// map as
//   s' = T s,  lambda = T^T lambda',  T = [[1, 0, -g_y / rho], [0, 1, g_x / rho], [0, 0, rho' / rho]]
// (the velocity at g, and the torque about g: power s.lambda is kept), so
// K' = T K T^T, b' = T b, and the law of the recentred patch is the one about
// O up to its normalisation: q_O(s) = (Pz' / Pz) T^T q'(T s), which L' = L
// Pz' / Pz carries. Only below kRecentreBelow (Bullet's patches are
// expressed about their centroid: diameter / rho ~ 1); costs a FrictionPatch
// there. Where the recentred patch or block is refused (its K' can be worse
// conditioned, T shears by g / rho), the block is solved about O as before.
constexpr double kRecentreBelow = 1e-2;
bool solveExactRecentred(const FrictionPatch& patch, const FrictionBlockInput& in, FrictionBlockResult& out) {
  const PatchShape& shape = patch.shape();
  if (!(shape.diameter() < kRecentreBelow * patch.rho())) return false;
  try {
    Vec2 g = Vec2::Zero();
    if (shape.isDisk()) {
      g = shape.centre();
    } else {
      for (const Vec2& v : shape.vertices()) g += v;
      g /= static_cast<double>(shape.vertices().size());
    }
    const PatchShape local = shape.inFrame(g, 0.0);
    const LinearPressure& p = patch.pressure();
    // (with mu = 1: the block solves the unit law q = Q / (mu Pz), which mu
    // does not enter, and the patch's own mu times the recentred pressure
    // may overflow the constructor's scale check where the patch's did not:
    // its bound mu A max|p| (1 + max|r| / rho) has the factor 2.5 about g
    // (max|r'| / rho' = 1.5 on a disk) against 1.0002 about O. Found by
    // fuzzing: mu = 1e300 on a 1e-8 m disk 5,300 diameters from O, a bound
    // of 1.2e308 about O and 2.9e308 about g; the recentred patch was
    // refused, the block went back to O, and its impulse was 2.7e-5 of L
    // off the law at its slip)
    const FrictionPatch recentred =
        patch.isHertz() ? FrictionPatch(local, HertzPressure{patch.Pz()}, 1.0)
                        : FrictionPatch(local, LinearPressure{p.p0 + p.cx * g.x() + p.cy * g.y(), p.cx, p.cy}, 1.0);
    const double rho = patch.rho();
    Mat3 T = Mat3::Identity();
    T(0, 2) = -g.y() / rho;
    T(1, 2) = g.x() / rho;
    T(2, 2) = recentred.rho() / rho;
    FrictionBlockInput localIn = in;
    localIn.b = T * in.b;
    localIn.K = T * in.K * T.transpose();
    localIn.warmSlip = T * in.warmSlip;
    localIn.warmGauge = T * in.warmGauge;
    const double pzRatio = recentred.Pz() / patch.Pz();
    localIn.L = in.L * pzRatio;
    if (!localIn.b.allFinite() || !localIn.K.allFinite() || !std::isfinite(localIn.L)) return false;
    double localCond = 0.0;
    FrictionBlockResult r = solveExact(recentred, localIn, &localCond);
    // The iteration stops at tol of the block's slip scale |b'| + L' |K'|.
    // About g a slip with the ICR inside the patch is mostly spin with rho'
    // ~ diameter, and |s'| can be 1e-9 of that scale (the block's b' and
    // L' K' lambda' cancel): its direction, which the law follows, was fixed
    // to tol |scale| / |s'| only (found by fuzzing: 1e-8 m disk 9,000
    // diameters from O, rho = 0.5, ICR 0.12 R from its centre, |s'| ~1e-9
    // of the scale, the impulse 4.2e-6 of L off the law at its slip; now
    // 1.6e-9, by brute-force quadrature).
    // Such a slip is polished from where it stopped with the tolerance
    // relative to |s'| itself; the iteration ends where double gives no more
    // progress (its own "no trial accepted" exit).
    const double localScale = localIn.b.norm() + localIn.L * localIn.K.norm();
    const double localTol = in.tolerance > 0.0 ? in.tolerance : kRelativeTolerance;
    if (!r.sticking && r.slip.norm() < kResolvedSlip * localScale) {
      FrictionBlockInput polish = localIn;
      polish.warmSlip = r.slip;
      polish.tolerance = std::max(localTol * r.slip.norm() / localScale, 1e-300);
      r = solveExact(recentred, polish, &localCond);
    }
    out = r;
    out.impulse = T.transpose() * r.impulse;
    out.slip = r.sticking ? Vec3::Zero() : Vec3(in.b + in.K * out.impulse);
    if (r.gaugeSlip.cwiseAbs().maxCoeff() > 0.0) {
      const Mat3 Tinv = T.inverse();
      out.gaugeSlip = Vec3(Tinv * r.gaugeSlip).normalized();
      out.gaugeValue = (1.0 / pzRatio) * (T.transpose() * r.gaugeValue);
    }
    return out.impulse.allFinite() && out.slip.allFinite();
  } catch (const Error&) {
    return false;
  }
}

// The block after validation, at the scale it is given.
FrictionBlockResult solveModel(const FrictionPatch& patch, Model model, const FrictionBlockInput& input) {
  if (model == Model::Ellipsoidal) {
    // K positive definite, as documented and as the exact path checks
    // (found by fuzzing: an indefinite K gave a NaN impulse here)
    requirePositiveDefinite(input.K);
    return requireFiniteResult(solveEllipsoidal(patch.Pi(), input));
  }
  // (K's plain condition number, as solveExact computed it; for a
  // recentred block, K's own, for the verification about O)
  double cond = 0.0;
  FrictionBlockResult r;
  if (solveExactRecentred(patch, input, r)) {
    const Mat3 Ksym = 0.5 * (input.K + input.K.transpose());
    cond = Ksym.norm() * inverseOf(requirePositiveDefiniteFactor(Ksym)).norm();
  } else {
    r = solveExact(patch, input, &cond);
  }
  return requireVerifiedExactSlip(patch, input, requireFiniteResult(r), cond);
}

}  // namespace

namespace {

// The block's domain in the patch (step.hpp), both laws; a patch outside it
// is refused whatever b, K and L are.
//  * pressure >= 0 on the patch, to kNegativePressureTol of the mean
//    pressure Pz / A: both blocks rest on a convex limit set (the exact one
//    on maximum dissipation, the ellipsoidal one on an SPD Pi), which a
//    pressure with negative parts does not give (found by fuzzing: a sliver
//    with Tx = 1 against Pz = 1e-8, min p = -1e8 of the mean, returned a
//    torque 1e18 times outside its bound; couples of 1e147 and more against
//    Pz = 1e-8 made Pi ~ 1e150 and overflowed the ellipsoidal L K Pi).
//    1e-6 is nearestAdmissibleLoads' own acceptance of its projection (its
//    results are ~1e-12 off in normal cases), so every pressure it returns,
//    the Bullet integration's, is inside.
//  * lever max|r| / rho within [kMinLever, kMaxLever]: the law turns from
//    force to torque across |w_z| / |w_xy| ~ 1 / lever, which the blocks
//    resolve to ~1e-14 lever (long) and ~1e-13 / lever (short) of the set,
//    measured over hard blocks (slip near that turn): at most 6e-10 of the
//    set at 1e5 and 8e-9 at 1e-5, with errors of the whole set beyond
//    (fuzzing: the exact block from 2.3e5 and below 1.6e-6; the same sweep
//    put the ellipsoidal block 0.9 of the set off from 3e7). Eq. (11) gives 1 to ~3; rho is a coordinate scale that
//    does not change the physics, so only a rho chosen more than 1e5 times
//    off the patch's size is refused.
constexpr double kNegativePressureTol = 1e-6;
constexpr double kMinLever = 1e-5, kMaxLever = 1e5;

// The exact law sums the pressure's terms about O, each up to A |c_k|
// max|r|^k / Pz of the unit law, over kernel integrals that cancel by
// diameter^2 / A on a sliver: its round-off is ~kTermsUlps eps times
// max(1, diameter^2 / A) times those terms (the fuzz targets' model; found
// up to ~90 ulps there). Where that reaches kLawNoDigits of the unit force
// the law has lost its digits, and the block's answer with it (found by
// fuzzing: a 1e-8 m x 0.5 m sliver with cy = -2.75e16 against Pz = 0.32
// gave a unit law whose torque reached 288 where its bound is 1, and the
// block torques 100 times outside the set). Ordinary patches are ~1e4 and
// more below it (a 1 m x 1 mm face with terms 10 times Pz: 1.4e-10).
// The unit law divides by Pz, which for a polygon comes from its area
// moments: summed about O they would round to ~eps max|r|^2 / A (products
// of coordinates up to max|r|^2), far beyond this model far from O (found
// by fuzzing: a 23-gon 900 diameters from O, a 1.2e-8 m quadrilateral
// 8,800 diameters from O and a 1.7e6 m sliver 9.6e9 m from O whose unit
// laws in pure translation had a force of 1 + 1.1e-7, 1 + 5.5e-7 and 1 +
// 1.45e-4). PatchShape sums them about the vertex mean where O is outside
// the patch (geometry.cpp), the frame in which the law integrates, so Pz
// keeps the law's digits: over 20,000 polygons (3 to 22 vertices, aspect
// 1 to 1e-6, 0 to 1e4 diameters from O, tilted pressures >= 0) the unit
// force in pure translation was 1 to 2.8 eps max(1, diameter^2 / A) times
// the terms over Pz (fuzz/README.md, item 58).
constexpr double kTermsUlps = 64.0, kLawNoDigits = 1e-6;
void requireExactLawDigits(const FrictionPatch& patch) {
  const PatchShape& shape = patch.shape();
  const LinearPressure& p = patch.pressure();
  const double rmax = shape.maxDistanceFromOrigin();
  const double terms = shape.area() * (std::abs(p.p0) + (std::abs(p.cx) + std::abs(p.cy)) * rmax) / patch.Pz();
  const double sliver = std::max(1.0, shape.diameter() / shape.area() * shape.diameter());
  const double roundOff = kTermsUlps * std::numeric_limits<double>::epsilon() * sliver * terms;
  if (!(roundOff <= kLawNoDigits)) {
    throw Error("friction block: the exact law has no digits for this pressure and patch (round-off ~" +
                internal::formatDouble(roundOff) + " of its force: terms about O " + internal::formatDouble(terms) +
                " times Pz on a patch of diameter^2 / area " + internal::formatDouble(sliver) + ")");
  }
}

void requireBlockDomain(const FrictionPatch& patch, Model model) {
  const PatchShape& shape = patch.shape();
  const double lever = shape.maxDistanceFromOrigin() / patch.rho();
  if (!(lever >= kMinLever && lever <= kMaxLever)) {
    throw Error("friction block out of range: the patch's lever max|r| / rho = " + internal::formatDouble(lever) +
                " lies outside [1e-5, 1e5] (rho = " + internal::formatDouble(patch.rho()) +
                " m); choose rho within 1e5 of the patch's size (default: Eq. (11))");
  }
  if (patch.isHertz()) return;  // the Hertz pressure (57) is >= 0
  const double meanPressure = patch.Pz() / shape.area();
  const double lowest = minPressure(shape, patch.pressure());
  if (!(lowest >= -kNegativePressureTol * meanPressure)) {
    throw Error("friction block: the pressure is negative on the patch (min p = " + internal::formatDouble(lowest) +
                " Pa against a mean of " + internal::formatDouble(meanPressure) +
                " Pa); the block needs p >= 0 (use nearestAdmissibleLoads)");
  }
  if (model == Model::Exact) requireExactLawDigits(patch);
}

}  // namespace

FrictionBlockResult solveFrictionBlock(const FrictionPatch& patch, Model model,
                                       const FrictionBlockInput& input) {
  validate(input);
  requireBlockDomain(patch, model);
  FrictionBlockResult out;
  if (input.L == 0.0) {  // no normal impulse: no friction
    out.slip = input.b;
    out.sticking = input.b.isZero(0.0);  // not |b|^2 == 0: that underflows for b ~ 1e-160
    return out;
  }
  if (input.b.isZero(0.0)) {  // already at rest: stick with zero impulse
    out.sticking = true;
    return out;
  }
  // The block is homogeneous: K -> a K, b -> c b, L -> (c / a) L (and the
  // warm start with b) give s -> c s, lambda -> (c / a) lambda. Far from unit
  // scale it is solved at |K| ~ 1 and |b| ~ 1, with a and c powers of two,
  // so the scaling is exact: squares of 1e-160 underflowed (found by
  // fuzzing: b of denormals, where |K^-1 b| came out 0 and the exact block
  // stuck with a zero impulse; with b = 1e-170 the exact block slipped with
  // a zero impulse). An L beyond 2^kMaxLeverage there (|L K Pi|^2 would
  // overflow) is tried at that bound: a block that sticks with it sticks
  // with any larger L; one that slips is left to the plain path, as is an L
  // that underflows. One range check on the common path.
  {
    const double bMax = input.b.cwiseAbs().maxCoeff(), kMax = input.K.cwiseAbs().maxCoeff();
    // (unit scale from 1e40 on, not 1e100: the ellipsoidal root search
    // squares |N(r)| ~ |b|^3, which overflows for |b| > 1e51; found by
    // fuzzing, b = 1.1e74 against L |K| = 0.25 returned a zero impulse)
    constexpr double kLow = 1e-40, kHigh = 1e40;
    constexpr int kMaxLeverage = 300;
    // (a K whose diagonal spans more than kMaxSpread keeps its scale: its
    // determinant leaves double's range at any scale, refused below)
    constexpr double kMaxSpread = 1e100;
    const bool spreadOk = input.K.diagonal().cwiseAbs().minCoeff() > kMax / kMaxSpread;
    if (!(bMax > kLow && bMax < kHigh && kMax > kLow && kMax < kHigh) && bMax > 0.0 && kMax > 0.0 && spreadOk) {
      const int ek = std::ilogb(kMax), es = std::ilogb(bMax);
      auto times2To = [](auto v, int e) {
        return decltype(v)(v.unaryExpr([e](double x) { return std::ldexp(x, e); }));
      };
      FrictionBlockInput unit = input;
      unit.b = times2To(input.b, -es);
      unit.K = times2To(input.K, -ek);
      unit.warmSlip = times2To(input.warmSlip, -es);
      // (a warm start far smaller or larger than b keeps its direction, the
      // exact block's only use of it: its squares would under- or overflow)
      const double warmMax = unit.warmSlip.cwiseAbs().maxCoeff();
      if (input.warmSlip.cwiseAbs().maxCoeff() > 0.0 && !(warmMax > kLow && warmMax < kHigh))
        unit.warmSlip = times2To(input.warmSlip, -std::ilogb(input.warmSlip.cwiseAbs().maxCoeff()));
      // (the ellipsoidal A = L K Pi counts Pi's size too: found by fuzzing,
      // b = 2.2e-308 against Pi ~ 1e281 (mu 1.5e10 times a couple of
      // 4e262) made L K Pi 1e301 at unit scale, refused as overflowing,
      // where the block plainly sticks)
      const double piMax = patch.Pi().cwiseAbs().maxCoeff();
      const bool piCounts = model == Model::Ellipsoidal && piMax > 0.0 && std::isfinite(piMax);
      const int ePi = piCounts ? std::max(0, std::ilogb(piMax)) : 0;
      const bool clamped = std::ilogb(input.L) + ek - es + ePi > kMaxLeverage;
      unit.L = clamped ? std::ldexp(1.0, kMaxLeverage - ePi) : std::ldexp(input.L, ek - es);
      if (unit.L >= std::numeric_limits<double>::min()) {
        FrictionBlockResult r = solveModel(patch, model, unit);
        if (!clamped || r.sticking) {
          r.impulse = times2To(r.impulse, es - ek);
          r.slip = times2To(r.slip, es);
          return requireFiniteResult(r);
        }
      } else {
        // L |K| below 2^-1022 of |b|: the impulse cannot move the slip off b
        // by one ulp and -K^-1 b is far outside L E, so the block slips
        // along b with the law there (found by fuzzing: |b| = 1e300 against
        // L |K| = 2e-9 kept the warm start's q, 0.77 of the set off the law)
        // (K must still be positive definite, as on every other path: found
        // by fuzzing, K = diag(-0.099, -0.071, 6.8e-4) against L = 5e-324 was
        // accepted here; checked at unit scale, where its minors are in range)
        requirePositiveDefinite(unit.K);
        FrictionBlockResult r;
        r.impulse = input.L * patch.unitQ(model, unit.b);
        r.slip = input.b + input.K * r.impulse;
        r.iterations = 1;
        return requireFiniteResult(r);
      }
    }
  }
  return solveModel(patch, model, input);
}

}  // namespace patchspin
