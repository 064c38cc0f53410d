// Patches on moving supports and under joints: a kinematic conveyor carries
// a coin along; a pinned spinning coin stops on time. Moved from patch_friction_solver_test.cpp.
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

// ---- kinematic support -----------------------------------------------------------
// A coin set down at rest on a kinematic conveyor belt (a box moved at vB
// along x, its velocity Bullet's from the transforms it is given) slips
// until friction has brought it to the belt's speed, then rides along:
// with Coulomb friction mu m g and no spin, v(t) = min(mu g t, vB), the
// slip ending at t* = vB / (mu g) = 0.17 s (closed form). Asserted for
// both laws: the coin stands on a patch against the belt in every step,
// its speed follows the closed form, and it neither tilts nor spins.
// kBeltSpeedTol: semi-implicit Euler integrates a constant acceleration
// exactly, so what is left is round-off, ~eps v per step, 120 steps: 4e-6
// m/s in float (measured 3.0e-6); the bound leaves a factor 25. The step
// whose interval holds t* is not compared (v(t) has its corner there).
// kBeltSpinTol: a flat coin sliding under uniform pressure feels no torque
// about any axis (measured 0 in float, 4e-30 rad/s in double).
// The belt is longer than wide (half 1 x 0.2 m), where float Bullet's
// narrowphase reports no contact for a coin set down on it until the coin
// is ~2.5 mm in (CoinHasItsPatchWhereBulletMissesTheContact): the patch is
// found from the faces (a kinematic box is probed as a static one is), and
// stock Bullet's coin, which sinks and tumbles, is 7e-2 m/s off and spins
// up to 6.4 rad/s (2.6 rad/s on a square belt).
TEST(PatchFrictionSolver, CoinOnAKinematicConveyorIsCarriedAlong) {
  constexpr double kBeltSpeed = 0.5;
  constexpr double kBeltSpeedTol = 1e-4, kBeltSpinTol = 1e-6;
  const double tStar = kBeltSpeed / (kMu * kG);
  const int steps = int(std::lround(0.5 / kDt));
  for (bool patch : {true, false})
    for (Model model : {Model::Ellipsoidal, Model::Exact}) {
      if (!patch && model == Model::Exact) continue;  // stock Bullet once
      Scene scene(kG);
      btRigidBody* belt = addTable(scene);
      scene.world().removeRigidBody(belt);
      belt->setCollisionFlags(belt->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      belt->setActivationState(DISABLE_DEACTIVATION);
      scene.world().addRigidBody(belt);
      btRigidBody* coin = addSetDownCoin(scene);
      if (patch) scene.solver().enablePatchFriction(coin, {model});
      double worstSpeed = 0.0, worstSpin = 0.0;
      int onPatch = 0;
      for (int k = 0; k < steps; ++k) {
        btTransform t = belt->getWorldTransform();
        t.setOrigin(btVector3(btScalar(kBeltSpeed * (k + 1) * kDt), 0, -kTableHalfZ));
        belt->setWorldTransform(t);
        scene.step(kDt);
        const double t0 = k * kDt, t1 = (k + 1) * kDt;
        if (!(t0 < tStar && tStar <= t1)) {
          const btVector3 v = coin->getLinearVelocity();
          const double expected = std::min(kMu * kG * t1, kBeltSpeed);
          worstSpeed = std::max(worstSpeed, std::hypot(double(v.x()) - expected, double(v.y())));
        }
        worstSpin = std::max(worstSpin, double(coin->getAngularVelocity().length()));
        const PatchReport* r = scene.solver().findPatchReport(coin);
        onPatch += r != nullptr && r->other == belt;
      }
      std::printf(
          "[conveyor] %s (%s): speed error %.2e m/s, spin %.2e rad/s, %d of %d steps on a patch\n",
          patch ? toString(model) : "stock", kDouble ? "double" : "float", worstSpeed, worstSpin,
          onPatch, steps);
      if (!patch) continue;
      EXPECT_EQ(onPatch, steps) << toString(model);
      EXPECT_LT(worstSpeed, kBeltSpeedTol) << toString(model);
      EXPECT_LT(worstSpin, kBeltSpinTol) << toString(model);
    }
}

// ---- joints ------------------------------------------------------------------------
// A coin held at its centre by a btGeneric6DofConstraint that locks only the
// horizontal translation (vertical and all rotations free: the ground alone
// carries the weight), pushed sideways by 2 mu m g: the joint carries the
// push, the patch sees pure spin. Uniform pressure on a centred disk: spin
// torque mu m g 2R/3, so with J_z = m R^2 / 2 it stops at
// t = 3 R omega0 / (4 mu g). The joint acts on velocities and restores its
// position error with ERP the next step, so its error is about one step's
// motion under the push, |F| dt^2 / m = 1.0e-4 m, and must not accumulate
// (free, the coin would travel metres): kPinDriftTol = twice that.
const double kPinDriftTol = 2.0 * (2 * kMu * kMass * kG) * kDt * kDt / kMass;

TEST(PatchFrictionSolver, PinnedSpinningCoinStopsOnTimeWithJointHoldingThePush) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(kR, kH, kMass, btVector3(0, 0, btScalar(kH / 2)), kMu);
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  btTransform frame;
  frame.setIdentity();
  btGeneric6DofConstraint pin(*coin, frame, true);
  pin.setLinearLowerLimit(btVector3(0, 0, 1));  // lower > upper: free (z only)
  pin.setLinearUpperLimit(btVector3(0, 0, 0));
  pin.setAngularLowerLimit(btVector3(1, 1, 1));
  pin.setAngularUpperLimit(btVector3(0, 0, 0));
  scene.world().addConstraint(&pin);
  const double omega0 = 30.0;
  coin->setAngularVelocity(btVector3(0, 0, btScalar(omega0)));
  const double tPredicted = 3.0 * kR * omega0 / (4.0 * kMu * kG);
  double t = 0, drift = 0;
  for (bool stuck = false; t < 2 * tPredicted && !stuck;) {
    coin->applyCentralForce(btVector3(btScalar(2 * kMu * kMass * kG), 0, 0));
    scene.step(kDt);
    t += kDt;
    const PatchReport* rep = scene.solver().findPatchReport(coin);
    stuck = rep && rep->sticking;
    const btVector3 p = coin->getWorldTransform().getOrigin();
    drift = std::max(drift, std::hypot(double(p.x()), double(p.y())));
  }
  std::printf("[joint] pinned coin stopped after %.4f s (predicted %.4f s), pivot drift %.2e m\n",
              t, tPredicted, drift);
  EXPECT_NEAR(t, tPredicted, 0.01 * tPredicted + kDt);
  EXPECT_LT(drift, kPinDriftTol);
  scene.world().removeConstraint(&pin);
}

}  // namespace
}  // namespace patchspin::bullet
