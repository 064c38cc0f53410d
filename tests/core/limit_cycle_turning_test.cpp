// Issue 34, item 3: the reference dynamics (Eq. (93), integrateReference)
// of the thick disk pushed at F = 0.4469 N turns its slip velocity at the
// rate per decade of slip that findLimitCycles predicts, measured from the
// trajectory over several decades of r.
//
// Thick disk: R = 1 m, centre of mass 0.4 m above the patch (cylinder H =
// 0.8 m), m = 1 kg, Jz = m R^2 / 2 = 0.5 kg m^2, mu = 0.5, g = 9.81, F along x,
// exact law. Its centre of mass lies on the patch's axis and its loads are
// fixed in the ground frame, so Eq. (93) in ground axes is x' = F_o(x / |x|)
// at every r: the fast dynamics holds exactly, not only as r -> 0, and the
// trajectory's w follows the cycle while r falls linearly in t. One period of
// the cycle is 16.4 decades of r (-2 pi of turn at -22.03 deg per decade);
// the reference integrator's step and error are relative to r, so it
// follows r over 60 decades in double.
//
// The cycle's prediction itself is checked against an independent RK4
// integrator with a brute-force quadrature of the law in
// tests/core/limit_cycles_test.cpp (ThickDiskExactLawEndsOnACycleAroundEachPole:
// turnPerDecade to 1e-4); this test compares the trajectory with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cycle_turning.hpp>
#include <patchspin/limit_cycles.hpp>

namespace patchspin {
namespace {

using testing::CycleTable;
using testing::TurnSample;

SimulationSpec thickDiskSpec() {
  SimulationSpec s;
  s.shape = SimulationSpec::Shape::Cylinder;
  s.R = 1.0;
  s.H = 0.8;
  s.mass = 1.0;
  s.mu = 0.5;
  s.g = 9.81;
  s.force = Vec2(0.4469, 0.0);
  return s;
}

// The cycle with w3 > 0 (counter-clockwise spin).
LimitCycle upperCycle(const FlatBodyModel& model) {
  const CycleAnalysis cycles = findLimitCycles(model, findLimitDirections(model));
  EXPECT_EQ(cycles.cycles.size(), 2u);
  for (const LimitCycle& c : cycles.cycles)
    if (c.w3Max > 0.0 && c.attracting) return c;
  ADD_FAILURE() << "no attracting cycle with w3 > 0";
  return LimitCycle();
}

// The reference run from slip direction w0 at r0 = 1 m/s down to r = 1e-60
// m/s, every accepted step sampled.
std::vector<TurnSample> referenceTurn(const FlatBodyModel& model, const Vec3& w0) {
  BodyState start;
  start.x = w0.normalized();
  ReferenceOptions options;
  options.tMax = 10.0;  // r falls at ~4.2 m/s^2: stops after ~0.25 s
  options.sampleDt = 1e-300;
  options.stopFraction = 1e-60;
  const ReferenceRun run = integrateReference(model, start, options);
  EXPECT_TRUE(run.stopped);
  EXPECT_FALSE(run.tipping);
  std::vector<Vec3> states;
  for (const auto& [t, s] : run.samples) states.push_back(s.x);
  return testing::turnSamples(states);
}

// Downward crossings of w2 = 0 with w1 > 0 (phi = 0 mod 2 pi), linear in w2
// within the step: {decades, phi} at each.
std::vector<std::pair<double, double>> crossings(const std::vector<TurnSample>& s) {
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const Vec3 a = s[i - 1].w, b = s[i].w;
    if (a.y() > 0.0 && b.y() <= 0.0 && b.x() > 0.0) {
      const double t = a.y() / (a.y() - b.y());
      out.emplace_back(s[i - 1].decades + t * (s[i].decades - s[i - 1].decades),
                       s[i - 1].phi + t * (s[i].phi - s[i - 1].phi));
    }
  }
  return out;
}

// The transient onto the cycle: the multiplier is 2e-12 per 16.4 decades, a
// factor e^-1 per 0.6 decade; after 8 decades the distance to the cycle is
// ~1e-6 of its start.
constexpr double kTransientDecades = 8.0;

TEST(LimitCycleTurning, ReferenceDynamicsTurnsAtTheCyclesRatePerDecade) {
  const FlatBodyModel model(flatBodyFromSpec(thickDiskSpec()), Model::Exact);
  const LimitCycle cycle = upperCycle(model);
  ASSERT_GT(cycle.period, 0.0);
  // counter-clockwise spin, sliding along the force, off the cycle
  const std::vector<TurnSample> s = referenceTurn(model, Vec3(0.6, 0.0, 0.8));
  std::vector<std::pair<double, double>> x;
  for (const auto& c : crossings(s))
    if (c.first > kTransientDecades) x.push_back(c);
  // two whole periods or more between 8 and 60 decades
  ASSERT_GE(x.size(), 3u);
  const double turn = x.back().second - x.front().second;
  const double decades = x.back().first - x.front().first;
  const double measured = turn / decades;  // [rad per decade], > 0 counter-clockwise
  std::printf("reference: %.6f deg per decade over %.4f decades (%zu periods), cycle %.6f\n",
              measured * 180 / M_PI, decades, x.size() - 1, cycle.turnPerDecade * 180 / M_PI);
  // DP5 at relTol 1e-10 and linear interpolation at the crossings: measured
  // 1e-7 relative over two periods (single periods at relTol 1e-12 scatter
  // by 2e-4, the step controller at the law's own accuracy). The issue asks
  // for 1 %; 1e-4 still fails on a phase error of a fiftieth of a step.
  constexpr double kRateTol = 1e-4;  // relative
  EXPECT_NEAR(measured, cycle.turnPerDecade, kRateTol * std::abs(cycle.turnPerDecade))
      << "measured " << measured * 180 / M_PI << " deg per decade over " << decades
      << " decades, predicted " << cycle.turnPerDecade * 180 / M_PI;
  // each whole period: -2 pi (clockwise for counter-clockwise spin)
  for (std::size_t i = 1; i < x.size(); ++i)
    EXPECT_NEAR(x[i].second - x[i - 1].second, cycle.turn, 1e-3) << i;
  EXPECT_LT(cycle.turnPerDecade, 0.0);
}

// Over part of a period the turn depends on where the window starts on the
// cycle: CycleTable predicts it from the cycle's orbit. The table is checked
// against the cycle's own period, turn and mean R*, then against the
// reference over 3-decade windows at several phases (the same prediction
// the Bullet test uses, tests/bullet/limit_cycle_turning_bullet_test.cpp).
TEST(LimitCycleTurning, ReferenceTurnOverAFewDecadesFollowsTheCyclesPhase) {
  const FlatBodyModel model(flatBodyFromSpec(thickDiskSpec()), Model::Exact);
  const LimitCycle cycle = upperCycle(model);
  ASSERT_GT(cycle.period, 0.0);
  const CycleTable table(model, cycle);
  // midpoint rule on ~400 segments of <= 0.12 rad: ~1e-5 relative
  constexpr double kTableTol = 1e-4;  // relative
  EXPECT_NEAR(table.period(), cycle.period, kTableTol * cycle.period);
  EXPECT_NEAR(table.turnPerPeriod(), cycle.turn, 1e-9);
  const double decadesPerPeriod = -cycle.period * cycle.meanRdot / std::log(10.0);
  EXPECT_NEAR(table.decadesPerPeriod(), decadesPerPeriod, kTableTol * decadesPerPeriod);

  const std::vector<TurnSample> s = referenceTurn(model, Vec3(0.6, 0.0, 0.8));
  constexpr double kWindow = 3.0;  // decades
  double lo = 1e9, hi = -1e9, worst = 0.0;
  for (double d0 = kTransientDecades; d0 + kWindow < 55.0; d0 += 1.7) {
    const double phiA = testing::phiAt(s, d0), phiB = testing::phiAt(s, d0 + kWindow);
    ASSERT_TRUE(std::isfinite(phiA) && std::isfinite(phiB)) << d0;
    // the prediction from the first sample in the window, whose w fixes the
    // phase, to the window's end
    std::size_t k = 0;
    while (k + 1 < s.size() && s[k].decades < d0) ++k;
    const double predicted = table.predictTurn(table.phaseOf(s[k].w), d0 + kWindow - s[k].decades);
    // the phase match (projection on the orbit's chords) and the linear
    // interpolation in decades at the end, each ~1e-4 rad at most (measured:
    // 4e-5 rad), against turns of 0.5 to 2.4 rad
    constexpr double kTurnTol = 1e-3;  // [rad]
    EXPECT_NEAR(phiB - s[k].phi, predicted, kTurnTol) << "window from " << d0 << " decades";
    worst = std::max(worst, std::abs(phiB - s[k].phi - predicted));
    lo = std::min(lo, (phiB - phiA) / kWindow);
    hi = std::max(hi, (phiB - phiA) / kWindow);
  }
  std::printf("3-decade windows: %.3f .. %.3f deg per decade, largest |turn - cycle| %.2e rad\n",
              lo * 180 / M_PI, hi * 180 / M_PI, worst);
  // the windows differ: the phase matters (a window's rate is not Gamma)
  EXPECT_GT(hi - lo, 0.05 * std::abs(cycle.turnPerDecade))
      << "rates per decade over 3-decade windows: " << lo * 180 / M_PI << " .. " << hi * 180 / M_PI
      << " deg";
}

// `patchspin simulate --engine reference` (simulateReference) reports the
// turn up to the record instant: started on the cycle at r0 = 1 m/s and
// recorded at 1e-8 r0, it is the cycle's turn over those 8 decades.
TEST(LimitCycleTurning, SimulateReferenceReportsTheCyclesTurn) {
  SimulationSpec spec = thickDiskSpec();
  const FlatBodyModel model(flatBodyFromSpec(spec), Model::Exact);
  const LimitCycle cycle = upperCycle(model);
  ASSERT_GT(cycle.period, 0.0);
  const CycleTable table(model, cycle);
  spec.v0 = cycle.point.head<2>();
  spec.omega0 = cycle.point.z() / model.rho();
  spec.recordAt = 1e-8;
  const SimulationResult r = simulateReference(spec);
  ASSERT_TRUE(r.stopped);
  const double predicted = table.predictTurn(table.phaseOf(cycle.point), 8.0);
  std::printf("simulate --engine reference: turn %.5f deg over 8 decades, cycle %.5f deg\n",
              r.turn * 180 / M_PI, predicted * 180 / M_PI);
  // the record lands on r = 1e-8 r0 to 1e-6 (4e-7 decades, ~3e-7 rad); the
  // table's phase match and midpoint rule ~1e-4 rad (the windows above)
  EXPECT_NEAR(r.turn, predicted, 1e-3);
}

}  // namespace
}  // namespace patchspin
