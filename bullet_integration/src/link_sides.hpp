// Link sides (internal): a patch's side on a Featherstone link for
// PatchMultiBodySolver — the 6 DOF rows J of (S1) through the multibody's
// Jacobian (fillConstraintJacobianMultiDof), their responses M^-1 J^T
// (calcAccelerationDeltasMultiDof), and the Bodies policy of patch_visit.hpp
// that reads and moves a patch through them:
//   DOF velocity   c = J (qdot0 + dqdot)      per link side, A's + and B's -
//   impulse d      dqdot += M^-1 J^T d       (Bullet's m_deltaVelocities,
//                                            and the multibody's own deltaV)
//   effective mass K6 += J M^-1 J^T          (S2)
// with qdot0 the multibody's velocity vector at the set-up (Bullet changes
// it only after the solve) and dqdot the solve's change, which Bullet's
// multibody rows read and write too (MultiBodyPatches.* guard it).
#pragma once

#include "patch_constraint.hpp"
#include "patch_visit.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <vector>

namespace patchspin::bullet::internal {

// One side of a patch on a Featherstone link: the 6 rows of J (signed) and
// their responses M^-1 J^T, n = 6 + dofs numbers each, at `offset` in the
// island's jac / resp.
struct LinkSide {
  btMultiBody* body = nullptr;  // null: no link on this side
  int link = -1;                // -1: the base
  int velocity = -1;  // the multibody's companion id: its dqdot in m_data.m_deltaVelocities
  int n = 0;
  std::size_t offset = 0;
  double sign = 1.0;  // +1 A, -1 B (both: the rows are J_A - J_B, on side 0)
};
struct LinkTerms {
  LinkSide side[2];
  Vec6 c0 = Vec6::Zero();  // J qdot0
};

// The Bodies of patch_visit.hpp: solver bodies (SolverBodies) plus links.
struct MultiBodyBodies {
  SolverBodies rigid;
  const std::vector<LinkTerms>& terms;
  const std::vector<btScalar>& jac;
  const std::vector<btScalar>& resp;
  btAlignedObjectArray<btScalar>& dqdot;

  Vec6 velocity(const PatchConstraint& pc) const {
    Vec6 c = rigid.velocity(pc);
    if (pc.articulated < 0) return c;
    const LinkTerms& t = terms[std::size_t(pc.articulated)];
    c += t.c0;
    for (const LinkSide& s : t.side) {
      if (!s.body) continue;
      const btScalar* v = &dqdot[s.velocity];
      for (int i = 0; i < 6; ++i) {
        const btScalar* J = &jac[s.offset + std::size_t(i * s.n)];
        double sum = 0.0;
        for (int k = 0; k < s.n; ++k) sum += double(J[k]) * double(v[k]);
        c[i] += sum;
      }
    }
    return c;
  }
  void apply(const PatchConstraint& pc, const Vec6& d) {
    rigid.apply(pc, d);
    if (pc.articulated < 0) return;
    for (const LinkSide& s : terms[std::size_t(pc.articulated)].side) {
      if (!s.body) continue;
      btScalar* v = &dqdot[s.velocity];
      for (int i = 0; i < 6; ++i) {
        if (d[i] == 0.0) continue;
        const btScalar* r = &resp[s.offset + std::size_t(i * s.n)];
        const btScalar x = flushed(d[i]);
        for (int k = 0; k < s.n; ++k) v[k] += r[k] * x;
        s.body->applyDeltaVeeMultiDof2(r, x);
      }
    }
  }
  // (a link's dqdot is not snapshot: its patches are visited every time)
  static bool settles(const PatchConstraint& pc) { return pc.articulated < 0; }
  void snapshot(const PatchConstraint& pc, btVector3* out) const { rigid.snapshot(pc, out); }
};

// The island's rows of the link sides, and Bullet's data they use.
struct LinkArrays {
  std::vector<btScalar>& jac;
  std::vector<btScalar>& resp;
  std::vector<btScalar>& scratch;
  btMultiBodyJacobianData& data;
};

// The link sides of a patch (state st; links[s] null: no link on side s):
// J, M^-1 J^T, J qdot0 and K6's share J M^-1 J^T, and each multibody's
// place in Bullet's delta velocities (given one if it has none yet, as
// Bullet's multibody contacts do). Two links of one multibody make one
// side, J_A - J_B.
void setUpLinkSides(const PatchState& st, const btMultiBodyLinkCollider* const links[2],
                    const LinkArrays& arrays, LinkTerms& terms, ArticulatedShare& share);

}  // namespace patchspin::bullet::internal
