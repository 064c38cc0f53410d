// The exact model, Eq. (16), on regions bounded by segments and circular arcs
// (internal::exactArcRegionBasis): against the brute-force oracle
// (tests/support/exact_arc_oracle.hpp), against exactDiskBasis for an uncut
// disk, and against exactPolygonBasis on fine inscribed polygons.
#include <patchspin/internal/exact.hpp>

#include <gtest/gtest.h>

#include "exact_arc_oracle.hpp"

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
// (centre o, radius a), its second the chord or the other arc.
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
  const Vec2 mid2 = region[1].kind == BoundaryPiece::Kind::Segment
                        ? Vec2(0.5 * (region[1].a + region[1].b))
                        : onCircle(region[1].centre, region[1].radius,
                                   0.5 * (region[1].angle0 + region[1].angle1));
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
      exactArcRegionBasis(nr.region, nr.rho, w, out);
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
// column scale (their oracle tests), so 1e-12 leaves a margin of 10.
TEST(ExactArcRegionBasis, WholeDiskMatchesDiskLaw) {
  constexpr double kDiskAgreementTol = 1e-12;
  const Vec2 o(0.3, -0.2);
  const double R = 0.7, rho = 0.45;
  const Region disk = {BoundaryPiece::arc(o, R, -1.0, -1.0 + 2.0 * M_PI)};
  const Vec3 scale = columnScales(disk, rho);
  double worst = 0.0;
  for (const auto& [label, w] : testDirections(disk, rho)) {
    ExactBasis arc, ref;
    exactArcRegionBasis(disk, rho, w, arc);
    internal::exactDiskBasis(o, R, rho, w, false, ref);
    const double err = relativeError(arc.F, ref.F, scale);
    worst = std::max(worst, err);
    EXPECT_LE(err, kDiskAgreementTol) << label;
  }
  std::printf("worst normwise difference to the disk law: %.3g\n", worst);
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
      exactArcRegionBasis(nr.region, nr.rho, w, arc);
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

}  // namespace
}  // namespace patchspin
