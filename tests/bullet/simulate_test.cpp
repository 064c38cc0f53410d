// patchspin::scenes::simulate against independent predictions: the exact
// model's free thin disk (limit ratio and stopping time), the ellipsoidal
// model's drift to pure spin and its slip-spin limit direction under a small
// push, and a box's spin-down under the exact spin torque.
#include <patchspin/analysis.hpp>
#include <patchspin/scenes/simulate.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace patchspin::scenes {
namespace {

const bool kDouble = std::string(buildPrecision()) == "double";

// ---- independent oracle: free thin uniform disk under local Coulomb friction --
// Unit disk (R = 1), uniform pressure of total 1 (mu g = 1, m = 1), sliding
// at speed eps along x and spinning at omega = 1. Point (x, y) slips with
// v = (eps - y, x); brute-force polar midpoint rule of
//   F = -∫ p v/|v| dA (along x),   T = -∫ p (x v_y - y v_x)/|v| dA.
// The integrand is bounded and jumps only at the one point where v = 0, so
// the rule converges like 1/N; N = 300 gives ~1e-5 (checked against N = 1000).
void diskForceTorque(double eps, int n, double& F, double& T) {
  F = T = 0;
  const double dr = 1.0 / n, dt = 2 * M_PI / (4 * n);
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * dr;
    for (int j = 0; j < 4 * n; ++j) {
      const double t = (j + 0.5) * dt, x = r * std::cos(t), y = r * std::sin(t);
      const double vx = eps - y, vy = x, v = std::hypot(vx, vy), dA = r * dr * dt / M_PI;
      F -= vx / v * dA;
      T -= (x * vy - y * vx) / v * dA;
    }
  }
}

// The ratio eps = v / (R omega) that the free disk keeps: with J = m R^2 / 2,
//   d(ln v)/dt = d(ln omega)/dt  <=>  F / eps = 2 T.
// While it is kept, v falls at the constant rate mu g |F|, so the disk stops at
//   t = eps R omega0 / (mu g |F(eps)|).
struct DiskLimit {
  double eps, stopCoefficient;
};
DiskLimit diskLimit() {
  constexpr int kN = 300;
  auto g = [&](double e) {
    double F, T;
    diskForceTorque(e, kN, F, T);
    return F / e - 2 * T;
  };
  double a = 0.5, b = 0.8;
  const double ga = g(a);
  for (int k = 0; k < 30; ++k) {
    const double m = 0.5 * (a + b);
    if ((g(m) > 0) == (ga > 0))
      a = m;
    else
      b = m;
  }
  DiskLimit d;
  d.eps = 0.5 * (a + b);
  double F, T;
  diskForceTorque(d.eps, kN, F, T);
  d.stopCoefficient = d.eps / std::abs(F);
  return d;
}

// Oracle accuracy (quadrature, 1/N) against the issue's figures.
constexpr double kOracleTol = 5e-4;

TEST(Simulate, OracleReproducesTheIssuesDiskConstants) {
  const DiskLimit d = diskLimit();
  std::printf("[oracle] eps* = %.6f, t_stop = %.6f R w0 / (mu g)\n", d.eps, d.stopCoefficient);
  EXPECT_NEAR(d.eps, 0.6530, kOracleTol);  // Farkas et al. 2003
  EXPECT_NEAR(d.stopCoefficient, 1.0600, kOracleTol);
}

SimulationSpec thinDisk(const std::string& model, double ratio, double omega0) {
  SimulationSpec s;
  s.engine = "bullet";
  s.precision = kDouble ? "double" : "float";
  s.model = model;
  s.shape = SimulationSpec::Shape::Cylinder;
  s.R = 0.05;
  // thin: the centre of mass 0.1 mm above the patch tilts the pressure by a
  // negligible 0.2 % of its mean across the disk
  s.H = 2e-4;
  s.mass = 1.0;
  s.mu = 0.3;
  s.g = 9.81;
  s.omega0 = omega0;
  s.v0 = Vec2(ratio * s.R * omega0, 0.0);
  s.keepTrajectory = true;
  return s;
}

// The implicit step is first order: over the ~500 steps of these runs the
// slip direction follows the continuous flow to about dt / t_stop ~ 0.2 %,
// well inside the issue's 1 % (w) and 2 % (stopping time).
constexpr double kRatioTol = 0.01;
constexpr double kStopRelTol = 0.02;

TEST(Simulate, ExactFreeThinDiskKeepsItsLimitRatioAndStopsOnTime) {
  const DiskLimit d = diskLimit();
  const SimulationSpec s = thinDisk("exact", d.eps, 60.0);
  const SimulationResult r = simulate(s);
  ASSERT_TRUE(r.stopped);
  const double tPredicted = d.stopCoefficient * s.R * s.omega0 / (s.mu * s.g);
  double worst = 0;
  for (const SimulationSample& q : r.trajectory) {
    if (q.r < s.recordAt * r.trajectory.front().r) break;
    worst = std::max(worst, std::abs(q.velocity.norm() / (s.R * std::abs(q.omega)) - d.eps));
  }
  std::printf(
      "[exact disk] t_stop %.5f s (predicted %.5f), eps_stop %.5f, worst ratio error %.2e\n",
      r.tStop, tPredicted, r.epsStop.value_or(-1), worst);
  EXPECT_LT(worst, kRatioTol);
  ASSERT_TRUE(r.epsStop);
  EXPECT_NEAR(*r.epsStop, d.eps, kRatioTol);
  EXPECT_NEAR(r.tStop, tPredicted, kStopRelTol * tPredicted);
}

// The sample at which simulate() recorded w (first with r < recordAt r0).
const SimulationSample& recordedSample(const SimulationResult& r, double recordAt) {
  for (const SimulationSample& q : r.trajectory)
    if (q.r < recordAt * r.trajectory.front().r) return q;
  return r.trajectory.back();
}

// From ratio 1 the ratio falls toward eps*. Independent prediction: with
// v = eps R omega, |F|, |T| from the oracle (per unit mu m g, R = 1),
//   d eps / d ln(omega) = (|F| - 2 eps |T|) / (2 |T|),
// integrated by RK4 in ln(omega) until the slip r = R omega sqrt(eps^2 + 4/9)
// (rho = 2R/3) reaches the r of the recorded sample. N = 150 quadrature
// (~2e-5) suffices for the 1 % comparison.
TEST(Simulate, ExactFreeThinDiskFromRatioOneFallsTowardLimitRatio) {
  const DiskLimit d = diskLimit();
  const SimulationSpec s = thinDisk("exact", 1.0, 60.0);
  const SimulationResult r = simulate(s);
  ASSERT_TRUE(r.stopped);
  ASSERT_TRUE(r.epsStop);
  // the ratio falls monotonically from 1 toward eps*
  double previous = 1.0 + 1e-9;
  for (const SimulationSample& q : r.trajectory) {
    if (q.r < s.recordAt * r.trajectory.front().r) break;
    const double ratio = q.velocity.norm() / (s.R * std::abs(q.omega));
    EXPECT_LE(ratio, previous + 1e-6);
    EXPECT_GE(ratio, d.eps - kRatioTol);
    previous = ratio;
  }
  const double rRecorded = recordedSample(r, s.recordAt).r;
  auto slope = [](double e) {
    double F, T;
    diskForceTorque(e, 150, F, T);
    return (std::abs(F) - 2 * e * std::abs(T)) / (2 * std::abs(T));
  };
  double eps = 1.0, lnw = std::log(s.omega0);
  const double h = -0.05;  // overshoots the recorded r by < 5 %, where eps changes by < 1e-3
  while (s.R * std::exp(lnw) * std::sqrt(eps * eps + 4.0 / 9.0) > rRecorded) {
    const double k1 = slope(eps), k2 = slope(eps + 0.5 * h * k1), k3 = slope(eps + 0.5 * h * k2),
                 k4 = slope(eps + h * k3);
    eps += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    lnw += h;
  }
  std::printf("[exact disk] from ratio 1: eps_stop %.5f, ODE %.5f (limit %.5f)\n", *r.epsStop, eps,
              d.eps);
  EXPECT_NEAR(*r.epsStop, eps, kRatioTol);
}

// ---- ellipsoidal thin disk: closed-form flow ------------------------------------
// Uniform pressure on a centred disk gives Pi = I (Sect. 4.5.2), so with
// rho = 2R/3 and J = m R^2 / 2 the slip state x = (u_x, u_y, rho w) obeys
//   dx/dt = mu g (f - w1, -w2, -(8/9) w3),   f = F / (mu m g),
// (8/9 = 2 rho^2 / R^2). Its slip-spin limit direction (w2 = 0, w3 != 0):
//   rdot = -(8/9) mu g,  w1 = 9 f,  w3 = sqrt(1 - 81 f^2)  (exists for f < 1/9).
TEST(Simulate, EllipsoidalThinDiskStaysOnSlipSpinLimitDirectionBelowMuMgOverNine) {
  SimulationSpec s = thinDisk("ellipsoidal", 0.0, 0.0);
  const double f = 0.05;  // below 1/9
  s.force = Vec2(f * s.mu * s.mass * s.g, 0.0);
  const double rho = 2.0 * s.R / 3.0;
  const Vec3 w(9 * f, 0.0, std::sqrt(1 - 81 * f * f));
  const double r0 = 2.0;  // [m/s]
  s.v0 = Vec2(r0 * w.x(), 0.0);
  s.omega0 = r0 * w.z() / rho;
  const SimulationResult r = simulate(s);
  ASSERT_TRUE(r.stopped);
  const double tPredicted = r0 / (8.0 / 9.0 * s.mu * s.g);
  double worst = 0;
  for (const SimulationSample& q : r.trajectory) {
    if (q.r < s.recordAt * r0) break;
    worst = std::max(worst, (q.w - w).norm());
  }
  std::printf(
      "[ellipsoidal limit dir] t_stop %.5f (predicted %.5f), w_stop (%.4f %.4f %.4f), worst |w - "
      "w*| %.2e\n",
      r.tStop, tPredicted, r.wStop.x(), r.wStop.y(), r.wStop.z(), worst);
  EXPECT_LT(worst, kRatioTol);
  EXPECT_LT((r.wStop - w).norm(), kRatioTol);
  EXPECT_NEAR(r.tStop, tPredicted, kStopRelTol * tPredicted);
}

// Free ellipsoidal disk: x1' = -mu g w1, x3' = -(8/9) mu g w3, so
// d ln(x1/x3)/dt = -(1/9) mu g / r < 0: the ratio falls toward pure spin.
// Independent check of every step: the implicit step of this flow,
//   x+ + c D x+/|x+| = x,   D = diag(1, 1, 8/9),   c = mu g dt,
// solved here by bisection on r = |x+| (x+ = (I + (c/r) D)^-1 x), sticks
// when |D^-1 x| <= c. The Bullet disk is not infinitely thin: friction at O,
// 0.1 mm below the centre of mass, tilts the pressure by ~h/R = 0.2 %, which
// moves Pi off I by as much; kDiscreteTol allows for that.
constexpr double kDiscreteTol = 3e-3;

Vec3 implicitEllipsoidalStep(const Vec3& x, double c) {
  const Vec3 D(1, 1, 8.0 / 9.0);
  if (x.cwiseQuotient(D).norm() <= c) return Vec3::Zero();
  auto next = [&](double r) { return Vec3(x.array() / (1.0 + c / r * D.array())); };
  double lo = 0, hi = x.norm();
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (lo + hi);
    (next(m).norm() > m ? lo : hi) = m;
  }
  return next(0.5 * (lo + hi));
}

TEST(Simulate, EllipsoidalFreeThinDiskFallsTowardPureSpin) {
  const SimulationSpec s = thinDisk("ellipsoidal", 1.0, 60.0);
  const SimulationResult r = simulate(s);
  ASSERT_TRUE(r.stopped);
  ASSERT_TRUE(r.epsStop);
  const double rho = 2.0 * s.R / 3.0;
  Vec3 x(s.v0.x(), 0, rho * s.omega0);
  double previous = 1.0 + 1e-9, worst = 0;
  for (size_t k = 1; k < r.trajectory.size(); ++k) {
    const SimulationSample& q = r.trajectory[k];
    x = implicitEllipsoidalStep(x, s.mu * s.g * s.dt);
    if (q.r < s.recordAt * r.trajectory.front().r) break;
    const double ratio = q.velocity.norm() / (s.R * std::abs(q.omega));
    const double expected = x.x() / (s.R * x.z() / rho);
    worst = std::max(worst, std::abs(ratio - expected));
    EXPECT_LE(ratio, previous + 1e-9);  // falls toward pure spin
    previous = ratio;
  }
  std::printf(
      "[ellipsoidal free disk] eps_stop %.5f from 1; worst deviation from the implicit flow %.2e\n",
      *r.epsStop, worst);
  EXPECT_LT(worst, kDiscreteTol);
  EXPECT_LT(*r.epsStop, 0.6);
}

// ---- box spinning in place --------------------------------------------------------
// Uniform pressure m g / A on the LX x LY face; pure spin gives the torque
// mu m g mean|r| for both models (exact (16) directly; ellipsoidal: Pi w for
// w = (0,0,1) is pi_xy / rho = mean|r| / rho). With J_z = m (LX^2 + LY^2)/12:
//   t_stop = omega0 J_z / (mu m g mean|r|).
// mean|r| by a brute-force midpoint grid (2000^2 cells, error ~1e-7).
double meanDistance(double lx, double ly) {
  constexpr int kN = 2000;
  double sum = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      sum += std::hypot((i + 0.5) / kN - 0.5, ((j + 0.5) / kN - 0.5) * ly / lx);
  return lx * sum / (double(kN) * kN);
}

TEST(Simulate, BoxSpinDownTimeFromExactSpinTorque) {
  const double lx = 0.1, ly = 0.06;
  const double meanR = meanDistance(lx, ly);
  for (const char* model : {"exact", "ellipsoidal", "stock"}) {
    SimulationSpec s;
    s.engine = "bullet";
    s.precision = kDouble ? "double" : "float";
    s.model = model;
    s.shape = SimulationSpec::Shape::Box;
    s.LX = lx;
    s.LY = ly;
    s.LZ = 0.04;
    s.mu = 0.3;
    s.omega0 = 20.0;
    const SimulationResult r = simulate(s);
    const double jz = s.mass * (lx * lx + ly * ly) / 12;
    const double tPredicted = s.omega0 * jz / (s.mu * s.mass * s.g * meanR);
    std::printf("[box spin-down] %-11s t_stop %.5f s, predicted %.5f s (%+.2f %%), stopped %d\n",
                model, r.tStop, tPredicted, 100 * (r.tStop / tPredicted - 1), int(r.stopped));
    if (std::string(model) == "stock") continue;  // printed for comparison only
    ASSERT_TRUE(r.stopped) << model;
    EXPECT_NEAR(r.tStop, tPredicted, 0.01 * tPredicted) << model;
    EXPECT_LT(r.displacement.norm(), 1e-6) << model << ": pure spin must not drift";
  }
}

TEST(Simulate, RejectsPrecisionOtherThanTheBuilds) {
  SimulationSpec s = thinDisk("exact", 0.5, 10.0);
  s.precision = kDouble ? "float" : "double";
  EXPECT_THROW(simulate(s), Error);
  s.precision = "half";
  EXPECT_THROW(simulate(s), Error);
  s = thinDisk("coulomb", 0.5, 10.0);
  EXPECT_THROW(simulate(s), Error);
}

// ---- agreement with the reference dynamics on attracting-dominant limit directions --
// The analysis module (findLimitDirections) predicts the attracting-dominant
// direction w* and its rate rdot; started there with slip r0, the body stays
// on w* and stops at r0 / |rdot|. The Bullet run is compared with that
// prediction (w within kLimitWTol, stop within kLimitStopTol, the issue's
// bounds) and with simulateReference's run of the same spec (adaptive
// Dormand-Prince, independent of Bullet): stop within kAgreementStopTol,
// recorded w within kLimitWTol.
constexpr double kLimitWTol = 0.02;
constexpr double kLimitStopTol = 0.03;
constexpr double kAgreementStopTol = 0.02;

struct LimitCase {
  const char* name;
  SimulationSpec spec;
};

void checkLimitCase(LimitCase c) {
  SimulationSpec& s = c.spec;
  const FlatBodyModel model(flatBodyFromSpec(s), modelFromString(s.model));
  const LimitAnalysis analysis = findLimitDirections(model);
  const LimitDirection* best = nullptr;
  for (const LimitDirection& d : analysis.directions)
    if (d.attracting && d.type == LimitType::Dominant && d.w.z() > 0 &&
        (!best || d.w.z() > best->w.z()))
      best = &d;
  ASSERT_NE(best, nullptr) << c.name << ": no attracting-dominant limit direction with spin";
  const Vec3 w = best->w;
  const double r0 = 1.5;  // [m/s]
  s.v0 = Vec2(r0 * w.x(), r0 * w.y());
  s.omega0 = r0 * w.z() / model.rho();
  s.keepTrajectory = true;
  const SimulationResult bullet = simulate(s);
  SimulationSpec ref = s;
  ref.engine = "reference";
  ref.keepTrajectory = false;
  const SimulationResult reference = simulateReference(ref);
  ASSERT_TRUE(bullet.stopped) << c.name;
  ASSERT_TRUE(reference.stopped) << c.name;
  const double tPredicted = r0 / std::abs(best->rdot);
  double worst = 0;
  for (const SimulationSample& q : bullet.trajectory) {
    if (q.r < s.recordAt * r0) break;
    worst = std::max(worst, (q.w - w).norm());
  }
  std::printf(
      "[limit %s] w* (%.4f %.4f %.4f) rdot %.4f: bullet t_stop %.5f, reference %.5f, predicted "
      "%.5f; "
      "worst |w - w*| %.2e, |w_stop(bullet) - w_stop(ref)| %.2e\n",
      c.name, w.x(), w.y(), w.z(), best->rdot, bullet.tStop, reference.tStop, tPredicted, worst,
      (bullet.wStop - reference.wStop).norm());
  EXPECT_LT(worst, kLimitWTol) << c.name;
  EXPECT_NEAR(bullet.tStop, tPredicted, kLimitStopTol * tPredicted) << c.name;
  EXPECT_NEAR(bullet.tStop, reference.tStop, kAgreementStopTol * reference.tStop) << c.name;
  EXPECT_LT((bullet.wStop - reference.wStop).norm(), kLimitWTol) << c.name;
}

TEST(Simulate, AgreesWithReferenceOnThinDiskPushedBelowMuMgOverNine) {
  SimulationSpec s = thinDisk("ellipsoidal", 0.0, 0.0);
  s.force = Vec2(0.05 * s.mu * s.mass * s.g, 0.0);
  checkLimitCase({"thin disk f=0.05", s});
}

TEST(Simulate, AgreesWithReferenceOnThickDisk) {
  SimulationSpec s = thinDisk("ellipsoidal", 0.0, 0.0);
  s.H = 0.06;  // centre of mass 3 cm above the patch of radius 5 cm
  s.force = Vec2(0.05 * s.mu * s.mass * s.g, 0.0);
  checkLimitCase({"thick disk", s});
}

TEST(Simulate, AgreesWithReferenceOnDiskWithInPlaneTorque) {
  SimulationSpec s = thinDisk("ellipsoidal", 0.0, 0.0);
  s.force = Vec2(0.03 * s.mu * s.mass * s.g, 0.0);      // fixes the frame of w
  s.torque = Vec3(0.0, 0.1 * s.mass * s.g * s.R, 0.0);  // centre of pressure 0.1 R off O
  checkLimitCase({"in-plane torque", s});
}

// A light coin (20 g) sliding and spinning freely: Bullet and the reference
// dynamics agree on the stop time, the travel and the recorded w. (A body of
// mass != 1 kg exercises the mass factor of the gyroscopic matrix (92).)
// Travel tolerance: one 240 Hz step at the initial speed, v0 dt.
TEST(Simulate, LightCoinAgreesWithReferenceOnTravel) {
  SimulationSpec s = thinDisk("exact", 0.5, 20.0);
  s.mass = 0.02;
  const SimulationResult bullet = simulate(s);
  SimulationSpec ref = s;
  ref.engine = "reference";
  const SimulationResult reference = simulateReference(ref);
  ASSERT_TRUE(bullet.stopped);
  ASSERT_TRUE(reference.stopped);
  const double kTravelTol = s.v0.norm() * s.dt;
  std::printf(
      "[light coin] t_stop bullet %.5f reference %.5f; travel bullet (%.5f %.5f) reference (%.5f "
      "%.5f)\n",
      bullet.tStop, reference.tStop, bullet.displacement.x(), bullet.displacement.y(),
      reference.displacement.x(), reference.displacement.y());
  EXPECT_NEAR(bullet.tStop, reference.tStop, kAgreementStopTol * reference.tStop);
  EXPECT_LT((bullet.displacement - reference.displacement).norm(), kTravelTol);
  EXPECT_LT((bullet.wStop - reference.wStop).norm(), kLimitWTol);
}

// When the step that crosses recordAt * r0 is the one that sticks (here
// recordAt * r0 = 8.3 mm/s is below one step's resolution mu g dt = 12 mm/s),
// the slip direction at the crossing is undefined; simulate() records the
// last slipping step's w. It keeps the spin (w3 near the reference's, within
// the issue's 0.02) instead of reporting the force direction with w3 = 0.
TEST(Simulate, StickStepRecordsLastSlippingDirection) {
  SimulationSpec s = thinDisk("exact", 0.0, 20.0);
  s.mass = 0.03;
  s.H = 0.005;
  s.v0 = Vec2(0.0, 0.5);
  s.force = Vec2(0.05 * s.mu * s.mass * s.g, 0.0);  // Case 3 of Sect. 6.1
  const SimulationResult bullet = simulate(s);
  SimulationSpec ref = s;
  ref.engine = "reference";
  ref.keepTrajectory = false;
  const SimulationResult reference = simulateReference(ref);
  ASSERT_TRUE(bullet.stopped);
  ASSERT_TRUE(bullet.epsStop.has_value());
  const SimulationSample* last = nullptr;
  for (const SimulationSample& q : bullet.trajectory)
    if (q.r > 0.0 && q.r >= 1e-5 * bullet.trajectory.front().r) last = &q;
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(bullet.wStop, last->w);
  EXPECT_NEAR(bullet.wStop.z(), reference.wStop.z(), kLimitWTol);
}

}  // namespace
}  // namespace patchspin::scenes
