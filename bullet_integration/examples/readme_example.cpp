// A coin sliding and spinning on the floor with the exact patch friction law.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include <btBulletDynamicsCommon.h>

#include <cstdio>

int main() {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  patchspin::bullet::PatchFrictionSolver solver;  // drop-in for btSequentialImpulseConstraintSolver
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, btScalar(-9.81)));

  btStaticPlaneShape groundShape(btVector3(0, 0, 1), 0);
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
  world.addRigidBody(&ground);

  // coin: R = 5 cm, H = 1 cm, 20 g; a collision margin below its thickness
  btCylinderShapeZ coinShape(btVector3(btScalar(0.05), btScalar(0.05), btScalar(0.005)));
  coinShape.setMargin(btScalar(0.001));
  btVector3 inertia;
  coinShape.calculateLocalInertia(btScalar(0.02), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(0.02), nullptr, &coinShape, inertia);
  info.m_startWorldTransform.setOrigin(btVector3(0, 0, btScalar(0.005)));
  info.m_friction = btScalar(0.3);
  btRigidBody coin(info);
  coin.setLinearVelocity(btVector3(btScalar(0.5), 0, 0));
  coin.setAngularVelocity(btVector3(0, 0, 20));
  world.addRigidBody(&coin);

  solver.enablePatchFriction(&coin, {patchspin::Model::Exact});

  bool stopped = false;
  for (int step = 1; step <= 240 && !stopped; ++step) {
    world.stepSimulation(btScalar(1.0 / 240.0), 0);
    if (const patchspin::bullet::PatchReport* patch = solver.findPatchReport(&coin)) {
      std::printf("t = %.4f s  Pz = %.4f N  r = %.4f m/s  w = (%+.3f %+.3f %+.3f)  %s\n",
                  step / 240.0, patch->loads.Pz, patch->r, patch->w.x(), patch->w.y(), patch->w.z(),
                  patch->sticking ? "stick" : "slip");
      stopped = patch->sticking;
    }
  }
  world.removeRigidBody(&coin);
  world.removeRigidBody(&ground);
  return stopped ? 0 : 1;  // the coin comes to rest within a second
}
