// The state of a PatchFrictionSolver that outlives an island solve
// (internal): per-body options, per-manifold states and step counts (per
// world, PatchSelection), settings, and the last step's stats and report
// sources. A lone solver owns
// one; the solvers of a PatchSolverPoolMt share one, each recording its
// islands' stats and reports in its own Member, merged at the end of the
// step (endStep).
//
// Invariant of a shared state: the islands of one step touch disjoint
// manifolds and dynamic bodies, so a PatchState, a manifold's points and a
// body's per-body counts are written by one solver only; what several
// solvers reach (the selection's maps, filters, caches, the
// unsupported-shape callback) is used under `selectionMutex` (stage 1, and
// a patch's hand-back in stage 2), and every other write goes to the
// solver's own Member. A lone solver takes no lock.
// (MultithreadedWorld.TwoThreadsSolveDisjointIslandsAsOneThread)
#pragma once

#include "patch_reports.hpp"
#include "patch_selection.hpp"

#include <deque>
#include <mutex>

namespace patchspin::bullet::internal {

struct PatchSolverShared {
  PatchSelection selection;
  PatchSolverSettings settings;
  parts::FrictionPartSettings friction;
  PatchSolverStats stats;  // of the last step, all islands
  PatchReports reports;    // of the last step, all islands
  // a pool's solvers' records of the step in hand (none for a lone solver)
  struct Member {
    PatchSolverStats stats;
    PatchReports reports;
  };
  std::deque<Member> members;  // (deque: stable addresses)
  std::mutex selectionMutex;

  bool pooled() const { return !members.empty(); }
  // Holds selectionMutex in a pool; empty for a lone solver.
  std::unique_lock<std::mutex> lockSelection() {
    return pooled() ? std::unique_lock<std::mutex>(selectionMutex) : std::unique_lock<std::mutex>();
  }
  // Start of a world step (prepareSolve): the step's records cleared.
  void beginStep();
  // End of a world step (allSolved): the members' records merged, reports
  // ordered by body (PatchReports::orderByBodies), stale states swept.
  void endStep();
};

// sum += s (counters added, maxPressureLag the larger).
void addStats(PatchSolverStats& sum, const PatchSolverStats& s);

}  // namespace patchspin::bullet::internal
