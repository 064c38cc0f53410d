// The body shape x support shape matrix of docs/bullet.md (SupportMatrix
// tests): each body shape set down flat on each support's top face, the
// plane z = 0, so every documented cell is one scene built here.
#pragma once

#include <patchspin/scenes/scene.hpp>

#include <string>
#include <vector>

namespace patchspin::scenes {

enum class BodyShape { Box, Cylinder, ConvexHull, Compound, Sphere, Capsule };
enum class SupportShape {
  Plane,         // btStaticPlaneShape
  Box,           // static btBoxShape, 1 x 1 x 0.1 m
  CylinderCap,   // static btCylinderShapeZ, R 0.5 m, H 0.1 m
  ConvexHull,    // static btConvexHullShape of the 1 x 1 x 0.1 m box
  DynamicBox,    // a 10 kg btBoxShape 1 x 1 x 0.1 m resting on a plane
  TriangleMesh,  // static btBvhTriangleMeshShape, 1 cm grid
  ScaledMesh,    // btScaledBvhTriangleMeshShape of a 4 mm grid, x 2.5
  Heightfield,   // static btHeightfieldTerrainShape, 1 cm grid
  Compound       // static btCompoundShape of the 1 x 1 x 0.1 m box and a second one 2 m off
};

// Every value, in the docs table's order.
const std::vector<BodyShape>& allBodyShapes();
const std::vector<SupportShape>& allSupportShapes();
// The names in the docs table's header and first column.
std::string toString(BodyShape b);
std::string toString(SupportShape s);

// The support, its top face the plane z = 0, friction 1.
btRigidBody* addSupport(Scene& scene, SupportShape s);
// A body of 1 kg, friction 0.3, resting on the plane z = 0 (1e-5 m into it),
// a flat face down where it has one: box 10 x 10 x 5 cm, cylinder R 5 cm H
// 1 cm (axis z), convex hull of a hexagonal prism (circumradius 5 cm, 2 cm
// high), compound of a 10 x 10 x 3 cm box with a cylinder post (R 2 cm, 6 cm
// high) on its top, sphere R 5 cm, capsule R 2 cm lying along x (10 cm
// between centres).
btRigidBody* addBodyOnTop(Scene& scene, BodyShape b);

}  // namespace patchspin::scenes
