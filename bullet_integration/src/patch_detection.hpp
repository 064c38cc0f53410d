// Flat faces of Bullet shapes and the patch where two of them touch.
// The patch comes from the real face geometry (half extents with margin for
// boxes and cylinders, the hull points for convex hulls), never from the
// manifold points: the manifold only says that the bodies touch and which
// way the normal points.
#pragma once

#include <patchspin/geometry.hpp>

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <optional>
#include <vector>

class btCollisionObject;
class btCollisionShape;

namespace patchspin::bullet::internal {

// One flat face of a shape, in world coordinates.
struct Face {
  enum class Kind { Disk, Polygon, Plane };
  Kind kind = Kind::Polygon;
  btVector3 normal{0, 0, 1};  // outward unit normal
  btVector3 centre{0, 0, 0};  // disk centre / polygon centroid / a point of the plane
  double radius = 0.0;        // disk only [m]
  // Polygon only: its vertices. A box face's are made when first asked for:
  // most lookups (a contact off the faces, an overlap kept from the last
  // step) need the normal and the centre only.
  const std::vector<btVector3>& polygonVertices() const;

  // (written by findFaceAlong)
  mutable std::vector<btVector3> vertices;         // made (hulls), or made on demand (boxes)
  mutable bool boxPending = false;                 // a box face whose vertices are not made yet
  btTransform boxTransform;                        // the box's world transform
  btVector3 boxCentre{0, 0, 0}, boxHalf{0, 0, 0};  // face centre, half extents (box frame)
  int boxU = 0, boxV = 0;                          // the face's in-plane axes (box frame)
};

// The face of `shape` at world pose `transform` whose outward normal is
// closest to `direction` (unit), with its cosine, written to `face` (every
// field; its vertex storage is reused: the solver asks twice per touching
// manifold and step); false for shapes without flat faces (`face` then
// unspecified). A compound is not a leaf: its children are
// (compound_children.hpp).
bool findFaceAlong(const btCollisionShape& shape, const btTransform& transform,
                   const btVector3& direction, double* cosine, Face& face);
// The same for `object`'s own shape at its world transform.
bool findFaceAlong(const btCollisionObject& object, const btVector3& direction, double* cosine,
                   Face& face);

// For a pair Bullet reports no contact for (an empty manifold): the face of
// `support` (a plane, a box or a cylinder's cap) whose outside `body`'s
// centre lies furthest in, as a contact normal (unit, out of `support`,
// into `body`), and the clearance of `body`'s lowest point along it above
// that face's plane [m] (negative: below it), both with collision margins,
// and that lowest point (world). False for other support shapes, for a
// body further outside a cylinder's side than outside its caps, and for a
// body that is not convex.
bool probeSupportFace(const btCollisionObject& body, const btCollisionObject& support,
                      btVector3* normal, double* clearance, btVector3* lowest);

// Sutherland-Hodgman: the part of convex `subject` inside convex `clip`
// (both counter-clockwise), in place (`out`: a buffer).
void clipConvex(std::vector<Vec2>& subject, const std::vector<Vec2>& clip, std::vector<Vec2>& out);

// Outline of a patch in its frame (about O), cheap to build and compare;
// the PatchShape (moment tables) is built from it only when it changes.
struct PatchOutline {
  enum class Kind { Disk, Polygon, ArcRegion };
  Kind kind = Kind::Disk;
  double radius = 0.0;         // disk, centred at O [m]
  std::vector<Vec2> vertices;  // polygon, counter-clockwise, centroid at O [m]
  // a disk cut by the other face's edges, or two disks' lens: its boundary,
  // counter-clockwise, area centroid at O [m]
  std::vector<BoundaryPiece> pieces;
  bool isDisk() const { return kind == Kind::Disk; }
  // Same outline up to `tol` [m] in every coordinate.
  bool matches(const PatchOutline& other, double tol) const;
  // Its size for relative tolerances [m]: the radius, or the distance of the
  // first vertex (piece's start) from O (0 for an empty outline).
  double size() const;
  // Throws Error for a degenerate polygon or region.
  PatchShape toShape() const;
};

// A flat patch between face `a` of the moving body and face `b` it stands on.
struct DetectedPatch {
  btVector3 origin{0, 0, 0};  // O (on b's plane), world
  btVector3 normal{0, 0, 1};  // z: b's outward normal (into a's body)
  btVector3 xAxis{1, 0, 0};   // in-plane axes
  btVector3 yAxis{0, 1, 0};
  PatchOutline outline;        // overlap, patch frame about O
  Vec2 centre = Vec2::Zero();  // O in the plane frame about a's projected face centre
  double gap = 0.0;            // signed distance of a's face centre above b's plane [m]
  // least distance of a's face above b's plane over the overlap [m]: the
  // gap where the faces are parallel, less where a is tilted on b (its low
  // side is the first to touch)
  double clearance = 0.0;
  btVector3 tilt{0, 0, 0};  // small rotation of a that makes it flat on b [rad]
};

// Builds the overlap of the two faces: a disk while a disk face lies fully
// inside the other face, a region bounded by segments and arcs where a disk
// face is cut (PatchShape::Kind::ArcRegion), otherwise a polygon. `xHint` is an in-plane
// direction for the x axis. nullopt if the overlap is empty or degenerate.
// With `overlap`, its outline and centre are taken instead of clipping the
// faces again (the caller's judgement: the two bodies have not moved
// relative to each other since it was built); the frame, gap and tilt are
// always computed from the faces.
std::optional<DetectedPatch> buildPatch(const Face& a, const Face& b, const btVector3& xHint,
                                        const DetectedPatch* overlap = nullptr);
// The same as `patch = *buildPatch(a, b, xHint, &patch)` without copying the
// outline: the frame, gap, tilt and origin recomputed from the faces, the
// outline and centre kept.
void refreshFrame(const Face& a, const Face& b, const btVector3& xHint, DetectedPatch& patch);

}  // namespace patchspin::bullet::internal
