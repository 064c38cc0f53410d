// Reported impulses (manifold_impulses.hpp).
#include "manifold_impulses.hpp"

#include <patchspin/parts/point_impulses.hpp>

#include <algorithm>
#include <array>

namespace patchspin::bullet::internal {

bool writeManifoldImpulses(const PatchConstraint& pc, btPersistentManifold& m) {
  const int count = std::min(m.getNumContacts(), parts::kMaxPoints);
  if (count == 0) return false;
  const PatchState& st = *pc.state;
  const Vec3 O = toEigen(st.geometry.origin);
  const Vec3 ex = pc.F.col(0), ey = pc.F.col(1);
  std::array<Vec2, parts::kMaxPoints> points;
  for (int k = 0; k < count; ++k) {
    const btManifoldPoint& p = m.getContactPoint(k);
    const Vec3 mid = 0.5 * (toEigen(p.m_positionWorldOnA) + toEigen(p.m_positionWorldOnB)) - O;
    points[std::size_t(k)] = Vec2(mid.dot(ex), mid.dot(ey));
  }
  const parts::PointImpulses spread =
      parts::spreadPatchImpulse(points.data(), count, pc.lamN, pc.lamF, pc.fb.rho);
  // Bullet's impulses act on body 0: the friction on A, or its reaction when
  // A is body 1; the normal impulse is a compression either way
  const double side = m.getBody0() == st.body ? 1.0 : -1.0;
  const btVector3 dir1 = toBt(ex), dir2 = toBt(ey);
  for (int k = 0; k < count; ++k) {
    btManifoldPoint& p = m.getContactPoint(k);
    p.m_appliedImpulse = btScalar(spread.normal[std::size_t(k)]);
    p.m_lateralFrictionDir1 = dir1;
    p.m_lateralFrictionDir2 = dir2;
    p.m_appliedImpulseLateral1 = btScalar(side * spread.tangent[std::size_t(k)].x());
    p.m_appliedImpulseLateral2 = btScalar(side * spread.tangent[std::size_t(k)].y());
  }
  return true;
}

}  // namespace patchspin::bullet::internal
