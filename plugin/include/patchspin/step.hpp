// The implicit 3-DOF friction block of one patch (DESIGN item 4), used inside
// solver iterations and by the reference dynamics.
//
// Coordinates are those of the slip state x_o = (u_x, u_y, rho w_z). The
// friction impulse is lambda = (P_x, P_y, T_z / rho) dt [N s]; applying it
// changes the slip by K lambda. b is the slip the block would have without its
// own impulse. With L = mu * (normal impulse) [N s] and the unit law
// q(w) = Q(w) / (mu Pz):
//     lambda = L q(w),   w = s / |s|,   s = b + K lambda       (slip)
//     s = 0, lambda = -K^-1 b inside the friction set L*E        (stick)
// Ellipsoidal (q = -Pi w), A = L K Pi: stick iff |A^-1 b| <= 1, else
// w = (r I + A)^-1 b with the scalar r > 0 such that |w| = 1.
// Exact: the law has maximum dissipation (convex limit set), so the block is
// the projection of -K^-1 b onto L*E in K's metric; solved as the minimum of
// the convex slip potential D(s) = 1/2 (s-b)^T K^-1 (s-b) - L min_{q in E} q.s
// by safeguarded Newton.
#pragma once

#include <patchspin/models.hpp>

namespace patchspin {

struct FrictionBlockInput {
  Vec3 b = Vec3::Zero();        // free slip [m/s]
  Mat3 K = Mat3::Identity();    // slip change per unit impulse, SPD [1/(kg)]
  double L = 0.0;               // mu * normal impulse [N s], >= 0
  Vec3 warmSlip = Vec3::Zero(); // previous solution's slip, or zero
  // Exact law only: where the stick test's search for the limit set's
  // boundary along -K^-1 b starts, a previous result's gaugeSlip, or zero
  // (then from the ellipsoidal estimate). Only its direction is used.
  Vec3 warmGauge = Vec3::Zero();
  // Relative residual at which the iterations stop, in [0, 1); 0 selects the
  // default 1e-14 (~100 ulps of double). A caller whose inputs carry less
  // precision (single-precision Bullet: ~6e-8) may stop earlier.
  double tolerance = 0.0;
};

struct FrictionBlockResult {
  Vec3 impulse = Vec3::Zero();  // lambda [N s]
  Vec3 slip = Vec3::Zero();     // s = b + K lambda [m/s]
  bool sticking = false;
  int iterations = 0;
  // Exact law, where the stick test located the boundary of the unit limit
  // set E along lambda0 = -K^-1 b: the slip direction w (unit) and the law
  // value q(w) there, a point of E's boundary whose direction is within the
  // block's tolerance of that ray. Zero when the test did not locate it (a
  // slip proven first, the ellipsoidal law).
  Vec3 gaugeSlip = Vec3::Zero();
  Vec3 gaugeValue = Vec3::Zero();
};

// Solves the block for `patch` (its Pi or its exact law; its Pz only sets the
// scale of q). Throws Error for non-finite input or a K that is not SPD (symmetric to
// 1e-10 of its largest entry; positive definite as decided by a Cholesky
// factorisation of its symmetric part, reliable to a unit-diagonal condition
// of ~1e15 whatever the diagonal's spread; a K singular to round-off fails).
// The block is homogeneous in (K, b, L); far from unit scale it is solved at
// |K| ~ |b| ~ 1 (powers of two), so b and K of 1e-300 or 1e300 are fine.
// It also refuses a K that is numerically singular: condition number above
// 1e10 once scaled to a unit diagonal (the exact law always checks; the
// ellipsoidal one when L K Pi is ill-conditioned), and the exact law a K
// whose diagonal spans more than 1e200 or whose determinant overflows: its
// slip potential needs K^-1. Every stick verifies b + K lambda = 0 (to 1e-10
// of |b| + |K| |lambda|) and refuses K as numerically singular otherwise.
// Every answer is checked as the exact solution of a nearby block: a stick
// stops the slip (above) with -K^-1 b from K's Cholesky factor, an
// ellipsoidal slip has its slip along w with |w| = 1, impulse -L Pi w, to
// max(1e-10, 100 tolerance) of |b| + |L K Pi| (else it is solved again by
// pivoted solves with rI + L K Pi, then with K + (r / L) Pi^-1 scaled by K's
// diagonal, which resolves a K with a unit-diagonal condition of 1.9e9 on
// a diagonal spanning 1.2e27; K is refused as numerically singular if even
// that misses), and, where K's
// plain condition number |K|_F |K^-1|_F times max(1, lever, 1 / lever)
// (the lever max|r| / rho, below) is 1e5 or more, an exact slip is
// the law at its own slip to 1e-7 and does not gain kinetic energy
// (s^T K^-1 s <= b^T K^-1 b), or the block is refused ("cannot resolve":
// its slip potential weighs the slip by K^-1). The Bullet
// integration's blocks have a unit-diagonal condition of at most ~10 and a
// diagonal span of ~6e3 (measured over the stress scenes).
// Both laws also refuse a K whose diagonal spans more than 1e30 (both
// blocks lose every digit from ~1e36 on; a physical K, the slip mobilities
// of the two bodies' force and spin rows, spans a ratio of lengths
// squared).
// Domain in the patch (both laws; Error outside it, whatever b, K and L):
//  * the pressure is >= 0 on the patch, to 1e-6 of the mean pressure Pz / A
//    (both laws' blocks need a convex limit set; nearestAdmissibleLoads
//    returns such pressures, and a Hertz pressure always is one);
//  * the lever max|r| / rho (farthest patch point from O over rho) lies in
//    [1e-5, 1e5]. Eq. (11)'s rho gives 1 to ~3; rho only scales the spin
//    coordinate, so this refuses only a rho set more than 1e5 times off the
//    patch's size. Within it the block is accurate to ~1e-14 lever (long)
//    and ~1e-13 / lever (short) of the limit set; beyond it, to nothing;
//  * exact law: its round-off, 64 eps max(1, diameter^2 / A) times the
//    pressure's terms about O over Pz, A (|p0| + (|cx| + |cy|) max|r|) /
//    Pz, stays below 1e-6 (a sliver with a pressure whose terms cancel has
//    no digits left; a 1 m x 1 mm face with terms 10 times Pz: 1.4e-10).
//    Far from O a polygon's Pz keeps its digits (its area moments are
//    summed about the vertex mean there; measured up to 2.8 eps of this
//    model in pure translation, 0 to 1e4 diameters from O), so its terms,
//    ~ the distance from O over the size times the pressure's tilt, are
//    all that count.
// The exact block of a patch smaller than 1e-2 rho (a patch far from O
// against its own size) is solved about the patch's centre, where its
// lever is ~1, and moved back to O (fuzz/README.md, item 56).
FrictionBlockResult solveFrictionBlock(const FrictionPatch& patch, Model model,
                                       const FrictionBlockInput& input);

}  // namespace patchspin
