// Frame invariance of the whole Bullet world (issue 30, item 5): a scene and
// the same scene under a seeded rigid transform of everything, gravity
// included, move alike. Positions and velocities are compared after mapping
// back to the original frame, patch reports in the body's frame (loads and
// wrench are in the patch frame, whose x axis is fixed in the moving body).
// Bullet itself is frame invariant only to round-off, so the tolerances are
// those of round-off grown over the run, per precision.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::Scene;

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr double kDt = 1.0 / 240.0;
constexpr int kSteps = 240;
// Bullet's own round-off differs between the frames (float 6e-8, double
// 1e-16 relative, on coordinates up to ~5 m) and grows over the run. The
// worst differences measured over the three transforms and both laws
// (float / double): position 1.4e-6 / 3.6e-15 m, orientation 2.5e-5 /
// 4.3e-14, velocity 3.4e-5 / 1.4e-13 m/s, loads and wrench 1.6e-5 / 4.6e-12
// of the body's weight, slip 1.7e-9 / 1.5e-18 m/s. The bounds leave 4-25x
// room above those and are far below any physical difference (a frame
// error in the patch frame or the inertia moves a body by millimetres).
constexpr double kPositionTol = kDouble ? 1e-13 : 1e-5;  // [m]
constexpr double kBasisTol = kDouble ? 1e-12 : 1e-4;     // rotation matrix entries [-]
constexpr double kVelocityTol = kDouble ? 1e-12 : 2e-4;  // [m/s], [rad/s]
constexpr double kReportTol = kDouble ? 1e-10 : 1e-4;    // of the body's weight (loads, wrench)
constexpr double kSlipTol = kDouble ? 1e-16 : 1e-8;      // [m/s]

using scenes::bt;

struct Trajectory {
  std::vector<btTransform> poses;    // per body, at the end, in the original frame
  std::vector<btVector3> v, w;       // per body, original frame
  std::vector<PatchReport> reports;  // at the end
};

// A coin sliding and spinning, a box sliding and spinning, a two-box stack
// sliding, on a large static box; everything under `frame` (identity: the
// original scene).
Trajectory runScene(Model model, const btTransform& frame) {
  Scene scene;
  scene.world().setGravity(frame.getBasis() * bt(0, 0, -9.81));
  btRigidBody* ground = scene.addStaticBox(bt(5, 5, 0.5), bt(0, 0, -0.5), 1.0);
  ground->setCenterOfMassTransform(frame * ground->getWorldTransform());
  std::vector<btRigidBody*> bodies;
  bodies.push_back(scene.addCylinder(0.05, 0.01, 0.2, bt(0, 0, 0.005), 0.5));
  bodies.push_back(scene.addBox(bt(0.08, 0.03, 0.02), 0.5, bt(0.4, 0, 0.02), 0.5));
  // the stack set down 0.2 mm into its supports: in contact from the first
  // step in every frame (where Bullet finds a touching contact at zero
  // depth is decided by round-off, so a stack set down exactly touching
  // starts differently in different frames)
  bodies.push_back(scene.addBox(bt(0.06, 0.06, 0.02), 0.4, bt(0, 0.5, 0.0198), 0.5));
  bodies.push_back(scene.addBox(bt(0.04, 0.04, 0.02), 1.0, bt(0, 0.5, 0.0596), 0.5));
  const btVector3 v[4] = {bt(0.5, 0, 0), bt(0.3, 0.2, 0), bt(0.4, 0, 0), bt(0.4, 0, 0)};
  const btVector3 w[4] = {bt(0, 0, 20), bt(0, 0, 8), bt(0, 0, 0), bt(0, 0, 3)};
  for (int i = 0; i < 4; ++i) {
    btRigidBody* b = bodies[std::size_t(i)];
    // (also the world inverse inertia and the interpolation transform)
    b->setCenterOfMassTransform(frame * b->getWorldTransform());
    b->setLinearVelocity(frame.getBasis() * v[i]);
    b->setAngularVelocity(frame.getBasis() * w[i]);
    scene.solver().enablePatchFriction(b, {model});
  }
  for (int s = 0; s < kSteps; ++s) scene.step(kDt);
  Trajectory r;
  const btTransform back = frame.inverse();
  for (const btRigidBody* b : bodies) {
    r.poses.push_back(back * b->getWorldTransform());
    r.v.push_back(back.getBasis() * b->getLinearVelocity());
    r.w.push_back(back.getBasis() * b->getAngularVelocity());
    const PatchReport* rep = scene.solver().findPatchReport(b);
    r.reports.push_back(rep ? *rep : PatchReport());
  }
  return r;
}

btTransform randomFrame(std::mt19937& rng) {
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const btQuaternion q(btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)));
  return btTransform(q.normalized(), bt(u(rng), u(rng), u(rng)));
}

void expectSameMotion(const Trajectory& a, const Trajectory& b) {
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    SCOPED_TRACE("body " + std::to_string(i));
    EXPECT_LT((a.poses[i].getOrigin() - b.poses[i].getOrigin()).length(), kPositionTol);
    for (int r = 0; r < 3; ++r)
      EXPECT_LT((a.poses[i].getBasis()[r] - b.poses[i].getBasis()[r]).length(), kBasisTol);
    EXPECT_LT((a.v[i] - b.v[i]).length(), kVelocityTol);
    EXPECT_LT((a.w[i] - b.w[i]).length(), kVelocityTol);
    const PatchReport& ra = a.reports[i];
    const PatchReport& rb = b.reports[i];
    ASSERT_EQ(ra.body != nullptr, rb.body != nullptr);
    if (!ra.body) continue;
    const double weight = std::abs(ra.loads.Pz);
    EXPECT_LT(std::abs(ra.loads.Pz - rb.loads.Pz), kReportTol * weight);
    EXPECT_LT(std::abs(ra.loads.Tx - rb.loads.Tx), kReportTol * weight);
    EXPECT_LT(std::abs(ra.loads.Ty - rb.loads.Ty), kReportTol * weight);
    EXPECT_LT((ra.Q - rb.Q).norm(), kReportTol * weight);
    EXPECT_LT((ra.slip - rb.slip).norm(), kSlipTol);
    EXPECT_EQ(ra.sticking, rb.sticking);
  }
}

TEST(FrameInvariance, TheWorldUnderThreeRigidTransformsMovesAlike) {
  for (const Model model : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(model));
    const Trajectory reference = runScene(model, btTransform::getIdentity());
    // every body is on a patch at the end (the reports are compared)
    for (const PatchReport& r : reference.reports) EXPECT_NE(r.body, nullptr);
    std::mt19937 rng(2024);
    for (int k = 0; k < 3; ++k) {
      SCOPED_TRACE("transform " + std::to_string(k));
      expectSameMotion(reference, runScene(model, randomFrame(rng)));
    }
  }
}

}  // namespace
}  // namespace patchspin::bullet
