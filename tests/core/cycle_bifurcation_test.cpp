// The bifurcation where the thick disk's limit cycle dies
// (patchspin/cycle_bifurcation.hpp), against an independent computation
// written here: the fold of fixed points of the fast dynamics re-derived
// from Newton-Euler with the exact law by brute-force quadrature
// (thick_disk_oracle.hpp), located by a plain Newton iteration on the
// extended system
//   V*(w) = 0 (two tangent components),  det J2(w) = 0,
// in the unknowns (w, F), J2 the projected Jacobian (31) by Richardson-
// extrapolated central differences of the oracle's V*; and the cycle's
// period near it by a plain RK4 run of the oracle's fast dynamics.
#include <gtest/gtest.h>

#include <cmath>
#include <patchspin/cycle_bifurcation.hpp>

#include "thick_disk_oracle.hpp"

namespace patchspin {
namespace {

using namespace thick_disk;

constexpr double kUnit = kMu * kMass * kG;  // mu m g [N]

// quadrature of the law at relTol 1e-10: V* to ~1e-10 relative (|F_o| ~ 5
// m/s^2), so the differences below carry ~5e-7 m/s^2 of noise
constexpr double kQuad = 1e-10;

// det J2 at w for force F: J2 in an orthonormal tangent basis (t1, t2) of w
// (det is basis-invariant), each column (4 D(k) - D(2k)) / 3 with D(k) the
// central difference at step k = 2e-3 (truncation O(k^4 V^(5)) ~ 1e-9;
// noise ~1e-6 m/s^2 per entry).
double detJ2(const Vec3& w, double F) {
  const Vec3 t1 = w.unitOrthogonal(), t2 = w.cross(t1);
  constexpr double k = 2e-3;
  auto column = [&](const Vec3& t) {
    // (a Vec3, not an Eigen expression of destroyed temporaries)
    auto D = [&](double s) -> Vec3 {
      return (oracleV(w + s * t, F, kQuad) - oracleV(w - s * t, F, kQuad)) / (2 * s);
    };
    const Vec3 d = (4.0 * D(k) - D(2 * k)) / 3.0;
    return Eigen::Vector2d(t1.dot(d), t2.dot(d));
  };
  Eigen::Matrix2d J;
  J.col(0) = column(t1);
  J.col(1) = column(t2);
  return J.determinant();
}

// The fold of fixed points: Newton on G(a, b, xi) = (e1.V*, e2.V*, det J2)
// at w = normalize(w0 + a e1 + b e2), F = xi mu m g; Jacobian by forward
// differences (step 1e-6; its error only slows convergence). Returns (w, xi).
std::pair<Vec3, double> oracleFold(const Vec3& w0, double xi0) {
  const Vec3 e1 = w0.unitOrthogonal(), e2 = w0.cross(e1);
  auto G = [&](const Eigen::Vector3d& x) {
    const Vec3 w = (w0 + x[0] * e1 + x[1] * e2).normalized();
    const double F = x[2] * kUnit;
    const Vec3 V = oracleV(w, F, kQuad);
    return Eigen::Vector3d(e1.dot(V), e2.dot(V), detJ2(w, F));
  };
  Eigen::Vector3d x(0.0, 0.0, xi0);
  for (int it = 0; it < 12; ++it) {
    const Eigen::Vector3d g = G(x);
    Eigen::Matrix3d J;
    constexpr double kStep = 1e-4;
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d y = x;
      y[j] += kStep;
      J.col(j) = (G(y) - g) / kStep;
    }
    const Eigen::Vector3d dx = J.lu().solve(-g);
    x += dx;
    if (dx.norm() < 1e-9) break;
  }
  return {(w0 + x[0] * e1 + x[1] * e2).normalized(), x[2]};
}

// Located from the sweep's bracket [0.13, 0.14] (cycle at 0.13, a node on
// its track at 0.14) to 1e-6 mu m g; the oracle's fold from a rough start
// (w3 > 0 pole's side, two digits from a coarse scan).
TEST(CycleBifurcation, ThickDiskCycleDiesInASaddleNodeOnTheCycle) {
  const double fWith = 0.13 * kUnit, fWithout = 0.14 * kUnit;
  const FlatBodyModel model(thickDisk(fWith), Model::Exact);
  const LimitAnalysis fixed = findLimitDirections(model);
  CycleOptions options;
  options.seeds = 8;
  options.backward = false;
  const CycleAnalysis cycles = findLimitCycles(model, fixed, options);
  const LimitCycle* up = nullptr;
  for (const LimitCycle& c : cycles.cycles) {
    if (c.attracting && c.w3Max > 0.0) up = &c;
  }
  ASSERT_NE(up, nullptr);
  constexpr double kLocateTol = 1e-6;  // in mu m g, the bisection's bracket
  const CycleBifurcation b =
      locateCycleBifurcation(thickDisk(0.0), Model::Exact, fWith, fWithout, *up, kLocateTol * kUnit,
                             {3e-3 * kUnit, 1e-3 * kUnit});
  ASSERT_EQ(b.kind, CycleBifurcation::SaddleNodeOnCycle);
  EXPECT_LE(b.forceError, kLocateTol * kUnit);

  const auto [wFold, xiFold] = oracleFold(Vec3(-0.15, -0.67, 0.73), 0.135);
  // the oracle's fold is a fixed point of its field with det J2 = 0 (Newton
  // converged: |G| < 1e-11, checked here on the field)
  EXPECT_LT(oracleV(wFold, xiFold * kUnit, kQuad).norm(), 1e-8);
  EXPECT_LT(std::abs(detJ2(wFold, xiFold * kUnit)), 1e-6);
  // The code's bracket [lo, hi] has no pair at lo and the pair at hi (its
  // own fixed-point solver, residual < 1e-11 |F_o|, still separates node and
  // saddle 4e-3 apart at hi - F* ~ 1e-7 mu m g); the oracle's fold converges
  // to |G| < 1e-11 (its det J2 carries ~1e-6 (m/s^2)^2 of difference noise,
  // which moves F* only at second order: along the branch xi - xi* ~ s^2,
  // det ~ s). So the two agree to the bracket: measured 1.1e-7.
  constexpr double kAgree = 2.0 * kLocateTol;  // in mu m g; the issue asks 1e-4
  EXPECT_NEAR(b.force / kUnit, xiFold, kAgree);
  // the midpoint of the pair is the saddle-node to O(hi - F*) (measured
  // 3e-6), and lies on the track of the cycle near F* (the cycle at F* -
  // 1e-3 mu m g passes within 1e-3 of it)
  EXPECT_LT((b.point - wFold).norm(), 1e-4);
  EXPECT_LT(b.distanceToCycle, 2e-3);
  // at the last force with the pair its eigenvalues through 0 are small:
  // |lambda| ~ 3.4 sqrt(xi - xi*) against -3 ... -4 m/s^2 of the other one
  EXPECT_LT(std::abs(b.nodeEigenvalue), 0.02);
  EXPECT_LT(std::abs(b.saddleEigenvalue), 0.02);

  // on the cycle's side the period diverges as (xi* - xi)^(-1/2): from 3e-3
  // to 1e-3 by sqrt(3) = 1.73 up to the O(sqrt(dxi)) regular part (> 1.5);
  // the extent stays finite (not a Hopf) and the multiplier tends to 0
  // (not a fold of cycles, where it tends to 1)
  ASSERT_EQ(b.approach.size(), 2u);
  const auto& far = b.approach[0];
  const auto& near = b.approach[1];
  EXPECT_GT(near.period / far.period, 1.5);
  EXPECT_GT(near.w3Max - near.w3Min, 0.25);
  EXPECT_LT(near.multiplier, far.multiplier);
  EXPECT_LT(near.multiplier, 1e-20);
}

}  // namespace
}  // namespace patchspin
