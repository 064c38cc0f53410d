// The implicit 3-DOF friction block of one patch (DESIGN item 4): the
// friction impulse of one solver visit and the slip it leaves, stick or
// slip.
//
// Coordinates are those of the slip state x_o = (u_x, u_y, rho w_z) (10); the
// impulse is lambda = (P_x, P_y, T_z / rho) dt. q(w) = Q(w) / (mu Pz) is the
// patch's unit law (FrictionPatch::unitQ) and E = {q(w)} its limit set.
//   slip:   lambda = L q(w),  w = s / |s|,  s = b + K lambda             (1)
//   stick:  s = 0,  lambda = -K^-1 b  inside L E                         (2)
// Ellipsoidal law, q = -Pi w (41), A = L K Pi: stick iff |A^-1 b| <= 1, else
//   w = (r I + A)^-1 b  with the scalar r > 0 such that |w| = 1.         (3)
// Exact law (16): maximum dissipation (E convex), so the block is the
// projection of -K^-1 b onto L E in K's metric, the minimum of
//   D(s) = 1/2 (s - b)^T K^-1 (s - b) - L min_{q in E} q.s.             (4)
// Friction never adds energy: s^T K^-1 s <= b^T K^-1 b, both laws
// (FrictionBlockTest.NeverAddsEnergy).
//
// Errors: throws Error, naming the cause, for
//  * non-finite input, L < 0, a tolerance outside [0, 1);
//  * K not symmetric (to 1e-10 of its largest entry) or not positive
//    definite (Cholesky of its symmetric part fails);
//  * K numerically singular: condition number 1e10 or more once scaled to a
//    unit diagonal (the exact law always tests it, the ellipsoidal one where
//    L K Pi is ill-conditioned), or a stick that leaves |b + K lambda| above
//    1e-10 (|b| + |K| |lambda|), or an ellipsoidal slip not along its law to
//    max(1e-10, 100 tolerance) of |b| + |L K Pi|;
//  * out of range: K's diagonal spanning more than 1e30, L K Pi (ellipsoidal)
//    or det K (exact) overflowing, or an answer that overflows double;
//  * a patch outside the block's domain: pressure below -1e-6 of the mean
//    Pz / A, lever max|r| / rho outside [1e-5, 1e5], or (exact law) a law
//    whose round-off model 64 eps max(1, diameter^2 / A) A (|p0| + (|cx| +
//    |cy|) max|r|) / Pz exceeds 1e-6;
//  * exact law with |K|_F |K^-1|_F max(1, lever, 1 / lever) of 1e5 or more:
//    a slip that is not the law at its own slip to 1e-6 of the set, or that
//    gains kinetic energy ("cannot resolve").
// Measured accuracy and the reasons for each bound:
// docs/notes/friction-block-measurements.md.
#pragma once

#include <patchspin/models.hpp>

namespace patchspin {

struct FrictionBlockInput {
  Vec3 b = Vec3::Zero();          // free slip: the slip without this block's impulse [m/s]
  Mat3 K = Mat3::Identity();      // slip change per unit impulse, SPD, 3x3 [1/kg]
  double L = 0.0;                 // friction bound mu * normal impulse, >= 0 [N s]
  Vec3 warmSlip = Vec3::Zero();   // previous solution's slip, or zero [m/s]
  Vec3 warmGauge = Vec3::Zero();  // exact law: a previous gaugeSlip (direction only), or zero
  double tolerance = 0.0;         // relative residual in [0, 1) where iterations stop; 0: 1e-14
  // exact law: the caller's Pi^-1 of this patch (patch.Pi().inverse(), kept
  // while the pressure stays), or null: the block inverts Pi itself
  const Mat3* piInverse = nullptr;
};

struct FrictionBlockResult {
  Vec3 impulse = Vec3::Zero();     // lambda [N s]
  Vec3 slip = Vec3::Zero();        // s = b + K lambda; zero when sticking [m/s]
  bool sticking = false;           // true: s = 0, lambda = -K^-1 b inside L E
  int iterations = 0;              // iterations spent (Newton, root search, polish)
  Vec3 gaugeSlip = Vec3::Zero();   // exact law: unit w whose q(w) lies along -K^-1 b; else zero
  Vec3 gaugeValue = Vec3::Zero();  // exact law: q(gaugeSlip), a point of E's boundary; else zero
};

// Slivers (an edge resting on a face). With O at the patch's centroid, a
// linear pressure p >= 0 has |grad p| <= 3 p0 / w (the centroid lies at
// least w / 3 from every supporting line; w the least width, A <= d w), so
// the exact law's terms A (|p0| + (|cx| + |cy|) max|r|) / Pz stay below
// 1 + 3 sqrt(2) d^2 / A, and its round-off model above below 1e-6 while
// s = d^2 / A <= kMaxSliverRatio (64 eps s (1 + 3 sqrt(2) s) = 1e-6 at
// s = 4074). A patch beyond it may lose the exact law's digits under an
// admissible pressure (and the pressure's projection, nearestAdmissibleLoads,
// its digits: measured at d^2 / A = 3e6): adapters leave it to point
// contacts before either (FrictionBlockSlivers.*).
constexpr double kMaxSliverRatio = 4000.0;
// d^2 / A of a shape [-] (4 / pi for a disk, 2 for a square).
inline double sliverRatio(const PatchShape& shape) {
  return shape.diameter() / shape.area() * shape.diameter();
}

// Solves the block (1)-(4) for `patch` (its Pi or its exact law; its Pz only
// sets the scale of q) with the law `model`. Homogeneous in (K, b, L): far
// from unit scale it is solved at |K| ~ |b| ~ 1 (powers of two, exact).
FrictionBlockResult solveFrictionBlock(const FrictionPatch& patch, Model model,
                                       const FrictionBlockInput& input);

}  // namespace patchspin
