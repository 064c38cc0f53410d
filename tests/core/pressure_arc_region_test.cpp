// minPressure and isAdmissible on arc regions against dense boundary
// sampling (a linear pressure's minimum over a convex region lies on its
// boundary).
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
  const std::vector<Vec2> box = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1),
                                 Vec2(-0.1, 0.1)};
  return {diskPolygonIntersection(Vec2(0.09, 0.03), 0.02, box),
          diskPolygonIntersection(Vec2(0.095, 0.092), 0.02, box),
          diskDiskIntersection(Vec2(0.0, 0.0), 0.02, Vec2(0.025, 0.01), 0.02),
          diskDiskIntersection(Vec2(0.0, 0.0), 0.02, Vec2(0.012, -0.015), 0.03)};
}

double sampledMin(const Region& region, const LinearPressure& p, int n) {
  double m = INFINITY;
  for (const Vec2& q : testing::exact_arc::boundarySamples(region, n)) m = std::min(m, p.at(q));
  return m;
}

// minPressure within [sampled min - sampling gap, sampled min + 1e-13 |p|]:
// 20000 samples per piece miss an arc's minimum by at most |grad p| R
// (span / 20000)^2 / 2 < 5e-8 |grad p| R (R < 0.03 here)
TEST(PressureArcRegion, MinPressureIsTheSampledMinimum) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Region& region : regions()) {
    const PatchShape shape = PatchShape::arcRegion(region);
    for (int i = 0; i < 200; ++i) {
      const LinearPressure p{1000.0 * u(rng), 1e5 * u(rng), 1e5 * u(rng)};
      const double scale = std::abs(p.p0) + std::hypot(p.cx, p.cy) * shape.maxDistanceFromOrigin();
      const double m = minPressure(shape, p), s = sampledMin(region, p, 20000);
      EXPECT_LE(m, s + 1e-13 * scale);
      EXPECT_GE(m, s - 5e-8 * std::hypot(p.cx, p.cy) * 0.03 - 1e-13 * scale);
    }
  }
}

// A pressure whose minimum is exactly delta: admissible iff delta >= -relTol
// of the mean pressure (the documented relative tolerance).
TEST(PressureArcRegion, IsAdmissibleAtTheEdge) {
  for (const Region& region : regions()) {
    const PatchShape shape = PatchShape::arcRegion(region);
    for (int k = 0; k < 16; ++k) {
      const double t = 2.0 * M_PI * k / 16;
      const LinearPressure slope{0.0, 1e5 * std::cos(t), 1e5 * std::sin(t)};
      const double m = minPressure(shape, slope);
      for (double mean : {10.0, 1000.0}) {
        // p0 such that min p = delta
        for (double rel : {-1e-6, 1e-6}) {
          const double delta = rel * mean;
          const LinearPressure p{-m + delta, slope.cx, slope.cy};
          const PatchLoads loads = loadsOf(shape, p);
          const double meanP = loads.Pz / shape.area();
          EXPECT_EQ(isAdmissible(shape, loads, 0.0), delta > 0.0)
              << "t " << t << " delta " << delta << " mean " << meanP;
        }
      }
    }
  }
}

}  // namespace
}  // namespace patchspin
