// Point impulses part: a patch's impulse spread over a few contact points
// (an adapter's record of the contact, e.g. Bullet's manifold points), so
// that whoever reads the points the engine's way sees the patch's force
// (issue 31, item 3; docs/solver.md, "Reported impulses").
//
// In the patch frame at O, with the points at r_i = (x_i, y_i) in the
// patch plane, the patch's normal impulse (Lambda_z, Lambda_Tx, Lambda_Ty)
// (S5) and friction impulse (f_x, f_y, lambda_s), whose couple about n is
// rho lambda_s (S1):
//   normal (S21):      p_i >= 0 with  sum p_i = Lambda_z  exactly, and
//                      sum p_i (y_i, -x_i) = (Lambda_Tx, Lambda_Ty)  when the
//                      centre of pressure lies in the points' convex hull;
//                      else the centre of pressure of the p_i is the hull's
//                      point nearest to it. Of those, the p_i with the least
//                      sum of squares (the most even spread).
//   tangential (S22):  t_i = p_i (a + b perp(r_i)), perp(r) = (-y, x), with
//                      sum t_i = (f_x, f_y) and sum r_i x t_i = rho lambda_s:
//                      the least sum |t_i|^2 / p_i (each point's share
//                      follows its load); a twist the loaded points cannot
//                      carry (all on one point) is not carried, b = 0, and
//                      the force still exactly.
// Closed forms (no decomposition, no heap: every patch, every step).
// Guarded by point_impulses_test (sums, moments, the least-norm property
// against random feasible perturbations, the nearest hull point against
// random convex combinations).
#pragma once

#include <patchspin/types.hpp>

#include <array>

namespace patchspin::parts {

// At most this many points (Bullet's manifolds keep four: MANIFOLD_CACHE_SIZE).
constexpr int kMaxPoints = 4;

struct PointImpulses {
  int count = 0;
  std::array<double, kMaxPoints> normal{};  // p_i [N s]
  std::array<Vec2, kMaxPoints> tangent;     // t_i in the patch frame [N s]
  bool momentMatched = false;               // the normal impulses carry the tipping couple exactly
  bool twistMatched = false;                // the tangential impulses carry the twist exactly
};

// `points`: r_0 .. r_(count-1) in the patch frame [m], 1 <= count <=
// kMaxPoints (else Error); lamN, lamF: the patch's accumulated impulses; rho
// [m]. No heap allocation (called for every patch in every step).
PointImpulses spreadPatchImpulse(const Vec2* points, int count, const Vec3& lamN, const Vec3& lamF,
                                 double rho);

}  // namespace patchspin::parts
