// Flat faces of Bullet shapes and their overlap patch (see patch_detection.hpp).
#include "patch_detection.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace patchspin::bullet::internal {
namespace {

// Vertices closer than this fraction of the patch size are merged
// (PatchShape rejects repeated vertices).
constexpr double kMergeFraction = 1e-9;

Vec2 toPlane(const btVector3& p, const btVector3& origin, const btVector3& ex,
             const btVector3& ey) {
  const btVector3 d = p - origin;
  return Vec2(double(d.dot(ex)), double(d.dot(ey)));
}

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Puts the points of a convex set in counter-clockwise order and merges
// near-duplicates. Faces and clipped overlaps arrive in cyclic order
// (box faces, hull faces, Sutherland-Hodgman output): then a reversal, if
// any, suffices (checked in O(n), no trigonometry). Otherwise they are
// sorted by their angle about the mean, each angle computed once. In place.
void counterClockwise(std::vector<Vec2>& pts) {
  if (pts.size() < 3) return;
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : pts) mean += p;
  mean /= double(pts.size());
  double size = 0.0;
  for (const Vec2& p : pts) size = std::max(size, (p - mean).norm());
  const double merge = kMergeFraction * size;
  const size_t n = pts.size();
  double area2 = 0.0;
  for (size_t i = 0; i < n; ++i) area2 += cross2(pts[i] - mean, pts[(i + 1) % n] - mean);
  if (area2 < 0.0) std::reverse(pts.begin(), pts.end());
  // already in angular order about the mean iff every step turns
  // counter-clockwise about it (by less than pi) and the steps pass the
  // angle 0 (from y < 0 to y >= 0) exactly once: they wind once around
  bool ordered = true;
  int windings = 0;
  for (size_t i = 0; i < n && ordered; ++i) {
    const Vec2 a = pts[i] - mean, b = pts[(i + 1) % n] - mean;
    ordered = cross2(a, b) > 0.0;
    windings += a.y() < 0.0 && b.y() >= 0.0;
  }
  if (!ordered || windings != 1) {
    std::vector<std::pair<double, Vec2>> byAngle;
    byAngle.reserve(n);
    for (const Vec2& p : pts)
      byAngle.emplace_back(std::atan2(p.y() - mean.y(), p.x() - mean.x()), p);
    std::sort(byAngle.begin(), byAngle.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t i = 0; i < n; ++i) pts[i] = byAngle[i].second;
  }
  // merged in place: pts[0, kept) are the points kept so far
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    if (kept == 0 || (pts[i] - pts[kept - 1]).norm() > merge) pts[kept++] = pts[i];
  }
  while (kept > 1 && (pts[0] - pts[kept - 1]).norm() <= merge) --kept;
  pts.resize(kept);
}
// Buffers of buildPatch, kept per thread: their storage is reused from
// patch to patch (a clipped overlap was six allocations).
struct Buffers {
  std::vector<Vec2> a, b, subject, out;
};
Buffers& buffers() {
  static thread_local Buffers b;
  return b;
}

}  // namespace

void clipConvex(std::vector<Vec2>& subject, const std::vector<Vec2>& clip, std::vector<Vec2>& out) {
  if (subject.empty()) return;
  // a circle (centre m, radius rMax) around the subject; it also holds every
  // clipped subject (a part of the subject's convex hull)
  Vec2 m = Vec2::Zero();
  for (const Vec2& p : subject) m += p;
  m /= double(subject.size());
  double rMax = 0.0;
  for (const Vec2& p : subject) rMax = std::max(rMax, (p - m).norm());
  for (size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Vec2& c1 = clip[i];
    const Vec2& c2 = clip[(i + 1) % clip.size()];
    const Vec2 edge = c2 - c1;
    // an edge farther from the circle's centre than its radius cuts nothing
    // (margin: far above the round-off of the cross products below)
    const double edgeLength = edge.norm();
    if (cross2(edge, m - c1) > edgeLength * (rMax + 1e-9 * ((m - c1).norm() + rMax))) continue;
    // an edge with every point on its inner side cuts nothing
    bool allInside = true;
    for (const Vec2& p : subject)
      if (cross2(edge, p - c1) < 0.0) {
        allInside = false;
        break;
      }
    if (allInside) continue;
    const size_t n = subject.size();
    // room for every point and crossing (each point gives two at most; a
    // convex cut gives n + 1, round-off near the line may give more)
    out.resize(2 * n);
    size_t k = 0;
    // (through pointers: the two buffers are references that the compiler
    // must otherwise assume to alias, reloading both at every store)
    const Vec2* const in = subject.data();
    Vec2* const o = out.data();
    // each point's side computed once (the next point's is carried over)
    const double s0 = cross2(edge, in[0] - c1);
    double sp = s0;
    for (size_t j = 0; j < n; ++j) {
      const Vec2& p = in[j];
      const bool last = j + 1 == n;
      const Vec2& q = in[last ? 0 : j + 1];
      const double sq = last ? s0 : cross2(edge, q - c1);
      if (sp >= 0.0) o[k++] = p;
      if ((sp >= 0.0) != (sq >= 0.0)) o[k++] = p + (q - p) * (sp / (sp - sq));
      sp = sq;
    }
    out.resize(k);
    subject.swap(out);
  }
}

namespace {

// True if the disk (centre, radius) lies inside the convex CCW polygon.
bool diskInsidePolygon(const Vec2& centre, double radius, const std::vector<Vec2>& poly) {
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 edge = poly[(i + 1) % poly.size()] - poly[i];
    // signed distance of the centre to the edge line, positive inside
    if (cross2(edge, centre - poly[i]) / edge.norm() < radius) return false;
  }
  return true;
}

// The face of a box (half extents h, with margin: the real box).
void boxFace(const btVector3& h, const btTransform& tr, const btVector3& localDir, double* cosine,
             Face& face) {
  int axis = localDir.closestAxis();
  const double sign = localDir[axis] >= 0 ? 1.0 : -1.0;
  btVector3 n(0, 0, 0);
  n[axis] = btScalar(sign);
  if (cosine) *cosine = double(n.dot(localDir));
  face.kind = Face::Kind::Polygon;
  face.normal = tr.getBasis() * n;
  face.radius = 0.0;
  face.vertices.clear();
  btVector3 c(0, 0, 0);
  c[axis] = btScalar(sign) * h[axis];
  face.centre = tr * c;
  // the vertices when asked for (Face::polygonVertices)
  face.boxPending = true;
  face.boxTransform = tr;
  face.boxCentre = c;
  face.boxHalf = h;
  face.boxU = (axis + 1) % 3;
  face.boxV = (axis + 2) % 3;
}

}  // namespace

const std::vector<btVector3>& Face::polygonVertices() const {
  if (boxPending) {
    const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    vertices.clear();
    vertices.reserve(4);
    for (int k = 0; k < 4; ++k) {
      btVector3 p = boxCentre;
      p[boxU] = btScalar(su[k]) * boxHalf[boxU];
      p[boxV] = btScalar(sv[k]) * boxHalf[boxV];
      vertices.push_back(boxTransform * p);
    }
    boxPending = false;
  }
  return vertices;
}

bool probeSupportFace(const btCollisionObject& body, const btCollisionObject& support,
                      btVector3* normal, double* clearance, btVector3* lowest) {
  const btCollisionShape* bodyShape = body.getCollisionShape();
  if (!bodyShape->isConvex()) return false;
  const btTransform& trB = support.getWorldTransform();
  const btVector3 centre = body.getWorldTransform().getOrigin();
  btVector3 n, onFace;
  switch (support.getCollisionShape()->getShapeType()) {
    case STATIC_PLANE_PROXYTYPE: {
      const auto* plane = static_cast<const btStaticPlaneShape*>(support.getCollisionShape());
      n = trB.getBasis() * plane->getPlaneNormal();
      onFace = trB * (plane->getPlaneNormal() * plane->getPlaneConstant());
      break;
    }
    case BOX_SHAPE_PROXYTYPE: {
      const auto* box = static_cast<const btBoxShape*>(support.getCollisionShape());
      const btVector3 h = box->getHalfExtentsWithMargin();
      const btVector3 p = trB.invXform(centre);
      int axis = 0;
      for (int i = 1; i < 3; ++i)
        if (btFabs(p[i]) - h[i] > btFabs(p[axis]) - h[axis]) axis = i;
      btVector3 local(0, 0, 0);
      local[axis] = p[axis] >= 0 ? btScalar(1) : btScalar(-1);
      n = trB.getBasis() * local;
      onFace = trB * (local * h[axis]);
      break;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      // the caps are the flat faces; a body further outside the side than
      // outside the caps has none to probe
      const auto* cyl = static_cast<const btCylinderShape*>(support.getCollisionShape());
      const int axis = cyl->getUpAxis();
      const btVector3 h = cyl->getHalfExtentsWithMargin();
      const btVector3 p = trB.invXform(centre);
      const double axial = double(btFabs(p[axis]) - h[axis]);
      const double radial = std::sqrt(std::max(0.0, double(p.length2() - p[axis] * p[axis]))) -
                            double(cyl->getRadius());
      if (!(axial >= radial)) return false;
      btVector3 local(0, 0, 0);
      local[axis] = p[axis] >= 0 ? btScalar(1) : btScalar(-1);
      n = trB.getBasis() * local;
      onFace = trB * (local * h[axis]);
      break;
    }
    default:
      return false;
  }
  // the body's lowest point along n, with its margin
  const btTransform& trA = body.getWorldTransform();
  const btVector3 low =
      trA * static_cast<const btConvexShape*>(bodyShape)->localGetSupportingVertex(
                trA.getBasis().transpose() * -n);
  *normal = n;
  *clearance = double(n.dot(low - onFace));
  *lowest = low;
  return true;
}

bool findFaceAlong(const btCollisionObject& object, const btVector3& direction, double* cosine,
                   Face& face) {
  return findFaceAlong(*object.getCollisionShape(), object.getWorldTransform(), direction, cosine,
                       face);
}

bool findFaceAlong(const btCollisionShape& leaf, const btTransform& tr, const btVector3& direction,
                   double* cosine, Face& face) {
  const btCollisionShape* shape = &leaf;
  const btVector3 localDir = tr.getBasis().transpose() * direction;
  switch (shape->getShapeType()) {
    case STATIC_PLANE_PROXYTYPE: {
      const auto* plane = static_cast<const btStaticPlaneShape*>(shape);
      face.kind = Face::Kind::Plane;
      face.normal = tr.getBasis() * plane->getPlaneNormal();
      face.centre = tr * (plane->getPlaneNormal() * plane->getPlaneConstant());
      face.radius = 0.0;
      face.vertices.clear();
      face.boxPending = false;
      if (cosine) *cosine = double(face.normal.dot(direction));
      return true;
    }
    case BOX_SHAPE_PROXYTYPE: {
      const auto* box = static_cast<const btBoxShape*>(shape);
      boxFace(box->getHalfExtentsWithMargin(), tr, localDir, cosine, face);
      return true;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      // btCylinderShape (y up), btCylinderShapeX, btCylinderShapeZ: the caps
      // are the two flat faces.
      const auto* cyl = static_cast<const btCylinderShape*>(shape);
      const int axis = cyl->getUpAxis();
      const btVector3 h = cyl->getHalfExtentsWithMargin();
      const double sign = localDir[axis] >= 0 ? 1.0 : -1.0;
      btVector3 n(0, 0, 0);
      n[axis] = btScalar(sign);
      if (cosine) *cosine = double(n.dot(localDir));
      face.kind = Face::Kind::Disk;
      face.normal = tr.getBasis() * n;
      face.centre = tr * (n * h[axis]);
      face.radius = double(cyl->getRadius());
      face.vertices.clear();
      face.boxPending = false;
      return true;
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
      // Polyhedral features are built once per shape (this writes to the
      // user's shape, as Bullet's own polyhedral contact clipping does).
      auto* hull = const_cast<btConvexHullShape*>(static_cast<const btConvexHullShape*>(shape));
      if (!hull->getConvexPolyhedron()) hull->initializePolyhedralFeatures();
      const btConvexPolyhedron* poly = hull->getConvexPolyhedron();
      if (!poly || poly->m_faces.size() == 0) return false;
      int best = -1;
      double bestCos = -2.0;
      for (int i = 0; i < poly->m_faces.size(); ++i) {
        const btScalar* pl = poly->m_faces[i].m_plane;
        const double c = double(btVector3(pl[0], pl[1], pl[2]).dot(localDir));
        if (c > bestCos) {
          bestCos = c;
          best = i;
        }
      }
      const btFace& f = poly->m_faces[best];
      face.kind = Face::Kind::Polygon;
      face.normal = tr.getBasis() * btVector3(f.m_plane[0], f.m_plane[1], f.m_plane[2]);
      face.radius = 0.0;
      face.vertices.clear();
      face.boxPending = false;
      btVector3 sum(0, 0, 0);
      for (int k = 0; k < f.m_indices.size(); ++k) {
        // Bullet's hull computer works on a quantized grid (vertices off by
        // ~1e-5 of the extent in the double build): snap each face vertex to
        // the nearest of the user's hull points, the real geometry
        btVector3 local = poly->m_vertices[f.m_indices[k]];
        btScalar nearest = SIMD_INFINITY;
        btVector3 snapped = local;
        for (int i = 0; i < hull->getNumPoints(); ++i) {
          const btVector3 q = hull->getScaledPoint(i);
          const btScalar d2 = (q - local).length2();
          if (d2 < nearest) {
            nearest = d2;
            snapped = q;
          }
        }
        const btVector3 p = tr * snapped;
        face.vertices.push_back(p);
        sum += p;
      }
      if (face.vertices.size() < 3) return false;
      face.centre = sum / btScalar(face.vertices.size());
      // normal of the snapped face (Newell), with the orientation of Bullet's plane
      btVector3 newell(0, 0, 0);
      for (size_t i = 0; i < face.vertices.size(); ++i)
        newell += face.vertices[i].cross(face.vertices[(i + 1) % face.vertices.size()]);
      if (newell.length2() > 0) {
        newell.normalize();
        face.normal = newell.dot(face.normal) < 0 ? -newell : newell;
      }
      if (cosine) *cosine = bestCos;
      return true;
    }
    default:
      return false;
  }
}

namespace {

// A clipped polygon about its area centroid (shoelace), returned in
// `centre`; false if it has no area.
bool polygonOutline(std::vector<Vec2>& poly, Vec2& centre) {
  if (poly.size() < 3) return false;
  double area2 = 0.0;
  Vec2 c = Vec2::Zero();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    const double cr = cross2(p, q);
    area2 += cr;
    c += cr * (p + q);
  }
  if (!(area2 > 0.0)) return false;
  centre = c / (3.0 * area2);
  for (Vec2& p : poly) p -= centre;
  return true;
}

// An arc region's outline about its area centroid (areaMomentsOf), returned
// in `centre`; one whole circle becomes a disk, segments alone a polygon.
// False if it has no area.
bool arcRegionOutline(PatchOutline& outline, Vec2& centre) {
  std::vector<BoundaryPiece>& pieces = outline.pieces;
  if (pieces.empty()) return false;
  const bool anyArc = std::any_of(pieces.begin(), pieces.end(), [](const BoundaryPiece& p) {
    return p.kind == BoundaryPiece::Kind::Arc;
  });
  if (!anyArc) {
    outline.kind = PatchOutline::Kind::Polygon;
    outline.vertices.clear();
    for (const BoundaryPiece& p : pieces) outline.vertices.push_back(p.a);
    pieces.clear();
    counterClockwise(outline.vertices);
    return polygonOutline(outline.vertices, centre);
  }
  if (pieces.size() == 1) {  // a whole disk (the other face's rim just outside it)
    outline.kind = PatchOutline::Kind::Disk;
    outline.radius = pieces[0].radius;
    centre = pieces[0].centre;
    pieces.clear();
    return true;
  }
  const AreaMoments m = areaMomentsOf(pieces);
  if (!(m.area > 0.0)) return false;
  centre = m.first / m.area;
  for (BoundaryPiece& p : pieces) {
    p.a -= centre, p.b -= centre;
    p.centre -= centre;
  }
  return true;
}

// The frame (normal, axes), gap and tilt of the patch between faces a and b;
// returns the provisional 2D origin (a's centre projected onto b's plane).
btVector3 setFrame(const Face& a, const Face& b, const btVector3& xHint, DetectedPatch& patch) {
  const btVector3 n = b.normal.normalized();
  patch.normal = n;
  btVector3 ex = xHint - n * xHint.dot(n);
  if (ex.length2() < btScalar(1e-6)) {
    btVector3 e1, e2;
    btPlaneSpace1(n, e1, e2);
    ex = e1;
  }
  ex.normalize();
  patch.xAxis = ex;
  patch.yAxis = n.cross(ex);

  // provisional 2D origin: a's centre projected onto b's plane
  const double gap = double(n.dot(a.centre - b.centre));
  const btVector3 base = a.centre - n * btScalar(gap);
  patch.gap = gap;
  // rotation that takes -a.normal onto n (small angle): theta = u x n
  patch.tilt = (-a.normal).cross(n);
  return base;
}

// The least of s . v over a region bounded by `pieces`: at a piece's end,
// or inside an arc at its point of outward normal -s / |s|.
double leastAlong(const std::vector<BoundaryPiece>& pieces, const Vec2& s) {
  double least = pieces.empty() ? 0.0 : s.dot(pieces[0].start());
  const double sNorm = s.norm();
  for (const BoundaryPiece& p : pieces) {
    least = std::min(least, s.dot(p.end()));
    if (p.kind != BoundaryPiece::Kind::Arc || !(sNorm > 0.0)) continue;
    // the angle of -s, taken into [angle0, angle0 + 2 pi)
    const double t =
        p.angle0 + std::remainder(std::atan2(-s.y(), -s.x()) - p.angle0 - M_PI, 2.0 * M_PI) + M_PI;
    if (t <= p.angle1) least = std::min(least, s.dot(p.centre) - p.radius * sNorm);
  }
  return least;
}

// patch.clearance from its frame, gap, centre and outline: a's face is a
// plane, so its height above b's plane is linear over the overlap and least
// at a vertex (polygon) or on the rim (disk).
void setClearance(const Face& a, DetectedPatch& patch) {
  const double an = double(a.normal.dot(patch.normal));
  patch.clearance = patch.gap;
  // a patch's faces are parallel within the flatness tolerance; this only
  // keeps the division below away from faces that do not face each other
  if (!(an < -0.5)) return;
  // height of a's face above b's plane at in-plane offset p from a's
  // projected centre: gap - (a.normal . p) / (a.normal . n)
  const Vec2 slope(-double(a.normal.dot(patch.xAxis)) / an,
                   -double(a.normal.dot(patch.yAxis)) / an);
  const PatchOutline& outline = patch.outline;
  double least = 0.0;  // the least of slope . v over the outline (about O)
  switch (outline.kind) {
    case PatchOutline::Kind::Disk:
      least = -outline.radius * slope.norm();
      break;
    case PatchOutline::Kind::Polygon:
      if (outline.vertices.empty()) break;
      least = slope.dot(outline.vertices[0]);
      for (const Vec2& v : outline.vertices) least = std::min(least, slope.dot(v));
      break;
    case PatchOutline::Kind::ArcRegion:
      least = leastAlong(outline.pieces, slope);
      break;
  }
  patch.clearance = patch.gap + slope.dot(patch.centre) + least;
}

}  // namespace

void refreshFrame(const Face& a, const Face& b, const btVector3& xHint, DetectedPatch& patch) {
  const btVector3 base = setFrame(a, b, xHint, patch);
  patch.origin =
      base + patch.xAxis * btScalar(patch.centre.x()) + patch.yAxis * btScalar(patch.centre.y());
  setClearance(a, patch);
}

std::optional<DetectedPatch> buildPatch(const Face& a, const Face& b, const btVector3& xHint,
                                        const DetectedPatch* overlap) {
  DetectedPatch patch;
  const btVector3 base = setFrame(a, b, xHint, patch);
  const btVector3& ex = patch.xAxis;
  const btVector3& ey = patch.yAxis;
  if (overlap) {
    patch.outline = overlap->outline;
    patch.centre = overlap->centre;
    patch.origin = base + ex * btScalar(patch.centre.x()) + ey * btScalar(patch.centre.y());
    setClearance(a, patch);
    return patch;
  }

  Buffers& buf = buffers();
  // a polygon face's vertices in the plane frame (disks are kept as disks)
  auto polygonOf = [&](const Face& f, std::vector<Vec2>& pts) {
    pts.clear();
    for (const btVector3& p : f.polygonVertices()) pts.push_back(toPlane(p, base, ex, ey));
    counterClockwise(pts);
  };
  // each face's polygon, built at most once
  bool haveA = false, haveB = false;
  auto polygonA = [&]() -> const std::vector<Vec2>& {
    if (!haveA) polygonOf(a, buf.a), haveA = true;
    return buf.a;
  };
  auto polygonB = [&]() -> const std::vector<Vec2>& {
    if (!haveB) polygonOf(b, buf.b), haveB = true;
    return buf.b;
  };

  // the overlap: a disk (centre, radius), a counter-clockwise polygon, or a
  // region bounded by segments and circular arcs (a disk cut by the other
  // face's edges, or two disks' lens), each exact
  PatchOutline& outline = patch.outline;
  Vec2 centre = Vec2::Zero();
  const Vec2 ca = toPlane(a.centre, base, ex, ey);
  const bool diskA = a.kind == Face::Kind::Disk, diskB = b.kind == Face::Kind::Disk;
  const Vec2 cb = diskB ? toPlane(b.centre, base, ex, ey) : Vec2::Zero();
  auto setDisk = [&](const Vec2& c, double r) {
    outline.kind = PatchOutline::Kind::Disk, outline.radius = r, centre = c;
  };
  if (b.kind == Face::Kind::Plane) {
    // an infinite plane: the patch is a's whole face
    if (diskA)
      setDisk(ca, a.radius);
    else
      outline.kind = PatchOutline::Kind::Polygon, outline.vertices = polygonA();
  } else if (diskA && !diskB && diskInsidePolygon(ca, a.radius, polygonB())) {
    setDisk(ca, a.radius);
  } else if (diskA && diskB && (ca - cb).norm() + a.radius <= b.radius) {
    setDisk(ca, a.radius);
  } else if (diskA && diskB && (ca - cb).norm() + b.radius <= a.radius) {
    setDisk(cb, b.radius);
  } else if (!diskA && diskB && diskInsidePolygon(cb, b.radius, polygonA())) {
    setDisk(cb, b.radius);
  } else if (diskA || diskB) {
    outline.kind = PatchOutline::Kind::ArcRegion;
    outline.pieces = diskA && diskB ? diskDiskIntersection(ca, a.radius, cb, b.radius)
                     : diskA        ? diskPolygonIntersection(ca, a.radius, polygonB())
                                    : diskPolygonIntersection(cb, b.radius, polygonA());
  } else {
    buf.subject = polygonA();
    clipConvex(buf.subject, polygonB(), buf.out);
    counterClockwise(buf.subject);
    outline.kind = PatchOutline::Kind::Polygon;
    outline.vertices = buf.subject;
  }
  if (outline.kind == PatchOutline::Kind::ArcRegion && !arcRegionOutline(outline, centre))
    return std::nullopt;
  if (outline.kind == PatchOutline::Kind::Polygon && !polygonOutline(outline.vertices, centre))
    return std::nullopt;
  // O at the centroid of the overlap
  patch.centre = centre;
  patch.origin = base + ex * btScalar(centre.x()) + ey * btScalar(centre.y());
  setClearance(a, patch);
  return patch;
}

bool PatchOutline::matches(const PatchOutline& other, double tol) const {
  if (kind != other.kind) return false;
  switch (kind) {
    case Kind::Disk:
      return std::abs(radius - other.radius) <= tol;
    case Kind::Polygon:
      if (vertices.size() != other.vertices.size()) return false;
      for (size_t i = 0; i < vertices.size(); ++i)
        if ((vertices[i] - other.vertices[i]).cwiseAbs().maxCoeff() > tol) return false;
      return true;
    case Kind::ArcRegion:
      if (pieces.size() != other.pieces.size()) return false;
      for (size_t i = 0; i < pieces.size(); ++i) {
        const BoundaryPiece &p = pieces[i], &q = other.pieces[i];
        if (p.kind != q.kind) return false;
        const bool same = p.kind == BoundaryPiece::Kind::Segment
                              ? (p.a - q.a).cwiseAbs().maxCoeff() <= tol &&
                                    (p.b - q.b).cwiseAbs().maxCoeff() <= tol
                              : (p.centre - q.centre).cwiseAbs().maxCoeff() <= tol &&
                                    std::abs(p.radius - q.radius) <= tol &&
                                    std::abs(p.angle0 - q.angle0) * p.radius <= tol &&
                                    std::abs(p.angle1 - q.angle1) * p.radius <= tol;
        if (!same) return false;
      }
      return true;
  }
  return false;
}

double PatchOutline::size() const {
  switch (kind) {
    case Kind::Disk:
      return radius;
    case Kind::Polygon:
      return vertices.empty() ? 0.0 : vertices[0].norm();
    case Kind::ArcRegion:
      return pieces.empty() ? 0.0 : pieces[0].start().norm();
  }
  return 0.0;
}

PatchShape PatchOutline::toShape() const {
  switch (kind) {
    case Kind::Disk:
      return PatchShape::disk(radius);
    case Kind::Polygon:
      return PatchShape::polygon(vertices);
    case Kind::ArcRegion:
      break;
  }
  return PatchShape::arcRegion(pieces);
}

}  // namespace patchspin::bullet::internal
