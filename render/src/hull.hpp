// Faces of the convex hull of a small point set, for drawing.
#pragma once

#include <patchspin/render/scene.hpp>
#include <vector>

namespace patchspin::render::internal {

struct HullFace {
  Vec3 normal;                 // outward unit normal
  std::vector<Vec3> vertices;  // counter-clockwise seen from outside
};

// Brute force: every plane through three points that has all points on one
// side is a face plane; the points on it, sorted by angle, are the face.
// O(n^4), meant for n <= ~64. Throws RenderError for fewer than 4 points or a
// flat point set.
std::vector<HullFace> convexHullFaces(const std::vector<Vec3>& points);

}  // namespace patchspin::render::internal
