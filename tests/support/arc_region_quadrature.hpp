// Brute-force area integrals over convex regions bounded by segments and
// arcs (nested adaptive Gauss-Kronrod between the region's chords at x, the
// oracle of exact_arc_oracle.hpp), independent of the core's Green's-theorem
// moments and of its exact law; and sampled geometry (points in a region by
// its chords). Used by arc_regions_test and the arc-region tests of the
// pressure and friction-law code.
#pragma once

#include "exact_arc_oracle.hpp"

#include <patchspin/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace patchspin::testing::arc_region {

using exact_arc::Region;
using exact_polygon::Vec9;

// x-range of a region and the x of its pieces' ends and arcs' extremes.
inline std::vector<double> xBreaks(const Region& region) {
  std::vector<double> xs;
  for (const BoundaryPiece& p : region) {
    xs.push_back(p.start().x());
    if (p.kind == BoundaryPiece::Kind::Arc)
      for (double t : {0.0, M_PI})
        if (exact_arc::angleWithin(t, p.angle0, p.angle1))
          xs.push_back(p.centre.x() + p.radius * std::cos(t));
  }
  return xs;
}

// ∫_region f(x, y) dA, f a 9-vector; tol per entry (absolute), x and y
// split at 0 (the kink of r at O).
template <class F>
Vec9 integrate(const Region& region, const F& f, const Vec9& tol) {
  std::vector<double> xs = xBreaks(region);
  const double xmin = *std::min_element(xs.begin(), xs.end());
  const double xmax = *std::max_element(xs.begin(), xs.end());
  xs.push_back(0.0);
  const Vec9 innerTol = 1e-2 * tol / (xmax - xmin);
  auto inner = [&](double x) -> Vec9 {
    double lo, hi;
    exact_arc::chordAt(region, x, lo, hi);
    if (!(hi > lo)) return Vec9::Zero();
    auto fy = [&](double y) -> Vec9 { return f(x, y); };
    return exact_polygon::integrateSplit(fy, lo, hi, {0.0}, innerTol);
  };
  return exact_polygon::integrateSplit(inner, xmin, xmax, xs, tol);
}

// Moment table (6 x 3, MomentTable's rows and columns) by brute force, each
// entry to tolFactor * area * max|f| max|phi| over the region.
inline Eigen::Matrix<double, 6, 3> momentTable(const Region& region, double tolFactor = 1e-13) {
  double rmax = 0.0;
  for (const Vec2& p : exact_arc::boundarySamples(region)) rmax = std::max(rmax, p.norm());
  const double A = exact_arc::area(region);
  const double s = std::max(1.0, rmax);
  Vec9 tol = Vec9::Constant(tolFactor * A * s * s * s);
  // (1, x, y, r) x (1, x, y) in two passes of nine
  auto polyAndR = [](double x, double y) {
    const double r = std::hypot(x, y);
    Vec9 v;
    v << 1.0, x, y, x * x, x * y, y * y, r, r * x, r * y;
    return v;
  };
  auto overR = [](double x, double y) {
    const double r = std::hypot(x, y);
    Vec9 v;
    if (r == 0.0) return Vec9(Vec9::Zero());
    v << x / r, x * x / r, x * y / r, y / r, y * x / r, y * y / r, 0.0, 0.0, 0.0;
    return v;
  };
  const Vec9 a = integrate(region, polyAndR, tol);
  const Vec9 b = integrate(region, overR, tol);
  Eigen::Matrix<double, 6, 3> m;
  m << a[0], a[1], a[2],  //
      a[1], a[3], a[4],   //
      a[2], a[4], a[5],   //
      a[6], a[7], a[8],   //
      b[0], b[1], b[2],   //
      b[3], b[4], b[5];
  return m;
}

// Inside test by the region's chord at x (the oracle's, independent of
// PatchShape::contains).
inline bool insideByChords(const Region& region, const Vec2& p) {
  double lo, hi;
  exact_arc::chordAt(region, p.x(), lo, hi);
  return hi > lo && p.y() >= lo && p.y() <= hi;
}

}  // namespace patchspin::testing::arc_region
