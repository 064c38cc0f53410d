// Patch shapes (disks and polygons; arc regions: patch_shape_arc_region.cpp),
// area moments, rho (11) and the moment table of Eq. (36) (its entries by
// kind: moment_tables.cpp).
#include <patchspin/geometry.hpp>

#include "arc_region_numerics.hpp"
#include "moment_tables.hpp"
#include "planar.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace patchspin {

using internal::formatDouble;

using internal::cross;
using internal::kPi;

namespace {

// Largest distance between two of the points: over the pairs i < j, as
// squared norms with one square root at the end (the same value as the
// largest (u - v).norm() over all ordered pairs: sqrt is monotonic, and
// |u - v| and |v - u| round alike), a quarter of the square roots' cost;
// a 64-gon patch (a clipped coin) has 2016 pairs.
double largestDistance(const std::vector<Vec2>& v) {
  double best2 = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      best2 = std::max(best2, (v[j] - v[i]).squaredNorm());
  return std::sqrt(best2);
}

}  // namespace

Mat3 AreaMoments::loadMatrix() const {
  Mat3 G;
  G << area, first.x(), first.y(),  //
      first.x(), xx, xy,            //
      first.y(), xy, yy;
  return G;
}

PatchShape PatchShape::disk(double radius, const Vec2& centre) {
  internal::requirePositive(radius, "disk radius R");
  internal::requireFinite(centre, "disk centre");
  PatchShape shape;
  shape.kind_ = Kind::Disk;
  shape.radius_ = radius;
  shape.centre_ = centre;
  shape.finish();
  return shape;
}

PatchShape PatchShape::polygon(std::vector<Vec2> vertices) {
  if (vertices.size() < 3) {
    throw Error("polygon needs at least 3 vertices: got " + std::to_string(vertices.size()));
  }
  double scale = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    // (the name is built only for the message: a shape rebuild in the
    // Bullet layer passes here for every vertex of every patch)
    if (!vertices[i].allFinite())
      internal::requireFinite(vertices[i], ("polygon vertex " + std::to_string(i)).c_str());
    scale = std::max(scale, vertices[i].cwiseAbs().maxCoeff());
  }
  // repeated vertices
  const double kSameVertex = 1e-12 * std::max(scale, 1e-300);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::size_t j = (i + 1) % vertices.size();
    if ((vertices[i] - vertices[j]).norm() <= kSameVertex) {
      throw Error("polygon has repeated vertex " + std::to_string(j) + " (same as vertex " +
                  std::to_string(i) + ")");
    }
  }
  // signed area (clockwise / zero area)
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    twiceArea += cross(vertices[i], vertices[(i + 1) % vertices.size()]);
  const double diameter = largestDistance(vertices);
  // relative zero-area threshold: area below 1e-12 of the diameter squared
  if (std::abs(twiceArea) <= 2e-12 * diameter * diameter) {
    throw Error("polygon has zero area (degenerate or collinear vertices)");
  }
  if (twiceArea < 0.0) {
    throw Error("polygon vertices are clockwise: give them counter-clockwise");
  }
  // drop collinear vertices, then require strictly left turns (convexity)
  const double kCollinear = 1e-12;
  std::vector<Vec2> kept;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = vertices[(i + n - 1) % n];
    const Vec2& cur = vertices[i];
    const Vec2& next = vertices[(i + 1) % n];
    const Vec2 e1 = cur - prev, e2 = next - cur;
    const double turn = cross(e1, e2) / (e1.norm() * e2.norm());
    if (std::abs(turn) <= kCollinear && e1.dot(e2) > 0.0) continue;  // collinear, straight on
    if (turn <= kCollinear) {
      throw Error("polygon is not convex (turns right or folds back at vertex " +
                  std::to_string(i) + ")");
    }
    kept.push_back(cur);
  }
  // all left turns: the total turning must be one full turn (rules out stars)
  double turning = 0.0;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Vec2 e1 = kept[i] - kept[(i + kept.size() - 1) % kept.size()];
    const Vec2 e2 = kept[(i + 1) % kept.size()] - kept[i];
    turning += std::atan2(cross(e1, e2), e1.dot(e2));
  }
  if (kept.size() < 3 || std::abs(turning - 2.0 * kPi) > 1e-6) {
    throw Error("polygon is not convex (self-intersecting, total turning " +
                formatDouble(turning / (2.0 * kPi)) + " turns)");
  }
  PatchShape shape;
  shape.kind_ = Kind::Polygon;
  shape.vertices_ = std::move(kept);
  shape.finish();
  return shape;
}

PatchShape PatchShape::rectangle(double lx, double ly, const Vec2& centre, double angle) {
  internal::requirePositive(lx, "rectangle side LX");
  internal::requirePositive(ly, "rectangle side LY");
  internal::requireFinite(centre, "rectangle centre");
  internal::requireFinite(angle, "rectangle angle");
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> v;
  const double hx = lx / 2.0, hy = ly / 2.0;
  for (const Vec2& corner : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}) {
    v.emplace_back(centre.x() + c * corner.x() - s * corner.y(),
                   centre.y() + s * corner.x() + c * corner.y());
  }
  return polygon(std::move(v));
}

PatchShape PatchShape::regularPolygon(int n, double circumradius, const Vec2& centre,
                                      double angle) {
  if (n < 3) throw Error("regular polygon needs n >= 3: got " + std::to_string(n));
  internal::requirePositive(circumradius, "regular polygon circumradius");
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    const double a = angle + 2.0 * kPi * i / n;
    v.emplace_back(centre.x() + circumradius * std::cos(a),
                   centre.y() + circumradius * std::sin(a));
  }
  return polygon(std::move(v));
}

void PatchShape::throwNotA(const char* what) {
  throw Error(what);
}

const std::vector<Vec2>& PatchShape::vertices() const {
  if (kind_ != Kind::Polygon) throw Error("vertices() asked of a patch that is not a polygon");
  return vertices_;
}

void PatchShape::finish() {
  // extent first: refuse what cannot be represented before any integral
  if (kind_ == Kind::Disk) {
    max_distance_ = centre_.norm() + radius_;
    diameter_ = 2.0 * radius_;
  } else if (kind_ == Kind::ArcRegion) {
    max_distance_ = internal::arcRegionMaxDistance(boundary_);
    diameter_ = internal::arcRegionDiameter(boundary_);
  } else {
    max_distance_ = 0.0;
    for (const Vec2& v : vertices_) max_distance_ = std::max(max_distance_, v.norm());
    diameter_ = largestDistance(vertices_);
  }
  // a linear pressure about O, p0 + cx x + cy y, loses (distance / size)^2
  // digits to cancellation on the patch (Eq. (94) has that condition): far
  // beyond kMaxOffset diameters nothing is left of Pi (found by fuzzing)
  constexpr double kMaxOffset = 1e4;
  if (!(max_distance_ <= kMaxOffset * diameter_)) {
    throw Error("patch too small for its distance from O: diameter " + formatDouble(diameter_) +
                " m, farthest point " + formatDouble(max_distance_) +
                " m from O (at most 1e4 diameters); put O near the patch");
  }
  // the moments reach |r|^5 and the inverse 1/|r|^4: sizes beyond ~1e60 m
  // or below ~1e-75 m over- or underflow double
  // (`complete` false: only the closed-form rows, no 1/r moments, no rho)
  auto takeTable = [&](const MomentTable& table, bool complete) {
    table_ = table;
    const auto& m = table_.m;
    moments_.area = m(MomentTable::kOne, 0);
    moments_.first = Vec2(m(MomentTable::kOne, 1), m(MomentTable::kOne, 2));
    moments_.xx = m(MomentTable::kX, 1);
    moments_.xy = m(MomentTable::kX, 2);
    moments_.yy = m(MomentTable::kY, 2);
    // G is SPD for any patch of positive area (Gram matrix of 1, x, y)
    if (loads_about_mean_) {
      // G^-1 = U^T G'^-1 U with U = [[1, 0, 0], [-g_x, 1, 0], [-g_y, 0, 1]]
      // (G = U^-1 G' U^-T), as a matrix for loadMatrixInverse(); solves go
      // through solveLoadMatrix, which applies the factors
      Mat3 U = Mat3::Identity();
      U(1, 0) = -load_origin_.x();
      U(2, 0) = -load_origin_.y();
      load_inverse_ = U.transpose() * local_load_inverse_ * U;
    } else {
      load_inverse_ = moments_.loadMatrix().inverse();
    }
    if (!table_.m.allFinite() || !(moments_.area > 0.0) || !load_inverse_.allFinite() ||
        !local_load_inverse_.allFinite() || !std::isfinite(max_distance_) ||
        !std::isfinite(diameter_) || !(!complete || defaultRho() > 0.0)) {
      throw Error("patch size out of range: its area moments over- or underflow double (diameter " +
                  formatDouble(diameter_) + " m, farthest point " + formatDouble(max_distance_) +
                  " m from O)");
    }
  };
  if (kind_ == Kind::Disk) {
    // the closed-form rows first: a disk out of range is refused before the
    // quadrature, which on its underflowing integrand would spend its whole
    // split budget first (0.25 s per refused R = 1e-105 disk; fuzz finding)
    takeTable(internal::diskPolynomialMoments(centre_, radius_), false);
    takeTable(internal::diskMomentTable(centre_, radius_), true);
  } else if (kind_ == Kind::ArcRegion) {
    // the polynomial rows about the start points' mean g where O lies
    // outside the patch (as for polygons), shifted to O
    loads_about_mean_ = max_distance_ > diameter_;
    load_origin_ = internal::startPointMean(boundary_);
    const AreaMoments local = internal::areaMomentsAbout(boundary_, load_origin_);
    if (loads_about_mean_) local_load_inverse_ = local.loadMatrix().inverse();
    MomentTable table = internal::arcRegionPolynomialRows(boundary_);
    takeTable(table, false);
    // rows with r: the exact law at pure spin about O, rho = the diameter
    internal::setArcRegionRRows(boundary_, diameter_, table);
    takeTable(table, true);
  } else {
    // the polynomial rows about the vertex mean where O lies outside the
    // patch (max|r| > diameter); about O itself they round to ~eps max|r|^2
    // / A <= eps diameter^2 / A there, a sliver's own round-off, and a patch
    // expressed about a point inside it (Bullet's: its centroid) keeps the
    // sums it always had
    loads_about_mean_ = max_distance_ > diameter_;
    // and the rows with r by quadrature about it where O is far (item 65)
    const bool farRows = max_distance_ > internal::kFarRowsOffset * diameter_;
    const MomentTable table = internal::polygonMomentTable(vertices_, loads_about_mean_, farRows,
                                                           local_load_inverse_, load_origin_);
    takeTable(table, true);
  }
}

Vec3 PatchShape::solveLoadMatrix(const Vec3& rhs) const {
  if (!loads_about_mean_) return load_inverse_ * rhs;
  // rhs about g (the moments of p shifted: ∫x' p = ∫x p - g_x Pz), G'^-1,
  // then p0 = p0' - g_x cx - g_y cy: the coefficients about O stay
  // consistent with each other, where G^-1 rhs as one matrix product
  // rounds them independently, each by eps (max|r| / size)^2 of the
  // pressure on the patch
  // (at unit scale, a power of two: g_x Pz and G'^-1 rhs' overflowed for
  // loads ~1e300 whose pressure is in range; found by fuzzing)
  const double largest = rhs.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return load_inverse_ * rhs;  // zero (or not finite)
  const int e = std::ilogb(largest);
  const Vec3 unit = rhs.unaryExpr([e](double x) { return std::ldexp(x, -e); });
  const Vec2& g = load_origin_;
  const Vec3 local =
      local_load_inverse_ * Vec3(unit[0], unit[1] - g.x() * unit[0], unit[2] - g.y() * unit[0]);
  const Vec3 c(local[0] - (g.x() * local[1] + g.y() * local[2]), local[1], local[2]);
  return c.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

bool PatchShape::contains(const Vec2& point, double tol) const {
  if (kind_ == Kind::Disk) return (point - centre_).norm() <= radius_ + tol;
  if (kind_ == Kind::ArcRegion) return internal::arcRegionContains(boundary_, point, tol);
  // edge by edge (no modulo, and an edge's length only where the point is
  // on its outer side: the Bullet layer tests every visit's centre of
  // pressure, nearly always inside)
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0, prev = n - 1; i < n; prev = i++) {
    const Vec2 e = vertices_[i] - vertices_[prev];
    const double c = cross(e, point - vertices_[prev]);
    if (c < 0.0 && c < -tol * e.norm()) return false;
  }
  return true;
}

PatchShape PatchShape::inFrame(const Vec2& newOrigin, double angle) const {
  internal::requireFinite(newOrigin, "new origin");
  internal::requireFinite(angle, "frame angle");
  const double c = std::cos(angle), s = std::sin(angle);
  auto map = [&](const Vec2& p) {
    const Vec2 q = p - newOrigin;
    return Vec2(c * q.x() + s * q.y(), -s * q.x() + c * q.y());
  };
  if (kind_ == Kind::Disk) return disk(radius_, map(centre_));
  if (kind_ == Kind::ArcRegion) {
    std::vector<BoundaryPiece> mapped = boundary_;
    for (BoundaryPiece& p : mapped) {
      p.a = map(p.a), p.b = map(p.b), p.centre = map(p.centre);
      p.angle0 -= angle, p.angle1 -= angle;
    }
    return arcRegion(std::move(mapped));
  }
  std::vector<Vec2> v;
  for (const Vec2& p : vertices_) v.push_back(map(p));
  return polygon(std::move(v));
}

std::string PatchShape::describe() const {
  std::ostringstream out;
  if (kind_ == Kind::Disk) {
    out << "disk R=" << radius_ << " m centred at (" << centre_.x() << ", " << centre_.y() << ")";
  } else if (kind_ == Kind::ArcRegion) {
    std::size_t arcs = 0;
    for (const BoundaryPiece& p : boundary_) arcs += p.kind == BoundaryPiece::Kind::Arc ? 1 : 0;
    out << "region of " << boundary_.size() << " pieces (" << arcs << " arcs)";
  } else {
    out << vertices_.size() << "-gon";
  }
  out << ", area " << moments_.area << " m^2, rho(11) " << defaultRho() << " m";
  return out.str();
}

}  // namespace patchspin
