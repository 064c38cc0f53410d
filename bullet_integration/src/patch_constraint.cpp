// Patch constraint set-up (patch_constraint.hpp).
#include "patch_constraint.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>

namespace patchspin::bullet::internal {

BodyTerms makeBodyTerms(const btSolverBody& sb, int id, const Vec3& r) {
  BodyTerms t;
  t.id = id;
  t.body.dynamic = sb.m_originalBody != nullptr;
  if (!t.body.dynamic) return t;
  t.v0 = sb.m_linearVelocity + sb.m_externalForceImpulse;
  t.w0 = sb.m_angularVelocity + sb.m_externalTorqueImpulse;
  t.body.r = r;
  t.body.invM = toEigen(sb.m_invMass).cwiseProduct(toEigen(sb.m_linearFactor));
  const btMatrix3x3& I = sb.m_originalBody->getInvInertiaTensorWorld();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) t.body.invI(i, k) = double(I[i][k]);
  const Vec3 af = toEigen(sb.m_angularFactor);
  if (!(af.x() == 1.0 && af.y() == 1.0 && af.z() == 1.0))  // (times 1: unchanged)
    t.body.invI = af.asDiagonal() * t.body.invI * af.asDiagonal();
  return t;
}

PointSoftness pointSoftness(const btManifoldPoint* point, const btCollisionObject& A,
                            const btCollisionObject& B, const btContactSolverInfo& info) {
  const int flags = point ? point->m_contactPointFlags : 0;
  double cfm = double(info.m_globalCfm), erp = double(info.m_erp2);
  double stiffness = 0.0, damping = 0.0;
  bool springy = false;
  if (flags & (BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP)) {
    if (flags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) cfm = double(point->m_contactCFM);
    if (flags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) erp = double(point->m_contactERP);
  } else if (point) {
    springy = (flags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) != 0;
    stiffness = double(point->m_combinedContactStiffness1);
    damping = double(point->m_combinedContactDamping1);
  } else if ((A.getCollisionFlags() | B.getCollisionFlags()) &
             btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) {
    springy = true;
    stiffness = double(gCalculateCombinedContactStiffnessCallback(&A, &B));
    damping = double(gCalculateCombinedContactDampingCallback(&A, &B));
  }
  const double dt = double(info.m_timeStep);
  if (springy) {
    const double denom = std::max(dt * stiffness + damping, double(SIMD_EPSILON));
    cfm = 1.0 / denom;
    erp = dt * stiffness / denom;
  }
  return {cfm / dt, erp};
}

bool makePatchConstraint(const Candidate& cand, const btPersistentManifold& m,
                         const btSolverBody& sbA, int idA, const btSolverBody& sbB, int idB,
                         const btContactSolverInfo& info, PatchConstraint& pc,
                         const ArticulatedShare* articulated) {
  PatchState& st = *cand.state;
  const double dt = double(info.m_timeStep);
  pc.state = &st;
  pc.fb.model = cand.options->model;
  pc.fb.dt = dt;
  pc.fb.mu = cand.mu;
  pc.fb.rho = st.friction->rho();
  pc.fb.stateSticking = st.sticking;
  pc.fb.law = st.law;
  pc.shape = parts::summarizeOutline(st.friction->shape());
  pc.shape.innerRadius2 = st.innerRadius2;
  const Vec3 O = toEigen(st.geometry.origin);
  const Vec3 ex = toEigen(st.geometry.xAxis);
  const Vec3 ey = toEigen(st.geometry.yAxis);
  pc.F.col(0) = ex;
  pc.F.col(1) = ey;
  pc.F.col(2) = toEigen(st.geometry.normal);
  pc.a = makeBodyTerms(sbA, idA, O - toEigen(sbA.m_worldTransform.getOrigin()));
  pc.b = makeBodyTerms(sbB, idB, O - toEigen(sbB.m_worldTransform.getOrigin()));
  pc.ids[0] = idA;
  pc.ids[1] = idB;
  // effective masses of the 6 DOFs and the friction block's Schur
  // complement (normal block held bilateral)
  // a soft contact: the normal block's compliance (S23) added to W
  const PointSoftness soft = pointSoftness(m.getNumContacts() > 0 ? &m.getContactPoint(0) : nullptr,
                                           *cand.A, *cand.B, info);
  pc.compliance = soft.cfm > 0.0 ? parts::patchCompliance(soft.cfm) : 0.0;
  Mat6 K6 = parts::patchEffectiveMass(pc.a.body, pc.b.body, pc.F, pc.fb.rho);
  if (articulated) K6 += articulated->K6;
  K6(0, 0) += pc.compliance;
  if (!parts::makePatchBlocks(K6, pc.k)) return false;
  // restitution from the normal velocity at O before the step (without the
  // step's external impulses, as Bullet's rows take it)
  double bounce = 0.0;
  if (cand.restitution > 0.0) {
    const btSolverBody* sb[2] = {&sbA, &sbB};
    Vec6 before = parts::patchVelocityOf(pc.a.body, pc.b.body, pc.F, pc.fb.rho,
                                         [&](int side, Vec3& v, Vec3& w) {
                                           v = toEigen(sb[side]->m_linearVelocity);
                                           w = toEigen(sb[side]->m_angularVelocity);
                                         });
    if (articulated) before += articulated->before;
    const double pending = st.pendingBounceStep == st.lastSeen - 1 ? st.pendingBounce : 0.0;
    const parts::Bounce b =
        parts::restitutionBounce(before[0], st.geometry.gap, dt, cand.restitution,
                                 double(info.m_restitutionVelocityThreshold), pending);
    bounce = b.now;
    st.pendingBounce = b.next;
    st.pendingBounceStep = st.lastSeen;
  }
  // position error: gap at O (< 0 penetrating) and tilt of the face
  const Vec3 tilt = toEigen(st.geometry.tilt);
  // (none on a patch pivoting on its edge: the tilt is its motion)
  const Vec3 tiltRate = st.pivoting ? Vec3::Zero() : Vec3(0.0, tilt.dot(ex), tilt.dot(ey));
  const parts::NormalTargets targets =
      pc.compliance > 0.0
          ? parts::softNormalTargets(st.geometry.gap, st.geometry.clearance, tiltRate,
                                     st.geometry.outline.size(), dt, info.m_splitImpulse != 0,
                                     double(info.m_erp), double(info.m_erp2), soft.erp, bounce)
          : parts::normalTargets(st.geometry.gap, st.geometry.clearance, tiltRate,
                                 st.geometry.outline.size(), dt, info.m_splitImpulse != 0,
                                 double(info.m_erp), double(info.m_erp2), bounce);
  pc.targetN = targets.velocity;
  // a pivoting patch starts the step clamped (the stack hold through its
  // pivots from the first visit); past the flatness limit its pivot edge
  // is the one beyond the last step's centre of pressure
  pc.interior = !st.pivoting;
  pc.pivotOnly = false;
  if (st.pivotOnly && st.normal > 0.0) {
    const Vec2 cop(-st.couple.dot(ey) / st.normal, st.couple.dot(ex) / st.normal);
    const double n = cop.norm();
    if (n > 0.0) {
      pc.pivotOnly = true;
      pc.pivotCop = cop * (10.0 * st.geometry.outline.size() / n);
    }
  }
  pc.targetPush = targets.push;
  return true;
}

void patchFrameOf(const PatchState& st, Mat3& F, Vec3& O) {
  O = toEigen(st.geometry.origin);
  F.col(0) = toEigen(st.geometry.xAxis);
  F.col(1) = toEigen(st.geometry.yAxis);
  F.col(2) = toEigen(st.geometry.normal);
}

bool warmStart(const Candidate& cand, const btContactSolverInfo& info, PatchConstraint& pc,
               Vec6& lam) {
  if (!(info.m_solverMode & SOLVER_USE_WARMSTARTING) || !cand.wasFlat) return false;
  const PatchState& st = *cand.state;
  const Vec3 ex = pc.F.col(0), ey = pc.F.col(1);
  const double f = kPatchWarmStartFactor;
  pc.lamN = f * Vec3(st.normal, st.couple.dot(ex), st.couple.dot(ey));
  pc.lamF = f * Vec3(st.frictionT.dot(ex), st.frictionT.dot(ey), st.frictionSpin);
  pc.fb.warmSlip = Vec3(st.slipT.dot(ex), st.slipT.dot(ey), st.slipSpin);
  lam << pc.lamN, pc.lamF;
  return true;
}

void storePatchState(const PatchConstraint& pc, const Vec6& c, long step) {
  PatchState& st = *pc.state;
  const Vec3 ex = pc.F.col(0), ey = pc.F.col(1);
  st.normal = pc.lamN[0];
  st.couple = pc.lamN[1] * ex + pc.lamN[2] * ey;
  st.frictionT = pc.lamF[0] * ex + pc.lamF[1] * ey;
  st.frictionSpin = pc.lamF[2];
  st.slipT = c[3] * ex + c[4] * ey;
  st.slipSpin = c[5];
  st.sticking = pc.fb.sticking;
  st.law.pressureCop = pc.fb.law.pressureCop;
  st.law.piInvValid = pc.fb.law.piInvValid;
  if (pc.fb.law.piInvValid) st.law.piInv = pc.fb.law.piInv;
  st.pivoting = pc.tipping;
  if (pc.fb.failed) {
    st.tipStep = step;
    st.flat = false;
  }
}

void flushCrumbs(btRigidBody& body) {
  const btScalar tiny = std::sqrt(std::numeric_limits<btScalar>::min());
  auto flushVector = [&](const btVector3& v) {
    const btScalar cut = std::max(tiny, btScalar(1e-12) * v.length());
    btVector3 out = v;
    bool changed = false;
    for (int i = 0; i < 3; ++i)
      if (out[i] != 0 && std::abs(out[i]) < cut) out[i] = 0, changed = true;
    return std::make_pair(out, changed);
  };
  const auto w = flushVector(body.getAngularVelocity());
  if (w.second) body.setAngularVelocity(w.first);
  const auto v = flushVector(body.getLinearVelocity());
  if (v.second) body.setLinearVelocity(v.first);
  btTransform tr = body.getWorldTransform();
  btMatrix3x3& basis = tr.getBasis();
  bool changed = false;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (basis[i][k] != 0 && std::abs(basis[i][k]) < tiny) basis[i][k] = 0, changed = true;
  if (changed) {
    body.setWorldTransform(tr);
    body.setInterpolationWorldTransform(tr);
  }
}

}  // namespace patchspin::bullet::internal
