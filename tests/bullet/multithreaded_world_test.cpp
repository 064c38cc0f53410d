// The multithreaded world (issue 31, item 5): btDiscreteDynamicsWorldMt
// with a PatchSolverPoolMt moves the bodies as btDiscreteDynamicsWorld with
// a PatchFrictionSolver does, bit for bit with the same reports and stats
// every step where Bullet hands each island's manifolds over in the same
// order; stats are reset every step; opt-ins go through the pool.
//
// The order: btDiscreteDynamicsWorld quickSorts the manifolds by island (not
// stably), btDiscreteDynamicsWorldMt keeps the dispatcher's order within an
// island. Where an island has several manifolds in another order (a stack,
// a pile), its Gauss-Seidel sweep visits its rows in another order and the
// worlds part by the solver's convergence error, not round-off. The tests
// that pin bit-identity give the pool each island in the single-threaded
// order (orderAsSingleThreaded); those in Bullet's own order state what
// holds there.
//
// Debian's Bullet 3.24 is built without BT_THREADSAFE: its task schedulers
// other than the sequential one are null, its btSpinMutex never locks, and
// btConstraintSolverPoolMt hands every island to its first solver. The
// world is stepped here with the sequential scheduler; two threads:
// multithreaded_world_two_threads_test.cpp.
#include "world_twins.hpp"

namespace patchspin::bullet {
namespace {

using namespace twins;
using scenes::Friction;
using scenes::Scene;
using scenes::SolverKind;

// Each island's manifolds handed to the pool in the single-threaded order:
// bit-identical motion, reports and stats, every step.
TEST(MultithreadedWorld, BlocksRowInTheSingleThreadedIslandOrderIsBitIdentical) {
  useSequentialScheduler();
  for (Friction law : {Friction::Ellipsoidal, Friction::Exact}) {
    SCOPED_TRACE(scenes::toString(law));
    Twin t = blocksRow(law);
    setIslandDispatch(*t.multi, solveInSingleThreadedOrder);
    long patches = 0, stackHolds = 0;
    runTwin(t, 480, [&](int) {
      patches += t.multi->pool().stats().patches;
      stackHolds += t.multi->pool().stats().stackHolds;
    });
    // the row's patches (rectangle, square, coin, the stack's three) and
    // the stack's holds
    EXPECT_GT(patches, 479 * 5);
    EXPECT_GT(stackHolds, 0);
  }
}

TEST(MultithreadedWorld, SlidingAndStackedIslandsInTheSingleThreadedOrderAreBitIdentical) {
  useSequentialScheduler();
  Twin t = islands();
  setIslandDispatch(*t.multi, solveInSingleThreadedOrder);
  runTwin(t, 480, [](int) {});
}

// 100 coins poured into a box: one island of many manifolds.
TEST(MultithreadedWorld, HundredCoinPourInTheSingleThreadedIslandOrderIsBitIdentical) {
  useSequentialScheduler();
  Twin t = pour();
  setIslandDispatch(*t.multi, solveInSingleThreadedOrder);
  runTwin(t, 360, [](int) {});
}

// Bullet's own order. The blocks row moves bit for bit as in the
// single-threaded world, in float and double; in double some patch loads
// and work counters differ from step 224 on (an island's rows in another
// order), while the motion does not: reports and stats are checked for
// completeness, not values.
TEST(MultithreadedWorld, BlocksRowInBulletsIslandOrderMovesBitIdentically) {
  useSequentialScheduler();
  Twin t = blocksRow(Friction::Ellipsoidal);
  for (int s = 0; s < 480; ++s) {
    t.single->step(kDt);
    t.multi->step(kDt);
    SCOPED_TRACE("step " + std::to_string(s));
    for (std::size_t i = 0; i < t.singleBodies.size(); ++i)
      ASSERT_TRUE(sameState(*t.singleBodies[i], *t.multiBodies[i])) << "body " << i;
    expectCompleteRecords(t);
  }
}

// The first step in which an island's rows are swept in another order, the
// two worlds' 10-iteration Gauss-Seidel solutions differ by a fraction of
// the contact impulses: measured 1.6e-4 (float) and 3.8e-4 (double) m/s in
// the 100-coin pour at step 8 (coins landing at 0.5 m/s; 6.6e-7 and
// 1.6e-6 m), after which the coins' collisions carry the difference to
// 4.5 and 2.6 mm by step 120. Bound: 1e-3 m/s, a 2.6-fold margin.
constexpr double kIslandOrderVelocity = 1e-3;  // [m/s]
TEST(MultithreadedWorld, HundredCoinPourInBulletsIslandOrderPartsByTheSolversConvergence) {
  useSequentialScheduler();
  Twin t = pour();
  int first = -1;
  for (int s = 0; s < 360; ++s) {
    t.single->step(kDt);
    t.multi->step(kDt);
    SCOPED_TRACE("step " + std::to_string(s));
    expectCompleteRecords(t);
    if (first >= 0) continue;
    for (std::size_t i = 0; i < t.singleBodies.size(); ++i) {
      const btRigidBody& a = *t.singleBodies[i];
      const btRigidBody& b = *t.multiBodies[i];
      if (sameState(a, b)) continue;
      first = s;
      EXPECT_LT(double((a.getLinearVelocity() - b.getLinearVelocity()).length()),
                kIslandOrderVelocity);
    }
    // until then, bit-identical: the same reports and stats
    if (first < 0) expectSameStep(t, s);
  }
  EXPECT_GT(first, 0) << "the pour no longer exercises another island order";
}

// Stats are the last step's, not a sum over steps (the pool resets them):
// a coin at rest has one patch, step after step.
TEST(MultithreadedWorld, StatsAreResetEveryStep) {
  useSequentialScheduler();
  Scene scene(9.81, 10, SolverKind::PatchPoolMt);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, btVector3(0, 0, btScalar(0.005)), 0.3);
  scene.pool().enablePatchFriction(coin, {Model::Ellipsoidal});
  for (int s = 0; s < 50; ++s) {
    scene.step(kDt);
    if (s < 5) continue;  // settled onto its patch
    EXPECT_EQ(scene.pool().stats().patches, 1);
    EXPECT_EQ(scene.pool().patchReports().size(), 1u);
  }
}

// Opting a body out and in again through the pool, between steps: it
// leaves and rejoins the patch law in both worlds at the same step, and
// every solver of the pool sees the same opt-in.
TEST(MultithreadedWorld, OptInAndOutThroughThePool) {
  useSequentialScheduler();
  Twin t = blocksRow(Friction::Ellipsoidal);
  setIslandDispatch(*t.multi, solveInSingleThreadedOrder);
  btRigidBody* coinSingle = nullptr;
  btRigidBody* coinMulti = nullptr;
  for (std::size_t i = 0; i < t.singleBodies.size(); ++i)
    if (t.singleBodies[i]->getCollisionShape()->getShapeType() == CYLINDER_SHAPE_PROXYTYPE) {
      coinSingle = t.singleBodies[i];
      coinMulti = t.multiBodies[i];
    }
  ASSERT_TRUE(coinSingle && coinMulti);
  PatchSolverPoolMt& pool = t.multi->pool();
  ASSERT_TRUE(pool.isPatchFrictionEnabled(coinMulti));
  const PatchOptions options{Model::Ellipsoidal, scenes::BlocksRowSpec().mu};
  runTwin(t, 240, [&](int s) {
    if (s == 40) {
      t.single->solver().disablePatchFriction(coinSingle);
      pool.disablePatchFriction(coinMulti);
      for (int i = 0; i < pool.numSolvers(); ++i)
        EXPECT_FALSE(pool.solver(i).isPatchFrictionEnabled(coinMulti));
    }
    if (s == 41) {
      EXPECT_EQ(pool.findPatchReport(coinMulti), nullptr);
    }
    if (s == 80) {
      t.single->solver().enablePatchFriction(coinSingle, options);
      pool.solver(pool.numSolvers() - 1).enablePatchFriction(coinMulti, options);
      EXPECT_TRUE(pool.isPatchFrictionEnabled(coinMulti));
    }
    if (s == 90) {
      EXPECT_NE(pool.findPatchReport(coinMulti), nullptr);
    }
  });
}

TEST(MultithreadedWorld, PoolOfNoSolversIsRefused) {
  EXPECT_THROW(PatchSolverPoolMt(0), Error);
}

// With a Bullet built with BT_THREADSAFE, the world's own task scheduler
// with two threads: skipped where there is none (Debian's Bullet).
TEST(MultithreadedWorld, BulletsTwoThreadSchedulerWhereBulletIsThreadSafe) {
  btITaskScheduler* scheduler = btCreateDefaultTaskScheduler();
  if (!scheduler) GTEST_SKIP() << "this Bullet is built without BT_THREADSAFE: one thread only";
  scheduler->setNumThreads(2);
  btSetTaskScheduler(scheduler);
  Twin t = islands();
  setIslandDispatch(*t.multi, solveInSingleThreadedOrder);
  runTwin(t, 480, [](int) {});
  btSetTaskScheduler(btGetSequentialTaskScheduler());
  delete scheduler;
}

}  // namespace
}  // namespace patchspin::bullet
