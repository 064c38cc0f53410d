// World step time with N coins sliding and spinning on a plane (same scene,
// same 10 solver iterations): patch friction (ellipsoidal, exact), stock
// Bullet (btSequentialImpulseConstraintSolver), and PatchFrictionSolver with
// no opted-in body (must cost what stock costs). Ratios are in
// bullet_integration/README.md.
#include <patchspin/bullet/patch_friction_solver.hpp>

#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace {

using patchspin::Model;
using patchspin::bullet::PatchFrictionSolver;

enum Variant { kEllipsoidal = 0, kExact = 1, kStock = 2, kNoneOptedIn = 3 };

constexpr double kDt = 1.0 / 240.0;
constexpr double kR = 0.05, kH = 0.01;

struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  btStaticPlaneShape groundShape{btVector3(0, 0, 1), 0};
  btCylinderShapeZ coinShape{btVector3(btScalar(kR), btScalar(kR), btScalar(kH / 2))};
  std::unique_ptr<btRigidBody> ground;
  std::vector<std::unique_ptr<btRigidBody>> coins;
  std::vector<btVector3> v0, w0;
  std::vector<btTransform> start;

  World(int n, Variant variant) {
    if (variant == kStock)
      solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    else
      solver = std::make_unique<PatchFrictionSolver>();
    world = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, solver.get(), &config);
    world->setGravity(btVector3(0, 0, btScalar(-9.81)));
    coinShape.setMargin(btScalar(1e-3));
    ground = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
    world->addRigidBody(ground.get());
    // coins on a grid 0.5 m apart, seeded random slide and spin
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int side = int(std::ceil(std::sqrt(double(n))));
    const btScalar jx = btScalar((3 * kR * kR + kH * kH) / 12), jz = btScalar(kR * kR / 2);
    for (int i = 0; i < n; ++i) {
      btTransform tr;
      tr.setIdentity();
      tr.setOrigin(btVector3(btScalar(0.5 * (i % side)), btScalar(0.5 * (i / side)), btScalar(kH / 2)));
      btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &coinShape, btVector3(jx, jx, jz));
      info.m_startWorldTransform = tr;
      info.m_friction = btScalar(0.3);
      auto coin = std::make_unique<btRigidBody>(info);
      coin->setActivationState(DISABLE_DEACTIVATION);
      world->addRigidBody(coin.get());
      start.push_back(tr);
      v0.emplace_back(btScalar(0.3 * u(rng)), btScalar(0.3 * u(rng)), 0);
      w0.emplace_back(0, 0, btScalar(10 * u(rng)));
      if (variant == kEllipsoidal || variant == kExact)
        static_cast<PatchFrictionSolver*>(solver.get())
            ->enablePatchFriction(coin.get(), {variant == kExact ? Model::Exact : Model::Ellipsoidal});
      coins.push_back(std::move(coin));
    }
    reset();
  }
  ~World() {
    for (auto& c : coins) world->removeRigidBody(c.get());
    world->removeRigidBody(ground.get());
  }
  // the coins stop after ~0.2 s: restart them from their initial state
  // (place, orientation, velocities) so that every step of the benchmark is
  // the same scene of coins sliding and spinning apart
  void reset() {
    for (size_t i = 0; i < coins.size(); ++i) {
      coins[i]->setWorldTransform(start[i]);
      coins[i]->setInterpolationWorldTransform(start[i]);
      coins[i]->setLinearVelocity(v0[i]);
      coins[i]->setAngularVelocity(w0[i]);
    }
  }
};

void BM_BulletWorldStep(benchmark::State& state) {
  const int n = int(state.range(0));
  const Variant variant = Variant(state.range(1));
  World w(n, variant);
  long k = 0;
  for (auto _ : state) {
    if (++k % 24 == 0) w.reset();
    w.world->stepSimulation(btScalar(kDt), 0);
  }
  state.counters["bodies"] = n;
  state.SetLabel(variant == kEllipsoidal ? "patch ellipsoidal"
                 : variant == kExact     ? "patch exact"
                 : variant == kStock     ? "stock Bullet"
                                         : "PatchFrictionSolver, none opted in");
}
BENCHMARK(BM_BulletWorldStep)
    ->ArgsProduct({{10, 100, 1000}, {kStock, kNoneOptedIn, kEllipsoidal, kExact}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
