// FrictionPatch: the ellipsoidal law (41) and the exact law (16) of one patch.
#include <patchspin/internal/exact.hpp>
#include <patchspin/models.hpp>

#include "arc_region_numerics.hpp"
#include "pressure_numerics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patchspin {

namespace {

// A given rho may differ from Eq. (11) by at most this factor either way:
// beyond it, max|r| / rho and its square in the exact law leave double's
// range for patches that are themselves in range (found by fuzzing).
constexpr double kRhoRange = 1e12;

double resolveRho(const PatchShape& shape, double rho) {
  internal::requireFinite(rho, "length scale rho");
  if (!(rho > 0.0)) return shape.defaultRho();
  const double natural = shape.defaultRho();
  if (rho < natural / kRhoRange || rho > natural * kRhoRange) {
    throw Error("length scale rho = " + internal::formatDouble(rho) +
                " m is out of range for this patch: Eq. (11) gives " +
                internal::formatDouble(natural) + " m; allowed 1e-12 to 1e12 times that");
  }
  return rho;
}

void requireMu(double mu) {
  internal::requireFinite(mu, "friction coefficient mu");
  if (mu < 0.0)
    throw Error("friction coefficient mu must be >= 0: got " + internal::formatDouble(mu));
}

// |w| without overflow or underflow (w may be scaled by 1e+-200).
double safeNorm(const Vec3& w) {
  const double m = w.cwiseAbs().maxCoeff();
  return m > 0.0 ? m * (w / m).norm() : 0.0;
}

Vec3 unitDirection(const Vec3& w, double* invNorm = nullptr) {
  internal::requireFinite(w, "slip direction w");
  const double m = w.cwiseAbs().maxCoeff();
  if (!(m > 0.0)) throw Error("slip direction w must be nonzero (w = 0 is sticking)");
  // (w / m).normalized() and 1 / safeNorm(w), sharing m and |w / m|
  const Vec3 scaled = w / m;
  const double n = std::sqrt(scaled.squaredNorm());
  if (invNorm) *invNorm = 1.0 / (m * n);
  return scaled / n;
}

// Largest |p| of a linear pressure on the closed patch.
double maxAbsPressure(const PatchShape& shape, const LinearPressure& p) {
  if (shape.isDisk())
    return std::abs(p.at(shape.centre())) + shape.radius() * internal::planarNorm(p.cx, p.cy);
  if (shape.kind() == PatchShape::Kind::ArcRegion) {
    // max |p| = max(-min p, -min(-p)), both at a piece's start or an arc's
    // point of outward normal along -+grad p
    const auto& b = shape.boundary();
    return std::max(-internal::arcRegionMinLinear(b, p.p0, p.cx, p.cy),
                    -internal::arcRegionMinLinear(b, -p.p0, -p.cx, -p.cy));
  }
  double m = 0.0;
  for (const Vec2& v : shape.vertices()) m = std::max(m, std::abs(p.at(v)));
  return m;
}

// Both laws are bounded by mu ∫|p| dA (1 + max|r| / rho) (exact) and
// mu Pz |Pi| (ellipsoidal); if those overflow, so would Q: refuse up front
// (found by fuzzing: mu = 1e300 gave Q = inf).
void requireFiniteScale(double mu, double absPressure, double Pz, const Mat3& Pi, double reach) {
  const double exactScale = mu * absPressure * (1.0 + reach);
  const double ellipsoidalScale = mu * Pz * Pi.cwiseAbs().maxCoeff();
  // the unit law q = Q / (mu Pz) divides by Pz: a denormal Pz overflows it
  if (!std::isfinite(1.0 / Pz)) {
    throw Error("normal force out of range: Pz = " + internal::formatDouble(Pz) +
                " N is below the smallest normal double");
  }
  if (!std::isfinite(exactScale) || !std::isfinite(ellipsoidalScale)) {
    throw Error("friction out of range: mu * pressure overflows double (mu = " +
                internal::formatDouble(mu) + ", Pz = " + internal::formatDouble(Pz) + " N)");
  }
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
  requireFiniteScale(mu_, moments_.Pz, moments_.Pz, Pi_, disk.maxDistanceFromOrigin() / rho_);
}

void FrictionPatch::setPressure(const LinearPressure& pressure) {
  // both may throw: update nothing until both succeed
  // (piMoments first requires the coefficients finite, with the same message)
  const PiMoments moments = patchspin::piMoments(shape_, pressure);  // throws if Pz <= 0
  const Mat3 Pi = ellipsoidalPi(moments, rho_);
  requireFiniteScale(mu_, shape_.area() * maxAbsPressure(shape_, pressure), moments.Pz, Pi,
                     shape_.maxDistanceFromOrigin() / rho_);
  moments_ = moments;
  pressure_ = pressure;
  hertz_ = false;
  Pi_ = Pi;
}

void FrictionPatch::setMu(double mu) {
  requireMu(mu);
  const double absPressure =
      hertz_ ? moments_.Pz : shape_.area() * maxAbsPressure(shape_, pressure_);
  requireFiniteScale(mu, absPressure, moments_.Pz, Pi_, shape_.maxDistanceFromOrigin() / rho_);
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

namespace {

// dQ/dw of the degree-0 homogeneous exact law scales as 1 / |w|: for a tiny
// (e.g. denormal) w it leaves double's range; say so instead of inf / NaN.
void requireFiniteJacobian(const Mat3* jacobian, const Vec3& w) {
  if (jacobian && !jacobian->allFinite()) {
    throw Error("exact law: dQ/dw overflows at |w| = " + internal::formatDouble(safeNorm(w)) +
                " (it scales as 1/|w|; pass a slip direction of moderate size)");
  }
}

}  // namespace

// scale * ∫ p k(w) dA: scale = -mu gives Eq. (16); -1/Pz the unit law.
Vec3 FrictionPatch::exactScaled(double scale, const Vec3& w, Mat3* jacobian,
                                double tolerance) const {
  double invNorm = 0.0;
  const Vec3 u = unitDirection(w, &invNorm);
  if (hertz_) {
    // ∫ p k dA = Pz ∫ p1 k dA, p1 the unit-load Hertz pressure (57)
    const Vec3 q =
        internal::exactDiskHertz(shape_.centre(), shape_.radius(), rho_, u, jacobian, tolerance);
    // homogeneous of degree 0: the Jacobian at w is the one at u over |w|
    if (jacobian) *jacobian = (scale * moments_.Pz) * Mat3(invNorm * *jacobian);
    requireFiniteJacobian(jacobian, w);
    return scale * moments_.Pz * q;
  }
  // the law's digits: it sums the pressure's terms about O, each up to
  // A |c_k| max|r|^k, over kernel integrals that cancel by diameter^2 / A on
  // a sliver, so its round-off is ~kTermsUlps eps max(1, diameter^2 / A)
  // times those terms (measured up to 26 ulps by the friction_q target).
  // Where that reaches kLawNoDigits of Pz the law is noise: refused, as the
  // exact friction block refuses it (found by fuzzing: Pz = 1.2e-5 from
  // terms of 2.5e5 on a triangle with diameter^2 / A = 4e10 gave |(Px, Py)|
  // = 0.51 against mu ∫|p| = 5.9e-6). An ordinary patch is ~1e4 and more
  // below it (a 1 m x 1 mm face with terms 10 times Pz: 1.4e-10).
  {
    constexpr double kTermsUlps = 64.0, kLawNoDigits = 1e-6;
    const double terms = shape_.area() * (std::abs(pressure_.p0) +
                                          (std::abs(pressure_.cx) + std::abs(pressure_.cy)) *
                                              shape_.maxDistanceFromOrigin());
    const double sliver = std::max(1.0, shape_.diameter() / shape_.area() * shape_.diameter());
    const double roundOff =
        kTermsUlps * std::numeric_limits<double>::epsilon() * sliver * (terms / moments_.Pz);
    if (!(roundOff <= kLawNoDigits)) {
      throw Error("exact law: no digits for this pressure and patch (round-off ~" +
                  internal::formatDouble(roundOff) + " of Pz: terms about O " +
                  internal::formatDouble(terms / moments_.Pz) +
                  " times Pz on a patch of diameter^2 / area " + internal::formatDouble(sliver) +
                  ")");
    }
  }
  // ∫ p k dA = F (p0, cx, cy) and its Jacobian sum_k c_k dF[k] (a polygon
  // integrates p itself in one pass)
  const Vec3 c = pressure_.coefficients();
  Vec3 integral;
  Mat3 sum;
  if (shape_.isDisk()) {
    internal::ExactBasis basis;
    internal::exactDiskBasis(shape_.centre(), shape_.radius(), rho_, u, jacobian != nullptr, basis,
                             tolerance);
    if (jacobian) sum = c[0] * basis.dF[0] + c[1] * basis.dF[1] + c[2] * basis.dF[2];
    integral = basis.F * c;
  } else if (shape_.kind() == PatchShape::Kind::ArcRegion) {
    // F (p0, cx, cy) from the basis (no single-pressure pass yet; the arc
    // law has no tolerance knob: full accuracy). A tolerance the other laws
    // refuse is refused here too (ExactQRefusesAToleranceNoLawAccepts;
    // found by the friction_q fuzz target)
    internal::requireFinite(tolerance, "exact arc region: tolerance");
    if (tolerance < 0.0) {
      throw Error("exact arc region: tolerance must be >= 0: got " +
                  internal::formatDouble(tolerance));
    }
    internal::ExactBasis basis;
    internal::exactArcRegionBasis(shape_.boundary(), rho_, u, jacobian != nullptr, basis);
    if (jacobian) sum = c[0] * basis.dF[0] + c[1] * basis.dF[1] + c[2] * basis.dF[2];
    integral = basis.F * c;
  } else {
    integral = internal::exactPolygonLaw(shape_.vertices(), rho_, u, c, jacobian ? &sum : nullptr,
                                         tolerance);
  }
  if (jacobian) {
    // scale (-1/Pz for the unit law) times invNorm may overflow on its own
    // while the product with the sum is finite (found by fuzzing): sum first
    *jacobian = scale * Mat3(invNorm * sum);
    requireFiniteJacobian(jacobian, w);
  }
  // the integral first: Eigen folds scale * (F c) into (scale F) c, which
  // underflows to 0 for a tiny mu (e.g. 1e-308) even when Q is representable
  const Vec3 Q = scale * integral;
  // the up-front check bounds |Q| by mu ∫|p| (1 + max|r| / rho) < DBL_MAX,
  // but the sum's own terms may exceed that bound by a few times (found by
  // fuzzing: a 3.5e9 m disk with that bound 4.7e307 gave Tz/rho = inf)
  if (!Q.allFinite()) {
    throw Error("exact law: Q overflows double (mu = " + internal::formatDouble(mu_) +
                ", Pz = " + internal::formatDouble(moments_.Pz) +
                " N); reduce the pressure or the lever max|r| / rho");
  }
  return Q;
}

std::optional<Vec3> FrictionPatch::QofSlip(Model model, const Vec3& x_o) const {
  internal::requireFinite(x_o, "slip state x_o");
  if (x_o.cwiseAbs().maxCoeff() == 0.0) return std::nullopt;  // sticking: set-valued
  return Q(model, x_o);                                       // Q normalises without under/overflow
}

}  // namespace patchspin
