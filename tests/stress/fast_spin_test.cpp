// A disk spinning at 1000 rad/s spins down on time, without rocking or
// drifting (issue 6). Moved from scenes_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stress_scenes.hpp"

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

// Coin R = 5 cm, H = 1 cm, 1 kg, mu 0.3, spinning in place at 1000 rad/s
// (rim speed 50 m/s). Uniform pressure on a centred disk: spin torque
// mu m g 2R/3 (exact law, and the ellipsoidal one with pi_xy = rho), J =
// m R^2 / 2, so it stops at t = 3 R omega0 / (4 mu g) = 12.74 s. Each step
// removes the same d omega exactly; float round-off of omega (6e-5 rad/s per
// step at 1000 rad/s) over 3000 steps stays below 2e-4 omega0:
// kSpinStopTol = 1e-3 relative, plus one step. Tilt rates below 1e-3 rad/s
// (the rocking bound); the centre stays within 1 % of R
// (kSpinDriftTol: a pure spin carries no net friction force).
constexpr double kSpinR = 0.05, kSpinH = 0.01, kSpinMu = 0.3, kOmega0 = 1000.0;
constexpr double kSpinStopTol = 1e-3;
constexpr double kTiltBound = 1e-3;
constexpr double kSpinDriftTol = 0.01 * kSpinR;

struct SpinResult {
  bool finite = true;
  double tStop = -1.0, tilt = 0.0, drift = 0.0;
};

SpinResult spinDown(Friction model, double tMax) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  btRigidBody* c = scene.addCylinder(kSpinR, kSpinH, 1.0, bt(0, 0, kSpinH / 2), kSpinMu);
  optIn(scene, c, model);
  c->setAngularVelocity(bt(0, 0, kOmega0));
  SpinResult r;
  for (int k = 1; k * kDt <= tMax; ++k) {
    scene.step(kDt);
    if (!isFinite(c)) {
      r.finite = false;
      break;
    }
    const btVector3 w = c->getAngularVelocity();
    r.tilt = std::max(r.tilt, std::hypot(double(w.x()), double(w.y())));
    const btVector3 p = c->getWorldTransform().getOrigin();
    r.drift = std::max(r.drift, std::hypot(double(p.x()), double(p.y())));
    const PatchReport* rep = scene.solver().findPatchReport(c);
    const bool stopped =
        model == Friction::Stock ? std::abs(double(w.z())) < 1e-3 * kOmega0 : rep && rep->sticking;
    if (stopped) {
      r.tStop = k * kDt;
      break;
    }
  }
  return r;
}

TEST(StressScenes, DiskSpinningAt1000RadPerSecondSpinsDownOnTime) {
  const double tPredicted = 3.0 * kSpinR * kOmega0 / (4.0 * kSpinMu * kG);
  Table table(
      "Disk spinning at 1000 rad/s (predicted stop " + fmt("%.4f", tPredicted) + " s)",
      {"model", "finite", "t_stop [s]", "rel. error", "max tilt rate [rad/s]", "centre drift [m]"});
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const SpinResult r = spinDown(m, 1.5 * tPredicted);
    table.add({toString(m), passFail(r.finite), fmt("%.4f", r.tStop),
               fmt("%.2e", (r.tStop - tPredicted) / tPredicted), fmt("%.2e", r.tilt),
               fmt("%.2e", r.drift)});
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(r.finite) << toString(m);
    EXPECT_NEAR(r.tStop, tPredicted, kSpinStopTol * tPredicted + kDt) << toString(m);
    EXPECT_LT(r.tilt, kTiltBound) << toString(m);
    EXPECT_LT(r.drift, kSpinDriftTol) << toString(m);
  }
  table.emit();
}

}  // namespace
}  // namespace patchspin::bullet::stress
