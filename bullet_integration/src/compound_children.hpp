// The leaf shape on one side of a contact manifold: a body's own shape, or,
// for a btCompoundShape, the child whose contact the manifold holds, with
// its world transform (the object's transform times the child's).
//
// Bullet's compound algorithms (btCompoundCollisionAlgorithm,
// btCompoundCompoundCollisionAlgorithm) give every child pair a manifold of
// its own between the two top-level objects, and tag each point with the
// child's index: btManifoldPoint::m_index0 for the manifold's body 0,
// m_index1 for body 1 (btManifoldResult::addContactPoint swaps them with the
// bodies). A nested compound's algorithm overwrites the tag with its own
// child's index, so the tag does not say which branch it came from: a
// compound with a compound child is not resolved (CompoundShapes.*).
#pragma once

#include <LinearMath/btTransform.h>

class btCollisionObject;
class btCollisionShape;
class btPersistentManifold;

namespace patchspin::bullet::internal {

// A shape with its world pose.
struct LeafShape {
  const btCollisionShape* shape = nullptr;
  btTransform transform;  // world
};

// The child index of `body0`'s side (the manifold's body 0, else body 1)
// tagged on the manifold's first point; -1 for a manifold without points or
// a side that is not a compound (Bullet tags those -1; triangle meshes tag
// their triangle, which is not a child).
int taggedChild(const btPersistentManifold& m, bool body0);

// The leaf of `object` for child index `child`: the object's own shape and
// transform if it is not a compound (child ignored); for a btCompoundShape,
// the child `child` and object transform * child transform. False (leaf
// unspecified) for a compound with an index out of range (-1: no point told
// which) or with a compound child (nested: the index is ambiguous).
bool resolveLeaf(const btCollisionObject& object, int child, LeafShape& leaf);

// True for an object whose shape is a btCompoundShape.
bool isCompound(const btCollisionObject& object);

}  // namespace patchspin::bullet::internal
