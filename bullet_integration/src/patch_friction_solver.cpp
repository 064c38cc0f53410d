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
// how often a part runs, never what it computes: Determinism.* pins the
// trajectories bit for bit.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include "manifold_impulses.hpp"
#include "patch_constraint.hpp"
#include "patch_reports.hpp"
#include "patch_selection.hpp"
#include "patch_solver_shared.hpp"

#include <patchspin/parts/load_sharing.hpp>

#include <algorithm>
#include <string>

namespace patchspin::bullet {

using internal::PatchConstraint;
using parts::Vec6;

namespace {

// Within a step, a slipping friction block whose input (b, L) changed by
// less than this, relative, since its last solve keeps that solution (the
// velocities carry ~6e-8 in float).
constexpr double kReuseRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-6;
// Relative residual at which a friction block solve stops: below the
// precision of the velocities it is computed from.
constexpr double kBlockRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-9;
// Pseudo-velocity iterations of the patch position correction per step.
constexpr int kPushIterations = 4;

parts::FrictionPartSettings frictionSettings(const PatchSolverSettings& s) {
  parts::FrictionPartSettings f;
  f.pressureRefreshTolerance = s.pressureRefreshTolerance;
  f.pressureLagTolerance = s.pressureLagTolerance;
  f.quickStick = s.quickStick;
  f.deferStickingRefresh = s.deferStickingRefresh;
  f.blockTolerance = kBlockRelTol;
  f.reuseTolerance = kReuseRelTol;
  return f;
}

// The velocity of a patch's dynamic body in the iterations: its fixed part
// plus the solver body's delta velocities (the line Bullet's rows read too).
template <class Velocity>
Vec6 patchVelocity(const PatchConstraint& pc, Velocity velocity) {
  return parts::patchVelocityOf(
      pc.a.body, pc.b.body, pc.F, pc.fb.rho,
      [&](int side, Vec3& v, Vec3& w) { velocity(side == 0 ? pc.a : pc.b, v, w); });
}
Vec6 constraintVelocity(const PatchConstraint& pc, const btAlignedObjectArray<btSolverBody>& pool) {
  return patchVelocity(pc, [&](const internal::BodyTerms& t, Vec3& v, Vec3& w) {
    v = internal::toEigen(t.v0 + pool[t.id].m_deltaLinearVelocity);
    w = internal::toEigen(t.w0 + pool[t.id].m_deltaAngularVelocity);
  });
}
void applyImpulse(const PatchConstraint& pc, btAlignedObjectArray<btSolverBody>& pool,
                  const Vec6& lam) {
  parts::applyPatchImpulse(pc.a.body, pc.b.body, pc.F, pc.fb.rho, lam,
                           [&](int side, const Vec3& dv, const Vec3& dw) {
                             btSolverBody& sb = pool[side == 0 ? pc.a.id : pc.b.id];
                             sb.m_deltaLinearVelocity += internal::toBt(dv);
                             sb.m_deltaAngularVelocity += internal::toBt(dw);
                           });
}
// The delta velocities of a patch's two solver bodies (a settled patch is
// skipped while they are unchanged).
void snapshotOf(const PatchConstraint& pc, const btAlignedObjectArray<btSolverBody>& pool,
                btVector3* out) {
  const btSolverBody& a = pool[pc.ids[0]];
  const btSolverBody& b = pool[pc.ids[1]];
  out[0] = a.m_deltaLinearVelocity;
  out[1] = a.m_deltaAngularVelocity;
  out[2] = b.m_deltaLinearVelocity;
  out[3] = b.m_deltaAngularVelocity;
}

// The target of a compliant normal row, t - (C lambda_z, 0, 0) (S23); t
// itself on a hard contact.
inline Vec3 softTarget(const Vec3& target, double compliance, const Vec3& lam) {
  if (compliance == 0.0) return target;
  return Vec3(target[0] - compliance * lam[0], target[1], target[2]);
}

// What a visit needs besides its patch.
struct VisitContext {
  btAlignedObjectArray<btSolverBody>& pool;
  const PatchSolverSettings& settings;
  const parts::FrictionPartSettings& friction;
  PatchSolverStats& stats;
};

// One visit of a patch (stage 5), with a support hold (0 none, 1 the
// support's normal block, 2 all six DOFs; sup: the held patch). False: the
// held support cannot take its share, and the visit is to be redone with
// less held (nothing was applied). `worst` gets the largest squared change.
bool visitPatch(VisitContext& cx, PatchConstraint& pc, PatchConstraint* sup,
                const parts::HeldBlocks* hold, int held, double& worst) {
  const parts::PatchBlocks& k = hold ? static_cast<const parts::PatchBlocks&>(*hold) : pc.k;
  FrictionPatch& friction = *pc.state->friction;
  // normal block (S4)-(S6)
  const Vec6 c = constraintVelocity(pc, cx.pool);
  // (soft: the compliant row c_n = t_n - C lamN, with (W + C)^-1 in k.Winv (S23))
  const parts::NormalImpulse normal = parts::solveNormalVelocity(
      k.Winv, pc.lamN, c.head<3>(), softTarget(pc.targetN, pc.compliance, pc.lamN), pc.shape,
      friction.shape());
  pc.interior = normal.interior;
  pc.tipping = normal.tipping;
  Vec6 d = Vec6::Zero();
  d.head<3>() = normal.lamN - pc.lamN;
  pc.lamN = normal.lamN;
  // friction block on the slip x_o, with the normal block held (Schur
  // complement Ks) while it is inside the admissible set (S7)-(S14)
  const Vec3 s = c.tail<3>() + k.Knf.transpose() * d.head<3>();
  bool refreshed = false;
  const Vec3 lamF =
      parts::solveFrictionVelocity(pc.fb, friction, pc.state->certs, pc.shape, k, pc.interior, s,
                                   pc.lamF, pc.lamN, held, cx.friction, cx.stats, refreshed);
  d.tail<3>() = lamF - pc.lamF;
  pc.lamF = lamF;
  if (pc.interior) {
    // the normal block follows the friction impulse: W dN = -Knf dF
    const Vec3 dn = -k.G * d.tail<3>();
    d.head<3>() += dn;
    pc.lamN += dn;
  }
  if (held == 2 &&
      !parts::frictionCanTake(sup->fb, *sup->state->friction, sup->lamN, sup->lamF, hold->gain * d))
    return false;
  applyImpulse(pc, cx.pool, d);
  worst = std::max(worst, d.squaredNorm());
  if (hold && !d.isZero(0.0)) {
    // the support takes what keeps its held DOFs where they were (S15)-(S16)
    const Vec6 ds = hold->gain * d;
    sup->lamN += ds.head<3>();
    sup->lamF += ds.tail<3>();
    sup->settled = false;
    sup->fb.haveLast = false;
    applyImpulse(*sup, cx.pool, ds);
    worst = std::max(worst, ds.squaredNorm());
  }
  if (cx.settings.skipSettledPatches && d.isZero(0.0) && !refreshed) {
    pc.settled = true;
    snapshotOf(pc, cx.pool, pc.snapshot);
  }
  return true;
}

// Patches whose normals agree within this angle [rad] share a plane for
// the load sharing (S25): a body on faces of one floor or of boxes of one
// height (both exactly parallel); tilted faces keep their own split.
constexpr double kShareParallel = 1e-3;

// The groups of (S25): per dynamic body, its hard patches on static or
// kinematic supports with no stack hold, parallel to the body's first such
// patch; a body with one such patch has none. (A patch's loads are shared
// only while its impulses leave the support's velocity unchanged.)
// `groupOf`: scratch by solver body id; linear in the patches, and nothing
// allocated for bodies on one patch (a pile of coins).
void groupSharedPatches(const std::vector<PatchConstraint>& patches, int numBodies,
                        std::vector<int>& groupOf, std::vector<std::vector<int>>& groups) {
  groups.clear();
  auto eligible = [](const PatchConstraint& pc) {
    return !pc.b.body.dynamic && pc.compliance == 0.0 && pc.stack.hold < 0 && pc.stack.loadHold < 0;
  };
  // pass 1: -1 none, -2 one, -3 several eligible patches
  groupOf.assign(std::size_t(numBodies), -1);
  bool several = false;
  for (const PatchConstraint& pc : patches) {
    if (!eligible(pc)) continue;
    int& g = groupOf[std::size_t(pc.a.id)];
    several = several || g == -2;
    g = g == -1 ? -2 : -3;
  }
  if (!several) return;
  // pass 2: a group per body with several, by index once made
  const double cosParallel = std::cos(kShareParallel);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const PatchConstraint& pc = patches[i];
    if (!eligible(pc)) continue;
    int& g = groupOf[std::size_t(pc.a.id)];
    if (g == -2) continue;
    if (g == -3) {
      g = int(groups.size());
      groups.push_back({int(i)});
    } else if (patches[std::size_t(groups[std::size_t(g)][0])].F.col(2).dot(pc.F.col(2)) >=
               cosParallel) {
      groups[std::size_t(g)].push_back(int(i));
    }
  }
  // (a body whose other patches are not parallel to its first)
  groups.erase(std::remove_if(groups.begin(), groups.end(),
                              [](const std::vector<int>& grp) { return grp.size() < 2; }),
               groups.end());
}

// (S25) for one group, in the frame of its first patch; a patch whose
// loads change is visited again and its friction block re-solved.
void shareGroupLoads(std::vector<PatchConstraint>& patches, const std::vector<int>& group,
                     std::vector<parts::SharedPatch>& buf) {
  const PatchConstraint& ref = patches[std::size_t(group[0])];
  const btVector3& o = ref.state->geometry.origin;
  const Vec3 ex = ref.F.col(0), ey = ref.F.col(1);
  buf.resize(group.size());
  for (std::size_t k = 0; k < group.size(); ++k) {
    const PatchConstraint& pc = patches[std::size_t(group[k])];
    const btVector3 d = pc.state->geometry.origin - o;
    const Vec3 dv(double(d.x()), double(d.y()), double(d.z()));
    parts::SharedPatch& sp = buf[k];
    sp.origin = Vec2(dv.dot(ex), dv.dot(ey));
    sp.R << pc.F.col(0).dot(ex), pc.F.col(1).dot(ex), pc.F.col(0).dot(ey), pc.F.col(1).dot(ey);
    sp.shape = &pc.state->friction->shape();
    sp.lamN = pc.lamN;
  }
  if (!parts::shareLoads(buf)) return;
  for (std::size_t k = 0; k < group.size(); ++k) {
    PatchConstraint& pc = patches[std::size_t(group[k])];
    if (buf[k].lamN == pc.lamN) continue;
    pc.lamN = buf[k].lamN;
    pc.settled = false;
    pc.fb.haveLast = false;
  }
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
  std::vector<internal::Candidate> candidates;    // of the chunk in hand
  std::vector<PatchConstraint> patches;           // of the island
  std::vector<parts::StackHold> holds;            // of the island's stacked patches
  std::vector<parts::StackPatchView> stackViews;  // scratch of stage 3 (link stacks)
  std::vector<parts::StackLinks> stackLinks;      // scratch of stage 3 (link stacks)
  std::vector<char> otherRows;                    // by solver body id: in one of Bullet's rows
  // stage 3b: one body's hard, unstacked patches on static supports in one
  // plane, their loads shared after every iteration (S25); indices in patches
  std::vector<std::vector<int>> shareGroups;
  std::vector<parts::SharedPatch> shareBuf;  // scratch
  std::vector<int> shareGroupOf;             // scratch: a body's group (solver body id)
  PatchConstraint retry;                     // a stacked patch's state before its visit
  std::vector<btRigidBody*> flushBodies;     // bodies of the island's patches
};

std::shared_ptr<internal::PatchSolverShared> PatchFrictionSolver::makeShared() {
  auto shared = std::make_shared<internal::PatchSolverShared>();
  shared->friction = frictionSettings(shared->settings);
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
  using patchspin::internal::formatDouble;
  if (!body) throw Error("enablePatchFriction: body is null");
  if (options.model != Model::Ellipsoidal && options.model != Model::Exact)
    throw Error("PatchOptions::model must be Model::Ellipsoidal or Model::Exact: got " +
                std::to_string(int(options.model)));
  if (options.mu) {
    patchspin::internal::requireFinite(*options.mu, "PatchOptions::mu");
    if (*options.mu < 0.0)
      throw Error("PatchOptions::mu must be >= 0: got " + formatDouble(*options.mu));
  }
  if (options.rho) {
    patchspin::internal::requirePositive(*options.rho, "PatchOptions::rho");
    if (!(*options.rho >= kMinRho && *options.rho <= kMaxRho))
      throw Error("PatchOptions::rho = " + formatDouble(*options.rho) +
                  " m can never make a patch: the lever max|r| / rho must lie in [1e-5, 1e5] "
                  "with max|r| in [1.25e-162, 1e6] m, so rho in [" +
                  formatDouble(kMinRho) + ", " + formatDouble(kMaxRho) + "] m");
  }
  patchspin::internal::requirePositive(options.flatnessTolerance,
                                       "PatchOptions::flatnessTolerance");
  if (options.flatnessTolerance > kMaxFlatnessTolerance)
    throw Error("PatchOptions::flatnessTolerance must be at most pi/8 = " +
                formatDouble(kMaxFlatnessTolerance) +
                " rad (a patch ends at twice it, within "
                "the 45 degrees beyond which a face no longer faces the contact): got " +
                formatDouble(options.flatnessTolerance));
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
  using patchspin::internal::formatDouble;
  for (const auto& [value, name] :
       {std::pair{settings.pressureRefreshTolerance, "pressureRefreshTolerance"},
        std::pair{settings.pressureLagTolerance, "pressureLagTolerance"}}) {
    patchspin::internal::requireFinite(value,
                                       (std::string("PatchSolverSettings::") + name).c_str());
    if (value < 0.0)
      throw Error(std::string("PatchSolverSettings::") + name + " must be >= 0: got " +
                  formatDouble(value));
  }
  impl_->shared->settings = settings;
  impl_->shared->friction = frictionSettings(settings);
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
    im.stackViews.clear();
    for (const PatchConstraint& pc : im.patches)
      im.stackViews.push_back({pc.a.id, pc.b.id, &pc.a.body, &pc.b.body, &pc.F, pc.fb.rho});
    parts::linkStackedPatches(im.stackViews, m_tmpSolverBodyPool.size(), im.otherRows,
                              im.stackLinks, im.holds);
    // a soft patch is solved on its own: the held blocks fold K6 without
    // its compliance (SoftContact.StackOfSoftBoxes)
    for (std::size_t i = 0; i < im.patches.size(); ++i) {
      parts::StackLinks& l = im.stackLinks[i];
      if (l.support < 0) continue;
      parts::StackLinks& s = im.stackLinks[std::size_t(l.support)];
      if (im.patches[i].compliance == 0.0 && im.patches[std::size_t(l.support)].compliance == 0.0)
        continue;
      if (s.load == int(i)) s.load = s.loadHold = -1;
      l.support = l.hold = -1;
    }
    for (std::size_t i = 0; i < im.patches.size(); ++i) im.patches[i].stack = im.stackLinks[i];
  }
  // 3b share loads (S25)
  groupSharedPatches(im.patches, m_tmpSolverBodyPool.size(), im.shareGroupOf, im.shareGroups);
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
  PatchSolverStats& stats = *im.stats;  // (held across the visits, not reloaded)
  VisitContext cx{m_tmpSolverBodyPool, im.shared->settings, im.shared->friction, stats};
  double worst = 0.0;
  for (PatchConstraint& pc : im.patches) {
    ++stats.visits;
    if (pc.settled) {
      btVector3 now[4];
      snapshotOf(pc, m_tmpSolverBodyPool, now);
      if (now[0] == pc.snapshot[0] && now[1] == pc.snapshot[1] && now[2] == pc.snapshot[2] &&
          now[3] == pc.snapshot[3]) {
        ++stats.skippedVisits;
        continue;  // same input, same (zero) change
      }
      pc.settled = false;
    }
    // a stacked patch: its support held while the support is on its patch
    // (all six DOFs while it sticks and can take its share, else its
    // normal block); a support on a static body: its load held alike
    PatchConstraint* sup = nullptr;
    const parts::StackHold* stackHold = nullptr;
    if (pc.stack.hold >= 0) {
      sup = &im.patches[std::size_t(pc.stack.support)];
      stackHold = &im.holds[std::size_t(pc.stack.hold)];
    } else if (pc.stack.loadHold >= 0) {
      sup = &im.patches[std::size_t(pc.stack.load)];
      stackHold = &im.holds[std::size_t(pc.stack.loadHold)];
    }
    const parts::HeldBlocks* normalHold =
        stackHold && stackHold->normal.valid ? &stackHold->normal : nullptr;
    if (!stackHold || !sup->interior) {
      visitPatch(cx, pc, nullptr, nullptr, 0, worst);
    } else if (sup->fb.sticking && stackHold->all.valid) {
      im.retry = pc;
      if (!visitPatch(cx, pc, sup, &stackHold->all, 2, worst)) {
        const parts::PressureRecord law =
            pc.fb.law;  // the law is not rolled back: nor is its record
        pc = im.retry;
        pc.fb.law = law;
        visitPatch(cx, pc, sup, normalHold, normalHold ? 1 : 0, worst);
      }
    } else {
      visitPatch(cx, pc, sup, normalHold, normalHold ? 1 : 0, worst);
    }
  }
  for (const std::vector<int>& group : im.shareGroups)
    shareGroupLoads(im.patches, group, im.shareBuf);
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
  auto& pool = m_tmpSolverBodyPool;
  for (int it = 0; it < kPushIterations; ++it) {
    for (PatchConstraint& pc : impl_->patches) {
      if (pc.targetPush.isZero()) continue;
      const Vec3 c = patchVelocity(pc, [&](const internal::BodyTerms& t, Vec3& v, Vec3& w) {
                       v = internal::toEigen(pool[t.id].m_pushVelocity);
                       w = internal::toEigen(pool[t.id].m_turnVelocity);
                     }).head<3>();
      const Vec3 lam = parts::solveNormalPosition(
          pc.k.Winv, pc.lamPush, c, softTarget(pc.targetPush, pc.compliance, pc.lamPush));
      Vec6 d = Vec6::Zero();
      d.head<3>() = lam - pc.lamPush;
      pc.lamPush = lam;
      parts::applyPatchImpulse(pc.a.body, pc.b.body, pc.F, pc.fb.rho, d,
                               [&](int side, const Vec3& dv, const Vec3& dw) {
                                 btSolverBody& sb = pool[side == 0 ? pc.a.id : pc.b.id];
                                 sb.m_pushVelocity += internal::toBt(dv);
                                 sb.m_turnVelocity += internal::toBt(dw);
                               });
    }
  }
}

// Stage 6.
btScalar PatchFrictionSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies,
                                                            int numBodies,
                                                            const btContactSolverInfo& info) {
  Impl& im = *impl_;
  PatchSolverStats& stats = *im.stats;
  stats.patches += long(im.patches.size());
  for (PatchConstraint& pc : im.patches) {
    stats.stackHolds += pc.stack.hold >= 0 || pc.stack.loadHold >= 0;
    const Vec6 c = constraintVelocity(pc, m_tmpSolverBodyPool);
    internal::storePatchState(pc, c, im.selection.step());
    im.reports->record(pc, c);
    if (internal::writeManifoldImpulses(pc, *pc.manifold))
      im.selection.markWritten(*pc.state);
    else
      ++stats.patchesWithoutPoints;
    const PatchLoads l = parts::toLoads(pc.lamN);
    if (l.Pz > 0.0 && pc.fb.mu > 0.0) {
      const Vec2 cop(l.Ty / l.Pz, -l.Tx / l.Pz);
      stats.maxPressureLag =
          std::max(stats.maxPressureLag, (cop - pc.fb.law.pressureCop).norm() / pc.shape.diameter);
    }
  }
  im.flushBodies.clear();
  for (const PatchConstraint& pc : im.patches)
    if (btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(pc.state->body)))
      im.flushBodies.push_back(body);
  im.patches.clear();
  im.shareGroups.clear();
  const btScalar out =
      btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
  for (btRigidBody* body : im.flushBodies) internal::flushCrumbs(*body);
  return out;
}

}  // namespace patchspin::bullet
