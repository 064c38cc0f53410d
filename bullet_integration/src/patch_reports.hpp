// Patch reports (internal): what each step's PatchReports are made of is
// recorded at the end of the step (~100 bytes a patch); the reports are
// filled from it at the first request after the step, so a step that nobody
// asks about does not pay for them.
#pragma once

#include "solver_data.hpp"

namespace patchspin::bullet::internal {

class PatchReports {
 public:
  // Between prepareSolve and allSolved the sources are being written.
  void beginStep();
  void endStep() { inStep_ = false; }
  // The patch's report source; c is its final DOF velocity.
  void record(const PatchConstraint& pc, const Vec6& c);
  // The sources `other` recorded in this step, appended (a pool's members).
  void append(const PatchReports& other);
  // The sources ordered by their bodies' world array indices, then their
  // others': one order whichever solver of a pool, on whichever thread,
  // recorded them (a body's patches are all in its island, recorded by one
  // solver in its manifolds' order, which the stable sort keeps).
  void orderByBodies();
  // The reports of the last step (filled once per step; in place, without
  // allocation once the storage has grown).
  const std::vector<PatchReport>& reports();
  const PatchReport* find(const btCollisionObject* body);

 private:
  void fill();
  std::vector<ReportSource> sources_;
  std::size_t count_ = 0;
  bool filled_ = true;
  bool inStep_ = false;
  std::vector<PatchReport> reports_;
  std::vector<long> shapeIds_;  // shapeId of each report's shape (copied only when it changes)
};

}  // namespace patchspin::bullet::internal
