// nearestAdmissibleLoads on arc regions: admissible output (p >= 0 on dense
// boundary samples), admissible input unchanged, idempotence, the cone
// projection's orthogonality, and against the exact projection of a disk
// (Kind::Disk's closed form) for a disk given as two half arcs.
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "arc_region_quadrature.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace patchspin {
namespace {

using testing::exact_arc::Region;

std::vector<Region> regions() {
  const std::vector<Vec2> box = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  auto centred = [](Region r) {
    const AreaMoments m = areaMomentsOf(r);
    const Vec2 g = m.first / m.area;
    for (BoundaryPiece& p : r) p.a -= g, p.b -= g, p.centre -= g;
    return r;
  };
  return {centred(diskPolygonIntersection(Vec2(0.09, 0.03), 0.02, box)),
          centred(diskPolygonIntersection(Vec2(0.095, 0.092), 0.02, box)),
          centred(diskDiskIntersection(Vec2(0.0, 0.0), 0.02, Vec2(0.025, 0.01), 0.02)),
          diskDiskIntersection(Vec2(0.0, 0.0), 0.02, Vec2(0.012, -0.015), 0.03)};
}

Vec3 scaled(const PatchLoads& l, double rho) {
  return Vec3(l.Pz, l.Tx / rho, l.Ty / rho);
}

// admissible: p >= -1e-12 of the mean pressure on 20000 boundary samples per
// piece (the kVerifyTol-free check of the output)
TEST(AdmissibleLoadsArcRegion, ProjectionIsAdmissibleIdempotentAndOrthogonal) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Region& region : regions()) {
    const PatchShape shape = PatchShape::arcRegion(region);
    const double rho = shape.defaultRho();
    int projected = 0;
    for (int i = 0; i < 300; ++i) {
      const PatchLoads loads{10.0 * (0.2 + u(rng)), 0.3 * u(rng), 0.3 * u(rng)};
      const PatchLoads out = nearestAdmissibleLoads(shape, loads, rho);
      if (isAdmissible(shape, loads, 0.0)) {
        EXPECT_EQ(out.asVector(), loads.asVector());
        continue;
      }
      if (!(loads.Pz > 0.0)) continue;
      if (out.Pz == 0.0) continue;  // the apex (polar cone)
      ++projected;
      const LinearPressure p = LinearPressure::fromLoads(shape, out);
      double lowest = INFINITY;
      for (const Vec2& q : testing::exact_arc::boundarySamples(region, 20000))
        lowest = std::min(lowest, p.at(q));
      EXPECT_GE(lowest, -1e-12 * out.Pz / shape.area());
      // on K's boundary to the circumscribed polygon's gap: min p <= |grad
      // p| 4.7e-6 R (+ round-off)
      EXPECT_LE(lowest, std::hypot(p.cx, p.cy) * 5e-6 * 0.03 + 1e-12 * out.Pz / shape.area());
      // idempotent
      const PatchLoads again = nearestAdmissibleLoads(shape, out, rho);
      EXPECT_EQ(again.asVector(), out.asVector());
      // a cone projection: (y - P y) . P y = 0
      const Vec3 y = scaled(loads, rho), py = scaled(out, rho);
      EXPECT_NEAR((y - py).dot(py), 0.0, 1e-12 * y.squaredNorm());
    }
    EXPECT_GT(projected, 50);
  }
}

// A disk of two half arcs centred at O (an ArcRegion) against Kind::Disk's
// exact closed-form projection: the result is admissible for the disk, so
// never nearer than the exact one (to 1e-12), and at most 2e-5 |y| farther
// (the circumscribed polygon lies within 4.7e-6 R of the disk; the cone's
// kern scales with R / 4 rho).
TEST(AdmissibleLoadsArcRegion, NearlyTheExactProjectionOnADisk) {
  const double R = 0.02;
  const PatchShape arcs = PatchShape::arcRegion(
      {BoundaryPiece::arc(Vec2::Zero(), R, 0.1, 0.1 + M_PI), BoundaryPiece::arc(Vec2::Zero(), R, 0.1 + M_PI, 0.1 + 2 * M_PI)});
  const PatchShape disk = PatchShape::disk(R);
  const double rho = disk.defaultRho();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 300; ++i) {
    const PatchLoads loads{10.0 * (0.2 + u(rng)), 0.2 * u(rng), 0.2 * u(rng)};
    if (isAdmissible(disk, loads, 0.0) || !(loads.Pz > 0.0)) continue;
    const Vec3 y = scaled(loads, rho);
    const double dArc = (scaled(nearestAdmissibleLoads(arcs, loads, rho), rho) - y).norm();
    const double dDisk = (scaled(nearestAdmissibleLoads(disk, loads, rho), rho) - y).norm();
    EXPECT_GE(dArc, dDisk - 1e-12 * y.norm());
    EXPECT_LE(dArc, dDisk + 2e-5 * y.norm());
    worst = std::max(worst, (dArc - dDisk) / y.norm());
  }
  RecordProperty("worst_excess", std::to_string(worst));
}

}  // namespace
}  // namespace patchspin
