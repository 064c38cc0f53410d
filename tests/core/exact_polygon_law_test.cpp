// internal::exactPolygonLaw, the exact model on a convex polygon for one
// linear pressure in one pass: against the brute-force oracle's basis
// (tests/support/exact_polygon_oracle.hpp) times the pressure, finite
// differences of its Jacobian, and the basis combined.
#include <patchspin/internal/exact.hpp>

#include <gtest/gtest.h>

#include "exact_polygon_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using internal::ExactBasis;
using internal::exactPolygonBasis;
using internal::exactPolygonLaw;
using namespace testing::exact_polygon;

// Pressures about O for a polygon, (p0, cx, cy): uniform, and two tilted ones
// with p = 1 at the vertex mean g and a slope of 0.7 (0.95) over the
// circumradius R, so p >= 0.05 on the patch; about O their terms cancel by
// |g| / R (50 sizes away for one test polygon).
std::vector<Vec3> testPressures(const Polygon& poly) {
  Vec2 g = Vec2::Zero();
  for (const Vec2& v : poly) g += v;
  g /= static_cast<double>(poly.size());
  double R = 0.0;
  for (const Vec2& v : poly) R = std::max(R, (v - g).norm());
  std::vector<Vec3> out{Vec3(1.0, 0.0, 0.0)};
  for (const Vec2& slope : {Vec2(0.7, 0.0), Vec2(-0.5, 0.8)}) {
    const Vec2 grad = slope / R;
    out.emplace_back(1.0 - grad.dot(g), grad.x(), grad.y());
  }
  return out;
}

// Bound of every entry of F c (the column scales weighted by |c_k|).
double lawScale(const Vec3& columnScale, const Vec3& c) {
  return columnScale.dot(c.cwiseAbs());
}

// The law against the brute-force oracle's F times the pressure, everywhere
// on the sphere, to the basis' contract (kContractTol of the scale).
TEST(ExactPolygonLaw, MatchesBruteForceOracleEverywhere) {
  double worst = 0.0;
  gOracleCapped = 0;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (const auto& [label, w] : testDirections(np.poly, np.rho)) {
      const Mat3 ref = oracleF(np.poly, np.rho, w);
      for (const Vec3& c : testPressures(np.poly)) {
        const Vec3 q = exactPolygonLaw(np.poly, np.rho, w, c, nullptr);
        const double err = (q - ref * c).cwiseAbs().maxCoeff() / lawScale(scale, c);
        worst = std::max(worst, err);
        EXPECT_LE(err, kContractTol) << np.name << " / " << label << " c = " << c.transpose();
      }
    }
  }
  EXPECT_EQ(gOracleCapped, 0) << "oracle did not converge";
  std::printf("law: worst relative error vs oracle: %.2e\n", worst);
}

// The law's Jacobian against central differences of the law's value, as the
// basis' test (same step, clearance of the ICR from the boundary and
// tolerance; see JacobianMatchesFiniteDifferences), and Euler's relation
// J w = 0 of the degree-0 homogeneous law.
TEST(ExactPolygonLaw, JacobianMatchesFiniteDifferences) {
  constexpr double kStep = 1e-5;
  constexpr double kFdTol = 1e-7;
  constexpr double kMinIcrClearance = 0.05;
  constexpr double kEulerTol = 1e-13;
  std::mt19937 rng(2025);
  std::normal_distribution<double> normal;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    const std::vector<Vec3> pressures = testPressures(np.poly);
    int checked = 0;
    for (int trial = 0; trial < 200 && checked < 25; ++trial) {
      Vec3 w(normal(rng), normal(rng), normal(rng));
      if (trial % 3 == 0) w.z() *= 1e-2;  // include the far branch
      w.normalize();
      const Vec2 c(-np.rho * w.y() / w.z(), np.rho * w.x() / w.z());
      double clearance = INFINITY;
      for (std::size_t i = 0; i < np.poly.size(); ++i) {
        const Vec2& a = np.poly[i];
        const Vec2& b = np.poly[(i + 1) % np.poly.size()];
        const double t = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        clearance = std::min(clearance, (a + t * (b - a) - c).norm());
      }
      if (clearance < kMinIcrClearance) continue;
      ++checked;
      double rmax = 0.0;
      for (const Vec2& v : np.poly) rmax = std::max(rmax, v.norm());
      const double h = kStep / (1.0 + rmax / np.rho);
      const Vec3& p = pressures[checked % pressures.size()];
      const double size = lawScale(scale, p);
      Mat3 J;
      exactPolygonLaw(np.poly, np.rho, w, p, &J);
      for (int j = 0; j < 3; ++j) {
        Vec3 wp = w, wm = w;
        wp[j] += h;
        wm[j] -= h;
        const Vec3 fd = (exactPolygonLaw(np.poly, np.rho, wp, p, nullptr) -
                         exactPolygonLaw(np.poly, np.rho, wm, p, nullptr)) /
                        (2 * h);
        EXPECT_LE((J.col(j) - fd).cwiseAbs().maxCoeff() / size, kFdTol)
            << np.name << " w = " << w.transpose() << " dw" << j;
      }
      EXPECT_LE((J * w).cwiseAbs().maxCoeff() / size, kEulerTol) << np.name;
    }
    EXPECT_GE(checked, 20) << np.name;
  }
}

// The law and the basis combined, sum_k c_k (F.col(k), dF[k]), are two
// summations of the same closed forms (one function against three, then
// combined): they agree to their rounding, which grows like kappa^3 eps
// towards the branch switch (kSumTol; measured 3.2e-14 of the scale here,
// 5.4e-13 for the Jacobians), at
// the special directions including ICRs on edges and vertices, and at the
// switch itself from either side. The Jacobians to kSumJacobianTol of
// max(|J|, scale) (the basis' own switch tolerance).
TEST(ExactPolygonLaw, AgreesWithTheBasisCombined) {
  constexpr double kSumTol = 1e-12;
  constexpr double kSumJacobianTol = 1e-10;
  constexpr double kSwitchRatio = 8.0;  // mirrors kFarRatio in exact_polygon.cpp
  double worst = 0.0, worstJ = 0.0;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    auto directions = testDirections(np.poly, np.rho);
    Vec2 g = Vec2::Zero();
    for (const Vec2& v : np.poly) g += v;
    g /= static_cast<double>(np.poly.size());
    double R = 0;
    for (const Vec2& v : np.poly) R = std::max(R, (v - g).norm());
    for (double angle : {0.3, 1.9, 4.0}) {
      const Vec2 dir(std::cos(angle), std::sin(angle));
      for (double side : {1 - 1e-14, 1 + 1e-14}) {
        directions.push_back({"switch", wForIcr(g + kSwitchRatio * side * R * dir, np.rho, 1)});
      }
    }
    for (const auto& [label, w] : directions) {
      ExactBasis basis;
      exactPolygonBasis(np.poly, np.rho, w, true, basis);
      for (const Vec3& c : testPressures(np.poly)) {
        Mat3 J;
        const Vec3 q = exactPolygonLaw(np.poly, np.rho, w, c, &J);
        const Mat3 basisJ = c[0] * basis.dF[0] + c[1] * basis.dF[1] + c[2] * basis.dF[2];
        const double size = lawScale(scale, c);
        const double err = (q - basis.F * c).cwiseAbs().maxCoeff() / size;
        const double errJ =
            (J - basisJ).cwiseAbs().maxCoeff() / std::max(basisJ.cwiseAbs().maxCoeff(), size);
        worst = std::max(worst, err);
        worstJ = std::max(worstJ, errJ);
        EXPECT_LE(err, kSumTol) << np.name << " / " << label << " c = " << c.transpose();
        EXPECT_LE(errJ, kSumJacobianTol) << np.name << " / " << label << " c = " << c.transpose();
      }
    }
  }
  std::printf("law vs basis combined: worst %.2e, Jacobian %.2e\n", worst, worstJ);
}

TEST(ExactPolygonLaw, RejectsInvalidInput) {
  const Polygon sq = unitSquare();
  const Vec3 c(1.0, 0.0, 0.0);
  EXPECT_THROW(exactPolygonLaw(sq, 0.5, Vec3::Zero(), c, nullptr), Error);
  EXPECT_THROW(exactPolygonLaw(sq, 0.0, Vec3(0, 0, 1), c, nullptr), Error);
  EXPECT_THROW(exactPolygonLaw({sq[3], sq[2], sq[1], sq[0]}, 0.5, Vec3(0, 0, 1), c, nullptr),
               Error);
  EXPECT_THROW(exactPolygonLaw(sq, 0.5, Vec3(0, 0, 1), Vec3(NAN, 0.0, 0.0), nullptr), Error);
}

}  // namespace
}  // namespace patchspin
