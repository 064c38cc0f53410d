// Exact model (16) on a disk: internal::exactDiskBasis (linear pressure
// basis) and internal::exactDiskHertz (Hertz pressure (57)), checked against
// the brute-force oracle of tests/support/oracle.hpp (nested adaptive G7-K15
// in polar coordinates about the disk centre, kernel from w directly: no ICR
// reduction, no series, no elliptic integrals), against the paper's closed
// forms (52)-(53), (58)-(59), and against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <patchspin/internal/exact.hpp>
#include <random>
#include <string>
#include <vector>

#include "closed_forms.hpp"
#include "oracle.hpp"

namespace patchspin {
namespace {

using internal::ExactBasis;
using internal::exactDiskBasis;
using internal::exactDiskHertz;

constexpr double kPi = 3.14159265358979323846;
// The contract of the issue: relative error <= 1e-10 everywhere on the sphere.
constexpr double kContractTol = 1e-10;
// Oracle target (relative to ∫|p k| dA): two orders below the contract, so a
// failure is the fast code's, not the oracle's.
constexpr double kOracleTol = 1e-12;
// Closed forms evaluated two ways in double precision (paper formula with
// std::comp_ellint vs our AGM/series): rounding plus the 1/eps cancellation of
// (52) near eps -> 0 and the ~eps^4 cancellation of (53), (59) as printed for
// eps up to 7 (7^4 * 1e-16 ~ 2.4e-13).
constexpr double kClosedFormTol = 1e-12;
// Finite differences with steps relative to lambda, the w-scale on which F
// varies (wScale below); errors relative to max |dF|. Away from the rim: the
// five-point stencil with h = 1e-3 lambda, truncation (h/lambda)^4 F^(5)/30 ~
// 1e-13 and rounding ~eps / (h/lambda) ~ 1e-13 (times the torque lever
// |C|/rho), so 1e-8 leaves a wide margin for larger high derivatives near the
// rim and switches while still catching any wrong term of the jacobian.
constexpr double kFdStepRel = 1e-3;
constexpr double kFdTol = 1e-8;
// At the rim F'' has a log singularity (the K terms), so differences are only
// O(h |log h|) accurate there: central differences with h = 1e-5 lambda give
// ~1e-5 * 12 ~ 1e-4 at worst.
constexpr double kFdRimStepRel = 1e-5;
constexpr double kFdRimTol = 1e-4;
// dF[k] w = 0 (degree-0 homogeneity) holds to rounding of the dual numbers
// (relative to max |dF|).
constexpr double kHomogeneityTol = 1e-13;
// Where exact_disk.cpp switches branches (delta^2 / R^2): series about the
// centre below kSwitchInside, elliptic closed forms up to kSwitchFar, series in
// 1/delta^2 beyond; the rim (delta = R) separates the two closed forms.
constexpr double kSwitchInside = 0.1;
constexpr double kSwitchFar = 10.0;
// Two sides of a branch switch 1e-12 apart (relative in delta^2): the true
// change is ~1e-12 times an O(1) derivative; the rest is the branches' error.
constexpr double kSwitchTol = 1e-12;

struct Disk {
  std::string name;
  Vec2 centre;
  double R;
  double rho;
};

const std::vector<Disk>& disks() {
  static const std::vector<Disk> d = {
      {"centred", Vec2(0.0, 0.0), 1.0, 2.0 / 3.0},  // O at the centre, rho of (47)
      {"offCentre", Vec2(0.3, -0.2), 0.5, 0.4},     // O inside the disk
      {"outsideO", Vec2(2.0, 1.5), 0.7, 1.1},       // O outside the disk
      {"farO", Vec2(-3.0, 4.0), 0.2, 0.5},          // O 25 radii away
  };
  return d;
}

// w whose ICR lies at C + f R (cos phi, sin phi): c = rho (-w2, w1)/w3.
Vec3 wForIcr(const Disk& d, double f, double phi, double w3 = 1.0) {
  const Vec2 c = d.centre + f * d.R * Vec2(std::cos(phi), std::sin(phi));
  return Vec3(c.y() * w3 / d.rho, -c.x() * w3 / d.rho, w3).normalized();
}

struct Case {
  std::string name;
  Vec3 w;
};

// Points of the sphere the contract names: pure spin, pure translation,
// w3 -> 0, ICR at the centre, near the branch switches, on/near the rim, far;
// plus seeded random directions.
std::vector<Case> cases(const Disk& d) {
  std::vector<Case> c = {
      {"spin+", Vec3(0, 0, 1)},
      {"spin-", Vec3(0, 0, -1)},
      {"translationX", Vec3(1, 0, 0)},
      {"translation", Vec3(0.6, -0.8, 0)},
      {"translation2", Vec3(-0.28, 0.96, 0)},
      {"w3=1e-3", Vec3(0.8, 0.6, 1e-3).normalized()},
      {"w3=-1e-6", Vec3(-0.6, 0.8, -1e-6).normalized()},
      {"w3=1e-9", Vec3(0.28, -0.96, 1e-9).normalized()},
      {"icrCentre", wForIcr(d, 0.0, 0.0)},
      {"icr0.3", wForIcr(d, 0.3, 1.0)},
      {"icrSwitchIn-", wForIcr(d, std::sqrt(kSwitchInside) * (1 - 1e-9), 2.0)},
      {"icrSwitchIn+", wForIcr(d, std::sqrt(kSwitchInside) * (1 + 1e-9), 2.0, -1.0)},
      {"icr0.7", wForIcr(d, 0.7, -2.5, -1.0)},
      {"rimIn1e-8", wForIcr(d, 1 - 1e-8, 0.4)},
      {"rim", wForIcr(d, 1.0, -1.2)},
      {"rimOut1e-8", wForIcr(d, 1 + 1e-8, 3.0, -1.0)},
      {"icr1.5", wForIcr(d, 1.5, 0.9)},
      {"icrSwitchOut-", wForIcr(d, std::sqrt(kSwitchFar) * (1 - 1e-9), -0.3)},
      {"icrSwitchOut+", wForIcr(d, std::sqrt(kSwitchFar) * (1 + 1e-9), -0.3, -1.0)},
      {"icr5", wForIcr(d, 5.0, 2.2)},
      {"icr100", wForIcr(d, 100.0, -2.9, -1.0)},
  };
  std::mt19937 rng(20261122);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 6; ++i) {
    c.push_back({"random" + std::to_string(i), Vec3(g(rng), g(rng), g(rng)).normalized()});
  }
  return c;
}

// Scale of column k: |F.col(k)| <= ∫|phi_k| dA (1 + max|P| / rho) <= S_k.
// Errors are measured relative to it (a column can vanish by symmetry, e.g.
// phi = x on a centred disk in pure x-translation).
double columnScale(const Disk& d, int k) {
  const double maxPhi = k == 0 ? 1.0 : std::abs(d.centre[k - 1]) + d.R;
  return kPi * d.R * d.R * maxPhi * (1.0 + (d.centre.norm() + d.R) / d.rho);
}

// F by brute force: column k = -Q(p = phi_k, mu = 1).
Mat3 oracleBasis(const Disk& d, const Vec3& w) {
  Mat3 F;
  const testing::ScalarField phi[3] = {[](const Vec2&) { return 1.0; },
                                       [](const Vec2& p) { return p.x(); },
                                       [](const Vec2& p) { return p.y(); }};
  for (int k = 0; k < 3; ++k) {
    testing::QuadratureReport report;
    F.col(k) = -testing::bruteForceQDisk(d.centre, d.R, phi[k], 1.0, d.rho, w, kOracleTol, &report);
    EXPECT_FALSE(report.capped) << "oracle capped";
  }
  return F;
}

Mat3 basis(const Disk& d, const Vec3& w, double tolerance = 0.0) {
  ExactBasis b;
  exactDiskBasis(d.centre, d.R, d.rho, w, false, b, tolerance);
  return b.F;
}

double columnError(const Disk& d, const Mat3& F, const Mat3& ref, int k) {
  return (F.col(k) - ref.col(k)).cwiseAbs().maxCoeff() / columnScale(d, k);
}

// ------------------------------------------------------------ vs oracle

TEST(ExactDiskBasis, MatchesBruteForceEverywhereOnTheSphere) {
  double worst = 0.0;
  std::string worstName;
  for (const Disk& d : disks()) {
    for (const Case& c : cases(d)) {
      const Mat3 F = basis(d, c.w);
      ASSERT_TRUE(F.allFinite()) << d.name << " " << c.name;
      const Mat3 ref = oracleBasis(d, c.w);
      for (int k = 0; k < 3; ++k) {
        const double err = columnError(d, F, ref, k);
        EXPECT_LE(err, kContractTol) << d.name << " " << c.name << " column " << k << "\nF=\n"
                                     << F << "\noracle=\n"
                                     << ref;
        if (err > worst) {
          worst = err;
          worstName = d.name + " " + c.name;
        }
      }
    }
  }
  std::printf("exactDiskBasis vs oracle: worst relative error %.2e (%s)\n", worst,
              worstName.c_str());
}

TEST(ExactDiskHertz, MatchesBruteForceEverywhereOnTheSphere) {
  double worst = 0.0;
  for (const Disk& d : disks()) {
    const testing::ScalarField p = testing::hertzField(d.centre, d.R, 1.0);
    // |result| <= 1 + max|P| / rho for a unit load
    const double scale = 1.0 + (d.centre.norm() + d.R) / d.rho;
    for (const Case& c : cases(d)) {
      const Vec3 h = exactDiskHertz(d.centre, d.R, d.rho, c.w, nullptr);
      ASSERT_TRUE(h.allFinite()) << d.name << " " << c.name;
      testing::QuadratureReport report;
      const Vec3 ref =
          -testing::bruteForceQDisk(d.centre, d.R, p, 1.0, d.rho, c.w, kOracleTol, &report);
      EXPECT_FALSE(report.capped);
      const double err = (h - ref).cwiseAbs().maxCoeff() / scale;
      EXPECT_LE(err, kContractTol)
          << d.name << " " << c.name << " " << h.transpose() << " vs " << ref.transpose();
      worst = std::max(worst, err);
    }
  }
  std::printf("exactDiskHertz vs oracle: worst relative error %.2e\n", worst);
}

// Q = -mu F (p0, cx, cy) for linear pressures with gradients (p >= 0 on the
// disk, and one that changes sign), against the oracle with that pressure.
TEST(ExactDiskBasis, LinearPressureWrenchMatchesBruteForce) {
  for (const Disk& d : disks()) {
    // p = p0 + g . (P - C) with |g| R up to 0.9 p0 (admissible) and 1.5 p0 (not)
    for (double slope : {0.9, 1.5}) {
      const Vec2 g = slope / d.R * Vec2(0.6, -0.8);
      LinearPressure p;
      p.p0 = 1.0 - g.dot(d.centre);
      p.cx = g.x();
      p.cy = g.y();
      const double mu = 0.4;
      const double scale =
          mu * kPi * d.R * d.R * (1.0 + slope) * (1.0 + (d.centre.norm() + d.R) / d.rho);
      for (const Case& c : cases(d)) {
        const Vec3 fast = -mu * basis(d, c.w) * p.coefficients();
        testing::QuadratureReport report;
        const Vec3 ref = testing::bruteForceQDisk(d.centre, d.R, testing::linearField(p), mu, d.rho,
                                                  c.w, kOracleTol, &report);
        EXPECT_FALSE(report.capped);
        EXPECT_LE((fast - ref).cwiseAbs().maxCoeff() / scale, kContractTol)
            << d.name << " " << c.name << " slope " << slope;
      }
    }
  }
}

// ------------------------------------------------------- paper closed forms

// Uniform pressure on a disk centred at O, Eq. (46), (50)-(53): with unit load
// p = 1/(pi R^2), Q = -mu Pz (P_eps cos phi, P_eps sin phi, pi_xy sign(w3) T_eps / rho),
// pi_xy = 2R/3. (52)-(53) verified (against the oracle below): they hold as
// printed with COMPLETE elliptic integrals of parameter m (the text says
// "incomplete"); (51) drops the sign(w3) of the torque.
TEST(ExactDiskBasis, UniformPressureMatchesPaperEq52And53) {
  const double R = 1.3, rho = 0.9;  // any rho: eps of (50) carries rho / R
  // eps <= 7: beyond, (52)-(53) evaluated as printed cancel ~eps^4 digits
  // (the far values are checked against the oracle in the sweep above)
  const std::vector<double> eps = {0.0, 0.05, 0.3, 0.7, 0.999, 1.0, 1.001, 1.6, 2.5, 7.0};
  for (double e : eps) {
    for (double sgn : {1.0, -1.0}) {
      // (50): eps = (rho/R) |w_xy| / |w3|
      const double phi = 0.7;
      const Vec3 w =
          Vec3(e * R / rho * std::cos(phi), e * R / rho * std::sin(phi), sgn).normalized();
      ExactBasis b;
      exactDiskBasis(Vec2::Zero(), R, rho, w, false, b);
      const Vec3 fast = -b.F.col(0) / (kPi * R * R);  // Q for mu = Pz = 1
      const Vec3 paper = testing::uniformDiskQ(R, 1.0, 1.0, rho, w);
      EXPECT_LE((fast - paper).cwiseAbs().maxCoeff(), kClosedFormTol)
          << "eps=" << e << " sign " << sgn;
    }
  }
  // the paper's formulas themselves against brute force at a few eps
  for (double e : {0.4, 1.0, 2.0}) {
    const Vec3 w = Vec3(e * R / rho, 0.0, 1.0).normalized();
    const Vec3 ref = testing::bruteForceQDisk(
        Vec2::Zero(), R, [&](const Vec2&) { return 1.0 / (kPi * R * R); }, 1.0, rho, w, kOracleTol);
    EXPECT_LE((testing::uniformDiskQ(R, 1.0, 1.0, rho, w) - ref).cwiseAbs().maxCoeff(),
              kContractTol)
        << "eps=" << e;
  }
}

// Hertz pressure (57) on a disk centred at O, Eq. (58)-(59), with
// pi_xy = 3 pi R / 16 (the paper's "3 pi r / 16" means the radius R; checked
// by the oracle below through T_eps(0) = 1).
TEST(ExactDiskHertz, MatchesPaperEq58And59) {
  const double R = 0.8, rho = 0.5;
  // not eps = 1 +- 1e-16 (the asin(1/eps) and sqrt(eps^2 - 1) of (58)-(59) as
  // printed are then each off by ~1e-8, cancelling only in exact arithmetic)
  // nor eps > 7 (~eps^4 digits cancel); both covered by the oracle sweep
  const std::vector<double> eps = {0.0, 0.1, 0.6, 0.999, 1.001, 1.5, 2.2, 2.3, 4.0, 7.0};
  for (double e : eps) {
    for (double sgn : {1.0, -1.0}) {
      const double phi = -2.1;
      const Vec3 w =
          Vec3(e * R / rho * std::cos(phi), e * R / rho * std::sin(phi), sgn).normalized();
      const Vec3 fast = -exactDiskHertz(Vec2::Zero(), R, rho, w, nullptr);
      const Vec3 paper = testing::hertzDiskQ(R, 1.0, 1.0, rho, w);
      EXPECT_LE((fast - paper).cwiseAbs().maxCoeff(), kClosedFormTol)
          << "eps=" << e << " sign " << sgn;
    }
  }
  for (double e : {0.0, 0.5, 1.0, 3.0}) {
    const Vec3 w = Vec3(0.0, e * R / rho, 1.0).normalized();
    const Vec3 ref = testing::bruteForceQDisk(
        Vec2::Zero(), R, testing::hertzField(Vec2::Zero(), R, 1.0), 1.0, rho, w, kOracleTol);
    EXPECT_LE((testing::hertzDiskQ(R, 1.0, 1.0, rho, w) - ref).cwiseAbs().maxCoeff(), kContractTol)
        << "eps=" << e;
  }
}

// ---------------------------------------------------------------- jacobian

// The ICR c = rho (-w2, w1)/w3 moves by about R when the unit w turns by
// lambda = R rho / (|C| + R)^2 (for |c| ~ |C| + R); F varies on that scale.
double wScale(const Disk& d) {
  const double L = d.centre.norm() + d.R;
  return std::min(1.0, d.R * d.rho / (L * L));
}

// d/dw of f by finite differences: central (rim) or five-point.
template <class Fn>
Mat3 fdJacobian(const Fn& f, const Vec3& w, double h, bool fivePoint) {
  Mat3 J;
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = h * Vec3::Unit(j);
    if (fivePoint) {
      J.col(j) = (f(w - 2.0 * e) - 8.0 * f(w - e) + 8.0 * f(w + e) - f(w + 2.0 * e)) / (12.0 * h);
    } else {
      J.col(j) = (f(w + e) - f(w - e)) / (2.0 * h);
    }
  }
  return J;
}

TEST(ExactDiskBasis, JacobianMatchesFiniteDifferences) {
  double worst = 0.0, worstRim = 0.0;
  std::string worstName;
  for (const Disk& d : disks()) {
    for (const Case& c : cases(d)) {
      ExactBasis b;
      exactDiskBasis(d.centre, d.R, d.rho, c.w, true, b);
      ASSERT_LE(columnError(d, b.F, basis(d, c.w), 0), 1e-15) << "value with and without jacobian";
      const bool rim = c.name.rfind("rim", 0) == 0;
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(b.dF[k].allFinite()) << d.name << " " << c.name;
        const Mat3 fd = fdJacobian([&](const Vec3& v) -> Vec3 { return basis(d, v).col(k); }, c.w,
                                   (rim ? kFdRimStepRel : kFdStepRel) * wScale(d), !rim);
        // dF ~ S_k / lambda >= S_k typically; S_k floors columns that are
        // stationary by symmetry (e.g. phi = x at pure spin about the centre)
        const double size = std::max(b.dF[k].cwiseAbs().maxCoeff(), columnScale(d, k));
        const double err = (b.dF[k] - fd).cwiseAbs().maxCoeff() / size;
        EXPECT_LE(err, rim ? kFdRimTol : kFdTol)
            << d.name << " " << c.name << " column " << k << "\ndF=\n"
            << b.dF[k] << "\nfd=\n"
            << fd;
        if (!rim && err > worst) worstName = d.name + " " + c.name;
        (rim ? worstRim : worst) = std::max(rim ? worstRim : worst, err);
        EXPECT_LE((b.dF[k] * c.w).norm() / size, kHomogeneityTol) << d.name << " " << c.name;
      }
    }
  }
  std::printf("exactDiskBasis jacobian vs finite differences: worst %.2e (%s; rim %.2e)\n", worst,
              worstName.c_str(), worstRim);
}

TEST(ExactDiskHertz, JacobianMatchesFiniteDifferences) {
  double worst = 0.0, worstRim = 0.0;
  for (const Disk& d : disks()) {
    const double scale = 1.0 + (d.centre.norm() + d.R) / d.rho;  // bounds |result|
    for (const Case& c : cases(d)) {
      Mat3 J;
      const Vec3 value = exactDiskHertz(d.centre, d.R, d.rho, c.w, &J);
      ASSERT_LE((value - exactDiskHertz(d.centre, d.R, d.rho, c.w, nullptr)).norm(), 1e-15);
      ASSERT_TRUE(J.allFinite());
      const bool rim = c.name.rfind("rim", 0) == 0;
      const Mat3 fd = fdJacobian(
          [&](const Vec3& v) { return exactDiskHertz(d.centre, d.R, d.rho, v, nullptr); }, c.w,
          (rim ? kFdRimStepRel : kFdStepRel) * wScale(d), !rim);
      const double size = std::max(J.cwiseAbs().maxCoeff(), scale);
      const double err = (J - fd).cwiseAbs().maxCoeff() / size;
      EXPECT_LE(err, rim ? kFdRimTol : kFdTol) << d.name << " " << c.name << "\nJ=\n"
                                               << J << "\nfd=\n"
                                               << fd;
      (rim ? worstRim : worst) = std::max(rim ? worstRim : worst, err);
      EXPECT_LE((J * c.w).norm() / size, kHomogeneityTol);
    }
  }
  std::printf("exactDiskHertz jacobian vs finite differences: worst %.2e (rim %.2e)\n", worst,
              worstRim);
}

// ------------------------------------------------------------- continuity

// The branches (series about the centre, closed forms, far series) meet at
// delta^2 = kSwitchInside R^2, R^2 (rim) and kSwitchFar R^2; w3 = 0 is inside
// the far branch.
TEST(ExactDiskBasis, ContinuousAcrossBranchSwitchesAndPureTranslation) {
  for (const Disk& d : disks()) {
    for (double f2 : {kSwitchInside, 1.0, kSwitchFar}) {
      for (double phi : {0.3, 2.0, -1.9}) {
        const double f = std::sqrt(f2);
        const Vec3 wm = wForIcr(d, f * (1.0 - 0.5e-12), phi),
                   wp = wForIcr(d, f * (1.0 + 0.5e-12), phi);
        ExactBasis bm, bp;
        exactDiskBasis(d.centre, d.R, d.rho, wm, true, bm);
        exactDiskBasis(d.centre, d.R, d.rho, wp, true, bp);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE((bm.F.col(k) - bp.F.col(k)).cwiseAbs().maxCoeff() / columnScale(d, k),
                    kSwitchTol)
              << d.name << " delta^2/R^2=" << f2 << " phi=" << phi;
          // the jacobian is continuous too (it has a log-type modulus of
          // continuity at the rim: ~1e-12 |log 1e-12| there), relative to its size
          const double size = std::max(bm.dF[k].cwiseAbs().maxCoeff(), columnScale(d, k));
          EXPECT_LE((bm.dF[k] - bp.dF[k]).cwiseAbs().maxCoeff() / size, 1e-9)
              << d.name << " delta^2/R^2=" << f2 << " phi=" << phi;
        }
      }
    }
    // across w3 = 0, steps of 1e-13 lambda (the true change is ~1e-13 relative)
    for (const Vec3& wt : {Vec3(1, 0, 0), Vec3(0.6, -0.8, 0)}) {
      ExactBasis b0, bp, bm;
      exactDiskBasis(d.centre, d.R, d.rho, wt, true, b0);
      exactDiskBasis(d.centre, d.R, d.rho, wt + Vec3(0, 0, 1e-13 * wScale(d)), true, bp);
      exactDiskBasis(d.centre, d.R, d.rho, wt - Vec3(0, 0, 1e-13 * wScale(d)), true, bm);
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE((bp.F.col(k) - b0.F.col(k)).cwiseAbs().maxCoeff() / columnScale(d, k),
                  kSwitchTol);
        EXPECT_LE((bm.F.col(k) - b0.F.col(k)).cwiseAbs().maxCoeff() / columnScale(d, k),
                  kSwitchTol);
        const double size = std::max(b0.dF[k].cwiseAbs().maxCoeff(), columnScale(d, k));
        EXPECT_LE((bp.dF[k] - bm.dF[k]).cwiseAbs().maxCoeff() / size, kSwitchTol);
      }
    }
  }
}

TEST(ExactDiskHertz, ContinuousAcrossBranchSwitches) {
  for (const Disk& d : disks()) {
    const double scale = 1.0 + (d.centre.norm() + d.R) / d.rho;
    for (double f2 : {1.0, kSwitchFar}) {
      const double f = std::sqrt(f2);
      const Vec3 wm = wForIcr(d, f * (1.0 - 0.5e-12), 0.8),
                 wp = wForIcr(d, f * (1.0 + 0.5e-12), 0.8);
      Mat3 Jm, Jp;
      const Vec3 hm = exactDiskHertz(d.centre, d.R, d.rho, wm, &Jm);
      const Vec3 hp = exactDiskHertz(d.centre, d.R, d.rho, wp, &Jp);
      EXPECT_LE((hm - hp).cwiseAbs().maxCoeff() / scale, kSwitchTol) << d.name << " " << f2;
      EXPECT_LE((Jm - Jp).cwiseAbs().maxCoeff() / std::max(Jm.cwiseAbs().maxCoeff(), scale), 1e-9)
          << d.name << " " << f2;
    }
  }
}

// ---------------------------------------------------------- other contract

// Degree-0 homogeneity in w, including extreme magnitudes.
TEST(ExactDiskBasis, HomogeneousOfDegreeZero) {
  const Disk& d = disks()[2];
  for (const Case& c : cases(d)) {
    const Mat3 F = basis(d, c.w);
    for (double s : {1e-200, 3.7, 1e200}) {
      EXPECT_LE((basis(d, s * c.w) - F).cwiseAbs().maxCoeff() / columnScale(d, 0), 1e-14) << c.name;
    }
  }
}

// tolerance > 0 trades accuracy for fewer series terms / AGM steps; the error
// against full accuracy must stay below the requested tolerance (relative to
// the column scale).
TEST(ExactDiskBasis, ToleranceKnobBoundsTheError) {
  for (double tol : {1e-4, 1e-7}) {
    double worst = 0.0;
    for (const Disk& d : disks()) {
      for (const Case& c : cases(d)) {
        const Mat3 full = basis(d, c.w), fast = basis(d, c.w, tol);
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, columnError(d, fast, full, k));
        }
        // Hertz: |result| <= 1 + max|P| / rho for a unit load
        const double hertzScale = 1.0 + (d.centre.norm() + d.R) / d.rho;
        const Vec3 hFull = exactDiskHertz(d.centre, d.R, d.rho, c.w, nullptr);
        const Vec3 hFast = exactDiskHertz(d.centre, d.R, d.rho, c.w, nullptr, tol);
        worst = std::max(worst, (hFull - hFast).cwiseAbs().maxCoeff() / hertzScale);
      }
    }
    EXPECT_LE(worst, tol) << "tolerance " << tol;
    std::printf("tolerance %.0e: worst relative deviation %.2e\n", tol, worst);
  }
}

// ICR exactly on the rim (m = 1 to the last bit: K = inf, only its limit
// (1 - m) K = 0 enters): finite, and equal to its neighbours.
TEST(ExactDiskBasis, IcrExactlyOnTheRim) {
  const Disk d{"unit", Vec2::Zero(), 1.0, 1.0};
  const Vec3 w(0.0, -1.0, 1.0);  // c = rho (-w2, w1) / w3 = (1, 0) exactly
  ExactBasis b;
  exactDiskBasis(d.centre, d.R, d.rho, w, true, b);
  Mat3 J;
  const Vec3 h = exactDiskHertz(d.centre, d.R, d.rho, w, &J);
  ASSERT_TRUE(b.F.allFinite() && b.dF[0].allFinite() && b.dF[1].allFinite() && b.dF[2].allFinite());
  ASSERT_TRUE(h.allFinite() && J.allFinite());
  for (double f : {1.0 - 1e-12, 1.0 + 1e-12}) {
    const Vec3 wn = wForIcr(d, f, 0.0) * std::sqrt(2.0);
    ExactBasis bn;
    exactDiskBasis(d.centre, d.R, d.rho, wn, true, bn);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(columnError(d, b.F, bn.F, k), kSwitchTol) << "f=" << f;
      const double size = std::max(b.dF[k].cwiseAbs().maxCoeff(), columnScale(d, k));
      EXPECT_LE((b.dF[k] - bn.dF[k]).cwiseAbs().maxCoeff() / size, 1e-9) << "f=" << f;
    }
    EXPECT_LE((h - exactDiskHertz(d.centre, d.R, d.rho, wn, nullptr)).cwiseAbs().maxCoeff(),
              kSwitchTol);
  }
}

// Never NaN: random geometry over many orders of magnitude and w with exact
// zeros (pure spin, pure translation, ICR at the centre).
TEST(ExactDiskBasis, FiniteForExtremeInputs) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> zero(0, 3);
  for (int i = 0; i < 3000; ++i) {
    const double R = std::pow(10.0, 6.0 * u(rng)), rho = R * std::pow(10.0, 3.0 * u(rng));
    const Vec2 C = R * std::pow(10.0, 3.0 * u(rng)) * Vec2(u(rng), u(rng));
    Vec3 w(u(rng), u(rng), u(rng));
    const int z = zero(rng);
    if (z < 3) w[z] = 0.0;
    if (i % 7 == 0) w = Vec3(C.y() / rho, -C.x() / rho, 1.0);  // ICR at the centre
    w *= std::pow(10.0, 100.0 * u(rng));
    ExactBasis b;
    exactDiskBasis(C, R, rho, w, true, b);
    Mat3 J;
    const Vec3 h = exactDiskHertz(C, R, rho, w, &J);
    ASSERT_TRUE(b.F.allFinite() && b.dF[0].allFinite() && b.dF[1].allFinite() &&
                b.dF[2].allFinite() && h.allFinite() && J.allFinite())
        << "R=" << R << " rho=" << rho << " C=" << C.transpose() << " w=" << w.transpose();
  }
}

TEST(ExactDiskBasis, RejectsBadInput) {
  ExactBasis b;
  const Vec3 w(0.1, 0.2, 0.3);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), 0.0, 1.0, w, false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), -1.0, 1.0, w, false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), 1.0, 0.0, w, false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2(NAN, 0.0), 1.0, 1.0, w, false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), 1.0, 1.0, Vec3::Zero(), false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), 1.0, 1.0, Vec3(INFINITY, 0, 0), false, b), Error);
  EXPECT_THROW(exactDiskBasis(Vec2::Zero(), 1.0, 1.0, w, false, b, -1.0), Error);
  EXPECT_THROW(exactDiskHertz(Vec2::Zero(), 1.0, 1.0, Vec3::Zero(), nullptr), Error);
}

}  // namespace
}  // namespace patchspin
