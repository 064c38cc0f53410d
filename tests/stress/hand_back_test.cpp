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
#include <limits>

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

// Round-off of one step's energy balance [J]: four ulps of btScalar in each
// body's height, times its weight (float, 1000:1: 5.8e-4 J; double 1e-12 J).
double roundOff(const scenes::HeavyOnLight& h) {
  double tol = 0.0;
  for (const btRigidBody* b : {h.light, h.heavy}) {
    const btScalar z = b->getCenterOfMassPosition().z();
    tol += 4.0 * kG / double(b->getInvMass()) *
           double(std::nextafter(z, std::numeric_limits<btScalar>::max()) - z);
  }
  return tol;
}

double tiltOf(const btRigidBody* b) {
  return std::acos(std::min(1.0, double(b->getWorldTransform().getBasis()[2][2])));
}

// One run: the push on the cube ramps from 0 to push M g over 2 s (push 0.5;
// 0: the stack at rest), until the light box tilts by 0.6 rad.
struct HandBackRun {
  double worst = 0.0;  // the largest energy gain in one step [J]
  int worstStep = -1;
  double roundOff = 0.0;  // of the energy balance at the start [J]
  // the balance's own arithmetic: three energies of up to |E| summed in
  // double, within 8 eps |E| (1000:1: ~2e-12 J)
  double arithmetic = 0.0;
  int tipStep = -1;                         // first step the light box turns faster than 1e-3 rad/s
  bool toppled = false;                     // the light box reached 0.6 rad
  double tiltLight = 0.0, tiltHeavy = 0.0;  // at the end [rad]
};
HandBackRun run(double ratio, Friction f, double push = 0.5) {
  scenes::HeavyOnLight h = scenes::makeHeavyOnLight(ratio, f);
  HandBackRun r;
  r.roundOff = roundOff(h);
  r.arithmetic = 8.0 * std::numeric_limits<double>::epsilon() * std::abs(energy(h));
  for (int k = 0; k < 480; ++k) {
    const double force = push * ratio * kG * k / 480.0;
    const double e0 = energy(h);
    const double x0 = double(h.heavy->getCenterOfMassPosition().x());
    h.heavy->applyCentralForce(btVector3(btScalar(force), 0, 0));
    h.scene->step(kDt);
    const double work = force * (double(h.heavy->getCenterOfMassPosition().x()) - x0);
    const double gain = energy(h) - e0 - work;
    if (gain > r.worst) r.worst = gain, r.worstStep = k;
    if (r.tipStep < 0 && double(h.light->getAngularVelocity().length()) > 1e-3) r.tipStep = k;
    r.tiltLight = tiltOf(h.light);
    r.tiltHeavy = tiltOf(h.heavy);
    if (r.tiltLight > 0.6) {
      r.toppled = true;
      break;
    }
  }
  return r;
}

// 10:1: no step gains more than stock Bullet's worst (measured, float:
// ellipsoidal and exact 0.0011 J, in the first steps' settling; stock
// 0.0066 J; before the tipping clamp solved the pivot's corners, 0.025 J
// where the light box's ground patch formed again while it rocked).
TEST(HandBack, TenToOneGainsNoMoreThanStock) {
  const double stock = run(10.0, Friction::Stock).worst;
  for (const Friction f : {Friction::Ellipsoidal, Friction::Exact}) {
    const double patch = run(10.0, f).worst;
    std::printf("[hand-back 10:1] %s %.4g J, stock %.4g J\n", scenes::toString(f), patch, stock);
    EXPECT_LE(patch, stock) << scenes::toString(f);
  }
}

// 100:1 and 1000:1 (issue 31, finding 8): the light box's ground patch
// pivots on its edge (kept as the edge's rows past the flatness limit) and
// the cube's patch is solved with that support held through its pivot
// rows, so nothing goes back to Bullet's points under the heavy cube.
// Measured worst steps, float, ellipsoidal and exact: 100:1 0.0013 J
// (stock 0.32 J), 1000:1 0.0014 J (stock 0 J: it crushes the light box
// within 23 steps, the cube only sinking). Before: 0.56 / 0.58 J and 158 J.
// At 1000:1 the bar is also the stack at rest (no push): in float it
// regains 1.3 mJ per step for its first 80 steps (the 1000 kg cube rises
// 9 ulps of its height a step, the same without the push and as it was
// before; none in double), and the round-off of the balance (roundOff).
// The pushed stack's creep step is compared with the resting one's to the
// balance's own arithmetic (the two differed by 6e-13 J, 3 eps of the
// stack's energy). In
// double the worst steps are 2.4e-18 J and 2.4e-17 J, stock's 0.38 J and 0;
// a hand-back under the cube gained 158 J in one step.
// And the physics: the stack tips as one body over the light box's far
// bottom edge, once the push's moment about it, 0.5 M g k / 480 x 0.25 m,
// passes the weight's, (M + m) g x 0.02 m: after step 76.9 (M = 1000 kg).
TEST(HandBack, HeavierRatiosGainNoMoreThanStock) {
  for (const double ratio : {100.0, 1000.0}) {
    const double stock = run(ratio, Friction::Stock).worst;
    for (const Friction f : {Friction::Ellipsoidal, Friction::Exact}) {
      const double resting = run(ratio, f, 0.0).worst;
      const HandBackRun r = run(ratio, f);
      std::printf(
          "[hand-back %g:1] %s %.4g J (step %d), at rest %.4g J, stock %.4g J; tips at "
          "step %d, end tilts %.3f / %.3f rad\n",
          ratio, scenes::toString(f), r.worst, r.worstStep, resting, stock, r.tipStep, r.tiltLight,
          r.tiltHeavy);
      EXPECT_LE(r.worst, std::max({stock, resting + r.arithmetic, r.roundOff}))
          << ratio << " " << scenes::toString(f);
      EXPECT_TRUE(r.toppled) << ratio << " " << scenes::toString(f);
      if (ratio == 1000.0) {
        const double tipStep = 480.0 * 0.02 * (ratio + 1.0) / (0.5 * 0.25 * ratio);
        EXPECT_GE(r.tipStep, tipStep - 1.0) << scenes::toString(f);
        EXPECT_LE(r.tipStep, tipStep + 5.0) << scenes::toString(f);
        EXPECT_LT(std::abs(r.tiltHeavy - r.tiltLight), 0.05) << scenes::toString(f);
      }
    }
  }
}

}  // namespace
}  // namespace patchspin
