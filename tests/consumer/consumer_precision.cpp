// A patchspin::bullet user compiles with the Bullet build's precision:
// BT_USE_DOUBLE_PRECISION reaches it from the double package, never from the
// float one, and the program links against the matching Bullet libraries.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include <btBulletDynamicsCommon.h>

#include <cstdio>

static_assert(sizeof(btScalar) == CONSUMER_EXPECTED_SCALAR_BYTES,
              "btScalar does not have the precision of the Bullet build patchspin was built with");

int main() {
  // a sphere falling for one step: calls into the linked Bullet libraries
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  patchspin::bullet::PatchFrictionSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, btScalar(-10)));
  btSphereShape shape(btScalar(0.1));
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(1), nullptr, &shape, btVector3(1, 1, 1));
  btRigidBody body(info);
  world.addRigidBody(&body);
  world.stepSimulation(btScalar(0.01), 0);
  world.removeRigidBody(&body);
  // one fixed step of 10 ms under gravity 10: v_z = -0.1 (semi-implicit Euler)
  const btScalar vz = body.getLinearVelocity().z();
  std::printf("btScalar: %zu bytes, v_z after one step: %.9f\n", sizeof(btScalar), double(vz));
  return vz < btScalar(-0.0999) && vz > btScalar(-0.1001) ? 0 : 1;
}
