// nearestAdmissibleLoads (admissible_loads.cpp): the projection of the scaled
// loads y = (Pz, Tx / rho, Ty / rho) onto the cone K of loads of pressures
// p >= 0, checked against a search by another method. K's boundary is the
// rays through the boundary of the kern (the centres of pressure of
// pressures >= 0); the kern's corners are the centres of pressure of the
// pressures that vanish on one side, here by brute-force quadrature (not
// from G); a disk's kern is the circle |cop - C| = R / 4, checked the same
// way. Dense sampling of those rays, golden-section refinement, and the
// apex give the nearest point.
#include <patchspin/pressure.hpp>

#include "convex_hull.hpp"
#include "oracle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>
#include <vector>

namespace patchspin {
namespace {

using testing::bruteForceIntegral;

constexpr double kPi = 3.14159265358979323846;
// The distance |y - p| is stationary at the projection, so the search's
// argument, located by golden section to ~sqrt(eps), costs it ~eps; the
// kern from quadrature (relTol 1e-13) and the core's G agree to ~1e-13.
constexpr double kDistanceRelTol = 1e-11;
// The nearest point itself is located by the search only to ~sqrt(eps) of
// the boundary parameter (times the lever of the scaled torques): points
// agree to 1e-6 of |y|, far below any solver's use and far above that error.
constexpr double kPointRelTol = 1e-6;
// KKT residuals of p (round-off of a few flops on O(|y|) values, and the
// quadrature kern's 1e-13): 1e-11 of |y|^2 or |y| |u|.
constexpr double kKktRelTol = 1e-11;
// Idempotence: p lies on K's boundary to round-off, so projecting it again
// moves it by round-off only.
constexpr double kIdempotenceRelTol = 1e-12;
constexpr double kOracleRelTol = 1e-13;

Vec3 scaled(const PatchLoads& l, double rho) {
  return Vec3(l.Pz, l.Tx / rho, l.Ty / rho);
}
// the ray of the loads with Pz = 1 and centre of pressure k: (Ty, -Tx) = k
Vec3 rayThrough(const Vec2& k, double rho) {
  return Vec3(1.0, -k.y() / rho, k.x() / rho);
}

// The kern: corners (polygons, counter-clockwise) or centre and radius.
struct Kern {
  std::vector<Vec2> corners;
  Vec2 centre = Vec2::Zero();
  double radius = 0.0;
};

Vec2 copByQuadrature(const PatchShape& shape, const testing::ScalarField& p) {
  const double Pz = bruteForceIntegral(shape, p, kOracleRelTol);
  const double mx = bruteForceIntegral(
      shape, [&](const Vec2& q) { return q.x() * p(q); }, kOracleRelTol);
  const double my = bruteForceIntegral(
      shape, [&](const Vec2& q) { return q.y() * p(q); }, kOracleRelTol);
  return Vec2(mx / Pz, my / Pz);
}

Kern kernOf(const PatchShape& shape) {
  Kern k;
  if (shape.isDisk()) {
    k.centre = shape.centre();
    k.radius = shape.radius() / 4.0;
    // the pressures R - (x - C).e vanish at C + R e: their centres of
    // pressure lie on the circle of radius R / 4 (I / (A R))
    for (int j = 0; j < 4; ++j) {
      const Vec2 e(std::cos(0.7 + j), std::sin(0.7 + j));
      const Vec2 cop = copByQuadrature(
          shape, [&](const Vec2& q) { return shape.radius() - (q - shape.centre()).dot(e); });
      EXPECT_NEAR((cop - (k.centre - k.radius * e)).norm(), 0.0, 1e-12 * shape.radius());
    }
    return k;
  }
  const std::vector<Vec2>& v = shape.vertices();
  std::vector<Vec2> cops;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], b = v[(i + 1) % v.size()];
    cops.push_back(copByQuadrature(shape, [&](const Vec2& q) {
      return (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();  // >= 0 inside
    }));
  }
  k.corners = testing::convexHull(cops);
  return k;
}

// Kern boundary point at parameter s in [0, segments).
Vec2 kernPoint(const Kern& k, double s) {
  if (k.corners.empty()) return k.centre + k.radius * Vec2(std::cos(s), std::sin(s));
  const std::size_t m = k.corners.size();
  const std::size_t j = std::min<std::size_t>(std::size_t(s), m - 1);
  const double f = s - double(j);
  return (1.0 - f) * k.corners[j] + f * k.corners[(j + 1) % m];
}

// Nearest point of K to y (y outside K): the apex or the nearest ray.
Vec3 searchNearest(const Kern& k, const Vec3& y, double rho) {
  auto nearestOnRay = [&](double s) {
    const Vec3 d = rayThrough(kernPoint(k, s), rho);
    return Vec3(std::max(0.0, d.dot(y) / d.squaredNorm()) * d);
  };
  auto dist = [&](double s) { return (nearestOnRay(s) - y).norm(); };
  Vec3 best = Vec3::Zero();
  double bestDist = y.norm();
  // golden section on [lo, hi], where the distance is unimodal
  auto refine = [&](double lo, double hi) {
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = dist(x1), f2 = dist(x2);
    for (int it = 0; it < 100; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = dist(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = dist(x2);
      }
    }
    for (double s : {lo, hi, 0.5 * (lo + hi)}) {
      if (dist(s) < bestDist) bestDist = dist(s), best = nearestOnRay(s);
    }
  };
  if (k.corners.empty()) {
    constexpr int kSamples = 4096;
    const double h = 2.0 * kPi / kSamples;
    int bestIndex = 0;
    for (int i = 1; i < kSamples; ++i)
      if (dist(i * h) < dist(bestIndex * h)) bestIndex = i;
    refine((bestIndex - 1) * h, (bestIndex + 1) * h);
  } else {
    // each side is a planar face of K: the distance to its rays is unimodal
    constexpr int kSamples = 64;
    for (std::size_t j = 0; j < k.corners.size(); ++j) {
      int bestIndex = 0;
      for (int i = 1; i <= kSamples; ++i)
        if (dist(j + double(i) / kSamples) < dist(j + double(bestIndex) / kSamples)) bestIndex = i;
      refine(j + std::max(0, bestIndex - 1) / double(kSamples),
             j + std::min(kSamples, bestIndex + 1) / double(kSamples));
    }
  }
  return best;
}

// Largest (y - p).u / |u| over K's generators: <= 0 when y - p is in the
// polar cone (the kern's corners for polygons, dense rays for disks).
double polarViolation(const Kern& k, const Vec3& r, double rho) {
  double worst = -INFINITY;
  const int n = k.corners.empty() ? 4096 : int(k.corners.size());
  for (int i = 0; i < n; ++i) {
    const Vec3 u =
        rayThrough(k.corners.empty() ? kernPoint(k, 2.0 * kPi * i / n) : k.corners[i], rho);
    worst = std::max(worst, r.dot(u) / u.norm());
  }
  return worst;
}

PatchShape cutDisk(double R, double cut, const Vec2& centre, int n) {
  // the disk of radius R about `centre` cut by the chord at `cut` R from it
  std::vector<Vec2> v;
  const double a = std::acos(cut);
  for (int i = 0; i < n; ++i) {
    const double th = a + (2.0 * kPi - 2.0 * a) * i / (n - 1.0);
    v.push_back(centre + R * Vec2(std::cos(th), std::sin(th)));
  }
  return PatchShape::polygon(v);
}

std::vector<PatchShape> randomShapes(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto offset = [&](double size) {  // O inside, near, or outside the patch
    const double r = 3.0 * size * u(rng), a = 2.0 * kPi * u(rng);
    return Vec2(r * std::cos(a), r * std::sin(a));
  };
  std::vector<PatchShape> out = {PatchShape::disk(0.05), PatchShape::regularPolygon(64, 0.05)};
  for (int i = 0; i < 4; ++i) {
    const double R = 0.01 + u(rng);
    out.push_back(PatchShape::disk(R, offset(R)));
    out.push_back(PatchShape::rectangle(R, R * (0.3 + u(rng)), offset(R), 2.0 * kPi * u(rng)));
    out.push_back(PatchShape::regularPolygon(6, R, offset(R), u(rng)));
    out.push_back(cutDisk(R, -0.5 + u(rng), offset(R), 64));
    std::vector<Vec2> cloud;  // a random convex polygon
    for (int j = 0; j < 10; ++j) cloud.push_back(R * Vec2(u(rng), u(rng)) + offset(R));
    out.push_back(PatchShape::polygon(testing::convexHull(cloud)));
  }
  // slivers (d^2 / A ~ 100 and ~ 1000, kMaxSliverRatio 4000), off O
  out.push_back(PatchShape::rectangle(1.0, 0.01, Vec2(0.2, 0.3), 0.4));
  out.push_back(PatchShape::polygon({{0.0, 0.0}, {1.0, 0.0005}, {0.4, 0.002}}));
  return out;
}

TEST(AdmissibleLoads, MatchesSearchAndKkt) {
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int projected = 0, apex = 0;
  for (const PatchShape& shape : randomShapes(rng)) {
    SCOPED_TRACE(shape.describe());
    const Kern kern = kernOf(shape);
    const Vec2 g = shape.centroid();
    for (double rhoFactor : {1.0, 1e-3, 1e3}) {
      const double rho = rhoFactor * shape.defaultRho();
      for (int t = 0; t < 12; ++t) {
        // centres of pressure from inside the patch to 30 diameters away
        const double reach = shape.diameter() * (t < 10 ? 0.1 + 1.5 * u(rng) : 30.0 * u(rng));
        const double a = 2.0 * kPi * u(rng), Pz = 0.1 + 10.0 * u(rng);
        const Vec2 cop = g + reach * Vec2(std::cos(a), std::sin(a));
        const PatchLoads x{Pz, -Pz * cop.y(), Pz * cop.x()};
        const PatchLoads r = nearestAdmissibleLoads(shape, x, rho);
        if (isAdmissible(shape, x, 0.0)) continue;
        ++projected;
        SCOPED_TRACE("rho factor " + std::to_string(rhoFactor) + ", trial " + std::to_string(t));
        const Vec3 y = scaled(x, rho), p = scaled(r, rho);
        const double ny = y.norm();
        // against the search
        const Vec3 ref = searchNearest(kern, y, rho);
        if (ref.isZero(0.0)) ++apex;
        EXPECT_NEAR((p - y).norm(), (ref - y).norm(), kDistanceRelTol * ny);
        EXPECT_LE((p - ref).norm(), kPointRelTol * ny);
        // KKT of the projection onto a cone: p in K, y - p in the polar
        // cone, (y - p) . p = 0
        EXPECT_TRUE(isAdmissible(shape, r, kKktRelTol));
        EXPECT_LE(polarViolation(kern, y - p, rho), kKktRelTol * ny);
        EXPECT_NEAR((y - p).dot(p), 0.0, kKktRelTol * ny * ny);
        // idempotence
        const Vec3 again = scaled(nearestAdmissibleLoads(shape, r, rho), rho);
        EXPECT_LE((again - p).norm(), kIdempotenceRelTol * ny);
      }
    }
  }
  // not vacuous: most loads lie outside K, a few project to the apex
  EXPECT_GT(projected, 500);
  EXPECT_GT(apex, 0);
}

// A disk far off O (|C| > R / 4) with a small rho: loads opposite C with a
// large torque across it lie on the far side of the cone's axis but not in
// its polar cone; there the projection is y minus its projection onto the
// polar cone (Moreau). Checked against the search as above.
TEST(AdmissibleLoads, DiskBeyondItsAxis) {
  const PatchShape disk = PatchShape::disk(0.2, Vec2(1.0, 0.0));
  const Kern kern = kernOf(disk);
  const double rho = 1e-2 * disk.defaultRho();
  // the cone {|w - a c| <= kappa a} in (a, w) as the quadric (a, w)^T H
  // (a, w) <= 0, c = C / rho, kappa = R / (4 rho): its axis is H's
  // eigenvector of the negative eigenvalue (Eigen's solver here)
  const Vec2 c = disk.centre() / rho;
  const double kappa = disk.radius() / (4.0 * rho);
  Mat3 H;
  H << c.squaredNorm() - kappa * kappa, -c.x(), -c.y(),  //
      -c.x(), 1.0, 0.0,                                  //
      -c.y(), 0.0, 1.0;
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(H);
  ASSERT_LT(eigen.eigenvalues()[0], 0.0);
  Vec3 axis = eigen.eigenvectors().col(0);
  if (axis[0] < 0.0) axis = -axis;
  // |across| > |C| / (R / 4) = 20 keeps the loads out of the polar cone
  for (double across : {25.0, 50.0, 500.0}) {
    // centre of pressure (-1, across) L / Pz: w = (Ty, -Tx) / rho
    const double Pz = 1e-3, L = 1.0;
    const PatchLoads x{Pz, -across * L, -L};
    const Vec3 y = scaled(x, rho);
    ASSERT_LT(axis.dot(Vec3(y[0], y[2], -y[1])), 0.0) << "not beyond the axis";
    const Vec3 p = scaled(nearestAdmissibleLoads(disk, x, rho), rho);
    const Vec3 ref = searchNearest(kern, y, rho);
    ASSERT_FALSE(ref.isZero(0.0)) << "in the polar cone: not the case meant";
    EXPECT_NEAR((p - y).norm(), (ref - y).norm(), kDistanceRelTol * y.norm());
    EXPECT_LE((p - ref).norm(), kPointRelTol * y.norm());
    EXPECT_NEAR((y - p).dot(p), 0.0, kKktRelTol * y.squaredNorm());
  }
}

// The kern test that opens nearestAdmissibleLoads (vertex pressures, on
// polygons of more than 16 vertices by a downhill walk from every eighth)
// decides as isAdmissible(shape, loads, 0): admissible loads come back
// bit for bit, inadmissible ones moved. Pressures with their minimum at
// zero, just above and just below (1e-9 of the mean), on 64-gons and
// smaller polygons.
TEST(AdmissibleLoads, KernTestAgreesWithIsAdmissible) {
  std::mt19937 rng(353);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<PatchShape> shapes = {
      cutDisk(0.05, 0.3, Vec2(0.01, 0.0), 64), PatchShape::regularPolygon(64, 0.1, Vec2(0.3, 0.1)),
      cutDisk(1.0, -0.6, Vec2(-0.5, 2.0), 40),
      PatchShape::rectangle(0.3, 0.1, Vec2(0.05, 0.0), 0.3), PatchShape::regularPolygon(6, 0.05)};
  int moved = 0, kept = 0;
  for (const PatchShape& shape : shapes) {
    SCOPED_TRACE(shape.describe());
    const double l = shape.diameter();
    for (int t = 0; t < 300; ++t) {
      LinearPressure p{0.0, 3.0 * u(rng) / l, 3.0 * u(rng) / l};
      double lowest = INFINITY;
      for (const Vec2& v : shape.vertices()) lowest = std::min(lowest, p.at(v));
      const double mean = 1.0 / shape.area();
      p.p0 = -lowest + (t % 3 == 0 ? 0.0 : t % 3 == 1 ? 1e-9 : -1e-9) * mean;
      const PatchLoads x = loadsOf(shape, p);
      const PatchLoads r = nearestAdmissibleLoads(shape, x, shape.defaultRho());
      const bool same = r.Pz == x.Pz && r.Tx == x.Tx && r.Ty == x.Ty;
      const double rho = shape.defaultRho();
      if (isAdmissible(shape, x, 0.0)) {
        EXPECT_TRUE(same) << "trial " << t;  // the documented contract
        ++kept;
      } else if (t % 3 == 2) {
        EXPECT_FALSE(same) << "trial " << t;  // 1e-9 of the mean outside
        ++moved;
      } else {
        // on the boundary to round-off: at most round-off away (the former
        // search answered an edge ray's point here, however far)
        EXPECT_LE((scaled(r, rho) - scaled(x, rho)).norm(),
                  kIdempotenceRelTol * scaled(x, rho).norm())
            << "trial " << t;
      }
    }
  }
  EXPECT_GT(moved, 400);
  EXPECT_GT(kept, 400);
}

}  // namespace
}  // namespace patchspin
