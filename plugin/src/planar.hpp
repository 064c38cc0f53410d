// Plane helpers shared by the core's geometry files (geometry.cpp,
// arc_regions.cpp, moment_tables.cpp, patch_shape_arc_region.cpp).
#pragma once

#include <patchspin/types.hpp>

namespace patchspin::internal {

constexpr double kPi = 3.14159265358979323846;

// z component of a x b: twice the signed area of the triangle (0, a, b),
// positive where b lies counter-clockwise of a.
inline double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace patchspin::internal
