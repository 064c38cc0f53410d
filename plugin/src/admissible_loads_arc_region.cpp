// The nearest admissible loads of an arc region (DESIGN item 2; the
// polygons' and disks' in admissible_loads.cpp): the Euclidean projection
// of the scaled loads y = (Pz, Tx / rho, Ty / rho) onto the cone K of the
// loads of linear pressures p >= 0 on the region.
// K is {p >= 0 on every boundary point}, on an arc a
// constraint between linear (its ends) and conic. Admissible loads come
// back unchanged (the exact test, minPressure's). Others: the KKT
// candidate whose local KKT conditions hold (projectArcRegionExact: a piece
// end's face, a segment's edge ray, an arc point found by Newton's method
// in y's negative interval on the arc, in closed form);
// if none holds, the projection onto the cone K_Q of a
// circumscribed polygon Q, coarse to fine (tangents 2 pi / 64 apart, then
// 2 pi / 1024 and 2 pi / 16384 within two coarser steps of the previous
// answer's touch angle: within 1.8e-8 R of the arc there), admissible as
// Q contains the region. Last, a uniform pressure of round-off size lifts
// a minimum that rounds below 0 (idempotence).
// Tests: tests/core/admissible_loads_arc_region_test.cpp (brute force, KKT,
// idempotence, the disk's closed form); fuzz/pressure_fuzz.cpp.
#include <patchspin/pressure.hpp>

#include "admissible_loads_internal.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace patchspin::internal {

namespace {

// Tangent steps of the circumscribed polygon, coarse to fine (file
// comment): every arc at kArcTangentSteps[0]; at level l > 0 also
// kArcTangentSteps[l] within kArcWindowSteps steps of level l - 1 of the
// touch angle of level l - 1's projection (where its zero line touches the
// arc: the outward normal -grad p).
constexpr double kTwoPiArc = 2.0 * 3.14159265358979323846;
constexpr double kArcTangentSteps[3] = {kTwoPiArc / 64.0, kTwoPiArc / 1024.0, kTwoPiArc / 16384.0};
constexpr double kArcWindowSteps = 2.0;

struct TangentWindow {
  double centre, halfWidth, step;
};

// The circumscribed polygon Q of an arc region: per piece its start point,
// then per arc the intersections of its tangents at the sorted tangent
// angles (its ends, the coarse grid, the windows' fine grids): the tangents
// at unit directions u, v meet at R (u + v) / (1 + u.v). Each grid's
// directions by a rotation recurrence (one sine and cosine per grid, not
// per vertex; ~1e-14 off the circle after a few hundred steps, what the
// final lift in nearestAdmissibleArcRegion absorbs). Q contains the region (its edges
// are supporting lines). `near` gets the index of the vertex nearest to
// the last window's centre (or npos).
struct TangentPoint {
  double angle;
  Vec2 dir;
};
// The tangent points of one arc, in a fixed buffer (no allocation per
// call). Their number is bounded whatever the region: the coarse grid has
// ceil(span / kArcTangentSteps[0]) + 1 <= 66 (span <= 2 pi (1 + 1e-12),
// PatchShape::arcRegion); a window of level l spans 2 kArcWindowSteps = 4
// steps of level l, 64 of level l + 1, so its grid has <= 65 + 1 points (one
// step for rounding) per centre, and an arc of nearly 2 pi meets it at two
// centres; two windows (levels 0 and 1); plus the arc's end: 66 + 2 * 2 *
// 66 + 1 = 331 <= kMaxTangentPoints. Beyond it: Error (a broken bound, not
// an input).
constexpr std::size_t kMaxTangentPoints = 384;
class TangentPoints {
 public:
  TangentPoint* begin() { return p_.data(); }
  TangentPoint* end() { return p_.data() + n_; }
  std::size_t size() const { return n_; }
  TangentPoint& operator[](std::size_t i) { return p_[i]; }
  TangentPoint& front() { return p_[0]; }
  TangentPoint& back() { return p_[n_ - 1]; }
  void clear() { n_ = 0; }
  void shrink(std::size_t n) { n_ = std::min(n_, n); }
  void push_back(const TangentPoint& t) {
    if (n_ == p_.size())
      throw Error("nearest admissible loads: more than " + std::to_string(p_.size()) +
                  " tangent points on one arc (internal bound broken)");
    p_[n_++] = t;
  }
  // the sorted ranges [0, middle) and [middle, size) merged, stable (as
  // std::inplace_merge, without its temporary buffer)
  void mergeFrom(std::size_t middle) {
    auto byAngle = [](const TangentPoint& a, const TangentPoint& b) { return a.angle < b.angle; };
    std::merge(p_.begin(), p_.begin() + middle, p_.begin() + middle, p_.begin() + n_,
               scratch_.begin(), byAngle);
    std::copy(scratch_.begin(), scratch_.begin() + n_, p_.begin());
  }

 private:
  std::array<TangentPoint, kMaxTangentPoints> p_, scratch_;
  std::size_t n_ = 0;
};
void addGrid(double lo, double hi, int k, TangentPoints& out) {
  const double step = (hi - lo) / k;
  const Vec2 rot(std::cos(step), std::sin(step));
  Vec2 d(std::cos(lo), std::sin(lo));
  for (int i = 0; i <= k; ++i) {
    out.push_back({lo + step * i, d});
    d = Vec2(d.x() * rot.x() - d.y() * rot.y(), d.x() * rot.y() + d.y() * rot.x());
  }
}
void circumscribedPolygon(const std::vector<BoundaryPiece>& boundary, const TangentWindow* windows,
                          int numWindows, std::vector<Vec2>& q, TangentPoints& points,
                          std::size_t& near) {
  q.clear();
  near = static_cast<std::size_t>(-1);
  double nearGap = std::numeric_limits<double>::infinity();
  for (const BoundaryPiece& p : boundary) {
    q.push_back(p.start());
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    const double t0 = p.angle0, t1 = p.angle1, span = t1 - t0;
    points.clear();
    addGrid(t0, t1, std::max(1, static_cast<int>(std::ceil(span / kArcTangentSteps[0]))), points);
    double lastCentre = std::numeric_limits<double>::quiet_NaN();
    for (int iw = 0; iw < numWindows; ++iw) {
      const TangentWindow& w = windows[iw];
      // the window's centre in [t0, t0 + 2 pi), and one turn lower
      double c = std::fmod(w.centre - t0, kTwoPiArc);
      if (c < 0.0) c += kTwoPiArc;
      for (const double centre : {t0 + c, t0 + c - kTwoPiArc}) {
        const double lo = std::max(t0, centre - w.halfWidth);
        const double hi = std::min(t1, centre + w.halfWidth);
        if (!(hi > lo)) continue;
        // (each grid is sorted: merged in, not sorted again)
        const std::size_t middle = points.size();
        addGrid(lo, hi, static_cast<int>(std::ceil((hi - lo) / w.step)), points);
        points.mergeFrom(middle);
        lastCentre = centre;
      }
    }
    // angles closer than a quarter of the finest step merged (the
    // grids overlap; near-equal tangents would make near-equal rows), the
    // arc's ends kept exactly
    constexpr double kMerge = 0.25 * kArcTangentSteps[2];
    std::size_t kept = 1;
    for (std::size_t i = 1; i < points.size(); ++i)
      if (points[i].angle - points[kept - 1].angle > kMerge) points[kept++] = points[i];
    points.shrink(kept);
    const TangentPoint end{t1, Vec2(std::cos(t1), std::sin(t1))};
    if (points.size() > 1 && t1 - points.back().angle <= kMerge) {
      points.back() = end;
    } else if (points.back().angle != t1) {
      points.push_back(end);
    }
    points.front().dir = Vec2(std::cos(t0), std::sin(t0));
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Vec2& u = points[i - 1].dir;
      const Vec2& v = points[i].dir;
      q.push_back(p.centre + p.radius / (1.0 + u.dot(v)) * Vec2(u + v));
      const double gap = std::abs(0.5 * (points[i - 1].angle + points[i].angle) - lastCentre);
      if (gap < nearGap) nearGap = gap, near = q.size() - 1;
    }
  }
}

// The exact projection onto K for an arc region, by its KKT conditions. A
// linear pressure >= 0 on a convex region bounded by segments and strictly
// convex arcs vanishes (if anywhere) at one piece end, along one segment, or
// at one arc point; so the projection is the one candidate among these
// whose KKT conditions hold (unique: the projection onto a closed convex
// cone), each tested locally, which by convexity is the whole test:
//  * a piece end P: the face projection z = y - (n.y / |n|^2) n, n = n(P),
//    n.y < 0, whose zero line through P supports the region: grad p_z . d
//    >= 0 for the two one-sided tangents d at P and for the sum of the two
//    inward normals (inside the tangent cone; the test that matters where
//    the pieces join smoothly, the cone a half-plane);
//  * a segment: its edge ray (edgeProjection's multipliers >= 0; the ray's
//    pressure, cross(b - a, x - a), is >= 0 on the region);
//  * an arc of centre c, radius R: with n(t) = N0 + R (cos t N1 + sin t N2)
//    the row of P(t) = c + R (cos t, sin t), the face projection at P(t) is
//    at squared distance f(t) = A^2 / q from y, A = n.y (y's pressure at
//    P(t), a0 + R |(a1, a2)| cos(t - psi) in closed form), q = |n|^2. A
//    face projection is the projection onto a half-space containing K, so
//    the answer, where it touches the arc only, is a maximum of f with
//    A < 0: a root of h = 2 A' q - A q' (f' = A h / q^2; h = 0 is grad p_z
//    normal to the arc) in y's negative interval on the arc, in closed form
//    (acos), where h < 0 at its start and h > 0 at its end. Solved by
//    Newton's method inside the bracket, from the minimum of A (the root
//    itself where q is constant along the arc: a disk in its own metric);
//    the candidate holds if grad p_z . u < 0 (p_z grows inwards).
// False where no candidate passes (the polygon scheme decides then).
// Tests: AdmissibleLoadsArcRegion.* (KKT optimality, brute force, the
// disk's closed form just outside the kern and at piece ends).
bool projectArcRegionExact(const PatchShape& shape, const Mat3& M, const Vec3& y, double rho,
                           Vec3& out) {
  const bool aboutMean = shape.maxDistanceFromOrigin() > shape.diameter();
  Mat3 PinvT;
  PinvT << 1.0, 0.0, 0.0, 0.0, 0.0, -rho, 0.0, rho, 0.0;
  const Mat3 MinvT = aboutMean ? Mat3::Zero() : Mat3(M.inverse().transpose());
  // n(phi): the pressure of scaled loads z at P is n(1, P) . z (linear in phi)
  auto rowOf = [&](const Vec3& phi) -> Vec3 {
    return aboutMean ? Vec3(PinvT * shape.solveLoadMatrix(phi)) : Vec3(MinvT * phi);
  };
  auto row = [&](const Vec2& P) { return rowOf(Vec3(1.0, P.x(), P.y())); };
  // grad p_z = (N1 . z, N2 . z)
  const Vec3 N1 = rowOf(Vec3(0.0, 1.0, 0.0)), N2 = rowOf(Vec3(0.0, 0.0, 1.0));
  auto gradOf = [&](const Vec3& z) { return Vec2(N1.dot(z), N2.dot(z)); };
  auto face = [&](const Vec3& n, Vec3& z) {
    const double ny = n.dot(y);
    if (!(ny < 0.0)) return false;
    z = y - ny / n.squaredNorm() * n;
    return z[0] > 0.0;
  };
  auto unit = [](const Vec2& v) { return Vec2(v / v.norm()); };
  auto leftOf = [](const Vec2& v) { return Vec2(-v.y(), v.x()); };
  // a piece's unit tangent (direction of travel) at its start or end
  auto tangent = [&](const BoundaryPiece& p, bool atEnd) {
    if (p.kind == BoundaryPiece::Kind::Segment) return unit(p.b - p.a);
    const double t = atEnd ? p.angle1 : p.angle0;
    return Vec2(-std::sin(t), std::cos(t));
  };
  const std::vector<BoundaryPiece>& b = shape.boundary();
  const std::size_t count = b.size();
  Vec3 z;
  for (std::size_t i = 0; i < count; ++i) {
    const BoundaryPiece& piece = b[i];
    const Vec3 nStart = row(piece.start());
    if (face(nStart, z)) {
      const Vec2 next = tangent(piece, false), prev = tangent(b[(i + count - 1) % count], true);
      const Vec2 g = gradOf(z);
      const double tol = kKktSlack * g.norm();
      const Vec2 inward = leftOf(next) + leftOf(prev);
      if (g.dot(next) >= -tol && g.dot(-prev) >= -tol && g.dot(inward) >= -tol * inward.norm()) {
        out = z;
        return true;
      }
    }
    if (piece.kind == BoundaryPiece::Kind::Segment && edgeProjection(nStart, row(piece.b), y, z) &&
        z[0] > 0.0) {
      out = z;
      return true;
    }
  }
  for (const BoundaryPiece& piece : b) {
    if (piece.kind != BoundaryPiece::Kind::Arc) continue;
    const double R = piece.radius, t0 = piece.angle0, t1 = piece.angle1;
    const Vec3 N0 = row(piece.centre);
    const double a0 = N0.dot(y), a1 = N1.dot(y), a2 = N2.dot(y);
    const double amp = R * std::hypot(a1, a2);
    if (!(a0 < amp)) continue;  // A >= 0 on the whole circle
    // A = a0 + amp cos(t - psi) < 0 on (m - w, m + w), m = psi + pi; where
    // |a0| < amp, h < 0 at m - w and h > 0 at m + w (A = 0 there, A' < 0
    // and > 0)
    const bool bounded = -a0 < amp;
    const double w = bounded ? kTwoPiArc / 2.0 - std::acos(-a0 / amp) : kTwoPiArc / 2.0;
    double m = std::fmod(std::atan2(a2, a1) + kTwoPiArc / 2.0 - t0, kTwoPiArc);
    if (m < 0.0) m += kTwoPiArc;
    m += t0;
    // h and h' at t (n = N0 + R v, v = cos N1 + sin N2, w = v')
    double hNow = 0.0, dhNow = 0.0;
    Vec3 nNow;
    auto evaluate = [&](double t) {
      const double c = std::cos(t), s = std::sin(t);
      const Vec3 v = c * N1 + s * N2, wv = c * N2 - s * N1;
      nNow = N0 + R * v;
      const double A = nNow.dot(y), dA = R * wv.dot(y), ddA = -R * v.dot(y);
      const double q = nNow.squaredNorm(), dq = 2.0 * R * wv.dot(nNow);
      const double ddq = 2.0 * R * (R * wv.squaredNorm() - v.dot(nNow));
      hNow = 2.0 * dA * q - A * dq;
      dhNow = 2.0 * ddA * q + dA * dq - A * ddq;
    };
    for (const double centre : {m - kTwoPiArc, m, m + kTwoPiArc}) {
      const bool knownLo = bounded && centre - w >= t0, knownHi = bounded && centre + w <= t1;
      const double lo = std::max(t0, centre - w), hi = std::min(t1, centre + w);
      if (!(hi > lo)) continue;
      // the bracket [a, bb] (h(a) < 0 < h(bb)) from the start: the
      // minimum of A, or the interval's end nearest to it
      double t = std::clamp(centre, lo, hi);
      evaluate(t);
      double a = lo, bb = hi;
      if (hNow < 0.0) {
        a = t;
        if (!knownHi) {
          const double keepT = t, keepH = hNow, keepDh = dhNow;
          const Vec3 keepN = nNow;
          evaluate(hi);
          if (!(hNow > 0.0)) continue;  // f grows to the arc's end: a piece end's
          t = keepT, hNow = keepH, dhNow = keepDh, nNow = keepN;
        }
      } else if (hNow > 0.0) {
        bb = t;
        if (!knownLo) {
          const double keepT = t, keepH = hNow, keepDh = dhNow;
          const Vec3 keepN = nNow;
          evaluate(lo);
          if (!(hNow < 0.0)) continue;
          t = keepT, hNow = keepH, dhNow = keepDh, nNow = keepN;
        }
      }
      // Newton inside the bracket (bisection where a step leaves it), to
      // round-off in t: done after a Newton step below 1e-9 of the
      // bracket's width (quadratic convergence: the next step would be
      // ~1e-18 of it; stepping on, the rounding in h left Newton jittering
      // about the root until the bracket collapsed, ~50 steps)
      const double small = 1e-9 * (hi - lo);
      for (int it = 0; it < 100 && hNow != 0.0; ++it) {
        if (hNow < 0.0)
          a = t;
        else
          bb = t;
        double next = t - hNow / dhNow;
        const bool newton = next > a && next < bb;
        if (!newton) next = 0.5 * (a + bb);
        if (!(next > a && next < bb)) break;  // the bracket is two neighbours
        const double step = std::abs(next - t);
        t = next;
        evaluate(t);
        if (step <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t) ||
            (newton && step <= small))
          break;
      }
      if (!face(nNow, z)) continue;
      const Vec2 u(std::cos(t), std::sin(t));
      if (gradOf(z).dot(u) < 0.0) {
        out = z;
        return true;
      }
    }
  }
  return false;
}

}  // namespace

PatchLoads nearestAdmissibleArcRegion(const PatchShape& shape, const PatchLoads& loads, double rho,
                                      bool& admissible) {
  admissible = true;
  if (isAdmissible(shape, loads, 0.0)) return loads;
  const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
  const Mat3 M = scaledLoadMatrix(shape, rho);
  const LinearPressure p = LinearPressure::fromLoads(shape, loads);
  // (the fallback's scratch: the windows, at most one per refined level;
  // Q, whose size grows with the number of pieces, which PatchShape does not
  // bound, allocated only here, off the exact path)
  TangentWindow windows[2];
  int numWindows = 0;
  std::vector<Vec2> q;
  TangentPoints points;
  Vec3 out = Vec3::Zero();
  const bool exact = projectArcRegionExact(shape, M, y, rho, out);
  for (int level = 0; level < 3 && !exact; ++level) {
    std::size_t near = 0;
    if (level == 0) q.reserve(256);
    circumscribedPolygon(shape.boundary(), windows, numWindows, q, points, near);
    // the walk's start: the vertex nearest to the last touch angle where y
    // violates it, else the most negative vertex of Q
    std::size_t worst = 0;
    if (near < q.size() && p.at(q[near]) < 0.0) {
      worst = near;
    } else {
      double lowest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < q.size(); ++k) {
        const double at = p.at(q[k]);
        if (at < lowest) lowest = at, worst = k;
      }
    }
    const KktResult found = projectPolygonByKkt(shape, q, M, y, rho, worst, out);
    if (found == KktResult::kInside) {
      out = y;  // p >= 0 on Q to round-off: y is on K_Q's boundary
    } else if (found != KktResult::kFound) {
      out = projectPolygonBySearch(shape, q, M, y, rho);
    }
    if (level == 2) break;
    // refine about the touch angle of this level's pressure
    const LinearPressure po = LinearPressure::fromLoads(shape, loadsOfScaled(out, rho));
    if (!(out[0] > 0.0) || !(std::abs(po.cx) + std::abs(po.cy) > 0.0)) break;
    windows[numWindows++] =
        TangentWindow{std::atan2(-po.cy, -po.cx), kArcWindowSteps * kArcTangentSteps[level],
                      kArcTangentSteps[level + 1]};
  }
  PatchLoads result = loadsOfScaled(out, rho);
  // where an active vertex of Q is a piece's end (on the region) its
  // pressure may round below 0: add the uniform pressure that lifts the
  // minimum to >= 0 (a change of round-off size), so that the result is
  // admissible with tolerance 0 and comes back unchanged (idempotence;
  // AdmissibleLoadsArcRegion.ProjectionIsAdmissibleIdempotentAndOrthogonal)
  // (lowest >= 0 with Pz > 0 is isAdmissible(shape, result, 0), its minimum
  // taken once per attempt)
  admissible = false;
  if (result.Pz > 0.0) {
    for (int attempt = 0; attempt < 4; ++attempt) {
      const double lowest = minPressure(shape, LinearPressure::fromLoads(shape, result));
      if (lowest >= 0.0) {
        admissible = true;
        break;
      }
      // (-lowest alone may round away in Pz: plus a few ulps of the mean)
      const double lift = -lowest + (attempt + 1) * 4.0 * std::numeric_limits<double>::epsilon() *
                                        (result.Pz / shape.area());
      const PatchLoads add = loadsOf(shape, LinearPressure{lift, 0.0, 0.0});
      result = PatchLoads{result.Pz + add.Pz, result.Tx + add.Tx, result.Ty + add.Ty};
    }
  }
  return result;
}

}  // namespace patchspin::internal
