// Shared by the coin-pour stress tests (coin_pour_test, rolling_coin_trap_test,
// coin_overlap_census_test): the pour's coins (scenes::PourSpec), its length
// unit and Bullet solver settings, and what "at rest" means for a coin.
// Measurements behind these choices: docs/notes/coin_pour.md.
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "stress_scenes.hpp"

namespace patchspin::bullet::stress {

using scenes::PourSpec;
constexpr double kPourR = PourSpec::kR, kPourH = PourSpec::kH, kPourMass = PourSpec::kMass;
constexpr double kPourMargin = PourSpec::kMargin;
// A coin is at rest below 1 cm/s (|v| + R |omega|): coins leaning on others
// are Bullet point contacts, which settle more slowly than patches.
constexpr double kPourRestSpeed = 1e-2;

// World units per metre of the pour (PATCHSPIN_POUR_UNIT: dm or m; the
// default is dm in float Bullet, m in double). In metres float Bullet misses
// a third of the overlaps between cylinder coins and the pile boils
// (CoinOverlapsSeenByBulletCensus); double Bullet misses none in metres, and
// in decimetres tilted coins on the floor spin up.
constexpr double kDecimetres = 10.0;  // world units per metre
inline double pourUnit() {
  const char* unit = std::getenv("PATCHSPIN_POUR_UNIT");
  if (!unit || std::string(unit).empty()) return kDouble ? 1.0 : kDecimetres;
  if (std::string(unit) == "dm") return kDecimetres;
  if (std::string(unit) == "m") return 1.0;
  throw std::invalid_argument(std::string("PATCHSPIN_POUR_UNIT: expected dm or m, got '") + unit +
                              "'");
}

// PATCHSPIN_POUR_COIN=hull pours the hull coins (scenes::pourCoinShape).
inline bool pourHullCoins() {
  const char* coin = std::getenv("PATCHSPIN_POUR_COIN");
  if (!coin || std::string(coin).empty() || std::string(coin) == "cylinder") return false;
  if (std::string(coin) == "hull") return true;
  throw std::invalid_argument(std::string("PATCHSPIN_POUR_COIN: expected cylinder or hull, got '") +
                              coin + "'");
}

// Bullet's solver settings for the pour: its defaults (one friction
// direction per contact point, along the slip when the step starts) with
// the scenes' 10 iterations, or the strongest point contacts tried on the
// 1000-coin pile (two directions, SOLVER_USE_2_FRICTION_DIRECTIONS, and 50
// iterations).
struct PourSolver {
  bool twoFrictionDirections = false;
  int iterations = 10;
};
constexpr PourSolver kStrongPointContacts{true, 50};

}  // namespace patchspin::bullet::stress
