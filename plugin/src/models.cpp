// FrictionPatch: the ellipsoidal law (41) and the exact law (16) of one patch.
#include <patchspin/internal/exact.hpp>
#include <patchspin/models.hpp>

#include <cmath>

namespace patchspin {

namespace {

double resolveRho(const PatchShape& shape, double rho) {
  internal::requireFinite(rho, "length scale rho");
  return rho > 0.0 ? rho : shape.defaultRho();
}

void requireMu(double mu) {
  internal::requireFinite(mu, "friction coefficient mu");
  if (mu < 0.0) throw Error("friction coefficient mu must be >= 0: got " + internal::formatDouble(mu));
}

// |w| without overflow or underflow (w may be scaled by 1e+-200).
double safeNorm(const Vec3& w) {
  const double m = w.cwiseAbs().maxCoeff();
  return m > 0.0 ? m * (w / m).norm() : 0.0;
}

Vec3 unitDirection(const Vec3& w) {
  internal::requireFinite(w, "slip direction w");
  const double m = w.cwiseAbs().maxCoeff();
  if (!(m > 0.0)) throw Error("slip direction w must be nonzero (w = 0 is sticking)");
  return (w / m).normalized();
}

}  // namespace

FrictionPatch::FrictionPatch(const PatchShape& shape, const LinearPressure& pressure, double mu,
                             double rho)
    : shape_(shape), mu_(mu), rho_(resolveRho(shape, rho)) {
  requireMu(mu);
  setPressure(pressure);
}

FrictionPatch::FrictionPatch(const PatchShape& disk, const HertzPressure& pressure, double mu,
                             double rho)
    : shape_(disk), hertz_(true), mu_(mu), rho_(resolveRho(disk, rho)) {
  requireMu(mu);
  moments_ = piMomentsHertz(disk, pressure);
  Pi_ = ellipsoidalPi(moments_, rho_);
}

void FrictionPatch::setPressure(const LinearPressure& pressure) {
  internal::requireFinite(pressure.coefficients(), "pressure (p0, cx, cy)");
  moments_ = patchspin::piMoments(shape_, pressure);  // throws if Pz <= 0
  pressure_ = pressure;
  hertz_ = false;
  Pi_ = ellipsoidalPi(moments_, rho_);
}

void FrictionPatch::setMu(double mu) {
  requireMu(mu);
  mu_ = mu;
}

Vec3 FrictionPatch::ellipsoidalQ(const Vec3& w, Mat3* jacobian) const {
  // Eq. (41): Q = -mu Pz Pi w
  const double scale = -mu_ * moments_.Pz;
  if (jacobian) *jacobian = scale * Pi_;
  return scale * (Pi_ * unitDirection(w));
}

Vec3 FrictionPatch::exactQ(const Vec3& w, Mat3* jacobian, const ExactAccuracy& accuracy) const {
  return exactScaled(-mu_, w, jacobian, accuracy.tolerance);
}

Vec3 FrictionPatch::unitQ(Model model, const Vec3& w, Mat3* jacobian) const {
  if (model == Model::Exact) return exactScaled(-1.0 / moments_.Pz, w, jacobian, 0.0);
  if (jacobian) *jacobian = -Pi_;
  return -(Pi_ * unitDirection(w));
}

// scale * ∫ p k(w) dA: scale = -mu gives Eq. (16); -1/Pz the unit law.
Vec3 FrictionPatch::exactScaled(double scale, const Vec3& w, Mat3* jacobian,
                                double tolerance) const {
  const Vec3 u = unitDirection(w);
  const double invNorm = 1.0 / safeNorm(w);
  if (hertz_) {
    // ∫ p k dA = Pz ∫ p1 k dA, p1 the unit-load Hertz pressure (57)
    const Vec3 q =
        internal::exactDiskHertz(shape_.centre(), shape_.radius(), rho_, u, jacobian, tolerance);
    // homogeneous of degree 0: the Jacobian at w is the one at u over |w|
    if (jacobian) *jacobian *= scale * moments_.Pz * invNorm;
    return scale * moments_.Pz * q;
  }
  internal::ExactBasis basis;
  const bool wantJacobian = jacobian != nullptr;
  if (shape_.isDisk()) {
    internal::exactDiskBasis(shape_.centre(), shape_.radius(), rho_, u, wantJacobian, basis,
                             tolerance);
  } else {
    internal::exactPolygonBasis(shape_.vertices(), rho_, u, wantJacobian, basis, tolerance);
  }
  // ∫ p k dA = F (p0, cx, cy)
  const Vec3 c = pressure_.coefficients();
  if (jacobian) {
    *jacobian = (scale * invNorm) * (c[0] * basis.dF[0] + c[1] * basis.dF[1] + c[2] * basis.dF[2]);
  }
  return scale * (basis.F * c);
}

std::optional<Vec3> FrictionPatch::QofSlip(Model model, const Vec3& x_o) const {
  internal::requireFinite(x_o, "slip state x_o");
  if (x_o.cwiseAbs().maxCoeff() == 0.0) return std::nullopt;  // sticking: set-valued
  return Q(model, x_o);  // Q normalises without under/overflow
}

}  // namespace patchspin
