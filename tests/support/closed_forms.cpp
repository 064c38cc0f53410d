// The paper's reference formulas, see closed_forms.hpp.
#include "closed_forms.hpp"

#include <cmath>
#include <limits>

namespace patchspin::testing {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double ellipticK(double m) {
  return std::comp_ellint_1(std::sqrt(m));
}
double ellipticE(double m) {
  return std::comp_ellint_2(std::sqrt(m));
}

double diskSlipRatio(const Vec3& w, double R, double rho) {
  const double wxy = std::hypot(w.x(), w.y());
  if (w.z() == 0.0) return std::numeric_limits<double>::infinity();
  return rho / R * wxy / std::abs(w.z());
}

// Eq. (52). At eps = 1 both branches meet: (eps^2 - 1) K -> 0, E(1) = 1, so
// P(1) = (4/3) 2 / pi = 8 / (3 pi).
double uniformDiskForce(double eps) {
  if (std::isinf(eps)) return 1.0;
  const double e2 = eps * eps;
  if (eps == 1.0) return 8.0 / (3.0 * kPi);
  if (eps < 1.0) {
    if (eps == 0.0) return 0.0;
    return 4.0 / 3.0 * ((e2 + 1.0) * ellipticE(e2) + (e2 - 1.0) * ellipticK(e2)) / (eps * kPi);
  }
  const double m = 1.0 / e2;
  return 4.0 / 3.0 * ((e2 + 1.0) * ellipticE(m) - (e2 - 1.0) * ellipticK(m)) / kPi;
}

// Eq. (53); at eps = 1: (2/3) 2 / pi = 4 / (3 pi). The eps >= 1 branch is
// divided by eps^-1, i.e. multiplied by eps.
double uniformDiskTorque(double eps) {
  if (std::isinf(eps)) return 0.0;
  const double e2 = eps * eps;
  if (eps == 1.0) return 4.0 / (3.0 * kPi);
  if (eps < 1.0)
    return 2.0 / 3.0 * ((4.0 - 2.0 * e2) * ellipticE(e2) + (e2 - 1.0) * ellipticK(e2)) / kPi;
  const double m = 1.0 / e2;
  return 2.0 / 3.0 * eps *
         ((4.0 - 2.0 * e2) * ellipticE(m) + (2.0 * e2 - 5.0 + 3.0 * m) * ellipticK(m)) / kPi;
}

// Eq. (58).
double hertzDiskForce(double eps) {
  if (std::isinf(eps)) return 1.0;
  const double e2 = eps * eps;
  if (eps <= 1.0) return 3.0 * kPi / 32.0 * eps * (4.0 - e2);
  return 3.0 / (16.0 * eps) *
         (e2 * (4.0 - e2) * std::asin(1.0 / eps) + (e2 + 2.0) * std::sqrt(e2 - 1.0));
}

// Eq. (59).
double hertzDiskTorque(double eps) {
  if (std::isinf(eps)) return 0.0;
  const double e2 = eps * eps;
  const double poly = 3.0 * e2 * e2 - 8.0 * e2 + 8.0;
  if (eps <= 1.0) return poly / 8.0;
  return (poly * std::asin(1.0 / eps) + (6.0 - 3.0 * e2) * std::sqrt(e2 - 1.0)) / (4.0 * kPi);
}

double uniformDiskPiXY(double R) {
  return 2.0 * R / 3.0;
}
// (48): pi_xy = (2 pi / Pz) ∫_0^R p(s) s^2 ds = 3 R ∫_0^1 t^2 sqrt(1 - t^2) dt = 3 pi R / 16.
double hertzDiskPiXY(double R) {
  return 3.0 * kPi * R / 16.0;
}

namespace {
template <class ForceFn, class TorqueFn>
Vec3 axisymmetricDiskQ(double R, double mu, double Pz, double rho, const Vec3& w, double piXY,
                       ForceFn force, TorqueFn torque) {
  const Vec3 u = w.normalized();
  const double wxy = std::hypot(u.x(), u.y());
  const double eps = diskSlipRatio(u, R, rho);
  Vec3 q = Vec3::Zero();
  if (wxy > 0.0) q.head<2>() = -mu * Pz * force(eps) * u.head<2>() / wxy;
  if (u.z() != 0.0) q.z() = -mu * Pz * piXY * std::copysign(torque(eps), u.z()) / rho;
  return q;
}
}  // namespace

Vec3 uniformDiskQ(double R, double mu, double Pz, double rho, const Vec3& w) {
  return axisymmetricDiskQ(R, mu, Pz, rho, w, uniformDiskPiXY(R), uniformDiskForce,
                           uniformDiskTorque);
}

Vec3 hertzDiskQ(double R, double mu, double Pz, double rho, const Vec3& w) {
  return axisymmetricDiskQ(R, mu, Pz, rho, w, hertzDiskPiXY(R), hertzDiskForce, hertzDiskTorque);
}

double thinStripForceAlong(double gamma) {
  return gamma == 0.0 ? 1.0 : std::asinh(gamma) / gamma;
}
double thinStripTorqueAlong(double gamma) {
  return gamma == 0.0
             ? 0.0
             : std::sqrt(1.0 + 1.0 / (gamma * gamma)) - std::asinh(gamma) / (gamma * gamma);
}
double thinStripForceAcross(double gamma) {
  return gamma <= 1.0 ? 1.0 : 1.0 / gamma;
}
double thinStripTorqueAcross(double gamma) {
  return gamma <= 1.0 ? 0.0 : 1.0 - 1.0 / (gamma * gamma);
}

// With rho = L/4, Q3 = Tz / rho = -mu Pz T.
Vec3 thinStripQAlong(double mu, double Pz, double theta) {
  const double gamma = 2.0 * std::tan(theta);
  return -mu * Pz * Vec3(thinStripForceAlong(gamma), 0.0, thinStripTorqueAlong(gamma));
}
Vec3 thinStripQAcross(double mu, double Pz, double theta) {
  const double gamma = 2.0 * std::tan(theta);
  return -mu * Pz * Vec3(0.0, thinStripForceAcross(gamma), thinStripTorqueAcross(gamma));
}

Mat3 referencePointMap(const Vec2& d, double rho) {
  Mat3 W = Mat3::Identity();
  W(0, 2) = -d.y() / rho;
  W(1, 2) = d.x() / rho;
  return W;
}

Mat3 thinStripPi(double a) {
  Mat3 Pi = Mat3::Identity();
  Pi(1, 2) = -2.0 * a;
  Pi(2, 1) = -4.0 * a;
  Pi(2, 2) = 1.0 + 4.0 * a * a;
  return Pi;
}

// Eq. (72): with ∫x^2 dA = pi R^4 / 4 and ∫x^2/r dA = pi R^3 / 3 over the disk,
// and Pz = p0 pi R^2 (70).
PiMoments linearDiskPiMoments(double R, double p0, double cx, double cy) {
  PiMoments m;
  m.Pz = p0 * kPi * R * R;
  m.pi_x = cx * R * R / (4.0 * p0);
  m.pi_y = cy * R * R / (4.0 * p0);
  m.pi_x0 = cx * R / (3.0 * p0);
  m.pi_y0 = cy * R / (3.0 * p0);
  m.pi_xy = 2.0 * R / 3.0;
  return m;
}

// Eq. (73) = (40) with (72) and rho = 2R/3.
Mat3 linearDiskPi(double R, double p0, double cx, double cy) {
  Mat3 Pi = Mat3::Identity();
  Pi(0, 2) = -cy * R / (3.0 * p0);
  Pi(1, 2) = cx * R / (3.0 * p0);
  Pi(2, 0) = -3.0 * cy * R / (8.0 * p0);
  Pi(2, 1) = 3.0 * cx * R / (8.0 * p0);
  return Pi;
}

}  // namespace patchspin::testing
