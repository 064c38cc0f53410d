// World step time with N coins sliding and spinning on a plane (same scene,
// same 10 solver iterations): patch friction (ellipsoidal, exact), stock
// Bullet (btSequentialImpulseConstraintSolver), and PatchFrictionSolver with
// no opted-in body (must cost what stock costs). Ratios are in
// bullet_integration/README.md.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/scene.hpp>
#include <patchspin/scenes/terrain.hpp>

#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include "interleaving.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using patchspin::Model;
using patchspin::bullet::PatchFrictionSolver;
using patchspin::scenes::Scene;
using patchspin::scenes::SolverKind;

enum Variant { kEllipsoidal = 0, kExact = 1, kStock = 2, kNoneOptedIn = 3 };

// Scene options beyond the variant (the skip-what-isn't-needed benchmarks).
struct SceneOptions {
  bool moving = true;         // seeded slide and spin; false: coins at rest
  bool allowSleep = false;    // Bullet may put resting coins to sleep
  double exactFraction = -1;  // >= 0: this fraction exact, the rest ellipsoidal
  patchspin::bullet::PatchSolverSettings settings;
  // the ground: the plane, or a triangle mesh or heightfield of it (5 cm
  // grid, under the coins' square, which is then centred on the origin)
  patchspin::scenes::Ground ground = patchspin::scenes::Ground::Plane;
};

constexpr double kDt = 1.0 / 240.0;
constexpr double kR = 0.05, kH = 0.01;

struct World {
  std::unique_ptr<Scene> scene;
  btDiscreteDynamicsWorld* world = nullptr;
  std::vector<btRigidBody*> coins;
  std::vector<btVector3> v0, w0;
  std::vector<btTransform> start;
  SceneOptions options;

  World(int n, Variant variant, const SceneOptions& opt = SceneOptions()) : options(opt) {
    scene = std::make_unique<Scene>(9.81, 10,
                                    variant == kStock ? SolverKind::Stock : SolverKind::Patch);
    world = &scene->world();
    // ground friction: Bullet's default 0.5 (combined with the coins' 0.3)
    const int side = int(std::ceil(std::sqrt(double(n))));
    double offset = 0.0;  // of the coins' square
    if (opt.ground == patchspin::scenes::Ground::Plane) {
      scene->addGroundPlane(0.5);
    } else {
      patchspin::scenes::GroundSpec g;
      g.kind = opt.ground;
      g.spacing = 0.05;
      g.halfSize = 0.25 * side + 0.5;
      offset = -0.25 * (side - 1);
      patchspin::scenes::addGround(*scene, g, 0.5);
    }
    btCollisionShape* coinShape = scene->addShape(std::make_unique<btCylinderShapeZ>(
        btVector3(btScalar(kR), btScalar(kR), btScalar(kH / 2))));
    coinShape->setMargin(btScalar(1e-3));
    // coins on a grid 0.5 m apart, seeded random slide and spin
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const btVector3 inertia = patchspin::scenes::cylinderInertia(1.0, kR, kH);
    for (int i = 0; i < n; ++i) {
      btTransform tr;
      tr.setIdentity();
      tr.setOrigin(btVector3(btScalar(offset + 0.5 * (i % side)),
                             btScalar(offset + 0.5 * (i / side)), btScalar(kH / 2)));
      btRigidBody* coin = scene->addBody(coinShape, 1.0, inertia, tr, 0.3);
      if (opt.allowSleep) coin->forceActivationState(ACTIVE_TAG);
      start.push_back(tr);
      const double vx = 0.3 * u(rng), vy = 0.3 * u(rng), wz = 10 * u(rng);
      v0.emplace_back(btScalar(opt.moving ? vx : 0.0), btScalar(opt.moving ? vy : 0.0), 0);
      w0.emplace_back(0, 0, btScalar(opt.moving ? wz : 0.0));
      if (variant == kEllipsoidal || variant == kExact) {
        Model model = variant == kExact ? Model::Exact : Model::Ellipsoidal;
        if (opt.exactFraction >= 0)
          model = (i % 100) < int(100 * opt.exactFraction) ? Model::Exact : Model::Ellipsoidal;
        patchSolver()->enablePatchFriction(coin, {model});
      }
      coins.push_back(coin);
    }
    if (variant != kStock) patchSolver()->setSettings(opt.settings);
    reset();
  }
  PatchFrictionSolver* patchSolver() { return &scene->solver(); }
  // the coins stop after ~0.2 s: restart them from their initial state
  // (place, orientation, velocities) so that every step of the benchmark is
  // the same scene of coins sliding and spinning apart
  void reset() {
    for (size_t i = 0; i < coins.size(); ++i) {
      if (options.allowSleep) continue;  // resting scene: leave them be
      coins[i]->setWorldTransform(start[i]);
      coins[i]->setInterpolationWorldTransform(start[i]);
      coins[i]->setLinearVelocity(v0[i]);
      coins[i]->setAngularVelocity(w0[i]);
    }
  }
};

// What the solver did in the last step, per active patch.
void addSolverCounters(benchmark::State& state, const PatchFrictionSolver& solver) {
  const auto& s = solver.stats();
  const double p = s.patches > 0 ? double(s.patches) : 1.0;
  state.counters["solves/patch"] = double(s.blockSolves) / p;
  state.counters["refreshes/patch"] = double(s.pressureRefreshes) / p;
  state.counters["visits/patch"] = double(s.visits) / p;
  state.counters["skipped/patch"] = double(s.skippedVisits) / p;
  state.counters["max_pressure_lag"] = s.maxPressureLag;
  state.counters["quick_sticks/patch"] = double(s.quickSticks) / p;
}

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
  if (variant == kEllipsoidal || variant == kExact) addSolverCounters(state, *w.patchSolver());
  state.SetLabel(variant == kEllipsoidal ? "patch ellipsoidal"
                 : variant == kExact     ? "patch exact"
                 : variant == kStock     ? "stock Bullet"
                                         : "PatchFrictionSolver, none opted in");
}
// Repeated kWorldStepRepetitions times, the repetitions of all variants
// interleaved in random order (main switches Google Benchmark's random
// interleaving on), and reported as aggregates with the fastest repetition
// ("_min"): the work is deterministic, so what varies between repetitions is
// the machine (single passes measured 'none opted in', which runs stock
// Bullet's code, at 0.94-1.26x stock). The ratios quoted in the README are
// of the _min rows.
constexpr int kWorldStepRepetitions = 5;
BENCHMARK(BM_BulletWorldStep)
    ->ArgsProduct({{10, 100, 1000}, {kStock, kNoneOptedIn, kEllipsoidal, kExact}})
    ->Repetitions(kWorldStepRepetitions)
    ->ComputeStatistics("min",
                        [](const std::vector<double>& v) {
                          return *std::min_element(v.begin(), v.end());
                        })
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

// The same sliding, spinning coins on a triangle mesh and on a heightfield
// of the plane (5 cm grid; issue 32: finding the coplanar triangles under a
// face must not cost more than Bullet's own narrowphase for the pair): N =
// 100, 1000; stock, ellipsoidal, exact; arg 2: 1 mesh, 2 heightfield.
void BM_CoinsOnTriangles(benchmark::State& state) {
  const int n = int(state.range(0));
  const Variant variant = Variant(state.range(1));
  SceneOptions opt;
  opt.ground = state.range(2) == 1 ? patchspin::scenes::Ground::TriangleMesh
                                   : patchspin::scenes::Ground::Heightfield;
  World w(n, variant, opt);
  long k = 0;
  for (auto _ : state) {
    if (++k % 24 == 0) w.reset();
    w.world->stepSimulation(btScalar(kDt), 0);
  }
  state.counters["bodies"] = n;
  if (variant == kEllipsoidal || variant == kExact) {
    addSolverCounters(state, *w.patchSolver());
    state.counters["not_patched"] = double(w.patchSolver()->stats().notPatched.total());
  }
  state.SetLabel(std::string(variant == kEllipsoidal ? "patch ellipsoidal"
                             : variant == kExact     ? "patch exact"
                                                     : "stock Bullet") +
                 (state.range(2) == 1 ? ", mesh" : ", heightfield"));
}
BENCHMARK(BM_CoinsOnTriangles)
    ->ArgsProduct({{100, 1000}, {kStock, kEllipsoidal, kExact}, {1, 2}})
    ->Repetitions(kWorldStepRepetitions)
    ->ComputeStatistics("min",
                        [](const std::vector<double>& v) {
                          return *std::min_element(v.begin(), v.end());
                        })
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

// ---- skip what a scene doesn't need (issue 6) ---------------------------------------
// 1000 sliding, spinning coins, ellipsoidal, with the solver's work-saving
// rules switched off one at a time: 0 default, 1 no skipping of settled
// patches, 2 Pi refreshed on every change of the centre of pressure, 3 both,
// 4 one refresh tolerance for every visit (no larger tolerance for a
// second refresh in the same step), 5 no quick stick test, 6 no deferred
// refreshes while sticking, 7 no settling on round-off.
void BM_SkipRules(benchmark::State& state) {
  SceneOptions opt;
  const int rules = int(state.range(0));
  // (1 and 2 combine into 3; 4, 5 and 6 are single rules)
  opt.settings.skipSettledPatches = !(rules == 1 || rules == 3);
  if (rules == 2 || rules == 3)
    opt.settings.pressureRefreshTolerance = opt.settings.pressureLagTolerance = 0.0;
  if (rules == 4) opt.settings.pressureLagTolerance = opt.settings.pressureRefreshTolerance;
  if (rules == 5) opt.settings.quickStick = false;
  if (rules == 6) opt.settings.deferStickingRefresh = false;
  if (rules == 7) opt.settings.settleOnRoundOff = false;
  World w(1000, kEllipsoidal, opt);
  long k = 0;
  for (auto _ : state) {
    if (++k % 24 == 0) w.reset();
    w.world->stepSimulation(btScalar(kDt), 0);
  }
  addSolverCounters(state, *w.patchSolver());
  state.SetLabel(rules == 0   ? "default"
                 : rules == 1 ? "no settled-patch skipping"
                 : rules == 2 ? "Pi refreshed on every change"
                 : rules == 3 ? "neither"
                 : rules == 4 ? "no second tolerance per step"
                 : rules == 5 ? "no quick stick test"
                 : rules == 6 ? "no deferred refreshes while sticking"
                              : "no settling on round-off");
}
BENCHMARK(BM_SkipRules)->DenseRange(0, 7)->Unit(benchmark::kMicrosecond);

// 1000 coins at rest on the plane (uniform pressure: Pi = I, never
// refreshed), awake: patch ellipsoidal / exact against stock; and the same
// with Pi refreshed on every change (round-off moves the centre of pressure).
void BM_RestingCoins(benchmark::State& state) {
  SceneOptions opt;
  opt.moving = false;
  const int variant = int(state.range(0));
  if (variant == 4) opt.settings.pressureRefreshTolerance = opt.settings.pressureLagTolerance = 0.0;
  World w(1000, variant == 4 ? kEllipsoidal : Variant(variant), opt);
  for (int k = 0; k < 24; ++k) w.world->stepSimulation(btScalar(kDt), 0);  // settle
  for (auto _ : state) w.world->stepSimulation(btScalar(kDt), 0);
  if (variant != kStock) addSolverCounters(state, *w.patchSolver());
  state.SetLabel(variant == kEllipsoidal ? "patch ellipsoidal"
                 : variant == kExact     ? "patch exact"
                 : variant == kStock     ? "stock Bullet"
                                         : "patch ellipsoidal, Pi refreshed on every change");
}
BENCHMARK(BM_RestingCoins)
    ->Arg(kStock)
    ->Arg(kEllipsoidal)
    ->Arg(kExact)
    ->Arg(4)
    ->Unit(benchmark::kMicrosecond);

// 1000 coins put to sleep by Bullet (deactivation allowed, at rest for > 2 s):
// patches of sleeping bodies cost nothing (their islands are not solved).
void BM_SleepingCoins(benchmark::State& state) {
  SceneOptions opt;
  opt.moving = false;
  opt.allowSleep = true;
  World w(1000, Variant(state.range(0)), opt);
  for (int k = 0; k < 720; ++k) w.world->stepSimulation(btScalar(kDt), 0);  // 3 s: asleep
  int sleeping = 0;
  for (const auto& c : w.coins) sleeping += c->getActivationState() == ISLAND_SLEEPING;
  for (auto _ : state) w.world->stepSimulation(btScalar(kDt), 0);
  state.counters["sleeping"] = sleeping;
  state.SetLabel(state.range(0) == kStock   ? "stock Bullet"
                 : state.range(0) == kExact ? "patch exact"
                                            : "patch ellipsoidal");
}
BENCHMARK(BM_SleepingCoins)
    ->Arg(kStock)
    ->Arg(kEllipsoidal)
    ->Arg(kExact)
    ->Unit(benchmark::kMicrosecond);

// The exact law only where a body asks for it: 1000 sliding coins with 0 %,
// 10 % and 100 % of them exact (the rest ellipsoidal).
void BM_ExactWhereAsked(benchmark::State& state) {
  SceneOptions opt;
  opt.exactFraction = double(state.range(0)) / 100.0;
  World w(1000, kEllipsoidal, opt);
  long k = 0;
  for (auto _ : state) {
    if (++k % 24 == 0) w.reset();
    w.world->stepSimulation(btScalar(kDt), 0);
  }
  state.counters["exact %"] = double(state.range(0));
  state.SetLabel(std::to_string(state.range(0)) + " % exact");
}
BENCHMARK(BM_ExactWhereAsked)->Arg(0)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace

// Google Benchmark's main, with random interleaving of the repetitions on
// unless the command line says otherwise.
int main(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  if (!patchspin::bench::initializeInterleaved(args)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
