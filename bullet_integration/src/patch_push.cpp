// Patch position correction (patch_push.hpp).
#include "patch_push.hpp"

#include "patch_visit.hpp"

#include <patchspin/parts/patch_body.hpp>

namespace patchspin::bullet::internal {

void pushPatches(std::vector<PatchConstraint>& patches, btAlignedObjectArray<btSolverBody>& pool) {
  for (int it = 0; it < kPushIterations; ++it) {
    for (PatchConstraint& pc : patches) {
      if (pc.articulated >= 0 || pc.targetPush.isZero()) continue;
      const Vec3 c = parts::patchVelocityOf(pc.a.body, pc.b.body, pc.F, pc.fb.rho,
                                            [&](int side, Vec3& v, Vec3& w) {
                                              const int id = side == 0 ? pc.a.id : pc.b.id;
                                              v = toEigen(pool[id].m_pushVelocity);
                                              w = toEigen(pool[id].m_turnVelocity);
                                            })
                         .head<3>();
      const Vec3 lam = parts::solveNormalPosition(
          pc.k.Winv, pc.lamPush, c, softTarget(pc.targetPush, pc.compliance, pc.lamPush));
      Vec6 d = Vec6::Zero();
      d.head<3>() = lam - pc.lamPush;
      pc.lamPush = lam;
      parts::applyPatchImpulse(pc.a.body, pc.b.body, pc.F, pc.fb.rho, d,
                               [&](int side, const Vec3& dv, const Vec3& dw) {
                                 btSolverBody& sb = pool[side == 0 ? pc.a.id : pc.b.id];
                                 sb.m_pushVelocity += toBt(dv);
                                 sb.m_turnVelocity += toBt(dw);
                               });
    }
  }
}

}  // namespace patchspin::bullet::internal
