// A coin under patch friction in a Bullet world: no creep under a push inside
// the friction limit, no energy gain, no rocking, no subnormal crumbs. Moved
// from patch_friction_solver_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bullet_scenes.hpp"

namespace patchspin::bullet {
namespace {

// ---- no creep ---------------------------------------------------------------
// A force inside the friction limit leaves the body exactly at rest: the
// friction block sticks (s = 0 for all six patch DOFs), so the centre of mass
// never moves by more than kCreepBound (bullet_scenes.hpp).

double creep(bool patch, Model model) {
  Coin coin(patch, model);
  const btVector3 start = coin.body->getWorldTransform().getOrigin();
  const btVector3 push(btScalar(0.9 * kMu * kMass * kG), 0, 0);
  for (int k = 0; k < 2400; ++k) {
    coin.body->applyCentralForce(push);
    coin.scene.step(kDt);
  }
  const btVector3 d = coin.body->getWorldTransform().getOrigin() - start;
  return std::hypot(double(d.x()), double(d.y()));
}

TEST(PatchFrictionSolver, NoCreepUnderPushInsideFrictionLimit) {
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    const double d = creep(true, model);
    std::printf("[creep] %s (%s): %.3e m over 10 s; stock Bullet: %.3e m\n", toString(model),
                kDouble ? "double" : "float", d, creep(false, model));
    RecordProperty(std::string("creep_") + toString(model), std::to_string(d));
    EXPECT_LT(d, kCreepBound) << toString(model);
  }
}

// ---- friction never adds energy ----------------------------------------------
// Sliding and spinning coin, no driving force: the kinetic energy may only
// fall, step by step. Allowed rise per step: round-off of the energy sum,
// 1e-12 (double) / 1e-5 (float: velocities stored in float, eps 6e-8, times
// the ~100 flops between steps) relative to the initial energy.
constexpr double kEnergyRelTol = kDouble ? 1e-12 : 1e-5;

TEST(PatchFrictionSolver, FrictionNeverIncreasesKineticEnergy) {
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    Coin coin(true, model);
    coin.body->setLinearVelocity(btVector3(1.0, 0.3, 0));
    coin.body->setAngularVelocity(btVector3(0, 0, 25.0));
    coin.scene.step(kDt);  // settle the gravity impulse on the first contact
    double e = coin.scene.kineticEnergy();
    const double e0 = e;
    double worstRise = -1e300;
    int steps = 0;
    for (; steps < 480 && e > 0; ++steps) {
      coin.scene.step(kDt);
      const double e1 = coin.scene.kineticEnergy();
      worstRise = std::max(worstRise, e1 - e);
      EXPECT_LE(e1, e + kEnergyRelTol * e0) << toString(model) << " step " << steps;
      e = e1;
    }
    std::printf("[energy] %s: E0 = %.4f J, largest step-to-step change %.3e J, final %.3e J\n",
                toString(model), e0, worstRise, e);
    EXPECT_LT(e, 1e-12 + 1e-6 * e0) << "coin should have stopped within 2 s";
  }
}

// ---- no rocking ---------------------------------------------------------------
// Resting and sliding coins keep their tilt rates below kTiltBound (issue
// bound); the normal block holds both tilt DOFs at O, and the position
// correction works on pseudo velocities only.

double worstTilt(bool patch, const btVector3& v0, double omega0, int steps) {
  Coin coin(patch);
  coin.body->setLinearVelocity(v0);
  coin.body->setAngularVelocity(btVector3(0, 0, btScalar(omega0)));
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    coin.scene.step(kDt);
    worst = std::max(worst, coin.tiltRate());
  }
  return worst;
}

TEST(PatchFrictionSolver, RestingCoinDoesNotRock) {
  const double ours = worstTilt(true, btVector3(0, 0, 0), 0, 480);
  std::printf("[rocking] resting coin: max tilt rate %.3e rad/s; stock Bullet %.3e rad/s\n", ours,
              worstTilt(false, btVector3(0, 0, 0), 0, 480));
  EXPECT_LT(ours, kTiltBound);
}

TEST(PatchFrictionSolver, SlidingAndSpinningCoinDoesNotRock) {
  const double ours = worstTilt(true, btVector3(1.5, 0, 0), 30, 480);
  std::printf(
      "[rocking] sliding+spinning coin: max tilt rate %.3e rad/s; stock Bullet %.3e rad/s\n", ours,
      worstTilt(false, btVector3(1.5, 0, 0), 30, 480));
  EXPECT_LT(ours, kTiltBound);
}

// A coin held flat keeps no subnormal-producing crumbs: every component of its
// angular velocity and orientation basis is either exactly 0 or large enough
// that its square is a normal btScalar (subnormal arithmetic is ~100x slower;
// without the solver's flush the tilt components sat at ~1e-18 rad/s and
// ~1e-21, whose products are subnormal in single precision).
TEST(PatchFrictionSolver, FlatCoinCarriesNoSubnormalCrumbs) {
  Coin coin(true);
  coin.body->setLinearVelocity(btVector3(0.4, -0.2, 0));
  coin.body->setAngularVelocity(btVector3(0, 0, 9));
  const btScalar tiny = std::sqrt(std::numeric_limits<btScalar>::min());
  int crumbs = 0;
  for (int k = 0; k < 240; ++k) {
    coin.scene.step(kDt);
    const btVector3 w = coin.body->getAngularVelocity();
    const btMatrix3x3& basis = coin.body->getWorldTransform().getBasis();
    for (int i = 0; i < 3; ++i) {
      if (w[i] != 0 && std::abs(w[i]) < tiny) ++crumbs;
      for (int j = 0; j < 3; ++j)
        if (basis[i][j] != 0 && std::abs(basis[i][j]) < tiny) ++crumbs;
    }
  }
  EXPECT_EQ(crumbs, 0);
}

// The work-saving rules (settled patches skipped, Pi refreshed only when the
// centre of pressure moves by 1e-6 of the diameter) change the result by no
// more than that: a sliding, spinning coin run with both rules off stops at
// the same time and place. Bound: the refresh rule leaves Pi ~1e-6 relative

}  // namespace
}  // namespace patchspin::bullet
