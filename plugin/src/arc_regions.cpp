// Convex regions bounded by segments and circular arcs (patchspin/geometry.hpp):
// the boundary pieces' end points, the exact boundaries of disk ∩ polygon and
// disk ∩ disk, their area moments by Green's theorem and their extents
// (arc_region_numerics.hpp). Guarded by tests/core/arc_regions_test.cpp.
//
// Area moments: the region is its chord polygon (the pieces' start points,
// signed triangles) plus, per arc, the circular segment between the arc and
// its chord (Green's theorem on the arc minus the chord). In the arc's frame
// (u along its mid direction, half-angle a, s = sin a, c = cos a), the
// segment {u >= R c} of the disk of radius R has
//   A = R^2 (a - s c),  ∫u = 2/3 R^3 s^3,  ∫v = 0,  ∫uv = 0,
//   ∫u^2 = R^4 ((a + s c) / 4 - c^3 s / 2)   (sector minus triangle),
//   ∫v^2 = R^4 ((4a - sin 4a) / 16 - 2/3 c s^3).
// These cancel for a flat arc (to ~eps / a^2 of A, and shifted from the
// centre to the chord, eps / a^6 of the chord-frame ∫u'^2). So for a <
// kSeriesHalfAngle (= 1) the segment's moments about its chord's midpoint
// (u' = u - R c) are taken from their series in a (circularSegmentMoments:
// exact within 1e-14 relative for all a, CircularSegmentMomentsMatchReference),
// in the frame of the chord the chord polygon uses (arcChord: the pieces'
// start and end points, radius |end - start| / (2 sin a)).
#include "arc_region_numerics.hpp"
#include "planar.hpp"
#include "polygon_edge_moments.hpp"

#include <patchspin/types.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace patchspin {

Vec2 BoundaryPiece::start() const {
  return kind == Kind::Segment ? a : centre + radius * Vec2(std::cos(angle0), std::sin(angle0));
}
Vec2 BoundaryPiece::end() const {
  return kind == Kind::Segment ? b : centre + radius * Vec2(std::cos(angle1), std::sin(angle1));
}

namespace {

using internal::cross;
using internal::kPi;
constexpr double kTwoPi = 2.0 * kPi;

double angleOf(const Vec2& v) {
  return std::atan2(v.y(), v.x());
}

// ccw span from angle t0 to t1 in (0, 2 pi]
double ccwSpan(double t0, double t1) {
  double d = std::fmod(t1 - t0, kTwoPi);
  if (d <= 0.0) d += kTwoPi;
  return d;
}

using Pieces = std::vector<BoundaryPiece>;

}  // namespace

std::vector<BoundaryPiece> diskPolygonIntersection(const Vec2& centre, double radius,
                                                   const std::vector<Vec2>& poly) {
  internal::requireFinite(centre, "disk centre");
  internal::requirePositive(radius, "disk radius");
  const std::size_t n = poly.size();
  if (n < 3) throw Error("diskPolygonIntersection: the polygon needs at least 3 vertices");
  // the inside part [t0, t1] of each edge a + t (b - a), t in [0, 1]
  struct Part {
    Vec2 from, to;
    bool fromOnCircle, toOnCircle;
  };
  std::vector<Part> parts;
  const double kShort = 1e-12 * radius;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i] - centre, b = poly[(i + 1) % n] - centre;
    const Vec2 e = b - a;
    const double ee = e.squaredNorm();
    if (!(ee > 0.0)) continue;
    // |a + t e|^2 = R^2: t^2 ee + 2 t (a.e) + |a|^2 - R^2 = 0
    const double half = a.dot(e);
    // discriminant / ee^2 = (half^2 - ee (|a|^2 - R^2)) / ee^2, with
    // ee (|a|^2 - R^2) - half^2 = ee * dist^2 - ee R^2 (dist of the line)
    const double dist2 = cross(a, e) * cross(a, e) / ee;
    const double disc = (radius - std::sqrt(dist2)) * (radius + std::sqrt(dist2));
    if (!(disc > 0.0)) continue;  // the line misses (or touches) the circle
    const double root = std::sqrt(disc * ee);
    const double t1 = (-half - root) / ee, t2 = (-half + root) / ee;
    const double lo = std::max(0.0, t1), hi = std::min(1.0, t2);
    if (!(hi > lo) || (hi - lo) * std::sqrt(ee) <= kShort) continue;
    Part part;
    part.fromOnCircle = t1 > 0.0;
    part.toOnCircle = t2 < 1.0;
    part.from = centre + (part.fromOnCircle ? Vec2(a + t1 * e) : a);
    part.to = centre + (part.toOnCircle ? Vec2(a + t2 * e) : b);
    if (!part.fromOnCircle) part.from = poly[i];
    if (!part.toOnCircle) part.to = poly[(i + 1) % n];
    parts.push_back(part);
  }
  Pieces out;
  if (parts.empty()) {
    // the disk lies in the polygon (its centre at least R inside every
    // edge) or misses it
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 e = poly[(i + 1) % n] - poly[i];
      if (cross(e, centre - poly[i]) < radius * e.norm()) return out;
    }
    out.push_back(BoundaryPiece::arc(centre, radius, 0.0, kTwoPi));
    return out;
  }
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const Part& p = parts[k];
    const Part& q = parts[(k + 1) % parts.size()];
    out.push_back(BoundaryPiece::segment(p.from, p.to));
    if (p.toOnCircle || q.fromOnCircle) {
      // leaves the polygon's inside at p.to: along the circle to q.from
      const double t0 = angleOf(p.to - centre);
      const double span = ccwSpan(t0, angleOf(q.from - centre));
      if (span * radius > kShort && span < kTwoPi) {
        out.push_back(BoundaryPiece::arc(centre, radius, t0, t0 + span));
      }
    }
  }
  return out;
}

std::vector<BoundaryPiece> diskDiskIntersection(const Vec2& c1, double r1, const Vec2& c2,
                                                double r2) {
  internal::requireFinite(c1, "first disk centre");
  internal::requireFinite(c2, "second disk centre");
  internal::requirePositive(r1, "first disk radius");
  internal::requirePositive(r2, "second disk radius");
  Pieces out;
  const Vec2 dv = c2 - c1;
  const double d = dv.norm();
  if (d >= r1 + r2) return out;
  if (d <= std::abs(r1 - r2)) {
    out.push_back(r1 <= r2 ? BoundaryPiece::arc(c1, r1, 0.0, kTwoPi)
                           : BoundaryPiece::arc(c2, r2, 0.0, kTwoPi));
    return out;
  }
  // a: distance of the common chord from c1 along c2 - c1; h its half-length
  const double a = (d * d + (r1 - r2) * (r1 + r2)) / (2.0 * d);
  const double h = std::sqrt(std::max(0.0, (r1 - a) * (r1 + a)));
  const double beta = angleOf(dv);
  const double a1 = std::atan2(h, a), a2 = std::atan2(h, d - a);
  out.push_back(BoundaryPiece::arc(c1, r1, beta - a1, beta + a1));
  out.push_back(BoundaryPiece::arc(c2, r2, beta + kPi - a2, beta + kPi + a2));
  return out;
}

AreaMoments areaMomentsOf(const std::vector<BoundaryPiece>& boundary) {
  const Vec2 g = internal::startPointMean(boundary);
  const AreaMoments m = internal::areaMomentsAbout(boundary, g);
  // parallel axes (as PatchShape's polygon rows about the vertex mean)
  AreaMoments out;
  const double gx = g.x(), gy = g.y(), A = m.area;
  out.area = A;
  out.xx = (A * gx * gx + 2.0 * gx * m.first.x()) + m.xx;
  out.yy = (A * gy * gy + 2.0 * gy * m.first.y()) + m.yy;
  out.xy = (A * gx * gy + (gx * m.first.y() + gy * m.first.x())) + m.xy;
  out.first = Vec2(A * gx + m.first.x(), A * gy + m.first.y());
  return out;
}

namespace internal {

SegmentMoments circularSegmentMoments(double a) {
  // Taylor coefficients (sympy, exact rationals rounded) of A / a^3, ∫u' / a^5,
  // ∫u'^2 / a^7 and ∫v^2 / a^5 in x = a^2: 14 terms leave < 1e-17 relative at
  // a = 1 (the largest, ∫v^2's, 1.2e-17 a^33)
  static constexpr std::array<double, 14> kArea = {
      0.6666666666666666,      -0.13333333333333333,    0.012698412698412698,
      -0.0007054673721340388,  2.565335898669232e-05,   -6.577784355562133e-07,
      1.2529113058213587e-08,  -1.8425166262078804e-10, 2.1549902060910882e-12,
      -2.0523716248486557e-14, 1.622428161935696e-16,   -1.0816187746237974e-18,
      6.163069940876338e-21,   -3.035995044766669e-23};
  static constexpr std::array<double, 14> kFirst = {
      0.13333333333333333,     -0.03492063492063492,   0.004497354497354497,
      -0.00036956870290203624, 2.133411855634078e-05,  -9.143927794721446e-07,
      3.0255958321629034e-08,  -7.962104817578651e-10, 1.7061655999029194e-11,
      -3.0346819589512514e-13, 4.55202294977351e-15,   -5.835926860447255e-17,
      6.468391840632451e-19,   -6.259734039348968e-21};
  static constexpr std::array<double, 14> kNormal2 = {
      0.0380952380952381,      -0.012698412698412698,   0.002077922077922078,
      -0.00022101355434688767, 1.7027064646112266e-05,  -1.004908567933778e-06,
      4.705852113041109e-08,   -1.7931981360627673e-09, 5.670629790189548e-11,
      -1.5122003926137848e-12, 3.4466309195867245e-14,  -6.7914019041372835e-16,
      1.1684137400830026e-17,  -1.7703240563522065e-19};
  static constexpr std::array<double, 14> kAlong2 = {
      0.13333333333333333,    -0.06349206349206349,   0.014814814814814815,
      -0.002180535513868847,  0.00022430244652466876, -1.7102239324461548e-05,
      1.0061983295721235e-06, -4.707576105205983e-08, 1.7933828495090037e-09,
      -5.670792033005742e-11, 1.5122122904203058e-12, -3.446638315270654e-14,
      6.791405850930842e-16,  -1.1684139228956074e-17};
  const double x = a * a;
  auto horner = [x](const std::array<double, 14>& c) {
    double v = c.back();
    for (std::size_t k = c.size() - 1; k-- > 0;) v = v * x + c[k];
    return v;
  };
  const double a3 = a * x, a5 = a3 * x;
  SegmentMoments m;
  if (a < kSeriesHalfAngle) {
    m.area = a3 * horner(kArea);
    m.first = a5 * horner(kFirst);
    m.normal2 = a5 * x * horner(kNormal2);
    m.along2 = a5 * horner(kAlong2);
    return m;
  }
  // closed forms (file comment), about the centre, then u' = u - c
  const double s = std::sin(a), c = std::cos(a);
  m.area = a - s * c;
  const double su = 2.0 / 3.0 * s * s * s;
  const double iuu = (a + s * c) / 4.0 - c * c * c * s / 2.0;
  m.along2 = (4.0 * a - std::sin(4.0 * a)) / 16.0 - 2.0 / 3.0 * c * s * s * s;
  m.first = su - c * m.area;
  m.normal2 = iuu - 2.0 * c * su + c * c * m.area;
  return m;
}

ArcChord arcChord(const BoundaryPiece& arc) {
  ArcChord c;
  c.half = 0.5 * (arc.angle1 - arc.angle0);
  const double tm = 0.5 * (arc.angle0 + arc.angle1);
  c.n = Vec2(std::cos(tm), std::sin(tm));
  c.e = Vec2(-c.n.y(), c.n.x());
  if (c.half >= kSeriesHalfAngle) {
    c.radius = arc.radius;
    c.mid = arc.centre + (arc.radius * std::cos(c.half)) * c.n;
    return c;
  }
  const Vec2 s0 = arc.start(), s1 = arc.end();
  const double L = (s1 - s0).norm();
  c.mid = 0.5 * (s0 + s1);
  if (!(L > 0.0)) return c;  // radius 0: no segment (a span within rounding)
  c.e = (s1 - s0) / L;
  c.n = Vec2(c.e.y(), -c.e.x());
  c.radius = 0.5 * L / std::sin(c.half);
  return c;
}

bool angleOnArc(double t, const BoundaryPiece& arc) {
  double d = std::fmod(t - arc.angle0, kTwoPi);
  if (d < 0.0) d += kTwoPi;
  return d <= arc.angle1 - arc.angle0;
}

Vec2 startPointMean(const std::vector<BoundaryPiece>& boundary) {
  Vec2 g = Vec2::Zero();
  for (const BoundaryPiece& p : boundary) g += p.start();
  return g / static_cast<double>(boundary.size());
}

AreaMoments areaMomentsAbout(const std::vector<BoundaryPiece>& boundary, const Vec2& g) {
  PolygonMomentSums sum;
  const std::size_t n = boundary.size();
  // chord polygon: signed triangles (g, a, b) (PatchShape's polygon rows),
  // a and b consecutive start points (no allocation: the adapter calls this
  // on every clip)
  const Vec2 first = boundary[0].start() - g;
  Vec2 b = first;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = b;
    b = i + 1 < n ? Vec2(boundary[i + 1].start() - g) : first;
    sum.addEdge(a, b);
  }
  // circular segments (file comment)
  for (const BoundaryPiece& p : boundary) {
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    const double R = p.radius, R2 = R * R, R4 = R2 * R2;
    const double half = 0.5 * (p.angle1 - p.angle0), mid = 0.5 * (p.angle0 + p.angle1);
    if (half < kSeriesHalfAngle) {
      // about the chord's midpoint (arcChord), (u', v) along (nu, e), shifted to g
      const ArcChord ch = arcChord(p);
      const double Rc = ch.radius, Rc2 = Rc * Rc, Rc4 = Rc2 * Rc2;
      const SegmentMoments seg = circularSegmentMoments(half);
      const double A = Rc2 * seg.area, su = Rc * Rc2 * seg.first;
      const double iuu = Rc4 * seg.normal2, ivv = Rc4 * seg.along2;
      const Vec2& nu = ch.n;
      const Vec2& e = ch.e;
      const double sxc = su * nu.x(), syc = su * nu.y();
      const double ixxc = iuu * nu.x() * nu.x() + ivv * e.x() * e.x();
      const double iyyc = iuu * nu.y() * nu.y() + ivv * e.y() * e.y();
      const double ixyc = iuu * nu.x() * nu.y() + ivv * e.x() * e.y();
      const Vec2 d = ch.mid - g;
      sum.area += A;
      sum.sx += sxc + A * d.x();
      sum.sy += syc + A * d.y();
      sum.ixx += ixxc + 2.0 * d.x() * sxc + A * d.x() * d.x();
      sum.iyy += iyyc + 2.0 * d.y() * syc + A * d.y() * d.y();
      sum.ixy += ixyc + d.x() * syc + d.y() * sxc + A * d.x() * d.y();
      continue;
    }
    const double s = std::sin(half), c = std::cos(half);
    const double A = R2 * (half - s * c);
    const double su = 2.0 / 3.0 * R * R2 * s * s * s;
    const double iuu = R4 * ((half + s * c) / 4.0 - c * c * c * s / 2.0);
    const double ivv =
        R4 * ((4.0 * half - std::sin(4.0 * half)) / 16.0 - 2.0 / 3.0 * c * s * s * s);
    const double cm = std::cos(mid), sm = std::sin(mid);
    // about the arc's centre, in the patch axes
    const double sxc = su * cm, syc = su * sm;
    const double ixxc = iuu * cm * cm + ivv * sm * sm;
    const double iyyc = iuu * sm * sm + ivv * cm * cm;
    const double ixyc = (iuu - ivv) * sm * cm;
    // shifted to g: the centre at d = centre - g
    const Vec2 d = p.centre - g;
    sum.area += A;
    sum.sx += sxc + A * d.x();
    sum.sy += syc + A * d.y();
    sum.ixx += ixxc + 2.0 * d.x() * sxc + A * d.x() * d.x();
    sum.iyy += iyyc + 2.0 * d.y() * syc + A * d.y() * d.y();
    sum.ixy += ixyc + d.x() * syc + d.y() * sxc + A * d.x() * d.y();
  }
  AreaMoments m;
  m.area = sum.area;
  m.first = Vec2(sum.sx, sum.sy);
  m.xx = sum.ixx, m.xy = sum.ixy, m.yy = sum.iyy;
  return m;
}

double arcRegionMaxDistance(const std::vector<BoundaryPiece>& boundary) {
  double best = 0.0;
  for (const BoundaryPiece& p : boundary) {
    best = std::max(best, p.start().norm());
    if (p.kind == BoundaryPiece::Kind::Arc) {
      best = std::max(best, p.end().norm());
      // the circle's farthest point from O, at the angle of the centre
      const double cn = p.centre.norm();
      if (cn == 0.0 || angleOnArc(angleOf(p.centre), p)) best = std::max(best, cn + p.radius);
    }
  }
  return best;
}

double arcRegionDiameter(const std::vector<BoundaryPiece>& boundary) {
  std::vector<Vec2> ends;
  for (const BoundaryPiece& p : boundary) ends.push_back(p.start());
  double best2 = 0.0;
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size(); ++j)
      best2 = std::max(best2, (ends[j] - ends[i]).squaredNorm());
  double best = std::sqrt(best2);
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const BoundaryPiece& p = boundary[i];
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    best = std::max(best, (p.end() - p.start()).norm());
    // an end point Q and its farthest point on this arc, c + R (c - Q) / |c - Q|
    for (const Vec2& q : ends) {
      const Vec2 v = p.centre - q;
      if (v.norm() > 0.0 && angleOnArc(angleOf(v), p)) best = std::max(best, v.norm() + p.radius);
    }
    for (std::size_t j = i; j < boundary.size(); ++j) {
      const BoundaryPiece& o = boundary[j];
      if (o.kind != BoundaryPiece::Kind::Arc) continue;
      // two circles' farthest pair lies on the line of their centres
      const Vec2 v = p.centre - o.centre;
      if (v.norm() > 1e-12 * (p.radius + o.radius)) {
        const double t = angleOf(v);
        if (angleOnArc(t, p) && angleOnArc(t + kPi, o))
          best = std::max(best, v.norm() + p.radius + o.radius);
      } else {
        // same centre: a diametral pair, some t on p with t + pi on o
        const double r = std::min(p.radius, o.radius);
        for (const double t : {p.angle0, p.angle1, o.angle0 + kPi, o.angle1 + kPi})
          if (angleOnArc(t, p) && angleOnArc(t + kPi, o))
            best = std::max(best, p.radius + o.radius), (void)r;
      }
    }
  }
  return best;
}

double arcRegionMinLinear(const std::vector<BoundaryPiece>& boundary, double p0, double cx,
                          double cy) {
  double lowest = std::numeric_limits<double>::infinity();
  const double gn = std::hypot(cx, cy);
  for (const BoundaryPiece& p : boundary) {
    const Vec2 s = p.start();
    lowest = std::min(lowest, p0 + cx * s.x() + cy * s.y());
    if (p.kind == BoundaryPiece::Kind::Arc && gn > 0.0 && angleOnArc(std::atan2(-cy, -cx), p)) {
      lowest = std::min(lowest, p0 + cx * p.centre.x() + cy * p.centre.y() - p.radius * gn);
    }
  }
  return lowest;
}

bool arcRegionContains(const std::vector<BoundaryPiece>& boundary, const Vec2& q, double tol) {
  for (const BoundaryPiece& p : boundary) {
    const Vec2 a = p.start(), b = p.end();
    const Vec2 e = b - a;
    const double c = cross(e, q - a);
    if (c >= 0.0 || c >= -tol * e.norm()) continue;  // inner side of the chord
    if (p.kind == BoundaryPiece::Kind::Arc && (q - p.centre).norm() <= p.radius + tol) continue;
    return false;
  }
  return true;
}

Vec2 arcRegionNearestBoundaryPoint(const std::vector<BoundaryPiece>& boundary, const Vec2& q,
                                   std::size_t& piece, double& t) {
  double best = std::numeric_limits<double>::infinity();
  Vec2 out = Vec2::Zero();
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const BoundaryPiece& p = boundary[i];
    Vec2 x;
    double ti;
    if (p.kind == BoundaryPiece::Kind::Segment) {
      const Vec2 e = p.b - p.a;
      const double ee = e.squaredNorm();
      ti = ee > 0.0 ? std::clamp((q - p.a).dot(e) / ee, 0.0, 1.0) : 0.0;
      x = p.a + ti * e;
    } else {
      // radial where the angle of Q lies on the arc, else the nearer end
      const Vec2 v = q - p.centre;
      const double span = p.angle1 - p.angle0;
      if (v.norm() > 0.0 && angleOnArc(angleOf(v), p)) {
        double d = std::fmod(angleOf(v) - p.angle0, kTwoPi);
        if (d < 0.0) d += kTwoPi;
        ti = d / span;
        x = p.centre + p.radius * v / v.norm();
      } else {
        const Vec2 s = p.start(), e = p.end();
        const bool atStart = (q - s).squaredNorm() <= (q - e).squaredNorm();
        ti = atStart ? 0.0 : 1.0;
        x = atStart ? s : e;
      }
    }
    const double dist = (x - q).norm();
    if (dist < best) best = dist, out = x, piece = i, t = ti;
  }
  return out;
}

}  // namespace internal
}  // namespace patchspin
