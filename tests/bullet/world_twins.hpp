// Twin worlds for the multithreaded world's tests (tests/bullet): one
// scene built twice, in btDiscreteDynamicsWorld with a PatchFrictionSolver
// and in btDiscreteDynamicsWorldMt with a PatchSolverPoolMt, compared bit
// for bit after each step; and the island dispatch that hands the pool
// each island's manifolds in the single-threaded world's order.
#pragma once

#include <patchspin/bullet/patch_solver_pool_mt.hpp>
#include <patchspin/scenes/catalogue.hpp>

#include <gtest/gtest.h>

#include <LinearMath/btThreads.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace patchspin::bullet::twins {

using scenes::Friction;
using scenes::Scene;
using scenes::SolverKind;

inline constexpr double kDt = 1.0 / 240.0;

template <class T>
inline bool sameBits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}
inline bool sameBits(const btVector3& a, const btVector3& b) {
  return std::memcmp(&a[0], &b[0], 3 * sizeof(btScalar)) == 0;
}
inline bool sameBits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

// Position, orientation and velocities, bit for bit.
inline bool sameState(const btRigidBody& a, const btRigidBody& b) {
  const btTransform& ta = a.getWorldTransform();
  const btTransform& tb = b.getWorldTransform();
  bool same = sameBits(ta.getOrigin(), tb.getOrigin()) &&
              sameBits(a.getLinearVelocity(), b.getLinearVelocity()) &&
              sameBits(a.getAngularVelocity(), b.getAngularVelocity());
  for (int r = 0; r < 3; ++r) same = same && sameBits(ta.getBasis()[r], tb.getBasis()[r]);
  return same;
}

inline void expectSameCounts(const NotPatchedCounts& a, const NotPatchedCounts& b) {
  EXPECT_EQ(a.unsupportedShape, b.unsupportedShape);
  EXPECT_EQ(a.sideContact, b.sideContact);
  EXPECT_EQ(a.notFlat, b.notFlat);
  EXPECT_EQ(a.offFaces, b.offFaces);
  EXPECT_EQ(a.tipCooldown, b.tipCooldown);
  EXPECT_EQ(a.noOverlap, b.noOverlap);
  EXPECT_EQ(a.lawRefused, b.lawRefused);
  EXPECT_EQ(a.sliver, b.sliver);
  EXPECT_EQ(a.singularBlocks, b.singularBlocks);
  EXPECT_EQ(a.crease, b.crease);
  EXPECT_EQ(a.badMesh, b.badMesh);
}

inline void expectSameStats(const PatchSolverStats& a, const PatchSolverStats& b) {
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
inline void expectSameReport(const PatchReport& a, const PatchReport& b) {
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

inline Twin blocksRow(Friction law) {
  Twin t;
  t.single = scenes::makeBlocksRow(scenes::BlocksRowSpec(), law, &t.singleBodies);
  t.multi =
      scenes::makeBlocksRow(scenes::BlocksRowSpec(), law, &t.multiBodies, SolverKind::PatchPoolMt);
  return t;
}
inline Twin pour() {
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
inline std::unique_ptr<Scene> makeIslands(SolverKind kind, std::vector<btRigidBody*>& bodies) {
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
inline Twin islands() {
  Twin t;
  t.single = makeIslands(SolverKind::Patch, t.singleBodies);
  t.multi = makeIslands(SolverKind::PatchPoolMt, t.multiBodies);
  return t;
}

// What holds in any island order: the pool's reports are the step's
// patches, as many as stats().patches counts, in the documented order (by
// body, then other; each pair once), each of an opted-in body.
inline void expectCompleteRecords(Twin& t) {
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
inline bool expectSameStep(Twin& t, int step) {
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
inline void useSequentialScheduler() {
  btITaskScheduler* sequential = btGetSequentialTaskScheduler();
  ASSERT_NE(sequential, nullptr);
  btSetTaskScheduler(sequential);
}

// Steps both twins `steps` times, comparing after each step; `between`
// (step index) runs before each step on both.
template <class Between>
inline void runTwin(Twin& t, int steps, Between between) {
  for (int s = 0; s < steps; ++s) {
    between(s);
    t.single->step(kDt);
    t.multi->step(kDt);
    if (!expectSameStep(t, s)) return;
  }
}

using Island = btSimulationIslandManagerMt::Island;
using SolverParams = btSimulationIslandManagerMt::SolverParams;

inline int islandOf(const btPersistentManifold* m) {
  const int tag0 = m->getBody0()->getIslandTag();
  return tag0 >= 0 ? tag0 : m->getBody1()->getIslandTag();
}

// The islands' manifolds in btDiscreteDynamicsWorld's order: the manifolds
// of the islands in hand, in the dispatcher's order, quickSorted by island
// id as btSimulationIslandManager does (Bullet's btAlignedObjectArray
// quickSort, the same predicate on the same input: the same permutation).
inline btAlignedObjectArray<btPersistentManifold*> singleThreadedOrder(
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
inline void orderAsSingleThreaded(btAlignedObjectArray<Island*>& islands,
                                  const SolverParams& params) {
  std::map<const btPersistentManifold*, int> batchOf;
  const btAlignedObjectArray<btPersistentManifold*> sorted =
      singleThreadedOrder(islands, params, batchOf);
  for (int b = 0; b < islands.size(); ++b) islands[b]->manifoldArray.resize(0);
  for (int i = 0; i < sorted.size(); ++i)
    islands[batchOf[sorted[i]]]->manifoldArray.push_back(sorted[i]);
}

inline void solveInSingleThreadedOrder(btAlignedObjectArray<Island*>* islands,
                                       const SolverParams& params) {
  orderAsSingleThreaded(*islands, params);
  btSimulationIslandManagerMt::serialIslandDispatch(islands, params);
}

inline void setIslandDispatch(Scene& scene, btSimulationIslandManagerMt::IslandDispatchFunc f) {
  static_cast<btSimulationIslandManagerMt*>(scene.world().getSimulationIslandManager())
      ->setIslandDispatchFunction(f);
}

}  // namespace patchspin::bullet::twins
