// Limit cycles of the fast dynamics on the sphere of slip directions
// (patchspin/limit_cycles.hpp) against an independent computation written
// here and in thick_disk_oracle.hpp: the thick disk's fast dynamics
// re-derived from Newton-Euler, the exact law (16) by brute-force quadrature
// (tests/support/oracle.hpp), and a plain fixed-step RK4 run from a seed.
#include <gtest/gtest.h>

#include <cmath>
#include <patchspin/limit_cycles.hpp>

#include "thick_disk_oracle.hpp"

namespace patchspin {
namespace {

using namespace thick_disk;

// A plain fixed-step RK4 run of w' = F_o - (w.F_o) w from w0 over [0, tEnd]
// (fast time, s^2/m), recording over [tFrom, tEnd] the extent of w3, the
// downward crossings of phi = atan2(w2, w1) through 0 (w2 from + to -,
// w1 > 0; linear interpolation), and, between the last two crossings, the
// integral of R* = w.F_o and the turn of phi.
struct OracleRun {
  double w3Min = 1e9, w3Max = -1e9;
  std::vector<double> crossings;
  double intR = 0.0, turn = 0.0;  // over [crossings[n-2], crossings[n-1]]
  Vec3 last = Vec3::Zero();
};

OracleRun runOracle(const Vec3& w0, double F, double h, double tFrom, double tEnd) {
  OracleRun out;
  Vec3 w = w0.normalized();
  std::vector<double> rdots, phis;
  double intR = 0.0, phi = std::atan2(w.y(), w.x()), prevZ = w.z();
  for (double t = 0.0; t < tEnd; t += h) {
    auto V = [&](const Vec3& x, double* rdot) {
      const Vec3 Fo = oracleField(x, F);
      if (rdot) *rdot = x.dot(Fo);
      return Vec3(Fo - x.dot(Fo) * x);
    };
    double r1, r2, r3, r4;
    const Vec3 k1 = V(w, &r1);
    const Vec3 k2 = V(w + h / 2 * k1, &r2);
    const Vec3 k3 = V(w + h / 2 * k2, &r3);
    const Vec3 k4 = V(w + h * k3, &r4);
    const Vec3 next = (w + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)).normalized();
    const double dR = h / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
    const double dphi =
        std::remainder(std::atan2(next.y(), next.x()) - std::atan2(w.y(), w.x()), 2.0 * M_PI);
    if (t + h >= tFrom) {
      // extremes of w3: the vertex of the parabola through three nodes
      // (error ~ the third derivative times a step cubed, < 1e-6)
      const double a = prevZ, b = w.z(), c = next.z();
      const double curv = a - 2.0 * b + c;
      if ((b >= a && b >= c) || (b <= a && b <= c)) {
        const double vertex = curv != 0.0 ? b - (c - a) * (c - a) / (8.0 * curv) : b;
        out.w3Min = std::min(out.w3Min, vertex);
        out.w3Max = std::max(out.w3Max, vertex);
      }
      if (w.y() > 0.0 && next.y() <= 0.0 && next.x() > 0.0) {
        // at the crossing, interpolated linearly within the step
        const double theta = w.y() / (w.y() - next.y());
        out.crossings.push_back(t + theta * h);
        rdots.push_back(intR + theta * dR);
        phis.push_back(phi + theta * dphi);
      }
    }
    intR += dR;
    phi += dphi;
    prevZ = w.z();
    w = next;
  }
  const std::size_t n = rdots.size();
  if (n >= 2) {
    out.intR = rdots[n - 1] - rdots[n - 2];
    out.turn = phis[n - 1] - phis[n - 2];
  }
  out.last = w;
  return out;
}

// Issue 34: F = 0.4469 N, F / (mu m g) = 0.0911. The oracle runs from a seed
// near the pole (inside the cycle, off the repelling focus) for 3.1 periods
// with h = 0.04 s^2/m (|F_o| <= 5.4 m/s^2: <= 0.22 rad per step, RK4 error
// ~1e-6 per period) and measures the last two periods.
TEST(LimitCycles, ThickDiskExactLawEndsOnACycleAroundEachPole) {
  constexpr double kF = 0.4469;
  const FlatBodyModel model(thickDisk(kF), Model::Exact);
  const LimitAnalysis fixed = findLimitDirections(model);
  for (const LimitDirection& d : fixed.directions) EXPECT_NE(d.type, LimitType::Dominant);
  const CycleAnalysis cycles = findLimitCycles(model, fixed);
  ASSERT_TRUE(cycles.complete());
  ASSERT_EQ(cycles.cycles.size(), 2u);
  for (const SeedEnd& e : cycles.forward) EXPECT_EQ(e.kind, SeedEnd::Cycle);
  const LimitCycle& up = cycles.cycles[0].w3Max > 0.0 ? cycles.cycles[0] : cycles.cycles[1];
  const LimitCycle& down = cycles.cycles[0].w3Max > 0.0 ? cycles.cycles[1] : cycles.cycles[0];

  const OracleRun run = runOracle(Vec3(0.3, 0.0, 0.95), kF, 0.04, 10.0, 28.0);
  ASSERT_GE(run.crossings.size(), 2u);
  // extent: RK4 at 0.22 rad per step and quadrature at 1e-6 move the
  // oracle's cycle by ~1e-6; both sides take the extremes as the vertex of
  // a parabola through three nodes (error ~1e-7)
  constexpr double kExtentTol = 1e-5;
  EXPECT_NEAR(up.w3Min, run.w3Min, kExtentTol);
  EXPECT_NEAR(up.w3Max, run.w3Max, kExtentTol);
  // the w3 < 0 cycle is the mirror image (w2, w3) -> (-w2, -w3)
  EXPECT_NEAR(down.w3Min, -run.w3Max, kExtentTol);
  EXPECT_NEAR(down.w3Max, -run.w3Min, kExtentTol);
  // period from successive crossings of phi = 0 (linear interpolation
  // within a step: the same ~1e-5 error at both ends, cancelling)
  constexpr double kPeriodTol = 1e-4;  // relative
  const std::size_t n = run.crossings.size();
  EXPECT_NEAR(up.period, run.crossings[n - 1] - run.crossings[n - 2], kPeriodTol * up.period);
  EXPECT_NEAR(down.period, up.period, kPeriodTol * up.period);
  // counter-clockwise spin, clockwise turn: -2 pi per period
  EXPECT_NEAR(up.turn, -2.0 * M_PI, 1e-9);
  // (the oracle's ends are interpolated linearly within a step: the
  // phase error ~ (h dphi/dt)^2 / 8, dphi/dt <= 3 rad per s^2/m, < 2e-3)
  constexpr double kInterpolatedTurn = 2e-3;
  EXPECT_NEAR(run.turn, -2.0 * M_PI, kInterpolatedTurn);
  EXPECT_NEAR(down.turn, 2.0 * M_PI, 1e-9);
  // mean R* and the turn per decade of slip (the oracle's integral between
  // interpolated crossings: its ends off by < 1e-3 of a step's R*, 1e-5 of
  // the period's)
  constexpr double kRateTol = 1e-4;  // relative
  EXPECT_NEAR(up.meanRdot * up.period, run.intR, kRateTol * std::abs(run.intR));
  EXPECT_NEAR(up.turnPerDecade, -std::log(10.0) * run.turn / run.intR,
              kRateTol * std::abs(up.turnPerDecade));
  // v / (R omega) = rho sqrt(1 - w3^2) / (R w3) at the w3 extremes
  auto ratio = [](double w3) { return kRho * std::sqrt(1.0 - w3 * w3) / (kR * w3); };
  // (|d ratio / d w3| <= 2.1 on the cycle: kExtentTol times that)
  constexpr double kRatioTol = 2.1 * kExtentTol;
  EXPECT_NEAR(up.slipRatioMin, ratio(run.w3Max), kRatioTol);
  EXPECT_NEAR(up.slipRatioMax, ratio(run.w3Min), kRatioTol);
  // strongly attracting: the oracle is on the cycle within its first period
  // (its extents after 10 s^2/m match to kExtentTol); the two multipliers
  // agree within the slope's absolute error (limit_cycles.hpp)
  EXPECT_TRUE(up.attracting);
  EXPECT_GT(up.multiplier, 0.0);
  EXPECT_LT(up.multiplier, 1e-6);
  EXPECT_NEAR(up.returnMapSlope, up.multiplier, 1e-7);
}

// F / (mu m g) = 0.40: two dominant directions attract; no cycle, and every
// seed ends at one of them. The oracle, from a seed, reaches the reported
// attracting direction (RK4 h = 0.02 for 12 s^2/m: the slower eigenvalue
// -1.87 m/s^2 contracts by e^-22).
TEST(LimitCycles, ThickDiskWithADominantDirectionHasNoCycle) {
  const double F = 0.40 * kMu * kMass * kG;
  const FlatBodyModel model(thickDisk(F), Model::Exact);
  const LimitAnalysis fixed = findLimitDirections(model);
  const CycleAnalysis cycles = findLimitCycles(model, fixed);
  EXPECT_TRUE(cycles.cycles.empty());
  EXPECT_TRUE(cycles.complete());
  for (const SeedEnd& e : cycles.forward) {
    ASSERT_EQ(e.kind, SeedEnd::FixedPoint);
    EXPECT_EQ(fixed.directions[static_cast<std::size_t>(e.index)].type, LimitType::Dominant);
  }
  const OracleRun run = runOracle(Vec3(0.3, 0.0, 0.95), F, 0.02, 0.0, 12.0);
  double nearest = 1e9;
  for (const LimitDirection& d : fixed.directions) {
    if (d.type == LimitType::Dominant) nearest = std::min(nearest, (d.w - run.last).norm());
  }
  EXPECT_LT(nearest, 1e-6);
}

// The free thick disk (F = 0) is axisymmetric: its fixed directions are
// the poles (unstable foci on the sphere) and the equator (pure sliding, a
// circle of fixed points), and its slip direction ends on a circle of
// latitude around each pole, turning along it: the curl of the curling
// demo. The oracle places the circle where the meridional component of its
// field V* changes sign, V*(w(t)) . e_t = 0 with w(t) = (sin t, 0, cos t),
// e_t = (cos t, 0, -sin t) (bisection to 1e-10 rad), and gives the period
// 2 pi sin t / |V*_phi| (speed along the circle). 16 seeds keep it short.
TEST(LimitCycles, FreeThickDiskCurlsOnACircleOfLatitude) {
  const FlatBodyModel model(thickDisk(0.0), Model::Exact);
  const LimitAnalysis fixed = findLimitDirections(model);
  ASSERT_EQ(fixed.continua.size(), 1u);
  EXPECT_FALSE(fixed.continua[0].sphere);
  CycleOptions options;
  options.seeds = 16;
  const CycleAnalysis cycles = findLimitCycles(model, fixed, options);
  ASSERT_TRUE(cycles.searched);
  EXPECT_TRUE(cycles.complete());
  const LimitCycle* up = nullptr;
  for (const LimitCycle& c : cycles.cycles)
    if (c.attracting && c.w3Max > 0.0) up = &c;
  ASSERT_NE(up, nullptr);
  for (const SeedEnd& e : cycles.forward) EXPECT_NE(e.kind, SeedEnd::Unresolved);

  auto meridional = [](double t) {
    const Vec3 w(std::sin(t), 0.0, std::cos(t));
    return oracleV(w, 0.0).dot(Vec3(std::cos(t), 0.0, -std::sin(t)));
  };
  // the sign change from away from the pole (> 0) to back towards it (< 0)
  double lo = NAN, hi = NAN;
  for (double t = 0.05; t < 1.5; t += 0.05) {
    if (meridional(t) > 0.0 && meridional(t + 0.05) < 0.0) {
      lo = t, hi = t + 0.05;
      break;
    }
  }
  ASSERT_TRUE(std::isfinite(lo));
  while (hi - lo > 1e-10) {
    const double mid = 0.5 * (lo + hi);
    (meridional(mid) > 0.0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  // (as in ThickDiskExactLawEndsOnACycleAroundEachPole: RK4 and the
  // oracle's 1e-6 quadrature move the circle by ~1e-6)
  constexpr double kExtentTol = 1e-5;
  EXPECT_NEAR(up->w3Min, std::cos(t), kExtentTol);
  EXPECT_NEAR(up->w3Max, std::cos(t), kExtentTol);
  const Vec3 w(std::sin(t), 0.0, std::cos(t));
  const double vPhi = oracleV(w, 0.0).y();  // e_phi = (0, 1, 0) at phi = 0
  ASSERT_GT(std::abs(vPhi), 0.1);           // turning: a cycle, not fixed points
  constexpr double kPeriodTol = 1e-4;       // relative
  EXPECT_NEAR(up->period, 2.0 * M_PI * std::sin(t) / std::abs(vPhi), kPeriodTol * up->period);
  EXPECT_NEAR(std::abs(up->turn), 2.0 * M_PI, 1e-9);
}

// The ellipsoidal law at the issue's force has dominant foci: no cycle.
TEST(LimitCycles, EllipsoidalLawAtTheIssuesForceHasNoCycle) {
  const FlatBodyModel model(thickDisk(0.4469), Model::Ellipsoidal);
  const LimitAnalysis fixed = findLimitDirections(model);
  const CycleAnalysis cycles = findLimitCycles(model, fixed);
  EXPECT_TRUE(cycles.cycles.empty());
  EXPECT_TRUE(cycles.complete());
  for (const SeedEnd& e : cycles.forward) EXPECT_EQ(e.kind, SeedEnd::FixedPoint);
}

// Issue 34, item 5: the fixed directions of the exact thick disk at
// F / (mu m g) = 0.15, 0.25, 0.40 are zeros of the independent field, with
// the same rate and, from central differences of that field on the
// tangent plane, the same eigenvalues (31): both negative (dominant), so
// the cycle of the 0.0911 case has given way to attracting directions.
TEST(LimitCycles, DominantDirectionsOfTheThickDiskAreZerosOfTheIndependentField) {
  for (double xi : {0.15, 0.25, 0.40}) {
    const double F = xi * kMu * kMass * kG;
    const FlatBodyModel model(thickDisk(F), Model::Exact);
    const LimitAnalysis fixed = findLimitDirections(model);
    int dominant = 0;
    for (const LimitDirection& d : fixed.directions) {
      if (d.type != LimitType::Dominant) continue;
      ++dominant;
      // quadrature at relTol 1e-10 here: F_o to ~1e-10 relative
      constexpr double kQuad = 1e-10;
      const Vec3 Fo = oracleField(d.w, F, kQuad);
      const double scale = Fo.norm();
      // the code's residual is < 1e-11 of the field, the oracle's ~1e-10
      constexpr double kFieldTol = 1e-8;  // relative to |F_o|
      EXPECT_LT((Fo - d.w.dot(Fo) * d.w).norm(), kFieldTol * scale) << xi;
      EXPECT_NEAR(d.w.dot(Fo), d.rdot, kFieldTol * scale) << xi;
      // projected Jacobian J2 = E^T dV* E of (31) by central differences on
      // the tangent plane: step 1e-3, truncation ~1e-6 |V'''| (~1e-5 m/s^2),
      // quadrature noise 1e-10 |F_o| / 1e-3 (~5e-7 m/s^2) per entry
      const Vec3 e1 = d.w.unitOrthogonal(), e2 = d.w.cross(e1);
      constexpr double kStep = 1e-3;
      auto V = [&](const Vec3& w) {
        const Vec3 x = w.normalized();
        const Vec3 f = oracleField(x, F, kQuad);
        return Vec3(f - x.dot(f) * x);
      };
      Eigen::Matrix2d J;
      for (int k = 0; k < 2; ++k) {
        const Vec3 e = k == 0 ? e1 : e2;
        const Vec3 dV = (V(d.w + kStep * e) - V(d.w - kStep * e)) / (2.0 * kStep);
        J(0, k) = e1.dot(dV);
        J(1, k) = e2.dot(dV);
      }
      const Eigen::Vector2cd lambda = J.eigenvalues();
      for (int k = 0; k < 2; ++k) EXPECT_LT(lambda[k].real(), 0.0) << xi;
      // the pair of (31) is invariant to the basis: trace and determinant,
      // to 1e-4 m/s^2 and 1e-3 (m/s^2)^2 (ten times the entries' error, times
      // |J| <= 6 m/s^2 for the determinant)
      constexpr double kTraceTol = 1e-4, kDetTol = 1e-3;
      const double tr = d.eigenvalues.sum().real();
      const double det = (d.eigenvalues[0] * d.eigenvalues[1]).real();
      EXPECT_NEAR(J.trace(), tr, kTraceTol) << xi;
      EXPECT_NEAR(J.determinant(), det, kDetTol) << xi;
    }
    EXPECT_EQ(dominant, 2) << xi;
  }
}

// A budget too short to reach anything: every seed is listed as unresolved,
// in both directions, none silently dropped. (1 / fieldScale of fast time,
// 50 RK4 steps: the cycle's period is 47 such units, and the slowest
// approach to a fixed direction takes longer than one.)
TEST(LimitCycles, SeedsThatReachNothingWithinTheBudgetAreListed) {
  const FlatBodyModel model(thickDisk(0.4469), Model::Exact);
  const LimitAnalysis fixed = findLimitDirections(model);
  CycleOptions options;
  options.seeds = 8;
  options.budget = 1.0;
  const CycleAnalysis cycles = findLimitCycles(model, fixed, options);
  EXPECT_FALSE(cycles.complete());
  ASSERT_EQ(cycles.forward.size(), 8u);
  ASSERT_EQ(cycles.backward.size(), 8u);
  std::size_t unresolvedForward = 0, unresolvedBackward = 0;
  for (const SeedEnd& e : cycles.forward) unresolvedForward += e.kind == SeedEnd::Unresolved;
  for (const SeedEnd& e : cycles.backward) unresolvedBackward += e.kind == SeedEnd::Unresolved;
  EXPECT_EQ(cycles.unresolvedForward.size(), unresolvedForward);
  EXPECT_EQ(cycles.unresolvedBackward.size(), unresolvedBackward);
  EXPECT_EQ(unresolvedForward, 8u);  // no attracting fixed direction, no cycle yet
}

}  // namespace
}  // namespace patchspin
