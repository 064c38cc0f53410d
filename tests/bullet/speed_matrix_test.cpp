// The speed matrix's scenes (scenes/speed_matrix.hpp) measure what they
// name: in `slipping` every coin still slips at the end of the episode, in
// `to-rest` every coin under a patch law has stopped, and the pile lands
// and settles; the two stock variants are the same world (the A/A
// control); the broadphase scope restores Bullet's margin; bad cell names
// are refused. Independent check: the closed form of a sliding coin's
// stopping time, v0 / (mu g), the least any law can give (friction never
// exceeds mu m g).
#include <patchspin/scenes/speed_matrix.hpp>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <gtest/gtest.h>

namespace patchspin::scenes {
namespace {

void runEpisode(SpeedWorld& w, SpeedScene s) {
  for (int k = 0; k < episodeSteps(s); ++k) w.scene->world().stepSimulation(btScalar(kSpeedDt), 0);
}

// The slowest coin (1.2 m/s) needs at least 1.2 / (0.5 g) = 0.245 s to
// stop; the episode is 48 steps = 0.2 s.
TEST(SpeedMatrix, SlippingCoinsAllSlipToTheEnd) {
  EXPECT_LT(episodeSteps(SpeedScene::Slipping) * kSpeedDt, 1.2 / (PileSpec::kMu * 9.81));
  for (SpeedVariant v : {SpeedVariant::Stock, SpeedVariant::Ellipsoidal, SpeedVariant::Exact}) {
    SpeedWorld w = makeSpeedWorld({SpeedScene::Slipping, 30, SpeedBroadphase::Default}, v);
    runEpisode(w, SpeedScene::Slipping);
    EXPECT_EQ(speedOutcome(w).slippingFraction, 1.0) << toString(v);
    EXPECT_EQ(w.scene->world().getNumCollisionObjects(), 31);  // coins and the plane
  }
}

// Launched at most 0.5 m/s: stopped after at most ~0.1 s under the patch
// laws (coupled slip and spin stop together), at rest for the rest of the
// 0.5 s episode.
TEST(SpeedMatrix, CoinsToRestHaveStoppedUnderThePatchLaws) {
  for (SpeedVariant v : {SpeedVariant::Ellipsoidal, SpeedVariant::Exact}) {
    SpeedWorld w = makeSpeedWorld({SpeedScene::ToRest, 30, SpeedBroadphase::Default}, v);
    runEpisode(w, SpeedScene::ToRest);
    EXPECT_EQ(speedOutcome(w).slippingFraction, 0.0) << toString(v);
  }
}

TEST(SpeedMatrix, StockAndItsControlAreTheSameWorld) {
  const SpeedCell cell{SpeedScene::Pile, 20, SpeedBroadphase::Tight};
  SpeedWorld a = makeSpeedWorld(cell, SpeedVariant::Stock);
  SpeedWorld b = makeSpeedWorld(cell, SpeedVariant::StockControl);
  {
    const SpeedBroadphaseScope scope(cell.broadphase);
    runEpisode(a, cell.scene);
    runEpisode(b, cell.scene);
  }
  ASSERT_EQ(a.bodies.size(), 20u);
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    EXPECT_EQ(a.bodies[i]->getWorldTransform().getOrigin(),
              b.bodies[i]->getWorldTransform().getOrigin());
  // the pile has landed and settled: the 20 bodies start in two layers,
  // 16 at 5 cm and 4 at 15 cm, and end below 10 cm (at most two 4 cm boxes
  // high) with less than 1 mJ of kinetic energy each (a 50 g coin at
  // 0.2 m/s; a coin falling the 4.5 cm from its start gains 22 mJ)
  for (const btRigidBody* body : a.bodies)
    EXPECT_LT(double(body->getWorldTransform().getOrigin().z()), 0.1);
  EXPECT_LT(speedOutcome(a).kineticEnergyPerBody, 1e-3);
}

TEST(SpeedMatrix, BroadphaseScopeRestoresTheMargin) {
  const btScalar before = gDbvtMargin;
  {
    const SpeedBroadphaseScope scope(SpeedBroadphase::Tight);
    EXPECT_EQ(gDbvtMargin, btScalar(0.005));
  }
  EXPECT_EQ(gDbvtMargin, before);
}

TEST(SpeedMatrix, CellNamesAreParsedOrRefused) {
  const SpeedCell c = speedCellFromString("to-rest:100:tight");
  EXPECT_EQ(c.scene, SpeedScene::ToRest);
  EXPECT_EQ(c.n, 100);
  EXPECT_EQ(c.broadphase, SpeedBroadphase::Tight);
  for (const char* bad : {"pile", "pile:10", "heap:10:default", "pile:ten:default",
                          "pile:0:default", "pile:10x:default", "pile:10:loose"})
    EXPECT_THROW(speedCellFromString(bad), Error) << bad;
  EXPECT_EQ(speedVariantFromString("stock-control"), SpeedVariant::StockControl);
  EXPECT_THROW(speedVariantFromString("fast"), Error);
}

}  // namespace
}  // namespace patchspin::scenes
