// The end of a patch's step (internal), stage 6 of both patch solvers: its
// state kept for the next step's warm start, its report, its impulses
// written onto the manifold's points (ReportedImpulses.*), and the step's
// statistics.
#pragma once

#include "patch_reports.hpp"
#include "patch_selection.hpp"
#include "solver_data.hpp"

#include <vector>

namespace patchspin::bullet::internal {

// `c`: the patch's DOF velocity at the end of the iterations.
void finishPatch(PatchConstraint& pc, const parts::Vec6& c, PatchSelection& selection,
                 PatchReports& reports, PatchSolverStats& stats);

// The opted-in rigid bodies of `patches`, whose velocities flushCrumbs
// cleans after Bullet's own finish.
void collectFlushBodies(const std::vector<PatchConstraint>& patches,
                        std::vector<btRigidBody*>& out);

}  // namespace patchspin::bullet::internal
