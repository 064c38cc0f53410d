// PatchSolverPoolMt (patch_solver_pool_mt.hpp).
#include <patchspin/bullet/patch_solver_pool_mt.hpp>

#include "patch_solver_shared.hpp"

#include <string>

namespace patchspin::bullet {

PatchSolverPoolMt::Members PatchSolverPoolMt::makeMembers(int numSolvers) {
  if (numSolvers < 1)
    throw Error("PatchSolverPoolMt: numSolvers must be >= 1: got " + std::to_string(numSolvers));
  Members m;
  m.shared = PatchFrictionSolver::makeShared();
  std::vector<std::unique_ptr<PatchFrictionSolver>> owned;
  for (int i = 0; i < numSolvers; ++i) owned.emplace_back(new PatchFrictionSolver(m.shared));
  for (auto& s : owned) {
    m.solvers.push_back(s.get());
    m.base.push_back(s.release());
  }
  return m;
}

PatchSolverPoolMt::PatchSolverPoolMt(int numSolvers) : PatchSolverPoolMt(makeMembers(numSolvers)) {}

PatchSolverPoolMt::PatchSolverPoolMt(Members members)
    : btConstraintSolverPoolMt(members.base.data(), int(members.base.size())),
      shared_(std::move(members.shared)),
      solvers_(std::move(members.solvers)) {}

PatchSolverPoolMt::~PatchSolverPoolMt() = default;

void PatchSolverPoolMt::enablePatchFriction(btRigidBody* body, const PatchOptions& options) {
  solvers_.front()->enablePatchFriction(body, options);
}
void PatchSolverPoolMt::disablePatchFriction(btRigidBody* body) {
  solvers_.front()->disablePatchFriction(body);
}
bool PatchSolverPoolMt::isPatchFrictionEnabled(const btCollisionObject* body) const {
  return solvers_.front()->isPatchFrictionEnabled(body);
}
void PatchSolverPoolMt::setSettings(const PatchSolverSettings& settings) {
  solvers_.front()->setSettings(settings);
}
const PatchSolverSettings& PatchSolverPoolMt::settings() const {
  return shared_->settings;
}
const PatchSolverStats& PatchSolverPoolMt::stats() const {
  return shared_->stats;
}
const std::vector<PatchReport>& PatchSolverPoolMt::patchReports() const {
  return solvers_.front()->patchReports();
}
const PatchReport* PatchSolverPoolMt::findPatchReport(const btCollisionObject* body) const {
  return solvers_.front()->findPatchReport(body);
}
std::optional<PatchReport> PatchSolverPoolMt::patchReportOf(const btCollisionObject* body) const {
  return solvers_.front()->patchReportOf(body);
}
const NotPatchedCounts* PatchSolverPoolMt::notPatchedOf(const btCollisionObject* body) const {
  return solvers_.front()->notPatchedOf(body);
}
void PatchSolverPoolMt::setUnsupportedShapeCallback(UnsupportedShapeCallback callback) {
  solvers_.front()->setUnsupportedShapeCallback(std::move(callback));
}

void PatchSolverPoolMt::prepareSolve(int numBodies, int numManifolds) {
  btConstraintSolverPoolMt::prepareSolve(numBodies, numManifolds);
  shared_->beginStep();
}

void PatchSolverPoolMt::allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btConstraintSolverPoolMt::allSolved(info, debugDrawer);
  shared_->endStep();
}

}  // namespace patchspin::bullet
