// Restitution on a patch contact (issue 31, item 1): a box and a coin
// dropped flat onto a plane rebound with Bullet's combined restitution and
// velocity threshold (parts::restitutionBounce), and land and leave flat
// (no rocking).
//
// Independent check: the free flight's closed form: a body leaving at speed
// e v0, v0 = sqrt(2 g h), rises e^2 h.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::Scene;
using scenes::SolverKind;

constexpr double kG = 9.81;
constexpr double kDrop = 0.1;  // height of the lower face above the plane at release [m]

enum class Body { Box, Coin };

struct Bounce {
  double apex = 0.0;          // lower face's height at the top of the first rebound [m]
  double maxTilt = 0.0;       // largest angle of the body's z axis from the vertical [rad]
  long patchSteps = 0;        // steps with a patch report (patch solver)
  double mass = 0.0;          // [kg]
  double pointImpulse = 0.0;  // largest sum of the manifold points' normal impulses in a step [N s]
};

// The body released at rest, lower face kDrop above the plane; the ground's
// restitution is 1, so the combined restitution (Bullet's product) is e.
Bounce drop(SolverKind kind, Body body, double e, double dt) {
  Scene scene(kG, 10, kind);
  btRigidBody* ground = scene.addGroundPlane(1.0);
  ground->setRestitution(1);
  const double halfHeight = body == Body::Box ? 0.05 : 0.005;
  btRigidBody* b = body == Body::Box
                       ? scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 0, kDrop + halfHeight), 0.5)
                       : scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, kDrop + halfHeight), 0.5);
  b->setRestitution(btScalar(e));
  if (kind == SolverKind::Patch) scene.solver().enablePatchFriction(b, {Model::Exact});
  Bounce out;
  out.mass = 1.0 / double(b->getInvMass());
  bool rising = false;
  const int steps = int(std::ceil(1.0 / dt));
  for (int i = 0; i < steps; ++i) {
    scene.step(dt);
    const btTransform& tr = b->getWorldTransform();
    const double z = double(tr.getOrigin().z()) - halfHeight;
    const double vz = double(b->getLinearVelocity().z());
    const double cosTilt = std::clamp(double(tr.getBasis()[2][2]), -1.0, 1.0);
    out.maxTilt = std::max(out.maxTilt, std::acos(cosTilt));
    if (kind == SolverKind::Patch && scene.solver().findPatchReport(b)) ++out.patchSteps;
    double sum = 0.0;
    btDispatcher& d = *scene.world().getDispatcher();
    for (int k = 0; k < d.getNumManifolds(); ++k) {
      const btPersistentManifold* m = d.getManifoldByIndexInternal(k);
      for (int j = 0; j < m->getNumContacts(); ++j)
        sum += double(m->getContactPoint(j).getAppliedImpulse());
    }
    out.pointImpulse = std::max(out.pointImpulse, sum);
    if (vz > 0.0) rising = true;
    if (rising) out.apex = std::max(out.apex, z);
    if (rising && vz < 0.0) break;  // past the top of the first rebound
  }
  return out;
}

// The rebound's apex against the closed form e^2 h: within 10 % of it plus
// one step of travel at the rebound speed e v0 (the world's semi-implicit
// Euler step overshoots a ballistic apex by up to v dt / 2, and the apex is
// seen at step granularity; measured: -3.7 % to +2.2 % at dt <= 1/240 s,
// +27 % at 1/60 s with e = 0.3). The patch lands and leaves flat: no tilt at
// all. The first bounce is carried by Bullet's points (the landing puts the
// faces in contact; the bounce comes the step after). (Stock Bullet in the
// same drops, float: its corner points bounce one after another, the box and
// coin rock by 0.16-2.6 rad and some flip over, so its "rebound" is no flat
// rebound to compare with: docs/notes/2026-11-28-contact-features.md.)
TEST(Restitution, FlatDropReboundsToTheClosedFormWithoutRocking) {
  const double v0 = std::sqrt(2.0 * kG * kDrop);
  for (const Body body : {Body::Box, Body::Coin})
    for (const double e : {0.3, 0.8})
      for (const double dt : {1.0 / 60.0, 1.0 / 240.0, 1.0 / 1000.0}) {
        const Bounce patch = drop(SolverKind::Patch, body, e, dt);
        const double ideal = e * e * kDrop;
        const std::string what = std::string(body == Body::Box ? "box" : "coin") +
                                 " e=" + std::to_string(e) + " dt=" + std::to_string(dt);
        EXPECT_GT(patch.patchSteps, 0) << what;
        // the bounce's impulse, m e v0 at least, is on Bullet's points
        EXPECT_GE(patch.pointImpulse, 0.9 * patch.mass * e * v0) << what;
        EXPECT_NEAR(patch.apex, ideal, 0.1 * ideal + e * v0 * dt) << what;
        EXPECT_LE(patch.maxTilt, 1e-6) << what;
      }
}

// Below Bullet's velocity threshold nothing bounces: a box set down at 0.1 m/s
// (threshold 0.2 m/s) stays on the plane.
TEST(Restitution, NoBounceBelowBulletsVelocityThreshold) {
  Scene scene(kG, 10, SolverKind::Patch);
  btRigidBody* ground = scene.addGroundPlane(1.0);
  ground->setRestitution(1);
  btRigidBody* b = scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 0, 0.0502), 0.5);
  b->setRestitution(1);
  b->setLinearVelocity(bt(0, 0, -0.1));
  scene.solver().enablePatchFriction(b, {Model::Exact});
  double highest = 0.0;
  for (int i = 0; i < 120; ++i) {
    scene.step(1.0 / 240.0);
    highest = std::max(highest, double(b->getWorldTransform().getOrigin().z()) - 0.05);
  }
  EXPECT_LE(highest, 2e-4 + 1e-6);  // never above where it was set down
  EXPECT_NE(scene.solver().findPatchReport(b), nullptr);
}

}  // namespace
}  // namespace patchspin::bullet
