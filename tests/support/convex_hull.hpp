// Convex hull of points in the plane, shared by the core tests and the fuzz
// targets (header only: the fuzz build has no test support library).
#pragma once

#include <patchspin/types.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace patchspin::testing {

// Counter-clockwise hull (collinear points dropped) of finite points,
// Andrew's monotone chain; fewer than 3 points when they are collinear.
inline std::vector<Vec2> convexHull(std::vector<Vec2> p) {
  if (p.size() < 2) return p;
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

}  // namespace patchspin::testing
