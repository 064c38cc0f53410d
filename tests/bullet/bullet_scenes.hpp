// Shared by the PatchFrictionSolver tests in Bullet worlds (tests/bullet):
// the coin on the ground plane and the tables it is set down on,
// built on the scene library (scenes/). Each scene is also run with stock
// Bullet (no body opted in) where its figure is printed beside ours.
#pragma once

#include <cmath>
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

namespace patchspin::bullet {

using scenes::Scene;

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

// The coin of the issue: R = 5 cm, H = 1 cm, 1 kg, mu = 0.3 (ground friction
// 1, so Bullet's combined friction is the body's).
constexpr double kR = 0.05, kH = 0.01, kMass = 1.0, kMu = 0.3;

struct Coin {
  Scene scene;
  btRigidBody* body;
  explicit Coin(bool patch, Model model = Model::Ellipsoidal) : scene(kG) {
    scene.addGroundPlane(1.0);
    body = scene.addCylinder(kR, kH, kMass, btVector3(0, 0, btScalar(kH / 2)), kMu);
    if (patch) scene.solver().enablePatchFriction(body, {model});
  }
  double tiltRate() const {
    const btVector3 w = body->getAngularVelocity();
    return std::hypot(double(w.x()), double(w.y()));
  }
};

// A static box whose top face is the plane z = 0, half halfLength x 0.2 x
// 0.05 m, friction 1: with the default 1 m, a face longer than wide, on
// which float Bullet's narrowphase misses a coin lying flat
// (CoinHasItsPatchWhereBulletMissesTheContact).
constexpr float kTableHalfZ = 0.05f;
inline btRigidBody* addTable(Scene& scene, double halfLength = 1.0) {
  return scene.addStaticBox(btVector3(btScalar(halfLength), 0.2f, kTableHalfZ),
                            btVector3(0, 0, -kTableHalfZ), 1.0);
}
// A static round table, a cylinder of radius 0.5 m whose top cap is the
// plane z = 0, friction 1: float Bullet's narrowphase misses a coin lying
// flat on a cylinder's cap of radius 0.2 m and more as it does on the long
// box (reproduced with plain Bullet: no contact until the coin is 2.25 mm
// in).
inline btRigidBody* addRoundTable(Scene& scene) {
  return scene.addCylinder(0.5, 2 * kTableHalfZ, 0.0, btVector3(0, 0, -kTableHalfZ), 1.0);
}
// The coin set down on the plane z = top, kSetDownDepth into it: Bullet
// finds no contact between faces that exactly touch.
constexpr double kSetDownDepth = 1e-5;
inline btRigidBody* addSetDownCoin(Scene& scene, double top = 0.0) {
  return scene.addCylinder(kR, kH, kMass, btVector3(0, 0, btScalar(top + kH / 2 - kSetDownDepth)),
                           kMu);
}

// A body held by friction moves by no more than this [m] (no creep; the
// friction block sticks, s = 0 for all six patch DOFs). Double: 1e-6 m over
// 10 s (the bound). Float: each step leaves a velocity of round-off
// size, ~eps_f * g dt = 6e-8 * 0.04 = 2.5e-9 m/s, i.e. 1e-11 m per step and
// 2.4e-8 m over 2400 steps if it always had the same sign; the bound 1e-5 m
// leaves a factor 400 for the solver's float arithmetic.
constexpr double kCreepBound = kDouble ? 1e-6 : 1e-5;

// Two blocks on the ground plane (friction 1): `upper` standing on `lower`,
// half extents [m], masses [kg], friction 0.5, both under the ellipsoidal
// law; added ground, lower, upper (the order of Bullet's manifolds).
struct BlockOnBlock {
  btRigidBody* lower;
  btRigidBody* upper;
};
inline BlockOnBlock addBlockOnBlock(Scene& scene, const btVector3& lowerHalf, double lowerMass,
                                    const btVector3& upperHalf, double upperMass,
                                    const btVector3& upperCentre) {
  scene.addGroundPlane(1.0);
  BlockOnBlock p;
  p.lower = scene.addBox(lowerHalf, lowerMass, btVector3(0, 0, lowerHalf.z()), 0.5);
  p.upper = scene.addBox(upperHalf, upperMass, upperCentre, 0.5);
  scene.solver().enablePatchFriction(p.lower, {Model::Ellipsoidal});
  scene.solver().enablePatchFriction(p.upper, {Model::Ellipsoidal});
  return p;
}

// Resting and sliding coins keep their tilt rates below 1e-3 rad/s (issue
// bound).
constexpr double kTiltBound = 1e-3;

}  // namespace patchspin::bullet
