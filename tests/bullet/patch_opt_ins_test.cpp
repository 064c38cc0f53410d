// Body lifetime of an opt-in (patch_opt_ins.hpp, PatchFrictionSolver's
// "Lifetime"): the opt-in is kept in the body, so it ends with the body. A
// new body never inherits a deleted one's options, whatever address it gets
// (issue 31: in a spawn/despawn loop 496 of 500 new bodies that were never
// opted in got patch friction with an old body's mu), in every order of
// remove / delete / re-add / re-enable; removing a body and adding it back
// keeps its options; the solver's copy of the options does not grow with
// the bodies. Run under ASan (the asan preset), a solver that read a
// deleted body would fail here as a heap-use-after-free. The same for a
// multibody's link collider (LinkColliderLifetime.*), whose opt-in is kept
// in its extension pointer.
#include "bullet_scenes.hpp"

#include <patchspin/bullet/patch_multibody_solver.hpp>
#include <patchspin/scenes/multibody_scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <new>
#include <optional>
#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::bt;

// A 10 cm cube of 1 kg resting on the ground plane (1e-4 m in, so that
// Bullet has its contact in the first step), its own box shape.
const btVector3 kHalf = bt(0.05, 0.05, 0.05);
const btVector3 kCubeInertia = bt(1.0 / 6 * 0.01, 1.0 / 6 * 0.01, 1.0 / 6 * 0.01);

btRigidBody::btRigidBodyConstructionInfo cubeInfo(btCollisionShape* shape, double x) {
  btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, shape, kCubeInertia);
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(bt(x, 0, 0.05 - 1e-4));
  info.m_friction = 0.5;
  return info;
}

// Storage for a body built with placement new: the next body built there has
// the deleted one's address, as an allocator may give it.
struct BodySlot {
  alignas(btRigidBody) unsigned char bytes[sizeof(btRigidBody)];
  btRigidBody* make(const btRigidBody::btRigidBodyConstructionInfo& info) {
    auto* b = new (bytes) btRigidBody(info);
    b->setActivationState(DISABLE_DEACTIVATION);
    return b;
  }
};

struct World {
  Scene scene{kG, 10};
  btBoxShape shape{kHalf};
  World() {
    scene.addGroundPlane(1.0);
    shape.setMargin(btScalar(1e-3));
  }
  PatchFrictionSolver& solver() { return scene.solver(); }
  // the body's patch report after one step, by value
  std::optional<PatchReport> stepAndReport(const btRigidBody* b) {
    scene.step(kDt);
    return solver().patchReportOf(b);
  }
};

// Removed, then deleted (with or without disablePatchFriction first), and a
// new body built at the same address and added: it is not opted in, gets no
// patch, and once enabled has its own options, not the old ones.
TEST(BodyLifetime, NewBodyAtADeletedBodysAddressIsNotOptedIn) {
  for (const bool disableFirst : {false, true}) {
    World w;
    BodySlot slot;
    btRigidBody* first = slot.make(cubeInfo(&w.shape, 0));
    w.scene.world().addRigidBody(first);
    w.solver().enablePatchFriction(first, {Model::Exact, 0.9});
    ASSERT_TRUE(w.stepAndReport(first)) << "the cube stands on a patch";
    w.scene.world().removeRigidBody(first);
    if (disableFirst) w.solver().disablePatchFriction(first);
    first->~btRigidBody();
    btRigidBody* second = slot.make(cubeInfo(&w.shape, 0));
    ASSERT_EQ(second, first);
    w.scene.world().addRigidBody(second);
    EXPECT_FALSE(w.solver().isPatchFrictionEnabled(second)) << disableFirst;
    for (int k = 0; k < 5; ++k)
      EXPECT_FALSE(w.stepAndReport(second)) << "never opted in; disable first " << disableFirst;
    EXPECT_EQ(w.solver().stats().patches, 0);
    w.solver().enablePatchFriction(second, {Model::Ellipsoidal, 0.2});
    const auto rep = w.stepAndReport(second);
    ASSERT_TRUE(rep);
    EXPECT_EQ(rep->model, Model::Ellipsoidal);
    EXPECT_EQ(rep->mu, 0.2);
    w.scene.world().removeRigidBody(second);
    second->~btRigidBody();
  }
}

// The same body removed and added again keeps its options, however long it
// was out; re-enabled while out, it comes back with the new ones; disabled
// while out, it comes back without.
TEST(BodyLifetime, RemovedAndReaddedBodyKeepsItsOptions) {
  World w;
  btRigidBody* box = w.scene.addBody(&w.shape, 1.0, kCubeInertia,
                                     cubeInfo(&w.shape, 0).m_startWorldTransform, 0.5);
  w.solver().enablePatchFriction(box, {Model::Exact, 0.35});
  ASSERT_TRUE(w.stepAndReport(box));
  // out for longer than the solver's memory of the manifold
  w.scene.world().removeRigidBody(box);
  for (int k = 0; k < 20; ++k) EXPECT_FALSE(w.stepAndReport(box));
  EXPECT_TRUE(w.solver().isPatchFrictionEnabled(box));
  w.scene.world().addRigidBody(box);
  auto rep = w.stepAndReport(box);
  ASSERT_TRUE(rep);
  EXPECT_EQ(rep->model, Model::Exact);
  EXPECT_EQ(rep->mu, 0.35);
  // re-enabled while out of the world
  w.scene.world().removeRigidBody(box);
  w.solver().enablePatchFriction(box, {Model::Ellipsoidal, 0.6});
  w.scene.world().addRigidBody(box);
  rep = w.stepAndReport(box);
  ASSERT_TRUE(rep);
  EXPECT_EQ(rep->model, Model::Ellipsoidal);
  EXPECT_EQ(rep->mu, 0.6);
  // disabled while out of the world
  w.scene.world().removeRigidBody(box);
  w.solver().disablePatchFriction(box);
  w.scene.world().addRigidBody(box);
  EXPECT_FALSE(w.stepAndReport(box));
  EXPECT_FALSE(w.solver().isPatchFrictionEnabled(box));
}

// Enabled before it is ever added to a world: opted in once it is added.
TEST(BodyLifetime, BodyEnabledBeforeItIsAddedIsOptedIn) {
  World w;
  BodySlot slot;
  btRigidBody* box = slot.make(cubeInfo(&w.shape, 0));
  w.solver().enablePatchFriction(box, {Model::Exact, 0.45});
  w.scene.world().addRigidBody(box);
  const auto rep = w.stepAndReport(box);
  ASSERT_TRUE(rep);
  EXPECT_EQ(rep->mu, 0.45);
  w.scene.world().removeRigidBody(box);
  box->~btRigidBody();
}

// A body opted in by one solver is not opted in for another (a body moved to
// a second world), and comes back to the first with its options.
TEST(BodyLifetime, OptInBelongsToTheSolverThatMadeIt) {
  World a, b;
  BodySlot slot;
  btRigidBody* box = slot.make(cubeInfo(&a.shape, 0));
  a.scene.world().addRigidBody(box);
  a.solver().enablePatchFriction(box, {Model::Exact, 0.7});
  ASSERT_TRUE(a.stepAndReport(box));
  a.scene.world().removeRigidBody(box);
  b.scene.world().addRigidBody(box);
  EXPECT_FALSE(b.solver().isPatchFrictionEnabled(box));
  EXPECT_FALSE(b.stepAndReport(box));
  b.solver().disablePatchFriction(box);  // not b's: left alone
  b.scene.world().removeRigidBody(box);
  a.scene.world().addRigidBody(box);
  const auto rep = a.stepAndReport(box);
  ASSERT_TRUE(rep);
  EXPECT_EQ(rep->mu, 0.7);
  a.scene.world().removeRigidBody(box);
  box->~btRigidBody();
}

// The loop of the finding: 500 bodies spawned, stepped and removed and
// deleted without disablePatchFriction; every other one opted in (mu 0.9),
// the others never. None of the never-opted-in bodies gets a patch, every
// opted-in one gets its own; stats().patches counts the opted-in ones only.
// The bodies come from the heap (an allocator reuses addresses: counted and
// printed; under ASan, whose quarantine does not, any read of a deleted
// body fails the run) and, in the second pass, from four slots in turn
// (every address reused 125 times). The opted-in bodies all share the
// solver's one copy of their options: the same code in their
// m_frictionSolverType.
TEST(BodyLifetime, SpawnDespawnLoopNeverGivesANewBodyAnOldOnesOptions) {
  constexpr int kSpawns = 500, kStepsEach = 3, kSlots = 4;
  for (const bool slots : {false, true}) {
    World w;
    std::vector<BodySlot> pool(kSlots);
    std::vector<const void*> seen;
    int reused = 0, inherited = 0, missing = 0;
    int code = 0;
    for (int i = 0; i < kSpawns; ++i) {
      const auto info = cubeInfo(&w.shape, 0);
      btRigidBody* body = slots ? pool[i % kSlots].make(info) : new btRigidBody(info);
      if (!slots) body->setActivationState(DISABLE_DEACTIVATION);
      reused += std::find(seen.begin(), seen.end(), body) != seen.end();
      seen.push_back(body);
      w.scene.world().addRigidBody(body);
      const bool optIn = i % 2 == 0;
      if (optIn) w.solver().enablePatchFriction(body, {Model::Exact, 0.9});
      for (int k = 0; k < kStepsEach; ++k) {
        const auto rep = w.stepAndReport(body);
        if (!optIn) {
          inherited += rep.has_value() || w.solver().stats().patches != 0;
        } else {
          missing += !rep || rep->mu != 0.9 || w.solver().stats().patches != 1;
        }
      }
      if (optIn) {
        if (code == 0) code = body->m_frictionSolverType;
        EXPECT_EQ(body->m_frictionSolverType, code) << "one copy of the options";
      } else {
        EXPECT_FALSE(w.solver().isPatchFrictionEnabled(body));
      }
      w.scene.world().removeRigidBody(body);  // no disablePatchFriction
      if (slots)
        body->~btRigidBody();
      else
        delete body;
    }
    std::printf(
        "[spawn/despawn %s] %d of %d bodies at a reused address; never opted in with a "
        "patch: %d; opted in without their own: %d\n",
        slots ? "slots" : "heap", reused, kSpawns, inherited, missing);
    if (slots) {
      EXPECT_EQ(reused, kSpawns - kSlots);
    }
    EXPECT_EQ(inherited, 0);
    EXPECT_EQ(missing, 0);
  }
}

// ---- link colliders (PatchMultiBodySolver) ---------------------------------
// A floating-base multibody cube (the same 10 cm, 1 kg) on the ground; its
// base collider is rebuilt in place, so that the new collider has the old
// one's address, as an allocator may give it.
struct LinkWorld {
  scenes::MultiBodyScene scene{kG, 10, true};
  btMultiBody* cube;
  LinkWorld() {
    scene.addGroundPlane(1.0);
    cube = scene.addBoxBase(kHalf, 1.0, bt(0, 0, 0.05 - 1e-4), 0.5, 1e-3);
  }
  PatchMultiBodySolver& solver() { return scene.solver(); }
  btMultiBodyLinkCollider* collider() { return cube->getBaseCollider(); }
  std::optional<PatchReport> stepAndReport() {
    scene.step(1.0 / 240);
    return solver().patchReportOf(collider());
  }
  // removes the base collider from the world, destroys it (with or without
  // disablePatchFriction first) and builds a new one at its address with the
  // same shape, pose and friction, added to the world as the base collider
  btMultiBodyLinkCollider* rebuildCollider(bool disableFirst) {
    btMultiBodyLinkCollider* old = collider();
    btCollisionShape* shape = old->getCollisionShape();
    const btTransform pose = old->getWorldTransform();
    const btScalar friction = old->getFriction();
    scene.world().removeCollisionObject(old);
    if (disableFirst) solver().disablePatchFriction(old);
    old->~btMultiBodyLinkCollider();
    auto* c = new (old) btMultiBodyLinkCollider(cube, -1);
    c->setCollisionShape(shape);
    c->setWorldTransform(pose);
    c->setFriction(friction);
    c->setActivationState(DISABLE_DEACTIVATION);
    scene.world().addCollisionObject(c, int(btBroadphaseProxy::DefaultFilter),
                                     int(btBroadphaseProxy::AllFilter));
    cube->setBaseCollider(c);
    return c;
  }
};

// Deleted (with or without disablePatchFriction first) and a new collider
// built at the same address: it is not opted in, gets no patch, and once
// enabled has its own options, not the old ones (an opt-in kept by the
// collider's address would pass to it).
TEST(LinkColliderLifetime, NewColliderAtADeletedCollidersAddressIsNotOptedIn) {
  for (const bool disableFirst : {false, true}) {
    LinkWorld w;
    btMultiBodyLinkCollider* first = w.collider();
    w.solver().enablePatchFriction(first, {Model::Exact, 0.9});
    const auto before = w.stepAndReport();
    ASSERT_TRUE(before) << "the cube stands on a patch";
    EXPECT_EQ(before->mu, 0.9);
    btMultiBodyLinkCollider* second = w.rebuildCollider(disableFirst);
    ASSERT_EQ(second, first);
    EXPECT_FALSE(w.solver().isPatchFrictionEnabled(second)) << disableFirst;
    for (int k = 0; k < 5; ++k)
      EXPECT_FALSE(w.stepAndReport()) << "never opted in; disable first " << disableFirst;
    EXPECT_EQ(w.solver().stats().patches, 0);
    w.solver().enablePatchFriction(second, {Model::Ellipsoidal, 0.2});
    const auto rep = w.stepAndReport();
    ASSERT_TRUE(rep);
    EXPECT_EQ(rep->model, Model::Ellipsoidal);
    EXPECT_EQ(rep->mu, 0.2);
  }
}

// The extension pointer is the user's when they set it: enable refuses the
// collider with an Error and leaves the pointer as it was; disable of a
// collider that is not opted in leaves it too. A collider opted in by one
// solver is not opted in for another.
TEST(LinkColliderLifetime, ExtensionPointerInUseIsRefusedAndKept) {
  LinkWorld w;
  btMultiBodyLinkCollider* c = w.collider();
  int userData = 0;
  c->internalSetExtensionPointer(&userData);
  EXPECT_THROW(w.solver().enablePatchFriction(c, {Model::Exact}), Error);
  EXPECT_EQ(c->internalGetExtensionPointer(), &userData);
  EXPECT_FALSE(w.solver().isPatchFrictionEnabled(c));
  w.solver().disablePatchFriction(c);
  EXPECT_EQ(c->internalGetExtensionPointer(), &userData);
  EXPECT_FALSE(w.stepAndReport());
  c->internalSetExtensionPointer(nullptr);
  w.solver().enablePatchFriction(c, {Model::Exact, 0.6});
  PatchMultiBodySolver other;
  EXPECT_FALSE(other.isPatchFrictionEnabled(c));
  other.disablePatchFriction(c);  // not other's: left alone
  EXPECT_TRUE(w.solver().isPatchFrictionEnabled(c));
  const auto rep = w.stepAndReport();
  ASSERT_TRUE(rep);
  EXPECT_EQ(rep->mu, 0.6);
  w.solver().disablePatchFriction(c);
  EXPECT_EQ(c->internalGetExtensionPointer(), nullptr);
  EXPECT_FALSE(w.stepAndReport());
}

}  // namespace
}  // namespace patchspin::bullet
