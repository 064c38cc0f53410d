// Patch shapes in the patch frame: origin O (the reference point), x and y in
// the contact plane, z along the contact normal into the moving body.
// Disks, convex polygons (rectangles as a helper) and convex regions bounded
// by segments and circular arcs (a disk cut by lines, a lens). O may lie anywhere,
// inside or outside the patch, up to 1e4 patch diameters away (beyond, the
// linear pressure about O has no digits left); every constructor throws
// Error for a farther O, and for sizes whose moments over- or underflow
// double (beyond ~1e60 m or below ~1e-75 m). Lengths in metres.
#pragma once

#include <patchspin/types.hpp>

#include <Eigen/Core>
#include <vector>

namespace patchspin {

// Area moments about O. A polygon's are summed about its vertex mean where O
// lies outside it, and shifted to O (parallel axes): summed about a far O
// their products of coordinates would round to ~eps max|r|^2 / A of the
// area (fuzz/README.md, item 58).
struct AreaMoments {
  double area = 0.0;          // A = ∫ dA                            [m^2]
  Vec2 first = Vec2::Zero();  // (∫ x dA, ∫ y dA)                    [m^3]
  double xx = 0.0;            // ∫ x^2 dA                             [m^4]
  double xy = 0.0;            // ∫ x y dA                             [m^4]
  double yy = 0.0;            // ∫ y^2 dA                             [m^4]

  // Load matrix of Eq. (94) for p = p0 + cx x + cy y (DESIGN item 2):
  //   [Pz, Ty, -Tx]^T = G (p0, cx, cy)^T,
  //   G = [[A, Sx, Sy], [Sx, Ixx, Ixy], [Sy, Ixy, Iyy]].
  Mat3 loadMatrix() const;
};

// The integrals behind Eq. (36) for a linear pressure (DESIGN item 1):
//   m(f, k) = ∫_A f(x,y) phi_k(x,y) dA,
// f in {1, x, y, r, x/r, y/r} (rows, r = sqrt(x^2+y^2) about O),
// phi in {1, x, y} (columns). For p = p0 + cx x + cy y every integral of
// Eq. (36) is m.row(f) * (p0, cx, cy)^T.
struct MomentTable {
  enum Row { kOne = 0, kX = 1, kY = 2, kR = 3, kXOverR = 4, kYOverR = 5 };
  Eigen::Matrix<double, 6, 3> m = Eigen::Matrix<double, 6, 3>::Zero();
};

// One piece of the boundary of a convex region, the region on its left
// (counter-clockwise): the segment from a to b, or the arc of the circle
// (centre, radius) from angle angle0 to angle1 > angle0 (counter-clockwise,
// so its outward normal is (cos t, sin t)). Each piece must end where the
// next one starts (the last where the first starts).
struct BoundaryPiece {
  enum class Kind { Segment, Arc };
  Kind kind = Kind::Segment;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // segment
  Vec2 centre = Vec2::Zero();               // arc
  double radius = 0.0, angle0 = 0.0, angle1 = 0.0;

  static BoundaryPiece segment(const Vec2& from, const Vec2& to) {
    BoundaryPiece p;
    p.a = from, p.b = to;
    return p;
  }
  static BoundaryPiece arc(const Vec2& c, double r, double t0, double t1) {
    BoundaryPiece p;
    p.kind = Kind::Arc, p.centre = c, p.radius = r, p.angle0 = t0, p.angle1 = t1;
    return p;
  }
  Vec2 start() const;
  Vec2 end() const;
};

// Boundary (counter-clockwise pieces, exact: no polygonal approximation) of
// the disk (centre, radius) intersected with a convex polygon (ccw vertices).
// Empty if the intersection has no area; one arc of 2 pi if the disk lies in
// the polygon; only segments if the polygon lies in the disk. Pieces shorter
// than ~1e-12 of the radius are merged into their neighbours.
std::vector<BoundaryPiece> diskPolygonIntersection(const Vec2& centre, double radius,
                                                   const std::vector<Vec2>& ccwConvexPolygon);
// Boundary of disk (c1, r1) ∩ disk (c2, r2): the lens (two arcs), the smaller
// disk whole (one arc of 2 pi) if it lies in the other, empty if no area.
std::vector<BoundaryPiece> diskDiskIntersection(const Vec2& c1, double r1, const Vec2& c2,
                                                double r2);
// Area, first and second moments about the origin of the region bounded by
// `boundary` (Green's theorem, closed form on segments and arcs). Summed
// about the first piece's start point and shifted, so a far origin costs no
// digits beyond those of the shift itself.
AreaMoments areaMomentsOf(const std::vector<BoundaryPiece>& boundary);

class PatchShape {
 public:
  enum class Kind { Disk, Polygon, ArcRegion };

  // A disk of radius R [m] centred at `centre` (patch frame). Throws Error for
  // R <= 0 or non-finite input.
  static PatchShape disk(double radius, const Vec2& centre = Vec2::Zero());
  // A convex polygon with counter-clockwise vertices in the patch frame.
  // Throws Error naming the problem for: fewer than 3 vertices, NaN/Inf,
  // clockwise order, non-convexity, repeated vertices or (near-)zero area.
  // Collinear interior vertices are removed.
  static PatchShape polygon(std::vector<Vec2> vertices);
  // A convex region bounded by counter-clockwise segments and arcs (e.g. from
  // diskPolygonIntersection / diskDiskIntersection). Throws Error naming the
  // problem for: no pieces, NaN/Inf, arcs with radius <= 0 or angle1 <= angle0
  // or a span beyond 2 pi, gaps between consecutive pieces beyond 1e-9 of the
  // region's size, clockwise order, non-convexity (a turn < 0 at a joint, an
  // arc's angle at a joint not matching the turn) or (near-)zero area. Pieces
  // shorter than 1e-12 of the region's size are dropped (their neighbours
  // joined). Normalised: a boundary without arcs gives Kind::Polygon (as
  // polygon()), a single arc of 2 pi gives Kind::Disk (as disk()), anything
  // else Kind::ArcRegion.
  static PatchShape arcRegion(std::vector<BoundaryPiece> boundary);
  // Rectangle lx by ly [m] centred at `centre`, rotated by `angle` [rad] about
  // its centre; sides along x and y when angle = 0.
  static PatchShape rectangle(double lx, double ly, const Vec2& centre = Vec2::Zero(),
                              double angle = 0.0);
  // Regular n-gon with circumradius [m], first vertex at polar angle `angle`.
  static PatchShape regularPolygon(int n, double circumradius, const Vec2& centre = Vec2::Zero(),
                                   double angle = 0.0);

  Kind kind() const { return kind_; }
  bool isDisk() const { return kind_ == Kind::Disk; }
  // Disk only (Error otherwise): radius and centre. (Inline: the friction
  // solver asks for them on every visit of a disk patch.)
  double radius() const {
    if (kind_ != Kind::Disk) throwNotA("radius() asked of a patch that is not a disk");
    return radius_;
  }
  const Vec2& centre() const {
    if (kind_ != Kind::Disk) throwNotA("centre() asked of a patch that is not a disk");
    return centre_;
  }
  // Polygon only (Error otherwise): counter-clockwise vertices.
  const std::vector<Vec2>& vertices() const;
  // ArcRegion only (Error otherwise): counter-clockwise boundary pieces, at
  // least one arc and at least two pieces.
  const std::vector<BoundaryPiece>& boundary() const;

  const AreaMoments& areaMoments() const { return moments_; }
  // Inverse of AreaMoments::loadMatrix(), cached (Eq. (94) solved per call).
  const Mat3& loadMatrixInverse() const { return load_inverse_; }
  // G^-1 rhs, Eq. (94) solved for the pressure coefficients about O. For a
  // polygon with O outside it (max|r| > diameter), through the load matrix
  // about its vertex mean g and exact shifts: loadMatrixInverse() * rhs
  // rounds p0 and (cx, cy) independently, and about a far O (or beside a
  // sliver) that leaves the pressure on the patch without digits.
  Vec3 solveLoadMatrix(const Vec3& rhs) const;
  const MomentTable& momentTable() const { return table_; }
  double area() const { return moments_.area; }
  Vec2 centroid() const { return moments_.first / moments_.area; }
  // rho of Eq. (11) about O: mean distance of the patch from O [m].
  double defaultRho() const { return table_.m(MomentTable::kR, 0) / moments_.area; }
  // Largest distance of a patch point from O [m].
  double maxDistanceFromOrigin() const { return max_distance_; }
  // Largest distance between two patch points [m].
  double diameter() const { return diameter_; }
  // True if (x, y) lies in the closed patch (within `tol` metres).
  bool contains(const Vec2& point, double tol = 0.0) const;

  // The same shape expressed in a patch frame whose origin is moved to
  // `newOrigin` (old frame coordinates) and whose axes are rotated by `angle`
  // [rad]: a point P maps to R(-angle) (P - newOrigin).
  PatchShape inFrame(const Vec2& newOrigin, double angle) const;

  std::string describe() const;

 private:
  PatchShape() = default;
  void finish();
  [[noreturn]] static void throwNotA(const char* what);

  Kind kind_ = Kind::Disk;
  double radius_ = 0.0;
  Vec2 centre_ = Vec2::Zero();
  std::vector<Vec2> vertices_;
  std::vector<BoundaryPiece> boundary_;
  AreaMoments moments_;
  MomentTable table_;
  Mat3 load_inverse_ = Mat3::Identity();
  // polygons with O outside: G'^-1 about the vertex mean load_origin_
  bool loads_about_mean_ = false;
  Vec2 load_origin_ = Vec2::Zero();
  Mat3 local_load_inverse_ = Mat3::Identity();
  double max_distance_ = 0.0;
  double diameter_ = 0.0;
};

}  // namespace patchspin
