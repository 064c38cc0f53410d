// The multithreaded world (issue 31, item 5): btDiscreteDynamicsWorldMt
// with a PatchSolverPoolMt moves the bodies as btDiscreteDynamicsWorld with
// a PatchFrictionSolver does, bit for bit with the same reports and stats
// every step where Bullet hands each island's manifolds over in the same
// order; stats are reset every step; opt-ins go through the pool; and two
// of the pool's solvers solving disjoint islands on two threads at once
// give the one-thread result.
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
// world is stepped here with the sequential scheduler; the two threads are
// the test's own (a custom island dispatch), which is sound with that
// Bullet for the reasons given at TwoThreadsSolveDisjointIslandsAsOneThread.
#include <patchspin/bullet/patch_solver_pool_mt.hpp>
#include <patchspin/scenes/catalogue.hpp>

#include <gtest/gtest.h>

#include <LinearMath/btThreads.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

// Bullet's count of split-impulse penetration rows solved (all solvers,
// unsynchronised; btSequentialImpulseConstraintSolver.cpp).
extern int gNumSplitImpulseRecoveries;

namespace patchspin::bullet {
namespace {

using scenes::Friction;
using scenes::Scene;
using scenes::SolverKind;

constexpr double kDt = 1.0 / 240.0;

template <class T>
bool sameBits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}
bool sameBits(const btVector3& a, const btVector3& b) {
  return std::memcmp(&a[0], &b[0], 3 * sizeof(btScalar)) == 0;
}
bool sameBits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

// Position, orientation and velocities, bit for bit.
bool sameState(const btRigidBody& a, const btRigidBody& b) {
  const btTransform& ta = a.getWorldTransform();
  const btTransform& tb = b.getWorldTransform();
  bool same = sameBits(ta.getOrigin(), tb.getOrigin()) &&
              sameBits(a.getLinearVelocity(), b.getLinearVelocity()) &&
              sameBits(a.getAngularVelocity(), b.getAngularVelocity());
  for (int r = 0; r < 3; ++r) same = same && sameBits(ta.getBasis()[r], tb.getBasis()[r]);
  return same;
}

void expectSameCounts(const NotPatchedCounts& a, const NotPatchedCounts& b) {
  EXPECT_EQ(a.unsupportedShape, b.unsupportedShape);
  EXPECT_EQ(a.sideContact, b.sideContact);
  EXPECT_EQ(a.notFlat, b.notFlat);
  EXPECT_EQ(a.offFaces, b.offFaces);
  EXPECT_EQ(a.tipCooldown, b.tipCooldown);
  EXPECT_EQ(a.noOverlap, b.noOverlap);
  EXPECT_EQ(a.lawRefused, b.lawRefused);
  EXPECT_EQ(a.singularBlocks, b.singularBlocks);
}

void expectSameStats(const PatchSolverStats& a, const PatchSolverStats& b) {
  EXPECT_EQ(a.blockSolves, b.blockSolves);
  EXPECT_EQ(a.pressureRefreshes, b.pressureRefreshes);
  EXPECT_EQ(a.deferredRefreshes, b.deferredRefreshes);
  EXPECT_EQ(a.quickSticks, b.quickSticks);
  EXPECT_EQ(a.blockErrors, b.blockErrors);
  EXPECT_EQ(a.patches, b.patches);
  EXPECT_EQ(a.visits, b.visits);
  EXPECT_EQ(a.skippedVisits, b.skippedVisits);
  EXPECT_EQ(a.shapeRebuilds, b.shapeRebuilds);
  EXPECT_EQ(a.stackHolds, b.stackHolds);
  EXPECT_TRUE(sameBits(a.maxPressureLag, b.maxPressureLag));
  EXPECT_EQ(a.patchesWithoutPoints, b.patchesWithoutPoints);
  expectSameCounts(a.notPatched, b.notPatched);
}

// Every field, bit for bit (`other` by its index in its world).
void expectSameReport(const PatchReport& a, const PatchReport& b) {
  EXPECT_EQ(a.other->getWorldArrayIndex(), b.other->getWorldArrayIndex());
  EXPECT_TRUE(sameBits(a.origin, b.origin));
  EXPECT_TRUE(sameBits(a.normal, b.normal));
  EXPECT_TRUE(sameBits(a.xAxis, b.xAxis));
  EXPECT_TRUE(sameBits(a.yAxis, b.yAxis));
  ASSERT_TRUE(a.shape && b.shape);
  EXPECT_TRUE(sameBits(a.shape->area(), b.shape->area()));
  EXPECT_EQ(a.model, b.model);
  EXPECT_TRUE(sameBits(a.mu, b.mu));
  EXPECT_TRUE(sameBits(a.rho, b.rho));
  EXPECT_TRUE(sameBits(a.loads.asVector(), b.loads.asVector()));
  EXPECT_TRUE(sameBits(a.pressure.coefficients(), b.pressure.coefficients()));
  EXPECT_TRUE(sameBits(a.Q, b.Q));
  EXPECT_TRUE(sameBits(a.slip, b.slip));
  EXPECT_TRUE(sameBits(a.r, b.r));
  EXPECT_TRUE(sameBits(a.w, b.w));
  EXPECT_EQ(a.sticking, b.sticking);
}

// One scene twice: single-threaded (btDiscreteDynamicsWorld and a
// PatchFrictionSolver) and multithreaded (btDiscreteDynamicsWorldMt and a
// PatchSolverPoolMt); the bodies in the same order in both.
struct Twin {
  std::unique_ptr<Scene> single, multi;
  std::vector<btRigidBody*> singleBodies, multiBodies;
};

Twin blocksRow(Friction law) {
  Twin t;
  t.single = scenes::makeBlocksRow(scenes::BlocksRowSpec(), law, &t.singleBodies);
  t.multi =
      scenes::makeBlocksRow(scenes::BlocksRowSpec(), law, &t.multiBodies, SolverKind::PatchPoolMt);
  return t;
}
Twin pour() {
  Twin t;
  t.single = scenes::makePour(scenes::PourSpec(), Friction::Ellipsoidal, &t.singleBodies);
  t.multi = scenes::makePour(scenes::PourSpec(), Friction::Ellipsoidal, &t.multiBodies, 9.81,
                             SolverKind::PatchPoolMt);
  return t;
}

// Separate islands on the ground plane (friction 1): coins (R 5 cm, H 1 cm,
// 1 kg) and boxes (10 x 6 x 4 cm, 1 kg) sliding and spinning on a 3 x 3
// grid 0.5 m apart, and two two-box stacks (10 x 10 x 4 cm below, 6 x 6 x
// 4 cm above), mu 0.3, every body under the ellipsoidal law.
std::unique_ptr<Scene> makeIslands(SolverKind kind, std::vector<btRigidBody*>& bodies) {
  auto scene = std::make_unique<Scene>(9.81, 10, kind);
  scene->addGroundPlane(1.0);
  constexpr double kMu = 0.3, kOverlap = 1e-5;  // (a box on a box: see BlockSpec::overlap)
  for (int i = 0; i < 9; ++i) {
    const double x = 0.5 * (i % 3 - 1), y = 0.5 * (i / 3 - 1);
    btRigidBody* b =
        i % 2 == 0 ? scene->addCylinder(0.05, 0.01, 1.0, scenes::bt(x, y, 0.005 - kOverlap), kMu)
                   : scene->addBox(scenes::bt(0.05, 0.03, 0.02), 1.0,
                                   scenes::bt(x, y, 0.02 - kOverlap), kMu);
    b->setLinearVelocity(scenes::bt(0.3 * std::cos(i), 0.3 * std::sin(i), 0));
    b->setAngularVelocity(scenes::bt(0, 0, 5.0 + i));
    bodies.push_back(b);
  }
  for (int k = 0; k < 2; ++k) {
    const double x = k == 0 ? -1.0 : 1.0;
    bodies.push_back(
        scene->addBox(scenes::bt(0.05, 0.05, 0.02), 1.0, scenes::bt(x, 0, 0.02 - kOverlap), kMu));
    bodies.push_back(scene->addBox(scenes::bt(0.03, 0.03, 0.02), 0.5,
                                   scenes::bt(x, 0, 0.06 - 2 * kOverlap), kMu));
    bodies.back()->setAngularVelocity(scenes::bt(0, 0, k == 0 ? 2.0 : -2.0));
  }
  for (btRigidBody* b : bodies) scene->solver().enablePatchFriction(b, {Model::Ellipsoidal});
  return scene;
}
Twin islands() {
  Twin t;
  t.single = makeIslands(SolverKind::Patch, t.singleBodies);
  t.multi = makeIslands(SolverKind::PatchPoolMt, t.multiBodies);
  return t;
}

// What holds in any island order: the pool's reports and stats are those of
// the step (patches counted once, every one reported, in the documented
// order), and patch the same contacts as the single-threaded world while
// the motion is the same.
void expectCompleteRecords(Twin& t) {
  const PatchSolverPoolMt& pool = t.multi->pool();
  const std::vector<PatchReport>& reports = pool.patchReports();
  EXPECT_EQ(pool.stats().patches, long(reports.size()));
  for (std::size_t i = 1; i < reports.size(); ++i) {
    const auto key = [](const PatchReport& r) {
      return std::pair(r.body->getWorldArrayIndex(), r.other->getWorldArrayIndex());
    };
    EXPECT_LT(key(reports[i - 1]), key(reports[i]));
  }
  for (const PatchReport& r : reports) EXPECT_TRUE(pool.isPatchFrictionEnabled(r.body));
}

// Compares the twins after a step: the same motion bit for bit, the same
// reports (every single-threaded one found by body in the pool's) and the
// same stats. Returns false at the first difference in motion.
bool expectSameStep(Twin& t, int step) {
  SCOPED_TRACE("step " + std::to_string(step));
  for (std::size_t i = 0; i < t.singleBodies.size(); ++i) {
    if (!sameState(*t.singleBodies[i], *t.multiBodies[i])) {
      ADD_FAILURE() << "body " << i << " moved differently";
      return false;
    }
  }
  const PatchFrictionSolver& single = t.single->solver();
  const PatchSolverPoolMt& pool = t.multi->pool();
  expectSameStats(single.stats(), pool.stats());
  EXPECT_EQ(single.patchReports().size(), pool.patchReports().size());
  for (const PatchReport& r : single.patchReports()) {
    // (a coin on the floor and on another coin has two patches)
    const int index = r.body->getWorldArrayIndex();
    const int other = r.other->getWorldArrayIndex();
    const btCollisionObject* twin = t.multi->world().getCollisionObjectArray()[index];
    const PatchReport* m = nullptr;
    for (const PatchReport& q : pool.patchReports())
      if (q.body == twin && q.other->getWorldArrayIndex() == other) m = &q;
    EXPECT_NE(m, nullptr) << "no report of body " << index << " on " << other;
    if (m) expectSameReport(r, *m);
    const NotPatchedCounts* ns = single.notPatchedOf(r.body);
    const NotPatchedCounts* nm = pool.notPatchedOf(twin);
    EXPECT_EQ(ns == nullptr, nm == nullptr);
    if (ns && nm) expectSameCounts(*ns, *nm);
  }
  expectCompleteRecords(t);
  return true;
}

// The world's island dispatch with the sequential scheduler (Debian's
// Bullet has no other).
void useSequentialScheduler() {
  btITaskScheduler* sequential = btGetSequentialTaskScheduler();
  ASSERT_NE(sequential, nullptr);
  btSetTaskScheduler(sequential);
}

// Steps both twins `steps` times, comparing after each step; `between`
// (step index) runs before each step on both.
template <class Between>
void runTwin(Twin& t, int steps, Between between) {
  for (int s = 0; s < steps; ++s) {
    between(s);
    t.single->step(kDt);
    t.multi->step(kDt);
    if (!expectSameStep(t, s)) return;
  }
}

using Island = btSimulationIslandManagerMt::Island;
using SolverParams = btSimulationIslandManagerMt::SolverParams;

int islandOf(const btPersistentManifold* m) {
  const int tag0 = m->getBody0()->getIslandTag();
  return tag0 >= 0 ? tag0 : m->getBody1()->getIslandTag();
}

// The islands' manifolds in btDiscreteDynamicsWorld's order: the manifolds
// of the islands in hand, in the dispatcher's order, quickSorted by island
// id as btSimulationIslandManager does (Bullet's btAlignedObjectArray
// quickSort, the same predicate on the same input: the same permutation).
btAlignedObjectArray<btPersistentManifold*> singleThreadedOrder(
    const btAlignedObjectArray<Island*>& islands, const SolverParams& params,
    std::map<const btPersistentManifold*, int>& batchOf) {
  for (int b = 0; b < islands.size(); ++b)
    for (int k = 0; k < islands[b]->manifoldArray.size(); ++k)
      batchOf[islands[b]->manifoldArray[k]] = b;
  btAlignedObjectArray<btPersistentManifold*> sorted;
  for (int i = 0; i < params.m_dispatcher->getNumManifolds(); ++i) {
    btPersistentManifold* m = params.m_dispatcher->getManifoldByIndexInternal(i);
    if (batchOf.count(m)) sorted.push_back(m);
  }
  struct ByIsland {
    bool operator()(const btPersistentManifold* a, const btPersistentManifold* b) const {
      return islandOf(a) < islandOf(b);
    }
  };
  sorted.quickSort(ByIsland());
  return sorted;
}

// Puts each batch's manifolds in the single-threaded order (within an
// island; islands do not interact within a batch).
void orderAsSingleThreaded(btAlignedObjectArray<Island*>& islands, const SolverParams& params) {
  std::map<const btPersistentManifold*, int> batchOf;
  const btAlignedObjectArray<btPersistentManifold*> sorted =
      singleThreadedOrder(islands, params, batchOf);
  for (int b = 0; b < islands.size(); ++b) islands[b]->manifoldArray.resize(0);
  for (int i = 0; i < sorted.size(); ++i)
    islands[batchOf[sorted[i]]]->manifoldArray.push_back(sorted[i]);
}

void solveInSingleThreadedOrder(btAlignedObjectArray<Island*>* islands,
                                const SolverParams& params) {
  orderAsSingleThreaded(*islands, params);
  btSimulationIslandManagerMt::serialIslandDispatch(islands, params);
}

void setIslandDispatch(Scene& scene, btSimulationIslandManagerMt::IslandDispatchFunc f) {
  static_cast<btSimulationIslandManagerMt*>(scene.world().getSimulationIslandManager())
      ->setIslandDispatchFunction(f);
}

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

// Two threads: the pool's solvers 0 and 1 solve the even and the odd
// islands at the same time (the world's island dispatch replaced by one
// that starts a thread; islands not merged into batches, each island's
// manifolds in the single-threaded order). With Debian's Bullet (no
// BT_THREADSAFE) this is sound because
//  * each solver has its own arrays, and an island's dynamic bodies,
//    manifolds and joints are its own: a solve writes nothing another
//    island's solve reads, except
//  * static bodies, shared by islands, which a solve only reads (a
//    kinematic body would get its companion id written: none here), and
//  * Bullet's global gNumSplitImpulseRecoveries, incremented without
//    synchronisation for contacts deeper than
//    m_splitImpulsePenetrationThreshold (4 cm): none here, asserted below;
//  * Debian's Bullet is built with BT_NO_PROFILE (its profile zones are
//    empty functions), and the pool's shared state takes its own lock
//    (patch_solver_shared.hpp).
// The world's own parallel loops (btParallelFor) stay sequential.
std::atomic<int> gIslandsSolved[2];
void solveIslandsOnTwoThreads(btAlignedObjectArray<Island*>* batches, const SolverParams& params) {
  orderAsSingleThreaded(*batches, params);
  // Bullet puts every island of fewer than 32 bodies into one batch: split
  // the batches into their islands again
  std::map<int, Island> byId;
  for (int b = 0; b < batches->size(); ++b) {
    const Island& batch = *(*batches)[b];
    EXPECT_EQ(batch.constraintArray.size(), 0);
    for (int k = 0; k < batch.bodyArray.size(); ++k)
      byId[batch.bodyArray[k]->getIslandTag()].bodyArray.push_back(batch.bodyArray[k]);
    for (int k = 0; k < batch.manifoldArray.size(); ++k)
      byId[islandOf(batch.manifoldArray[k])].manifoldArray.push_back(batch.manifoldArray[k]);
  }
  std::vector<Island*> islands;
  for (auto& entry : byId) islands.push_back(&entry.second);
  auto& pool = *static_cast<PatchSolverPoolMt*>(params.m_solverPool);
  std::atomic<int> ready{0};
  auto solve = [&](int parity) {
    // both threads start together, so that their solves overlap
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
    for (std::size_t i = std::size_t(parity); i < islands.size(); i += 2) {
      btSimulationIslandManagerMt::solveIsland(&pool.solver(parity), *islands[i], params);
      ++gIslandsSolved[parity];
    }
  };
  std::thread odd(solve, 1);
  solve(0);
  odd.join();
}

TEST(MultithreadedWorld, TwoThreadsSolveDisjointIslandsAsOneThread) {
  useSequentialScheduler();
  for (bool rowScene : {true, false}) {
    SCOPED_TRACE(rowScene ? "blocks row" : "islands");
    Twin t = rowScene ? blocksRow(Friction::Ellipsoidal) : islands();
    auto* manager =
        static_cast<btSimulationIslandManagerMt*>(t.multi->world().getSimulationIslandManager());
    manager->setMinimumSolverBatchSize(1);  // batches not merged further
    manager->setIslandDispatchFunction(solveIslandsOnTwoThreads);
    // (and the single-threaded world solves each island alone, as here: an
    // island alone may stop its iterations earlier than in a batch)
    t.single->world().getSolverInfo().m_minimumSolverBatchSize = 1;
    gIslandsSolved[0] = gIslandsSolved[1] = 0;
    const int recoveries = gNumSplitImpulseRecoveries;
    runTwin(t, 480, [](int) {});
    EXPECT_EQ(gNumSplitImpulseRecoveries, recoveries);
    // both solvers, on both threads, took islands (the islands scene:
    // nine sliding bodies and two stacks, eleven islands a step)
    EXPECT_GT(gIslandsSolved[0].load(), 0);
    EXPECT_GT(gIslandsSolved[1].load(), 0);
    if (!rowScene) {
      EXPECT_EQ(gIslandsSolved[0].load() + gIslandsSolved[1].load(), 11 * 480);
    }
  }
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
