// Patch body part: one body's side of a flat contact patch and the patch's
// six degrees of freedom (DESIGN items 4, 5; docs/solver.md, Eqs. (S1)-(S2)).
// No engine types: an adapter fills PatchBody from its own bodies and adds
// the velocity changes this part returns.
//
// The DOFs, in the patch frame F = [ex ey n] at the reference point O, of the
// relative velocity of A over B (B enters with a minus):
//   0: n.u(O)   1: ex.omega   2: ey.omega       normal block
//   3: ex.u(O)  4: ey.u(O)    5: rho n.omega    friction block: x_o       (S1)
// with u(O) = v + omega x r, r = O - centre of mass.
#pragma once

#include <patchspin/types.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace patchspin::parts {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

struct PatchBody {
  bool dynamic = false;      // a static or kinematic body adds nothing
  Vec3 r = Vec3::Zero();     // lever O - centre of mass, world [m]
  Vec3 invM = Vec3::Zero();  // inverse mass (x) linear factor, world axes [1/kg]
  Mat3 invI = Mat3::Zero();  // world inverse inertia with the angular factor [1/(kg m^2)]
};

// Effective mass of the six DOFs for one body, K6 = J M^-1 J^T       (S2)
// (patch_body_test: against the dense product with patchBodyRows).
Mat6 patchEffectiveMass(const PatchBody& body, const Mat3& F, double rho);
// Both bodies' sum.
Mat6 patchEffectiveMass(const PatchBody& a, const PatchBody& b, const Mat3& F, double rho);

// The DOFs' rows for one body (A's side): c = J [v; omega]           (S1)
Mat6 patchBodyRows(const PatchBody& body, const Mat3& F, double rho);

// The DOF velocities of the patch; `velocity(side, v, w)` gives a dynamic
// body's world velocities (side 0: A, 1: B), a static body's are not asked.
// A template in the header, as applyPatchImpulse: the adapter's gather and
// this sum compile into one function at each use (every patch visit calls
// it; docs/notes/2026-11-28-solver-parts.md counts the call's cost).
template <class Velocity>
inline Vec6 patchVelocityOf(const PatchBody& a, const PatchBody& b, const Mat3& F, double rho,
                            Velocity velocity) {
  Vec3 u = Vec3::Zero(), w = Vec3::Zero();
  Vec3 v, om;
  if (a.dynamic) {
    velocity(0, v, om);
    u += v + om.cross(a.r);
    w += om;
  }
  if (b.dynamic) {
    velocity(1, v, om);
    u -= v + om.cross(b.r);
    w -= om;
  }
  const Vec3 uf = F.transpose() * u, wf = F.transpose() * w;
  Vec6 c;
  c << uf.z(), wf.x(), wf.y(), uf.x(), uf.y(), rho * wf.z();
  return c;
}

// The same from A's (va, wa) and B's (vb, wb) world velocities.
inline Vec6 patchVelocity(const PatchBody& a, const Vec3& va, const Vec3& wa, const PatchBody& b,
                          const Vec3& vb, const Vec3& wb, const Mat3& F, double rho) {
  return patchVelocityOf(a, b, F, rho, [&](int side, Vec3& v, Vec3& w) {
    v = side == 0 ? va : vb;
    w = side == 0 ? wa : wb;
  });
}

// A generalised impulse `lam` of the six DOFs as velocity changes of the two
// bodies: world force f = F (l3, l4, l0) at O and couple m = F (l1, l2,
// rho l5) on A, minus both on B. `add(side, dv, dw)` is called for each
// dynamic body, side 0 for A and 1 for B.
template <class Add>
void applyPatchImpulse(const PatchBody& a, const PatchBody& b, const Mat3& F, double rho,
                       const Vec6& lam, Add add) {
  const Vec3 f = F * Vec3(lam[3], lam[4], lam[0]);
  const Vec3 m = F * Vec3(lam[1], lam[2], rho * lam[5]);
  if (a.dynamic) add(0, a.invM.cwiseProduct(f), a.invI * (m + a.r.cross(f)));
  if (b.dynamic) add(1, -b.invM.cwiseProduct(f), -(b.invI * (m + b.r.cross(f))));
}

}  // namespace patchspin::parts
