// Flat body on a plane, Sect. 5: mass and gyroscopic matrices (91)-(92),
// external wrench (79), (89) and the pressure coupling (94)-(97), Sect. 5.6.
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <patchspin/analysis.hpp>
#include <patchspin/internal/exact.hpp>
#include <patchspin/pressure.hpp>

namespace patchspin {

namespace {

void requireNonNegative(double value, const char* what) {
  internal::requireFinite(value, what);
  if (value < 0.0)
    throw Error(std::string(what) + " must be >= 0: got " + internal::formatDouble(value));
}

}  // namespace

namespace internal {
std::vector<Vec3> fibonacciSphere(int n) {
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(n));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    points.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
  }
  return points;
}
}  // namespace internal

FlatBodyModel::FlatBodyModel(const FlatBody& body, Model model) : body_(body), model_(model) {
  internal::requirePositive(body.mass, "mass m");
  internal::requirePositive(body.Jz, "inertia Jz");
  internal::requireFinite(body.Jxz, "inertia Jxz");
  internal::requireFinite(body.Jyz, "inertia Jyz");
  internal::requireFinite(body.com, "centre of mass r_c");
  requireNonNegative(body.mu, "friction coefficient mu");
  internal::requirePositive(body.g, "gravity g");
  // denormal mu or g: fewer than 53 bits, and m g, mu m g round to the
  // denormal grid before the limit solver's unit scale can help (found by
  // fuzzing: mu = 2.7e-310, or g = 1.8e-322 against mu = 2.6e256, gave
  // limit directions 1e-3 to 6e-2 of the field off the fixed point)
  constexpr double kSmallest = std::numeric_limits<double>::min();
  if (body.mu > 0.0 && body.mu < kSmallest)
    throw Error("friction coefficient mu = " + internal::formatDouble(body.mu) +
                " is denormal (below 2.2e-308): use 0 or a normal double");
  if (body.g < kSmallest)
    throw Error("gravity g = " + internal::formatDouble(body.g) +
                " m/s^2 is denormal (below 2.2e-308)");
  internal::requireFinite(body.force, "force");
  internal::requireFinite(body.torque, "torque");
  internal::requireFinite(body.rho, "length scale rho");
  rho_ = body.rho > 0.0 ? body.rho : body.shape.defaultRho();

  // Eq. (78): x_c = W x_o;  (91): M = W^T diag(m, m, Jz) W
  const double xc = body.com.x(), yc = body.com.y(), zc = body.com.z();
  Mat3 W;
  W << 1.0, 0.0, -yc / rho_, 0.0, 1.0, xc / rho_, 0.0, 0.0, 1.0 / rho_;
  const Mat3 Mc = Vec3(body.mass, body.mass, body.Jz).asDiagonal();
  M_ = W.transpose() * Mc * W;
  Minv_ = M_.inverse();

  // Eq. (97), j = J / Jz
  const double jxz = body.Jxz / body.Jz, jyz = body.Jyz / body.Jz;
  N_ << jxz * yc, -(jxz * xc + zc), rho_ * jxz, jyz * yc + zc, -jyz * xc, rho_ * jyz;
}

Mat3 FlatBodyModel::gyroscopicMatrix(double omega) const {
  // Eq. (92) = W^T G_C W. The paper's G_C of (89) and hence (92) drop the
  // mass: (82)-(83) read m (v_cx' - w_z v_cy) = ..., so G_C = m w_z [[0,-1,0],
  // [1,0,0],[0,0,0]] and G = m w_z [[0,-1,-xc],[1,0,-yc],[xc,yc,0]] (xc, yc
  // over rho). Without m the ground-frame velocity turns at the wrong rate.
  const double xc = body_.com.x() / rho_, yc = body_.com.y() / rho_;
  Mat3 G;
  G << 0.0, -1.0, -xc, 1.0, 0.0, -yc, xc, yc, 0.0;
  return (body_.mass * omega) * G;
}

BodyLoads FlatBodyModel::bodyLoads() const {
  BodyLoads loads;
  loads.force = Vec3(body_.force.x(), body_.force.y(), -body_.mass * body_.g);
  loads.couple = body_.torque;
  return loads;
}

Vec3 FlatBodyModel::externalWrench(const BodyLoads& loads) const {
  // Eq. (79): T_e about O = couple + r_c x P_e;  (89): Q_e = (P_ex, P_ey, T_ez / rho)
  const Vec3 Te = loads.couple + body_.com.cross(loads.force);
  return Vec3(loads.force.x(), loads.force.y(), Te.z() / rho_);
}

void FlatBodyModel::frictionBasis(Model model, const Vec3& w, Mat3& F,
                                  std::array<Mat3, 3>* dF) const {
  const PatchShape& shape = body_.shape;
  if (model == Model::Exact) {
    internal::ExactBasis basis;
    if (shape.isDisk()) {
      internal::exactDiskBasis(shape.centre(), shape.radius(), rho_, w, dF != nullptr, basis);
    } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
      internal::exactArcRegionBasis(shape.boundary(), rho_, w, dF != nullptr, basis);
    } else {
      internal::exactPolygonBasis(shape.vertices(), rho_, w, dF != nullptr, basis);
    }
    F = basis.F;
    if (dF) *dF = basis.dF;
    return;
  }
  // Ellipsoidal (40)-(41) per pressure basis function phi_k in {1, x, y}:
  //   Pz Pi = sum_k p_k D_k,  D_k = [[m1, 0, -m_y/r], [0, m1, m_x/r], [-m_y, m_x, m_r] / rho]
  const auto& m = shape.momentTable().m;
  using Row = MomentTable::Row;
  for (int k = 0; k < 3; ++k) {
    Mat3 D;
    D << m(Row::kOne, k), 0.0, -m(Row::kYOverR, k), 0.0, m(Row::kOne, k), m(Row::kXOverR, k),
        -m(Row::kY, k) / rho_, m(Row::kX, k) / rho_, m(Row::kR, k) / rho_;
    F.col(k) = D * w;
    if (dF) (*dF)[static_cast<std::size_t>(k)] = D;
  }
}

ContactState FlatBodyModel::contact(const Vec3& wIn, double omega, const BodyLoads& loads,
                                    bool wantJacobian) const {
  const Vec3 w = wIn.normalized();
  const double xc = body_.com.x(), yc = body_.com.y(), zc = body_.com.z();
  const Vec3& Pe = loads.force;
  const Vec3 Te = loads.couple + body_.com.cross(loads.force);
  ContactState out;
  out.Pz = -Pe.z();  // Eq. (95)
  if (!(out.Pz > 0.0)) {
    throw Error("flat body: the normal force must press the body onto the plane (Pz = " +
                internal::formatDouble(out.Pz) + " N)");
  }
  // Eq. (96): physical pressure moment about O, tau = tau0 + N Q, with
  //   tau0 = (-Tex - Pey zc - Jyz w^2 + jxz X,  -Tey + Pex zc + Jxz w^2 + jyz X),
  //   X = Tez + Pex yc - Pey xc.
  const double X = Te.z() + Pe.x() * yc - Pe.y() * xc;
  const double jxz = body_.Jxz / body_.Jz, jyz = body_.Jyz / body_.Jz;
  const double w2 = omega * omega;
  const double tau0x = -Te.x() - Pe.y() * zc - body_.Jyz * w2 + jxz * X;
  const double tau0y = -Te.y() + Pe.x() * zc + body_.Jxz * w2 + jyz * X;
  // moment of p about O is (∫y p, -∫x p), and G p = (∫p, ∫x p, ∫y p) (94):
  //   G p = h0 + H Q,  h0 = (Pz, -tau0y, tau0x),  H = [0; -N_y; N_x]
  const Vec3 h0(out.Pz, -tau0y, tau0x);
  Mat3 H = Mat3::Zero();
  H.row(1) = -N_.row(1);
  H.row(2) = N_.row(0);
  // Q = -mu F(w) p  =>  (G + mu H F) p = h0
  Mat3 F;
  std::array<Mat3, 3> dF;
  frictionBasis(model_, w, F, wantJacobian ? &dF : nullptr);
  const Mat3 G = body_.shape.areaMoments().loadMatrix();
  const double mu = body_.mu;
  const Mat3 A = G + mu * H * F;
  Eigen::FullPivLU<Mat3> lu(A);
  if (!lu.isInvertible()) throw Error("flat body: singular pressure equations (Sect. 5.6)");
  out.pressure = lu.solve(h0);
  out.Q = -mu * F * out.pressure;
  if (wantJacobian) {
    // dQ = -mu (Dp + F dp),  Dp = sum_k p_k dF_k,  dp = -A^-1 mu H Dp
    Mat3 Dp = Mat3::Zero();
    for (int k = 0; k < 3; ++k) Dp += out.pressure[k] * dF[static_cast<std::size_t>(k)];
    const Mat3 dp = -lu.solve(mu * H * Dp);
    out.dQdw = -mu * (Dp + F * dp);
  }
  LinearPressure p;
  p.p0 = out.pressure[0];
  p.cx = out.pressure[1];
  p.cy = out.pressure[2];
  out.minPressure = minPressure(body_.shape, p);
  return out;
}

ContactState FlatBodyModel::contactAtRest(const Vec3& Qs, const BodyLoads& loads) const {
  const double xc = body_.com.x(), yc = body_.com.y(), zc = body_.com.z();
  const Vec3& Pe = loads.force;
  const Vec3 Te = loads.couple + body_.com.cross(loads.force);
  ContactState out;
  out.Pz = -Pe.z();
  if (!(out.Pz > 0.0)) {
    throw Error("flat body: the normal force must press the body onto the plane (Pz = " +
                internal::formatDouble(out.Pz) + " N)");
  }
  const double X = Te.z() + Pe.x() * yc - Pe.y() * xc;
  const double jxz = body_.Jxz / body_.Jz, jyz = body_.Jyz / body_.Jz;
  const Eigen::Vector2d tau =
      Eigen::Vector2d(-Te.x() - Pe.y() * zc + jxz * X, -Te.y() + Pe.x() * zc + jyz * X) + N_ * Qs;
  const Mat3 G = body_.shape.areaMoments().loadMatrix();
  out.pressure = G.fullPivLu().solve(Vec3(out.Pz, -tau.y(), tau.x()));
  out.Q = Qs;
  LinearPressure p;
  p.p0 = out.pressure[0];
  p.cx = out.pressure[1];
  p.cy = out.pressure[2];
  out.minPressure = minPressure(body_.shape, p);
  return out;
}

bool FlatBodyModel::canStick(const BodyLoads& loads) const {
  // at rest (x_o = 0, omega = 0) Eq. (93) needs Q = -Q_e
  const Vec3 Qs = -externalWrench(loads);
  const ContactState rest = contactAtRest(Qs, loads);
  const double scale = body_.mu * rest.Pz;
  // a tolerance of 1e-9 of the friction scale: round-off of the solves below
  const double kStickTol = 1e-9;
  if (model_ == Model::Ellipsoidal) {
    // friction set {-Pz Pi v mu : |v| <= 1}:  stick iff |(Pz Pi)^-1 Qs| <= mu
    Mat3 F;
    std::array<Mat3, 3> dF;
    frictionBasis(Model::Ellipsoidal, Vec3::UnitX(), F, &dF);
    Mat3 PzPi = Mat3::Zero();
    for (int k = 0; k < 3; ++k) PzPi += rest.pressure[k] * dF[static_cast<std::size_t>(k)];
    if (scale == 0.0) return Qs.norm() == 0.0;
    return (PzPi.fullPivLu().solve(Qs)).norm() <= body_.mu * (1.0 + kStickTol);
  }
  // exact law: maximum dissipation makes its friction set
  //   {Q : g(w) = (Q - Q(w)).w >= 0 for all unit w},  -Q(w).w = D(w) = mu ∫ p |v(w)| dA.
  // g is minimised from the best point of a coarse grid by Newton on the
  // sphere: grad D = -Q(w) (D is homogeneous of degree 1), so the tangent
  // gradient is P (Qs - Q(w)) and the Hessian -E^T dQ/dw E - (w.(Qs - Q)) I.
  const double tol = -kStickTol * std::max(scale, 1e-300);
  auto g = [&](const Vec3& w, Vec3* Qw, Mat3* dQ) {
    Mat3 F;
    std::array<Mat3, 3> dF;
    frictionBasis(Model::Exact, w, F, dQ ? &dF : nullptr);
    *Qw = -body_.mu * F * rest.pressure;
    if (dQ) {
      dQ->setZero();
      for (int k = 0; k < 3; ++k)
        *dQ -= body_.mu * rest.pressure[k] * dF[static_cast<std::size_t>(k)];
    }
    return (Qs - *Qw).dot(w);
  };
  Vec3 best = Vec3::UnitX(), Qw;
  double lowest = 1e300;
  for (const Vec3& w : internal::fibonacciSphere(400)) {
    const double v = g(w, &Qw, nullptr);
    if (v < lowest) lowest = v, best = w;
  }
  Vec3 w = best;
  for (int it = 0; it < 30 && lowest >= tol; ++it) {
    Mat3 dQ;
    const double v = g(w, &Qw, &dQ);
    lowest = std::min(lowest, v);
    Vec3 a = std::abs(w.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    Eigen::Matrix<double, 3, 2> E;
    E.col(0) = (a - a.dot(w) * w).normalized();
    E.col(1) = w.cross(E.col(0));
    const Eigen::Vector2d grad = E.transpose() * (Qs - Qw);
    const Mat2 H = -E.transpose() * dQ * E - v * Mat2::Identity();
    Eigen::Vector2d step = -grad / std::max(H.norm(), 1e-300);  // gradient step
    if (H.determinant() > 0.0 && H.trace() > 0.0) step = H.fullPivLu().solve(-grad);
    if (step.norm() > 0.2) step *= 0.2 / step.norm();
    if (step.norm() < 1e-14) break;
    w = (w + E * step).normalized();
  }
  lowest = std::min(lowest, g(w, &Qw, nullptr));
  return lowest >= tol;
}

Vec3 FlatBodyModel::limitField(const Vec3& w, Mat3* jac) const {
  const BodyLoads loads = bodyLoads();
  const ContactState c = contact(w, 0.0, loads, jac != nullptr);
  if (jac) *jac = Minv_ * c.dQdw;
  return Minv_ * (c.Q + externalWrench(loads));
}

Mat3 FlatBodyModel::linearB() const {
  // Eq. (99): B = -mu Pz M^-1 Pi, with Pi from the (w-independent) pressure
  const ContactState c = contact(Vec3::UnitX(), 0.0, bodyLoads(), false);
  Mat3 F;
  std::array<Mat3, 3> dF;
  frictionBasis(Model::Ellipsoidal, Vec3::UnitX(), F, &dF);
  Mat3 PzPi = Mat3::Zero();
  for (int k = 0; k < 3; ++k) PzPi += c.pressure[k] * dF[static_cast<std::size_t>(k)];
  return -body_.mu * Minv_ * PzPi;
}

Vec3 FlatBodyModel::linearC() const {
  // Eq. (100) at r = 0 (G x_o = 0)
  return Minv_ * externalWrench(bodyLoads());
}

}  // namespace patchspin
