// Bullet's per-body rolling and spinning friction on an opted-in body
// (issue 31, item 4). The rule (docs/bullet.md): on a patch contact the
// patch law replaces Bullet's spinning friction (the law is the patch's
// resistance to spin) and its rolling friction (a flat face does not roll:
// the normal block holds its tilt); on every other contact of an opted-in
// body, and on bodies not opted in, Bullet's rolling and spinning friction
// act unchanged.
//
// Independent check: the same world without the setting (patch contacts) or
// with stock Bullet's solver (other contacts), bit for bit.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::Scene;
using scenes::SolverKind;

constexpr double kDt = 1.0 / 240.0;

struct Track {
  std::vector<btTransform> poses;
  std::vector<btVector3> w;
  long patchSteps = 0;
};

enum class Body { Coin, RimCoin, Sphere };

// One body launched on a plane with the given rolling and spinning friction;
// `optIn`: opted in to the exact law.
Track run(SolverKind kind, Body body, double rolling, double spinning, bool optIn) {
  Scene scene(9.81, 10, kind);
  scene.addGroundPlane(1.0);
  btRigidBody* b = nullptr;
  if (body == Body::Sphere) {
    b = scene.addSphere(0.05, 0.1, bt(0, 0, 0.05), 0.5);
    b->setLinearVelocity(bt(1.0, 0, 0));
    b->setAngularVelocity(bt(0, 20.0, 3.0));
  } else if (body == Body::Coin) {
    b = scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, 0.005), 0.5);
    b->setLinearVelocity(bt(0.3, 0, 0));
    b->setAngularVelocity(bt(0, 0, 15.0));
  } else {
    // a coin standing on its rim, rolling along x: no flat patch
    b = scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, 0.05), 0.5);
    b->setCenterOfMassTransform(
        btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(SIMD_HALF_PI)), bt(0, 0, 0.05)));
    b->setLinearVelocity(bt(1.0, 0, 0));
    b->setAngularVelocity(bt(0, 20.0, 0));
  }
  b->setRollingFriction(btScalar(rolling));
  b->setSpinningFriction(btScalar(spinning));
  if (optIn) scene.solver().enablePatchFriction(b, {Model::Exact});
  Track t;
  for (int i = 0; i < 120; ++i) {
    scene.step(kDt);
    t.poses.push_back(b->getWorldTransform());
    t.w.push_back(b->getAngularVelocity());
    if (kind == SolverKind::Patch && scene.solver().findPatchReport(b)) ++t.patchSteps;
  }
  return t;
}

void expectSame(const Track& a, const Track& b, const char* what) {
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    ASSERT_TRUE(a.poses[i].getOrigin() == b.poses[i].getOrigin()) << what << " step " << i;
    ASSERT_TRUE(a.poses[i].getBasis() == b.poses[i].getBasis()) << what << " step " << i;
    ASSERT_TRUE(a.w[i] == b.w[i]) << what << " step " << i;
  }
}

TEST(RollingSpinningFriction, ThePatchLawReplacesThemOnAPatch) {
  const Track plain = run(SolverKind::Patch, Body::Coin, 0.0, 0.0, true);
  const Track set = run(SolverKind::Patch, Body::Coin, 0.05, 0.05, true);
  EXPECT_EQ(plain.patchSteps, 120);
  expectSame(plain, set, "coin on its face");
  // while stock Bullet's spinning friction does act on the same coin
  const Track stockPlain = run(SolverKind::Stock, Body::Coin, 0.0, 0.0, false);
  const Track stockSet = run(SolverKind::Stock, Body::Coin, 0.05, 0.05, false);
  EXPECT_NE(stockPlain.w.back().z(), stockSet.w.back().z());
}

TEST(RollingSpinningFriction, BulletsActUnchangedOffPatches) {
  for (const Body body : {Body::Sphere, Body::RimCoin}) {
    const char* what = body == Body::Sphere ? "sphere" : "coin on its rim";
    const Track stock = run(SolverKind::Stock, body, 0.02, 0.02, false);
    const Track optedIn = run(SolverKind::Patch, body, 0.02, 0.02, true);
    EXPECT_EQ(optedIn.patchSteps, 0) << what;
    expectSame(stock, optedIn, what);
    // and the setting does act there
    const Track without = run(SolverKind::Stock, body, 0.0, 0.0, false);
    EXPECT_FALSE(without.w.back() == stock.w.back()) << what;
  }
}

}  // namespace
}  // namespace patchspin::bullet
