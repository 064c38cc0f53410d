// The moment tables of moment_tables.cpp at the ends of their range: patches
// far from O, O near a disk's rim, slivers, moments outside double's range.
// Oracles: a hypergeometric series, Taylor expansions, brute-force
// quadrature, and the rows' closed form evaluated in 50 digits.
#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "error_matchers.hpp"
#include "oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace patchspin {
namespace {

using testing::throwsNaming;

constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Gauss hypergeometric 2F1(a, b; c; z) by its series (|z| <= 1, c - a - b > 0).
double hypergeometric(double a, double b, double c, double z) {
  double term = 1.0, sum = 1.0;
  for (int n = 0; n < 200000; ++n) {
    term *= (a + n) * (b + n) / ((c + n) * (n + 1.0)) * z;
    sum += term;
    if (std::abs(term) < 1e-17 * std::abs(sum)) break;
  }
  return sum;
}

using Big = boost::multiprecision::cpp_bin_float_50;

Big bigAsinh(const Big& u) {
  const Big a = abs(u);
  const Big v = log(a + sqrt(1 + a * a));
  return u < 0 ? Big(-v) : v;
}

// The table's rows in 50 digits: area, first moments, and the nine entries
// with r, entry (f, k) = ∫ f phi_k dA with f in {r, x/r, y/r} and phi in
// {1, x, y}, by the exact signed triangles (O, a, b) over the edges:
// ∫_tri g dA = cross(a, b) / (deg + 2) ∫_0^1 g(a + t (b - a)) dt for g
// homogeneous of degree deg, along the edge e(tau) = F + tau t^ with
//   ∫ 1/r = asinh(tau / d), ∫ tau / r = r, ∫ tau^2 / r = (tau r - d^2 asinh(tau / d)) / 2,
//   ∫ r = (tau r + d^2 asinh(tau / d)) / 2, ∫ tau r = r^3 / 3.
struct BigTable {
  Big area = 0, sx = 0, sy = 0;
  std::array<std::array<Big, 3>, 3> withR;  // [f: r, x/r, y/r][phi: 1, x, y] (zero)
};

BigTable bigTable(const std::vector<Vec2>& v) {
  BigTable out;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Big ax = v[i].x(), ay = v[i].y(), bx = v[(i + 1) % n].x(), by = v[(i + 1) % n].y();
    const Big c = ax * by - ay * bx;
    out.area += c / 2;
    out.sx += c / 6 * (ax + bx);
    out.sy += c / 6 * (ay + by);
    if (c == 0) continue;
    const Big ex = bx - ax, ey = by - ay;
    const Big L = sqrt(ex * ex + ey * ey);
    const Big tx = ex / L, ty = ey / L;
    const Big ta = ax * tx + ay * ty, tb = bx * tx + by * ty;
    const Big fx = ax - ta * tx, fy = ay - ta * ty;
    const Big d = abs(c) / L;
    const Big ra = sqrt(ta * ta + d * d), rb = sqrt(tb * tb + d * d);
    const Big jm0 = bigAsinh(tb / d) - bigAsinh(ta / d);
    const Big jm1 = rb - ra;
    const Big tr = tb * rb - ta * ra;
    const Big jm2 = (tr - d * d * jm0) / 2, j10 = (tr + d * d * jm0) / 2;
    const Big j11 = (rb * rb * rb - ra * ra * ra) / 3;
    const Big s0 = c / (2 * L), s1 = c / (3 * L), s2 = c / (4 * L);
    auto& w = out.withR;
    w[0][0] += s1 * j10;
    w[0][1] += s2 * (fx * j10 + tx * j11);
    w[0][2] += s2 * (fy * j10 + ty * j11);
    const Big xxOverR = fx * fx * jm0 + 2 * fx * tx * jm1 + tx * tx * jm2;
    const Big yyOverR = fy * fy * jm0 + 2 * fy * ty * jm1 + ty * ty * jm2;
    const Big xyOverR = fx * fy * jm0 + (fx * ty + fy * tx) * jm1 + tx * ty * jm2;
    w[1][0] += s0 * (fx * jm0 + tx * jm1);
    w[1][1] += s1 * xxOverR;
    w[1][2] += s1 * xyOverR;
    w[2][0] += s0 * (fy * jm0 + ty * jm1);
    w[2][1] += s1 * xyOverR;
    w[2][2] += s1 * yyOverR;
  }
  return out;
}

// The scale of entry (f, k): A max|f| max|phi_k| over the patch (|x/r|,
// |y/r| <= 1, |r| <= max|r|, |x| <= the vertices' max|x|), times a sliver's
// max(1, diameter^2 / A): its area itself is rounded that much by the
// vertex differences (fuzz round 8, item 58; the polynomial rows alike).
std::array<std::array<double, 3>, 3> entryScales(const PatchShape& shape) {
  double mx = 0.0, my = 0.0;
  for (const Vec2& p : shape.vertices()) {
    mx = std::max(mx, std::abs(p.x()));
    my = std::max(my, std::abs(p.y()));
  }
  const double A = shape.area(), D = shape.diameter();
  const double base = A * std::max(1.0, D * D / A);
  const double fMax[3] = {shape.maxDistanceFromOrigin(), 1.0, 1.0};
  const double phiMax[3] = {1.0, mx, my};
  std::array<std::array<double, 3>, 3> s{};
  for (int f = 0; f < 3; ++f)
    for (int k = 0; k < 3; ++k) s[f][k] = base * fMax[f] * phiMax[k];
  return s;
}

constexpr MomentTable::Row kRowsWithR[3] = {MomentTable::kR, MomentTable::kXOverR,
                                            MomentTable::kYOverR};

// Largest error of the nine entries with r against the 50-digit closed
// form, in units of eps times the entry's scale.
double worstRowError(const PatchShape& shape) {
  const BigTable ref = bigTable(shape.vertices());
  const auto scale = entryScales(shape);
  const auto& m = shape.momentTable().m;
  double worst = 0.0;
  for (int f = 0; f < 3; ++f)
    for (int k = 0; k < 3; ++k) {
      const double error = static_cast<double>(abs(Big(m(kRowsWithR[f], k)) - ref.withR[f][k]));
      worst = std::max(worst, error / (kEps * scale[f][k]));
    }
  return worst;
}

// The tolerance of the rows with r, in eps times the entry's scale: the
// quadrature adds positive weights times integrands evaluated to a few
// ulps, each point formed as the vertex mean plus its local offset
// (measured against the 50-digit closed form about O: 3.3 over the
// sweep below, 4.6 on the far heptagon; the old double closed form was 3
// to 15 at 3-4 diameters, 4e4 at 100, 1.5e8 at 3560, 3.9e8 at 9000).
constexpr double kRowTolerance = 16.0;

// Item 65's input (fuzz/corpus/pi/passes-far-sliver-cancelling-pressure-
// rows-about-vertex-mean), vertices as decoded: a 1 m x 1e-8 m sliver 3,560 m
// from O.
PatchShape farSliver() {
  return PatchShape::polygon({Vec2(-3559.9649976123574, -0.4594039769687297),
                              Vec2(-3560.5349744299015, 0.36225679698988017),
                              Vec2(-3560.5349744381178, 0.36225679129011201),
                              Vec2(-3559.9649976205733, -0.45940398266849786)});
}

// The second round's open input (fuzz/corpus/pi/passes-far-heptagon-xy-
// over-r-rows-about-vertex-mean, was open-far-heptagon-xy-over-r): a 1 m
// heptagon 6,754 m from O, whose ∫xy/r was 3.9e-6 of A max|y| off.
PatchShape farHeptagon() {
  return PatchShape::polygon({Vec2(-6753.8004140509947, 0.47592741706291586),
                              Vec2(-6754.1148482872486, 0.17695191129093826),
                              Vec2(-6754.077146205992, -0.25529083884940296),
                              Vec2(-6753.7156992096307, -0.49531284865203656),
                              Vec2(-6753.3026830336512, -0.36237346261792053),
                              Vec2(-6753.1491080055357, 0.043421994132563195),
                              Vec2(-6753.3706193416037, 0.41650103397957677)});
}

// fuzz round 1, item 1 (PatchShape::disk hung with O just inside the rim)
// ∫ |P - O| dA over a unit disk with O at distance delta from its centre is
// (2 pi / 3) 2F1(-1/2, -3/2; 1; delta^2) (delta <= 1), a series independent of
// the table's quadrature (exact_disk.cpp's header).
TEST(MomentTable, DiskWithOriginNearTheRimMatchesTheHypergeometricSeries) {
  // the series' truncation at delta -> 1 (terms ~ n^-4) and the table's
  // 1e-15 quadrature tolerance: 1e-11 relative
  constexpr double kSeriesTol = 1e-11;
  for (double gap : {1e-3, 1e-4, 1e-6, 1e-9, 1e-12}) {
    for (double angle : {0.0, 1.0, kPi / 2.0}) {
      const double delta = 1.0 - gap;
      const PatchShape disk = PatchShape::disk(1.0, delta * Vec2(std::cos(angle), std::sin(angle)));
      const double expected = 2.0 * kPi / 3.0 * hypergeometric(-0.5, -1.5, 1.0, delta * delta);
      EXPECT_NEAR(disk.momentTable().m(MomentTable::kR, 0), expected, kSeriesTol * expected)
          << "gap " << gap << " angle " << angle;
    }
  }
}

// fuzz round 1, item 1 (a small disk far from O hung, or lost digits on the y axis)
// Far away, ∫ r dA = A (delta + R^2 / (8 delta)) and ∫ (x, y)/r dA =
// A (1 - R^2 / (8 delta^2)) C/delta, up to O((R / delta)^4) relative (Taylor
// expansion of |C + q| over the disk).
TEST(MomentTable, SmallDiskFarFromOriginMatchesItsExpansion) {
  for (double ratio : {3e3, 9e3}) {
    for (const Vec2& dir : {Vec2(1.0, 0.0), Vec2(0.0, -1.0), Vec2(0.6, 0.8)}) {
      const double R = 1e-3, delta = ratio * R;
      const PatchShape disk = PatchShape::disk(R, delta * dir);
      const double A = disk.area();
      // the expansion's next term, (R / delta)^4, plus the table's 1e-14
      const double tol = std::pow(R / delta, 4) + 1e-13;
      const auto& m = disk.momentTable().m;
      EXPECT_NEAR(m(MomentTable::kR, 0) / A, delta + R * R / (8.0 * delta), tol * delta);
      const double radial = 1.0 - R * R / (8.0 * delta * delta);
      EXPECT_NEAR(m(MomentTable::kXOverR, 0) / A, radial * dir.x(), tol);
      EXPECT_NEAR(m(MomentTable::kYOverR, 0) / A, radial * dir.y(), tol);
    }
  }
}

// fuzz rounds 1-2, items 2 and 12
// Moments beyond double's range, or a patch so far from O that the pressure
// about O has no digits: an Error naming the problem; 1e4 diameters is fine.
TEST(Shape, RefusesMomentsOutOfRangeAndPatchesTooFarFromO) {
  EXPECT_TRUE(throwsNaming([] { PatchShape::disk(1e200); }, {"out of range"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::disk(1e-100); }, {"out of range"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::rectangle(1e100, 1e100); }, {"out of range"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::disk(1e-8, Vec2(0.5, 0.5)); }, {"distance from o"}));
  EXPECT_TRUE(throwsNaming([] { PatchShape::regularPolygon(23, 1e-8, Vec2(0.5, 0.5)); },
                           {"distance from o"}));
  // huge coordinates that the polygon checks see as degenerate
  EXPECT_TRUE(throwsNaming(
      [] {
        PatchShape::polygon({{0, 0}, {1e300, 0}, {0, 1e300}});
      },
      {"area", "out of range"}));
  // 1e4 diameters is still fine, and finite
  const PatchShape far = PatchShape::disk(1.0, Vec2(0.9e4 * 2.0, 0.0));
  EXPECT_TRUE(far.momentTable().m.allFinite());
}

// fuzz round 2, item 15 (edge integrals far from their edge)
// A sliver 1.8e9 m long and 1 m wide passing 0.5 m from O: the rows x/r and
// y/r against brute-force quadrature, to the fan's cancellation
// (max|r|^2 / A eps).
TEST(MomentTable, LongSliverPassingNearOMatchesBruteForceQuadrature) {
  const std::vector<Vec2> v{{-913801215.0, -8.6380121600000006},
                            {913801217.0, 9.6380121600000006},
                            {913801217.0, 10.638012160000001},
                            {-913801215.0, -7.6380121600000006}};
  const PatchShape sliver = PatchShape::polygon(v);
  const auto& m = sliver.momentTable().m;
  // the oracle's relative accuracy (of ∫|f|), and the table's: the fan of
  // triangles from O cancels ~max|r|^2 / A = 5e8 times eps = 1e-7
  constexpr double kOracleTol = 1e-10;
  constexpr double kTableTol = 1e-6;
  auto absIntegral = [&](const std::function<double(const Vec2&)>& f) {
    return testing::bruteForceIntegral(
        sliver, [&](const Vec2& p) { return std::abs(f(p)); }, kOracleTol);
  };
  const std::function<double(const Vec2&)> xyOverR = [](const Vec2& p) {
    return p.x() * p.y() / p.norm();
  };
  const std::function<double(const Vec2&)> yyOverR = [](const Vec2& p) {
    return p.y() * p.y() / p.norm();
  };
  const std::function<double(const Vec2&)> xxOverR = [](const Vec2& p) {
    return p.x() * p.x() / p.norm();
  };
  EXPECT_NEAR(m(MomentTable::kXOverR, 2), testing::bruteForceIntegral(sliver, xyOverR, kOracleTol),
              kTableTol * absIntegral(xyOverR));
  EXPECT_NEAR(m(MomentTable::kYOverR, 2), testing::bruteForceIntegral(sliver, yyOverR, kOracleTol),
              kTableTol * absIntegral(yyOverR));
  EXPECT_NEAR(m(MomentTable::kXOverR, 1), testing::bruteForceIntegral(sliver, xxOverR, kOracleTol),
              kTableTol * absIntegral(xxOverR));
}

// fuzz round 10, item 65
// Convex polygons (3 to 10 vertices, aspect 1 to 1e-8) 5 to 9,000 diameters
// from O: every entry with r within kRowTolerance of the 50-digit closed form.
TEST(MomentTable, PolygonRowsWithRFarFromOMatch50Digits) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  double worstOverall = 0.0;
  for (const double offset : {5.0, 6.0, 16.0, 100.0, 1000.0, 3560.0, 9000.0}) {
    for (int trial = 0; trial < 30; ++trial) {
      const int n = 3 + static_cast<int>(rng() % 8);
      const double aspect = std::pow(10.0, -8.0 * unit(rng) * unit(rng));
      std::vector<double> angles(n);
      for (double& a : angles) a = 2.0 * kPi * unit(rng);
      std::sort(angles.begin(), angles.end());
      const double turn = 2.0 * kPi * unit(rng), c = std::cos(turn), s = std::sin(turn);
      const double direction = 2.0 * kPi * unit(rng);
      std::vector<Vec2> local;
      for (const double a : angles) {
        const double x = std::cos(a), y = aspect * std::sin(a);
        local.emplace_back(c * x - s * y, s * x + c * y);
      }
      // centroid `offset` diameters from O: every point within one diameter
      // of it, so the farthest is (offset - 1) to (offset + 1) diameters away
      std::vector<Vec2> v;
      PatchShape shape = PatchShape::disk(1.0);
      try {
        const PatchShape near = PatchShape::polygon(local);
        const double D = near.diameter();
        const Vec2 centre = offset * D * Vec2(std::cos(direction), std::sin(direction));
        for (const Vec2& p : near.vertices()) v.push_back(p - near.centroid() + centre);
        shape = PatchShape::polygon(v);
      } catch (const Error&) {
        continue;  // vertices too close (a random draw): not this test's subject
      }
      const double far = shape.maxDistanceFromOrigin() / shape.diameter();
      ASSERT_GT(far, 4.0);  // the quadrature's regime (moment_tables.hpp, kFarRowsOffset)
      const double worst = worstRowError(shape);
      EXPECT_LE(worst, kRowTolerance)
          << "offset " << far << ", " << n << " vertices, aspect " << aspect;
      worstOverall = std::max(worstOverall, worst);
      ++checked;
    }
  }
  EXPECT_GE(checked, 150);
  const double heptagon = worstRowError(farHeptagon());
  EXPECT_LE(heptagon, kRowTolerance) << "the second round's far heptagon";
  std::printf("[ info ] %d polygons, worst entry with r %.2f eps of its scale; heptagon %.2f\n",
              checked, worstOverall, heptagon);
}

// fuzz round 10, item 65 (the fuzz input)
// A sliver 3,560 m from O with cy = -DBL_MAX (the pressure changes sign across
// it): (pi_x0, pi_y0) is the 50-digit value to the rows' round-off, propagated
// (kRowTolerance eps times each term's scale, over Pz).
TEST(PiMoments, FarSliverWithACancellingPressureMatches50Digits) {
  const PatchShape shape = farSliver();
  ASSERT_GT(shape.maxDistanceFromOrigin() / shape.diameter(), 3000.0);
  EXPECT_LE(worstRowError(shape), kRowTolerance);

  const LinearPressure p{-4.345085471868515e-06, 0.188690185546875, -1.7976931348623157e+308};
  const PiMoments pm = piMoments(shape, p);
  // the reference in 50 digits, from the 50-digit table
  const BigTable ref = bigTable(shape.vertices());
  const Big c[3] = {Big(p.p0), Big(p.cx), Big(p.cy)};
  const Big Pz = ref.area * c[0] + ref.sx * c[1] + ref.sy * c[2];
  ASSERT_GT(Pz, 0);
  const auto scale = entryScales(shape);
  for (int f = 1; f < 3; ++f) {
    const Big exact =
        (ref.withR[f][0] * c[0] + ref.withR[f][1] * c[1] + ref.withR[f][2] * c[2]) / Pz;
    const double got = f == 1 ? pm.pi_x0 : pm.pi_y0;
    // |Δ (∫ f p)| <= kRowTolerance eps sum_k |c_k| scale_k, plus Pz's own
    // rounding (relative: the polynomial rows, 4 eps max(1, D^2 / A))
    const double D = shape.diameter(), A = shape.area();
    double terms = 0.0;
    for (int k = 0; k < 3; ++k) terms += std::abs(static_cast<double>(c[k])) * scale[f][k];
    const double tolerance =
        kRowTolerance * kEps * terms / static_cast<double>(Pz) +
        4.0 * kEps * std::max(1.0, D * D / A) * std::abs(static_cast<double>(exact));
    EXPECT_NEAR(got, static_cast<double>(exact), tolerance) << (f == 1 ? "pi_x0" : "pi_y0");
    std::printf("[ info ] %s %.17g, 50 digits %.17g, off %.2g (tolerance %.2g)\n",
                f == 1 ? "pi_x0" : "pi_y0", got, static_cast<double>(exact),
                std::abs(got - static_cast<double>(exact)), tolerance);
  }
  // and so within the target's bound, ∫|p| / Pz as pi_fuzz computes it (its message)
  EXPECT_LE(std::hypot(pm.pi_x0, pm.pi_y0), 9.4583940991483004);
}

}  // namespace
}  // namespace patchspin
