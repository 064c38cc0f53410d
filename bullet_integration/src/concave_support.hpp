// The plane under a flat face on a triangle mesh or a heightfield.
// A face resting on coplanar triangles gets one patch over its whole area,
// whatever the triangle count: the support is the triangles' common plane,
// found from the triangles themselves (never from the manifold points, whose
// normals carry Bullet's internal-edge artefacts).
#pragma once

#include "patch_detection.hpp"

class btCollisionShape;

namespace patchspin::bullet::internal {

// Triangles closer to the reference triangle's plane than this angle [rad]
// are coplanar with it. A plane sampled into a float heightfield or a mesh
// exporter's float vertices tilts its triangles by ~1e-6 rad; a crease of
// 1e-3 rad changes the height under a 10 cm face by 0.1 mm at most, below
// the 1 mm collision margins of the scenes (ConcaveSupport.CreaseIsCounted).
constexpr double kCoplanarAngle = 1e-3;
// The coplanar triangles cover the face when their clipped areas sum to
// its area within this fraction (float vertices at 100 m from the origin
// make a 5 cm coin's sum ~3e-4 short); more than this over: overlapping
// triangles, a bad mesh.
constexpr double kCoverFraction = 1e-3;

// Shapes whose triangles are looked up under a face: btBvhTriangleMeshShape
// (and its multimaterial variant), btScaledBvhTriangleMeshShape,
// btTriangleMeshShape, btHeightfieldTerrainShape.
bool isTriangleSupport(const btCollisionShape& shape);

enum class SupportPlane {
  Found,      // one plane of coplanar triangles covers the whole face
  Crease,     // the face hangs over a crease, an edge of the mesh, or a
              // triangle that rises above the plane under it
  BadMesh,    // a non-finite vertex or overlapping coplanar triangles under the face
  NoTriangle  // no triangle faces the face within `slack`
};

// The plane of `support` (a triangle shape at world transform `tr`) under
// face `a` of the moving body (world coordinates): the plane of the facing
// triangle that covers most of the face, and every triangle under the face
// coplanar with it (kCoplanarAngle) or below it. Triangles are looked up
// within `slack` [m] of the face's bounding box; a disk is tested as its
// circumscribed 16-gon (its area 1.3 % over, so its whole disk is covered).
// On Found, `plane` is a Face::Kind::Plane with the outward normal (into
// the body, whatever the triangles' winding) and a point of the plane
// offset by the shape's margin.
SupportPlane findSupportPlane(const btCollisionShape& support, const btTransform& tr, const Face& a,
                              double slack, Face& plane);

// The unit normal of the triangle of `support` through `point` (world; a
// contact point on the support), oriented towards `towards` (the body's
// centre): of the triangles within `tol` [m] of the point, the one whose
// plane passes nearest it. Bullet's contact normal on a mesh may be a
// triangle edge's (sideways, or reversed); this is the surface's. False if
// no triangle is that near or a vertex is not finite.
bool triangleNormalAt(const btCollisionShape& support, const btTransform& tr,
                      const btVector3& point, const btVector3& towards, double tol,
                      btVector3* normal);

}  // namespace patchspin::bullet::internal
