// Tipping: a tall box stands below its tipping force and falls above it; a
// box kicked onto its edge pivots on its patch and falls back. Moved from
// patch_friction_solver_test.cpp.
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

// ---- tipping ------------------------------------------------------------------------
// Tall box 5 x 5 x 30 cm, 1 kg, mu 0.8 (no sliding: mu m g = 7.8 N), pushed
// at its centre of mass 15 cm up. It tips once F h > m g a / 2, i.e.
// F > m g (0.025 / 0.15) = 1.64 N. Below that it must stand still (patch
// held, no creep); above, the normal block's load leaves the admissible set
// and Bullet's point contacts let it fall over.
double tiltAfterPush(double force, double* drift) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  btRigidBody* box =
      scene.addBox(btVector3(0.025f, 0.025f, 0.15f), 1.0, btVector3(0, 0, 0.15f), 0.8);
  scene.solver().enablePatchFriction(box, {Model::Ellipsoidal});
  const btVector3 start = box->getWorldTransform().getOrigin();
  for (int k = 0; k < 480; ++k) {
    box->applyCentralForce(btVector3(btScalar(force), 0, 0));
    scene.step(kDt);
  }
  const btVector3 up = box->getWorldTransform().getBasis().getColumn(2);
  if (drift) *drift = double((box->getWorldTransform().getOrigin() - start).length());
  return std::acos(std::clamp(double(up.z()), -1.0, 1.0));
}

TEST(PatchFrictionSolver, TallBoxStandsBelowTippingForceAndFallsAbove) {
  double drift = 0;
  const double below = tiltAfterPush(1.2, &drift);
  const double above = tiltAfterPush(2.5, nullptr);
  std::printf("[tipping] tilt after 2 s: F = 1.2 N %.3e rad (drift %.3e m), F = 2.5 N %.3f rad\n",
              below, drift, above);
  EXPECT_LT(below, 1e-6);
  EXPECT_LT(drift, kCreepBound);
  EXPECT_GT(above, 0.5) << "the box should have tipped over";
}

// Re-entry: the same tall box kicked by 3 N for 0.1 s rises onto an edge (its
// load leaves the admissible set: the patch pivots on the edge, kept past
// the flatness limit as that edge's rows, issue 31), but without the energy
// to topple (it would need m g 2.07 mm = 0.020 J) it falls back onto its
// face: a report in every step, the box flat at the end (tilt below 1e-3
// rad, the rocking bound) and at rest. (Before, the tipped patch went back
// to Bullet's points for a cooldown and returned when flat.)
TEST(PatchFrictionSolver, TippedBoxPivotsOnItsPatchAndFallsBack) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  btRigidBody* box =
      scene.addBox(btVector3(0.025f, 0.025f, 0.15f), 1.0, btVector3(0, 0, 0.15f), 0.8);
  scene.solver().enablePatchFriction(box, {Model::Exact});
  int stepsWithoutPatch = 0, firstLost = -1, lastLost = -1;
  double maxTilt = 0.0;
  for (int k = 0; k < 960; ++k) {
    if (k < 24) box->applyCentralForce(btVector3(3.0f, 0, 0));
    scene.step(kDt);
    const btVector3 up = box->getWorldTransform().getBasis().getColumn(2);
    maxTilt = std::max(maxTilt, std::acos(std::clamp(double(up.z()), -1.0, 1.0)));
    if (!scene.solver().findPatchReport(box)) {
      ++stepsWithoutPatch;
      if (firstLost < 0) firstLost = k;
      lastLost = k;
    }
  }
  const btVector3 up = box->getWorldTransform().getBasis().getColumn(2);
  const double tilt = std::acos(std::clamp(double(up.z()), -1.0, 1.0));
  std::printf("[re-entry] max tilt %.3f rad; no patch in %d steps (%d..%d); final tilt %.2e rad\n",
              maxTilt, stepsWithoutPatch, firstLost, lastLost, tilt);
  EXPECT_GT(maxTilt, 0.02)
      << "the kick should raise the box onto its edge (beyond the flatness tolerance)";
  EXPECT_LT(maxTilt, std::atan(0.025 / 0.15)) << "the box must not topple";
  EXPECT_EQ(stepsWithoutPatch, 0) << "the box pivots on its patch's edge rows";
  ASSERT_NE(scene.solver().findPatchReport(box), nullptr)
      << "the patch must return once the box is flat";
  EXPECT_LT(lastLost, 900) << "the patch must be back well before the end";
  EXPECT_LT(tilt, kTiltBound);
  EXPECT_LT(box->getLinearVelocity().length(), 1e-3);
  EXPECT_LT(box->getAngularVelocity().length(), 1e-2);
}

// Two opted-in blocks stacked: the patch between them is the upper block's
// (findPatchReport(upper) finds it, standing on the lower block), whichever
// order Bullet lists the pair in; the lower block's own patch is on the

}  // namespace
}  // namespace patchspin::bullet
