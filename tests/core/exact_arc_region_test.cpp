// The exact model, Eq. (16), on regions bounded by segments and circular arcs
// (internal::exactArcRegionBasis): against the brute-force oracle
// (tests/support/exact_arc_oracle.hpp), against exactDiskBasis for an uncut
// disk, and against exactPolygonBasis on fine inscribed polygons.
#include <patchspin/geometry.hpp>
#include <patchspin/internal/exact.hpp>

#include <gtest/gtest.h>

#include "exact_arc_oracle.hpp"
#include "gauss_legendre_long.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace patchspin {
namespace {

using internal::BoundaryPiece;
using internal::exactArcRegionBasis;
using internal::ExactBasis;
using namespace testing::exact_arc;
using testing::exact_polygon::kContractTol;
using testing::exact_polygon::kernel;
using testing::exact_polygon::relativeError;
using testing::exact_polygon::wForIcr;

struct NamedRegion {
  std::string name;
  Region region;
  double rho;
};

std::vector<NamedRegion> testRegions() {
  const Vec2 o(0.1, -0.05);
  return {
      {"disk segment, more than half", diskSegment(o, 0.6, 0.4, 0.25), 0.4},
      {"disk segment, less than half", diskSegment(o, 0.6, 2.0, -0.3), 0.35},
      {"disk segment, O outside", diskSegment(Vec2(1.2, 0.7), 0.5, -1.0, 0.1), 0.5},
      {"thin disk segment", diskSegment(o, 0.6, 1.0, -0.5), 0.3},
      {"lens, equal radii", lens(Vec2(-0.3, 0.0), 0.5, Vec2(0.3, 0.1), 0.5), 0.4},
      {"lens, unequal radii", lens(Vec2(0.0, -0.2), 0.7, Vec2(0.5, 0.4), 0.4), 0.3},
  };
}

// Directions at the special places of a region: its first piece is an arc
// (centre o, radius a), its second (if any) the chord or the other arc.
std::vector<std::pair<std::string, Vec3>> testDirections(const Region& region, double rho) {
  std::vector<std::pair<std::string, Vec3>> ws;
  ws.push_back({"pure spin +", Vec3(0, 0, 1)});
  ws.push_back({"pure spin -", Vec3(0, 0, -1)});
  ws.push_back({"translation x", Vec3(1, 0, 0)});
  ws.push_back({"translation oblique", Vec3(-0.6, 0.8, 0)});
  const Vec2 dir(0.8, -0.6);
  for (double w3 : {1e-3, 1e-6, 1e-9, -1e-9}) {
    const double s = std::sqrt(1.0 - w3 * w3);
    ws.push_back({"w3 = " + std::to_string(w3), Vec3(s * dir.x(), s * dir.y(), w3)});
  }
  const BoundaryPiece& arc = region[0];
  const Vec2 o = arc.centre;
  const double a = arc.radius;
  const double tm = 0.5 * (arc.angle0 + arc.angle1);
  const Vec2 corner = arc.start(), corner2 = arc.end();
  const BoundaryPiece& next = region[1 % region.size()];  // the arc itself for a whole disk
  const Vec2 mid2 = next.kind == BoundaryPiece::Kind::Segment
                        ? Vec2(0.5 * (next.a + next.b))
                        : onCircle(next.centre, next.radius, 0.5 * (next.angle0 + next.angle1));
  ws.push_back({"ICR at corner", wForIcr(corner, rho, 1.0)});
  ws.push_back({"ICR at other corner, spin -", wForIcr(corner2, rho, -1.0)});
  ws.push_back({"ICR on arc", wForIcr(onCircle(o, a, tm), rho, 1.0)});
  ws.push_back({"ICR on arc near corner", wForIcr(onCircle(o, a, arc.angle0 + 1e-3), rho, -1.0)});
  ws.push_back({"ICR just inside arc", wForIcr(onCircle(o, a * (1.0 - 1e-9), tm + 0.3), rho, 1.0)});
  ws.push_back(
      {"ICR just outside arc", wForIcr(onCircle(o, a * (1.0 + 1e-9), tm - 0.3), rho, 1.0)});
  ws.push_back(
      {"ICR on the circle off the arc", wForIcr(onCircle(o, a, arc.angle0 - 0.2), rho, 1.0)});
  ws.push_back({"ICR on the second piece", wForIcr(mid2, rho, 1.0)});
  ws.push_back({"ICR at the circle's centre", wForIcr(o, rho, 1.0)});
  // m = 4 a D / (D + a)^2 = 0.1 (series / closed-form switch) at D = 0.02633 a
  ws.push_back({"ICR near centre, series side", wForIcr(o + 0.0263 * a * dir, rho, 1.0)});
  ws.push_back({"ICR near centre, elliptic side", wForIcr(o + 0.0264 * a * dir, rho, -1.0)});
  ws.push_back({"ICR 3 radii out", wForIcr(onCircle(o, 3.0 * a, tm), rho, 1.0)});
  ws.push_back({"ICR 7.9 radii out", wForIcr(onCircle(o, 7.9 * a, tm + 1.0), rho, 1.0)});
  ws.push_back({"ICR 9 radii out", wForIcr(onCircle(o, 9.0 * a, tm + 1.0), rho, 1.0)});
  ws.push_back({"ICR 15.9 radii out", wForIcr(onCircle(o, 15.9 * a, tm + 2.0), rho, 1.0)});
  ws.push_back({"ICR 17 radii out", wForIcr(onCircle(o, 17.0 * a, tm + 2.0), rho, -1.0)});
  ws.push_back({"ICR 30 radii out", wForIcr(onCircle(o, 30.0 * a, tm), rho, -1.0)});
  std::mt19937 rng(2026);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 4; ++i) {
    const Vec3 w(normal(rng), normal(rng), normal(rng));
    ws.push_back({"random " + std::to_string(i), w.normalized()});
  }
  return ws;
}

TEST(ExactArcRegionBasis, MatchesBruteForceOracleEverywhere) {
  double worst = 0.0;
  testing::exact_polygon::gOracleCapped = 0;
  for (const NamedRegion& nr : testRegions()) {
    const Vec3 scale = columnScales(nr.region, nr.rho);
    for (const auto& [label, w] : testDirections(nr.region, nr.rho)) {
      ExactBasis out;
      exactArcRegionBasis(nr.region, nr.rho, w, false, out);
      ASSERT_TRUE(out.F.allFinite()) << nr.name << " / " << label;
      const Mat3 ref = oracleF(nr.region, nr.rho, w);
      const double err = relativeError(out.F, ref, scale);
      worst = std::max(worst, err);
      EXPECT_LE(err, kContractTol) << nr.name << " / " << label << "\nF =\n"
                                   << out.F << "\noracle =\n"
                                   << ref;
    }
  }
  EXPECT_EQ(testing::exact_polygon::gOracleCapped, 0);
  std::printf("worst normwise error against the oracle: %.3g\n", worst);
}

// The cut vanishes: one arc of 2 pi is the disk, whose closed form
// (exact_disk.cpp: complete elliptic integrals and series) is independent of
// the boundary moments. Tolerance: both laws are accurate to ~1e-13 of the
// column scale (their oracle tests), so 1e-12 leaves a margin of 10; dF as well.
TEST(ExactArcRegionBasis, WholeDiskMatchesDiskLaw) {
  constexpr double kDiskAgreementTol = 1e-12;
  // relative to max |dF[k]|: measured 1.8e-11 to 4.3e-11 (the disk law's dF is ~1e-11)
  constexpr double kDiskJacobianTol = 1e-10;
  const Vec2 o(0.3, -0.2);
  const double R = 0.7, rho = 0.45;
  const Region disk = {BoundaryPiece::arc(o, R, -1.0, -1.0 + 2.0 * M_PI)};
  const Vec3 scale = columnScales(disk, rho);
  double worst = 0.0, worstJacobian = 0.0;
  for (const auto& [label, w] : testDirections(disk, rho)) {
    ExactBasis arc, ref;
    exactArcRegionBasis(disk, rho, w, true, arc);
    internal::exactDiskBasis(o, R, rho, w, true, ref);
    const double err = relativeError(arc.F, ref.F, scale);
    worst = std::max(worst, err);
    EXPECT_LE(err, kDiskAgreementTol) << label;
    for (int k = 0; k < 3; ++k) {
      const double size = ref.dF[k].cwiseAbs().maxCoeff();
      const double jerr = (arc.dF[k] - ref.dF[k]).cwiseAbs().maxCoeff() / size;
      worstJacobian = std::max(worstJacobian, jerr);
      EXPECT_LE(jerr, kDiskJacobianTol) << label << " column " << k;
    }
  }
  std::printf("worst normwise difference to the disk law: F %.3g, dF %.3g\n", worst, worstJacobian);
}

// Against the polygon law on inscribed polygons with n = 256 and 1024
// vertices per arc: the polygon's error is its area deficit, O(n^-2), so
// e(1024) ~ |F(256) - F(1024)| / 15 (Richardson). Asserted: the arc law is
// within 0.2 |F(256) - F(1024)| of F(1024) (the prediction 1/15 with a
// margin of 3), plus 1e-13 of the scale for rounding.
TEST(ExactArcRegionBasis, AgreesWithFinePolygonsToTheirDiscretisationError) {
  double worstRatio = 0.0;
  for (const NamedRegion& nr : testRegions()) {
    const Vec3 scale = columnScales(nr.region, nr.rho);
    const auto coarse = polygonOf(nr.region, 256), fine = polygonOf(nr.region, 1024);
    for (const auto& [label, w] : testDirections(nr.region, nr.rho)) {
      ExactBasis arc, pc, pf;
      exactArcRegionBasis(nr.region, nr.rho, w, false, arc);
      internal::exactPolygonBasis(coarse, nr.rho, w, false, pc);
      internal::exactPolygonBasis(fine, nr.rho, w, false, pf);
      const double discretisation = relativeError(pc.F, pf.F, scale);
      const double err = relativeError(arc.F, pf.F, scale);
      EXPECT_LE(err, 0.2 * discretisation + 1e-13)
          << nr.name << " / " << label << ": |F(256) - F(1024)| = " << discretisation;
      worstRatio = std::max(worstRatio, (err - 1e-13) / discretisation);
    }
  }
  std::printf("worst |arc - F(1024)| / |F(256) - F(1024)|: %.3g (1/15 expected)\n", worstRatio);
}

// dF[k] against central differences of F.col(k) in w, Richardson-extrapolated
// (4 D(h/2) - D(h)) / 3, h = kStep / (1 + max|P|/rho) (the polygon test's
// scaling). Plain central differences at kStep = 1e-5 were measured at 3e-8:
// truncation h^2 |F'''| / 6 (|F'''| grows like (rho / w3^2)^3 for ICRs a few
// sizes out) plus F's own rounding (~5e-13, moments of size kappa^3) / h.
// Extrapolated, the worst error was 1.7e-9 / 8.5e-10 / 1.75e-9 at kStep =
// 3e-3 / 1e-3 / 3e-4 (truncation O(h^4) against rounding / h), so kFdTol =
// 1e-8 of the column scale at 1e-3, the ICR at least kMinIcrClearance from
// the boundary (F'' is log-singular on it); dF[k] w = 0 to rounding.
TEST(ExactArcRegionBasis, JacobianMatchesFiniteDifferences) {
  constexpr double kStep = 1e-3;
  constexpr double kFdTol = 1e-8;
  constexpr double kMinIcrClearance = 0.05;
  constexpr double kEulerTol = 1e-12;
  auto centralDifference = [](const NamedRegion& nr, const Vec3& w, int j, double h) {
    ExactBasis plus, minus;
    Vec3 wp = w, wm = w;
    wp[j] += h;
    wm[j] -= h;
    exactArcRegionBasis(nr.region, nr.rho, wp, false, plus);
    exactArcRegionBasis(nr.region, nr.rho, wm, false, minus);
    return Mat3((plus.F - minus.F) / (2 * h));
  };
  std::mt19937 rng(2025);
  std::normal_distribution<double> normal;
  double worst = 0.0;
  for (const NamedRegion& nr : testRegions()) {
    const Vec3 scale = columnScales(nr.region, nr.rho);
    const std::vector<Vec2> samples = boundarySamples(nr.region, 2000);
    double rmax = 0.0;
    for (const Vec2& p : samples) rmax = std::max(rmax, p.norm());
    int checked = 0;
    for (int trial = 0; trial < 300 && checked < 30; ++trial) {
      Vec3 w(normal(rng), normal(rng), normal(rng));
      if (trial % 3 == 0) w.z() *= 1e-2;  // include the far branch
      if (trial % 3 == 1) w.z() *= 0.3;   // ICRs a few sizes out
      w.normalize();
      const Vec2 c(-nr.rho * w.y() / w.z(), nr.rho * w.x() / w.z());
      double clearance = INFINITY;
      for (const Vec2& p : samples) clearance = std::min(clearance, (p - c).norm());
      if (clearance < kMinIcrClearance) continue;
      ++checked;
      const double h = kStep / (1.0 + rmax / nr.rho);
      ExactBasis out;
      exactArcRegionBasis(nr.region, nr.rho, w, true, out);
      for (int j = 0; j < 3; ++j) {
        const Mat3 fd =
            (4.0 * centralDifference(nr, w, j, 0.5 * h) - centralDifference(nr, w, j, h)) / 3.0;
        for (int k = 0; k < 3; ++k) {
          const double err = (out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / scale[k];
          worst = std::max(worst, err);
          EXPECT_LE(err, kFdTol) << nr.name << " w = " << w.transpose() << " column " << k << " dw"
                                 << j;
        }
      }
      for (int k = 0; k < 3; ++k)
        EXPECT_LE((out.dF[k] * w).cwiseAbs().maxCoeff() / scale[k], kEulerTol) << nr.name;
    }
    EXPECT_GE(checked, 25) << nr.name;
  }
  std::printf("worst dF error against central differences: %.3g\n", worst);
}

// ICR on the arc, at a corner, on the chord and at the circle's centre (the
// series side): F is C^1 there, so dF must be finite and match central
// differences to O(hc log hc) of its own size, hc <= 1e-6 of the radius the
// ICR's step (as the polygon's JacobianContinuousWithIcrOnBoundary): 1e-4.
TEST(ExactArcRegionBasis, JacobianContinuousWithIcrOnBoundary) {
  constexpr double kIcrStep = 1e-6;
  constexpr double kFdTolSingular = 1e-4;
  double worst = 0.0;
  for (const NamedRegion& nr : testRegions()) {
    const BoundaryPiece& arc = nr.region[0];
    const double tm = 0.5 * (arc.angle0 + arc.angle1);
    const Vec2 second = nr.region[1].kind == BoundaryPiece::Kind::Segment
                            ? Vec2(0.5 * (nr.region[1].a + nr.region[1].b))
                            : nr.region[1].start();
    for (const Vec2& c : {onCircle(arc.centre, arc.radius, tm), arc.start(), second,
                          onCircle(arc.centre, arc.radius, tm + 0.2), Vec2(arc.centre)}) {
      const Vec3 w = wForIcr(c, nr.rho, 1.0);
      const double dcdw = nr.rho / std::abs(w.z()) * (1.0 + c.norm() / nr.rho);
      const double h = kIcrStep * arc.radius / dcdw;
      ExactBasis out;
      exactArcRegionBasis(nr.region, nr.rho, w, true, out);
      double size = 0.0;
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(out.dF[k].allFinite()) << nr.name << " c = " << c.transpose();
        size = std::max(size, out.dF[k].cwiseAbs().maxCoeff());
      }
      for (int j = 0; j < 3; ++j) {
        ExactBasis plus, minus;
        Vec3 wp = w, wm = w;
        wp[j] += h;
        wm[j] -= h;
        exactArcRegionBasis(nr.region, nr.rho, wp, false, plus);
        exactArcRegionBasis(nr.region, nr.rho, wm, false, minus);
        const Mat3 fd = (plus.F - minus.F) / (2 * h);
        for (int k = 0; k < 3; ++k) {
          const double err = (out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / size;
          worst = std::max(worst, err);
          EXPECT_LE(err, kFdTolSingular)
              << nr.name << " c = " << c.transpose() << " column " << k << " dw" << j;
        }
      }
    }
  }
  std::printf("worst dF error against central differences, ICR on the boundary: %.3g\n", worst);
}

// dF against the polygon law's Jacobian on inscribed 256- and 1024-gons, as
// for F (Richardson: the 1024-gon's error ~ 1/15 of their difference; 0.2
// asserted, plus 1e-12 of |dF| for rounding). ICRs on or next to the
// boundary are left out: there the polygons' dF differs from the arc's by
// O(1) near the cut-off vertices, not O(n^-2).
TEST(ExactArcRegionBasis, JacobianAgreesWithFinePolygons) {
  double worstRatio = 0.0;
  for (const NamedRegion& nr : testRegions()) {
    const auto coarse = polygonOf(nr.region, 256), fine = polygonOf(nr.region, 1024);
    for (const auto& [label, w] : testDirections(nr.region, nr.rho)) {
      const bool onBoundary = label.find("ICR") != std::string::npos &&
                              label.find("out") == std::string::npos &&
                              label.find("centre") == std::string::npos;
      if (onBoundary) continue;
      ExactBasis arc, pc, pf;
      exactArcRegionBasis(nr.region, nr.rho, w, true, arc);
      internal::exactPolygonBasis(coarse, nr.rho, w, true, pc);
      internal::exactPolygonBasis(fine, nr.rho, w, true, pf);
      for (int k = 0; k < 3; ++k) {
        const double size = pf.dF[k].cwiseAbs().maxCoeff();
        const double discretisation = (pc.dF[k] - pf.dF[k]).cwiseAbs().maxCoeff();
        const double err = (arc.dF[k] - pf.dF[k]).cwiseAbs().maxCoeff();
        EXPECT_LE(err, 0.2 * discretisation + 1e-12 * size)
            << nr.name << " / " << label << " column " << k
            << ": |dF(256) - dF(1024)| = " << discretisation;
        if (discretisation > 0.0) worstRatio = std::max(worstRatio, err / discretisation);
      }
    }
  }
  std::printf("worst |dF - dF(1024)| / |dF(256) - dF(1024)|: %.3g (1/15 expected)\n", worstRatio);
}

// The frame centre g and region radius of exactArcRegionBasis (as
// exact_arc_region.cpp defines them: g the mean of the pieces' start points
// and arc mid points, the radius the largest |P - g| on the boundary, here
// from dense samples plus the arcs' extremes), so that the ICR can be placed
// kappa radii from g.
void lawFrame(const Region& region, Vec2& g, double& radius) {
  g = Vec2::Zero();
  int count = 0;
  for (const BoundaryPiece& p : region) {
    if (p.kind == BoundaryPiece::Kind::Arc) {
      g += onCircle(p.centre, p.radius, 0.5 * (p.angle0 + p.angle1));
      ++count;
    }
    g += p.start();
    ++count;
  }
  g /= count;
  radius = 0.0;
  for (const Vec2& p : boundarySamples(region, 20000)) radius = std::max(radius, (p - g).norm());
}

// The far branch (ICR beyond 8 region radii of g, or w3 = 0: Green's
// theorem and a boundary Gauss rule whose orders target 1e-13 of F's
// scale) at kappa from just beyond the switch to 1e7 and at infinity, in 8
// directions each, both spins, on every test region, the whole disk, a
// disk cut at R (1 - 1e-8) (arcs of 2 pi and almost 2 pi) and a sliver cap
// (height R / 200: an arc of radius 10 region radii):
//  * F (alone and with dF: the rule's orders differ) against the oracle to
//    kFarOracleTol = 2e-12 of the column scale: 20
//    times the rule's target, twice the oracle's own per-entry tolerance
//    (1e-12, an overestimate), 50 times under the 1e-10 contract;
//  * dF against Richardson-extrapolated central differences (as
//    JacobianMatchesFiniteDifferences, step 1e-3 / (1 + max|P|/rho)) to
//    kFarFdTol = 1e-9 of the column scale: the differences' own error
//    (measured up to 1.5e-10, not shrinking with h: F's rounding and its
//    quadrature error, which jumps where the rule's order changes, over h),
//    a tenth of JacobianMatchesFiniteDifferences' 1e-8;
//    kappa starts at 8.1 so that the steps, which change kappa by < 0.5 %,
//    stay in the far branch (the near branch's rounding / h would dominate);
//  * dF[k] w = 0 to kEulerTol (degree-0 homogeneity).
// The ICR at an arc's centre: pure spin about O, the centre of a unit coin
// cut to a thin cap ~30 cap radii from it (the far branch), rho its chord
// (PatchShape's table rows with r). There the arc's singular factor is
// constant; the far rule's order took log(0) (NaN converted to int: the pi
// fuzz target's cap, under UBSan, which the sanitizer presets run this test
// under). Tolerance as FarBranchMatchesOracleAcrossKappa's.
TEST(ExactArcRegionBasis, IcrAtAnArcsCentreMatchesOracle) {
  constexpr double kFarOracleTol = 2e-12;
  const double span = 0.061337777932991562;
  const Region cap = {BoundaryPiece::arc(Vec2::Zero(), 1.0, 0.0, span),
                      BoundaryPiece::segment(Vec2(std::cos(span), std::sin(span)), Vec2(1.0, 0.0))};
  const double rho = 2.0 * std::sin(span / 2.0);
  const Vec3 scale = columnScales(cap, rho);
  for (double spin : {1.0, -1.0}) {
    const Vec3 w(0.0, 0.0, spin);
    const Mat3 ref = oracleF(cap, rho, w);
    for (bool jacobian : {false, true}) {
      ExactBasis out;
      exactArcRegionBasis(cap, rho, w, jacobian, out);
      EXPECT_LE(relativeError(out.F, ref, scale), kFarOracleTol)
          << "spin " << spin << ", jacobian " << jacobian;
    }
  }
}

TEST(ExactArcRegionBasis, FarBranchMatchesOracleAcrossKappa) {
  constexpr double kFarOracleTol = 2e-12;
  constexpr double kFarFdTol = 1e-9;
  constexpr double kEulerTol = 1e-12;
  constexpr double kStep = 1e-3;
  double worst = 0.0, worstFd = 0.0, worstEuler = 0.0;
  testing::exact_polygon::gOracleCapped = 0;
  std::vector<NamedRegion> regions = testRegions();
  const Vec2 o(0.3, -0.2);
  regions.push_back({"whole disk", {BoundaryPiece::arc(o, 0.7, -1.0, -1.0 + 2.0 * M_PI)}, 0.45});
  regions.push_back(
      {"disk cut at R (1 - 1e-8)", diskSegment(o, 0.7, 0.7, 0.7 * (1.0 - 1e-8)), 0.45});
  for (const NamedRegion& nr : regions) {
    const Vec3 scale = columnScales(nr.region, nr.rho);
    Vec2 g;
    double radius;
    lawFrame(nr.region, g, radius);
    double rmax = 0.0;
    for (const Vec2& p : boundarySamples(nr.region, 2000)) rmax = std::max(rmax, p.norm());
    const double h = kStep / (1.0 + rmax / nr.rho);
    std::vector<std::pair<std::string, Vec3>> ws;
    for (int i = 0; i < 8; ++i) {
      const double a = 0.3 + 2.0 * M_PI * i / 8.0;
      const Vec2 e(std::cos(a), std::sin(a));
      ws.push_back({"translation " + std::to_string(i), Vec3(e.x(), e.y(), 0.0)});
      for (double kappa : {8.1, 9.0, 12.0, 20.0, 50.0, 1e2, 1e3, 1e4, 1e5, 1e7}) {
        const double spin = i % 2 == 0 ? 1.0 : -1.0;
        ws.push_back({"kappa " + std::to_string(kappa) + " direction " + std::to_string(i),
                      wForIcr(g + kappa * radius * e, nr.rho, spin)});
      }
    }
    for (const auto& [label, w] : ws) {
      ExactBasis out, alone;
      exactArcRegionBasis(nr.region, nr.rho, w, true, out);
      exactArcRegionBasis(nr.region, nr.rho, w, false, alone);  // F alone: its own orders
      const Mat3 ref = oracleF(nr.region, nr.rho, w);
      for (const Mat3& F : {out.F, alone.F}) {
        const double err = relativeError(F, ref, scale);
        worst = std::max(worst, err);
        EXPECT_LE(err, kFarOracleTol) << nr.name << " / " << label;
      }
      for (int j = 0; j < 3; ++j) {
        auto central = [&](double step) {
          ExactBasis plus, minus;
          Vec3 wp = w, wm = w;
          wp[j] += step;
          wm[j] -= step;
          exactArcRegionBasis(nr.region, nr.rho, wp, false, plus);
          exactArcRegionBasis(nr.region, nr.rho, wm, false, minus);
          return Mat3((plus.F - minus.F) / (2.0 * step));
        };
        const Mat3 fd = (4.0 * central(0.5 * h) - central(h)) / 3.0;
        for (int k = 0; k < 3; ++k) {
          const double e = (out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / scale[k];
          worstFd = std::max(worstFd, e);
          EXPECT_LE(e, kFarFdTol) << nr.name << " / " << label << " column " << k << " dw" << j;
        }
      }
      for (int k = 0; k < 3; ++k) {
        const double e = (out.dF[k] * w).cwiseAbs().maxCoeff() / scale[k];
        worstEuler = std::max(worstEuler, e);
        EXPECT_LE(e, kEulerTol) << nr.name << " / " << label;
      }
    }
  }
  EXPECT_EQ(testing::exact_polygon::gOracleCapped, 0);
  std::printf(
      "far branch: worst F error against the oracle %.3g, dF against differences %.3g, "
      "|dF w| %.3g\n",
      worst, worstFd, worstEuler);
}

// More pieces than exactArcRegionBasis keeps on the stack (16): a 20-gon
// given as 20 segments against the polygon law on its vertices (an
// independent edge sum and fan rule), near and far ICRs and w3 = 0. Both
// laws are within ~1e-13 of their oracles, so kPolygonAgreementTol = 1e-12
// of the column scale.
TEST(ExactArcRegionBasis, ManySegmentsMatchPolygonLaw) {
  constexpr double kPolygonAgreementTol = 1e-12;
  std::vector<Vec2> poly;
  Region region;
  for (int i = 0; i < 20; ++i)
    poly.push_back(onCircle(Vec2(0.2, -0.1), 0.5, 2.0 * M_PI * i / 20.0));
  for (int i = 0; i < 20; ++i)
    region.push_back(BoundaryPiece::segment(poly[i], poly[(i + 1) % 20]));
  const double rho = 0.4;
  const Vec3 scale = columnScales(region, rho);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    Vec3 w(normal(rng), normal(rng), normal(rng));
    if (i % 3 == 0) w.z() *= 1e-2;  // far ICRs
    if (i % 10 == 0) w.z() = 0.0;
    ExactBasis arc, ref;
    exactArcRegionBasis(region, rho, w, false, arc);
    internal::exactPolygonBasis(poly, rho, w, false, ref);
    const double err = relativeError(arc.F, ref.F, scale);
    worst = std::max(worst, err);
    EXPECT_LE(err, kPolygonAgreementTol) << "w = " << w.transpose();
  }
  std::printf("20 segments against the polygon law: worst %.3g\n", worst);
}

// The cut shrinks to nothing: a disk segment cut at h = R (1 - eps) differs
// from the whole disk by the cap of area ~ (4 sqrt(2) / 3) R^2 eps^(3/2), whose
// contribution to every column is at most its area times the column scale per
// unit area (|k| <= 1 + |P| / rho, |phi| <= max|phi|). Asserted: the
// normwise difference to the disk law is within 2 cap areas / disk area, plus
// 1e-12 for the two laws' rounding (a short chord, an arc of almost 2 pi).
TEST(ExactArcRegionBasis, VanishingCutApproachesDiskLaw) {
  const Vec2 o(0.3, -0.2);
  const double R = 0.7, rho = 0.45;
  for (double eps : {1e-4, 1e-8, 1e-12}) {
    const Region segment = diskSegment(o, R, 0.7, R * (1.0 - eps));
    const Region disk = {BoundaryPiece::arc(o, R, 0.0, 2.0 * M_PI)};
    const Vec3 scale = columnScales(disk, rho);
    const double cap = 4.0 * std::sqrt(2.0) / 3.0 * R * R * std::pow(eps, 1.5);
    const double bound = 2.0 * cap / (M_PI * R * R) + 1e-12;
    double worst = 0.0;
    for (const auto& [label, w] : testDirections(segment, rho)) {
      ExactBasis arc, ref;
      exactArcRegionBasis(segment, rho, w, false, arc);
      internal::exactDiskBasis(o, R, rho, w, false, ref);
      const double err = relativeError(arc.F, ref.F, scale);
      worst = std::max(worst, err);
      EXPECT_LE(err, bound) << "eps = " << eps << " / " << label;
    }
    std::printf("cut at R (1 - %.0e): worst difference to the disk law %.3g (bound %.3g)\n", eps,
                worst, bound);
  }
}

// Never NaN: a dense deterministic sweep of w with extreme component
// magnitudes (10^-300 .. 1), and ICRs placed exactly on the circle, at its
// centre and at the arc's ends; F bounded by its column scale (|k| <= 1 +
// |P| / rho), dF finite.
TEST(ExactArcRegionBasis, FiniteAndBoundedEverywhere) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> expo(-300, 0);
  for (const NamedRegion& nr : testRegions()) {
    const Vec3 scale = columnScales(nr.region, nr.rho);
    std::vector<Vec3> ws;
    for (int i = 0; i < 400; ++i) {
      Vec3 w(normal(rng), normal(rng), normal(rng));
      w[i % 3] *= std::pow(10.0, expo(rng));
      ws.push_back(w);
    }
    const BoundaryPiece& arc = nr.region[0];
    for (int i = 0; i <= 64; ++i) {
      const double t = arc.angle0 + (arc.angle1 - arc.angle0) * i / 64.0;
      ws.push_back(wForIcr(onCircle(arc.centre, arc.radius, t), nr.rho, i % 2 ? 1.0 : -1.0));
    }
    ws.push_back(wForIcr(arc.centre, nr.rho, 1.0));
    ws.push_back(wForIcr(arc.end(), nr.rho, 1.0));
    for (const Vec3& w : ws) {
      ExactBasis out;
      exactArcRegionBasis(nr.region, nr.rho, w, true, out);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(out.F.col(k).allFinite() && out.dF[k].allFinite())
            << nr.name << " w = " << w.transpose();
        EXPECT_LE(out.F.col(k).cwiseAbs().maxCoeff(), scale[k] * (1.0 + 1e-12)) << nr.name;
      }
    }
  }
}

using patchspin::testing::gaussLegendreLong;

// A cap of the unit circle about c0 (half-angle h about direction t0, closed
// by its chord) and F on it by a tensor Gauss-Legendre rule (40 x 40) in the
// chord's frame, as its pieces' end points define it (the segment's ends,
// mid M, direction e, outward n, radius R' = |end - start| / (2 sin h)):
// y along e in [-L/2, L/2], x along n in [0, (L/2 - y)(L/2 + y) /
// (sqrt(R'^2 - y^2) + R' cos h)] (the height without cancellation). The
// kernel is the oracle's; the rule is exact to rounding while the ICR is
// many cap sizes away (the integrand analytic on a neighbourhood of the cap
// many times its size). Also the cap's area.
Region flatCap(const Vec2& c0, double t0, double h) {
  Region cap = {BoundaryPiece::arc(c0, 1.0, t0 - h, t0 + h),
                BoundaryPiece::segment(Vec2::Zero(), Vec2::Zero())};
  cap[1] = BoundaryPiece::segment(cap[0].end(), cap[0].start());
  return cap;
}
Mat3 capByChordRule(const Region& cap, double rho, const Vec3& w, double& area) {
  // the half-angle as stored (t0 +- h rounds it by ~eps t0 / h relative)
  const double h = 0.5 * (cap[0].angle1 - cap[0].angle0);
  std::vector<long double> gx, gw;
  gaussLegendreLong(40, gx, gw);
  const Vec2 s0 = cap[0].start(), s1 = cap[0].end();
  const double L = (s1 - s0).norm();
  const Vec2 e = (s1 - s0) / L, n(e.y(), -e.x()), M = 0.5 * (s0 + s1);
  const double Rp = 0.5 * L / std::sin(h);
  Mat3 F = Mat3::Zero();
  area = 0.0;
  for (std::size_t i = 0; i < gx.size(); ++i) {
    const double y = 0.5 * L * static_cast<double>(gx[i]);
    const double wy = 0.5 * L * static_cast<double>(gw[i]);
    const double top =
        (0.5 * L - y) * (0.5 * L + y) / (std::sqrt(Rp * Rp - y * y) + Rp * std::cos(h));
    for (std::size_t j = 0; j < gx.size(); ++j) {
      const double x = 0.5 * top * (1.0 + static_cast<double>(gx[j]));
      const double wt = wy * 0.5 * top * static_cast<double>(gw[j]);
      const Vec2 P = M + x * n + y * e;
      F += wt * kernel(w, rho, P.x(), P.y()) * Vec3(1.0, P.x(), P.y()).transpose();
      area += wt;
    }
  }
  return F;
}

// Flat caps (half-angles 0.05 down to 5e-10, the pi fuzz target's 1e-9 span)
// in the far branch, which for an arc of radius > 16 region sizes is an
// area rule (farAreaRule: Green's theorem on the thin cap cancelled to eps
// / h, the arc's points about its centre to eps / h^2, |(pi_x0, pi_y0)| =
// 1.83 at h = 5e-10). Directions: pure spin about O (the circle's centre,
// as the moment table's rows with r), translations and ICRs 12 to 1e4 cap
// sizes from the cap. Asserted, relative to the column scale A max|phi|
// (1 + max|P|/rho) of the reference's A:
//  * F, with and without dF, against capByChordRule to kFlatCapTol = 1e-13
//    (the far rule's target; both rules exact to rounding here);
//  * F with and without dF to kFlatCapTol of each other (the friction_q
//    fuzz check: 3e-9 at h = 1.7e-4 before);
//  * dF against Richardson-extrapolated central differences to 1e-8 of the
//    scale (JacobianMatchesFiniteDifferences' kFdTol), steps that move the
//    ICR by 1e-3 of its distance, for h >= 1e-4 (on smaller caps F's
//    rounding over such steps exceeds the tolerance: 6e-4 at h = 5e-10);
//  * at pure spin about O, |(F(0, 0), F(1, 0))| <= A (1 + kUnitTol), A the
//    area moments' (the kernel is a unit vector; kUnitTol = 1e-14, a few
//    rounding errors of the area and the sum).
TEST(ExactArcRegionBasis, FlatCapsMatchChordQuadrature) {
  constexpr double kFlatCapTol = 1e-13, kUnitTol = 1e-14;
  const double t0 = 0.7;
  const Vec2 dir0(std::cos(t0), std::sin(t0));
  for (const Vec2& c0 : {Vec2(0.0, 0.0), Vec2(0.3, -0.2), Vec2(-dir0)}) {
    // the last: the cap at O (within h^2), where ICRs a few cap sizes out
    // are given to eps of the cap (elsewhere w fixes them to eps of |P|,
    // 1e-7 of a cap of 2e-9)
    const bool capAtO = c0 == -dir0;
    for (double h : {0.05, 1.7e-4, 1e-6, 5e-10}) {
      const Region cap = flatCap(c0, t0, h);
      const Vec2 mid = c0 + std::cos(h) * dir0;
      const double capSize = std::sin(h);
      for (double rho : {1.0, capSize}) {
        std::vector<std::pair<std::string, Vec3>> ws = {{"translation", Vec3(0.6, -0.8, 0)}};
        if (capAtO) {
          for (double kappa : {12.0, 100.0, 1e4})
            for (double dir : {0.0, 2.0, 4.0})
              ws.push_back({"ICR " + std::to_string(kappa) + " sizes out",
                            wForIcr(mid + kappa * capSize * Vec2(std::cos(dir), std::sin(dir)), rho,
                                    dir > 1.0 ? -1.0 : 1.0)});
        } else {
          ws.push_back({"pure spin about O", Vec3(0, 0, 1)});
          ws.push_back({"pure spin about O, -", Vec3(0, 0, -1)});
        }
        for (const auto& [label, w] : ws) {
          char at[160];
          std::snprintf(at, sizeof at, "h = %g, rho = %g, c0 = (%g, %g), %s", h, rho, c0.x(),
                        c0.y(), label.c_str());
          double A = 0.0;
          const Mat3 ref = capByChordRule(cap, rho, w, A);
          double rmax = 0.0;
          for (const BoundaryPiece& p : cap) rmax = std::max(rmax, p.start().norm());
          const double s = A * (1.0 + (rmax + capSize) / rho);
          const Vec3 scale(s, s * (rmax + capSize), s * (rmax + capSize));
          ExactBasis plain, withJ;
          exactArcRegionBasis(cap, rho, w, false, plain);
          exactArcRegionBasis(cap, rho, w, true, withJ);
          EXPECT_LE(relativeError(plain.F, ref, scale), kFlatCapTol) << at << "\n"
                                                                     << plain.F << "\n"
                                                                     << ref;
          EXPECT_LE(relativeError(withJ.F, ref, scale), kFlatCapTol) << at;
          EXPECT_LE(relativeError(withJ.F, plain.F, scale), kFlatCapTol) << at;
          // dF against Richardson-extrapolated central differences, as
          // JacobianMatchesFiniteDifferences (kFdTol 1e-8 of the scale)
          auto difference = [&](int j, double step) {
            ExactBasis plus, minus;
            Vec3 wp = w, wm = w;
            wp[j] += step, wm[j] -= step;
            exactArcRegionBasis(cap, rho, wp, false, plus);
            exactArcRegionBasis(cap, rho, wm, false, minus);
            return Mat3((plus.F - minus.F) / (2.0 * step));
          };
          // the step moves the ICR by <= 1e-3 of its distance to the cap
          // (rho |dw| / |w3|, plus |c| |dw3| / |w3|), or, in translation,
          // puts it >= 1e3 (rho / max|P|) away
          double step = 1e-3 * std::min(1.0, rho / (rmax + capSize));
          if (w.z() != 0.0) {
            const Vec2 c(-rho * w.y() / w.z(), rho * w.x() / w.z());
            step = std::min(1e-3, 1e-3 * (c - mid).norm() * std::abs(w.z()) / (rho + c.norm()));
          }
          for (int j = 0; j < 3 && h >= 1e-4; ++j) {
            const Mat3 fd = (4.0 * difference(j, 0.5 * step) - difference(j, step)) / 3.0;
            for (int k = 0; k < 3; ++k)
              EXPECT_LE((withJ.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / scale[k], 1e-8)
                  << at << " column " << k << " dw" << j;
          }
          if (w == Vec3(0, 0, 1) && c0 == Vec2::Zero()) {
            const double area = areaMomentsOf(cap).area;
            EXPECT_NEAR(area, A, 1e-14 * A) << at;
            EXPECT_LE(plain.F.col(0).head<2>().norm(), area * (1.0 + kUnitTol)) << at;
          }
        }
      }
    }
  }
}

// A square face on a disk whose radius is just below the square's
// half-diagonal (by a relative 1e-7 and 1e-12): four short arcs at the
// corners (spans 1.3e-3 and 4e-6 rad), a region the Green's-theorem branches
// handle with their arcs about the centre (radius ~ the region's size).
// Against the brute-force oracle at testDirections' places (the first
// piece an arc) to the contract kContractTol, as
// MatchesBruteForceOracleEverywhere; F with and without dF to 1e-13 of the
// column scale (the far rule's target; the near branch's F does not
// depend on it).
TEST(ExactArcRegionBasis, ShortCornerArcsMatchOracle) {
  const double half = 0.05;
  const Vec2 c(0.002, -0.001);
  const std::vector<Vec2> square = {c + Vec2(-half, -half), c + Vec2(half, -half),
                                    c + Vec2(half, half), c + Vec2(-half, half)};
  for (double cut : {1e-7, 1e-12}) {
    const double R = std::sqrt(2.0) * half * (1.0 - cut);
    Region region = diskPolygonIntersection(c, R, square);
    ASSERT_EQ(region.size(), 8u);
    if (region[0].kind != BoundaryPiece::Kind::Arc)
      std::rotate(region.begin(), region.begin() + 1, region.end());
    ASSERT_EQ(region[0].kind, BoundaryPiece::Kind::Arc);
    const double rho = 0.04;
    const Vec3 scale = columnScales(region, rho);
    for (const auto& [label, w] : testDirections(region, rho)) {
      ExactBasis plain, withJ;
      exactArcRegionBasis(region, rho, w, false, plain);
      exactArcRegionBasis(region, rho, w, true, withJ);
      const Mat3 ref = oracleF(region, rho, w);
      EXPECT_LE(relativeError(plain.F, ref, scale), kContractTol)
          << "cut " << cut << " / " << label;
      EXPECT_LE(relativeError(withJ.F, plain.F, scale), 1e-13) << "cut " << cut << " / " << label;
    }
  }
}

// Thin regions (area below 1e-3 size^2) are their chord polygon plus the
// arcs' circular segments (exact_arc_region.cpp: summed boundary terms lost
// eps size^2 / area). The pi fuzz target's sliver, 1.04 m x 1e-9 m with a
// 1e-9 rad arc of radius 1 about O at its foot (its circular segment 1e-28
// of the area), against the polygon law on its pieces' start points, at
// pure spin about O (on its edge: |∫x (x/r)| was 1.5 ∫x), translations and
// ICRs on, near and far from it: within kThinTol = 1e-13 of the column
// scale (the two laws' own ~1e-13 against their oracles; the arc's segment
// is 1e-19 of the scale), F and dF.
TEST(ExactArcRegionBasis, ThinRegionsMatchPolygonLaw) {
  constexpr double kThinTol = 1e-13;
  const Region sliver = {
      BoundaryPiece::segment(Vec2(-1.2912755008898694e-236, 0.04044342041015625),
                             Vec2(6.123233995736766e-17, -1)),
      BoundaryPiece::arc(Vec2(0, 0), 1, -1.5707963267948966, -1.5707963257900757),
      BoundaryPiece::segment(Vec2(1.0048209543902383e-09, -1),
                             Vec2(1.0048211152025033e-09, -1.0230525589846103e-306)),
      BoundaryPiece::segment(Vec2(1.0048211152025033e-09, -1.0230525589846103e-306),
                             Vec2(-1.2912755008898694e-236, 0.04044342041015625))};
  std::vector<Vec2> chord;
  for (const BoundaryPiece& p : sliver) chord.push_back(p.start());
  for (double rho : {0.49035674092091064, 1e-9}) {
    const std::vector<std::pair<std::string, Vec3>> ws = {
        {"pure spin about O", Vec3(0, 0, 1)},
        {"pure spin about O, -", Vec3(0, 0, -1)},
        {"translation", Vec3(0.6, -0.8, 0)},
        {"ICR mid-sliver", wForIcr(Vec2(5e-10, -0.5), rho, 1.0)},
        {"ICR beside the sliver", wForIcr(Vec2(0.01, -0.3), rho, -1.0)},
        {"ICR 20 m out", wForIcr(Vec2(20.0, 3.0), rho, 1.0)}};
    double area = 0.0;
    for (std::size_t i = 0; i < chord.size(); ++i)
      area += 0.5 * (chord[i].x() * chord[(i + 1) % chord.size()].y() -
                     chord[i].y() * chord[(i + 1) % chord.size()].x());
    const double s = area * (1.0 + 1.05 / rho);
    const Vec3 scale(s, s * 1.1e-9, s * 1.05);
    for (const auto& [label, w] : ws) {
      ExactBasis arc, poly;
      exactArcRegionBasis(sliver, rho, w, true, arc);
      internal::exactPolygonBasis(chord, rho, w, true, poly);
      EXPECT_LE(relativeError(arc.F, poly.F, scale), kThinTol) << "rho " << rho << ", " << label;
      for (int k = 0; k < 3; ++k)
        EXPECT_LE(relativeError(arc.dF[k], poly.dF[k], scale), kThinTol)
            << "rho " << rho << ", " << label << ", dF " << k;
    }
  }
}

// The near branch on flat caps (arcs of radius > 16 region sizes: their
// boundary moments by graded Gauss panels in the chord frame,
// addFlatArcMoments; about the centre they were 3.3e-5 of the scale off at h
// = 0.01, 11 at h = 1e-3). The unit circle's cap at O, rho its half-chord,
// ICRs at its centroid, a chord end, the arc's middle, 2 and 6 cap sizes
// out: F against the brute-force oracle to the contract kContractTol (the
// oracle's chord heights lose ~eps / h^2, 2.5e-11 at h = 3e-3; measured
// worst 2.7e-11), dF (ICRs off the boundary) against finite differences.
TEST(ExactArcRegionBasis, FlatCapsNearBranchMatchOracle) {
  const double t0 = 0.7;
  const Vec2 dir0(std::cos(t0), std::sin(t0)), e(-dir0.y(), dir0.x());
  for (double h : {0.05, 0.01, 3e-3}) {
    const Region cap = flatCap(-dir0, t0, h);
    const double rho = std::sin(h);
    const Vec3 scale = columnScales(cap, rho);
    const Vec2 mid = -dir0 + std::cos(h) * dir0;
    const std::vector<std::pair<std::string, Vec2>> icrs = {
        {"centroid", mid - 0.3 * h * h * dir0},
        {"chord end", cap[0].start()},
        {"arc middle", mid + (1.0 - std::cos(h)) * dir0},
        {"2 sizes out", mid + 2.0 * h * e},
        {"6 sizes out", mid + 6.0 * h * dir0}};
    for (const auto& [label, icr] : icrs) {
      for (double spin : {1.0, -1.0}) {
        const Vec3 w = wForIcr(icr, rho, spin);
        ExactBasis out;
        exactArcRegionBasis(cap, rho, w, true, out);
        const Mat3 ref = oracleF(cap, rho, w);
        EXPECT_LE(relativeError(out.F, ref, scale), kContractTol)
            << "h = " << h << ", ICR at " << label << ", spin " << spin;
        if (label == "chord end" || label == "arc middle") continue;  // (F'' log-singular)
        // dF against Richardson differences: the smaller error of steps 1e-3
        // and 1e-4 (truncation falls with the step, F's rounding over the
        // step grows: measured at h = 0.05, ICR 6 sizes out, 3.9e-9 / 4.1e-8 /
        // 7e-7 at 1e-3 / 1e-4 / 1e-5; at h = 0.01 3.1e-8 at best), to
        // kNearFdTol = 1e-7 of the scale (a wrong dF term is >= 1e-3)
        auto difference = [&](int j, double dw) {
          ExactBasis plus, minus;
          Vec3 wp = w, wm = w;
          wp[j] += dw, wm[j] -= dw;
          exactArcRegionBasis(cap, rho, wp, false, plus);
          exactArcRegionBasis(cap, rho, wm, false, minus);
          return Mat3((plus.F - minus.F) / (2.0 * dw));
        };
        constexpr double kNearFdTol = 1e-7;
        for (int j = 0; j < 3; ++j) {
          double best = INFINITY;
          for (double step : {1e-3, 1e-4}) {
            const Mat3 fd = (4.0 * difference(j, 0.5 * step) - difference(j, step)) / 3.0;
            double err = 0.0;
            for (int k = 0; k < 3; ++k)
              err = std::max(err, (out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / scale[k]);
            best = std::min(best, err);
          }
          EXPECT_LE(best, kNearFdTol) << "h = " << h << ", ICR at " << label << ", dw" << j;
        }
      }
    }
  }
}

}  // namespace
}  // namespace patchspin
