// The leaf shape on one side of a manifold (compound_children.hpp).
#include "compound_children.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace patchspin::bullet::internal {

bool isCompound(const btCollisionObject& object) {
  return object.getCollisionShape()->getShapeType() == COMPOUND_SHAPE_PROXYTYPE;
}

int taggedChild(const btPersistentManifold& m, bool body0) {
  if (m.getNumContacts() == 0) return -1;
  const btManifoldPoint& p = m.getContactPoint(0);
  return body0 ? p.m_index0 : p.m_index1;
}

bool resolveLeaf(const btCollisionObject& object, int child, LeafShape& leaf) {
  const btCollisionShape* shape = object.getCollisionShape();
  if (shape->getShapeType() != COMPOUND_SHAPE_PROXYTYPE) {
    leaf.shape = shape;
    leaf.transform = object.getWorldTransform();
    return true;
  }
  const auto* compound = static_cast<const btCompoundShape*>(shape);
  const int n = compound->getNumChildShapes();
  if (child < 0 || child >= n) return false;
  // a nested compound makes every tag ambiguous (see the header)
  for (int i = 0; i < n; ++i)
    if (compound->getChildShape(i)->getShapeType() == COMPOUND_SHAPE_PROXYTYPE) return false;
  leaf.shape = compound->getChildShape(child);
  leaf.transform = object.getWorldTransform() * compound->getChildTransform(child);
  return true;
}

}  // namespace patchspin::bullet::internal
