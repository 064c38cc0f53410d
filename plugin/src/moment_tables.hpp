// The moment tables of Eq. (36) of polygons and disks, each by its own
// method (moment_tables.cpp), for PatchShape::finish (geometry.cpp), and of
// arc regions (patch_shape_arc_region.cpp). Guarded by
// tests/core/geometry_test.cpp and arc_regions_test.cpp.
#pragma once

#include <patchspin/geometry.hpp>

#include <vector>

namespace patchspin::internal {

// Beyond this many diameters from O (max|r| > kFarRowsOffset diameter, so
// every patch point is at least 3 diameters from O) a polygon's rows with r
// come from quadrature over triangles fanned out from its vertex mean
// (farPolygonRRows): the closed-form edge integrals (polygonMomentTable) sum triangles
// (O, a, b) about O, whose terms reach ~max|r|^2 L each and cancel to the
// patch's, so they lose ~eps offset^2 to eps offset^3 of the rows' scale
// (offset = max|r| / diameter; the second round's open item and the tenth
// round's far sliver, fuzz/README.md item 65). Measured against the same
// closed form in 50 digits, on 200 polygons per offset (3-10 vertices, aspect
// 1 to 1e-8), in units of eps A max|f| max|phi| max(1, diameter^2 / A):
// closed form 3 to 15 at 3-4 diameters, 770 at 16, 4e4 at 100, 1.5e8 at
// 3560; the fan's 8 x 8 rule at most 4.1 from 3 diameters on (below 1.0
// with its nodes in long double; 4.6 on the second round's far heptagon;
// at 2 diameters its 8-point rule has not converged: 1.5e4). Patches about a point inside them
// (the Bullet layer's, about their centroid: max|r| <= diameter) never get
// here: one comparison.
constexpr double kFarRowsOffset = 4.0;

// Moment table of the convex polygon `v` about O: the polynomial rows by the
// exact triangle formulas (about the vertex mean, shifted to O, where
// `aboutVertexMean`: then `localInverse` gets G'^-1 about it and `g` the
// vertex mean), the rows with r by closed-form edge integrals, or (`farRows`)
// by a Gauss rule over triangles fanned out from the vertex mean.
MomentTable polygonMomentTable(const std::vector<Vec2>& v, bool aboutVertexMean, bool farRows,
                               Mat3& localInverse, Vec2& g);

// The closed-form rows of a disk's table: 1, x and y times (1, x, y).
MomentTable diskPolynomialMoments(const Vec2& centre, double R);

// Moment table of a disk (centre C, radius R) about O (the rows with r by
// adaptive quadrature in polar coordinates about O).
MomentTable diskMomentTable(const Vec2& centre, double R);

// The polynomial rows of an arc region's table (areaMomentsOf, Green's
// theorem); the rows with r are left zero.
MomentTable arcRegionPolynomialRows(const std::vector<BoundaryPiece>& boundary);

// The rows with r of an arc region's table from the exact law at pure spin
// about O with radius `rho`, Eq. (39).
void setArcRegionRRows(const std::vector<BoundaryPiece>& boundary, double rho, MomentTable& table);

}  // namespace patchspin::internal
