// pressure.cpp at the ends of its range: loads and pressures outside
// double's range, non-finite coefficients, Eq. (94) and the admissible-load
// projection about a far O. Oracles: long double sums about the vertex mean
// (vertex_mean_loads.hpp) and a dense scan of a disk's boundary rays.
#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "error_matchers.hpp"
#include "fuzz_inputs.hpp"
#include "oracle.hpp"
#include "vertex_mean_loads.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::loadsAboutVertexMean;
using testing::LongLoads;
using testing::refusedAsNotFinite;
using testing::throwsNaming;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMax = std::numeric_limits<double>::max();

// fuzz round 1, items 7 and 8
// Loads or pressures outside double's range, a bad rho for the projection
// metric, non-finite moments: an Error naming the problem; Pz <= 0 projects
// to the zero load (documented fallback).
TEST(Pressure, RefusesLoadsAndPressuresOutOfRange) {
  const PatchShape square = PatchShape::rectangle(1e-3, 1e-3);
  // loads whose pressure overflows (found by fuzzing: p = -inf)
  EXPECT_TRUE(throwsNaming(
      [&] {
        LinearPressure::fromLoads(square, {1e308, 1e308, 0.0});
      },
      {"out of range"}));
  // a pressure that is not finite on the patch (minPressure gave inf)
  EXPECT_TRUE(throwsNaming(
      [&] {
        minPressure(square, LinearPressure{-kMax, -kMax, 0.0});
      },
      {"out of range"}));
  // rho for the projection metric: positive, and within 1e12 of Eq. (11)
  const PatchLoads loads{1.0, 0.01, 0.0};
  EXPECT_TRUE(throwsNaming([&] { nearestAdmissibleLoads(square, loads, 0.0); }, {"rho"}));
  EXPECT_TRUE(throwsNaming([&] { nearestAdmissibleLoads(square, loads, 6e-322); }, {"rho"}));
  EXPECT_TRUE(throwsNaming([&] { nearestAdmissibleLoads(square, loads, 1e308); }, {"rho"}));
  // documented fallback: Pz <= 0 maps to zero load
  const PatchLoads none = nearestAdmissibleLoads(square, {-2.0, 0.3, 0.1}, square.defaultRho());
  EXPECT_EQ(none.asVector(), Vec3::Zero());
  // Pi: rho must be positive and finite; moments finite
  const PiMoments pm = piMoments(square, LinearPressure::uniform(square, 1.0));
  EXPECT_TRUE(throwsNaming([&] { ellipsoidalPi(pm, 0.0); }, {"rho"}));
  EXPECT_TRUE(throwsNaming([&] { ellipsoidalPi(pm, -1.0); }, {"rho"}));
  EXPECT_TRUE(throwsNaming([&] { ellipsoidalPi(pm, kNan); }, {"rho"}));
  EXPECT_TRUE(throwsNaming(
      [&] {
        piMoments(square, LinearPressure{kInf, 0.0, 0.0});
      },
      {"pressure"}));
  EXPECT_TRUE(throwsNaming(
      [&] {
        piMoments(square, LinearPressure{1.0, kNan, 0.0});
      },
      {"pressure"}));
}

// fuzz round 9, item 63 (ilogb(NaN) = INT_MIN negated: UB, trapped by the asan preset)
// A pressure with a NaN or infinite coefficient is refused as not finite on
// every shape; finite coefficients whose vertex products overflow keep the
// rescaled sum.
TEST(MinPressure, RefusesNonFiniteCoefficients) {
  // the premise of the class: NaN has no binary exponent; glibc returns
  // FP_ILOGBNAN, whose negation is not an int when it is INT_MIN
  EXPECT_EQ(std::ilogb(kNan), FP_ILOGBNAN);
  const PatchShape quad = testing::ilogbQuadrilateral();
  const PatchShape square = PatchShape::rectangle(2.0, 2.0);
  const PatchShape disk = PatchShape::disk(0.5, Vec2(3.0, -1.0));
  const std::vector<LinearPressure> pressures = {
      {kNan, kNan, kNan}, {kNan, 0.0, 0.0},  {1.0, kNan, 0.0}, {1.0, 0.0, kNan},
      {kInf, 0.0, 0.0},   {1.0, -kInf, 0.0}, {kNan, kInf, 1.0}};
  for (const PatchShape& shape : {quad, square, disk}) {
    for (const LinearPressure& p : pressures) {
      EXPECT_TRUE(refusedAsNotFinite([&] { minPressure(shape, p); }))
          << "(p0, cx, cy) = (" << p.p0 << ", " << p.cx << ", " << p.cy << ")";
    }
  }
  // finite coefficients whose products overflow at a vertex keep the
  // eighth round's rescaled sum (not refused): p = DBL_MAX (-1 + x + y) on
  // the triangle (-1, 1), (1, -1), (1, 1) is -DBL_MAX, -DBL_MAX, +DBL_MAX at
  // its vertices (exact), though p0 + cx x overflows to -inf at (-1, 1)
  const PatchShape triangle =
      PatchShape::polygon({Vec2(-1.0, 1.0), Vec2(1.0, -1.0), Vec2(1.0, 1.0)});
  const LinearPressure big{-kMax, kMax, kMax};
  EXPECT_EQ(big.at(Vec2(-1.0, 1.0)), -kInf);  // the plain sum overflows
  EXPECT_EQ(minPressure(triangle, big), -kMax);
}

// fuzz round 8, item 61
// minPressure where cx x and cy y overflow with opposite signs but their sum
// does not: the lowest vertex, against long double, to kUlps eps of the terms.
TEST(MinPressure, WithOverflowingVertexProductsIsTheLowestVertex) {
  const PatchShape triangle = PatchShape::polygon({{0.0, 0.0},
                                                   {428990.26137603901, 604750.50188696722},
                                                   {428989.27616420639, 604750.330503618}});
  const LinearPressure p{-5.1874508961404106e+297, -5.22801961128216e+303, 3.708582688189708e+303};
  long double lowest = std::numeric_limits<long double>::infinity(), terms = 0.0L;
  for (const Vec2& v : triangle.vertices()) {
    const long double x = static_cast<long double>(p.cx) * v.x(),
                      y = static_cast<long double>(p.cy) * v.y();
    if (p.p0 + x + y < lowest)
      lowest = p.p0 + x + y, terms = std::abs(p.p0) + std::abs(x) + std::abs(y);
  }
  ASSERT_LT(std::abs(lowest), static_cast<long double>(std::numeric_limits<double>::max()));
  constexpr double kUlps = 8.0;
  const double core = minPressure(triangle, p);
  // (in long double: the terms, 4.5e309, are beyond double's range)
  EXPECT_LE(std::abs(static_cast<long double>(core) - lowest), kUlps * kEps * terms)
      << core << " vs " << static_cast<double>(lowest);
}

// fuzz round 8, item 59
// 500 convex polygons 1 to 1e4 diameters from O: fromLoads (Eq. (94)) returns
// the pressure at every vertex to kPressure of the mean, and loads pushed
// outside the set project to admissible loads, refused at most kRefused times.
TEST(Loads, FromLoadsAndNearestAdmissibleKeepTheirDigitsFarFromO) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  constexpr double kPressure = 1e-6;
  constexpr int kRefused = 5;
  int refused = 0, checked = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const double offset = std::pow(10.0, 3.9 * U(rng)) + 1.0;  // (below the 1e4 limit)
    const int n = 3 + static_cast<int>(U(rng) * 20);
    const double aspect = std::pow(10.0, -4.0 * U(rng)),
                 size = std::pow(10.0, -6.0 + 12.0 * U(rng));
    const double angle = 2.0 * kPi * U(rng), direction = 2.0 * kPi * U(rng);
    std::vector<Vec2> v;
    const Vec2 centre = offset * 2.0 * size * Vec2(std::cos(direction), std::sin(direction));
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * kPi * i / n;
      const Vec2 u(std::cos(t), aspect * std::sin(t));
      v.push_back(centre + size * Vec2(std::cos(angle) * u.x() - std::sin(angle) * u.y(),
                                       std::sin(angle) * u.x() + std::cos(angle) * u.y()));
    }
    const PatchShape shape = PatchShape::polygon(v);
    ASSERT_GT(shape.maxDistanceFromOrigin(), shape.diameter());
    // p = 1 + t n.(x - g) / halfwidth >= 0 (t <= 1), given about O
    Vec2 g = Vec2::Zero();
    for (const Vec2& a : shape.vertices()) g += a;
    g /= static_cast<double>(shape.vertices().size());
    const double th = 2.0 * kPi * U(rng), tilt = U(rng);
    const Vec2 nrm(std::cos(th), std::sin(th));
    double halfWidth = 0.0;
    for (const Vec2& a : shape.vertices())
      halfWidth = std::max(halfWidth, std::abs(nrm.dot(a - g)));
    const LinearPressure p{1.0 - tilt * nrm.dot(g) / halfWidth, tilt * nrm.x() / halfWidth,
                           tilt * nrm.y() / halfWidth};
    const LongLoads l = loadsAboutVertexMean(shape.vertices(), p);
    const PatchLoads loads{double(l.Pz), double(l.Tx), double(l.Ty)};
    const LinearPressure back = LinearPressure::fromLoads(shape, loads);
    const double mean = loads.Pz / shape.area();
    for (const Vec2& a : shape.vertices()) {
      auto at = [&](const LinearPressure& q) {
        return static_cast<long double>(q.p0) + static_cast<long double>(q.cx) * a.x() +
               static_cast<long double>(q.cy) * a.y();
      };
      worst = std::max(worst, static_cast<double>(std::abs(at(back) - at(p))) / mean);
    }
    // loads outside: the torques about g pushed 3 times past the patch
    const double reach = 3.0 * shape.diameter() * loads.Pz;
    const PatchLoads outside{loads.Pz, loads.Tx + reach * std::cos(th),
                             loads.Ty + reach * std::sin(th)};
    try {
      const PatchLoads near = nearestAdmissibleLoads(shape, outside, shape.defaultRho());
      EXPECT_TRUE(isAdmissible(shape, near, 1e-6)) << "trial " << trial;
      ++checked;
    } catch (const Error& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find("no admissible projection"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_LT(worst, kPressure);
  EXPECT_LE(refused, kRefused) << checked << " projected";
}

// fuzz round 8, item 62
// On a disk not centred at O the projection is admissible and as near as the
// nearest of 200,000 scanned boundary rays, to kScan.
TEST(NearestAdmissible, OnAnOffCentreDiskIsTheNearestBoundaryRay) {
  struct Case {
    double R;
    Vec2 centre;
    PatchLoads loads;
    double rho;
  };
  const std::vector<Case> cases = {{0.5,
                                    {0.5000005187294978, -0.0015335067838567222},
                                    {6.008148193359375e-05, 1e-300, -6.2008168049345967e-49},
                                    116391936.0},
                                   {5368184832.0,
                                    {2154373347.0781322, -642361449.92492497},
                                    {3.770163170556893e+146, 0.5, 0.5},
                                    4044283405.5980945}};
  constexpr double kScan = 1e-6;
  for (const Case& c : cases) {
    const PatchShape disk = PatchShape::disk(c.R, c.centre);
    const PatchLoads near = nearestAdmissibleLoads(disk, c.loads, c.rho);
    EXPECT_TRUE(isAdmissible(disk, near, 1e-6));
    const Vec3 y(c.loads.Pz, c.loads.Tx / c.rho, c.loads.Ty / c.rho);
    auto scaled = [&](const PatchLoads& l) { return Vec3(l.Pz, l.Tx / c.rho, l.Ty / c.rho); };
    double nearest = y.norm();  // the zero load
    constexpr int kRays = 200000;
    for (int i = 0; i < kRays; ++i) {
      const double th = 2.0 * kPi * i / kRays;
      const Vec2 n(std::cos(th), std::sin(th));
      const Vec3 u = scaled(
          loadsOf(disk, LinearPressure{1.0 + n.dot(c.centre) / c.R, -n.x() / c.R, -n.y() / c.R}));
      const double t = std::max(0.0, u.dot(y) / u.squaredNorm());
      nearest = std::min(nearest, (t * u - y).norm());
    }
    EXPECT_LE((scaled(near) - y).norm(), nearest * (1.0 + kScan)) << "R = " << c.R;
  }
}

}  // namespace
}  // namespace patchspin
