// The exact friction block, Eq. (16): a projection onto the convex limit set
// in K's metric (friction_block.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "friction_block_solvers.hpp"
#include "spd3.hpp"

namespace patchspin::internal {

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
  // soft directions by K^-1 up to 1e300. A unit-scaled K within it has |K|,
  // |K^-1| < 1e200 (FrictionBlockConditioning.ExactWithABadlyScaledKIsTheLawToItsResolution).
  constexpr double kMaxDiagonalSpread = 1e200;
  if (!(Ksym.diagonal().maxCoeff() < kMaxDiagonalSpread * Ksym.diagonal().minCoeff()))
    throw Error("friction block out of range: the diagonal of K spans more than 1e200 (" +
                internal::formatDouble(Ksym.diagonal().minCoeff()) + " to " +
                internal::formatDouble(Ksym.diagonal().maxCoeff()) + ")");
  const Mat3 Kinv = inverseOf(kLlt);
  // det K and K^-1 in double's range, else K^-1 b = 0 would stick
  // (FrictionBlockScale.FarFromUnitScaleIsTheLaw)
  if (!std::isfinite(det) || !Kinv.allFinite())
    throw Error("friction block out of range: det K overflows double (" +
                internal::formatDouble(det) + ")");
  // numerically singular K refused: the slip potential below needs K^-1;
  // the common path pays one product of two norms (the scaled condition is
  // at most 3 times this plain one, spd3.hpp)
  // (FrictionBlockConditioning.NumericallySingularKIsRefusedOrTheLaw)
  const double cond = Ksym.norm() * Kinv.norm();
  *plainCondition = cond;
  if (!(cond < kSingularCondition / 3.0)) requireNotNumericallySingular(Ksym, Kinv);
  // lambda0 = -K^-1 b by the Cholesky factor (stickSolve): the stick is
  // decided with the impulse it returns, and a stick verifies b + K lambda =
  // 0 (requireStopsTheSlip). Guarded by
  // FrictionBlockConditioning.StickWithAnIllConditionedKStopsTheSlip and
  // FrictionBlockConditioning.ExactStickRefusesCofactorsWithoutDigits.
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
    const Vec3 c =
        in.piInverse ? Vec3(*in.piInverse * lambda0) : Vec3(patch.Pi().inverse() * lambda0);
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
    // (only a candidate: an ellipsoidal refusal is caught and the exact block
    // goes on without it; the one input known to reach it is refused by both
    // laws before, FrictionBlock.BothLawsRefuseAnAlmostAllNegativePressure)
    Vec3 ellipsoidalSlip = Vec3::Zero();
    try {
      ellipsoidalSlip = solveEllipsoidal(patch.Pi(), in).slip;
    } catch (const Error&) {
    }
    if (ellipsoidalSlip.norm() > 0.0 && ellipsoidalSlip.allFinite())
      scoreCandidate(ellipsoidalSlip.normalized(), true);
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
  // The law's own round-off is ~1e-14 (rms) to ~5e-13 (worst) of |q|, so a
  // residual near the tolerance can be noise: once it grows back from an
  // iterate already below kGaugeNoise |q|, the Newton steps only move w
  // within that noise, and the smaller of the two is the boundary point
  // (its q off lambda0 by that residual: the stick decision, |lambda0|
  // against L |q(w)|, moves by its square). Guarded by
  // FrictionBlockTest.ExactGaugeIsTheBoundaryPointAndWarmStartsTheStickTest.
  constexpr double kGaugeNoise = 1e-12;
  // (a non-finite Newton step falls back to -res / |q|, kTinyNorm guarding
  // q = 0; kMaxGaugeStep of the tangent plane is a quarter turn)
  constexpr double kTinyNorm = 1e-300, kMaxGaugeStep = 0.5;
  Vec3 prevW = w, prevQ = Vec3::Zero();
  bool gaugeProvesSlip = false;
  double prevRes = INFINITY;
  for (int it = 0; it < kMaxIterations && !slipProven; ++it) {
    q = patch.unitQ(Model::Exact, w, &J);
    // The law is odd, q(-w) = -q(w), so J(-w) = J(w): an iterate whose value
    // points away from lambda0 is taken at -w, on lambda0's side, without an
    // evaluation. Else Newton on the residual across l meets the antipodal
    // root, q(w) along -l, as readily (from a warm start of an earlier visit
    // whose lambda0 has turned over), and stays there
    // (ExactBlock.GaugeStartedAtTheAntipodeIsTheBoundaryPoint).
    if (q.dot(l) < 0.0) w = -w, q = -q;
    const Eigen::Vector2d res(e1.dot(q), e2.dot(q));
    // Every iterate's q(w) is a law value, a support point of E: its gap
    // h(w) < 0 (see `gap`) proves the slip as a candidate's does, and its
    // value and Jacobian start the iteration on D below without the further
    // candidates (ExactBlock.GaugeIterateThatSeparatesProvesTheSlip). At the
    // gauge point h = (|lambda0| - L |q|) (l.w) with l.w < 0 (q.w < 0 for
    // every law value), so a slip is proven there at the latest.
    const double hw = -w.dot(Kinvb) - in.L * q.dot(w);
    if (hw < 0.0) {
      if (res.norm() <= tol * q.norm()) out.gaugeSlip = w, out.gaugeValue = q;
      gaugeProvesSlip = true;
      bestScore = hw / std::sqrt(w.dot(Kinv * w)), bestU = w, bestQ = q, bestH = hw;
      bestHasJ = true, bestJ = J;
      break;
    }
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
    if (!step.allFinite()) step = -res / (q.norm() + kTinyNorm);
    // damp: at most a quarter turn per iteration
    const double len = step.norm();
    if (len > kMaxGaugeStep) step *= kMaxGaugeStep / len;
    w = (w + step[0] * t1 + step[1] * t2).normalized();
    out.iterations = it + 1;
  }
  // (only where the iteration found q(w) along lambda0; otherwise the slip
  // branch below decides, with its own stick fallback:
  // FrictionBlock.ExactRefusesALongLeverWithOOnTheRim)
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
  // few candidate directions (warm start, ellipsoidal solution, the gauge
  // iterate that proved the slip, else b, the gauge direction, and a coarse
  // sphere if none has h < 0), then damped Newton on
  // D with every trial moved to r* on its ray; trials outside the cone are
  // rejected, which keeps the iterates off the kink of D at s = 0.
  if (!slipProven && !gaugeProvesSlip) {
    scoreCandidate(in.b.normalized(), false);
    scoreCandidate(w, false);
    // -lambda0 = K^-1 b: its gap is L h_E(l) - |lambda0|, the plain gauge
    // test along lambda0
    // (FrictionBlock.ExactRefusesALongLeverWithOOnTheRim)
    scoreCandidate(-l, false);
    // and its force and its torque part alone: E's extent along torque and
    // along force differ by the lever max|r| / rho, so with a long (short)
    // lever a direction with any torque (force) part has a huge support and
    // the separating directions lie in the force plane (on the torque axis)
    // (FrictionBlock.ExactRefusesALongLeverWithASlipInTheForcePlane)
    const Vec3 forcePart(-l.x(), -l.y(), 0.0), torquePart(0.0, 0.0, -l.z());
    if (forcePart.norm() > 0.0) scoreCandidate(forcePart.normalized(), false);
    if (torquePart.norm() > 0.0) scoreCandidate(torquePart.normalized(), false);
  }
  if (!(bestScore < 0.0)) {
    // golden-angle (Fibonacci) sphere, deterministic
    std::vector<Vec3> sphere;
    // (128 directions: neighbours ~0.3 rad apart, enough to meet the cone
    // h < 0 of any slip the candidates above missed)
    constexpr int kSphereSamples = 128;
    constexpr double kGoldenAngle = 2.39996322972865332;  // pi (3 - sqrt 5)
    for (int i = 0; i < kSphereSamples; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / kSphereSamples;
      const double rxy = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = kGoldenAngle * i;
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
  constexpr double kPotentialRoundOff = 1e-13;
  // D is O(|b|^2 / |K|); its decrease is invisible below this round-off level
  // (kPotentialRoundOff, ~500 ulps of its terms), where the Newton steps are
  // judged by the gradient instead
  const double roundOffD = kPotentialRoundOff * (std::abs(D) + in.b.dot(Kinvb));
  // With a badly scaled K (diagonal entries kBadlyScaledK apart) that level
  // is wrong: b's part along K's stiff directions dominates b^T K^-1 b while
  // the slip there equals b's to round-off and adds nothing to D. There the
  // round-off of each evaluation is taken from its own terms
  // (FrictionBlockConditioning.ExactWithABadlyScaledKIsTheLawToItsResolution).
  constexpr double kBadlyScaledK = 1e8;
  const double kDiagMax = Ksym.diagonal().maxCoeff(), kDiagMin = Ksym.diagonal().minCoeff();
  const bool badlyScaledK = !(kDiagMax < kBadlyScaledK * kDiagMin);
  const Mat3 absKinv = badlyScaledK ? Mat3(Kinv.cwiseAbs()) : Mat3::Zero();
  auto roundOffAt = [&](const Vec3& x, const Vec3& qx) {
    if (!badlyScaledK) return 0.5 * roundOffD;
    const Vec3 d = (x - in.b).cwiseAbs();
    return kPotentialRoundOff * (d.dot(absKinv * d) + in.L * qx.cwiseAbs().dot(x.cwiseAbs()));
  };
  // |K grad D| at a converged iterate s whose q is the law at s (else -1)
  double convergedStep = -1.0;
  for (int it = 0; it < kMaxIterations; ++it) {
    ++out.iterations;
    // converged: the slip b + K L q(s^) equals s to ~1e-14 of the slip scale
    const double kGrad = (in.K * grad).norm();
    if (kGrad <= tol * scale) {
      convergedStep = kGrad;
      break;
    }
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
      // Only while J du is itself small (with a long lever J is huge); else
      // the step is taken in full below (FrictionBlock.ExactRefusesALongLever).
      // du to first order, the step's part across s over |s|: the difference
      // of the two unit vectors loses its digits once |dir| / |s| nears eps
      // (ExactBlock.FarPolygonSpinningAboutAPointInsideIsTheLaw).
      if (linearisedStep(tol)) break;
    }
    // backtracking: sufficient decrease of D (Armijo, kSufficientDecrease), or
    // (at round-off level of D) of |grad D|, down to t = 2^-kMaxHalvings: the
    // descent fallback -K grad can be 1e18 times too long along a badly scaled
    // K's stiff direction (FrictionBlock.ExactRefusesALongLeverWithAStiffSpin)
    constexpr int kMaxHalvings = 200;
    constexpr double kSufficientDecrease = 1e-4;
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
      // shorter ones (ExactBlock.TinyDiskWithAHugeKIsTheLaw)
      if (sNew == s) break;
      const double DNew = potential(sNew, qNew);
      const Vec3 gradNew = Kinv * (sNew - in.b) - in.L * qNew;
      const bool decrease = DNew <= D + kSufficientDecrease * t * grad.dot(dir);
      const bool flatButBetter =
          DNew <= D + roundOffAt(s, q) + roundOffAt(sNew, qNew) && gradNew.norm() < grad.norm();
      if (decrease || flatButBetter) {
        s = sNew, q = qNew, J = jNew, D = DNew, grad = gradNew;
        accepted = true;
      }
    }
    if (!accepted) {
      // no further progress possible in double precision. A tolerance below
      // what double resolves (the caller's, e.g. 1e-18) never met the
      // shortcut above, and the iterate's own q then is the law at s, not at
      // the returned slip b + K L q: the step is finished as the shortcut
      // would at the default tolerance, where it qualifies
      // (ExactBlock.FarPolygonSpinningAboutAPointInsideIsTheLaw).
      linearisedStep(std::max(tol, kRelativeTolerance));
      break;
    }
  }
  // consistency with the returned slip: where the map s -> b + K L q(s^)
  // contracts (|K| L |dq/ds| < kContraction: the slip hardly depends on the
  // impulse), fixed-point steps make the impulse the law at the returned
  // slip's direction (FrictionBlockScale.ExactWithAFreeSlipOf1e230IsTheLawAtItsSlip).
  // (J: the law's Jacobian on the unit sphere at the last iterate, so
  // |dq/ds| = |J| / |s|.) The result is kept only if it does not raise the
  // potential D (FrictionBlockTest.NeverAddsEnergy).
  // A converged iterate needs no polish where its q is already the law at
  // the returned slip to the polish's own tol: s_out = b + K L q = s - K grad
  // turns the direction by at most |K grad| / |s|, so q(s_out^) differs from
  // q = q(s^) by at most |J| |K grad| / |s| to first order (kPolishMargin
  // leaves room for the second-order term, |J'| times that angle squared)
  // (ExactBlock.WarmStartedSlipIsTheLawAtItsSlip).
  constexpr double kPolishMargin = 0.5;
  const bool lawAtSlip =
      convergedStep >= 0.0 && J.norm() * convergedStep <= kPolishMargin * tol * q.norm() * s.norm();
  constexpr double kContraction = 0.5;    // error at least halved per step
  constexpr int kMaxFixedPointSteps = 8;  // 2^-8 of it at least, then stop
  Vec3 qPolished = q;
  for (int k = 0; k < kMaxFixedPointSteps && !lawAtSlip; ++k) {
    const Vec3 sOut = in.b + in.K * (in.L * qPolished);
    if (!(sOut.norm() > 0.0) || !sOut.allFinite()) break;
    if (!(in.K.norm() * in.L * J.norm() < kContraction * sOut.norm())) break;
    const Vec3 qOut = patch.unitQ(Model::Exact, sOut);
    const bool settled = (qOut - qPolished).norm() <= tol * qPolished.norm();
    qPolished = qOut;
    if (settled) break;
  }
  if (!(qPolished == q)) {
    const Vec3 sPolished = in.b + in.K * (in.L * qPolished);
    if (potential(sPolished, qPolished) <= D + roundOffAt(s, q) + roundOffAt(sPolished, qPolished))
      q = qPolished;
  }
  out.impulse = in.L * q;
  out.slip = in.b + in.K * out.impulse;
  return out;
}

// The exact block with an ill-conditioned K verifies that a slip is the law at
// its own slip direction, impulse = L q(s^), s = b + K impulse (a residual: the
// returned state is then the exact solution of the block to the law's
// round-off), and refuses the block otherwise: the slip potential weighs the
// slip by K^-1, so its Newton iteration works at K's plain condition number,
// and far beyond kVerifyCondition its descent tests are round-off.
//  * kVerifyCondition (|K|_F |K^-1|_F, at least the 2-norm condition): below
//    every mis-solved block known and above what the Bullet integration feeds
//    the block, so the check costs nothing there
//    (docs/notes/friction-block-measurements.md);
//  * the direction of s is checked where it is resolved (kResolvedSlip), to
//    kVerifyLaw of the set's size (the step fuzz target's tolerance);
//  * the slip's kinetic energy may not grow, s^T K^-1 s <= b^T K^-1 b
//    (maximum dissipation), to kVerifyEnergy, resolved or not.
// Guarded by FrictionBlockIllConditioned.ExactBlockWithAnIllConditionedKIsTheLawOrRefused.
constexpr double kVerifyCondition = 1e5, kVerifyLaw = 1e-6, kVerifyEnergy = 1e-10;
FrictionBlockResult requireVerifiedExactSlip(const FrictionPatch& patch,
                                             const FrictionBlockInput& in,
                                             const FrictionBlockResult& r, double cond) {
  if (r.sticking || in.L == 0.0) return r;
  // (times the lever's distance from 1: the law turns from force to torque
  // across |w_z| / |w_xy| ~ 1 / lever, so the iteration's round-off reaches
  // the law magnified by it; ExactBlock.VerifiedBlockIsTheLawAtItsSlip)
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
  // force up to ∫|p| / Pz ~ 1 (p >= 0), torque up to that times the lever,
  // not |q|, which for a long lever's translation is 1e-5 of the set)
  const double lawSize = 1.0 + lever;
  const double scale = in.b.stableNorm() + in.L * internal::stableMatrixNorm(in.K) * lawSize;
  const double miss = (r.impulse / in.L - q).stableNorm();
  if (!(r.slip.stableNorm() > kResolvedSlip * scale) || miss <= kVerifyLaw * lawSize) return r;
  throw Error("friction block: the exact block cannot resolve this K (condition number " +
              internal::formatDouble(cond) + "): its impulse misses the law at its slip by " +
              internal::formatDouble(miss / lawSize) + " of the law's size");
}

}  // namespace patchspin::internal
