// Two threads (issue 31, item 5): two of a PatchSolverPoolMt's solvers
// solve disjoint islands on two std::threads at once, in a
// btDiscreteDynamicsWorldMt whose island dispatch is the test's own, and
// the world moves as btDiscreteDynamicsWorld does, bit for bit with the
// same reports and stats. Debian's Bullet has no thread-safe task
// scheduler (no BT_THREADSAFE), so the threads are the test's.
#include "world_twins.hpp"

#include <atomic>
#include <map>
#include <thread>
#include <vector>

// Bullet's count of split-impulse penetration rows solved (all solvers,
// unsynchronised; btSequentialImpulseConstraintSolver.cpp).
extern int gNumSplitImpulseRecoveries;

namespace patchspin::bullet {
namespace {

using namespace twins;
using scenes::Friction;

// The pool's solvers 0 and 1 solve the even and the odd
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

}  // namespace
}  // namespace patchspin::bullet
