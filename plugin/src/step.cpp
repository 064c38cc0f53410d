// The implicit 3-DOF friction block (DESIGN item 4); see step.hpp.
#include <patchspin/step.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

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

  // slip: damped Newton on D from the ellipsoidal solution (or the warm start)
  Vec3 s = in.warmSlip;
  if (!(s.norm() > 0.0)) s = solveEllipsoidal(patch.Pi(), in).slip;
  if (!(s.norm() > 0.0)) s = in.b;
  const double scale = in.b.norm() + in.L * in.K.norm();
  auto potential = [&](const Vec3& x, Vec3* qOut, Mat3* jOut) {
    const Vec3 qx = patch.unitQ(Model::Exact, x, jOut);
    if (qOut) *qOut = qx;
    const Vec3 d = x - in.b;
    return 0.5 * d.dot(Kinv * d) - in.L * qx.dot(x);
  };
  double D = potential(s, &q, &J);
  for (int it = 0; it < kMaxIterations; ++it) {
    ++out.iterations;
    const Vec3 grad = Kinv * (s - in.b) - in.L * q;
    if (grad.norm() * in.K.norm() <= kRelativeTolerance * scale) break;
    Mat3 H = Kinv - (in.L / s.norm()) * 0.5 * (J + J.transpose());
    Vec3 dir = -H.ldlt().solve(grad);
    if (!dir.allFinite() || dir.dot(grad) >= 0.0) dir = -in.K * grad;  // fall back to descent
    // Armijo backtracking on D
    double t = 1.0;
    Vec3 qNew = q;
    Mat3 jNew = J;
    Vec3 sNew = s;
    double DNew = D;
    for (int k = 0; k < 60; ++k, t *= 0.5) {
      sNew = s + t * dir;
      if (!(sNew.norm() > 0.0)) continue;
      DNew = potential(sNew, &qNew, &jNew);
      if (DNew <= D + 1e-4 * t * grad.dot(dir)) break;
    }
    if (!(DNew < D) && t < 1e-15) break;  // no further decrease possible
    s = sNew, q = qNew, J = jNew, D = DNew;
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
