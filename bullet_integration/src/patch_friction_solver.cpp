// PatchFrictionSolver: Bullet's sequential-impulse solver with a normal
// block and a friction block per flat contact patch (DESIGN items 2, 4, 5;
// the equations (S1)-(S19) are in docs/solver.md). Bullet's own rows run
// first in every stage; the patch stages, per island, in this order:
//
//   1 select        manifolds of opted-in bodies -> candidate patches
//                   (PatchSelection); all others go to Bullet's rows
//                   (in a PatchSolverPoolMt, under the pool's lock:
//                   patch_solver_shared.hpp)
//   2 set up        per patch: bodies, frame, effective-mass blocks,
//                   position targets (makePatchConstraint), warm start
//   3 link stacks   a patch on a body that stands on a patch of its own is
//                   solved with that support held (parts::linkStackedPatches)
//   4 push          split-impulse iterations: normal-block position solve
//                   on the pseudo velocities (parts::solveNormalPosition)
//   5 iterate       per patch: normal block, then friction block with the
//                   normal block held, then the coupled support share
//   6 store         warm start and law record into the PatchState, report
//                   sources, the impulses onto the manifold's points
//                   (writeManifoldImpulses), then Bullet's write-back and
//                   the crumb flush
//
// Work-saving rules (settings().skipSettledPatches, quickStick, ...) change
// how often a part runs, never what it computes, except settleOnRoundOff,
// which drops a visit's change below the blocks' own precision:
// Determinism.* pins the trajectories bit for bit.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include "patch_constraint.hpp"
#include "patch_finish.hpp"
#include "patch_push.hpp"
#include "patch_reports.hpp"
#include "patch_selection.hpp"
#include "patch_solver_shared.hpp"
#include "patch_stacks.hpp"
#include "patch_visit.hpp"

#include <algorithm>
#include <string>

namespace patchspin::bullet {

using internal::PatchConstraint;
using parts::Vec6;

namespace {

Vec6 constraintVelocity(const PatchConstraint& pc, btAlignedObjectArray<btSolverBody>& pool) {
  return internal::SolverBodies{pool}.velocity(pc);
}
void applyImpulse(const PatchConstraint& pc, btAlignedObjectArray<btSolverBody>& pool,
                  const Vec6& lam) {
  internal::SolverBodies{pool}.apply(pc, lam);
}

}  // namespace

struct PatchFrictionSolver::Impl {
  explicit Impl(std::shared_ptr<internal::PatchSolverShared> s)
      : shared(std::move(s)),
        selection(shared->selection),
        reports(&shared->reports),
        stats(&shared->stats) {}
  // options, states, settings, step: the solver's own, or its pool's
  std::shared_ptr<internal::PatchSolverShared> shared;
  internal::PatchSelection& selection;  // shared->selection
  // where this solver records its islands: the shared records (a lone
  // solver), or its own in a pool (merged by PatchSolverShared::endStep)
  internal::PatchReports* reports;
  PatchSolverStats* stats;
  std::vector<internal::Candidate> candidates;  // of the chunk in hand
  std::vector<PatchConstraint> patches;         // of the island
  std::vector<parts::StackHold> holds;          // of the island's stacked patches
  internal::StackScratch stacks;                // scratch of stage 3 (link stacks)
  std::vector<char> otherRows;                  // by solver body id: in one of Bullet's rows
  // stage 3b: one body's hard, unstacked patches on static supports in one
  // plane, their loads shared after every iteration (S25); indices in patches
  std::vector<std::vector<int>> shareGroups;
  std::vector<parts::SharedPatch> shareBuf;  // scratch
  std::vector<int> shareGroupOf;             // scratch: a body's group (solver body id)
  std::vector<btRigidBody*> flushBodies;     // bodies of the island's patches
};

std::shared_ptr<internal::PatchSolverShared> PatchFrictionSolver::makeShared() {
  auto shared = std::make_shared<internal::PatchSolverShared>();
  shared->friction = internal::frictionSettings(shared->settings);
  return shared;
}

PatchFrictionSolver::PatchFrictionSolver() : impl_(std::make_unique<Impl>(makeShared())) {}

PatchFrictionSolver::PatchFrictionSolver(std::shared_ptr<internal::PatchSolverShared> shared)
    : impl_(std::make_unique<Impl>(std::move(shared))) {
  internal::PatchSolverShared::Member& member = impl_->shared->members.emplace_back();
  impl_->reports = &member.reports;
  impl_->stats = &member.stats;
}

PatchFrictionSolver::~PatchFrictionSolver() = default;

void PatchFrictionSolver::enablePatchFriction(btRigidBody* body, const PatchOptions& options) {
  if (!body) throw Error("enablePatchFriction: body is null");
  internal::checkPatchOptions(options);
  impl_->selection.optIns().enable(*body, options);
}

void PatchFrictionSolver::disablePatchFriction(btRigidBody* body) {
  if (body) impl_->selection.optIns().disable(*body);
}

bool PatchFrictionSolver::isPatchFrictionEnabled(const btCollisionObject* body) const {
  return impl_->selection.optIns().optionsOf(body) != nullptr;
}

const std::vector<PatchReport>& PatchFrictionSolver::patchReports() const {
  return impl_->shared->reports.reports();
}

const PatchReport* PatchFrictionSolver::findPatchReport(const btCollisionObject* body) const {
  return impl_->shared->reports.find(body);
}

const NotPatchedCounts* PatchFrictionSolver::notPatchedOf(const btCollisionObject* body) const {
  return impl_->selection.notPatchedOf(body);
}

void PatchFrictionSolver::setUnsupportedShapeCallback(UnsupportedShapeCallback callback) {
  impl_->selection.setUnsupportedShapeCallback(std::move(callback));
}

std::optional<PatchReport> PatchFrictionSolver::patchReportOf(const btCollisionObject* body) const {
  const PatchReport* r = impl_->shared->reports.find(body);
  return r ? std::optional<PatchReport>(*r) : std::nullopt;
}

void PatchFrictionSolver::setSettings(const PatchSolverSettings& settings) {
  internal::checkSolverSettings(settings);
  impl_->shared->settings = settings;
  impl_->shared->friction = internal::frictionSettings(settings);
}
const PatchSolverSettings& PatchFrictionSolver::settings() const {
  return impl_->shared->settings;
}
const PatchSolverStats& PatchFrictionSolver::stats() const {
  return impl_->shared->stats;
}

void PatchFrictionSolver::prepareSolve(int numBodies, int numManifolds) {
  btSequentialImpulseConstraintSolver::prepareSolve(numBodies, numManifolds);
  impl_->shared->beginStep();
}

void PatchFrictionSolver::allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btSequentialImpulseConstraintSolver::allSolved(info, debugDrawer);
  impl_->shared->endStep();
}

btScalar PatchFrictionSolver::solveGroup(btCollisionObject** bodies, int numBodies,
                                         btPersistentManifold** manifolds, int numManifolds,
                                         btTypedConstraint** constraints, int numConstraints,
                                         const btContactSolverInfo& info, btIDebugDraw* debugDrawer,
                                         btDispatcher* dispatcher) {
  {
    const std::unique_lock<std::mutex> lock = impl_->shared->lockSelection();
    impl_->selection.enterWorld(dispatcher);
  }
  return btSequentialImpulseConstraintSolver::solveGroup(bodies, numBodies, manifolds, numManifolds,
                                                         constraints, numConstraints, info,
                                                         debugDrawer, dispatcher);
}

// Stages 1-3.
void PatchFrictionSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                          const btContactSolverInfo& info) {
  Impl& im = *impl_;
  im.patches.clear();
  im.shareGroups.clear();
  im.holds.clear();
  // no opted-in body: stock Bullet, stock cost
  if (!im.selection.optIns().any()) {
    btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
    return;
  }
  // In chunks of manifolds: first the chunk's selection, then, in the
  // manifolds' order, Bullet's contacts and the patches' set-up, exactly as
  // one pass would make them; each pass's code stays in the instruction
  // cache and a chunk's data in L2 (docs/notes/solver-work-saving.md).
  constexpr int kChunk = 256;
  for (int begin = 0; begin < numManifolds; begin += kChunk) {
    const int end = std::min(numManifolds, begin + kChunk);
    // 1 select (the rest handed back to Bullet's rows)
    im.candidates.clear();
    {
      const std::unique_lock<std::mutex> lock = im.shared->lockSelection();
      for (int i = begin; i < end; ++i)
        if (!im.selection.select(manifolds[i], i, double(info.m_timeStep), *im.stats,
                                 im.candidates))
          im.selection.handBack(manifolds[i]);
    }
    // 2 set up (Bullet's contacts for the rest, in order)
    std::size_t next = 0;
    for (int i = begin; i < end; ++i) {
      btPersistentManifold* m = manifolds[i];
      if (next == im.candidates.size() || im.candidates[next].index != i) {
        convertContact(m, info);
        continue;
      }
      const internal::Candidate& cand = im.candidates[next++];
      const int idA = getOrInitSolverBody(*const_cast<btCollisionObject*>(cand.A), info.m_timeStep);
      const int idB = getOrInitSolverBody(*const_cast<btCollisionObject*>(cand.B), info.m_timeStep);
      im.patches.emplace_back();
      PatchConstraint& pc = im.patches.back();
      if (!internal::makePatchConstraint(cand, *m, m_tmpSolverBodyPool[idA], idA,
                                         m_tmpSolverBodyPool[idB], idB, info, pc)) {
        im.patches.pop_back();
        cand.state->flat = false;  // no usable effective mass: Bullet's contact
        {
          const std::unique_lock<std::mutex> lock = im.shared->lockSelection();
          im.selection.countSingular(cand, *im.stats);
          im.selection.handBack(m);
        }
        convertContact(m, info);
        continue;
      }
      pc.manifold = m;
      Vec6 lam;
      if (internal::warmStart(cand, info, pc, lam)) applyImpulse(pc, m_tmpSolverBodyPool, lam);
    }
  }
  // 3 link stacks
  if (im.shared->settings.supportedStacks &&
      std::any_of(im.patches.begin(), im.patches.end(),
                  [](const PatchConstraint& pc) { return pc.b.body.dynamic; })) {
    // the bodies in Bullet's rows (joints are converted before the contacts)
    im.otherRows.assign(std::size_t(m_tmpSolverBodyPool.size()), 0);
    for (const btConstraintArray* pool :
         {&m_tmpSolverContactConstraintPool, &m_tmpSolverNonContactConstraintPool})
      for (int i = 0; i < pool->size(); ++i) {
        im.otherRows[std::size_t((*pool)[i].m_solverBodyIdA)] = 1;
        im.otherRows[std::size_t((*pool)[i].m_solverBodyIdB)] = 1;
      }
    internal::linkPatchStacks(im.patches, m_tmpSolverBodyPool.size(), im.otherRows, im.stacks,
                              im.holds);
  }
  // 3b share loads (S25)
  internal::groupSharedPatches(im.patches, m_tmpSolverBodyPool.size(), im.shareGroupOf,
                               im.shareGroups);
}

// Stage 5, after Bullet's rows in each iteration.
btScalar PatchFrictionSolver::solveSingleIteration(
    int iteration, btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
    int numManifolds, btTypedConstraint** constraints, int numConstraints,
    const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  const btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info,
      debugDrawer);
  if (iteration >= info.m_numIterations) return residual;
  Impl& im = *impl_;
  internal::SolverBodies bodiesOf{m_tmpSolverBodyPool};
  // (stats held across the visits, not reloaded)
  internal::VisitContext<internal::SolverBodies> cx{bodiesOf, im.shared->settings,
                                                    im.shared->friction, *im.stats};
  internal::PatchIteration it{im.patches, im.holds, im.shareGroups, im.shareBuf};
  const double worst = internal::iteratePatches(cx, it);
  return std::max(residual, btScalar(worst));
}

// Stage 4: position correction on Bullet's pseudo velocities (push / turn),
// which move the bodies but never enter their real velocities: no rocking.
void PatchFrictionSolver::solveGroupCacheFriendlySplitImpulseIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
    btIDebugDraw* debugDrawer) {
  btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySplitImpulseIterations(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  // (zero iterations: Bullet solves nothing, nor does the patch;
  // BadInput.ZeroSolverIterationsSolveNothingAsInBullet)
  if (!info.m_splitImpulse || info.m_numIterations <= 0) return;
  internal::pushPatches(impl_->patches, m_tmpSolverBodyPool);
}

// Stage 6.
btScalar PatchFrictionSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies,
                                                            int numBodies,
                                                            const btContactSolverInfo& info) {
  Impl& im = *impl_;
  PatchSolverStats& stats = *im.stats;
  stats.patches += long(im.patches.size());
  for (PatchConstraint& pc : im.patches)
    internal::finishPatch(pc, constraintVelocity(pc, m_tmpSolverBodyPool), im.selection,
                          *im.reports, stats);
  internal::collectFlushBodies(im.patches, im.flushBodies);
  im.patches.clear();
  im.shareGroups.clear();
  const btScalar out =
      btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
  for (btRigidBody* body : im.flushBodies) internal::flushCrumbs(*body);
  return out;
}

}  // namespace patchspin::bullet
