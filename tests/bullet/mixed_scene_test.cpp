// A mixed scene (patch coins and boxes, plain spheres, a stack) stays sane.
// Moved from patch_friction_solver_test.cpp.
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

// ---- mixed scene ---------------------------------------------------------------------
// Patch coins and boxes, ordinary spheres and a stack of three opted-in
// blocks, 3 s: nothing explodes (finite, speeds below the largest initial
// speed), nothing sinks into the ground by more than 2 mm (Bullet's own
// contacts allow ~1 mm of penetration with its default erp), the stack
// stands (top block within 1 mm of where it started) and comes to rest.
TEST(PatchFrictionSolver, MixedSceneStaysSane) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  struct Item {
    btRigidBody* body;
    double halfHeight;
  };
  std::vector<Item> items;
  for (int i = 0; i < 3; ++i) {
    btRigidBody* c = scene.addCylinder(
        kR, kH, kMass, btVector3(btScalar(-0.5 + 0.2 * i), 0.4f, btScalar(kH / 2)), kMu);
    c->setLinearVelocity(btVector3(0.5f, btScalar(-0.3 * i), 0));
    c->setAngularVelocity(btVector3(0, 0, btScalar(10.0 * (i + 1))));
    scene.solver().enablePatchFriction(c, {i == 1 ? Model::Exact : Model::Ellipsoidal});
    items.push_back({c, kH / 2});
  }
  for (int i = 0; i < 2; ++i) {
    btRigidBody* b = scene.addBox(btVector3(0.05f, 0.04f, 0.03f), 0.5,
                                  btVector3(btScalar(0.3 + 0.2 * i), -0.4f, 0.03f), 0.4);
    b->setLinearVelocity(btVector3(-0.8f, 0.2f, 0));
    b->setAngularVelocity(btVector3(0, 0, 5));
    scene.solver().enablePatchFriction(b, {Model::Exact});
    items.push_back({b, 0.03});
  }
  for (int i = 0; i < 3; ++i) {
    btRigidBody* s =
        scene.addSphere(0.04, 0.3, btVector3(btScalar(-0.3 + 0.3 * i), -0.1f, 0.04f), 0.5);
    s->setLinearVelocity(btVector3(0.3f, btScalar(0.5 - 0.2 * i), 0));
    items.push_back({s, 0.04});
  }
  std::vector<btRigidBody*> stack;
  for (int i = 0; i < 3; ++i) {
    btRigidBody* b = scene.addBox(btVector3(0.08f, 0.08f, 0.05f), 1.0,
                                  btVector3(0.8f, 0.8f, btScalar(0.05 + 0.1 * i)), 0.6);
    scene.solver().enablePatchFriction(b, {Model::Ellipsoidal});
    stack.push_back(b);
    items.push_back({b, 0.05 + 0.1 * i});
  }
  const btVector3 topStart = stack.back()->getWorldTransform().getOrigin();
  double vmax = 0;
  for (int k = 0; k < 720; ++k) {
    scene.step(kDt);
    for (const Item& it : items) {
      const btVector3 p = it.body->getWorldTransform().getOrigin();
      const double v = double(it.body->getLinearVelocity().length());
      ASSERT_TRUE(std::isfinite(double(p.x() + p.y() + p.z())) && std::isfinite(v)) << "step " << k;
      vmax = std::max(vmax, v);
      EXPECT_GT(double(p.z()), it.halfHeight - 2e-3) << "step " << k;
    }
  }
  EXPECT_LT(vmax, 1.0);
  const btVector3 top = stack.back()->getWorldTransform().getOrigin();
  std::printf("[mixed] max speed %.3f m/s, stack top moved %.3e m, %zu patches\n", vmax,
              double((top - topStart).length()), scene.solver().patchReports().size());
  EXPECT_LT(double((top - topStart).length()), 1e-3);
  for (btRigidBody* b : stack) EXPECT_LT(double(b->getLinearVelocity().length()), 1e-3);
}

}  // namespace
}  // namespace patchspin::bullet
