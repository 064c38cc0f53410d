// The hand-back (issue 31, finding 8d): a heavy cube pushed along a tall
// light box until the light box tips over its edge; its ground patch goes
// back to Bullet's points while it pivots. Energy is balanced step by step:
// the change of kinetic and potential energy of both bodies less the push's
// work, against stock Bullet's in the same scene.
//
// Independent check: the energy balance itself (bodies' state only, no
// solver quantity) and stock Bullet's run.
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace patchspin {
namespace {

using scenes::Friction;

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

// Kinetic (Scene::kineticEnergy) plus potential energy of the two boxes [J].
double energy(const scenes::HeavyOnLight& h) {
  double potential = 0.0;
  for (const btRigidBody* b : {h.light, h.heavy})
    potential += kG * double(b->getCenterOfMassPosition().z()) / double(b->getInvMass());
  return h.scene->kineticEnergy() + potential;
}

// The largest energy gain in one step [J]: the push on the cube ramps from
// 0 to 0.5 M g over 2 s, until the light box tilts by 0.6 rad.
double worstGain(double ratio, Friction f) {
  scenes::HeavyOnLight h = scenes::makeHeavyOnLight(ratio, f);
  double worst = 0.0;
  for (int k = 0; k < 480; ++k) {
    const double push = 0.5 * ratio * kG * k / 480.0;
    const double e0 = energy(h);
    const double x0 = double(h.heavy->getCenterOfMassPosition().x());
    h.heavy->applyCentralForce(btVector3(btScalar(push), 0, 0));
    h.scene->step(kDt);
    const double work = push * (double(h.heavy->getCenterOfMassPosition().x()) - x0);
    worst = std::max(worst, energy(h) - e0 - work);
    if (std::acos(std::min(1.0, double(h.light->getWorldTransform().getBasis()[2][2]))) > 0.6)
      break;
  }
  return worst;
}

// 10:1: no step gains more than stock Bullet's worst (measured, float:
// ellipsoidal 0.0038 J, stock 0.0066 J; before the tipping clamp solved
// the pivot's corners, 0.025 J where the light box's ground patch formed
// again while it rocked, spinning it up to 1.4 rad/s).
TEST(HandBack, TenToOneGainsNoMoreThanStock) {
  const double stock = worstGain(10.0, Friction::Stock);
  for (const Friction f : {Friction::Ellipsoidal, Friction::Exact}) {
    const double patch = worstGain(10.0, f);
    std::printf("[hand-back 10:1] %s %.4g J, stock %.4g J\n", scenes::toString(f), patch, stock);
    EXPECT_LE(patch, stock) << scenes::toString(f);
  }
}

// 100:1 and 1000:1: open (docs/limitations.md). Measured, float, ellipsoidal:
// 0.57 J and 158 J against stock's 0.32 J and 0 J; at 1000:1 the cube's
// patch ends while the light box's ground patch holds it flat, and the
// cube on Bullet's points over it gains energy for several steps.
TEST(HandBack, DISABLED_HeavierRatiosGainNoMoreThanStock) {
  for (const double ratio : {100.0, 1000.0}) {
    const double stock = worstGain(ratio, Friction::Stock);
    for (const Friction f : {Friction::Ellipsoidal, Friction::Exact})
      EXPECT_LE(worstGain(ratio, f), stock) << ratio << " " << scenes::toString(f);
  }
}

}  // namespace
}  // namespace patchspin
