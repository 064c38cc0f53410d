// The exact model on convex polygons, Eq. (16), with linear pressure basis
// (1, x, y): internal::exactPolygonBasis against an independent brute-force
// oracle (tests/support/exact_polygon_oracle.hpp), closed forms for pure
// translation and pure spin, and central finite differences for dF.
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

TEST(ExactPolygonBasis, MatchesBruteForceOracleEverywhere) {
  double worst = 0.0;
  gOracleCapped = 0;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (const auto& [label, w] : testDirections(np.poly, np.rho)) {
      ExactBasis out;
      exactPolygonBasis(np.poly, np.rho, w, false, out);
      ASSERT_TRUE(out.F.allFinite()) << np.name << " / " << label;
      const Mat3 ref = oracleF(np.poly, np.rho, w);
      const double err = relativeError(out.F, ref, scale);
      worst = std::max(worst, err);
      EXPECT_LE(err, kContractTol) << np.name << " / " << label << "\nF =\n"
                                   << out.F << "\noracle =\n"
                                   << ref;
    }
  }
  EXPECT_EQ(gOracleCapped, 0) << "oracle did not converge";
  std::printf("worst relative error vs oracle: %.2e\n", worst);
}

// Random convex polygons (hull of random points, 3..9 vertices, random
// offset from O and random rho) at random w, ICRs mostly on or near the
// patch, against the oracle.
Polygon convexHull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& p, const Vec2& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  });
  auto cross = [](const Vec2& o, const Vec2& p, const Vec2& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  Polygon hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {  // upper chain
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

TEST(ExactPolygonBasis, RandomConvexPolygonsMatchOracle) {
  constexpr int kPolygons = 20;  // 150 measured once: worst 3.4e-14
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<double> normal;
  gOracleCapped = 0;
  double worst = 0.0;
  for (int i = 0; i < kPolygons; ++i) {
    std::vector<Vec2> pts;
    const int n = 3 + i % 7;
    const Vec2 offset(1.5 * uni(rng), 1.5 * uni(rng));
    for (int j = 0; j < n + 2; ++j) pts.emplace_back(offset + Vec2(uni(rng), 0.6 * uni(rng)));
    const Polygon poly = convexHull(pts);
    if (poly.size() < 3) continue;
    const double rho = 0.2 + 0.5 * (uni(rng) + 1.0);
    const Vec3 scale = columnScales(poly, rho);
    for (int j = 0; j < 3; ++j) {
      // ICR: random point near the patch (w3 of either sign) or random w
      Vec3 w;
      if (j < 2) {
        const Vec2 c = poly[j % poly.size()] + 0.7 * Vec2(uni(rng), uni(rng));
        w = wForIcr(c, rho, j == 0 ? 1.0 : -1.0);
      } else {
        w = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
      }
      ExactBasis out;
      exactPolygonBasis(poly, rho, w, false, out);
      const double err = relativeError(out.F, oracleF(poly, rho, w), scale);
      worst = std::max(worst, err);
      EXPECT_LE(err, kContractTol) << "polygon " << i << " w = " << w.transpose();
    }
  }
  EXPECT_EQ(gOracleCapped, 0) << "oracle did not converge";
  std::printf("worst relative error vs oracle: %.2e\n", worst);
}

// More vertices than the implementation keeps on the stack (32): a 40-gon,
// O off-centre, against the oracle at a few places of the sphere.
TEST(ExactPolygonBasis, ManyVerticesMatchOracle) {
  Polygon poly;
  for (int i = 0; i < 40; ++i) {
    const double a = 2.0 * M_PI * i / 40.0;
    poly.emplace_back(0.2 + 0.5 * std::cos(a), -0.1 + 0.35 * std::sin(a));
  }
  const double rho = 0.35;
  const Vec3 scale = columnScales(poly, rho);
  gOracleCapped = 0;
  for (const Vec3& w : {Vec3(0, 0, 1), wForIcr(poly[3], rho, -1.0),
                        wForIcr(Vec2(0.3, 0.1), rho, 1.0), Vec3(0.3, -0.2, 0.01).normalized()}) {
    ExactBasis out;
    exactPolygonBasis(poly, rho, w, false, out);
    EXPECT_LE(relativeError(out.F, oracleF(poly, rho, w), scale), kContractTol) << w.transpose();
  }
  EXPECT_EQ(gOracleCapped, 0) << "oracle did not converge";
}

// With the Jacobian requested, F must be the same numbers: the edge sum's
// values are the same code either way (its derivative is summed apart), and the
// far rule may use one order more (both orders' errors are <= 2e-15 of the
// scale, measured), so kSameTol = 1e-14.
TEST(ExactPolygonBasis, ValueIndependentOfJacobianRequest) {
  constexpr double kSameTol = 1e-14;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (const auto& [label, w] : testDirections(np.poly, np.rho)) {
      ExactBasis a, b;
      exactPolygonBasis(np.poly, np.rho, w, false, a);
      exactPolygonBasis(np.poly, np.rho, w, true, b);
      EXPECT_LE(relativeError(a.F, b.F, scale), kSameTol) << np.name << " / " << label;
    }
  }
}

// Pure translation w = (cos t, sin t, 0): v/|v| = (cos t, sin t) is constant, so
//   F.col(k) = ∫ phi_k (cos t, sin t, (x sin t - y cos t) / rho) dA,
// i.e. polygon area moments (Green's theorem formulas, computed here).
TEST(ExactPolygonBasis, PureTranslationMatchesAreaMoments) {
  constexpr double kClosedFormTol = 1e-13;  // both sides are a few rounded sums
  for (const NamedPolygon& np : testPolygons()) {
    // moments A, Sx, Sy, Ixx, Ixy, Iyy by Green's theorem
    double A = 0, Sx = 0, Sy = 0, Ixx = 0, Ixy = 0, Iyy = 0;
    const Polygon& p = np.poly;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec2& a = p[i];
      const Vec2& b = p[(i + 1) % p.size()];
      const double cr = a.x() * b.y() - b.x() * a.y();
      A += cr / 2;
      Sx += (a.x() + b.x()) * cr / 6;
      Sy += (a.y() + b.y()) * cr / 6;
      Ixx += (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) * cr / 12;
      Iyy += (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) * cr / 12;
      Ixy += (a.x() * b.y() + 2 * a.x() * a.y() + 2 * b.x() * b.y() + b.x() * a.y()) * cr / 24;
    }
    const Vec3 scale = columnScales(p, np.rho);
    for (double t : {0.0, 0.7, 2.0, -2.5}) {
      const double c = std::cos(t), s = std::sin(t);
      Mat3 ref;
      ref.col(0) << A * c, A * s, (Sx * s - Sy * c) / np.rho;
      ref.col(1) << Sx * c, Sx * s, (Ixx * s - Ixy * c) / np.rho;
      ref.col(2) << Sy * c, Sy * s, (Ixy * s - Iyy * c) / np.rho;
      ExactBasis out;
      exactPolygonBasis(p, np.rho, Vec3(c, s, 0.0), true, out);
      EXPECT_LE(relativeError(out.F, ref, scale), kClosedFormTol) << np.name << " t=" << t;
    }
  }
}

// Pure spin about O, w = (0, 0, 1): k = (-y, x, r^2/rho) / r, so
//   F.col(0) = (∫ -y/r, ∫ x/r, ∫ r / rho) dA,
// the moment integrals of Eq. (36) (paper's Eq. (42) third column). Checked
// with the oracle's Cartesian quadrature of these scalar integrands, split
// at O where r is not smooth.
TEST(ExactPolygonBasis, PureSpinAboutOriginGivesRadialMoments) {
  for (const NamedPolygon& np : testPolygons()) {
    const Polygon& p = np.poly;
    // radial moments via the 9-vector oracle with a custom integrand
    double xmin = INFINITY, xmax = -INFINITY;
    std::vector<double> xb{0.0};
    for (const Vec2& v : p) {
      xmin = std::min(xmin, v.x());
      xmax = std::max(xmax, v.x());
      xb.push_back(v.x());
    }
    const Vec3 scale = columnScales(p, np.rho);
    const Vec9 tol = Vec9::Constant(kOracleTol * scale[0]);
    const Vec9 innerTol = 1e-2 * tol / (xmax - xmin);
    auto inner = [&](double x) -> Vec9 {
      double lo, hi;
      chordAt(p, x, lo, hi);
      if (!(hi > lo)) return Vec9::Zero();
      auto fy = [&](double y) -> Vec9 {
        const double r = std::hypot(x, y);
        Vec9 out = Vec9::Zero();
        if (r > 0) out.head<3>() << -y / r, x / r, r / np.rho;
        return out;
      };
      return integrateSplit(fy, lo, hi, {0.0}, innerTol);
    };
    gOracleCapped = 0;
    const Vec3 moments = integrateSplit(inner, xmin, xmax, xb, tol).head<3>();
    ASSERT_EQ(gOracleCapped, 0) << "oracle did not converge";
    for (double s : {1.0, -1.0}) {
      ExactBasis out;
      exactPolygonBasis(p, np.rho, Vec3(0, 0, s), false, out);
      EXPECT_LE((out.F.col(0) - s * moments).cwiseAbs().maxCoeff() / scale[0], kContractTol)
          << np.name << " spin " << s << "\n"
          << out.F.col(0).transpose() << "\n"
          << (s * moments).transpose();
    }
  }
}

// F is continuous across w3 = 0 (c passes through infinity): at w3 = +-eps
// it differs from the pure-translation value by O(eps) (the kernel changes by
// O(eps |P| / rho)). kContinuitySlope bounds that Lipschitz constant relative
// to the column scale, with margin: the kernel's change is <= 2 eps |P|/rho.
// dF (the kernel's derivative m m^T / |v|, m ~ 1 + |P|/rho) changes by
// O(eps (1 + |P|/rho)^2) relative to the column scale, same slope.
TEST(ExactPolygonBasis, ContinuousAcrossPureTranslation) {
  constexpr double kContinuitySlope = 10.0;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    double rmax = 0.0;
    for (const Vec2& v : np.poly) rmax = std::max(rmax, v.norm());
    ExactBasis zero;
    exactPolygonBasis(np.poly, np.rho, Vec3(0.6, 0.8, 0.0), true, zero);
    for (double eps : {1e-300, 1e-200, 1e-15, 1e-12, 1e-8, -1e-8, -1e-15, -1e-300}) {
      ExactBasis out;
      exactPolygonBasis(np.poly, np.rho, Vec3(0.6, 0.8, eps), true, out);
      ASSERT_TRUE(out.F.allFinite());
      const double bound = kContinuitySlope * std::abs(eps) * (1.0 + rmax / np.rho) + 1e-15;
      EXPECT_LE(relativeError(out.F, zero.F, scale), bound) << np.name << " eps " << eps;
      // the Jacobian is continuous there too (both sides use the same rule)
      const double lever = 1.0 + rmax / np.rho;
      const double boundJacobian = kContinuitySlope * std::abs(eps) * lever * lever + 1e-15;
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE((out.dF[k] - zero.dF[k]).cwiseAbs().maxCoeff() / scale[k], boundJacobian)
            << np.name << " eps " << eps;
      }
    }
  }
}

// The two branches (edge sum / quadrature) meet at kappa = |c - g| / Rpoly = 8
// (g = vertex mean, Rpoly = circumradius about g). Just inside and just
// outside the switch (c moved by 2e-14 of its distance, so F itself moves
// by ~1e-14), F and dF must agree to the accuracy of both branches: F to
// kSwitchTol (measured <= 6e-13 over shapes and rho), dF to
// kSwitchJacobianTol: the derivative of the cancelling edge sum in c is
// multiplied by dc/dw ~ kappa^2 / rho, measured <= 1.4e-10 with the former
// dual-number derivative and 6.1e-11 with the boundary-integral one (2x0.5
// rectangle, rho = 0.1, 64 directions), ~1e-11 for the shapes here.
TEST(ExactPolygonBasis, BranchesAgreeAtTheSwitch) {
  constexpr double kSwitchTol = 1e-12;
  constexpr double kSwitchJacobianTol = 1e-10;
  constexpr double kSwitchRatio = 8.0;  // mirrors kFarRatio in exact_polygon.cpp
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    Vec2 g = Vec2::Zero();
    for (const Vec2& v : np.poly) g += v;
    g /= static_cast<double>(np.poly.size());
    double R = 0;
    for (const Vec2& v : np.poly) R = std::max(R, (v - g).norm());
    for (double angle : {0.3, 1.9, 4.0}) {
      const Vec2 dir(std::cos(angle), std::sin(angle));
      ExactBasis in, out;
      exactPolygonBasis(np.poly, np.rho,
                        wForIcr(g + kSwitchRatio * (1 - 1e-14) * R * dir, np.rho, 1), true, in);
      exactPolygonBasis(np.poly, np.rho,
                        wForIcr(g + kSwitchRatio * (1 + 1e-14) * R * dir, np.rho, 1), true, out);
      EXPECT_LE(relativeError(in.F, out.F, scale), kSwitchTol) << np.name << " angle " << angle;
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE((in.dF[k] - out.dF[k]).cwiseAbs().maxCoeff() / scale[k], kSwitchJacobianTol)
            << np.name << " angle " << angle << " column " << k;
      }
    }
  }
}

// dF[k] against central differences of F.col(k) in w (w unnormalized: F is
// homogeneous of degree 0). w enters the kernel as w3 |P| / rho, so the step
// is h = kStep / (1 + max|P| / rho) in every component: truncation
// h^2 |F'''| / 6 and rounding eps |F| / h are then both ~1e-11 relative when
// the ICR is at least kMinIcrClearance from the boundary (F'' is
// log-singular where the ICR crosses an edge), so kFdTol = 1e-7 relative to
// the column scale.
TEST(ExactPolygonBasis, JacobianMatchesFiniteDifferences) {
  constexpr double kStep = 1e-5;
  constexpr double kFdTol = 1e-7;
  constexpr double kMinIcrClearance = 0.05;
  constexpr double kEulerTol = 1e-13;  // dF[k] w = 0 up to rounding
  std::mt19937 rng(2024);
  std::normal_distribution<double> normal;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    int checked = 0;
    for (int trial = 0; trial < 200 && checked < 25; ++trial) {
      Vec3 w(normal(rng), normal(rng), normal(rng));
      if (trial % 3 == 0) w.z() *= 1e-2;  // include the far branch
      w.normalize();
      if (w.z() != 0.0) {
        const Vec2 c(-np.rho * w.y() / w.z(), np.rho * w.x() / w.z());
        double clearance = INFINITY;
        for (std::size_t i = 0; i < np.poly.size(); ++i) {
          const Vec2& a = np.poly[i];
          const Vec2& b = np.poly[(i + 1) % np.poly.size()];
          const double t = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
          clearance = std::min(clearance, (a + t * (b - a) - c).norm());
        }
        if (clearance < kMinIcrClearance) continue;
      }
      ++checked;
      double rmax = 0.0;
      for (const Vec2& v : np.poly) rmax = std::max(rmax, v.norm());
      const double h = kStep / (1.0 + rmax / np.rho);
      ExactBasis out;
      exactPolygonBasis(np.poly, np.rho, w, true, out);
      for (int j = 0; j < 3; ++j) {
        ExactBasis plus, minus;
        Vec3 wp = w, wm = w;
        wp[j] += h;
        wm[j] -= h;
        exactPolygonBasis(np.poly, np.rho, wp, false, plus);
        exactPolygonBasis(np.poly, np.rho, wm, false, minus);
        const Mat3 fd = (plus.F - minus.F) / (2 * h);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE((out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / scale[k], kFdTol)
              << np.name << " w = " << w.transpose() << " column " << k << " dw" << j;
        }
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE((out.dF[k] * w).cwiseAbs().maxCoeff() / scale[k], kEulerTol) << np.name;
      }
    }
    EXPECT_GE(checked, 20) << np.name;
  }
}

// At an ICR on an edge or a vertex F is still C^1 (its second derivative is
// log-singular there), so the Jacobian must be finite and match central
// differences to O(hc log hc) relative to its own size, hc the step of the
// ICR: the w step is h = kIcrStep L / |dc/dw| (L the edge length,
// |dc/dw| <= (rho/|w3|)(1 + |c|/rho)), so hc <= 1e-6 L and the error is
// ~1e-6 * 14; rounding eps L / (h |dc/dw|) ~ 1e-10. kFdTolSingular = 1e-4.
TEST(ExactPolygonBasis, JacobianContinuousWithIcrOnBoundary) {
  constexpr double kIcrStep = 1e-6;
  constexpr double kFdTolSingular = 1e-4;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec2 a = np.poly[0], b = np.poly[1];
    const double L = (b - a).norm();
    for (const Vec2& c : {a, Vec2(0.5 * (a + b)), Vec2(0.3 * a + 0.7 * b)}) {
      const Vec3 w = wForIcr(c, np.rho, 1.0);
      const double dcdw = np.rho / std::abs(w.z()) * (1.0 + c.norm() / np.rho);
      const double h = kIcrStep * L / dcdw;
      ExactBasis out;
      exactPolygonBasis(np.poly, np.rho, w, true, out);
      double size = 0.0;
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(out.dF[k].allFinite());
        size = std::max(size, out.dF[k].cwiseAbs().maxCoeff());
      }
      for (int j = 0; j < 3; ++j) {
        ExactBasis plus, minus;
        Vec3 wp = w, wm = w;
        wp[j] += h;
        wm[j] -= h;
        exactPolygonBasis(np.poly, np.rho, wp, false, plus);
        exactPolygonBasis(np.poly, np.rho, wm, false, minus);
        const Mat3 fd = (plus.F - minus.F) / (2 * h);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE((out.dF[k].col(j) - fd.col(k)).cwiseAbs().maxCoeff() / size, kFdTolSingular)
              << np.name << " c = " << c.transpose() << " column " << k << " dw" << j;
        }
      }
    }
  }
}

// Never NaN: a dense deterministic sweep of w, including extreme magnitudes
// of the components, for every test polygon; F bounded by its column scale.
TEST(ExactPolygonBasis, FiniteAndBoundedEverywhere) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> expo(-300, 0);
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (int i = 0; i < 400; ++i) {
      Vec3 w(normal(rng), normal(rng), normal(rng));
      w[i % 3] *= std::pow(10.0, expo(rng));
      if (i % 7 == 0) w *= 1e-150;
      ExactBasis out;
      exactPolygonBasis(np.poly, np.rho, w, true, out, i % 2 ? 0.0 : 1e-6);
      ASSERT_TRUE(out.F.allFinite()) << np.name << " w = " << w.transpose();
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(out.dF[k].allFinite()) << np.name << " w = " << w.transpose();
        EXPECT_LE(out.F.col(k).cwiseAbs().maxCoeff(), scale[k] * (1 + 1e-12));
      }
    }
  }
}

// The tolerance knob trades far-branch quadrature order for speed; the
// result must still meet the requested tolerance (relative to the scale).
TEST(ExactPolygonBasis, ToleranceKnobIsHonoured) {
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (double tol : {1e-4, 1e-6, 1e-9}) {
      for (double kappaAngle : {0.2, 2.2}) {
        for (double dist : {10.0, 30.0, 300.0}) {
          const Vec3 w =
              wForIcr(dist * Vec2(std::cos(kappaAngle), std::sin(kappaAngle)), np.rho, 1.0);
          ExactBasis fast, exact;
          exactPolygonBasis(np.poly, np.rho, w, false, fast, tol);
          exactPolygonBasis(np.poly, np.rho, w, false, exact);
          EXPECT_LE(relativeError(fast.F, exact.F, scale), tol) << np.name << " tol " << tol;
        }
      }
    }
  }
}

// Degree-0 homogeneity: F(s w) = F(w) and dF(s w) = dF(w) / s for any s > 0,
// including magnitudes whose squares overflow or underflow. kHomogeneityTol:
// the scaled input differs from w by one rounding per component.
TEST(ExactPolygonBasis, HomogeneousOfDegreeZero) {
  constexpr double kHomogeneityTol = 1e-13;
  for (const NamedPolygon& np : testPolygons()) {
    const Vec3 scale = columnScales(np.poly, np.rho);
    for (const Vec3& w : {Vec3(0.3, -0.5, 0.8), Vec3(0.6, 0.8, 1e-3), Vec3(-0.6, 0.8, 0.0)}) {
      ExactBasis ref;
      exactPolygonBasis(np.poly, np.rho, w, true, ref);
      for (double s : {1e-300, 1e-160, 1e-5, 7.0, 1e160, 1e300}) {
        ExactBasis out;
        exactPolygonBasis(np.poly, np.rho, s * w, true, out);
        EXPECT_LE(relativeError(out.F, ref.F, scale), kHomogeneityTol) << np.name << " s " << s;
        for (int k = 0; k < 3; ++k) {
          const double size = std::max(ref.dF[k].cwiseAbs().maxCoeff(), scale[k]);
          EXPECT_LE((s * out.dF[k] - ref.dF[k]).cwiseAbs().maxCoeff() / size, kHomogeneityTol)
              << np.name << " s " << s;
        }
      }
    }
  }
}

TEST(ExactPolygonBasis, RejectsInvalidInput) {
  ExactBasis out;
  const Polygon sq = unitSquare();
  EXPECT_THROW(exactPolygonBasis(sq, 0.5, Vec3::Zero(), false, out), Error);
  EXPECT_THROW(exactPolygonBasis(sq, 0.5, Vec3(NAN, 0, 1), false, out), Error);
  EXPECT_THROW(exactPolygonBasis(sq, 0.0, Vec3(0, 0, 1), false, out), Error);
  EXPECT_THROW(exactPolygonBasis(sq, -1.0, Vec3(0, 0, 1), false, out), Error);
  EXPECT_THROW(exactPolygonBasis({sq[0], sq[1]}, 0.5, Vec3(0, 0, 1), false, out), Error);
  EXPECT_THROW(exactPolygonBasis({sq[3], sq[2], sq[1], sq[0]}, 0.5, Vec3(0, 0, 1), false, out),
               Error);
  EXPECT_THROW(exactPolygonBasis(sq, 0.5, Vec3(0, 0, 1), false, out, -1.0), Error);
}

}  // namespace
}  // namespace patchspin
