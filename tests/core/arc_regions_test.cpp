// Arc regions (arc_regions.cpp, PatchShape::arcRegion): the exact boundaries
// of disk ∩ polygon and disk ∩ disk against sampled geometry, their area
// moments against brute-force quadrature and the 4096-gon limit, and the
// ArcRegion shape's moment table, extents and validation.
#include <patchspin/geometry.hpp>

#include <gtest/gtest.h>

#include "arc_region_quadrature.hpp"
#include "clip_polygon.hpp"
#include "error_matchers.hpp"
#include "gauss_legendre_long.hpp"

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::exact_arc::Region;
namespace aq = testing::arc_region;

std::vector<Vec2> square(const Vec2& c, double half) {
  return {c + Vec2(-half, -half), c + Vec2(half, -half), c + Vec2(half, half),
          c + Vec2(-half, half)};
}

struct DiskPolygonCase {
  std::string name;
  Vec2 centre;
  double radius;
  std::vector<Vec2> polygon;
};

// A coin of radius 2 cm over a box face's edge (its centre 0.5 R inside the
// edge), over a corner, wholly inside, around a small triangle, a thin
// sliver, beside it.
std::vector<DiskPolygonCase> diskPolygonCases() {
  const double R = 0.02;
  return {
      {"coin over an edge at 0.5 R", Vec2(0.1 - 0.5 * R, 0.03), R, square(Vec2::Zero(), 0.1)},
      {"coin over a corner", Vec2(0.095, 0.092), R, square(Vec2::Zero(), 0.1)},
      {"coin inside", Vec2(0.01, 0.02), R, square(Vec2::Zero(), 0.1)},
      {"triangle inside the coin",
       Vec2(0.001, 0.0),
       R,
       {Vec2(-0.01, -0.01), Vec2(0.012, -0.008), Vec2(0.0, 0.011)}},
      {"triangle crossing the rim",
       Vec2(0.0, 0.0),
       R,
       {Vec2(-0.01, -0.01), Vec2(0.03, -0.005), Vec2(0.0, 0.025)}},
      {"thin cut, 0.05 R deep", Vec2(0.1 + 0.95 * R, 0.0), R, square(Vec2::Zero(), 0.1)},
  };
}

// in the region iff in both (away from their boundaries by 1e-9 R)
void expectSameSet(const Region& region, const std::function<double(const Vec2&)>& signedDepth,
                   const Vec2& lo, const Vec2& hi, double R, const std::string& name) {
  int checked = 0;
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 200; ++j) {
      const Vec2 p(lo.x() + (hi.x() - lo.x()) * (i + 0.37) / 201.0,
                   lo.y() + (hi.y() - lo.y()) * (j + 0.61) / 201.0);
      const double depth = signedDepth(p);  // > 0 inside both
      if (std::abs(depth) <= 1e-9 * R) continue;
      ++checked;
      ASSERT_EQ(aq::insideByChords(region, p), depth > 0.0)
          << name << " at (" << p.x() << ", " << p.y() << ")";
    }
  }
  EXPECT_GT(checked, 30000) << name;
}

double polygonDepth(const std::vector<Vec2>& poly, const Vec2& p) {
  double d = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], e = poly[(i + 1) % poly.size()] - a;
    d = std::min(d, (e.x() * (p - a).y() - e.y() * (p - a).x()) / e.norm());
  }
  return d;
}

TEST(ArcRegions, DiskPolygonIntersectionIsTheSampledSet) {
  for (const DiskPolygonCase& c : diskPolygonCases()) {
    const Region region = diskPolygonIntersection(c.centre, c.radius, c.polygon);
    ASSERT_FALSE(region.empty()) << c.name;
    auto depth = [&](const Vec2& p) {
      return std::min(c.radius - (p - c.centre).norm(), polygonDepth(c.polygon, p));
    };
    expectSameSet(region, depth, c.centre - Vec2(1.2, 1.2) * c.radius,
                  c.centre + Vec2(1.2, 1.2) * c.radius, c.radius, c.name);
    // (and a valid shape)
    EXPECT_NO_THROW(PatchShape::arcRegion(region)) << c.name;
  }
  // the documented special cases: one full arc, only segments, nothing
  EXPECT_EQ(diskPolygonIntersection(Vec2(0.01, 0.02), 0.02, square(Vec2::Zero(), 0.1)).size(), 1u);
  const Region inner = diskPolygonIntersection(Vec2::Zero(), 1.0, square(Vec2::Zero(), 0.5));
  ASSERT_EQ(inner.size(), 4u);
  for (const BoundaryPiece& p : inner) EXPECT_EQ(p.kind, BoundaryPiece::Kind::Segment);
  EXPECT_TRUE(diskPolygonIntersection(Vec2(3.0, 0.0), 1.0, square(Vec2::Zero(), 0.5)).empty());
}

TEST(ArcRegions, DiskDiskIntersectionIsTheSampledSet) {
  struct Case {
    Vec2 c1;
    double r1;
    Vec2 c2;
    double r2;
  };
  for (const Case& c : {Case{Vec2(0, 0), 0.02, Vec2(0.025, 0.01), 0.02},
                        Case{Vec2(0, 0), 0.02, Vec2(0.012, -0.015), 0.03},
                        Case{Vec2(0.1, 0.2), 0.02, Vec2(0.105, 0.2), 0.005},
                        Case{Vec2(0, 0), 0.02, Vec2(0.039, 0.0), 0.02}}) {
    const Region region = diskDiskIntersection(c.c1, c.r1, c.c2, c.r2);
    ASSERT_FALSE(region.empty());
    auto depth = [&](const Vec2& p) {
      return std::min(c.r1 - (p - c.c1).norm(), c.r2 - (p - c.c2).norm());
    };
    expectSameSet(region, depth, c.c1 - Vec2(1.5, 1.5) * c.r1, c.c1 + Vec2(1.5, 1.5) * c.r1, c.r1,
                  "lens");
  }
  EXPECT_EQ(diskDiskIntersection(Vec2(0, 0), 1.0, Vec2(0.2, 0), 0.5).size(), 1u);
  EXPECT_TRUE(diskDiskIntersection(Vec2(0, 0), 1.0, Vec2(2.5, 0), 0.5).empty());
}

std::vector<std::pair<std::string, Region>> testRegions() {
  std::vector<std::pair<std::string, Region>> out;
  for (const DiskPolygonCase& c : diskPolygonCases()) {
    const Region r = diskPolygonIntersection(c.centre, c.radius, c.polygon);
    bool arc = false;
    for (const BoundaryPiece& p : r) arc = arc || p.kind == BoundaryPiece::Kind::Arc;
    if (r.size() > 1 && arc) out.push_back({c.name, r});
  }
  out.push_back({"lens", diskDiskIntersection(Vec2(0, 0), 0.02, Vec2(0.025, 0.01), 0.02)});
  out.push_back(
      {"unequal lens", diskDiskIntersection(Vec2(0, 0), 0.02, Vec2(0.012, -0.015), 0.03)});
  // half-angle 0.14: its segments' closed forms cancel by ~a^-2 = 50
  out.push_back({"thin lens", diskDiskIntersection(Vec2(0, 0), 0.02, Vec2(0.0396, 0.0), 0.02)});
  // about their centroid (the Bullet layer's frame) and 3 diameters away
  const Region lensAtO =
      diskDiskIntersection(Vec2(-0.0125, -0.005), 0.02, Vec2(0.0125, 0.005), 0.02);
  out.push_back({"lens about its centroid", lensAtO});
  Region far = lensAtO;
  for (BoundaryPiece& p : far) p.centre += Vec2(0.06, 0.03), p.a += Vec2(0.06, 0.03);
  out.push_back({"lens 3 diameters from O", far});
  return out;
}

// Area moments against brute force (tolerance 1e-12 of A max|r|^k: the
// oracle's own 1e-13 plus the closed forms' few ulps times the
// cancellation of a flat arc's segment, ~a^-2 eps with a >= 0.3 here)
TEST(ArcRegions, AreaMomentsMatchQuadrature) {
  constexpr double kTol = 1e-12;
  for (const auto& [name, region] : testRegions()) {
    const Eigen::Matrix<double, 6, 3> ref = aq::momentTable(region);
    const AreaMoments m = areaMomentsOf(region);
    double rmax = 0.0;
    for (const Vec2& p : testing::exact_arc::boundarySamples(region))
      rmax = std::max(rmax, p.norm());
    const double A = ref(0, 0);
    EXPECT_NEAR(m.area, A, kTol * A) << name;
    EXPECT_NEAR(m.first.x(), ref(0, 1), kTol * A * rmax) << name;
    EXPECT_NEAR(m.first.y(), ref(0, 2), kTol * A * rmax) << name;
    EXPECT_NEAR(m.xx, ref(1, 1), kTol * A * rmax * rmax) << name;
    EXPECT_NEAR(m.xy, ref(1, 2), kTol * A * rmax * rmax) << name;
    EXPECT_NEAR(m.yy, ref(2, 2), kTol * A * rmax * rmax) << name;
  }
}

using patchspin::testing::gaussLegendreLong;

// The circular segment of radius R and half-angle a (the arc from -a to a
// of the circle about (-R cos a, 0), closed by its chord on the y axis; the
// chord's midpoint at O): its area, ∫x, ∫x^2, ∫y^2 against a 32-node
// Gauss-Legendre rule in long double over theta in [-a, a] of the slices
// x in [0, R (cos theta - cos a)], dy = R cos theta dtheta, with cos theta -
// cos a = 2 sin((a - theta)/2) sin((a + theta)/2) (no cancellation; the
// integrands are entire, the rule exact to long double's rounding for a <=
// 3). Asserted: 1e-14 relative for a from 1e-12 to 3 (the closed forms alone
// cancel to ~eps / a^2 of the area and eps / a^6 of ∫x^2: all at a = 5e-10;
// the series below a = 1 and the closed forms above stay within 2e-15 by
// measurement); ∫y, ∫xy zero by symmetry (to 1e-14 of A R, A R^2).
TEST(ArcRegions, CircularSegmentMomentsMatchReference) {
  constexpr double kTol = 1e-14;
  std::vector<long double> gx, gw;
  gaussLegendreLong(32, gx, gw);
  const double R = 0.7;
  for (double a = 1e-12; a <= 3.0; a *= 1.7) {
    long double A = 0.0L, sx = 0.0L, ixx = 0.0L, iyy = 0.0L;
    const long double al = a, Rl = R;
    for (std::size_t i = 0; i < gx.size(); ++i) {
      const long double t = al * gx[i], wt = al * gw[i];
      const long double h = 2.0L * std::sin(0.5L * (al - t)) * std::sin(0.5L * (al + t));
      const long double dy = Rl * std::cos(t) * wt, y = Rl * std::sin(t), x = Rl * h;
      A += x * dy, sx += 0.5L * x * x * dy, ixx += x * x * x / 3.0L * dy, iyy += y * y * x * dy;
    }
    const Region cap = {BoundaryPiece::arc(Vec2(-R * std::cos(a), 0.0), R, -a, a),
                        BoundaryPiece::segment(Vec2::Zero(), Vec2::Zero())};
    Region region = cap;
    region[1] = BoundaryPiece::segment(cap[0].end(), cap[0].start());
    ASSERT_EQ(0.5 * (region[0].start() + region[0].end()), Vec2::Zero()) << a;
    const AreaMoments m = areaMomentsOf(region);
    const std::string at = "a = " + std::to_string(a);
    EXPECT_NEAR(m.area, static_cast<double>(A), kTol * static_cast<double>(A)) << at;
    EXPECT_NEAR(m.first.x(), static_cast<double>(sx), kTol * static_cast<double>(sx)) << at;
    EXPECT_NEAR(m.xx, static_cast<double>(ixx), kTol * static_cast<double>(ixx)) << at;
    EXPECT_NEAR(m.yy, static_cast<double>(iyy), kTol * static_cast<double>(iyy)) << at;
    EXPECT_NEAR(m.first.y(), 0.0, kTol * static_cast<double>(A) * R) << at;
    EXPECT_NEAR(m.xy, 0.0, kTol * static_cast<double>(A) * R * R) << at;
  }
}

using testing::clipPolygon;

// The n-gon limit: the disk as a regular n-gon clipped by the polygon. The
// n-gon misses a circular segment of area R^2 (h - sin(h) cos(h)) ~ 2/3 R^2
// h^3 per side (h = pi / n), R^2 span (2 pi / n)^2 / 12 along an arc of
// span `span`: the moments converge as n^-2; asserted: the error of the
// area within 1.2 times that prediction (the cut points do not fall on the
// n-gon's vertices) and the ratio of the errors at n and 2n 4 +- 10 %
// (Richardson), the second moments to the same relative bound.
TEST(ArcRegions, AreaMomentsAreThePolygonLimit) {
  for (const DiskPolygonCase& c : diskPolygonCases()) {
    const Region region = diskPolygonIntersection(c.centre, c.radius, c.polygon);
    const AreaMoments m = areaMomentsOf(region);
    double arcSpan = 0.0;
    for (const BoundaryPiece& p : region)
      if (p.kind == BoundaryPiece::Kind::Arc) arcSpan += p.angle1 - p.angle0;
    if (arcSpan == 0.0) continue;
    double previous = 0.0;
    for (int n : {1024, 2048, 4096}) {
      std::vector<Vec2> ngon;
      for (int i = 0; i < n; ++i) {
        const double t = 2.0 * M_PI * i / n;
        ngon.push_back(c.centre + c.radius * Vec2(std::cos(t), std::sin(t)));
      }
      const PatchShape p = PatchShape::polygon(clipPolygon(ngon, c.polygon));
      const double h = 2.0 * M_PI / n;
      const double predicted = c.radius * c.radius * arcSpan * h * h / 12.0 / m.area;
      const double err = std::abs(p.area() - m.area) / m.area;
      EXPECT_LT(err, 1.2 * predicted) << c.name << " n = " << n;
      if (previous > 0.0) {
        EXPECT_NEAR(previous / err, 4.0, 0.4) << c.name;
      }
      previous = err;
      const double s = m.area * (c.radius + c.centre.norm()) * (c.radius + c.centre.norm());
      EXPECT_NEAR(p.areaMoments().xx, m.xx, 1.2 * predicted * s) << c.name;
      EXPECT_NEAR(p.areaMoments().yy, m.yy, 1.2 * predicted * s) << c.name;
      EXPECT_NEAR(p.areaMoments().xy, m.xy, 1.2 * predicted * s) << c.name;
    }
  }
}

// The shape's moment table against brute force (1e-10 of A max|f| max|phi|)
TEST(ArcRegions, MomentTableMatchesQuadrature) {
  constexpr double kTol = 1e-10;
  for (const auto& [name, region] : testRegions()) {
    const PatchShape shape = PatchShape::arcRegion(region);
    ASSERT_EQ(shape.kind(), PatchShape::Kind::ArcRegion) << name;
    const Eigen::Matrix<double, 6, 3> ref = aq::momentTable(region);
    const double rmax = shape.maxDistanceFromOrigin();
    for (int f = 0; f < 6; ++f) {
      const double fmax = (f == 0 || f >= 4) ? 1.0 : rmax;
      for (int k = 0; k < 3; ++k) {
        const double scale = shape.area() * fmax * (k == 0 ? 1.0 : rmax);
        EXPECT_NEAR(shape.momentTable().m(f, k), ref(f, k), kTol * scale)
            << name << " row " << f << " column " << k;
      }
    }
  }
}

// Extents against dense boundary samples, contains against the chords.
TEST(ArcRegions, ExtentsAndContains) {
  for (const auto& [name, region] : testRegions()) {
    const PatchShape shape = PatchShape::arcRegion(region);
    const std::vector<Vec2> pts = testing::exact_arc::boundarySamples(region, 1000);
    double rmax = 0.0, diam = 0.0;
    for (const Vec2& p : pts) rmax = std::max(rmax, p.norm());
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j)
        diam = std::max(diam, (pts[i] - pts[j]).norm());
    // (1000 samples per piece, its ends included: a maximum between two
    // samples is missed by at most R (span / 1000)^2 / 8 < 1e-5 R)
    EXPECT_GE(shape.maxDistanceFromOrigin(), rmax * (1.0 - 1e-12)) << name;
    EXPECT_LE(shape.maxDistanceFromOrigin(), rmax * (1.0 + 1e-6)) << name;
    EXPECT_GE(shape.diameter(), diam * (1.0 - 1e-12)) << name;
    EXPECT_LE(shape.diameter(), diam * (1.0 + 1e-5)) << name;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.2, 1.2);
    const Vec2 g = shape.centroid();
    for (int i = 0; i < 4000; ++i) {
      const Vec2 p = g + shape.diameter() * Vec2(u(rng), u(rng));
      const bool inside = aq::insideByChords(region, p);
      // (away from the boundary by 1e-9 of the size)
      if (shape.contains(p, 1e-9 * shape.diameter()) != shape.contains(p, -1e-9 * shape.diameter()))
        continue;
      EXPECT_EQ(shape.contains(p), inside) << name << " at " << p.transpose();
    }
  }
}

TEST(ArcRegions, NormalisesAndValidates) {
  // a full arc is a disk; segments only a polygon
  const PatchShape d =
      PatchShape::arcRegion({BoundaryPiece::arc(Vec2(1, 2), 0.5, 0.3, 0.3 + 2 * M_PI)});
  EXPECT_EQ(d.kind(), PatchShape::Kind::Disk);
  EXPECT_EQ(d.radius(), 0.5);
  const PatchShape p =
      PatchShape::arcRegion(diskPolygonIntersection(Vec2::Zero(), 1.0, square(Vec2::Zero(), 0.5)));
  EXPECT_EQ(p.kind(), PatchShape::Kind::Polygon);
  EXPECT_EQ(p.vertices().size(), 4u);
  // a piece of rounding length is dropped
  Region seg = testing::exact_arc::diskSegment(Vec2::Zero(), 1.0, 0.0, 0.5);
  seg.insert(seg.begin() + 1, BoundaryPiece::segment(seg[0].end(), seg[0].end() + Vec2(1e-15, 0)));
  EXPECT_EQ(PatchShape::arcRegion(seg).boundary().size(), 2u);
  // errors naming the problem
  using testing::throwsNaming;
  EXPECT_TRUE(throwsNaming([] { PatchShape::arcRegion({}); }, {"no boundary pieces"}));
  Region open = testing::exact_arc::diskSegment(Vec2::Zero(), 1.0, 0.0, 0.5);
  open[1].a += Vec2(0.01, 0.0);
  EXPECT_TRUE(throwsNaming([&] { PatchShape::arcRegion(open); }, {"not closed"}));
  Region nan = testing::exact_arc::diskSegment(Vec2::Zero(), 1.0, 0.0, 0.5);
  nan[0].radius = NAN;
  EXPECT_TRUE(throwsNaming([&] { PatchShape::arcRegion(nan); }, {"finite"}));
  // two overlapping disks' outer boundary (a peanut): right turns where the
  // arcs meet
  const Region peanut = {BoundaryPiece::arc(Vec2(-0.5, 0), 1.0, M_PI / 3, 5 * M_PI / 3),
                         BoundaryPiece::arc(Vec2(0.5, 0), 1.0, -2 * M_PI / 3, 2 * M_PI / 3)};
  EXPECT_TRUE(throwsNaming([&] { PatchShape::arcRegion(peanut); }, {"not convex"}));
  Region clockwise = {BoundaryPiece::segment(Vec2(0, 0), Vec2(0, 1)),
                      BoundaryPiece::segment(Vec2(0, 1), Vec2(1, 0)),
                      BoundaryPiece::segment(Vec2(1, 0), Vec2(0, 0))};
  EXPECT_TRUE(throwsNaming([&] { PatchShape::arcRegion(clockwise); }, {"clockwise"}));
  Region backwards = open;
  backwards[0].angle1 = backwards[0].angle0 - 0.1;
  EXPECT_TRUE(throwsNaming([&] { PatchShape::arcRegion(backwards); }, {"angles must increase"}));
  // asking the wrong kind
  EXPECT_THROW(d.boundary(), Error);
  EXPECT_THROW(PatchShape::arcRegion(testRegions()[0].second).vertices(), Error);
}

TEST(ArcRegions, InFrameMovesTheRegion) {
  const Region region = testRegions()[0].second;
  const PatchShape shape = PatchShape::arcRegion(region);
  const Vec2 o(0.03, -0.01);
  const double angle = 0.7;
  const PatchShape moved = shape.inFrame(o, angle);
  ASSERT_EQ(moved.kind(), PatchShape::Kind::ArcRegion);
  EXPECT_NEAR(moved.area(), shape.area(), 1e-14 * shape.area());
  const Vec2 q = shape.centroid() - o;
  const Vec2 expected(std::cos(angle) * q.x() + std::sin(angle) * q.y(),
                      -std::sin(angle) * q.x() + std::cos(angle) * q.y());
  EXPECT_NEAR((moved.centroid() - expected).norm(), 0.0, 1e-14 * shape.diameter());
  EXPECT_NE(moved.describe().find("arcs"), std::string::npos);
}

}  // namespace
}  // namespace patchspin

namespace patchspin {
namespace {

// O 100 diameters from a lens: the table against quadrature (1e-10 of A
// max|f| max|phi| as above; the rows with r come from the far branch of the
// exact law), and Eq. (94) solved about the start points' mean: the loads of
// the solved pressure give back the loads (1e-12 of Pz max|r|).
TEST(ArcRegions, FarOrigin) {
  Region lens = diskDiskIntersection(Vec2(-0.0125, -0.005), 0.02, Vec2(0.0125, 0.005), 0.02);
  const Vec2 shift(2.4, -1.8);  // |shift| = 3 m, ~100 diameters
  for (BoundaryPiece& p : lens) p.a += shift, p.b += shift, p.centre += shift;
  const PatchShape shape = PatchShape::arcRegion(lens);
  const Eigen::Matrix<double, 6, 3> ref = aq::momentTable(lens);
  const double rmax = shape.maxDistanceFromOrigin();
  for (int f = 0; f < 6; ++f) {
    const double fmax = (f == 0 || f >= 4) ? 1.0 : rmax;
    for (int k = 0; k < 3; ++k) {
      const double scale = shape.area() * fmax * (k == 0 ? 1.0 : rmax);
      EXPECT_NEAR(shape.momentTable().m(f, k), ref(f, k), 1e-10 * scale) << f << " " << k;
    }
  }
  const Vec3 rhs(10.0, 10.0 * (shift.x() + 0.001), 10.0 * (shift.y() - 0.002));  // (Pz, Ty, -Tx)
  const Vec3 c = shape.solveLoadMatrix(rhs);
  const Vec3 back = shape.areaMoments().loadMatrix() * c;
  EXPECT_LT((back - rhs).norm(), 1e-12 * 10.0 * rmax);
}

}  // namespace
}  // namespace patchspin
