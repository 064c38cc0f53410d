// PatchMultiBodySolver: btMultiBodyConstraintSolver with PatchFrictionSolver's
// patches, whose sides may be Featherstone links. The stages are those of
// patch_friction_solver.cpp (1 select, 2 set up, 3 link stacks, of rigid
// bodies only, 4 push, 5 iterate, 6 store), with the patch visits of
// patch_visit.hpp; a side on a link reads and moves through its Jacobian
// (link_sides.hpp).
#include <patchspin/bullet/patch_multibody_solver.hpp>

#include "link_sides.hpp"
#include "patch_constraint.hpp"
#include "patch_finish.hpp"
#include "patch_push.hpp"
#include "patch_reports.hpp"
#include "patch_selection.hpp"
#include "patch_solver_shared.hpp"
#include "patch_stacks.hpp"
#include "patch_visit.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>

namespace patchspin::bullet {

using internal::LinkArrays;
using internal::LinkSide;
using internal::LinkTerms;
using internal::MultiBodyBodies;
using internal::PatchConstraint;
using parts::Mat6;
using parts::Vec6;

struct PatchMultiBodySolver::Impl {
  Impl() : shared(std::make_shared<internal::PatchSolverShared>()), selection(shared->selection) {
    shared->friction = internal::frictionSettings(shared->settings);
    linkBody.m_originalBody = nullptr;
    linkBody.m_worldTransform.setIdentity();
    linkBody.m_linearVelocity.setZero();
    linkBody.m_angularVelocity.setZero();
  }
  std::shared_ptr<internal::PatchSolverShared> shared;
  internal::PatchSelection& selection;
  std::vector<internal::Candidate> candidates;
  std::vector<btPersistentManifold*> rest;  // manifolds left to Bullet's rows
  std::vector<PatchConstraint> patches;
  std::vector<LinkTerms> terms;  // of the patches with a link side
  std::vector<btScalar> jac, resp, scratch;
  std::vector<parts::StackHold> holds;  // of the island's stacked patches (stage 3)
  internal::StackScratch stacks;        // scratch of stage 3
  std::vector<char> otherRows;  // by solver body id: in one of Bullet's rows or a link's patch
  std::vector<std::vector<int>> shareGroups;
  std::vector<parts::SharedPatch> shareBuf;
  std::vector<int> shareGroupOf;
  std::vector<btRigidBody*> flushBodies;
  // stands for a link side in makePatchConstraint: no m_originalBody, so
  // its BodyTerms are those of a body that adds nothing
  btSolverBody linkBody;
};

PatchMultiBodySolver::PatchMultiBodySolver() : impl_(std::make_unique<Impl>()) {}
PatchMultiBodySolver::~PatchMultiBodySolver() = default;

void PatchMultiBodySolver::enablePatchFriction(btCollisionObject* body,
                                               const PatchOptions& options) {
  if (!body) throw Error("enablePatchFriction: body is null");
  internal::checkPatchOptions(options);
  if (btRigidBody* rb = btRigidBody::upcast(body)) {
    impl_->selection.optIns().enable(*rb, options);
  } else if (btMultiBodyLinkCollider* c = btMultiBodyLinkCollider::upcast(body)) {
    impl_->selection.optIns().enable(*c, options);
  } else {
    throw Error(
        "enablePatchFriction: the body is neither a btRigidBody nor a btMultiBodyLinkCollider");
  }
}

void PatchMultiBodySolver::disablePatchFriction(btCollisionObject* body) {
  if (!body) return;
  if (btRigidBody* rb = btRigidBody::upcast(body))
    impl_->selection.optIns().disable(*rb);
  else if (btMultiBodyLinkCollider* c = btMultiBodyLinkCollider::upcast(body))
    impl_->selection.optIns().disable(*c);
}

bool PatchMultiBodySolver::isPatchFrictionEnabled(const btCollisionObject* body) const {
  return impl_->selection.optIns().optionsOf(body) != nullptr;
}

void PatchMultiBodySolver::setSettings(const PatchSolverSettings& settings) {
  internal::checkSolverSettings(settings);
  impl_->shared->settings = settings;
  impl_->shared->friction = internal::frictionSettings(settings);
}
const PatchSolverSettings& PatchMultiBodySolver::settings() const {
  return impl_->shared->settings;
}
const PatchSolverStats& PatchMultiBodySolver::stats() const {
  return impl_->shared->stats;
}
const std::vector<PatchReport>& PatchMultiBodySolver::patchReports() const {
  return impl_->shared->reports.reports();
}
const PatchReport* PatchMultiBodySolver::findPatchReport(const btCollisionObject* body) const {
  return impl_->shared->reports.find(body);
}
std::optional<PatchReport> PatchMultiBodySolver::patchReportOf(
    const btCollisionObject* body) const {
  const PatchReport* r = impl_->shared->reports.find(body);
  return r ? std::optional<PatchReport>(*r) : std::nullopt;
}
const NotPatchedCounts* PatchMultiBodySolver::notPatchedOf(const btCollisionObject* body) const {
  return impl_->selection.notPatchedOf(body);
}
void PatchMultiBodySolver::setUnsupportedShapeCallback(UnsupportedShapeCallback callback) {
  impl_->selection.setUnsupportedShapeCallback(std::move(callback));
}

void PatchMultiBodySolver::prepareSolve(int numBodies, int numManifolds) {
  btMultiBodyConstraintSolver::prepareSolve(numBodies, numManifolds);
  impl_->shared->beginStep();
}

void PatchMultiBodySolver::allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btMultiBodyConstraintSolver::allSolved(info, debugDrawer);
  impl_->shared->endStep();
}

void PatchMultiBodySolver::solveMultiBodyGroup(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
    btTypedConstraint** constraints, int numConstraints,
    btMultiBodyConstraint** multiBodyConstraints, int numMultiBodyConstraints,
    const btContactSolverInfo& info, btIDebugDraw* debugDrawer, btDispatcher* dispatcher) {
  impl_->selection.enterWorld(dispatcher);
  btMultiBodyConstraintSolver::solveMultiBodyGroup(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, multiBodyConstraints,
      numMultiBodyConstraints, info, debugDrawer, dispatcher);
}

// Stages 1-3 (3 and 3b, stack holds and load sharing, between rigid bodies only).
void PatchMultiBodySolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                           const btContactSolverInfo& info) {
  Impl& im = *impl_;
  im.patches.clear();
  im.terms.clear();
  im.jac.clear();
  im.resp.clear();
  im.shareGroups.clear();
  im.holds.clear();
  if (!im.selection.optIns().any()) {
    btMultiBodyConstraintSolver::convertContacts(manifolds, numManifolds, info);
    return;
  }
  // 1 select; Bullet's rows (and the multibody constraints' rows) for the rest
  im.candidates.clear();
  im.rest.clear();
  for (int i = 0; i < numManifolds; ++i)
    if (!im.selection.select(manifolds[i], i, double(info.m_timeStep), im.shared->stats,
                             im.candidates)) {
      im.selection.handBack(manifolds[i]);
      im.rest.push_back(manifolds[i]);
    }
  btMultiBodyConstraintSolver::convertContacts(im.rest.data(), int(im.rest.size()), info);
  // 2 set up
  MultiBodyBodies bodies{
      {m_tmpSolverBodyPool}, im.terms, im.jac, im.resp, m_data.m_deltaVelocities};
  for (const internal::Candidate& cand : im.candidates) {
    btPersistentManifold* m = manifolds[cand.index];
    const btCollisionObject* objs[2] = {cand.A, cand.B};
    const btMultiBodyLinkCollider* links[2] = {btMultiBodyLinkCollider::upcast(cand.A),
                                               btMultiBodyLinkCollider::upcast(cand.B)};
    int ids[2] = {-1, -1};
    for (int s = 0; s < 2; ++s)
      if (!links[s])
        ids[s] = getOrInitSolverBody(*const_cast<btCollisionObject*>(objs[s]), info.m_timeStep);
    const btSolverBody& sbA = links[0] ? im.linkBody : m_tmpSolverBodyPool[ids[0]];
    const btSolverBody& sbB = links[1] ? im.linkBody : m_tmpSolverBodyPool[ids[1]];
    const bool articulated = links[0] || links[1];
    internal::ArticulatedShare share;
    LinkTerms terms;
    btContactSolverInfo linkInfo = info;
    if (articulated) {
      // (Bullet's multibody contacts put the position error into the
      // velocity target: so does a patch on a link)
      linkInfo.m_splitImpulse = 0;
      const LinkArrays arrays{im.jac, im.resp, im.scratch, m_data};
      setUpLinkSides(*cand.state, links, arrays, terms, share);
    }
    im.patches.emplace_back();
    PatchConstraint& pc = im.patches.back();
    if (!internal::makePatchConstraint(cand, *m, sbA, ids[0], sbB, ids[1],
                                       articulated ? linkInfo : info, pc,
                                       articulated ? &share : nullptr)) {
      im.patches.pop_back();
      cand.state->flat = false;  // no usable effective mass: Bullet's contact
      im.selection.countSingular(cand, im.shared->stats);
      im.selection.handBack(m);
      if (articulated)
        convertMultiBodyContact(m, info);
      else
        convertContact(m, info);
      continue;
    }
    pc.manifold = m;
    if (articulated) {
      pc.articulated = int(im.terms.size());
      im.terms.push_back(terms);
    }
    Vec6 lam;
    if (internal::warmStart(cand, info, pc, lam)) bodies.apply(pc, lam);
  }
  // 3 link stacks, among the patches between solver bodies
  if (im.shared->settings.supportedStacks &&
      std::any_of(im.patches.begin(), im.patches.end(), [](const PatchConstraint& pc) {
        return pc.articulated < 0 && pc.b.body.dynamic;
      }))
    linkRigidStacks(im);
  // 3b share loads (S25), rigid bodies' patches
  internal::groupSharedPatches(im.patches, m_tmpSolverBodyPool.size(), im.shareGroupOf,
                               im.shareGroups);
}

// Stage 3 for the patches between solver bodies, as PatchFrictionSolver's:
// a body in one of Bullet's rows (rigid or multibody) or on a link's patch
// is in "other rows" (its support's share would not be projected onto
// them).
void PatchMultiBodySolver::linkRigidStacks(Impl& im) {
  im.otherRows.assign(std::size_t(m_tmpSolverBodyPool.size()), 0);
  auto mark = [&](int id) {
    if (id >= 0) im.otherRows[std::size_t(id)] = 1;
  };
  for (const btConstraintArray* pool :
       {&m_tmpSolverContactConstraintPool, &m_tmpSolverNonContactConstraintPool})
    for (int i = 0; i < pool->size(); ++i) {
      mark((*pool)[i].m_solverBodyIdA);
      mark((*pool)[i].m_solverBodyIdB);
    }
  for (const btMultiBodyConstraintArray* rows :
       {&m_multiBodyNormalContactConstraints, &m_multiBodyNonContactConstraints})
    for (int i = 0; i < rows->size(); ++i) {
      mark((*rows)[i].m_solverBodyIdA);
      mark((*rows)[i].m_solverBodyIdB);
    }
  internal::linkPatchStacks(im.patches, m_tmpSolverBodyPool.size(), im.otherRows, im.stacks,
                            im.holds);
}

// Stage 5, after Bullet's rows (joint limits and motors included) in each
// iteration.
btScalar PatchMultiBodySolver::solveSingleIteration(
    int iteration, btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
    int numManifolds, btTypedConstraint** constraints, int numConstraints,
    const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  const btScalar residual = btMultiBodyConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info,
      debugDrawer);
  Impl& im = *impl_;
  if (iteration >= info.m_numIterations || im.patches.empty()) return residual;
  MultiBodyBodies bodiesOf{
      {m_tmpSolverBodyPool}, im.terms, im.jac, im.resp, m_data.m_deltaVelocities};
  internal::VisitContext<MultiBodyBodies> cx{bodiesOf, im.shared->settings, im.shared->friction,
                                             im.shared->stats};
  internal::PatchIteration it{im.patches, im.holds, im.shareGroups, im.shareBuf};
  const double worst = internal::iteratePatches(cx, it);
  for (const LinkTerms& t : im.terms)
    for (const LinkSide& s : t.side)
      if (s.body) s.body->setPosUpdated(false);
  return std::max(residual, btScalar(worst));
}

// Stage 4: the position correction of patches between solver bodies on
// Bullet's pseudo velocities, as PatchFrictionSolver's (a patch on a link
// has its position error in its velocity target: no push).
void PatchMultiBodySolver::solveGroupCacheFriendlySplitImpulseIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
    btIDebugDraw* debugDrawer) {
  btMultiBodyConstraintSolver::solveGroupCacheFriendlySplitImpulseIterations(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  if (!info.m_splitImpulse || info.m_numIterations <= 0) return;
  internal::pushPatches(impl_->patches, m_tmpSolverBodyPool);
}

// Stage 6; a link side also gets the patch's force as its constraint force
// (joint feedback), as Bullet's multibody rows give theirs.
btScalar PatchMultiBodySolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies,
                                                             int numBodies,
                                                             const btContactSolverInfo& info) {
  Impl& im = *impl_;
  PatchSolverStats& stats = im.shared->stats;
  stats.patches += long(im.patches.size());
  MultiBodyBodies bodiesOf{
      {m_tmpSolverBodyPool}, im.terms, im.jac, im.resp, m_data.m_deltaVelocities};
  const double dt = double(info.m_timeStep);
  for (PatchConstraint& pc : im.patches) {
    internal::finishPatch(pc, bodiesOf.velocity(pc), im.selection, im.shared->reports, stats);
    if (pc.articulated < 0) continue;
    // force f at O and couple m on A (minus both on B), as forces over dt
    const Vec3 f = pc.F * Vec3(pc.lamF[0], pc.lamF[1], pc.lamN[0]) / dt;
    const Vec3 mo = pc.F * Vec3(pc.lamN[1], pc.lamN[2], pc.fb.rho * pc.lamF[2]) / dt;
    const Vec3 O = internal::toEigen(pc.state->geometry.origin);
    const LinkTerms& t = im.terms[std::size_t(pc.articulated)];
    const btMultiBodyLinkCollider* links[2] = {btMultiBodyLinkCollider::upcast(pc.state->body),
                                               btMultiBodyLinkCollider::upcast(pc.state->other)};
    for (int s = 0; s < 2; ++s) {
      if (!links[s]) continue;
      btMultiBody* body = links[s]->m_multiBody;
      const int link = links[s]->m_link;
      const double sign = s == 0 ? 1.0 : -1.0;
      const btVector3 origin =
          link < 0 ? body->getBasePos() : body->getLink(link).m_cachedWorldTransform.getOrigin();
      const Vec3 r = O - internal::toEigen(origin);
      const btVector3 force = internal::toBt(sign * f);
      const btVector3 torque = internal::toBt(sign * (mo + r.cross(f)));
      if (link < 0) {
        body->addBaseConstraintForce(force);
        body->addBaseConstraintTorque(torque);
      } else {
        body->addLinkConstraintForce(link, force);
        body->addLinkConstraintTorque(link, torque);
      }
    }
    for (const LinkSide& s : t.side)
      if (s.body) s.body->setCompanionId(-1);
  }
  internal::collectFlushBodies(im.patches, im.flushBodies);
  im.patches.clear();
  im.terms.clear();
  im.shareGroups.clear();
  const btScalar out =
      btMultiBodyConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
  for (btRigidBody* body : im.flushBodies) internal::flushCrumbs(*body);
  return out;
}
}  // namespace patchspin::bullet
