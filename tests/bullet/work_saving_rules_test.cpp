// The solver's work-saving rules (settled patches skipped, lazy pressure
// refresh, quick stick tests, deferred refreshes) leave the motion as it is.
// Moved from patch_friction_solver_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bullet_scenes.hpp"

namespace patchspin::bullet {
namespace {

// behind, i.e. ~1e-6 of the travel and of the stopping time; 1e-4 leaves room
// for float round-off accumulated over ~250 steps (sqrt(250) * 6e-8 * 100).
TEST(PatchFrictionSolver, WorkSavingRulesDoNotChangeTheMotion) {
  double maxLag = 0.0;  // over every step of the run with the rules on
  auto run = [&maxLag](bool savings, double* stopTime, PatchSolverStats* stats) {
    Coin coin(true, Model::Exact);
    if (!savings) {
      PatchSolverSettings off{0.0, false, 0.0, false};
      off.deferStickingRefresh = false;
      off.settleOnRoundOff = false;
      coin.scene.solver().setSettings(off);
    }
    coin.body->setLinearVelocity(btVector3(0.5, 0.1, 0));
    coin.body->setAngularVelocity(btVector3(0, 0, 12));
    *stopTime = -1;
    for (int k = 0; k < 480 && *stopTime < 0; ++k) {
      coin.scene.step(kDt);
      if (savings) maxLag = std::max(maxLag, coin.scene.solver().stats().maxPressureLag);
      if (k == 10) *stats = coin.scene.solver().stats();
      if (coin.body->getLinearVelocity().length() < 1e-6 &&
          coin.body->getAngularVelocity().length() < 1e-5)
        *stopTime = (k + 1) * kDt;
    }
    return coin.body->getWorldTransform().getOrigin();
  };
  double tOn = 0, tOff = 0;
  PatchSolverStats sOn, sOff;
  const btVector3 pOn = run(true, &tOn, &sOn), pOff = run(false, &tOff, &sOff);
  std::printf(
      "[savings] stop %.5f s vs %.5f s; travel differs by %.2e m; solves/step %ld vs %ld, "
      "refreshes %ld vs %ld; "
      "largest pressure lag %.2e of the diameter\n",
      tOn, tOff, double((pOn - pOff).length()), sOn.blockSolves, sOff.blockSolves,
      sOn.pressureRefreshes, sOff.pressureRefreshes, maxLag);
  ASSERT_GT(tOn, 0.0);
  EXPECT_NEAR(tOn, tOff, 1.5 * kDt);  // same step, or the neighbour
  EXPECT_LT(double((pOn - pOff).length()), 1e-4 * double(pOn.length()));
  EXPECT_EQ(sOn.patches, 1);
  EXPECT_LT(sOn.blockSolves, sOff.blockSolves) << "the rules should save block solves";
  // a move beyond the second tolerance refreshes again in the same step
  // (the stop), so the friction law never lags by more than it
  EXPECT_LE(maxLag, PatchSolverSettings().pressureLagTolerance);
  // a coin at rest sticks by the quick test alone (no block solve) for both
  // laws; without the test the solver does the work
  for (Model model : {Model::Ellipsoidal, Model::Exact})
    for (bool quick : {true, false}) {
      Coin rest(true, model);
      PatchSolverSettings settings;
      settings.quickStick = quick;
      rest.scene.solver().setSettings(settings);
      for (int k = 0; k < 10; ++k) rest.scene.step(kDt);
      const PatchSolverStats& s = rest.scene.solver().stats();
      EXPECT_EQ(s.patches, 1);
      if (quick) {
        EXPECT_GE(s.quickSticks, 1) << int(model);
        EXPECT_EQ(s.blockSolves, 0) << int(model);
      } else {
        EXPECT_EQ(s.quickSticks, 0) << int(model);
        EXPECT_GE(s.blockSolves, 1) << int(model);
      }
      EXPECT_LT(double(rest.body->getLinearVelocity().length()), 1e-6) << int(model);
    }
  EXPECT_THROW(Coin(true).scene.solver().setSettings(PatchSolverSettings{-1e-6, true}), Error);
  EXPECT_THROW(Coin(true).scene.solver().setSettings(PatchSolverSettings{1e-6, true, -1e-3}),
               Error);
}

// The quick stick tests (the ellipsoid for the ellipsoidal law; for the
// exact law the bicone, the hull of the bicone with a law value, and the fan
// of tetrahedra between law values, see exactHullSticks) must never stick a
// block that the full solve lets slip.
// A box (exact law on a 10 x 10 cm square) on the floor gets a slowly
// growing twist and push, T_z = 0.1 t N m and F_x = 2 t N (the combined
// load reaches the limit set's boundary off the bicone), and breaks away at
// the same step with the quick tests as without them; with them it needs
// fewer block solves (7 against 671; 31 before the fan: near the limit the
// fan certifies what the hull could not).
TEST(PatchFrictionSolver, QuickStickTestsBreakAwayWhereTheSolveDoes) {
  auto run = [](bool quick, long* solves, long* quickSticks) {
    Scene scene(kG);
    scene.addGroundPlane(1.0);
    btRigidBody* box =
        scene.addBox(btVector3(0.05f, 0.05f, 0.025f), 1.0, btVector3(0, 0, 0.025f), 0.5);
    scene.solver().enablePatchFriction(box, {Model::Exact});
    PatchSolverSettings settings;
    settings.quickStick = quick;
    scene.solver().setSettings(settings);
    *solves = *quickSticks = 0;
    for (int k = 0; k < 480; ++k) {
      const double t = k * kDt;
      box->applyTorque(btVector3(0, 0, btScalar(0.1 * t)));
      box->applyCentralForce(btVector3(btScalar(2.0 * t), 0, 0));
      scene.step(kDt);
      *solves += scene.solver().stats().blockSolves;
      *quickSticks += scene.solver().stats().quickSticks;
      if (box->getLinearVelocity().length() > 1e-4f || box->getAngularVelocity().length() > 1e-3f)
        return k;
    }
    return -1;
  };
  long solvesOn = 0, solvesOff = 0, quickOn = 0, quickOff = 0;
  const int breakOn = run(true, &solvesOn, &quickOn), breakOff = run(false, &solvesOff, &quickOff);
  std::printf(
      "[quick stick] breakaway at step %d (quick tests) and %d (full solves); block solves %ld vs "
      "%ld, "
      "quick sticks %ld\n",
      breakOn, breakOff, solvesOn, solvesOff, quickOn);
  ASSERT_GT(breakOff, 0) << "the load should break the box away within 2 s";
  EXPECT_EQ(breakOn, breakOff);
  EXPECT_EQ(quickOff, 0);
  EXPECT_LT(solvesOn, solvesOff);
}

// Deferred refreshes (PatchSolverSettings::deferStickingRefresh): a patch
// that sticks deep inside its limit set keeps its law while the centre of
// pressure moves by up to 1e-2 of the diameter. The stick impulse does not
// depend on the law, so a settling scene must come out as with the rule off:
// an offset stack of three boxes (its centres of pressure move as the
// Gauss-Seidel iterations shift the load) beside a coin sliding to a stop.
// Bound: the rule changes which path certifies some sticks (quick test or
// block solve: -K^-1 b by two computations), a round-off difference
// (float: ~1e-7 of the impulse) that the settling scene damps; 1e-5 m is
// 100 times the float round-off of the 10 cm scene's positions.
constexpr double kDeferPositionTol = kDouble ? 1e-9 : 1e-5;

// The settling scene of the deferred-refresh and round-off tests: on a
// ground plane, an offset stack of three boxes (the middle one exact, the
// others ellipsoidal) beside a coin (exact) sliding and spinning to a stop;
// the bodies, the coin last.
std::vector<btRigidBody*> addSettlingScene(Scene& scene) {
  scene.addGroundPlane(1.0);
  std::vector<btRigidBody*> bodies;
  for (int i = 0; i < 3; ++i) {
    btRigidBody* b = scene.addBox(
        btVector3(0.08f, 0.06f, 0.03f), 1.0,
        btVector3(btScalar(0.025 * i), btScalar(-0.015 * i), btScalar(0.03 + 0.06 * i)), 0.6);
    scene.solver().enablePatchFriction(b, {i == 1 ? Model::Exact : Model::Ellipsoidal});
    bodies.push_back(b);
  }
  btRigidBody* coin =
      scene.addCylinder(kR, kH, kMass, btVector3(-0.5f, 0.3f, btScalar(kH / 2)), kMu);
  coin->setLinearVelocity(btVector3(0.6f, 0.1f, 0));
  coin->setAngularVelocity(btVector3(0, 0, 8));
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  bodies.push_back(coin);
  return bodies;
}

TEST(PatchFrictionSolver, DeferredRefreshesLeaveASettlingSceneAsItIs) {
  auto run = [](bool defer, PatchSolverStats* sum) {
    Scene scene(kG);
    const std::vector<btRigidBody*> bodies = addSettlingScene(scene);
    btRigidBody* coin = bodies.back();
    PatchSolverSettings settings;
    settings.deferStickingRefresh = defer;
    scene.solver().setSettings(settings);
    *sum = PatchSolverStats{};
    for (int k = 0; k < 480; ++k) {
      scene.step(kDt);
      const PatchSolverStats& st = scene.solver().stats();
      sum->pressureRefreshes += st.pressureRefreshes;
      sum->deferredRefreshes += st.deferredRefreshes;
      sum->blockErrors += st.blockErrors;
    }
    std::vector<btVector3> out;
    for (btRigidBody* b : bodies) out.push_back(b->getWorldTransform().getOrigin());
    out.push_back(coin->getLinearVelocity());
    return out;
  };
  PatchSolverStats on, off;
  const auto a = run(true, &on), b = run(false, &off);
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    worst = std::max(worst, double((a[i] - b[i]).length()));
  std::printf(
      "[defer] refreshes %ld with the rule (%ld deferred) vs %ld without; positions differ by %.2e "
      "m\n",
      on.pressureRefreshes, on.deferredRefreshes, off.pressureRefreshes, worst);
  EXPECT_EQ(off.deferredRefreshes, 0);
  EXPECT_GT(on.deferredRefreshes, 0);
  EXPECT_LT(on.pressureRefreshes, off.pressureRefreshes);
  EXPECT_EQ(on.blockErrors, 0);
  EXPECT_LT(worst, kDeferPositionTol);
  EXPECT_LT(double(a.back().length()), 1e-3);  // the coin has stopped
}

// Settling on round-off (PatchSolverSettings::settleOnRoundOff, float
// Bullet; in double it changes nothing, bit for bit): a visit whose change
// lies within the friction block's precision of the patch's normal impulse
// is not applied, and the patch settles.
//  * A coin sliding and spinning on a plane (both laws) then takes two
//    visits per step, the one that solves and the one that finds nothing
//    left; without the rule the second often applied a change of ~1e-12
//    of its impulse and a third visit was needed (88 and 92 visits in 40
//    steps against 81, float).
//  * The dropped changes are round-off: the settling scene of the test
//    above (an offset stack of three boxes beside a coin sliding to a stop,
//    480 steps) comes out as with the rule off, to kDeferPositionTol (the
//    same round-off argument: the two runs differ by changes of ~1e-9 of
//    the impulses in float, 1e-12 in double, which the settling damps).
TEST(PatchFrictionSolver, SettlingOnRoundOffSavesAVisitAndKeepsTheMotion) {
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    long real[2] = {0, 0};
    int mostOn = 0;
    btVector3 end[2];
    for (bool rule : {true, false}) {
      Coin coin(true, model);
      PatchSolverSettings settings;
      settings.settleOnRoundOff = rule;
      coin.scene.solver().setSettings(settings);
      coin.scene.step(kDt);
      for (int k = 0; k < 40; ++k) {
        coin.body->setLinearVelocity(btVector3(0.3f, 0.1f, coin.body->getLinearVelocity().z()));
        coin.body->setAngularVelocity(btVector3(0, 0, 8));
        coin.scene.step(kDt);
        const PatchSolverStats& st = coin.scene.solver().stats();
        ASSERT_EQ(st.patches, 1);
        const int visits = int(st.visits - st.skippedVisits);
        real[rule ? 0 : 1] += visits;
        // (the first step starts the slide from rest, its warm start far
        // off: it takes three)
        if (rule && k > 0) mostOn = std::max(mostOn, visits);
      }
      end[rule ? 0 : 1] = coin.body->getWorldTransform().getOrigin();
    }
    std::printf("[round-off] %s: %ld visits in 40 steps with the rule, %ld without\n",
                model == Model::Exact ? "exact" : "ellipsoidal", real[0], real[1]);
    if (kDouble) {  // no effect in double: bit for bit
      EXPECT_EQ(real[0], real[1]) << int(model);
      EXPECT_EQ(end[0], end[1]) << int(model);
      continue;
    }
    EXPECT_LE(mostOn, 2) << int(model);
    EXPECT_LT(real[0], real[1]) << int(model);
    EXPECT_LT(double((end[0] - end[1]).length()), kDeferPositionTol) << int(model);
  }
  auto run = [](bool rule, long* visits) {
    Scene scene(kG);
    const std::vector<btRigidBody*> bodies = addSettlingScene(scene);
    PatchSolverSettings settings;
    settings.settleOnRoundOff = rule;
    scene.solver().setSettings(settings);
    *visits = 0;
    for (int k = 0; k < 480; ++k) {
      scene.step(kDt);
      *visits += scene.solver().stats().visits - scene.solver().stats().skippedVisits;
    }
    std::vector<btVector3> out;
    for (btRigidBody* b : bodies) out.push_back(b->getWorldTransform().getOrigin());
    return out;
  };
  long on = 0, off = 0;
  const auto a = run(true, &on), b = run(false, &off);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, double((a[i] - b[i]).length()));
  std::printf(
      "[round-off] settling scene: %ld visits with the rule, %ld without; positions "
      "differ by %.2e m\n",
      on, off, worst);
  if (kDouble) {
    EXPECT_EQ(on, off);
    EXPECT_EQ(worst, 0.0);
  } else {
    EXPECT_LT(on, off);
    EXPECT_LT(worst, kDeferPositionTol);
  }
}

}  // namespace
}  // namespace patchspin::bullet
