// Friction laws of a flat contact patch (Sect. 2, 4).
//
// Slip state x_o = (u_x, u_y, rho w_z) (10), r = |x_o|, w = x_o / r (13)-(14).
// Friction wrench Q = (P_x, P_y, T_z / rho) (17), about O, in the patch frame.
//
//   ellipsoidal  Q(w) = -mu Pz Pi w                                  (41)
//   exact        Q(w) = -mu ∫_A p(x,y) k(w; x,y) dA                   (16)
//                k = (v_x, v_y, (x v_y - y v_x) / rho) / |v|,
//                v = (w1 - w3 y / rho, w2 + w3 x / rho)              (1)
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>

#include <optional>

namespace patchspin {

// Accuracy of the exact model. kFull aims at 1e-12 relative error (the tests
// hold it to 1e-10); coarser settings trade error for time where the
// implementation has a numerical branch (see the README's table).
struct ExactAccuracy {
  double tolerance = 0.0;  // 0: full accuracy; otherwise a target relative error
};

// Everything that defines the friction law of one patch: shape, pressure,
// mu and rho. Pi (40) is cached and refreshed when the pressure changes.
class FrictionPatch {
 public:
  // Linear pressure. rho <= 0 selects Eq. (11) about O. Throws Error for
  // mu < 0, non-finite input, a pressure with Pz <= 0 or whose moments
  // overflow, or a rho more than 1e12 times off Eq. (11) either way.
  FrictionPatch(const PatchShape& shape, const LinearPressure& pressure, double mu,
                double rho = 0.0);
  // Hertz pressure (57) on a disk.
  FrictionPatch(const PatchShape& disk, const HertzPressure& pressure, double mu, double rho = 0.0);

  const PatchShape& shape() const { return shape_; }
  double mu() const { return mu_; }
  double rho() const { return rho_; }
  double Pz() const { return moments_.Pz; }
  bool isHertz() const { return hertz_; }
  const LinearPressure& pressure() const { return pressure_; }
  const PiMoments& piMoments() const { return moments_; }
  // Pi of Eq. (40).
  const Mat3& Pi() const { return Pi_; }

  // New linear pressure (e.g. from the solver's normal block): refreshes Pi
  // in a few dozen flops. Throws Error if Pz <= 0.
  void setPressure(const LinearPressure& pressure);
  void setLoads(const PatchLoads& loads) { setPressure(LinearPressure::fromLoads(shape_, loads)); }
  void setMu(double mu);

  // Friction wrench for a slip direction w (any nonzero vector; normalised
  // internally). `jacobian`, if given, receives dQ/dw of the formula as
  // written: -mu Pz Pi for (41), and the derivative of the degree-0
  // homogeneous (16) for the exact model (so dQ/dw w = 0 there).
  Vec3 ellipsoidalQ(const Vec3& w, Mat3* jacobian = nullptr) const;
  Vec3 exactQ(const Vec3& w, Mat3* jacobian = nullptr,
              const ExactAccuracy& accuracy = ExactAccuracy()) const;
  Vec3 Q(Model model, const Vec3& w, Mat3* jacobian = nullptr) const {
    return model == Model::Ellipsoidal ? ellipsoidalQ(w, jacobian) : exactQ(w, jacobian);
  }

  // The law for unit mu Pz: q(w) = Q(w) / (mu Pz), defined also for mu = 0.
  // Used by the friction block (friction_block.hpp), whose impulse is L q(w).
  Vec3 unitQ(Model model, const Vec3& w, Mat3* jacobian = nullptr) const;

  // Friction wrench for a slip state x_o = (u_x, u_y, rho w_z). At x_o = 0 the
  // law is set-valued (sticking): returns std::nullopt, never NaN; the
  // sticking wrench is the solver's business (see friction_block.hpp).
  std::optional<Vec3> QofSlip(Model model, const Vec3& x_o) const;

 private:
  Vec3 exactScaled(double scale, const Vec3& w, Mat3* jacobian, double tolerance) const;

  PatchShape shape_;
  LinearPressure pressure_;
  bool hertz_ = false;
  double mu_ = 0.0;
  double rho_ = 0.0;
  PiMoments moments_;
  Mat3 Pi_ = Mat3::Identity();
};

// Slip-state helpers, Eq. (10), (13)-(14).
inline Vec3 slipState(double ux, double uy, double omega_z, double rho) {
  return Vec3(ux, uy, rho * omega_z);
}

}  // namespace patchspin
