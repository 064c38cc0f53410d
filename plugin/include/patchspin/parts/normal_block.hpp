// Normal block part: the 3-DOF normal block of a flat patch (DESIGN item 5;
// docs/solver.md, Eqs. (S4)-(S6), (S17)-(S19)): the normal velocity at O and the two tilt
// rates, held by the impulse (Lambda_z, Lambda_Tx, Lambda_Ty) while its centre
// of pressure lies on the patch; off the patch the centre of pressure is
// clamped to it and the body is tipping.
//
// Life cycle per step (Jolt-style): normalTargets (properties) -> warm start
// (the adapter applies the last step's impulse) -> solveNormalVelocity in
// every iteration -> solveNormalPosition in the split-impulse iterations.
#pragma once

#include <algorithm>
#include <cmath>

#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>

namespace patchspin::parts {

// Distance of the centre of pressure beyond the patch, relative to the patch
// diameter, beyond which the body counts as tipping: small against 1, large
// against round-off (normal_block_test).
constexpr double kTipRelTol = 1e-3;
// Closing a patch's gap may take the low side of a face tilted on the other
// (within the flatness tolerance) this far into it, relative to the patch
// size (1e-3: the sink of a tilt of 1e-3 rad, a twentieth of the default
// flatness tolerance; guarded by PatchShapeIsRebuiltOnlyWhenTheOutlineChanges
// and the pour tests).
constexpr double kLowSideSinkRelTol = 1e-3;

// What the normal block reads of the patch's outline (fixed within a step).
struct PatchOutlineSummary {
  bool disk = true;
  Vec2 centre = Vec2::Zero();           // disk centre in the patch frame [m]
  double radius = 0.0, diameter = 0.0;  // [m]
  // squared radius of the largest disk about O inside a polygon patch [m^2]:
  // a centre of pressure within it is on the patch without the edge tests
  double innerRadius2 = 0.0;
};
PatchOutlineSummary summarizeOutline(const PatchShape& shape);

// Normal impulses (Lambda_z, couple about x, couple about y) on the moving
// body <-> loads of Eq. (94): the pressure's couple on the body is
// (int y p, -int x p) = (-Tx, -Ty) with Tx = -int y p, Ty = int x p (Eq. (3)), (S5)
inline PatchLoads toLoads(const Vec3& lamN) {
  return PatchLoads{lamN[0], -lamN[1], -lamN[2]};
}

// The point of the patch nearest to p (p itself if inside; on an arc of an
// arc region, radial).
Vec2 nearestPointOn(const PatchShape& shape, const Vec2& p);
// The pivot points of a centre of pressure cop off the patch, as the clamp
// takes them: the two corners of the polygon edge nearest to cop when its
// nearest point is inside that edge, else the nearest point (a vertex or a
// disk's rim). Returns how many (1 or 2) were written to out.
int pivotPoints(const PatchShape& shape, const Vec2& cop, Vec2 (&out)[2]);
// Squared distance from O to the nearest edge line of a polygon patch, less
// a relative 1e-9 for round-off (0 if O is not inside; disks: 0; arc
// regions: the radius of the disk about O inside every segment's half-plane
// and every arc's circle).
double innerRadiusSquared(const PatchShape& shape);

// Velocity targets from the position error: gap at O (< 0 penetrating) and
// tilt rate (0, tilt.ex, tilt.ey) of the face.                             (S17)-(S19)
//   gap > 0:        close at most the gap in one step, no deeper than
//                   kLowSideSinkRelTol * size past the low side (clearance)
//   split impulse:  pseudo-velocity target (-gap, tilt) * erp / dt
//   otherwise:      Baumgarte, (-gap, tilt) * erp2 / dt in the velocity target
// plus the restitution velocity `bounce` (restitutionBounce) in the normal
// velocity target (as Bullet adds its restitution to a row's velocity
// error); the tilt rates get none (a face that lands flat leaves flat: no
// rocking).
struct NormalTargets {
  Vec3 velocity = Vec3::Zero();  // of the iterations [m/s, rad/s, rad/s]
  Vec3 push = Vec3::Zero();      // of the split-impulse iterations
};
NormalTargets normalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                            double dt, bool splitImpulse, double erp, double erp2, double bounce);

// Restitution as Bullet's btSequentialImpulseConstraintSolver::restitutionCurve:
// a contact closing at `approach` (normal velocity before the step, < 0
// closing [m/s]) is to separate at restitution * -approach; none when
// |approach| < threshold (Bullet's m_restitutionVelocityThreshold), nor for a
// separating contact or a negative coefficient (normal_block_test).
inline double restitutionVelocity(double approach, double restitution, double threshold) {
  if (std::abs(approach) < threshold) return 0.0;
  return std::max(0.0, restitution * -approach);
}

// When the bounce happens (S20). Where the faces touch (gap <= 0 [m]) it is this
// step's: the larger of restitutionVelocity and `pending`, the bounce owed by
// a landing in the last step. Across a gap the body closes in this step at
// its approach speed, it lands (the gap's target holds it at the face) and
// bounces in the next step, off the face, with the speed it landed at; a
// gap that stays open gives none. (Bullet's row adds its bounce to the gap's
// target instead: a patch found across a gap would then spend the bounce
// slowing the approach, step after step; restitution_test.)
struct Bounce {
  double now = 0.0;   // restitution velocity of this step's normal target [m/s]
  double next = 0.0;  // owed to the next step (a landing) [m/s]
};
inline Bounce restitutionBounce(double approach, double gap, double dt, double restitution,
                                double threshold, double pending) {
  Bounce b;
  if (gap <= 0.0)
    b.now = std::max(restitutionVelocity(approach, restitution, threshold), pending);
  else if (pending > 0.0)
    b.now = pending;  // landed in the last step, a round-off or a sink allowance above the face
  else if (gap <= -approach * dt)
    b.next = restitutionVelocity(approach, restitution, threshold);
  return b;
}

// Soft contacts (S23)-(S24). Bullet makes a contact point compliant with a
// CFM c_p (velocity per impulse, its cfm after the 1/dt) and an ERP e_p: a
// contact stiffness k and damping d give c_p = 1 / (dt (dt k + d)) and e_p =
// dt k / (dt k + d), and the point's row converges to
//   u_n = e_p depth / dt - c_p lambda,
// an implicit spring-damper (lambda / dt = k depth - (d + dt k) u_n). A soft
// patch is as compliant along its normal as a full manifold of such points
// (kSoftContactPoints) in parallel, and held flat as a hard patch is (its
// tilt rows stay rigid: no rocking on the springs):
//   c_n = t_n - (c_p / kSoftContactPoints) (Lambda_z, 0, 0)                (S23)
// so, resting, it sinks m g / (kSoftContactPoints k), as a body on a full
// manifold does in Bullet (soft_contact_test).
// Bullet's manifold capacity (MANIFOLD_CACHE_SIZE): a face resting flat
// fills it.
constexpr int kSoftContactPoints = 4;
inline double patchCompliance(double pointCfm) {
  return pointCfm / kSoftContactPoints;
}

// The targets of a soft patch: the gap's error in the normal velocity target
// with e_p (Baumgarte, as Bullet's rows put a soft contact's: its spring is
// that error); the tilt's as on a hard patch (S18)-(S19); a gap closes as
// (S17). Plus the restitution velocity `bounce`.                          (S24)
NormalTargets softNormalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                                double dt, bool splitImpulse, double erp, double erp2,
                                double softErp, double bounce);

struct NormalImpulse {
  Vec3 lamN = Vec3::Zero();  // accumulated (Lambda_z, Lambda_Tx, Lambda_Ty) [N s, N m s]
  bool interior = false;     // centre of pressure on the patch: the block held bilateral
  bool tipping = false;      // clamped by more than kTipRelTol of the diameter
};
// The clamp of solveNormalVelocity (S6): y's centre of pressure cop is off the
// patch, so the body pivots on the patch's boundary. out gets the impulse
// of the point contacts there that stop their normal velocity (the
// velocity condition of (S4) on those points alone, W = Winv^-1 the normal
// DOFs' velocity per impulse, residual = target - c_n before this visit):
// the two corners of the polygon edge (or arc region's segment) nearest to
// cop, both pushing; else the one nearest point (a vertex, a disk's rim, an
// arc's radial point, or the corner of that edge
// that pushes), pushing or nothing; and whether that is tipping (cop more
// than kTipRelTol of the diameter off). Keeping y's normal force at the
// nearest point instead over-pushed a pivoting body's edge: a heavy box
// pushing a light one over spun it up (normal_block_test).
void clampNormalImpulse(const Mat3& Winv, const Vec3& lamN, const Vec3& residual, const Vec2& cop,
                        const PatchOutlineSummary& outline, const PatchShape& shape,
                        NormalImpulse& out);
// One velocity solve:                                                     (S4)-(S6)
//   y = lamN - W^-1 (c_n - target),  accepted while y_z > 0 and its centre of
//   pressure (-y2 / y0, y1 / y0) is on the patch; else clamped onto it.
// (Inline, as Jolt keeps its parts' solve steps: every patch visit calls it;
// the clamp, the rare path, is the call.)
inline NormalImpulse solveNormalVelocity(const Mat3& Winv, const Vec3& lamN, const Vec3& cn,
                                         const Vec3& target, const PatchOutlineSummary& outline,
                                         const PatchShape& shape) {
  const Vec3 y = lamN - Winv * (cn - target);
  NormalImpulse out;
  if (y[0] > 0.0) {
    // centre of pressure (Ty / Pz, -Tx / Pz) = (-y2 / y0, y1 / y0)
    const Vec2 cop(-y[2] / y[0], y[1] / y[0]);
    const bool onPatch =
        outline.disk ? (cop - outline.centre).squaredNorm() <= outline.radius * outline.radius
                     : cop.squaredNorm() <= outline.innerRadius2 || shape.contains(cop);
    if (onPatch) {
      out.lamN = y;
      out.interior = true;
    } else {
      clampNormalImpulse(Winv, lamN, target - cn, cop, outline, shape, out);
    }
  }
  return out;
}

// One position solve on the pseudo velocities: pushes only apart.          (S18)
inline Vec3 solveNormalPosition(const Mat3& Winv, const Vec3& lamPush, const Vec3& c,
                                const Vec3& target) {
  Vec3 lam = lamPush - Winv * (c - target);
  if (lam[0] < 0.0) lam.setZero();
  return lam;
}

}  // namespace patchspin::parts
