// The implicit 3-DOF friction block (DESIGN item 4); see step.hpp.
#include <patchspin/step.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace patchspin {

namespace {

// Newton iterations stop when the residual is below this fraction of the
// problem's own slip scale |b| + L |K|: ~100 ulps, well below any physical
// effect yet reachable in double precision.
constexpr double kRelativeTolerance = 1e-14;
constexpr int kMaxIterations = 100;

void validate(const FrictionBlockInput& in) {
  internal::requireFinite(in.b, "friction block free slip b");
  internal::requireFinite(in.warmSlip, "friction block warm-start slip");
  if (!in.K.allFinite()) throw Error("friction block matrix K must be finite");
  internal::requireFinite(in.L, "friction block bound L");
  if (in.L < 0.0) throw Error("friction block bound L must be >= 0: got " + internal::formatDouble(in.L));
}

// Ellipsoidal law q(w) = -Pi w. With A = L K Pi the slip s = b - A w must
// equal r w: w = (r I + A)^-1 b with |w| = 1, a scalar root in r > 0.
// phi(r) = |(r I + A)^-1 b|^2 - 1 is positive at r = 0 (slip case) and
// negative for r > |b| + |A|_F, so a safeguarded Newton on the bracket
// converges; phi'(r) = -2 w . (r I + A)^-1 w.
FrictionBlockResult solveEllipsoidal(const Mat3& Pi, const FrictionBlockInput& in) {
  FrictionBlockResult out;
  const Mat3 A = in.L * in.K * Pi;
  Eigen::FullPivLU<Mat3> luA(A);
  if (luA.isInvertible()) {
    const Vec3 w0 = luA.solve(in.b);
    if (w0.norm() <= 1.0) {  // stick: lambda = -L Pi w0 = -K^-1 b
      out.sticking = true;
      out.impulse = -in.L * (Pi * w0);
      out.slip.setZero();
      return out;
    }
  }
  double lo = 0.0, hi = in.b.norm() + A.norm();
  double r = hi;
  if (in.warmSlip.norm() > 0.0 && in.warmSlip.norm() < hi) r = in.warmSlip.norm();
  Vec3 w = in.b;
  const double scale = in.b.norm() + A.norm();
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it + 1;
    const Eigen::PartialPivLU<Mat3> lu(r * Mat3::Identity() + A);
    w = lu.solve(in.b);
    const double phi = w.squaredNorm() - 1.0;
    if (phi > 0.0) lo = r; else hi = r;
    const double dphi = -2.0 * w.dot(lu.solve(w));
    double next = (dphi < 0.0) ? r - phi / dphi : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // safeguard: bisect
    if (std::abs(phi) <= kRelativeTolerance || hi - lo <= kRelativeTolerance * scale) break;
    r = next;
  }
  w.normalize();
  out.impulse = -in.L * (Pi * w);
  out.slip = in.b + in.K * out.impulse;
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
FrictionBlockResult solveExact(const FrictionPatch& patch, const FrictionBlockInput& in) {
  FrictionBlockResult out;
  const Eigen::LLT<Mat3> llt(0.5 * (in.K + in.K.transpose()));
  if (llt.info() != Eigen::Success) throw Error("friction block matrix K is not positive definite");
  const Mat3 Kinv = llt.solve(Mat3::Identity());
  const Vec3 lambda0 = -Kinv * in.b;
  const double lambda0Norm = lambda0.norm();
  if (lambda0Norm == 0.0) {
    out.sticking = true;
    return out;
  }

  // gauge of E along lambda0: residual = component of q(w) across lambda0
  const Vec3 l = lambda0 / lambda0Norm;
  Vec3 e1 = l.unitOrthogonal();
  Vec3 e2 = l.cross(e1);
  Vec3 w = -(patch.Pi().fullPivLu().solve(l));  // ellipsoidal: q = -Pi w
  if (!(w.norm() > 0.0) || !w.allFinite()) w = -l;
  w.normalize();
  Vec3 q;
  Mat3 J;
  for (int it = 0; it < kMaxIterations; ++it) {
    q = patch.unitQ(Model::Exact, w, &J);
    const Eigen::Vector2d res(e1.dot(q), e2.dot(q));
    if (res.norm() <= kRelativeTolerance * q.norm() && q.dot(l) > 0.0) break;
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
  if (q.dot(l) > 0.0 && lambda0Norm <= in.L * q.norm()) {
    out.sticking = true;
    out.impulse = lambda0;
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
  const Vec3 Kinvb = Kinv * in.b;
  auto gap = [&](const Vec3& u, Vec3& qu, Mat3* ju) {
    qu = patch.unitQ(Model::Exact, u, ju);
    return -u.dot(Kinvb) - in.L * qu.dot(u);
  };
  std::vector<Vec3> candidates;
  if (in.warmSlip.norm() > 0.0) candidates.push_back(in.warmSlip.normalized());
  const Vec3 ellipsoidalSlip = solveEllipsoidal(patch.Pi(), in).slip;
  if (ellipsoidalSlip.norm() > 0.0) candidates.push_back(ellipsoidalSlip.normalized());
  candidates.push_back(in.b.normalized());
  candidates.push_back(w);
  Vec3 bestU = in.b.normalized();
  double bestScore = 0.0;  // most negative h / |u|_{K^-1}
  auto scoreCandidates = [&](const std::vector<Vec3>& dirs) {
    for (const Vec3& u : dirs) {
      Vec3 qu;
      const double score = gap(u, qu, nullptr) / std::sqrt(u.dot(Kinv * u));
      if (score < bestScore) bestScore = score, bestU = u;
    }
  };
  scoreCandidates(candidates);
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
    scoreCandidates(sphere);
  }
  if (!(bestScore < 0.0)) {
    // no direction with a support gap: lambda0 is inside L E after all
    out.sticking = true;
    out.impulse = lambda0;
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
  Vec3 s = radialOptimum(bestU, q, J, inCone);
  double D = potential(s, q);
  Vec3 grad = Kinv * (s - in.b) - in.L * q;
  const double scale = in.b.norm() + in.L * in.K.norm();
  // D is O(|b|^2 / |K|); its decrease is invisible below this round-off level,
  // where the Newton steps are judged by the gradient instead
  const double roundOffD = 1e-13 * (std::abs(D) + in.b.dot(Kinvb));
  for (int it = 0; it < kMaxIterations; ++it) {
    ++out.iterations;
    // converged: the slip b + K L q(s^) equals s to ~1e-14 of the slip scale
    if ((in.K * grad).norm() <= kRelativeTolerance * scale) break;
    const Mat3 H = Kinv - (in.L / s.norm()) * 0.5 * (J + J.transpose());
    Vec3 dir = -H.ldlt().solve(grad);
    if (!dir.allFinite() || dir.dot(grad) >= 0.0) dir = -in.K * grad;  // fall back to descent
    // backtracking: sufficient decrease of D, or (at round-off level of D) of |grad D|
    double t = 1.0;
    bool accepted = false;
    for (int k = 0; k < 60 && !accepted; ++k, t *= 0.5) {
      Vec3 sNew = s + t * dir;
      if (!(sNew.norm() > 0.0)) continue;
      Vec3 qNew;
      Mat3 jNew;
      sNew = radialOptimum(sNew, qNew, jNew, inCone);
      if (!inCone) continue;
      const double DNew = potential(sNew, qNew);
      const Vec3 gradNew = Kinv * (sNew - in.b) - in.L * qNew;
      const bool decrease = DNew <= D + 1e-4 * t * grad.dot(dir);
      const bool flatButBetter = DNew <= D + roundOffD && gradNew.norm() < grad.norm();
      if (decrease || flatButBetter) {
        s = sNew, q = qNew, J = jNew, D = DNew, grad = gradNew;
        accepted = true;
      }
    }
    if (!accepted) break;  // no further progress possible in double precision
  }
  out.impulse = in.L * q;
  out.slip = in.b + in.K * out.impulse;
  return out;
}

}  // namespace

FrictionBlockResult solveFrictionBlock(const FrictionPatch& patch, Model model,
                                       const FrictionBlockInput& input) {
  validate(input);
  FrictionBlockResult out;
  if (input.L == 0.0) {  // no normal impulse: no friction
    out.slip = input.b;
    out.sticking = input.b.squaredNorm() == 0.0;
    return out;
  }
  if (input.b.squaredNorm() == 0.0) {  // already at rest: stick with zero impulse
    out.sticking = true;
    return out;
  }
  if (model == Model::Ellipsoidal) return solveEllipsoidal(patch.Pi(), input);
  return solveExact(patch, input);
}

}  // namespace patchspin
