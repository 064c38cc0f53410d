// A coin rolling on its rim, pushed into the floor past Bullet's
// split-impulse threshold, stays there: Bullet's limit cycle, in every model
// (the rim is a point contact, Bullet's). Moved from scenes_test.cpp; found
// as "escaped" coins in scratch runs of the 100-coin pours
// (docs/notes/coin_pour.md). Bullet's split-impulse threshold is 0.04 world
// units, 4 mm in the float pour's decimetres; deeper contacts are corrected
// by a split impulse whose turn is scaled by m_splitImpulseTurnErp (0.1).
// Started in the state of such a coin, a lone coin is trapped in decimetres
// in every model; with the turn erp at 1, or in metres (Baumgarte at this
// depth), it comes out and lies flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pour_scenes.hpp"

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

TEST(StressScenes, ARollingCoinSunkPastBulletsSplitThresholdStaysInTheFloor) {
  constexpr double kTrapTime = 10.0;  // [s]
  // depth of the coin's lowest point under the floor [m] (the state below is
  // 4.9 mm in; a coin out of the floor has its outline on it)
  constexpr double kTrappedDepth = 4e-3, kReleasedDepth = 1e-4;
  constexpr double kFlatTilt = 1e-3;  // [rad] lying flat (trapped: 0.089)
  struct Run {
    std::string label;
    Friction model;
    double unit;
    double turnErp;  // Bullet's m_splitImpulseTurnErp
  };
  const double defaultTurnErp = double(btContactSolverInfo().m_splitImpulseTurnErp);
  const std::vector<Run> runs = {
      {"stock, dm", Friction::Stock, kDecimetres, defaultTurnErp},
      {"ellipsoidal, dm", Friction::Ellipsoidal, kDecimetres, defaultTurnErp},
      {"exact, dm", Friction::Exact, kDecimetres, defaultTurnErp},
      {"stock, dm, turn erp 1", Friction::Stock, kDecimetres, 1.0},
      {"ellipsoidal, dm, turn erp 1", Friction::Ellipsoidal, kDecimetres, 1.0},
      {"stock, m", Friction::Stock, 1.0, defaultTurnErp},
      {"ellipsoidal, m", Friction::Ellipsoidal, 1.0, defaultTurnErp},
  };
  Table table("A coin rolling on its rim, started 4.9 mm into the floor, after " +
                  fmt("%.0f", kTrapTime) + " s",
              {"run", "lowest point [mm]", "tilt [rad]", "max speed in the last 1 s [m/s]"});
  for (const Run& run : runs) {
    const double unit = run.unit;
    Scene scene(kG * unit, PourSolver{}.iterations);  // the pours' solver settings
    scene.world().getSolverInfo().m_splitImpulseTurnErp = btScalar(run.turnErp);
    scene.addGroundPlane(1.0);
    btRigidBody* coin = scene.addCylinder(unit * kPourR, unit * kPourH, kPourMass, bt(0, 0, 0), 0.4,
                                          unit * kPourMargin);
    const btVector3 up = bt(0.011, -0.087, 0.996).normalized();
    const btVector3 axis = bt(0, 0, 1).cross(up);
    btTransform t;
    t.setIdentity();
    t.setRotation(btQuaternion(axis.normalized(), btAsin(axis.length())));
    t.setOrigin(bt(0, 0, -0.0006 * unit));
    coin->setWorldTransform(t);
    coin->setLinearVelocity(bt(0.0094 * unit, -0.0062 * unit, -0.0532 * unit));
    coin->setAngularVelocity(bt(3.359, 11.912, 2.433));
    optIn(scene, coin, run.model);
    const int steps = int(std::lround(kTrapTime / kDt));
    double maxSpeed = 0.0;
    for (int k = 0; k < steps; ++k) {
      scene.step(kDt);
      if (k >= steps - int(std::lround(1.0 / kDt)))
        maxSpeed =
            std::max(maxSpeed, (double(coin->getLinearVelocity().length()) +
                                double(coin->getAngularVelocity().length()) * unit * kPourR) /
                                   unit);
    }
    ASSERT_TRUE(isFinite(coin)) << run.label;
    const double lowest = extremeZ(coin, true) / unit;
    const double tilt = std::acos(
        std::min(1.0, std::abs(double(coin->getWorldTransform().getBasis().getColumn(2).z()))));
    table.add({run.label, fmt("%+.3f", 1e3 * lowest), fmt("%.3f", tilt), fmt("%.3e", maxSpeed)});
    if (unit == kDecimetres && run.turnErp == defaultTurnErp) {
      // Bullet's limit cycle (above), whatever the coin's friction model
      EXPECT_LT(lowest, -kTrappedDepth) << run.label << ": the coin came out of the floor";
      EXPECT_GT(maxSpeed, kPourRestSpeed) << run.label;
    } else {
      // released: the coin lies flat on the floor, and at rest on its patch
      // (stock Bullet's flat coin, in metres, falls at g dt in every step
      // and is pushed back: 4.1e-2 m/s in float, 9e-9 in double)
      EXPECT_GT(lowest, -kReleasedDepth) << run.label;
      EXPECT_LT(tilt, kFlatTilt) << run.label;
      if (run.model != Friction::Stock) {
        EXPECT_LT(maxSpeed, kPourRestSpeed) << run.label;
      }
    }
  }
  table.emit();
}

}  // namespace
}  // namespace patchspin::bullet::stress
