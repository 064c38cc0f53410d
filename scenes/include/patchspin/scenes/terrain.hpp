// Grounds other than the plane: a static triangle mesh or heightfield whose
// surface is the plane z = x tan(slope) (z = 0 by default) over a square
// grid, so a run on it has the plane as its reference; and meshes with the
// defects real level geometry has (ConcaveSupport tests, terrain demo).
#pragma once

#include <patchspin/scenes/scene.hpp>

#include <string>

namespace patchspin::scenes {

enum class Ground { Plane, TriangleMesh, Heightfield };
const char* toString(Ground g);
// Throws Error for an unknown name ("plane", "mesh", "heightfield").
Ground groundFromString(const std::string& name);

// What is wrong with a triangle mesh ground (TriangleMesh only).
enum class MeshDefect {
  None,
  AlternateWinding,  // every other triangle wound clockwise (normal down)
  Degenerate,        // a zero-area triangle along every grid cell's diagonal
  Duplicate,         // every triangle listed twice
  NaNVertex,         // one vertex NaN, at the grid's corner (x, y) = (-h, -h)
  NaNVertexAtOrigin  // one vertex NaN, the grid's vertex nearest the origin
};

struct GroundSpec {
  Ground kind = Ground::Plane;
  double halfSize = 0.25;  // the grid covers |x|, |y| <= halfSize [m]
  double spacing = 0.01;   // grid cell [m]: two triangles per cell
  double slope = 0.0;      // the surface rises along x at this angle [rad]
  // with a crease: the surface is level (z = 0) for x <= creaseX and
  // z = (x - creaseX) tan(slope) beyond (a ramp for a positive slope, a
  // drop for a negative one); slope non-zero, made by the heights
  bool crease = false;
  double creaseX = 0.0;  // [m]
  // the slope made by the ground body's transform (a rotation about y)
  // instead of by the heights: a level grid, tilted
  bool slopeInTransform = false;
  MeshDefect defect = MeshDefect::None;
  // TriangleMesh only: != 1: the mesh is built `meshScale` times smaller and
  // drawn at full size by a btScaledBvhTriangleMeshShape (the same surface)
  double meshScale = 1.0;
};

// The ground of `spec` as a static body of the given friction (Bullet
// multiplies the two bodies' frictions: 1 leaves the body's own). Throws
// Error for a non-positive size or spacing, more than 4e6 grid cells, or a
// slope outside (-pi/2, pi/2).
btRigidBody* addGround(Scene& scene, const GroundSpec& spec, double friction);

// A block (spec: side a, half height, mass, mu, overlap) at rest flat on the
// ground's surface z = x tan(slope) at x = y = 0, a face's edges along the
// slope; gravity -g z. The block slides down (towards -x) once
// tan(slope) > mu, with a = g (sin(slope) - mu cos(slope)).
btRigidBody* addBlockOnSlope(Scene& scene, const GroundSpec& ground, double a, double halfH,
                             double mass, double mu, double overlap);

}  // namespace patchspin::scenes
