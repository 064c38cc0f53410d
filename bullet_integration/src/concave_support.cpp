// The plane under a face on a triangle mesh or heightfield (concave_support.hpp).
#include "concave_support.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace patchspin::bullet::internal {
namespace {

using Vec3d = Eigen::Vector3d;

// A disk is tested as its circumscribed regular polygon of this many sides.
constexpr int kDiskTestSides = 16;
// A triangle whose doubled area is below this fraction of its longest edge
// squared is degenerate: it covers nothing and is skipped.
constexpr double kDegenerateFraction = 1e-9;
// Round-off allowance of a plane height, in ulps of Bullet's scalar times
// the coordinates' size.
constexpr double kHeightRoundOffUlps = 64.0;

Vec3d toEigen(const btVector3& v) {
  return Vec3d(double(v.x()), double(v.y()), double(v.z()));
}
btVector3 toBt(const Vec3d& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}
double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
double signedArea(const std::vector<Vec2>& p) {
  double a2 = 0.0;
  for (size_t i = 0; i < p.size(); ++i) a2 += cross2(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a2;
}
bool finite(const btVector3& v) {
  return std::isfinite(double(v.x())) && std::isfinite(double(v.y())) &&
         std::isfinite(double(v.z()));
}

struct Triangle {
  btVector3 v[3];
};

// Collects the triangles Bullet reports in a box (shape coordinates).
struct Collector final : btTriangleCallback {
  std::vector<Triangle>* out = nullptr;
  bool nonFinite = false;
  void processTriangle(btVector3* t, int /*partId*/, int /*triangleIndex*/) override {
    nonFinite = nonFinite || !finite(t[0]) || !finite(t[1]) || !finite(t[2]);
    out->push_back({{t[0], t[1], t[2]}});
  }
};

// The part of one triangle under the face: its clipped outline's vertices
// (in `Buffers::pieces` from `first`), area, and the triangle's plane
// (unit normal out of the support, towards the body, and a vertex).
struct Piece {
  size_t first = 0, count = 0;
  double area = 0.0;
  Vec3d normal, vertex;
};

struct Buffers {
  std::vector<Triangle> triangles;
  std::vector<Vec2> face, subject, out, pieceVertices;
  std::vector<Piece> pieces;
};
Buffers& buffers() {
  static thread_local Buffers b;
  return b;
}

}  // namespace

bool isTriangleSupport(const btCollisionShape& shape) {
  switch (shape.getShapeType()) {
    case TRIANGLE_MESH_SHAPE_PROXYTYPE:
    case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
    case MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE:
    case TERRAIN_SHAPE_PROXYTYPE:
      return true;
    default:
      return false;
  }
}

SupportPlane findSupportPlane(const btCollisionShape& support, const btTransform& tr, const Face& a,
                              double slack, Face& plane) {
  Buffers& buf = buffers();
  // the face in the shape's frame: centre c, outward normal nA (towards the
  // support), in-plane axes (u, v); a point q of the plane of the face is
  // c + x u + y v, its depth along nA is t
  const btMatrix3x3 basisT = tr.getBasis().transpose();
  const Vec3d c = toEigen(tr.invXform(a.centre));
  const Vec3d nA = toEigen(basisT * a.normal).normalized();
  if (!c.allFinite() || !nA.allFinite()) return SupportPlane::NoTriangle;
  Vec3d u = nA.unitOrthogonal();
  Vec3d v = nA.cross(u);
  auto toFace2 = [&](const Vec3d& p) { return Vec2((p - c).dot(u), (p - c).dot(v)); };

  buf.face.clear();
  if (a.kind == Face::Kind::Disk) {
    const double rc = a.radius / std::cos(M_PI / kDiskTestSides);
    for (int i = 0; i < kDiskTestSides; ++i) {
      const double phi = 2.0 * M_PI * i / kDiskTestSides;
      buf.face.emplace_back(rc * std::cos(phi), rc * std::sin(phi));
    }
  } else if (a.kind == Face::Kind::Polygon) {
    for (const btVector3& p : a.polygonVertices())
      buf.face.push_back(toFace2(toEigen(tr.invXform(p))));
  } else {
    return SupportPlane::NoTriangle;  // a plane is not a moving body's face
  }
  if (signedArea(buf.face) < 0.0) std::reverse(buf.face.begin(), buf.face.end());
  const double faceArea = signedArea(buf.face);
  double size = 0.0;
  for (const Vec2& q : buf.face) size = std::max(size, q.norm());
  if (!(faceArea > 0.0) || !std::isfinite(size)) return SupportPlane::NoTriangle;

  // the triangles within `slack` plus half the face's size of its bounding box
  const double reach = slack + 0.5 * size;
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec2& q : buf.face) {
    const Vec3d p = c + q.x() * u + q.y() * v;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= reach;
  hi.array() += reach;
  buf.triangles.clear();
  Collector collect;
  collect.out = &buf.triangles;
  static_cast<const btConcaveShape&>(support).processAllTriangles(&collect, toBt(lo), toBt(hi));
  if (collect.nonFinite) return SupportPlane::BadMesh;

  // each triangle's part under the face
  buf.pieces.clear();
  buf.pieceVertices.clear();
  for (const Triangle& t : buf.triangles) {
    const Vec3d p0 = toEigen(t.v[0]), p1 = toEigen(t.v[1]), p2 = toEigen(t.v[2]);
    const Vec3d e1 = p1 - p0, e2 = p2 - p0;
    Vec3d n = e1.cross(e2);
    const double n2 = n.norm();
    const double edge2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (p2 - p1).squaredNorm()});
    if (!(n2 > kDegenerateFraction * edge2)) continue;  // degenerate: covers nothing
    n /= n2;
    if (n.dot(nA) > 0.0) n = -n;  // either winding: out of the support
    buf.subject = {toFace2(p0), toFace2(p1), toFace2(p2)};
    if (signedArea(buf.subject) < 0.0) std::swap(buf.subject[1], buf.subject[2]);
    clipConvex(buf.subject, buf.face, buf.out);
    if (buf.subject.size() < 3) continue;
    const double area = signedArea(buf.subject);
    if (!(area > 0.0)) continue;
    Piece piece;
    piece.first = buf.pieceVertices.size();
    piece.count = buf.subject.size();
    piece.area = area;
    piece.normal = n;
    piece.vertex = p0;
    buf.pieceVertices.insert(buf.pieceVertices.end(), buf.subject.begin(), buf.subject.end());
    buf.pieces.push_back(piece);
  }
  if (buf.pieces.empty()) return SupportPlane::NoTriangle;

  // the reference plane: the piece of the largest area
  const Piece& ref =
      *std::max_element(buf.pieces.begin(), buf.pieces.end(),
                        [](const Piece& p, const Piece& q) { return p.area < q.area; });
  // depth along nA of the point of a triangle's plane over q (face frame)
  auto depth = [&](const Piece& p, const Vec2& q) {
    const Vec3d onFace = c + q.x() * u + q.y() * v;
    return p.normal.dot(p.vertex - onFace) / p.normal.dot(nA);
  };
  const double cosCoplanar = std::cos(kCoplanarAngle);
  const double heightTol =
      kCoplanarAngle * size +
      kHeightRoundOffUlps * double(std::numeric_limits<btScalar>::epsilon()) * (c.norm() + size);
  double covered = 0.0;
  for (const Piece& p : buf.pieces) {
    const bool parallel = p.normal.dot(ref.normal) >= cosCoplanar;
    bool coplanar = parallel, bump = false;
    for (size_t k = p.first; k < p.first + p.count; ++k) {
      const Vec2& q = buf.pieceVertices[k];
      // (a steep triangle's depth is computed only for the bump test)
      const double dp = depth(p, q), dr = depth(ref, q);
      if (!(std::abs(dp - dr) <= heightTol)) coplanar = false;
      if (dp < dr - heightTol) bump = true;  // nearer the body than the plane
    }
    if (coplanar) {
      covered += p.area;
    } else if (bump) {
      return SupportPlane::Crease;
    }
  }
  if (covered > (1.0 + kCoverFraction) * faceArea) return SupportPlane::BadMesh;
  if (covered < (1.0 - kCoverFraction) * faceArea) return SupportPlane::Crease;

  const double margin = double(support.getMargin());
  plane.kind = Face::Kind::Plane;
  plane.normal = tr.getBasis() * toBt(ref.normal);
  // (the plane's point under the face's centre: near the face, where the
  // solver's float differences are taken)
  plane.centre = tr * toBt(c + depth(ref, Vec2::Zero()) * nA + margin * ref.normal);
  plane.radius = 0.0;
  plane.vertices.clear();
  plane.boxPending = false;
  return SupportPlane::Found;
}

bool triangleNormalAt(const btCollisionShape& support, const btTransform& tr,
                      const btVector3& point, const btVector3& towards, double tol,
                      btVector3* normal) {
  Buffers& buf = buffers();
  const Vec3d p = toEigen(tr.invXform(point));
  const Vec3d to = toEigen(tr.invXform(towards));
  if (!p.allFinite() || !to.allFinite() || !(tol > 0.0)) return false;
  buf.triangles.clear();
  Collector collect;
  collect.out = &buf.triangles;
  static_cast<const btConcaveShape&>(support).processAllTriangles(
      &collect, toBt(p - Vec3d::Constant(tol)), toBt(p + Vec3d::Constant(tol)));
  if (collect.nonFinite) return false;
  double best = tol;
  Vec3d bestNormal = Vec3d::Zero();
  for (const Triangle& t : buf.triangles) {
    const Vec3d p0 = toEigen(t.v[0]), p1 = toEigen(t.v[1]), p2 = toEigen(t.v[2]);
    Vec3d n = (p1 - p0).cross(p2 - p0);
    const double edge2 =
        std::max({(p1 - p0).squaredNorm(), (p2 - p0).squaredNorm(), (p2 - p1).squaredNorm()});
    if (!(n.norm() > kDegenerateFraction * edge2)) continue;
    n.normalize();
    const double d = std::abs(n.dot(p - p0));
    if (d <= best) {
      best = d;
      bestNormal = n.dot(to - p0) >= 0.0 ? n : Vec3d(-n);
    }
  }
  if (bestNormal.isZero()) return false;
  *normal = tr.getBasis() * toBt(bestNormal);
  return true;
}

}  // namespace patchspin::bullet::internal
