// Loads of a linear pressure on a polygon in long double, summed about the
// polygon's vertex mean: an oracle for Eq. (94) far from O, independent of
// the core's sums (no product of coordinates beyond the patch's size).
#pragma once

#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>

#include <cstddef>
#include <vector>

namespace patchspin::testing {

struct LongLoads {
  long double Pz, Tx, Ty;
};

// The polygon's area moments about its vertex mean g, in long double by the
// triangle formulas, and the loads (Pz, Tx, Ty) about O of a linear pressure
// p about O: the moments of p about g, moved to O.
inline LongLoads loadsAboutVertexMean(const std::vector<Vec2>& v, const LinearPressure& p) {
  long double gx = 0.0L, gy = 0.0L;
  for (const Vec2& a : v) gx += a.x(), gy += a.y();
  gx /= static_cast<long double>(v.size());
  gy /= static_cast<long double>(v.size());
  long double A = 0.0L, sx = 0.0L, sy = 0.0L, ixx = 0.0L, ixy = 0.0L, iyy = 0.0L;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % v.size()];
    const long double ax = a.x() - gx, ay = a.y() - gy, bx = b.x() - gx, by = b.y() - gy;
    const long double c = ax * by - ay * bx;
    A += c / 2.0L, sx += c / 6.0L * (ax + bx), sy += c / 6.0L * (ay + by);
    ixx += c / 12.0L * (ax * ax + ax * bx + bx * bx);
    iyy += c / 12.0L * (ay * ay + ay * by + by * by);
    ixy += c / 24.0L * (2.0L * ax * ay + ax * by + bx * ay + 2.0L * bx * by);
  }
  const long double p0 = static_cast<long double>(p.p0) + static_cast<long double>(p.cx) * gx +
                         static_cast<long double>(p.cy) * gy;
  const long double Pz = p0 * A + p.cx * sx + p.cy * sy;
  const long double mx = p0 * sx + p.cx * ixx + p.cy * ixy;  // ∫ x' p about g
  const long double my = p0 * sy + p.cx * ixy + p.cy * iyy;
  // Eq. (94): Ty = ∫ x p, Tx = -∫ y p (about O)
  return {Pz, -(my + gy * Pz), mx + gx * Pz};
}

}  // namespace patchspin::testing
