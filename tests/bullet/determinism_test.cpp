// Determinism: trajectory hashes of three scenes (the coin trio, the blocks
// row with a stack, a 100-coin pour), with the solver's work-saving rules on
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
#include <patchspin/bullet/scene.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace patchspin::bullet {
namespace {

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

btVector3 bt(double x, double y, double z) { return btVector3(btScalar(x), btScalar(y), btScalar(z)); }

enum class Law { Stock, Ellipsoidal, Exact };
void optIn(Scene& scene, btRigidBody* b, Law law) {
  if (law != Law::Stock) scene.solver().enablePatchFriction(b, {law == Law::Exact ? Model::Exact : Model::Ellipsoidal});
}

// One coin (R = 5 cm, H = 1 cm, 0.2 kg, mu = 0.5 against the plane's 1)
// sliding at 0.5 m/s and spinning at 20 rad/s, as the coin demo's trio.
Hashes coin(Law law) {
  Scene scene;
  scene.addGroundPlane(1.0);
  btRigidBody* c = scene.addCylinder(0.05, 0.01, 0.2, bt(0, 0, 0.005), 0.5);
  c->setLinearVelocity(bt(0.5, 0, 0));
  c->setAngularVelocity(bt(0, 0, 20));
  optIn(scene, c, law);
  return run(scene, {c}, 480);
}

// Three boxes of aspect 1:1, 3:1 and 7:1 sliding and spinning side by side,
// and a stack (a 2 kg box on a 0.2 kg one) pushed along the floor.
Hashes blocks(Law law) {
  Scene scene;
  scene.addGroundPlane(1.0);
  std::vector<btRigidBody*> bodies;
  const btVector3 halves[3] = {bt(0.05, 0.05, 0.02), bt(0.09, 0.03, 0.02), bt(0.14, 0.02, 0.02)};
  for (int i = 0; i < 3; ++i) {
    btRigidBody* b = scene.addBox(halves[i], 0.5, bt(0.4 * i, 0, 0.02), 0.5);
    b->setLinearVelocity(bt(0.3, 0.1 * i, 0));
    b->setAngularVelocity(bt(0, 0, 6.0 + 3.0 * i));
    bodies.push_back(b);
  }
  btRigidBody* lower = scene.addBox(bt(0.06, 0.06, 0.02), 0.2, bt(0, 0.5, 0.02), 0.5);
  btRigidBody* upper = scene.addBox(bt(0.04, 0.04, 0.02), 2.0, bt(0, 0.5, 0.06), 0.5);
  lower->setLinearVelocity(bt(0.4, 0, 0));
  upper->setLinearVelocity(bt(0.4, 0, 0));
  upper->setAngularVelocity(bt(0, 0, 3));
  bodies.push_back(lower);
  bodies.push_back(upper);
  for (btRigidBody* b : bodies) optIn(scene, b, law);
  return run(scene, bodies, 480);
}

// 100 coins (R = 2 cm, H = 4 mm, 10 g) in a 10 x 10 layer with seeded
// offsets, tilts, throws and spins, poured into a walled box.
Hashes pour(Law law) {
  Scene scene;
  scene.addGroundPlane(1.0);
  for (int side = 0; side < 4; ++side) {
    const double sx = side < 2 ? (side == 0 ? -1 : 1) : 0, sy = side >= 2 ? (side == 2 ? -1 : 1) : 0;
    const btVector3 half = sx != 0 ? bt(0.05, 0.45, 0.1) : bt(0.45, 0.05, 0.1);
    scene.addStaticBox(half, bt(sx * 0.35, sy * 0.35, 0.1), 1.0);
  }
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<btRigidBody*> coins;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const btVector3 p = bt((i - 4.5) * 0.055 + 0.005 * u(rng), (j - 4.5) * 0.055 + 0.005 * u(rng),
                             0.03 + 0.01 * ((i + j) % 3));
      btRigidBody* c = scene.addCylinder(0.02, 0.004, 0.01, p, 0.4);
      btTransform t = c->getWorldTransform();
      t.setRotation(btQuaternion(bt(u(rng), u(rng), 0).normalized(), btScalar(0.3 * std::abs(u(rng)))));
      c->setWorldTransform(t);
      c->setLinearVelocity(bt(0.3 * u(rng), 0.3 * u(rng), -0.5));
      c->setAngularVelocity(bt(0, 0, 10 * u(rng)));
      optIn(scene, c, law);
      coins.push_back(c);
    }
  return run(scene, coins, 360);
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
    std::printf("%s (%s): motion 0x%016llxull, work 0x%016llxull\n", name, kDouble ? "double" : "float",
                static_cast<unsigned long long>(got.motion), static_cast<unsigned long long>(got.work));
  EXPECT_EQ(got.motion, kDouble ? pinned.motionDouble : pinned.motionFloat)
      << name << ": the motion or the reports changed";
  EXPECT_EQ(got.work, kDouble ? pinned.workDouble : pinned.workFloat) << name << ": the solver's work counters changed";
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
  expectHashes("coin stock", coin(Law::Stock),
               {0xea83f73dcb9199a9ull, 0x0fa5400ee6ae8725ull,
                0xc06fe979eade0798ull, 0x0fa5400ee6ae8725ull});
  const Hashes ellipsoidal = coin(Law::Ellipsoidal), exact = coin(Law::Exact);
  EXPECT_GT(ellipsoidal.total.patches, 0);
  EXPECT_GT(exact.total.patches, 0);
  expectHashes("coin ellipsoidal", ellipsoidal,
               {0x2f95a488869445a9ull, 0xdc9d13be2c40039aull,
                0x6311d17604f51588ull, 0x5c561fefa2d231e2ull});
  expectHashes("coin exact", exact,
               {0x07d064eaaede979bull, 0x8ad949bfc8818b55ull,
                0x2ae89a9132011e31ull, 0x281875fec696cca3ull});
}

TEST(Determinism, BlocksRowAndStackAreBitIdentical) {
  const Hashes ellipsoidal = blocks(Law::Ellipsoidal), exact = blocks(Law::Exact);
  expectExercised("blocks ellipsoidal", ellipsoidal, true);
  expectExercised("blocks exact", exact, true);
  expectHashes("blocks ellipsoidal", ellipsoidal,
               {0xd0fecba1b28ce11bull, 0x615e2a7b82f02d64ull,
                0x40d82319b1cd05d2ull, 0x82e73757538399b2ull});
  expectHashes("blocks exact", exact,
               {0xd23aa194a7138b18ull, 0xa3a6b1e6cfdceb21ull,
                0x2209ff878b259c34ull, 0xa86b9938779ebe7eull});
}

TEST(Determinism, HundredCoinPourIsBitIdentical) {
  const Hashes ellipsoidal = pour(Law::Ellipsoidal), exact = pour(Law::Exact);
  expectExercised("pour ellipsoidal", ellipsoidal, false);
  expectExercised("pour exact", exact, false);
  expectHashes("pour ellipsoidal", ellipsoidal,
               {0x94d7e1c0260bc729ull, 0xabe8949d80459661ull,
                0x75fa9534d1aa7cb0ull, 0xe9a9bd2dfab8ce88ull});
  expectHashes("pour exact", exact,
               {0xa5f1a1f1740f4439ull, 0x016b51f0b9896280ull,
                0xcd52f9b3483018abull, 0xdd0684ec551e125full});
}

}  // namespace
}  // namespace patchspin::bullet
