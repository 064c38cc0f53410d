// The state a pool's solvers share (patch_solver_shared.hpp).
#include "patch_solver_shared.hpp"

#include <algorithm>

namespace patchspin::bullet::internal {

// (a field added to the stats must be merged here, and in
// NotPatchedCounts::operator+=: the sizes below count the fields, 8 bytes each)
static_assert(sizeof(NotPatchedCounts) == 11 * 8);
static_assert(sizeof(parts::FrictionPartCounters) == 5 * 8);
static_assert(sizeof(PatchSolverStats) == (5 + 7 + 11) * 8);
void addStats(PatchSolverStats& sum, const PatchSolverStats& s) {
  sum.blockSolves += s.blockSolves;
  sum.pressureRefreshes += s.pressureRefreshes;
  sum.deferredRefreshes += s.deferredRefreshes;
  sum.quickSticks += s.quickSticks;
  sum.blockErrors += s.blockErrors;
  sum.patches += s.patches;
  sum.visits += s.visits;
  sum.skippedVisits += s.skippedVisits;
  sum.shapeRebuilds += s.shapeRebuilds;
  sum.stackHolds += s.stackHolds;
  sum.maxPressureLag = std::max(sum.maxPressureLag, s.maxPressureLag);
  sum.patchesWithoutPoints += s.patchesWithoutPoints;
  sum.notPatched += s.notPatched;
}

void PatchSolverShared::beginStep() {
  selection.beginStep();
  reports.beginStep();
  stats = PatchSolverStats();
  for (Member& m : members) {
    m.reports.beginStep();
    m.stats = PatchSolverStats();
  }
}

void PatchSolverShared::endStep() {
  if (pooled()) {
    for (Member& m : members) {
      addStats(stats, m.stats);
      reports.append(m.reports);
      m.reports.endStep();
    }
    reports.orderByBodies();
  }
  reports.endStep();
  selection.endStep();
}

}  // namespace patchspin::bullet::internal
