// Mesh and heightfield grounds (terrain.hpp).
#include <patchspin/scenes/terrain.hpp>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>

#include <cmath>
#include <limits>
#include <vector>

namespace patchspin::scenes {

const char* toString(Ground g) {
  switch (g) {
    case Ground::Plane:
      return "plane";
    case Ground::TriangleMesh:
      return "mesh";
    case Ground::Heightfield:
      return "heightfield";
  }
  return "?";
}

Ground groundFromString(const std::string& name) {
  for (Ground g : {Ground::Plane, Ground::TriangleMesh, Ground::Heightfield})
    if (name == toString(g)) return g;
  throw Error("unknown ground '" + name + "' (plane, mesh, heightfield)");
}

namespace {

// the ground body's transform: the slope's rotation about y when it is made
// by the transform, else the identity
btTransform groundTransform(const GroundSpec& s) {
  btTransform tr;
  tr.setIdentity();
  if (s.slopeInTransform) tr.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(-s.slope)));
  return tr;
}

double heightAt(const GroundSpec& s, double x) {
  if (s.slopeInTransform) return 0.0;
  if (s.crease) return x <= s.creaseX ? 0.0 : (x - s.creaseX) * std::tan(s.slope);
  return x * std::tan(s.slope);
}

btRigidBody* addMesh(Scene& scene, const GroundSpec& s, int cells, double friction) {
  auto mesh =
      std::make_unique<btTriangleMesh>(/*use32bitIndices=*/true, /*use4componentVertices=*/true);
  auto vertex = [&](int i, int j) {
    const double x = -s.halfSize + i * s.spacing, y = -s.halfSize + j * s.spacing;
    return bt(x / s.meshScale, y / s.meshScale, heightAt(s, x) / s.meshScale);
  };
  const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
  int triangle = 0;
  auto add = [&](btVector3 a, btVector3 b, btVector3 c) {
    if (s.defect == MeshDefect::AlternateWinding && triangle % 2 == 1) std::swap(b, c);
    ++triangle;
    mesh->addTriangle(a, b, c, /*removeDuplicateVertices=*/false);
    if (s.defect == MeshDefect::Duplicate) mesh->addTriangle(a, b, c, false);
  };
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      btVector3 p00 = vertex(i, j);
      const btVector3 p10 = vertex(i + 1, j), p01 = vertex(i, j + 1), p11 = vertex(i + 1, j + 1);
      if (s.defect == MeshDefect::NaNVertex && i == 0 && j == 0) p00.setX(nan);
      if (s.defect == MeshDefect::NaNVertexAtOrigin && i == cells / 2 && j == cells / 2)
        p00.setX(nan);
      add(p00, p10, p11);  // counter-clockwise seen from above
      add(p00, p11, p01);
      if (s.defect == MeshDefect::Degenerate) add(p00, p11, btScalar(0.5) * (p00 + p11));
    }
  }
  btTriangleMesh* kept = scene.keep(std::move(mesh));
  auto shape = std::make_unique<btBvhTriangleMeshShape>(kept, /*useQuantizedAabbCompression=*/true);
  if (s.meshScale == 1.0)
    return scene.addBody(std::move(shape), 0, btVector3(0, 0, 0), groundTransform(s), friction);
  auto* unscaled = static_cast<btBvhTriangleMeshShape*>(scene.addShape(std::move(shape)));
  auto scaled = std::make_unique<btScaledBvhTriangleMeshShape>(
      unscaled, bt(s.meshScale, s.meshScale, s.meshScale));
  return scene.addBody(std::move(scaled), 0, btVector3(0, 0, 0), groundTransform(s), friction);
}

btRigidBody* addHeightfield(Scene& scene, const GroundSpec& s, int cells, double friction) {
  const int n = cells + 1;
  auto heights = std::make_unique<std::vector<btScalar>>(std::size_t(n) * std::size_t(n));
  double top = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double z = heightAt(s, -s.halfSize + i * s.spacing);
      (*heights)[std::size_t(j) * std::size_t(n) + std::size_t(i)] = btScalar(z);
      top = std::max(top, std::abs(z));
    }
  // Bullet centres the shape on its height range: [-top, top] keeps the
  // local origin at z = 0
  const btScalar bound = btScalar(top + 1.0);
  std::vector<btScalar>* kept = scene.keep(std::move(heights));
  auto shape = std::make_unique<btHeightfieldTerrainShape>(n, n, kept->data(), -bound, bound,
                                                           /*upAxis=*/2, /*flipQuadEdges=*/false);
  shape->setLocalScaling(bt(s.spacing, s.spacing, 1.0));
  return scene.addBody(std::move(shape), 0, btVector3(0, 0, 0), groundTransform(s), friction);
}

}  // namespace

btRigidBody* addGround(Scene& scene, const GroundSpec& s, double friction) {
  if (!(s.halfSize > 0) || !(s.spacing > 0) || !std::isfinite(s.halfSize / s.spacing))
    throw Error("addGround: halfSize and spacing must be positive");
  if (!(std::abs(s.slope) < M_PI / 2)) throw Error("addGround: slope outside (-pi/2, pi/2)");
  if (!(s.meshScale > 0) || !std::isfinite(s.meshScale) ||
      (s.meshScale != 1.0 && s.kind != Ground::TriangleMesh))
    throw Error("addGround: meshScale must be positive, and 1 but for a triangle mesh");
  if (s.crease && (s.slope == 0.0 || s.slopeInTransform))
    throw Error("addGround: a crease needs a slope made by the heights");
  const double cellsD = std::round(2.0 * s.halfSize / s.spacing);
  if (!(cellsD >= 1 && cellsD <= 2000)) throw Error("addGround: 1 to 2000 cells per side");
  const int cells = int(cellsD);
  switch (s.kind) {
    case Ground::Plane: {
      if (s.crease || s.defect != MeshDefect::None)
        throw Error("addGround: a plane has no crease and no defects");
      if (s.slope == 0.0) return scene.addGroundPlane(friction);
      const btVector3 n(btScalar(-std::sin(s.slope)), 0, btScalar(std::cos(s.slope)));
      btTransform tr;
      tr.setIdentity();
      return scene.addBody(std::make_unique<btStaticPlaneShape>(n, 0), 0, btVector3(0, 0, 0), tr,
                           friction);
    }
    case Ground::TriangleMesh:
      return addMesh(scene, s, cells, friction);
    case Ground::Heightfield:
      if (s.defect != MeshDefect::None) throw Error("addGround: a heightfield has no mesh defects");
      return addHeightfield(scene, s, cells, friction);
  }
  throw Error("addGround: unknown ground kind");
}

btRigidBody* addBlockOnSlope(Scene& scene, const GroundSpec& ground, double a, double halfH,
                             double mass, double mu, double overlap) {
  const btQuaternion q(btVector3(0, 1, 0), btScalar(-ground.slope));
  const btVector3 normal = quatRotate(q, btVector3(0, 0, 1));
  btRigidBody* b =
      scene.addBox(bt(a / 2, a / 2, halfH), mass, normal * btScalar(halfH - overlap), mu);
  btTransform tr = b->getWorldTransform();
  tr.setRotation(q);
  b->setWorldTransform(tr);
  b->setInterpolationWorldTransform(tr);
  if (b->getMotionState()) b->getMotionState()->setWorldTransform(tr);
  return b;
}

}  // namespace patchspin::scenes
