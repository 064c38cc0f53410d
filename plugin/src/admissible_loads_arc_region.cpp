// The nearest admissible loads of an arc region (DESIGN item 2; the
// polygons' and disks' in admissible_loads.cpp): the Euclidean projection
// of the scaled loads y = (Pz, Tx / rho, Ty / rho) onto the cone K of the
// loads of linear pressures p >= 0 on the region.
// K is {p >= 0 on every boundary point}, on an arc a
// constraint between linear (its ends) and conic. Admissible loads come
// back unchanged (the exact test, minPressure's). Others: the nearest
// feasible KKT candidate (projectArcRegionExact: a piece end's face, a
// segment's edge ray, an arc point whose face projection touches there);
// if none is feasible, the projection onto the cone K_Q of a
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
// at one arc point where its outward normal is -grad p; so the projection
// is the nearest feasible one of: each piece end's face projection, each
// segment's edge ray (multipliers >= 0), and per arc the face projection of
// the point P(t) whose projection's own touch angle is t (a root of
// r(t) = cross((cos t, sin t), -grad p_z(t)), bracketed on kArcSamples
// points and solved by the Illinois method). Feasible: minPressure >= -kExactFeasible of the mean
// pressure. False where no candidate is feasible (the polygon scheme
// decides then).
constexpr int kArcSamples = 16;
constexpr double kExactFeasible = 1e-10;
bool projectArcRegionExact(const PatchShape& shape, const Mat3& M, const Vec3& y, double rho,
                           Vec3& out) {
  const bool aboutMean = shape.maxDistanceFromOrigin() > shape.diameter();
  Mat3 PinvT;
  PinvT << 1.0, 0.0, 0.0, 0.0, 0.0, -rho, 0.0, rho, 0.0;
  const Mat3 MinvT = aboutMean ? Mat3::Zero() : Mat3(M.inverse().transpose());
  // n(P): the pressure at P of scaled loads z is n(P) . z
  auto row = [&](const Vec2& P) -> Vec3 {
    const Vec3 phi(1.0, P.x(), P.y());
    return aboutMean ? Vec3(PinvT * shape.solveLoadMatrix(phi)) : Vec3(MinvT * phi);
  };
  auto pressureOf = [&](const Vec3& z) {
    return LinearPressure::fromLoads(shape, loadsOfScaled(z, rho));
  };
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& z) {
    const double d = (z - y).norm();
    if (!(d < best) || !(z[0] > 0.0)) return;
    const double mean = z[0] / shape.area();
    if (!(minPressure(shape, pressureOf(z)) >= -kExactFeasible * mean)) return;
    best = d, out = z;
  };
  auto face = [&](const Vec3& n, Vec3& z) {
    const double ny = n.dot(y);
    if (!(ny < 0.0)) return false;
    z = y - ny / n.squaredNorm() * n;
    return true;
  };
  const std::vector<BoundaryPiece>& b = shape.boundary();
  Vec3 z;
  for (const BoundaryPiece& piece : b) {
    const Vec3 nStart = row(piece.start());
    if (face(nStart, z)) consider(z);
    if (piece.kind == BoundaryPiece::Kind::Segment && edgeProjection(nStart, row(piece.b), y, z))
      consider(z);
  }
  // the KKT point is unique (the projection onto a closed convex cone): a
  // feasible piece end or segment is it, and the arcs (kArcSamples + 1
  // samples and the root search's steps, a sine, cosine and pressure each)
  // are searched only where none is (AdmissibleLoadsArcRegion.*: KKT
  // optimality against brute force)
  if (std::isfinite(best)) return true;
  for (const BoundaryPiece& piece : b) {
    if (piece.kind != BoundaryPiece::Kind::Arc) continue;
    // r(t) and the face projection at P(t)
    auto residual = [&](double t, Vec3& zt) {
      const Vec2 u(std::cos(t), std::sin(t));
      if (!face(row(piece.centre + piece.radius * u), zt))
        return std::numeric_limits<double>::quiet_NaN();
      const LinearPressure pz = pressureOf(zt);
      return u.x() * -pz.cy - u.y() * -pz.cx;
    };
    const double t0 = piece.angle0, span = piece.angle1 - piece.angle0;
    double prevT = t0, prevR = residual(t0, z);
    for (int i = 1; i <= kArcSamples; ++i) {
      const double t = t0 + span * i / kArcSamples;
      const double r = residual(t, z);
      if (std::isfinite(prevR) && std::isfinite(r) && (prevR < 0.0) != (r < 0.0)) {
        // the Illinois method on the bracket [prevT, t], to round-off
        double a = prevT, fa = prevR, bb = t, fb = r, c = a, last = a;
        int side = 0;
        bool ok = false;
        for (int it = 0; it < 100; ++it) {
          c = (fa * bb - fb * a) / (fa - fb);
          if (!(c > std::min(a, bb) && c < std::max(a, bb))) c = 0.5 * (a + bb);
          const double fc = residual(c, z);
          if (!std::isfinite(fc)) break;
          ok = true;
          if (fc == 0.0 ||
              std::abs(c - last) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(c))
            break;
          last = c;
          if ((fc < 0.0) == (fb < 0.0)) {
            bb = c, fb = fc;
            if (side == -1) fa *= 0.5;
            side = -1;
          } else {
            a = c, fa = fc;
            if (side == 1) fb *= 0.5;
            side = 1;
          }
        }
        if (ok) consider(z);  // (z: the projection at the last c)
      }
      prevT = t, prevR = r;
    }
  }
  return std::isfinite(best);
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
