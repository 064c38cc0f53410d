#include "hull.hpp"

#include <algorithm>
#include <cmath>

namespace patchspin::render::internal {

std::vector<HullFace> convexHullFaces(const std::vector<Vec3>& points) {
  const std::size_t n = points.size();
  if (n < 4) throw RenderError("convex hull needs at least 4 points, got " + std::to_string(n));
  // length scale of the set; a point is "on" a plane within kPlaneTol * scale
  double scale = 0.0;
  for (const Vec3& p : points) scale = std::max(scale, (p - points[0]).norm());
  // relative tolerance: far above double rounding of the dot products, far below
  // any feature a viewer could see
  constexpr double kPlaneTol = 1e-9;
  const double tol = kPlaneTol * std::max(scale, 1e-300);

  std::vector<HullFace> faces;
  std::vector<std::pair<Vec3, double>> planes;  // (normal, offset) found so far
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Vec3 normal = (points[j] - points[i]).cross(points[k] - points[i]);
        const double len = normal.norm();
        if (len <= tol * scale) continue;  // (nearly) collinear triple
        normal /= len;
        double offset = normal.dot(points[i]);
        // all points on one side? orient the normal outwards
        int above = 0, below = 0;
        for (const Vec3& p : points) {
          const double d = normal.dot(p) - offset;
          if (d > tol) ++above;
          if (d < -tol) ++below;
        }
        if (above > 0 && below > 0) continue;
        if (above > 0) {
          normal = -normal;
          offset = -offset;
        }
        // skip planes already found
        bool known = false;
        for (const auto& [m, c] : planes) {
          if ((m - normal).norm() < 1e-9 && std::abs(c - offset) < tol) known = true;
        }
        if (known) continue;
        planes.emplace_back(normal, offset);
        // the face: 2-D convex hull (monotone chain) of the points on the plane
        std::vector<Vec3> onPlane;
        for (const Vec3& p : points) {
          if (std::abs(normal.dot(p) - offset) <= tol) onPlane.push_back(p);
        }
        // in-plane axis from two distinct points (the triple i, j, k has them)
        const Vec3 ex = (points[j] - points[i]).normalized();
        const Vec3 ey = normal.cross(ex);
        auto less = [&](const Vec3& a, const Vec3& b) {
          const double ax = a.dot(ex), bx = b.dot(ex);
          return ax < bx - tol || (std::abs(ax - bx) <= tol && a.dot(ey) < b.dot(ey));
        };
        std::sort(onPlane.begin(), onPlane.end(), less);
        // z-component of (b - a) x (c - a) in the face's (ex, ey) frame
        auto turn = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
          return normal.dot((b - a).cross(c - a));
        };
        HullFace face;
        face.normal = normal;
        std::vector<Vec3>& h = face.vertices;
        for (int pass = 0; pass < 2; ++pass) {
          const std::size_t base = h.size();
          for (const Vec3& p : onPlane) {
            while (h.size() >= base + 2 && turn(h[h.size() - 2], h.back(), p) <= tol * scale) {
              h.pop_back();
            }
            h.push_back(p);
          }
          h.pop_back();  // the last point starts the other chain
          std::reverse(onPlane.begin(), onPlane.end());
        }
        if (face.vertices.size() >= 3) faces.push_back(std::move(face));
      }
    }
  }
  if (faces.size() < 4) throw RenderError("convex hull points are flat or degenerate");
  return faces;
}

}  // namespace patchspin::render::internal
