// Normal block part (normal_block.hpp; docs/solver.md (S4)-(S6), (S17)-(S20), (S23)-(S24)).
#include <patchspin/parts/normal_block.hpp>

#include "../arc_region_numerics.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace patchspin::parts {

PatchOutlineSummary summarizeOutline(const PatchShape& shape) {
  PatchOutlineSummary s;
  s.disk = shape.isDisk();
  if (s.disk) {
    s.centre = shape.centre();
    s.radius = shape.radius();
  }
  s.diameter = shape.diameter();
  return s;
}

namespace {
// The point of a polygon's boundary nearest to p: on edge `edge` (from
// vertex edge to the next) at parameter t in [0, 1] (0, 1: a vertex).
struct BoundaryPoint {
  Vec2 point;
  std::size_t edge = 0;
  double t = 0.0;
};
BoundaryPoint nearestOnEdges(const std::vector<Vec2>& v, const Vec2& p) {
  BoundaryPoint best{v[0]};
  double bestDist = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], e = v[(i + 1) % v.size()] - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec2 q = a + t * e;
    if ((q - p).norm() < bestDist) {
      bestDist = (q - p).norm();
      best = {q, i, t};
    }
  }
  return best;
}
}  // namespace

Vec2 nearestPointOn(const PatchShape& shape, const Vec2& p) {
  if (shape.isDisk()) {
    const Vec2 d = p - shape.centre();
    const double n = d.norm();
    return n <= shape.radius() ? p : Vec2(shape.centre() + d * (shape.radius() / n));
  }
  if (shape.contains(p)) return p;
  if (shape.kind() == PatchShape::Kind::ArcRegion) {
    // (on an arc the nearest point of an outside point is radial)
    std::size_t piece = 0;
    double t = 0.0;
    return internal::arcRegionNearestBoundaryPoint(shape.boundary(), p, piece, t);
  }
  return nearestOnEdges(shape.vertices(), p).point;
}

int pivotPoints(const PatchShape& shape, const Vec2& cop, Vec2 (&out)[2]) {
  if (shape.isDisk()) {
    out[0] = nearestPointOn(shape, cop);
    return 1;
  }
  if (shape.kind() == PatchShape::Kind::ArcRegion) {
    // as clampNormalImpulse: inside a segment piece its two ends, else the
    // nearest boundary point (on an arc, radial)
    std::size_t piece = 0;
    double t = 0.0;
    out[0] = internal::arcRegionNearestBoundaryPoint(shape.boundary(), cop, piece, t);
    const BoundaryPiece& b = shape.boundary()[piece];
    if (b.kind == BoundaryPiece::Kind::Segment && t > 0.0 && t < 1.0) {
      out[0] = b.a, out[1] = b.b;
      return 2;
    }
    return 1;
  }
  const std::vector<Vec2>& v = shape.vertices();
  const BoundaryPoint nearest = nearestOnEdges(v, cop);
  if (nearest.t > 0.0 && nearest.t < 1.0) {
    out[0] = v[nearest.edge];
    out[1] = v[(nearest.edge + 1) % v.size()];
    return 2;
  }
  out[0] = nearest.point;
  return 1;
}

double innerRadiusSquared(const PatchShape& shape) {
  if (shape.isDisk()) return 0.0;
  if (shape.kind() == PatchShape::Kind::ArcRegion) {
    // the disk about O inside every segment's half-plane and every arc's
    // circle lies in the region (which contains that intersection; equal to
    // it for a disk cut by a polygon, a lens)
    double best = std::numeric_limits<double>::infinity();
    for (const BoundaryPiece& piece : shape.boundary()) {
      if (piece.kind == BoundaryPiece::Kind::Arc) {
        best = std::min(best, piece.radius - piece.centre.norm());
        continue;
      }
      const Vec2 e = piece.b - piece.a;
      const double len = e.norm();
      if (!(len > 0.0)) continue;
      best = std::min(best, (e.x() * -piece.a.y() - e.y() * -piece.a.x()) / len);
    }
    if (!(best > 0.0) || !std::isfinite(best)) return 0.0;
    const double r = best * (1.0 - 1e-9);
    return r * r;
  }
  const auto& v = shape.vertices();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, prev = v.size() - 1; i < v.size(); prev = i++) {
    const Vec2 e = v[i] - v[prev];
    const double len = e.norm();
    if (!(len > 0.0)) continue;
    // signed distance of O from the edge line, > 0 on the inner side (counter-clockwise)
    const double d = (e.x() * -v[prev].y() - e.y() * -v[prev].x()) / len;
    best = std::min(best, d);
  }
  if (!(best > 0.0) || !std::isfinite(best)) return 0.0;
  const double r = best * (1.0 - 1e-9);
  return r * r;
}

namespace {
// (S17): where a is tilted on b, the gap closes only until a's low side is
// kLowSideSinkRelTol of the patch size into b
Vec3 gapTarget(double gap, double clearance, double size, double dt) {
  const double sink = kLowSideSinkRelTol * size;
  return Vec3(-std::clamp(clearance + sink, 0.0, gap) / dt, 0.0, 0.0);
}
}  // namespace

NormalTargets normalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                            double dt, bool splitImpulse, double erp, double erp2, double bounce) {
  NormalTargets t;
  if (gap > 0.0) {
    t.velocity = gapTarget(gap, clearance, size, dt);  // (the tilt: corrected by the push)
  } else if (splitImpulse) {
    t.push = (Vec3(-gap, 0.0, 0.0) + tiltRate) * erp / dt;
  } else {
    t.velocity = (Vec3(-gap, 0.0, 0.0) + tiltRate) * erp2 / dt;
  }
  if (gap > 0.0 && splitImpulse) t.push = tiltRate * erp / dt;
  t.velocity[0] += bounce;
  return t;
}

NormalTargets softNormalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                                double dt, bool splitImpulse, double erp, double erp2,
                                double softErp, double bounce) {
  NormalTargets t =
      normalTargets(gap, clearance, tiltRate, size, dt, splitImpulse, erp, erp2, bounce);
  if (gap <= 0.0) {
    t.velocity[0] = -gap * softErp / dt + bounce;
    t.push[0] = 0.0;
  }
  return t;
}

void clampNormalImpulse(const Mat3& Winv, const Vec3& lamN, const Vec3& residual, const Vec2& cop,
                        const PatchOutlineSummary& outline, const PatchShape& shape,
                        NormalImpulse& out) {
  // (cop is off the patch: a polygon's nearest point is on its boundary)
  // (an arc region: the nearest point on its pieces; inside a segment piece
  // that segment's two ends as the polygon's corners, on an arc one point)
  BoundaryPoint nearest;
  bool inEdge = false;  // nearest inside an edge: its ends
  Vec2 corners[2];
  if (shape.isDisk()) {
    nearest = BoundaryPoint{nearestPointOn(shape, cop)};
  } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
    std::size_t piece = 0;
    double t = 0.0;
    nearest.point = internal::arcRegionNearestBoundaryPoint(shape.boundary(), cop, piece, t);
    const BoundaryPiece& b = shape.boundary()[piece];
    if (b.kind == BoundaryPiece::Kind::Segment && t > 0.0 && t < 1.0) {
      corners[0] = b.a, corners[1] = b.b, inEdge = true;
      nearest.t = t;
    }
  } else {
    nearest = nearestOnEdges(shape.vertices(), cop);
    if (nearest.t > 0.0 && nearest.t < 1.0) {
      const std::vector<Vec2>& v = shape.vertices();
      corners[0] = v[nearest.edge], corners[1] = v[(nearest.edge + 1) % v.size()], inEdge = true;
    }
  }
  out.tipping = (cop - nearest.point).norm() > kTipRelTol * outline.diameter;
  const Mat3 W = Winv.inverse();
  // a point p's row: the normal velocity there is row(p) . c_n, and a force
  // P at p is the impulse P row(p); the rows' impulses must bring row . c_n
  // to row . target: row^T W lamN' = row^T (residual + W lamN)
  const Vec3 rhs = residual + W * lamN;
  auto row = [](const Vec2& p) { return Vec3(1.0, p.y(), -p.x()); };
  auto single = [&](const Vec2& p) {
    const Vec3 a = row(p);
    out.lamN = std::max(0.0, a.dot(rhs) / a.dot(W * a)) * a;
  };
  if (inEdge) {
    // inside an edge: its two corners
    const Vec2& p1 = corners[0];
    const Vec2& p2 = corners[1];
    const Vec3 a1 = row(p1), a2 = row(p2);
    Eigen::Matrix2d A;
    A << a1.dot(W * a1), a1.dot(W * a2), a2.dot(W * a1), a2.dot(W * a2);
    const Vec2 P = A.inverse() * Vec2(a1.dot(rhs), a2.dot(rhs));
    if (P.allFinite() && P[0] >= 0.0 && P[1] >= 0.0) {
      out.lamN = P[0] * a1 + P[1] * a2;
      return;
    }
    single(P[0] > P[1] ? p1 : p2);  // the corner that pushes (or nothing)
    return;
  }
  single(nearest.point);
}

}  // namespace patchspin::parts
