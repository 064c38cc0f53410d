// Determinism: trajectory hashes of three catalogue scenes (the coin trio,
// the blocks row with its stack, the 100-coin pour; scenes/catalogue.hpp),
// with the solver's work-saving rules on
// (the default settings). They pin the solver's arithmetic, bit for bit, so
// that a restructuring of the solver can show it changed nothing: every
// refactoring commit keeps these hashes, or its message says which changed
// and why. A hash is of the bytes of every body's transform and velocities
// and of every patch report's fields, each step, and separately of the
// solver's work counters (PatchSolverStats) each step.
//
// The expected values are of this machine's Debian Bullet 3.24 and g++ 12,
// float and double. Re-baseline only for a reason a commit message states:
// PATCHSPIN_PRINT_HASHES=1 prints the values.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/catalogue.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::Friction;
using scenes::Scene;

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr double kDt = 1.0 / 240.0;

// FNV-1a, 64 bits, over raw bytes.
class Hash {
 public:
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ c[i]) * 0x100000001B3ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void vector(const btVector3& v) {
    for (int i = 0; i < 3; ++i) value(v[i]);
  }
  void vector(const Vec3& v) {
    for (int i = 0; i < 3; ++i) value(v[i]);
  }
  std::uint64_t get() const { return h_; }

 private:
  std::uint64_t h_ = 0xCBF29CE484222325ull;
};

struct Hashes {
  std::uint64_t motion = 0, work = 0;
  PatchSolverStats total;  // the counters summed over the steps
};

// Steps `scene` and hashes the motion of `bodies` and the solver's reports
// and counters after every step.
Hashes run(Scene& scene, const std::vector<btRigidBody*>& bodies, int steps) {
  std::map<const btCollisionObject*, int> index;
  for (std::size_t i = 0; i < bodies.size(); ++i) index[bodies[i]] = int(i);
  Hash motion, work;
  PatchSolverStats total;
  for (int s = 0; s < steps; ++s) {
    scene.step(kDt);
    for (const btRigidBody* b : bodies) {
      const btTransform& t = b->getWorldTransform();
      motion.vector(t.getOrigin());
      for (int r = 0; r < 3; ++r) motion.vector(t.getBasis()[r]);
      motion.vector(b->getLinearVelocity());
      motion.vector(b->getAngularVelocity());
    }
    for (const PatchReport& r : scene.solver().patchReports()) {
      const auto it = index.find(r.body);
      motion.value(it == index.end() ? -1 : it->second);
      motion.vector(r.origin);
      motion.vector(r.normal);
      motion.value(r.loads.Pz);
      motion.value(r.loads.Tx);
      motion.value(r.loads.Ty);
      motion.vector(r.Q);
      motion.vector(r.slip);
      motion.value(r.sticking);
    }
    const PatchSolverStats& st = scene.solver().stats();
    for (long v : {st.patches, st.visits, st.skippedVisits, st.quickSticks, st.blockSolves,
                   st.pressureRefreshes, st.deferredRefreshes, st.shapeRebuilds, st.stackHolds,
                   st.blockErrors})
      work.value(v);
    work.value(st.maxPressureLag);
    total.patches += st.patches;
    total.stackHolds += st.stackHolds;
    total.quickSticks += st.quickSticks;
    total.blockSolves += st.blockSolves;
    total.skippedVisits += st.skippedVisits;
  }
  return {motion.get(), work.get(), total};
}

// The coin demo's coin under one law (stock: not opted in).
Hashes coin(Friction law) {
  btRigidBody* c = nullptr;
  const std::unique_ptr<Scene> scene = scenes::makeCoin(scenes::CoinSpec(), law, &c);
  return run(*scene, {c}, 480);
}

// The blocks demo's row: a sliding and spinning block, a square spinning in
// place, a stack of three, a coin, a rolling sphere (never opted in).
Hashes blocks(Friction law) {
  std::vector<btRigidBody*> bodies;
  const std::unique_ptr<Scene> scene = scenes::makeBlocksRow(scenes::BlocksRowSpec(), law, &bodies);
  return run(*scene, bodies, 480);
}

// The 100-coin pour as its tests start it (seeded), in metres.
Hashes pour(Friction law) {
  std::vector<btRigidBody*> coins;
  const std::unique_ptr<Scene> scene = scenes::makePour(scenes::PourSpec(), law, &coins);
  return run(*scene, coins, 360);
}

bool printHashes() {
  const char* v = std::getenv("PATCHSPIN_PRINT_HASHES");
  return v && *v && std::string(v) != "0";
}

// The pinned hashes of one run, float and double Bullet.
struct Pinned {
  std::uint64_t motionFloat, workFloat, motionDouble, workDouble;
};

void expectHashes(const char* name, const Hashes& got, const Pinned& pinned) {
  if (printHashes())
    std::printf("%s (%s): motion 0x%016llxull, work 0x%016llxull\n", name,
                kDouble ? "double" : "float", static_cast<unsigned long long>(got.motion),
                static_cast<unsigned long long>(got.work));
  EXPECT_EQ(got.motion, kDouble ? pinned.motionDouble : pinned.motionFloat)
      << name << ": the motion or the reports changed";
  EXPECT_EQ(got.work, kDouble ? pinned.workDouble : pinned.workFloat)
      << name << ": the solver's work counters changed";
}

// The scenes exercise what they pin: patches, quick sticks, block solves,
// skipped visits and (the blocks row's stack) stack holds.
void expectExercised(const char* name, const Hashes& h, bool stack) {
  SCOPED_TRACE(name);
  EXPECT_GT(h.total.patches, 0);
  EXPECT_GT(h.total.quickSticks, 0);
  EXPECT_GT(h.total.blockSolves, 0);
  EXPECT_GT(h.total.skippedVisits, 0);
  if (stack) {
    EXPECT_GT(h.total.stackHolds, 0);
  }
}

TEST(Determinism, CoinTrioIsBitIdentical) {
  expectHashes(
      "coin stock", coin(Friction::Stock),
      {0xc9686c2ba75e1315ull, 0x0fa5400ee6ae8725ull, 0x81a8de17dc45eeecull, 0x0fa5400ee6ae8725ull});
  const Hashes ellipsoidal = coin(Friction::Ellipsoidal), exact = coin(Friction::Exact);
  EXPECT_GT(ellipsoidal.total.patches, 0);
  EXPECT_GT(exact.total.patches, 0);
  expectHashes(
      "coin ellipsoidal", ellipsoidal,
      {0x9dcf59bbf02af804ull, 0x5d174e0211408198ull, 0xb53c0a720c0f0e4full, 0x7106f6e28b1280f9ull});
  expectHashes(
      "coin exact", exact,
      {0x542493f99fb3a842ull, 0x85e2e460c04a9978ull, 0x2f5a6a9ec107a962ull, 0x67ca297cde22e281ull});
}

TEST(Determinism, BlocksRowAndStackAreBitIdentical) {
  const Hashes ellipsoidal = blocks(Friction::Ellipsoidal), exact = blocks(Friction::Exact);
  expectExercised("blocks ellipsoidal", ellipsoidal, true);
  expectExercised("blocks exact", exact, true);
  expectHashes(
      "blocks ellipsoidal", ellipsoidal,
      {0x15a3b7ab55e76c18ull, 0x4aa8099129b5c5ceull, 0x1f7e4f4aa22ab7a4ull, 0x420ee391f8f19325ull});
  expectHashes(
      "blocks exact", exact,
      {0x7c0cf0213504af94ull, 0x6a2c0ae6a04bff15ull, 0x5f4396e892435853ull, 0x1c9779954d8dea49ull});
}

TEST(Determinism, HundredCoinPourIsBitIdentical) {
  const Hashes ellipsoidal = pour(Friction::Ellipsoidal), exact = pour(Friction::Exact);
  expectExercised("pour ellipsoidal", ellipsoidal, false);
  expectExercised("pour exact", exact, false);
  expectHashes(
      "pour ellipsoidal", ellipsoidal,
      {0x806633625d1d1a3aull, 0xae56d52cf85247a6ull, 0x0884d21b635bc1eeull, 0x2b80157ab079a705ull});
  expectHashes(
      "pour exact", exact,
      {0xd1cc835251d141adull, 0xe7b91f3c464d72e6ull, 0x9903b19c6d2c9c10ull, 0x9331c6af49c12ba3ull});
}

}  // namespace
}  // namespace patchspin::bullet
