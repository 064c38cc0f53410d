// Patch visits (internal): the iteration stage of a patch solver, shared by
// PatchFrictionSolver (bodies: Bullet's solver bodies) and
// PatchMultiBodySolver (also Featherstone links, through their Jacobians).
// What differs between the two is how a patch reads its DOF velocity and
// applies an impulse, given by a `Bodies` policy:
//   Vec6 velocity(const PatchConstraint&)        the DOF velocity c (S1)
//   void apply(const PatchConstraint&, const Vec6& d)   impulse change d
//   bool settles(const PatchConstraint&)         may be skipped while settled
//   void snapshot(const PatchConstraint&, btVector3* out)  what "unchanged" means
// The parts (normal block, friction block, stack holds, load sharing) are
// the core's; the arithmetic is the one PatchFrictionSolver always did
// (Determinism.* pins it bit for bit).
#pragma once

#include "solver_data.hpp"

#include <patchspin/parts/load_sharing.hpp>
#include <patchspin/parts/pivot_rows.hpp>

#include <algorithm>
#include <vector>

namespace patchspin::bullet::internal {

// Within a step, a slipping friction block whose input (b, L) changed by
// less than this, relative, since its last solve keeps that solution (the
// velocities carry ~6e-8 in float).
constexpr double kReuseRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-6;
// Relative residual at which a friction block solve stops: below the
// precision of the velocities it is computed from.
constexpr double kBlockRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-9;
// Pseudo-velocity iterations of the patch position correction per step.
constexpr int kPushIterations = 4;
// A visit's impulse change below the blocks' own relative precision
// (kBlockRelTol) of the patch's normal impulse (couples: times the patch's
// diameter) is their round-off, not a change (a slipping coin's second
// visit reads float velocities and finds ~1e-12 of it): it is not applied,
// and the patch settles (PatchSolverSettings::settleOnRoundOff;
// PatchFrictionSolver.SettlingOnRoundOffSavesAVisitAndKeepsTheMotion).
// Float Bullet only: in double the solver's velocities carry ~1e-16, and
// any threshold above that decides differently in a rotated frame or
// another island order (FrameInvariance.*, MultithreadedWorld.* pin those
// to round-off), so there only an exactly zero change settles, as before.
constexpr double kNegligibleChange = sizeof(btScalar) == sizeof(double) ? 0.0 : kBlockRelTol;

// True if every component of the impulse change d (S1 order: Lambda_z, the
// two couples, the friction DOFs) lies within kNegligibleChange of the
// normal impulse lamZ (couples: of lamZ times `size` [m]).
inline bool negligibleChange(const Vec6& d, double lamZ, double size) {
  const double f = kNegligibleChange * lamZ, m = f * size;
  return std::abs(d[0]) <= f && std::abs(d[1]) <= m && std::abs(d[2]) <= m && std::abs(d[3]) <= f &&
         std::abs(d[4]) <= f && std::abs(d[5]) <= f;
}

parts::FrictionPartSettings frictionSettings(const PatchSolverSettings& s);

// PatchOptions and PatchSolverSettings checked as enablePatchFriction and
// setSettings document (Error otherwise).
void checkPatchOptions(const PatchOptions& options);
void checkSolverSettings(const PatchSolverSettings& settings);

// The target of a compliant normal row, t - (C lambda_z, 0, 0) (S23); t
// itself on a hard contact.
inline Vec3 softTarget(const Vec3& target, double compliance, const Vec3& lam) {
  if (compliance == 0.0) return target;
  return Vec3(target[0] - compliance * lam[0], target[1], target[2]);
}

// The Bodies of PatchFrictionSolver's patches, and of the rigid sides of
// PatchMultiBodySolver's: Bullet's solver bodies, whose velocity in the
// iterations is the fixed part plus the delta velocities (the line
// Bullet's rows read too).
struct SolverBodies {
  btAlignedObjectArray<btSolverBody>& pool;
  Vec6 velocity(const PatchConstraint& pc) const {
    return parts::patchVelocityOf(pc.a.body, pc.b.body, pc.F, pc.fb.rho,
                                  [&](int side, Vec3& v, Vec3& w) {
                                    const BodyTerms& t = side == 0 ? pc.a : pc.b;
                                    v = toEigen(t.v0 + pool[t.id].m_deltaLinearVelocity);
                                    w = toEigen(t.w0 + pool[t.id].m_deltaAngularVelocity);
                                  });
  }
  void apply(const PatchConstraint& pc, const Vec6& lam) {
    parts::applyPatchImpulse(pc.a.body, pc.b.body, pc.F, pc.fb.rho, lam,
                             [&](int side, const Vec3& dv, const Vec3& dw) {
                               btSolverBody& sb = pool[side == 0 ? pc.a.id : pc.b.id];
                               sb.m_deltaLinearVelocity += toBt(dv);
                               sb.m_deltaAngularVelocity += toBt(dw);
                             });
  }
  static bool settles(const PatchConstraint&) { return true; }
  // the delta velocities of the patch's two solver bodies (a settled patch
  // is skipped while they are unchanged)
  void snapshot(const PatchConstraint& pc, btVector3* out) const {
    const btSolverBody& a = pool[pc.ids[0]];
    const btSolverBody& b = pool[pc.ids[1]];
    out[0] = a.m_deltaLinearVelocity;
    out[1] = a.m_deltaAngularVelocity;
    out[2] = b.m_deltaLinearVelocity;
    out[3] = b.m_deltaAngularVelocity;
  }
};

// What a visit needs besides its patch.
template <class Bodies>
struct VisitContext {
  Bodies& bodies;
  const PatchSolverSettings& settings;
  const parts::FrictionPartSettings& friction;
  PatchSolverStats& stats;
};

// One visit of a patch (stage 5), with a support hold (0 none, 1 the
// support's normal block, 2 all six DOFs; sup: the held patch). False: the
// held support cannot take its share, and the visit is to be redone with
// less held (nothing was applied). `worst` gets the largest squared change.
// pivots: the held support's pivot rows (a support clamped at its edge,
// holdThroughPivots), which must keep pushing: false (nothing applied) if
// the support's share would make one pull.
template <class Bodies>
bool visitPatch(VisitContext<Bodies>& cx, PatchConstraint& pc, PatchConstraint* sup,
                const parts::HeldBlocks* hold, int held, double& worst,
                const parts::PivotRows* pivots = nullptr) {
  const parts::PatchBlocks& k = hold ? static_cast<const parts::PatchBlocks&>(*hold) : pc.k;
  FrictionPatch& friction = *pc.state->friction;
  const Vec3 lamNBefore = pc.lamN, lamFBefore = pc.lamF;
  // normal block (S4)-(S6)
  const Vec6 c = cx.bodies.velocity(pc);
  // (soft: the compliant row c_n = t_n - C lamN, with (W + C)^-1 in k.Winv (S23))
  const Vec3 targetN = softTarget(pc.targetN, pc.compliance, pc.lamN);
  const Vec3 residualN = targetN - c.head<3>();
  parts::NormalImpulse normal;
  if (pc.pivotOnly) {
    // past the flatness limit: only the pivot edge's rows, never interior
    parts::clampNormalImpulse(k.Winv, pc.lamN, residualN, pc.pivotCop, pc.shape, friction.shape(),
                              normal);
    normal.tipping = normal.lamN[0] > 0.0;
  } else {
    normal = parts::solveNormalVelocity(k.Winv, pc.lamN, c.head<3>(), targetN, pc.shape,
                                        friction.shape());
  }
  pc.interior = normal.interior;
  pc.tipping = normal.tipping;
  Vec6 d = Vec6::Zero();
  bool refreshed = false;
  // a clamped patch that sticks: its pivot rows and friction DOFs together
  // (S26), kept while the pivots push and the friction can take it
  bool pivotSolved = false;
  if (!normal.interior && pc.fb.sticking) {
    const parts::PivotRows rows = parts::pivotRowsOf(friction.shape(), normal.lamN);
    Mat6 K6;
    K6 << k.Winv.inverse(), k.Knf, k.Knf.transpose(), k.Kff;
    Vec6 r;
    r << residualN, -c.tail<3>();
    Vec6 dj;
    if (parts::solvePivotsWithFriction(K6, rows, pc.lamN, r, dj) &&
        parts::frictionCanTake(pc.fb, friction, pc.lamN, pc.lamF, dj)) {
      d = dj;
      pc.lamN += dj.head<3>();
      pc.lamF += dj.tail<3>();
      pivotSolved = true;
    }
  }
  if (!pivotSolved) {
    d.head<3>() = normal.lamN - pc.lamN;
    pc.lamN = normal.lamN;
    // friction block on the slip x_o, with the normal block held (Schur
    // complement Ks) while it is inside the admissible set (S7)-(S14)
    const Vec3 s = c.tail<3>() + k.Knf.transpose() * d.head<3>();
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
  }
  if (kNegligibleChange > 0.0 && cx.settings.settleOnRoundOff &&
      negligibleChange(d, std::max(lamNBefore[0], pc.lamN[0]), pc.shape.diameter)) {
    pc.lamN = lamNBefore, pc.lamF = lamFBefore;
    d.setZero();
  }
  if (held == 2 &&
      !parts::frictionCanTake(sup->fb, *sup->state->friction, sup->lamN, sup->lamF, hold->gain * d))
    return false;
  if (pivots && !parts::pivotsPush(*pivots, sup->lamN + (hold->gain * d).head<3>())) return false;
  cx.bodies.apply(pc, d);
  worst = std::max(worst, d.squaredNorm());
  if (hold && !d.isZero(0.0)) {
    // the support takes what keeps its held DOFs where they were (S15)-(S16)
    const Vec6 ds = hold->gain * d;
    sup->lamN += ds.head<3>();
    sup->lamF += ds.tail<3>();
    sup->settled = false;
    sup->fb.haveLast = false;
    cx.bodies.apply(*sup, ds);
    worst = std::max(worst, ds.squaredNorm());
  }
  if (cx.settings.skipSettledPatches && d.isZero(0.0) && !refreshed && cx.bodies.settles(pc)) {
    pc.settled = true;
    cx.bodies.snapshot(pc, pc.snapshot);
  }
  return true;
}

// What a visit changes in its patch before it can refuse (visitPatch's
// false, nothing applied): the normal block's outcome, the impulses and the
// friction block's state. A refused try is undone from it, the law's record
// aside (the law itself is not rolled back: nor is its record). The rest of
// the patch (bodies, blocks, links) a visit only reads.
struct VisitUndo {
  bool interior = true, tipping = false;
  Vec3 lamN = Vec3::Zero(), lamF = Vec3::Zero();
  parts::FrictionBlockState fb;

  explicit VisitUndo(const PatchConstraint& pc)
      : interior(pc.interior), tipping(pc.tipping), lamN(pc.lamN), lamF(pc.lamF), fb(pc.fb) {}
  void restore(PatchConstraint& pc) const {
    const parts::PressureRecord law = pc.fb.law;
    pc.interior = interior, pc.tipping = tipping, pc.lamN = lamN, pc.lamF = lamF;
    pc.fb = fb;
    pc.fb.law = law;
  }
};

// A stacked patch visited with its support clamped at its edge (S27): the
// support's pivot rows held, and its friction DOFs while it sticks, the
// pivots kept pushing; tried in turn with both pivots, then each alone (a
// sticking support: always with its friction held, as the load's share
// at 1000:1 is far beyond what its friction solve alone carries in the
// iterations). False if none took (nothing applied). Guarded by HandBack.*.
template <class Bodies>
bool holdThroughPivots(VisitContext<Bodies>& cx, PatchConstraint& pc, PatchConstraint& sup,
                       const parts::StackHold& sh, double& worst) {
  const parts::PivotRows both = parts::pivotRowsOf(sup.state->friction->shape(), sup.lamN);
  if (both.n == 0) return false;
  parts::PivotRows tries[3] = {both};
  int nt = 1;
  for (int k = 0; k < both.n && both.n == 2; ++k) {
    tries[nt].n = 1;
    tries[nt++].a[0] = both.a[k];
  }
  Mat6 K6;
  K6 << pc.k.Winv.inverse(), pc.k.Knf, pc.k.Knf.transpose(), pc.k.Kff;
  const bool friction = sup.fb.sticking;
  for (int t = 0; t < nt; ++t) {
    const parts::PivotRows& rows = tries[t];
    Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6> H =
        Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6>::Zero(rows.n + (friction ? 3 : 0), 6);
    for (int k = 0; k < rows.n; ++k) H.block<1, 3>(k, 0) = rows.a[k].transpose();
    if (friction) H.block<3, 3>(rows.n, 3).setIdentity();
    parts::HeldBlocks h;
    parts::foldHeldRows(K6, sh.heldK, sh.coupling, H, h);
    if (!h.valid) continue;
    const VisitUndo undo(pc);
    if (visitPatch(cx, pc, &sup, &h, friction ? 2 : 1, worst, &rows)) return true;
    undo.restore(pc);
  }
  return false;
}

// The groups of (S25): per dynamic body, its hard patches on static or
// kinematic supports with no stack hold, parallel to the body's first such
// patch; a body with one such patch has none. (A patch's loads are shared
// only while its impulses leave the support's velocity unchanged.) Only
// patches between solver bodies (not articulated) take part. `groupOf`:
// scratch by solver body id.
void groupSharedPatches(const std::vector<PatchConstraint>& patches, int numBodies,
                        std::vector<int>& groupOf, std::vector<std::vector<int>>& groups);

// (S25) for one group, in the frame of its first patch; a patch whose
// loads change is visited again and its friction block re-solved.
void shareGroupLoads(std::vector<PatchConstraint>& patches, const std::vector<int>& group,
                     std::vector<parts::SharedPatch>& buf);

// The island's patches and their scratch, for one iteration of stage 5.
struct PatchIteration {
  std::vector<PatchConstraint>& patches;
  const std::vector<parts::StackHold>& holds;
  const std::vector<std::vector<int>>& shareGroups;
  std::vector<parts::SharedPatch>& shareBuf;
};

// Stage 5, one iteration: every patch visited (a settled one skipped while
// its bodies are unchanged), stacked patches with their support held, then
// the load sharing. Returns the largest squared impulse change.
template <class Bodies>
double iteratePatches(VisitContext<Bodies>& cx, PatchIteration& it) {
  PatchSolverStats& stats = cx.stats;
  double worst = 0.0;
  for (PatchConstraint& pc : it.patches) {
    ++stats.visits;
    if (pc.settled) {
      btVector3 now[4];
      cx.bodies.snapshot(pc, now);
      if (now[0] == pc.snapshot[0] && now[1] == pc.snapshot[1] && now[2] == pc.snapshot[2] &&
          now[3] == pc.snapshot[3]) {
        ++stats.skippedVisits;
        continue;  // same input, same (zero) change
      }
      pc.settled = false;
    }
    // a stacked patch: its support held while the support is on its patch
    // (all six DOFs while it sticks and can take its share, else its
    // normal block), through its pivot rows while it is clamped at its
    // edge; a support on a static body: its load held alike
    PatchConstraint* sup = nullptr;
    const parts::StackHold* stackHold = nullptr;
    if (pc.stack.hold >= 0) {
      sup = &it.patches[std::size_t(pc.stack.support)];
      stackHold = &it.holds[std::size_t(pc.stack.hold)];
    } else if (pc.stack.loadHold >= 0) {
      sup = &it.patches[std::size_t(pc.stack.load)];
      stackHold = &it.holds[std::size_t(pc.stack.loadHold)];
    }
    const parts::HeldBlocks* normalHold =
        stackHold && stackHold->normal.valid ? &stackHold->normal : nullptr;
    if (stackHold && pc.stack.hold >= 0 && !sup->interior &&
        holdThroughPivots(cx, pc, *sup, *stackHold, worst))
      continue;
    if (!stackHold || !sup->interior) {
      visitPatch(cx, pc, nullptr, nullptr, 0, worst);
    } else if (sup->fb.sticking && stackHold->all.valid) {
      const VisitUndo undo(pc);
      if (!visitPatch(cx, pc, sup, &stackHold->all, 2, worst)) {
        undo.restore(pc);
        visitPatch(cx, pc, sup, normalHold, normalHold ? 1 : 0, worst);
      }
    } else {
      visitPatch(cx, pc, sup, normalHold, normalHold ? 1 : 0, worst);
    }
  }
  for (const std::vector<int>& group : it.shareGroups)
    shareGroupLoads(it.patches, group, it.shareBuf);
  return worst;
}

}  // namespace patchspin::bullet::internal
