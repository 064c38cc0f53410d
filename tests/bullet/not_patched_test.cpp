// Nothing silent (issue 31, item 7): every contact of an opted-in body that
// does not become a patch is counted by reason, in stats() and per body
// (notPatchedOf), and a shape pair that can never make a patch is told once
// to the unsupported-shape callback.
//
// Independent check: scenes whose contact is known by construction (a
// sphere, a coin on its rim, a box landing on its edge, a coin on its face,
// a box on a nested compound).
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <utility>
#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::Scene;

constexpr double kDt = 1.0 / 240.0;

TEST(NotPatched, ASphereIsAnUnsupportedShapeToldOnce) {
  Scene scene;
  btRigidBody* ground = scene.addGroundPlane(1.0);
  btRigidBody* ball = scene.addSphere(0.05, 0.1, bt(0, 0, 0.0499), 0.5);
  btRigidBody* ball2 = scene.addSphere(0.05, 0.1, bt(0.3, 0, 0.0499), 0.5);
  std::vector<std::pair<const btCollisionObject*, const btCollisionObject*>> told;
  scene.solver().setUnsupportedShapeCallback(
      [&](const btCollisionObject* body, const btCollisionObject* other) {
        told.emplace_back(body, other);
      });
  scene.solver().enablePatchFriction(ball, {Model::Exact});
  scene.solver().enablePatchFriction(ball2, {Model::Exact});
  for (int i = 0; i < 30; ++i) {
    scene.step(kDt);
    EXPECT_EQ(scene.solver().stats().notPatched.unsupportedShape, 2) << "step " << i;
    EXPECT_EQ(scene.solver().stats().notPatched.total(), 2) << "step " << i;
    const NotPatchedCounts* c = scene.solver().notPatchedOf(ball);
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->unsupportedShape, 1);
  }
  // one pair of shape types (sphere on plane): told once, with the first ball
  ASSERT_EQ(told.size(), 1u);
  EXPECT_TRUE(told[0].first == ball || told[0].first == ball2);
  EXPECT_EQ(told[0].second, ground);
}

TEST(NotPatched, ACoinOnItsRimIsASideContact) {
  Scene scene;
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, 0.0499), 0.5);
  coin->setCenterOfMassTransform(
      btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(SIMD_HALF_PI)), bt(0, 0, 0.0499)));
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  scene.step(kDt);
  const NotPatchedCounts* c = scene.solver().notPatchedOf(coin);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->sideContact, 1);
  EXPECT_EQ(c->total(), 1);
  EXPECT_EQ(scene.solver().findPatchReport(coin), nullptr);
}

TEST(NotPatched, ABoxOnItsEdgeIsNotFlat) {
  Scene scene;
  scene.addGroundPlane(1.0);
  // tilted 0.3 rad about x: its lowest edge touches the plane
  const double tilt = 0.3, hy = 0.05, hz = 0.03;
  const double z = hy * std::sin(tilt) + hz * std::cos(tilt) - 1e-4;
  btRigidBody* box = scene.addBox(bt(0.05, hy, hz), 1.0, bt(0, 0, z), 0.5);
  box->setCenterOfMassTransform(
      btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(tilt)), bt(0, 0, z)));
  scene.solver().enablePatchFriction(box, {Model::Exact});
  scene.step(kDt);
  const NotPatchedCounts* c = scene.solver().notPatchedOf(box);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->notFlat, 1);
  EXPECT_EQ(scene.solver().stats().notPatched.total(), 1);
}

TEST(NotPatched, ACoinOnItsFaceLeavesNothing) {
  Scene scene;
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, 0.005), 0.5);
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  for (int i = 0; i < 10; ++i) {
    scene.step(kDt);
    EXPECT_EQ(scene.solver().notPatchedOf(coin), nullptr);
    EXPECT_EQ(scene.solver().stats().notPatched.total(), 0);
  }
  EXPECT_NE(scene.solver().findPatchReport(coin), nullptr);
}

// A box whose rotation is locked (setAngularFactor(0)): the patch's tilt and
// spin DOFs have no effective mass, so the contact stays Bullet's, counted.
TEST(NotPatched, ABoxWithItsRotationLockedHasSingularBlocks) {
  Scene scene;
  scene.addGroundPlane(1.0);
  btRigidBody* box = scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 0, 0.0499), 0.5);
  box->setAngularFactor(0);
  scene.solver().enablePatchFriction(box, {Model::Exact});
  scene.step(kDt);
  const NotPatchedCounts* c = scene.solver().notPatchedOf(box);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->singularBlocks, 1);
  EXPECT_EQ(c->total(), 1);
  EXPECT_EQ(scene.solver().findPatchReport(box), nullptr);
}

// A box on a static compound whose box child is in a compound of its own:
// Bullet tags a contact with the innermost child's index only, which does
// not say which branch it came from (compound_children.hpp), so the contact
// is an unsupported shape (a box on a plain compound's box child makes a
// patch: CompoundShapes.*).
TEST(NotPatched, ABoxOnANestedCompoundIsAnUnsupportedShape) {
  Scene scene;
  auto top = std::make_unique<btCompoundShape>();
  auto inner = std::make_unique<btCompoundShape>();
  btCollisionShape* child = scene.addShape(std::make_unique<btBoxShape>(bt(0.5, 0.5, 0.05)));
  inner->addChildShape(btTransform::getIdentity(), child);
  top->addChildShape(btTransform::getIdentity(), scene.addShape(std::move(inner)));
  btTransform at = btTransform::getIdentity();
  at.setOrigin(bt(0, 0, -0.05));
  btRigidBody* table = scene.addBody(std::move(top), 0.0, btVector3(0, 0, 0), at, 1.0);
  btRigidBody* box = scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 0, 0.0499), 0.5);
  int told = 0;
  scene.solver().setUnsupportedShapeCallback(
      [&](const btCollisionObject* body, const btCollisionObject* other) {
        ++told;
        EXPECT_EQ(body, box);
        EXPECT_EQ(other, table);
      });
  scene.solver().enablePatchFriction(box, {Model::Exact});
  for (int i = 0; i < 5; ++i) scene.step(kDt);
  const NotPatchedCounts* c = scene.solver().notPatchedOf(box);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->unsupportedShape, 1);
  EXPECT_EQ(told, 1);
}

}  // namespace
}  // namespace patchspin::bullet
