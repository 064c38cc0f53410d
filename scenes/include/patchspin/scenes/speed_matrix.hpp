// The speed matrix's scenes (issue 35; bench/bench_bullet_speed_matrix.cpp):
// each cell is a scene, a body count N and a broadphase setting, and each
// run of a cell builds a fresh world from the same seeded start and steps
// it for the scene's whole episode on its own trajectory (dt 1/240 s, 10
// solver iterations, sleeping disabled), so every solver pays for what its
// own motion makes (landing, settling, its own contacts).
//
//   slipping  N coins (the pile's: R 4 cm, H 1 cm, 50 g, mu 0.5) spread
//             0.8 m apart on a plane, launched at 1.2-1.5 m/s with 10-20
//             rad/s of spin; the 0.2 s episode ends before the fastest law
//             could stop one (v / (mu g) >= 0.24 s), and they never meet
//             (each travels at most 0.3 m)
//   to-rest   the same coins launched at 0.2-0.5 m/s with 2-10 rad/s: they
//             stop within about 0.1 s and lie at rest for the rest of the
//             0.5 s episode
//   pile      scenes::pileRain / addPile: coins and boxes rained into a
//             walled box, 1 s (landing, collisions, settling)
#pragma once

#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/scene.hpp>

#include <memory>
#include <string>
#include <vector>

namespace patchspin::scenes {

enum class SpeedScene { Slipping, ToRest, Pile };
// Stock, and StockControl (stock again: the A/A control that shows the
// machine's noise), the patch solver with no body opted in, every body
// ellipsoidal, every body exact.
enum class SpeedVariant { Stock, StockControl, NoneOptedIn, Ellipsoidal, Exact };
// Default: Bullet's btDbvtBroadphase as a world makes it (gDbvtMargin 5 cm).
// Tight: gDbvtMargin 5 mm (SpeedBroadphaseScope): the broadphase reports
// fewer pairs, stock costs less and the patch solver's share shows.
enum class SpeedBroadphase { Default, Tight };

struct SpeedCell {
  SpeedScene scene = SpeedScene::Slipping;
  int n = 10;
  SpeedBroadphase broadphase = SpeedBroadphase::Default;
};

const char* toString(SpeedScene s);
const char* toString(SpeedVariant v);
const char* toString(SpeedBroadphase b);
// Parses "slipping:100:tight" (scene:N:broadphase); Error on anything else.
SpeedCell speedCellFromString(const std::string& text);
SpeedVariant speedVariantFromString(const std::string& name);

// Steps in the scene's episode at dt = kSpeedDt.
inline constexpr double kSpeedDt = 1.0 / 240.0;
int episodeSteps(SpeedScene s);

// Sets Bullet's gDbvtMargin for the broadphase while it lives (the world
// must be built and stepped inside it), and restores the old value.
class SpeedBroadphaseScope {
 public:
  explicit SpeedBroadphaseScope(SpeedBroadphase b);
  ~SpeedBroadphaseScope();
  SpeedBroadphaseScope(const SpeedBroadphaseScope&) = delete;
  SpeedBroadphaseScope& operator=(const SpeedBroadphaseScope&) = delete;

 private:
  double saved_;
};

// A fresh world of the cell under the variant (built, not stepped).
struct SpeedWorld {
  std::unique_ptr<Scene> scene;
  std::vector<btRigidBody*> bodies;  // the N bodies
};
SpeedWorld makeSpeedWorld(const SpeedCell& cell, SpeedVariant v);

// What the episode did, to show that each cell measured what it names:
// the fraction of bodies slipping (centre speed above 1 mm/s or spin above
// 0.01 rad/s) and the kinetic energy per body [J] at the end.
struct SpeedOutcome {
  double slippingFraction = 0.0;
  double kineticEnergyPerBody = 0.0;
};
SpeedOutcome speedOutcome(const SpeedWorld& w);

}  // namespace patchspin::scenes
