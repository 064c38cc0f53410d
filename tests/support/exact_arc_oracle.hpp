// Brute-force oracle of the exact model, Eq. (16), on convex regions bounded
// by segments and circular arcs (disk segments, lenses), with the linear
// pressure basis (1, x, y): the polygon oracle's nested adaptive
// Gauss-Kronrod in Cartesian coordinates (x outer, y inner between the lower
// and upper boundary), the chord at x found by intersecting the vertical line
// with every piece. Independent of the boundary moments in the core. Used by
// exact_arc_region_test.
#pragma once

#include "exact_polygon_oracle.hpp"

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace patchspin::testing::exact_arc {

using internal::BoundaryPiece;
using Region = std::vector<BoundaryPiece>;
using exact_polygon::Vec9;

inline bool angleWithin(double t, double t0, double t1) {
  const double k = std::floor((t - t0) / (2.0 * M_PI));
  const double tt = t - k * 2.0 * M_PI;  // in [t0, t0 + 2 pi)
  return tt <= t1;
}

// y-range of the convex region on the vertical line at x.
inline void chordAt(const Region& region, double x, double& lo, double& hi) {
  lo = INFINITY;
  hi = -INFINITY;
  for (const BoundaryPiece& p : region) {
    if (p.kind == BoundaryPiece::Kind::Segment) {
      if (p.a.x() == p.b.x()) continue;
      const double t = (x - p.a.x()) / (p.b.x() - p.a.x());
      if (t < 0.0 || t > 1.0) continue;
      const double y = p.a.y() + t * (p.b.y() - p.a.y());
      lo = std::min(lo, y), hi = std::max(hi, y);
      continue;
    }
    const double dx = x - p.centre.x();
    if (std::abs(dx) > p.radius) continue;
    const double h = std::sqrt(std::max(0.0, p.radius * p.radius - dx * dx));
    for (double sy : {-1.0, 1.0}) {
      if (angleWithin(std::atan2(sy * h, dx), p.angle0, p.angle1)) {
        const double y = p.centre.y() + sy * h;
        lo = std::min(lo, y), hi = std::max(hi, y);
      }
    }
  }
}

// Boundary points (n per piece), for extents.
inline std::vector<Vec2> boundarySamples(const Region& region, int n = 400) {
  std::vector<Vec2> pts;
  for (const BoundaryPiece& p : region) {
    for (int i = 0; i <= n; ++i) {
      const double s = static_cast<double>(i) / n;
      if (p.kind == BoundaryPiece::Kind::Segment) {
        pts.push_back(p.a + s * (p.b - p.a));
      } else {
        const double t = p.angle0 + s * (p.angle1 - p.angle0);
        pts.push_back(p.centre + p.radius * Vec2(std::cos(t), std::sin(t)));
      }
    }
  }
  return pts;
}

// Area by the boundary integral 1/2 ∮ x dy - y dx (arc: a (o . e) + a^2 per dt).
inline double area(const Region& region) {
  double a2 = 0.0;
  for (const BoundaryPiece& p : region) {
    if (p.kind == BoundaryPiece::Kind::Segment) {
      a2 += p.a.x() * p.b.y() - p.a.y() * p.b.x();
    } else {
      const Vec2& o = p.centre;
      const double r = p.radius;
      auto prim = [&](double t) {
        return r * (o.x() * std::sin(t) - o.y() * std::cos(t)) + r * r * t;
      };
      a2 += prim(p.angle1) - prim(p.angle0);
    }
  }
  return 0.5 * a2;
}

// Column scales as the polygon tests': area * max|phi_k| * (1 + max|P|/rho).
inline Vec3 columnScales(const Region& region, double rho) {
  double rmax = 0.0, mx = 0.0, my = 0.0;
  for (const Vec2& p : boundarySamples(region)) {
    rmax = std::max(rmax, p.norm());
    mx = std::max(mx, std::abs(p.x()));
    my = std::max(my, std::abs(p.y()));
  }
  const double s = area(region) * (1.0 + rmax / rho);
  return Vec3(s, s * mx, s * my);
}

// F by brute force (exact_polygon::oracleFBetweenChords), x split at the
// pieces' end points and the arcs' extreme x.
inline Mat3 oracleF(const Region& region, double rho, const Vec3& w) {
  std::vector<double> xbreaks;
  for (const BoundaryPiece& p : region) {
    xbreaks.push_back(p.start().x());
    if (p.kind == BoundaryPiece::Kind::Arc) {
      for (double t : {0.0, M_PI})
        if (angleWithin(t, p.angle0, p.angle1))
          xbreaks.push_back(p.centre.x() + p.radius * std::cos(t));
    }
  }
  // the extremes of x are among the pieces' ends and the arcs' extreme points
  const double xmin = *std::min_element(xbreaks.begin(), xbreaks.end());
  const double xmax = *std::max_element(xbreaks.begin(), xbreaks.end());
  return exact_polygon::oracleFBetweenChords(
      [&](double x, double& lo, double& hi) { chordAt(region, x, lo, hi); }, xmin, xmax,
      std::move(xbreaks), columnScales(region, rho), rho, w);
}

// ---- shapes ----

inline Vec2 onCircle(const Vec2& o, double r, double t) {
  return o + r * Vec2(std::cos(t), std::sin(t));
}

// Disk (o, R) cut by the line (P - o).n = h, n = (cos beta, sin beta), the
// part (P - o).n <= h kept: arc from beta + alpha to beta + 2 pi - alpha,
// alpha = acos(h / R), then the chord back.
inline Region diskSegment(const Vec2& o, double R, double beta, double h) {
  const double alpha = std::acos(h / R);
  const double t0 = beta + alpha, t1 = beta + 2.0 * M_PI - alpha;
  return {BoundaryPiece::arc(o, R, t0, t1),
          BoundaryPiece::segment(onCircle(o, R, t1), onCircle(o, R, t0))};
}

// Disk (o1, R1) ∩ disk (o2, R2) (they must intersect): the arc of each
// circle inside the other, by the law of cosines.
inline Region lens(const Vec2& o1, double R1, const Vec2& o2, double R2) {
  const Vec2 d = o2 - o1;
  const double D = d.norm(), g1 = std::atan2(d.y(), d.x()), g2 = g1 + M_PI;
  const double a1 = std::acos((D * D + R1 * R1 - R2 * R2) / (2.0 * D * R1));
  const double a2 = std::acos((D * D + R2 * R2 - R1 * R1) / (2.0 * D * R2));
  return {BoundaryPiece::arc(o1, R1, g1 - a1, g1 + a1),
          BoundaryPiece::arc(o2, R2, g2 - a2, g2 + a2)};
}

// The region's boundary as a polygon: n points per arc (end points included
// once), segments as they are.
inline std::vector<Vec2> polygonOf(const Region& region, int perArc) {
  std::vector<Vec2> poly;
  for (const BoundaryPiece& p : region) {
    if (p.kind == BoundaryPiece::Kind::Segment) {
      poly.push_back(p.a);
      continue;
    }
    for (int i = 0; i < perArc; ++i)
      poly.push_back(onCircle(p.centre, p.radius,
                              p.angle0 + (p.angle1 - p.angle0) * i / static_cast<double>(perArc)));
  }
  return poly;
}

}  // namespace patchspin::testing::exact_arc
