// Patch constraint set-up (internal): a selected patch's constraint for one
// island solve — bodies, frame, effective-mass blocks, position targets and
// the warm start — and the end-of-step write-back of its state.
#pragma once

#include "solver_data.hpp"

#include <BulletDynamics/ConstraintSolver/btContactSolverInfo.h>

class btRigidBody;

namespace patchspin::bullet::internal {

// Warm start of the patch blocks: the full impulses of the last step (each
// block is solved directly, so a steadily sliding or resting patch converges
// in one visit and is then skipped), not Bullet's m_warmstartingFactor.
constexpr double kPatchWarmStartFactor = 1.0;

// The constraint of `cand` (manifold m) between solver bodies sbA (id idA)
// and sbB (idB); false if its effective mass has no usable blocks (e.g. a
// body with locked rotation: the manifold goes to Bullet).
// `articulated`: the share of sides that are no solver body (a Featherstone
// link: sbA / sbB then a body without m_originalBody), added to K6 and to
// the DOF velocity before the step (restitution); null: none.
struct ArticulatedShare {
  Mat6 K6 = Mat6::Zero();      // J M^-1 J^T of those sides
  Vec6 before = Vec6::Zero();  // J qdot of those sides at the set-up
};
bool makePatchConstraint(const Candidate& cand, const btPersistentManifold& m,
                         const btSolverBody& sbA, int idA, const btSolverBody& sbB, int idB,
                         const btContactSolverInfo& info, PatchConstraint& pc,
                         const ArticulatedShare* articulated = nullptr);
// The patch frame F = [ex ey n] and reference point O of a candidate's
// state (as makePatchConstraint sets them).
void patchFrameOf(const PatchState& st, Mat3& F, Vec3& O);

// A contact point's CFM (velocity per impulse, after Bullet's 1/dt) and ERP
// by Bullet's rule (btSequentialImpulseConstraintSolver::
// setupContactConstraint): the point's own CFM/ERP if set, else its contact
// stiffness and damping, else the world's m_globalCfm with m_erp2. For an
// empty manifold (point null), the bodies' stiffness and damping combined
// by Bullet's callbacks. Soft when the CFM is positive.
struct PointSoftness {
  double cfm = 0.0;
  double erp = 0.0;
};
PointSoftness pointSoftness(const btManifoldPoint* point, const btCollisionObject& A,
                            const btCollisionObject& B, const btContactSolverInfo& info);

// The warm start of a patch that ended the last step flat (false otherwise
// or without SOLVER_USE_WARMSTARTING): sets pc.lamN, pc.lamF and the friction
// block's warm slip, and `lam`, the impulse to apply.
bool warmStart(const Candidate& cand, const btContactSolverInfo& info, PatchConstraint& pc,
               Vec6& lam);

// The end of the step: warm start, stick state, the law's pressure record
// and tipping into the PatchState; c is the patch's final DOF velocity.
void storePatchState(const PatchConstraint& pc, const Vec6& c, long step);

// Velocity components far below their vector's precision, or whose square
// is subnormal, set to exactly zero after the write-back (a patch holds its
// body flat: the tilt crumbs it leaves make float arithmetic ~100x slower).
// Nothing representable changes.
void flushCrumbs(btRigidBody& body);

}  // namespace patchspin::bullet::internal
