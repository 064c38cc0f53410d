// Geometry of convex regions bounded by segments and arcs (PatchShape's
// ArcRegion kind; arc_regions.cpp): moments about a chosen point, extents,
// extremes of a linear function, nearest boundary points. Guarded by
// tests/core/arc_regions_test.cpp.
#pragma once

#include <patchspin/geometry.hpp>

#include <vector>

namespace patchspin::internal {

// Moments of the circular segment of unit radius and half-angle a (between
// the arc and its chord) about the chord's midpoint, u' along the arc's mid
// direction, v along the chord: area, ∫u', ∫u'^2, ∫v^2 (∫v = ∫u'v = 0).
// By series in a below kSeriesHalfAngle, closed forms above (arc_regions.cpp;
// CircularSegmentMomentsMatchReference).
struct SegmentMoments {
  double area = 0.0, first = 0.0, normal2 = 0.0, along2 = 0.0;
};
constexpr double kSeriesHalfAngle = 1.0;
SegmentMoments circularSegmentMoments(double a);

// The frame of an arc's circular segment: its chord's midpoint, the unit
// outward normal n and chord direction e (counter-clockwise), the radius
// and half-angle h. Below kSeriesHalfAngle from the arc's own start and end
// points (the chord polygon's), radius |end - start| / (2 sin h), so that a
// flat arc's segment sits on that chord to rounding (its height R (1 - cos
// h) is below the ~eps R of the points for h < 1e-8); above, from the
// centre and mid angle.
struct ArcChord {
  Vec2 mid, n, e;
  double radius = 0.0, half = 0.0;
};
ArcChord arcChord(const BoundaryPiece& arc);

// True if angle t lies on the arc [angle0, angle1] (mod 2 pi).
bool angleOnArc(double t, const BoundaryPiece& arc);

// Area moments about the point g (coordinates P - g): the chord polygon of the
// pieces' start points (signed triangles about g) plus each arc's circular
// segment (circularSegmentMoments about its chord's midpoint below
// kSeriesHalfAngle, the closed form about the arc's centre above; shifted
// to g).
AreaMoments areaMomentsAbout(const std::vector<BoundaryPiece>& boundary, const Vec2& g);

// Mean of the pieces' start points (a point of the closed convex region).
Vec2 startPointMean(const std::vector<BoundaryPiece>& boundary);

// Largest |P| over the region (attained on the boundary).
double arcRegionMaxDistance(const std::vector<BoundaryPiece>& boundary);
// Largest distance between two points of the region: over the pairs of
// pieces, end points, each arc's farthest point from the other's end points,
// and two arcs' points on the line of their centres.
double arcRegionDiameter(const std::vector<BoundaryPiece>& boundary);

// Smallest value of p0 + cx x + cy y over the region: at a piece's start
// point or at an arc's point of outward normal -(cx, cy)/|(cx, cy)|.
double arcRegionMinLinear(const std::vector<BoundaryPiece>& boundary, double p0, double cx,
                          double cy);

// Point P within `tol` of the region: for every piece, P on the inner side of
// its chord or (an arc) within its circle (the region beyond a chord is that
// arc's circular segment).
bool arcRegionContains(const std::vector<BoundaryPiece>& boundary, const Vec2& p, double tol);

// Nearest boundary point to P; `piece` gets its piece index, `t` the
// segment parameter in [0, 1] (arcs: (angle - angle0) / span).
Vec2 arcRegionNearestBoundaryPoint(const std::vector<BoundaryPiece>& boundary, const Vec2& p,
                                   std::size_t& piece, double& t);

}  // namespace patchspin::internal
