// Reported impulses (issue 31, item 3): after each step a patch's impulses
// are on its manifold's points, Bullet's way (m_appliedImpulse,
// m_appliedImpulseLateral1/2 along m_lateralFrictionDir1/2), and sum to
// the patch's force and moments (internal::writeManifoldImpulses,
// parts::spreadPatchImpulse).
//
// Independent checks: Newton's second law on the body over the step (the
// weight m g dt of a body at rest; m dv of a sliding box, I_z dw of a
// spinning one: the only horizontal impulse or twist on it is the
// contact's), and the patch report.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::Scene;
using scenes::SolverKind;

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr double kG = 9.81, kDt = 1.0 / 240.0;
// The point impulses are the patch's, spread in double and stored as
// btScalar: their sums carry the scalar's round-off (float 6e-8 relative per
// value); Newton's law on the body adds the velocities' round-off (float:
// ~1e-7 m/s on 1 m/s, against impulses of ~0.01 N s on 1 kg).
constexpr double kSumRelTol = kDouble ? 1e-12 : 1e-6;
constexpr double kNewtonRelTol = kDouble ? 1e-9 : 2e-4;

// The points' impulses on `body` in world axes: force and couple about O
// (normal and lateral), from the manifold between body and the plane.
struct PointSums {
  int points = 0;
  double normal = 0.0;         // sum of m_appliedImpulse [N s]
  btVector3 lateral{0, 0, 0};  // on body [N s]
  btVector3 couple{0, 0, 0};   // of all point impulses on body about O [N m s]
};
PointSums pointSums(Scene& scene, const btCollisionObject* body, const btVector3& O) {
  PointSums s;
  btDispatcher& d = *scene.world().getDispatcher();
  for (int i = 0; i < d.getNumManifolds(); ++i) {
    const btPersistentManifold& m = *d.getManifoldByIndexInternal(i);
    if (m.getBody0() != body && m.getBody1() != body) continue;
    const double side = m.getBody0() == body ? 1.0 : -1.0;
    for (int k = 0; k < m.getNumContacts(); ++k) {
      const btManifoldPoint& p = m.getContactPoint(k);
      ++s.points;
      s.normal += double(p.m_appliedImpulse);
      const btVector3 f = btScalar(side) * (p.m_appliedImpulse * p.m_normalWorldOnB +
                                            p.m_appliedImpulseLateral1 * p.m_lateralFrictionDir1 +
                                            p.m_appliedImpulseLateral2 * p.m_lateralFrictionDir2);
      const btVector3 at = btScalar(0.5) * (p.m_positionWorldOnA + p.m_positionWorldOnB);
      s.lateral += f - f.dot(btVector3(0, 0, 1)) * btVector3(0, 0, 1);
      s.couple += (at - O).cross(f);
    }
  }
  return s;
}

// A body at rest on a plane or a static box: its points carry its weight.
TEST(ReportedImpulses, RestingBodysPointsCarryItsWeight) {
  for (const bool coin : {true, false})
    for (const bool plane : {true, false}) {
      Scene scene(kG, 10, SolverKind::Patch);
      if (plane)
        scene.addGroundPlane(1.0);
      else
        scene.addStaticBox(bt(1, 1, 0.1), bt(0, 0, -0.1), 1.0);
      const double mass = coin ? 0.02 : 1.0;
      btRigidBody* b = coin ? scene.addCylinder(0.05, 0.01, mass, bt(0, 0, 0.005), 0.5)
                            : scene.addBox(bt(0.05, 0.04, 0.03), mass, bt(0, 0, 0.03), 0.5);
      scene.solver().enablePatchFriction(b, {Model::Exact});
      for (int i = 0; i < 120; ++i) scene.step(kDt);
      const PatchReport* r = scene.solver().findPatchReport(b);
      ASSERT_NE(r, nullptr);
      const PointSums s = pointSums(scene, b, r->origin);
      const std::string what =
          std::string(coin ? "coin" : "box") + (plane ? " on plane" : " on box");
      if (s.points == 0) {
        // Bullet's convex-convex test misses a coin resting on a box face
        // (float: until ~2 mm in; the probe found the patch): no point to
        // carry the force, and the patch is counted as such
        EXPECT_TRUE(coin && !plane) << what;
        EXPECT_EQ(scene.solver().stats().patchesWithoutPoints, 1) << what;
        continue;
      }
      EXPECT_NEAR(s.normal, mass * kG * kDt, kSumRelTol * mass * kG * kDt) << what;
      EXPECT_NEAR(s.normal, r->loads.Pz * kDt, kSumRelTol * mass * kG * kDt) << what;
      EXPECT_EQ(scene.solver().stats().patchesWithoutPoints, 0) << what;
    }
}

// A box sliding without spin: the lateral point impulses sum to mu m g dt
// against the motion, which is the box's loss of momentum in the step.
TEST(ReportedImpulses, SlidingBoxsLateralImpulsesSumToCoulombFriction) {
  const double mu = 0.4, mass = 1.0;
  Scene scene(kG, 10, SolverKind::Patch);
  scene.addGroundPlane(1.0);
  btRigidBody* b = scene.addBox(bt(0.05, 0.04, 0.03), mass, bt(0, 0, 0.03), mu);
  scene.solver().enablePatchFriction(b, {Model::Exact});
  for (int i = 0; i < 10; ++i) scene.step(kDt);  // settled on the plane
  b->setLinearVelocity(bt(1.0, 0.5, 0));
  b->setAngularVelocity(bt(0, 0, 0));
  for (int i = 0; i < 5; ++i) {
    const btVector3 v0 = b->getLinearVelocity();
    scene.step(kDt);
    const PatchReport* r = scene.solver().findPatchReport(b);
    ASSERT_NE(r, nullptr);
    ASSERT_FALSE(r->sticking);
    const PointSums s = pointSums(scene, b, r->origin);
    const double coulomb = mu * mass * kG * kDt;
    EXPECT_NEAR(s.lateral.length(), coulomb, 1e-3 * coulomb);  // the exact law: mu Pz
    // mu Pz for a pure slide; the box picks up a spin ~1e-9 of its slide (the
    // pressure is not centred while it decelerates), which lowers the force
    // by that order (double: 1.3e-9 relative), far below 1e-6
    EXPECT_NEAR(s.lateral.length(), mu * s.normal, 1e-6 * coulomb);
    const btVector3 dp = btScalar(mass) * (b->getLinearVelocity() - v0);
    const btVector3 dpLateral(dp.x(), dp.y(), 0);
    EXPECT_NEAR((s.lateral - dpLateral).length(), 0.0, kNewtonRelTol * coulomb);
    EXPECT_LT(s.lateral.dot(v0), 0.0);
  }
}

// A box spinning in place on a static box (Bullet's box-box contact keeps
// four points; on a plane it often keeps one, which cannot carry a twist):
// the point impulses' twist about the normal is the patch's friction torque,
// and the box's loss of spin in the step.
TEST(ReportedImpulses, SpinningBoxsPointsCarryTheFrictionTorque) {
  const double mu = 0.4, mass = 1.0;
  Scene scene(kG, 10, SolverKind::Patch);
  scene.addStaticBox(bt(1, 1, 0.1), bt(0, 0, -0.1), 1.0);  // box-box: up to 4 points
  const btVector3 half = bt(0.05, 0.04, 0.03);
  btRigidBody* b = scene.addBox(half, mass, bt(0, 0, 0.03), mu);
  scene.solver().enablePatchFriction(b, {Model::Exact});
  for (int i = 0; i < 10; ++i) scene.step(kDt);
  b->setLinearVelocity(bt(0, 0, 0));
  b->setAngularVelocity(bt(0, 0, 6.0));
  const double Iz = mass * (double(half.x() * half.x()) + double(half.y() * half.y())) / 3.0;
  for (int i = 0; i < 5; ++i) {
    const double w0 = double(b->getAngularVelocity().z());
    scene.step(kDt);
    const PatchReport* r = scene.solver().findPatchReport(b);
    ASSERT_NE(r, nullptr);
    const PointSums s = pointSums(scene, b, r->origin);
    const double twist = double(s.couple.z());
    ASSERT_GE(s.points, 3);                           // a twist needs points off one line
    const double reported = r->rho * r->Q.z() * kDt;  // T_z dt
    EXPECT_NEAR(twist, reported, kSumRelTol * std::abs(reported) + 1e-12);
    EXPECT_LT(twist, 0.0);  // against the spin
    const double dL = Iz * (double(b->getAngularVelocity().z()) - w0);
    EXPECT_NEAR(twist, dL, kNewtonRelTol * std::abs(dL) * 10.0);
  }
}

// Bullet's contact callbacks still see an opted-in body's contact points.
int gAdded = 0, gProcessed = 0;
bool countAdded(btManifoldPoint&, const btCollisionObjectWrapper*, int, int,
                const btCollisionObjectWrapper*, int, int) {
  ++gAdded;
  return false;
}
bool countProcessed(btManifoldPoint&, void*, void*) {
  ++gProcessed;
  return false;
}
TEST(ReportedImpulses, ContactCallbacksKeepWorking) {
  for (const SolverKind kind : {SolverKind::Patch, SolverKind::Stock}) {
    gAdded = gProcessed = 0;
    const ContactAddedCallback added = gContactAddedCallback;
    const ContactProcessedCallback processed = gContactProcessedCallback;
    gContactAddedCallback = countAdded;
    gContactProcessedCallback = countProcessed;
    {
      Scene scene(kG, 10, kind);
      scene.addGroundPlane(1.0);
      btRigidBody* b = scene.addBox(bt(0.05, 0.04, 0.03), 1.0, bt(0, 0, 0.029), 0.5);
      b->setCollisionFlags(b->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      if (kind == SolverKind::Patch) scene.solver().enablePatchFriction(b, {Model::Exact});
      for (int i = 0; i < 30; ++i) scene.step(kDt);
      if (kind == SolverKind::Patch) {
        EXPECT_NE(scene.solver().findPatchReport(b), nullptr);
      }
    }
    gContactAddedCallback = added;
    gContactProcessedCallback = processed;
    EXPECT_GE(gAdded, 4);
    EXPECT_GE(gProcessed, 30);
  }
}

}  // namespace
}  // namespace patchspin::bullet
