// Nonsmooth analysis of a flat body on a plane (Sect. 3, 5, 6): the model of
// the body (mass matrix (91), gyroscopic matrix (92), pressure coupling
// (94)-(97)), its limit directions (106)-(111) with their classification
// (31)-(34), and a reference integrator of its slip motion (93).
//
// Frames: the patch frame of the core (origin O, z along the contact normal
// into the body). Sign convention: the paper's Eq. (3) writes the pressure
// moments as Tx = -∫y p, Ty = ∫x p, which is minus the physical moment of the
// pressure on the body about O, (∫y p, -∫x p). The Newton-Euler equations
// (85)-(86) need the physical moment, so this module works with it: a couple
// +T about x presses the -y side of the patch (c_y < 0). The paper's
// Sect. 6.2-6.3 formulas therefore hold here with w2 -> -w2 (6.2) and
// T -> -T (6.3); see tests/core/analysis_limits_test.cpp.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <optional>
#include <patchspin/geometry.hpp>
#include <patchspin/models.hpp>
#include <patchspin/simulation.hpp>
#include <patchspin/types.hpp>
#include <vector>

namespace patchspin {

// A rigid body standing on a flat patch of a horizontal plane (Sect. 5.1).
// All vectors in the patch frame at psi = 0.
struct FlatBody {
  PatchShape shape = PatchShape::disk(1.0);  // contact patch
  double mass = 1.0;                         // m [kg]
  double Jz = 0.5;                           // inertia about the z axis through C [kg m^2]
  double Jxz = 0.0;                          // inertia tensor entries about C, so that the
  double Jyz = 0.0;                          //   angular momentum is omega_z (Jxz, Jyz, Jz) (80)
  Vec3 com = Vec3::Zero();                   // r_c = (x_c, y_c, z_c) [m]
  double mu = 0.3;                           // friction coefficient [-]
  double g = 9.81;                           // gravity [m/s^2]; normal force -m g at C
  Vec2 force = Vec2::Zero();                 // horizontal force at C [N]
  Vec3 torque = Vec3::Zero();                // external couple [N m]
  double rho = 0.0;                          // length scale of x_o; <= 0: Eq. (11) about O
};

// Loads acting on the body besides the contact, patch frame.
struct BodyLoads {
  Vec3 force = Vec3::Zero();   // resultant force, applied at C (its z part includes -m g) [N]
  Vec3 couple = Vec3::Zero();  // pure couple [N m]
};

// Contact of the body for one slip direction (Sect. 5.4, 5.6).
struct ContactState {
  Vec3 pressure = Vec3::Zero();  // (p0, cx, cy) of the linear pressure (69)
  double Pz = 0.0;               // normal force [N], Eq. (95)
  Vec3 Q = Vec3::Zero();         // friction wrench (P_x, P_y, T_z / rho), (17)
  Mat3 dQdw = Mat3::Zero();      // dQ/dw including the pressure's dependence on w
  double minPressure = 0.0;      // smallest pressure on the patch [Pa]
};

// The flat body under one friction model: everything Sect. 5 derives from it.
class FlatBodyModel {
 public:
  // Throws Error for non-finite input, m <= 0, Jz <= 0, mu < 0, g <= 0, and
  // for a denormal mu or g (0 < mu < 2.2e-308, g < 2.2e-308): they carry
  // fewer than 53 bits and the loads built from them round to the denormal
  // grid (limit directions 1e-3 to 6e-2 of the field off the fixed point).
  FlatBodyModel(const FlatBody& body, Model model);

  const FlatBody& body() const { return body_; }
  Model model() const { return model_; }
  double rho() const { return rho_; }
  // Mass matrix (91) and gyroscopic matrix (92) in x_o coordinates.
  const Mat3& massMatrix() const { return M_; }
  Mat3 gyroscopicMatrix(double omega) const;
  // Matrix N of (97): the friction wrench's share of the pressure moments.
  const Eigen::Matrix<double, 2, 3>& N() const { return N_; }
  // True when Q depends nonlinearly on w: N != 0 (Sect. 5.6) or the exact law.
  bool isNonlinear() const { return model_ == Model::Exact || !N_.isZero(0.0); }

  // The body's own loads (gravity, force, couple) at psi = 0.
  BodyLoads bodyLoads() const;
  // External wrench Q_e = (P_ex, P_ey, T_ez / rho) about O, Eq. (79), (89).
  Vec3 externalWrench(const BodyLoads& loads) const;

  // Pressure and friction for slip direction w (unit), spin omega [rad/s]
  // (enters through the Jxz, Jyz terms of (96)) and loads. Solves the three
  // linear equations of Sect. 5.6 for (p0, cx, cy). Throws Error if the
  // normal force is not positive or the system is singular.
  ContactState contact(const Vec3& w, double omega, const BodyLoads& loads,
                       bool wantJacobian = false) const;
  // Contact at rest (no slip) carrying the static friction wrench Qs.
  ContactState contactAtRest(const Vec3& Qs, const BodyLoads& loads) const;
  // True if the body can stick: the wrench -Q_e that holds it lies in the
  // friction set of the pressure it produces (maximum dissipation duality).
  bool canStick(const BodyLoads& loads) const;

  // Limit vector field at r = 0, Eq. (98) with x_o -> 0 (psi = 0):
  //   F_o(w) = M^-1 (Q(w) + Q_e);  jac = dF_o/dw.
  Vec3 limitField(const Vec3& w, Mat3* jac = nullptr) const;
  // Linear case (ellipsoidal, N = 0): F_o = B w + c, Eq. (99)-(100).
  Mat3 linearB() const;
  Vec3 linearC() const;

 private:
  // F(w) with Q = -mu F(w) p for p = (p0, cx, cy); dF[k] = d F.col(k) / dw.
  void frictionBasis(Model model, const Vec3& w, Mat3& F, std::array<Mat3, 3>* dF) const;

  FlatBody body_;
  Model model_;
  double rho_ = 0.0;
  Mat3 M_ = Mat3::Identity();
  Mat3 Minv_ = Mat3::Identity();
  Eigen::Matrix<double, 2, 3> N_ = Eigen::Matrix<double, 2, 3>::Zero();
};

// Type of a limit direction, Def. 1-2.
enum class LimitType { Dominant, Isolated, Saddle, Nonhyperbolic };
const char* toString(LimitType type);

struct LimitDirection {
  Vec3 w = Vec3::Zero();    // unit slip direction
  double rdot = 0.0;        // R* = w . F_o(w), Eq. (103) [m/s^2]
  bool attracting = false;  // R* < 0 (Def. 1)
  LimitType type = LimitType::Nonhyperbolic;
  Eigen::Vector2cd eigenvalues;  // nontrivial eigenvalues of the projected Jacobian (31) [1/s]
  double residual = 0.0;         // |(rdot I - B) w - c| or |V*(w)| [m/s^2]
  double minPressure = 0.0;      // smallest pressure on the patch in this direction [Pa]
};

// A continuum of limit directions (Prop. 1, 3): a circle {n.w = offset} on
// the sphere, or the whole sphere.
struct LimitContinuum {
  bool sphere = false;
  Vec3 normal = Vec3::UnitZ();  // unit normal of the circle's plane
  double offset = 0.0;          // the plane is normal . w = offset
  double rdot = 0.0;
  bool attracting = false;
  Vec3 centre() const { return offset * normal; }
  double radius() const;
};

struct LimitAnalysis {
  std::vector<LimitDirection> directions;  // isolated limit directions
  std::vector<LimitContinuum> continua;    // continua (at most one in the linear case)
  bool tipping = false;                    // the pressure turns negative in some reported direction
  bool linear = true;  // solved by the eigenproblem (111), else the sphere solver
  // Poincare-Hopf on the sphere: (#non-saddles - #saddles) must be 2 when all
  // points are hyperbolic and no continuum exists; false flags a miss.
  bool indexConsistent = true;
};

struct LimitOptions {
  int seeds = 600;            // seed points of the sphere solver (nonlinear case)
  bool sphereSolver = false;  // use the sphere solver also in the linear case (cross-check)
};

// All limit directions of the body at rest in the frame psi = 0.
// Far from unit scale the field is solved for the body with its loads and
// masses scaled by powers of two (F_o is linear in both), so fields of 1e-300
// or 1e280 give the same directions, with rates in the body's own units
// (the scale is the larger of the friction field, mu times the pressure's
// loads, and the external one, M^-1 Q_e; a high centre of mass counts in
// the pressure's loads, as the lever of tipping couples, not in M^-1 Q_e).
// Refused with patchspin::Error up front: a centre of mass more than 1e5
// radii of gyration sqrt(Jz / m) from O horizontally. The mass matrix (91)
// then has a unit-diagonal condition of ~4 (1 + m (x_c^2 + y_c^2) / Jz) >=
// 4e10 and neither its inverse nor the field acting through it has digits;
// a physical body touches the ground within a few radii of gyration.
// Degenerate fields are decided up front:
//  * friction below 1e-10 of the external wrench's field c = M^-1 Q_e
//    (mu = 0 included): the two directions +-c / |c|, polished by Newton;
//  * mu = 0 and no external wrench: F_o = 0, every direction is a limit
//    direction: one continuum with `sphere` set and rate 0, no directions;
//  * a field with no digits (friction ~1e-280 of unit loads with no external
//    wrench, e.g. a denormal mu), or masses and loads whose ratio leaves
//    double's range (a denormal Jz against m = 1): patchspin::Error.
LimitAnalysis findLimitDirections(const FlatBodyModel& model,
                                  const LimitOptions& options = LimitOptions());

// Classification of a fixed point w of F_o, Eq. (31)-(34).
LimitDirection classifyDirection(const FlatBodyModel& model, const Vec3& w);

// --- reference dynamics (93) -----------------------------------------------

// State of the body: position of O and heading in the ground frame, slip
// state in the ground frame (u_x, u_y, rho omega) (so no gyroscopic term).
struct BodyState {
  Vec2 position = Vec2::Zero();  // [m]
  double psi = 0.0;              // [rad]
  Vec3 x = Vec3::Zero();         // (u_x, u_y, rho omega) of O, ground axes [m/s]
};

struct ReferenceOptions {
  double tMax = 10.0;          // [s]
  double recordAt = 0.01;      // record w when r first falls below recordAt * r0
  double relTol = 1e-10;       // local error tolerance of the adaptive step
  double sampleDt = 0.0;       // > 0: trajectory samples every sampleDt [s]
  double stopFraction = 1e-9;  // r below stopFraction * r0: slip has ended
};

struct ReferenceRun {
  bool stopped = false;
  double tStop = 0.0;
  Vec3 wRecord = Vec3::Zero();  // ground-frame w at the recording instant (zero if never)
  double tRecord = 0.0;
  BodyState recordState;
  // turn of the slip velocity's direction (ground axes, unwrapped, > 0
  // counter-clockwise) from the start to the recording instant [rad]
  double turnRecord = 0.0;
  BodyState final;
  int steps = 0;
  // smallest pressure on the patch over the run's steps, over the mean pressure
  // Pz / A; negative: the linear pressure turned negative (the body would tip)
  double minPressureRatio = 1.0;
  bool tipping = false;
  std::vector<std::pair<double, BodyState>> samples;
};

// Integrates the slip motion of `model`'s body with its force and couple
// constant in the ground frame (given at psi = 0 = initial heading) by an
// adaptive Dormand-Prince 5(4) step, until slip ends (the stopping instant
// is found by the linear extrapolation r -> 0 at the final rate) or tMax.
ReferenceRun integrateReference(const FlatBodyModel& model, const BodyState& initial,
                                const ReferenceOptions& options = ReferenceOptions());

// The body of a SimulationSpec (cylinder or box) in its patch frame.
FlatBody flatBodyFromSpec(const SimulationSpec& spec);
// `patchspin simulate --engine reference`. Throws Error for model "stock".
SimulationResult simulateReference(const SimulationSpec& spec);

namespace internal {
// n deterministic, nearly uniform points on the unit sphere (Fibonacci lattice).
std::vector<Vec3> fibonacciSphere(int n);
}  // namespace internal

}  // namespace patchspin
