// A robot's flat foot in btMultiBodyDynamicsWorld: a leg (a floating-base
// shin with a box foot as its link) stands on the floor and is twisted about
// the vertical with 0.8 of the largest torque the foot's friction holds.
// With the exact patch law the foot holds; exits 0 if it turned less than
// 1e-4 rad in 2 s.
#include <patchspin/bullet/patch_multibody_solver.hpp>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

int main() {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  patchspin::bullet::PatchMultiBodySolver solver;  // instead of btMultiBodyConstraintSolver
  btMultiBodyDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, btScalar(-9.81)));

  btStaticPlaneShape groundShape(btVector3(0, 0, 1), 0);
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  ground.setFriction(1);  // Bullet multiplies the two frictions
  world.addRigidBody(&ground);

  // the leg: shin 2 kg (6 x 6 x 20 cm) as the floating base, the foot
  // 1 kg (16 x 8 x 2 cm) as link 0, fixed under it
  const btVector3 footHalf(btScalar(0.08), btScalar(0.04), btScalar(0.01));
  const btScalar footMass = 1, shinMass = 2, rise = btScalar(0.11);
  btBoxShape footShape(footHalf),
      shinShape(btVector3(btScalar(0.03), btScalar(0.03), btScalar(0.1)));
  footShape.setMargin(btScalar(0.001));
  btVector3 footInertia, shinInertia;
  footShape.calculateLocalInertia(footMass, footInertia);
  shinShape.calculateLocalInertia(shinMass, shinInertia);
  btMultiBody leg(1, shinMass, shinInertia, false, false);
  leg.setBasePos(btVector3(0, 0, btScalar(0.01) + rise));
  leg.setupFixed(0, footMass, footInertia, -1, btQuaternion::getIdentity(), btVector3(0, 0, -rise),
                 btVector3(0, 0, 0));
  leg.finalizeMultiDof();
  world.addMultiBody(&leg);
  btMultiBodyLinkCollider foot(&leg, 0);
  foot.setCollisionShape(&footShape);
  foot.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, btScalar(0.01))));
  foot.setFriction(btScalar(0.6));
  world.addCollisionObject(&foot, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
  leg.getLink(0).m_collider = &foot;

  // opt in every link with a collider (a URDF model's too), exact law
  for (int i = 0; i < leg.getNumLinks(); ++i)
    if (btMultiBodyLinkCollider* c = leg.getLink(i).m_collider)
      solver.enablePatchFriction(c, {patchspin::Model::Exact});

  // the largest yaw torque a 16 x 8 cm sole under uniform pressure holds:
  // mu M g times the sole's mean distance from its centre (5.58 cm)
  const double a = 0.08, b = 0.04, d = std::hypot(a, b);
  const double dbar =
      (d + a * a / (2 * b) * std::log((b + d) / a) + b * b / (2 * a) * std::log((a + d) / b)) / 3;
  const double limit = 0.6 * 3.0 * 9.81 * dbar;
  const btQuaternion q0 = leg.getWorldToBaseRot();
  for (int step = 1; step <= 480; ++step) {
    leg.addLinkTorque(0, btVector3(0, 0, btScalar(0.8 * limit)));
    world.stepSimulation(btScalar(1.0 / 240.0), 0);
  }
  const btQuaternion q = leg.getWorldToBaseRot() * q0.inverse();
  // the turn's angle, from its vector part
  const double v = std::sqrt(double(q.x() * q.x() + q.y() * q.y() + q.z() * q.z()));
  const double turn = 2 * std::asin(std::min(1.0, v));
  const patchspin::bullet::PatchReport* patch = solver.findPatchReport(&foot);
  std::printf(
      "yaw torque %.3f N m (limit %.3f): foot turned %.2e rad in 2 s, patch %s, Pz %.2f N\n",
      0.8 * limit, limit, turn, patch ? "yes" : "no", patch ? patch->loads.Pz : 0.0);
  world.removeCollisionObject(&foot);
  world.removeMultiBody(&leg);
  world.removeRigidBody(&ground);
  return patch && turn < 1e-4 ? 0 : 1;
}
