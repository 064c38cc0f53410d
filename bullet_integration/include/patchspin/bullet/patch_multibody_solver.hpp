// Drop-in replacement for btMultiBodyConstraintSolver that gives opted-in
// Featherstone links (and rigid bodies) the patch friction of
// PatchFrictionSolver (patch_friction_solver.hpp):
//
//   patchspin::bullet::PatchMultiBodySolver solver;
//   btMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
//   solver.enablePatchFriction(multiBody->getLink(i).m_collider, {patchspin::Model::Exact});
//
// A flat contact of an opted-in link collider (a link, or a floating base)
// with the ground, a rigid body or another link becomes one patch: its 3
// normal and 3 friction rows (the DOFs of patch_body.hpp, (S1)) act through
// the multibody's Jacobians, J = d(DOFs)/d(qdot) (Bullet's
// fillConstraintJacobianMultiDof), with the effective mass
// K6 = J M^-1 J^T (calcAccelerationDeltasMultiDof), and are solved in the
// same iterations as Bullet's rows, joint limits and motors included, by
// the same normal and friction block parts as PatchFrictionSolver's
// (patch_visit.hpp). Patches between rigid bodies are those of
// PatchFrictionSolver. The contact's position error enters the patch's
// velocity target for a patch on a link (Bullet's multibody contacts have
// no split impulse), the split-impulse push for one between rigid bodies.
//
// Not (yet) done on links: a patch on a link, or on a body that stands on
// a link's patch, is solved without stack holds (plain Gauss-Seidel with
// its support, as Bullet's own rows; stacks of rigid bodies get
// PatchFrictionSolver's holds), and a link's several patches do not share
// their loads (S25). A link's patch on an empty manifold (Bullet's points
// dropped) is kept within the contact-breaking distance only, not also
// the distance the link closes in the step (its speed is not looked up).
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>

#include <memory>
#include <optional>
#include <vector>

namespace patchspin::bullet {

namespace internal {
struct PatchSolverShared;
}

class PatchMultiBodySolver : public btMultiBodyConstraintSolver {
 public:
  PatchMultiBodySolver();
  ~PatchMultiBodySolver() override;
  PatchMultiBodySolver(const PatchMultiBodySolver&) = delete;
  PatchMultiBodySolver& operator=(const PatchMultiBodySolver&) = delete;

  // Opts `body` in: a btMultiBodyLinkCollider (a link's, or the base's of a
  // floating-base multibody) or a btRigidBody, with the checks and the
  // rigid body's lifetime rules of PatchFrictionSolver::enablePatchFriction.
  // A link collider's opt-in is kept in the collider itself (in Bullet's
  // internal extension pointer), so it ends with the collider as a rigid
  // body's does; Error if that pointer is already set (by a user or an
  // extension). Any other collision object: Error.
  void enablePatchFriction(btCollisionObject* body, const PatchOptions& options = PatchOptions());
  // Opts `body` out (null, or not opted in by this solver: no-op).
  void disablePatchFriction(btCollisionObject* body);
  bool isPatchFrictionEnabled(const btCollisionObject* body) const;

  void setSettings(const PatchSolverSettings& settings);
  const PatchSolverSettings& settings() const;
  // Last step.
  const PatchSolverStats& stats() const;
  // As PatchFrictionSolver's (lifetime included); `body` is the opted-in
  // link collider or rigid body.
  const std::vector<PatchReport>& patchReports() const;
  const PatchReport* findPatchReport(const btCollisionObject* body) const;
  std::optional<PatchReport> patchReportOf(const btCollisionObject* body) const;
  const NotPatchedCounts* notPatchedOf(const btCollisionObject* body) const;
  void setUnsupportedShapeCallback(UnsupportedShapeCallback callback);

  void prepareSolve(int numBodies, int numManifolds) override;
  void allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
  void solveMultiBodyGroup(btCollisionObject** bodies, int numBodies,
                           btPersistentManifold** manifolds, int numManifolds,
                           btTypedConstraint** constraints, int numConstraints,
                           btMultiBodyConstraint** multiBodyConstraints,
                           int numMultiBodyConstraints, const btContactSolverInfo& info,
                           btIDebugDraw* debugDrawer, btDispatcher* dispatcher) override;

 protected:
  void convertContacts(btPersistentManifold** manifolds, int numManifolds,
                       const btContactSolverInfo& info) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifolds, int numManifolds,
                                btTypedConstraint** constraints, int numConstraints,
                                const btContactSolverInfo& info,
                                btIDebugDraw* debugDrawer) override;
  void solveGroupCacheFriendlySplitImpulseIterations(
      btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
      btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
      btIDebugDraw* debugDrawer) override;
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                         const btContactSolverInfo& info) override;

 private:
  struct Impl;
  void linkRigidStacks(Impl& im);
  std::unique_ptr<Impl> impl_;
};

}  // namespace patchspin::bullet
