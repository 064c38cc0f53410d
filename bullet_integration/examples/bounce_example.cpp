// A box dropped flat on the floor with restitution, its contact force read
// the Bullet way: from the manifold points' applied impulses, which a patch
// contact fills like any other contact. Prints the force while it bounces and
// settles; exits 0 if it bounced, landed flat and ends carrying its weight.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>

int main() {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  patchspin::bullet::PatchFrictionSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  const btScalar g = btScalar(9.81), dt = btScalar(1.0 / 240.0);
  world.setGravity(btVector3(0, 0, -g));

  btStaticPlaneShape groundShape(btVector3(0, 0, 1), 0);
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  ground.setRestitution(1);  // Bullet multiplies the two restitutions
  world.addRigidBody(&ground);

  // box: 10 cm cube, 1 kg, dropped flat from 10 cm, restitution 0.6
  const btScalar mass = 1;
  btBoxShape boxShape(btVector3(btScalar(0.05), btScalar(0.05), btScalar(0.05)));
  btVector3 inertia;
  boxShape.calculateLocalInertia(mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &boxShape, inertia);
  info.m_startWorldTransform.setOrigin(btVector3(0, 0, btScalar(0.15)));
  info.m_restitution = btScalar(0.6);
  btRigidBody box(info);
  world.addRigidBody(&box);
  solver.enablePatchFriction(&box, {patchspin::Model::Exact});

  bool bounced = false, touched = false;
  double maxTilt = 0, force = 0;
  for (int step = 1; step <= 480; ++step) {
    world.stepSimulation(dt, 0);
    // the contact force on the box from its manifolds' points [N]
    force = 0;
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
      const btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
      for (int k = 0; k < m->getNumContacts(); ++k)
        force += double(m->getContactPoint(k).getAppliedImpulse()) / double(dt);
    }
    touched = touched || force > 0;
    bounced = bounced || (touched && box.getLinearVelocity().z() > btScalar(0.5));
    const btMatrix3x3& basis =
        box.getWorldTransform().getBasis();  // tilt: sin of the z axis' angle
    maxTilt = std::fmax(maxTilt, std::hypot(double(basis[0][2]), double(basis[1][2])));
    if (step % 12 == 0 || force > 100)
      std::printf("t = %.3f s  z = %.4f m  vz = %+.3f m/s  contact force = %8.2f N\n",
                  step * double(dt), double(box.getCenterOfMassPosition().z()) - 0.05,
                  double(box.getLinearVelocity().z()), force);
  }
  world.removeRigidBody(&box);
  world.removeRigidBody(&ground);
  // at rest the points carry the weight (m g = 9.81 N) to the solver's precision
  const bool carries = std::fabs(force - double(mass * g)) < 1e-3 * double(mass * g);
  std::printf("bounced: %s, largest tilt %.2g rad, final force %.4f N\n", bounced ? "yes" : "no",
              maxTilt, force);
  return bounced && maxTilt < 1e-6 && carries ? 0 : 1;
}
