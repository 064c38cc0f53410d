// The end of a patch's step (patch_finish.hpp).
#include "patch_finish.hpp"

#include "manifold_impulses.hpp"
#include "patch_constraint.hpp"

#include <algorithm>

namespace patchspin::bullet::internal {

void finishPatch(PatchConstraint& pc, const parts::Vec6& c, PatchSelection& selection,
                 PatchReports& reports, PatchSolverStats& stats) {
  stats.stackHolds += pc.stack.hold >= 0 || pc.stack.loadHold >= 0;
  storePatchState(pc, c, selection.step());
  reports.record(pc, c);
  if (writeManifoldImpulses(pc, *pc.manifold))
    selection.markWritten(*pc.state);
  else
    ++stats.patchesWithoutPoints;
  const PatchLoads l = parts::toLoads(pc.lamN);
  if (l.Pz > 0.0 && pc.fb.mu > 0.0) {
    const Vec2 cop(l.Ty / l.Pz, -l.Tx / l.Pz);
    stats.maxPressureLag =
        std::max(stats.maxPressureLag, (cop - pc.fb.law.pressureCop).norm() / pc.shape.diameter);
  }
}

void collectFlushBodies(const std::vector<PatchConstraint>& patches,
                        std::vector<btRigidBody*>& out) {
  out.clear();
  for (const PatchConstraint& pc : patches)
    if (btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(pc.state->body)))
      out.push_back(body);
}

}  // namespace patchspin::bullet::internal
