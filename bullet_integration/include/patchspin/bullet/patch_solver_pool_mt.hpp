// Bullet's solver pool for btDiscreteDynamicsWorldMt, made of
// PatchFrictionSolvers that share one state:
//
//   patchspin::bullet::PatchSolverPoolMt pool(2);
//   btDiscreteDynamicsWorldMt world(&dispatcher, &broadphase, &pool, nullptr, &config);
//   pool.enablePatchFriction(body, {patchspin::Model::Ellipsoidal});
//
// The world hands each island (or batch of small islands) to one solver of
// the pool; the solvers share the opted-in bodies' options, the patches'
// states across steps, the settings, the stats and the reports, and keep
// only their island's scratch. The pool forwards the world's once-per-step
// calls (prepareSolve, allSolved) that btConstraintSolverPoolMt does not:
// stats are reset each step and reports hold every island's patches, as
// with a PatchFrictionSolver in btDiscreteDynamicsWorld
// (MultithreadedWorld.*). The motion is the single-threaded world's, bit
// for bit where an island's manifolds come in the same order (docs/bullet.md,
// "Multithreaded world").
//
// Threads: islands solved at the same time by different solvers of the pool
// are safe (patch_solver_shared.hpp states what is shared and how). Which
// solver takes an island is Bullet's choice: with a Bullet built without
// BT_THREADSAFE (Debian's) the world solves its islands one after the other
// on the calling thread, always with the pool's first solver.
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h>

#include <memory>
#include <optional>
#include <vector>

namespace patchspin::bullet {

class PatchSolverPoolMt : public btConstraintSolverPoolMt {
 public:
  // A pool of numSolvers >= 1 solvers (Error otherwise); Bullet's advice:
  // at least as many as the task scheduler has threads.
  explicit PatchSolverPoolMt(int numSolvers);
  ~PatchSolverPoolMt() override;
  PatchSolverPoolMt(const PatchSolverPoolMt&) = delete;
  PatchSolverPoolMt& operator=(const PatchSolverPoolMt&) = delete;

  int numSolvers() const { return int(solvers_.size()); }
  // The i-th solver (owned by the pool). Its per-body API, settings, stats
  // and reports are the pool's; it can solve an island (solveGroup) while
  // another solver of the pool solves another one, on another thread.
  PatchFrictionSolver& solver(int i) { return *solvers_.at(std::size_t(i)); }

  // As PatchFrictionSolver's, for every solver of the pool.
  void enablePatchFriction(btRigidBody* body, const PatchOptions& options = PatchOptions());
  void disablePatchFriction(btRigidBody* body);
  bool isPatchFrictionEnabled(const btCollisionObject* body) const;
  void setSettings(const PatchSolverSettings& settings);
  const PatchSolverSettings& settings() const;
  // All islands of the last step.
  const PatchSolverStats& stats() const;
  // All islands' patches of the last step, ordered by their bodies' world
  // array indices (btCollisionObject::getWorldArrayIndex), then the other
  // bodies': the same order whichever solver, on whichever thread, solved
  // them. Lifetime as PatchFrictionSolver::patchReports.
  const std::vector<PatchReport>& patchReports() const;
  const PatchReport* findPatchReport(const btCollisionObject* body) const;
  std::optional<PatchReport> patchReportOf(const btCollisionObject* body) const;
  const NotPatchedCounts* notPatchedOf(const btCollisionObject* body) const;
  // The callback is called from the thread solving the island, one call at
  // a time (under the pool's lock): it must not call into the pool.
  void setUnsupportedShapeCallback(UnsupportedShapeCallback callback);

  // btConstraintSolver hooks called once per world step (not forwarded by
  // btConstraintSolverPoolMt): the shared step begins and ends here.
  void prepareSolve(int numBodies, int numManifolds) override;
  void allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;

 private:
  struct Members {
    std::shared_ptr<internal::PatchSolverShared> shared;
    std::vector<PatchFrictionSolver*> solvers;
    std::vector<btConstraintSolver*> base;  // the same, for btConstraintSolverPoolMt
  };
  static Members makeMembers(int numSolvers);
  explicit PatchSolverPoolMt(Members members);

  std::shared_ptr<internal::PatchSolverShared> shared_;
  std::vector<PatchFrictionSolver*> solvers_;  // deleted by btConstraintSolverPoolMt
};

}  // namespace patchspin::bullet
