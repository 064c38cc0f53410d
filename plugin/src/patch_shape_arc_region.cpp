// PatchShape's arc regions (Kind::ArcRegion): the checks of
// PatchShape::arcRegion and the region's moment table of Eq. (36). Its
// polynomial rows by Green's theorem (areaMomentsOf, arc_regions.cpp); its
// rows with r from the exact law at pure spin about O, Eq. (39):
// k = (-y/r, x/r, r/rho), so F = ∫ phi (-y/r, x/r, r/rho) dA; checked
// against brute-force quadrature in arc_regions_test.cpp.
#include <patchspin/geometry.hpp>

#include "arc_region_numerics.hpp"
#include "moment_tables.hpp"
#include "planar.hpp"

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace patchspin {

using internal::cross;
using internal::formatDouble;
using internal::kPi;

PatchShape PatchShape::arcRegion(std::vector<BoundaryPiece> boundary) {
  using Piece = BoundaryPiece;
  if (boundary.empty()) throw Error("arc region has no boundary pieces");
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const Piece& p = boundary[i];
    const std::string name = "arc region piece " + std::to_string(i);
    if (p.kind == Piece::Kind::Segment) {
      if (!p.a.allFinite() || !p.b.allFinite())
        throw Error(name + ": segment end points must be finite");
    } else {
      if (!p.centre.allFinite() || !std::isfinite(p.radius) || !std::isfinite(p.angle0) ||
          !std::isfinite(p.angle1))
        throw Error(name + ": arc centre, radius and angles must be finite");
      if (!(p.radius > 0.0)) throw Error(name + ": arc radius must be > 0");
      if (!(p.angle1 > p.angle0))
        throw Error(name + ": arc angles must increase (counter-clockwise, angle1 > angle0)");
      if (p.angle1 - p.angle0 > 2.0 * kPi * (1.0 + 1e-12))
        throw Error(name + ": arc spans more than a full turn");
    }
  }
  // the region's size: extent of the pieces' points about the first start
  const Vec2 s0 = boundary[0].start();
  double size = 0.0;
  for (const Piece& p : boundary) {
    size = std::max(size, (p.start() - s0).norm());
    if (p.kind == Piece::Kind::Arc)
      size = std::max(size, std::min(2.0, p.angle1 - p.angle0) * p.radius);
  }
  // pieces shorter than 1e-12 of it (rounding) are dropped
  const double kShortPiece = 1e-12 * size;
  auto length = [](const Piece& p) {
    return p.kind == Piece::Kind::Segment ? (p.b - p.a).norm() : p.radius * (p.angle1 - p.angle0);
  };
  std::vector<Piece> kept;
  for (const Piece& p : boundary)
    if (length(p) > kShortPiece) kept.push_back(p);
  if (kept.empty()) throw Error("arc region has zero area (every piece has zero length)");
  // a single full arc is a disk
  if (kept.size() == 1) {
    const Piece& p = kept[0];
    if (p.kind == Piece::Kind::Arc && p.angle1 - p.angle0 >= 2.0 * kPi * (1.0 - 1e-12))
      return disk(p.radius, p.centre);
    throw Error("arc region is not closed: a single piece that is not a full circle");
  }
  // closed: each piece ends where the next starts (to 1e-9 of the size)
  const std::size_t n = kept.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double gap = (kept[i].end() - kept[(i + 1) % n].start()).norm();
    if (!(gap <= 1e-9 * size)) {
      throw Error("arc region is not closed: piece " + std::to_string(i) + " ends " +
                  formatDouble(gap) + " m from where piece " + std::to_string((i + 1) % n) +
                  " starts");
    }
  }
  // segments join their neighbouring arcs' end points exactly
  for (std::size_t i = 0; i < n; ++i) {
    Piece& p = kept[i];
    if (p.kind != Piece::Kind::Segment) continue;
    const Piece& prev = kept[(i + n - 1) % n];
    const Piece& next = kept[(i + 1) % n];
    if (prev.kind == Piece::Kind::Arc) p.a = prev.end();
    if (next.kind == Piece::Kind::Arc) p.b = next.start();
  }
  bool anyArc = false;
  for (const Piece& p : kept) anyArc = anyArc || p.kind == Piece::Kind::Arc;
  if (!anyArc) {
    std::vector<Vec2> v;
    for (const Piece& p : kept) v.push_back(p.a);
    return polygon(std::move(v));
  }
  // orientation and area
  const AreaMoments m = internal::areaMomentsAbout(kept, internal::startPointMean(kept));
  if (std::abs(m.area) <= 1e-12 * size * size)
    throw Error("arc region has zero area (degenerate pieces)");
  if (m.area < 0.0) throw Error("arc region is clockwise: give its pieces counter-clockwise");
  // convexity: turning >= 0 at every joint, arcs bulge outward (they turn
  // left by their span), and one full turn in all
  auto tangentIn = [](const Piece& p) -> Vec2 {
    if (p.kind == Piece::Kind::Segment) return (p.b - p.a).normalized();
    return Vec2(-std::sin(p.angle0), std::cos(p.angle0));
  };
  auto tangentOut = [](const Piece& p) -> Vec2 {
    if (p.kind == Piece::Kind::Segment) return (p.b - p.a).normalized();
    return Vec2(-std::sin(p.angle1), std::cos(p.angle1));
  };
  constexpr double kTurnSlack = 1e-9;
  double turning = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 t1 = tangentOut(kept[i]), t2 = tangentIn(kept[(i + 1) % n]);
    const double turn = std::atan2(cross(t1, t2), t1.dot(t2));
    if (turn < -kTurnSlack || turn > kPi - kTurnSlack) {
      throw Error("arc region is not convex (turns right or folds back where piece " +
                  std::to_string((i + 1) % n) + " starts)");
    }
    turning += turn;
    if (kept[i].kind == Piece::Kind::Arc) turning += kept[i].angle1 - kept[i].angle0;
  }
  if (std::abs(turning - 2.0 * kPi) > 1e-6) {
    throw Error("arc region is not convex (self-intersecting, total turning " +
                formatDouble(turning / (2.0 * kPi)) + " turns)");
  }
  PatchShape shape;
  shape.kind_ = Kind::ArcRegion;
  shape.boundary_ = std::move(kept);
  shape.finish();
  return shape;
}

const std::vector<BoundaryPiece>& PatchShape::boundary() const {
  if (kind_ != Kind::ArcRegion)
    throw Error("boundary() asked of a patch that is not an arc region");
  return boundary_;
}

namespace internal {

MomentTable arcRegionPolynomialRows(const std::vector<BoundaryPiece>& boundary) {
  const AreaMoments about = areaMomentsOf(boundary);
  MomentTable table;
  auto& m = table.m;
  m(MomentTable::kOne, 0) = about.area;
  m(MomentTable::kOne, 1) = m(MomentTable::kX, 0) = about.first.x();
  m(MomentTable::kOne, 2) = m(MomentTable::kY, 0) = about.first.y();
  m(MomentTable::kX, 1) = about.xx;
  m(MomentTable::kX, 2) = m(MomentTable::kY, 1) = about.xy;
  m(MomentTable::kY, 2) = about.yy;
  return table;
}

void setArcRegionRRows(const std::vector<BoundaryPiece>& boundary, double rho, MomentTable& table) {
  // (file comment)
  auto& m = table.m;
  ExactBasis basis;
  exactArcRegionBasis(boundary, rho, Vec3(0.0, 0.0, 1.0), false, basis);
  for (int k = 0; k < 3; ++k) {
    m(MomentTable::kXOverR, k) = basis.F(1, k);
    m(MomentTable::kYOverR, k) = -basis.F(0, k);
    m(MomentTable::kR, k) = rho * basis.F(2, k);
  }
}

}  // namespace internal

}  // namespace patchspin
