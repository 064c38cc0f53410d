// Internal to the renderer: fixed-function OpenGL drawing of the scene's
// bodies, meshes and arrows, and the camera's matrices (renderer.cpp).
// Every function draws in the current GL context and matrix.
#pragma once

#include <patchspin/render/scene.hpp>

#include <utility>
#include <vector>

#include "hull.hpp"

namespace patchspin::render::drawing {

using Mat4 = Eigen::Matrix4d;

constexpr double kPi = 3.14159265358979323846;

Rgb scaled(Rgb c, double s);
// glColor4d of c clamped to [0, 1], with alpha
void colour(Rgb c, double alpha = 1.0);
void vertex(const Vec3& p);
void normal(const Vec3& n);

// view matrix: world -> eye, like gluLookAt
Mat4 lookAt(const Camera& cam);
// projection matrix, like gluPerspective
Mat4 perspective(double fovYDeg, double aspect, double zNear, double zFar);
// projection onto the plane z = h along the directional light `light`
Mat4 shadowMatrix(const Vec3& light, double h);
// largest 1-2-5 step not above x
double niceStep(double x);

// Geometry passes draw either shaded (colours, decals, outlines) or as a flat
// silhouette (shadow pass: position only).
enum class Pass { Shaded, Silhouette };

// Hull faces of recently drawn point sets: a hull is built once, not in
// every pass of every frame.
class HullCache {
 public:
  const std::vector<internal::HullFace>& faces(const std::vector<Vec3>& points) {
    for (const auto& [key, value] : entries_) {
      if (key == points) return value;
    }
    constexpr std::size_t kMaxEntries = 64;
    if (entries_.size() >= kMaxEntries) entries_.clear();
    entries_.emplace_back(points, internal::convexHullFaces(points));
    return entries_.back().second;
  }

 private:
  std::vector<std::pair<std::vector<Vec3>, std::vector<internal::HullFace>>> entries_;
};

// A static mesh: flat-shaded triangles, each normal turned towards the eye
// (both sides lit), then the edges in a darker shade.
void drawMesh(const SceneMesh& mesh, const Vec3& eye);
// A body at its pose: cylinder, box (with its spin marker) or convex hull.
void drawBody(const SceneBody& body, Pass pass, HullCache& hulls);
// Shaft and cone along +z of length len, lit.
void drawArrowGeometry(double len, double shaftRadius, double headLength, double headRadius);
// a unit vector perpendicular to v
Vec3 anyPerpendicular(const Vec3& v);

}  // namespace patchspin::render::drawing
