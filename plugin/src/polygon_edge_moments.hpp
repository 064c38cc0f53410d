// The polynomial area moments (1, x, y times 1, x, y) of a polygon, summed
// edge by edge over the signed triangles (0, a, b) about the coordinates'
// origin (the polygon's rows in moment_tables.cpp, the chord polygon of an arc
// region in arc_regions.cpp). With c = cross(a, b):
//   A   += c / 2
//   Sx  += c / 6 (ax + bx)                 Sy += c / 6 (ay + by)
//   Ixx += c / 12 (ax^2 + ax bx + bx^2)    Iyy += c / 12 (ay^2 + ay by + by^2)
//   Ixy += c / 24 (2 ax ay + ax by + bx ay + 2 bx by)
// Both callers' sums go through here operation for operation (the Bullet
// layer's Determinism hashes and tests/core/geometry_test.cpp,
// arc_regions_test.cpp guard them).
#pragma once

#include "planar.hpp"

#include <patchspin/types.hpp>

namespace patchspin::internal {

struct PolygonMomentSums {
  double area = 0.0, sx = 0.0, sy = 0.0, ixx = 0.0, ixy = 0.0, iyy = 0.0;

  // Adds the signed triangle (0, a, b): a and b consecutive vertices.
  void addEdge(const Vec2& a, const Vec2& b) {
    const double c = cross(a, b);
    area += c / 2.0;
    sx += c / 6.0 * (a.x() + b.x());
    sy += c / 6.0 * (a.y() + b.y());
    ixx += c / 12.0 * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x());
    iyy += c / 12.0 * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y());
    ixy += c / 24.0 * (2.0 * a.x() * a.y() + a.x() * b.y() + b.x() * a.y() + 2.0 * b.x() * b.y());
  }
};

}  // namespace patchspin::internal
