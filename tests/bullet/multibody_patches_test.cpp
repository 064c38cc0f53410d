// PatchMultiBodySolver in a btMultiBodyDynamicsWorld (issue 33): patches
// on Featherstone links against the ground, a rigid body and another link,
// each against an independent prediction and, where there is one, the
// rigid-body twin under PatchFrictionSolver; stock Bullet's figure printed
// beside ours. Scenes: scenes/multibody_scene.hpp, scenes/grasp.hpp.
#include <patchspin/bullet/patch_multibody_solver.hpp>
#include <patchspin/scenes/grasp.hpp>
#include <patchspin/scenes/multibody_scene.hpp>
#include <patchspin/scenes/scene.hpp>
#include <patchspin/scenes/turn_angle.hpp>

#include "closed_forms.hpp"
#include "oracle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::MultiBodyScene;
using scenes::Scene;

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);
constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

// ---- the free thin disk under uniform pressure (closed_forms.hpp) ----------
// A uniform disk (J = m R^2 / 2) sliding at v = eps R omega keeps eps where
// the relative decelerations agree: the force is mu m g P(eps), the torque
// mu m g (2R/3) T(eps) (P, T of Eq. (52)-(53), T(0) = 1), so
//   P(eps) / eps = (4/3) T(eps),
// and while it is kept v falls at mu g P(eps): the disk stops at
//   t = eps R omega0 / (mu g P(eps)).
struct DiskLimit {
  double eps, stopCoefficient;
};
DiskLimit diskLimit() {
  auto f = [](double e) {
    return testing::uniformDiskForce(e) / e - 4.0 / 3.0 * testing::uniformDiskTorque(e);
  };
  double a = 0.5, b = 0.8;
  const bool fa = f(a) > 0;
  for (int k = 0; k < 50; ++k) {
    const double m = 0.5 * (a + b);
    ((f(m) > 0) == fa ? a : b) = m;
  }
  const double eps = 0.5 * (a + b);
  return {eps, eps / testing::uniformDiskForce(eps)};
}

// The thin coin of simulate_test (R = 5 cm, 0.2 mm thick: its centre of
// mass 0.1 mm above the patch tilts the pressure by a negligible 0.2 %),
// 1 kg, mu = 0.3 on a ground of friction 1, exact law, spun at omega0 and
// sliding at the limit ratio.
constexpr double kR = 0.05, kH = 2e-4, kMass = 1.0, kMu = 0.3, kOmega0 = 60.0;

struct CoinRun {
  bool stopped = false;
  double tStop = 0.0;  // first step end with slip below kStopFraction of the start's
  double eps = 0.0;    // v / (R omega) when the slip first fell below kRecordAt of it
};
constexpr double kStopFraction = 1e-5, kRecordAt = 0.1;

// Runs `step` until the slip |(v, R omega)| falls below kStopFraction of its
// start (at most 3 s); `observe` gives the planar speed and spin.
CoinRun runCoin(const std::function<void()>& step,
                const std::function<void(double& v, double& w)>& observe) {
  CoinRun run;
  double v, w;
  observe(v, w);
  const double r0 = std::hypot(v, kR * w);
  bool recorded = false;
  for (int k = 1; k <= int(3.0 / kDt); ++k) {
    step();
    observe(v, w);
    const double r = std::hypot(v, kR * w);
    if (!recorded && r < kRecordAt * r0) {
      recorded = true;
      run.eps = v / (kR * std::abs(w));
    }
    if (r < kStopFraction * r0) {
      run.stopped = true;
      run.tStop = k * kDt;
      break;
    }
  }
  return run;
}

CoinRun rigidCoin(double eps, bool patch) {
  Scene scene(kG, 10, patch ? scenes::SolverKind::Patch : scenes::SolverKind::Stock);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(kR, kH, kMass, bt(0, 0, kH / 2), kMu);
  if (patch) scene.solver().enablePatchFriction(coin, {Model::Exact});
  coin->setLinearVelocity(bt(eps * kR * kOmega0, 0, 0));
  coin->setAngularVelocity(bt(0, 0, kOmega0));
  return runCoin([&] { scene.step(kDt); },
                 [&](double& v, double& w) {
                   const btVector3 u = coin->getLinearVelocity();
                   v = std::hypot(double(u.x()), double(u.y()));
                   w = double(coin->getAngularVelocity().z());
                 });
}

// The rigid coin in a multibody world (PatchMultiBodySolver's patches
// between solver bodies).
CoinRun rigidCoinAmongLinks(double eps) {
  MultiBodyScene scene(kG, 10, true);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(kR, kH, kMass, bt(0, 0, kH / 2), kMu);
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  coin->setLinearVelocity(bt(eps * kR * kOmega0, 0, 0));
  coin->setAngularVelocity(bt(0, 0, kOmega0));
  return runCoin([&] { scene.step(kDt); },
                 [&](double& v, double& w) {
                   const btVector3 u = coin->getLinearVelocity();
                   v = std::hypot(double(u.x()), double(u.y()));
                   w = double(coin->getAngularVelocity().z());
                 });
}

CoinRun multiBodyCoin(double eps, bool patch) {
  MultiBodyScene scene(kG, 10, patch);
  scene.addGroundPlane(1.0);
  btMultiBody* coin = scene.addCylinderBase(kR, kH, kMass, bt(0, 0, kH / 2), kMu);
  if (patch) scene.solver().enablePatchFriction(coin->getBaseCollider(), {Model::Exact});
  coin->setBaseVel(bt(eps * kR * kOmega0, 0, 0));
  coin->setBaseOmega(bt(0, 0, kOmega0));
  return runCoin([&] { scene.step(kDt); },
                 [&](double& v, double& w) {
                   const btVector3 u = coin->getBaseVel();
                   v = std::hypot(double(u.x()), double(u.y()));
                   w = double(coin->getBaseOmega().z());
                 });
}

// The closed form's limit ratio is the literature's (Farkas et al. 2003:
// 0.6530; stop coefficient 1.0600, simulate_test's quadrature) to its 4
// digits.
TEST(MultiBodyPatches, DiskOracleIsTheLiteraturesLimit) {
  const DiskLimit d = diskLimit();
  EXPECT_NEAR(d.eps, 0.6530, 5e-4);
  EXPECT_NEAR(d.stopCoefficient, 1.0600, 5e-4);
}

// A rigid coin in a multibody world moves as in an ordinary one: the same
// patch, Bullet's rows around it built by btMultiBodyConstraintSolver.
// (Same steps, same tolerance as below.)
TEST(MultiBodyPatches, RigidCoinAmongLinksStopsAsInAnOrdinaryWorld) {
  const DiskLimit d = diskLimit();
  const CoinRun among = rigidCoinAmongLinks(d.eps);
  const CoinRun rb = rigidCoin(d.eps, true);
  std::printf("[rigid coin, %s] multibody world t_stop %.4f s eps %.4f; ordinary %.4f s eps %.4f\n",
              kDouble ? "double" : "float", among.tStop, among.eps, rb.tStop, rb.eps);
  ASSERT_TRUE(among.stopped);
  ASSERT_TRUE(rb.stopped);
  EXPECT_NEAR(among.tStop, rb.tStop, 0.02 * rb.tStop);
  EXPECT_NEAR(among.eps, rb.eps, 0.03);
}

// A stack of rigid blocks in a multibody world: the upper one (2 kg) slides
// and spins on the lower (1 kg), which stands on the ground; both opted
// in. The patches are PatchFrictionSolver's, the stack held as there
// (stackHolds), so the blocks move as in an ordinary world: bit for bit,
// as both worlds hand the same manifolds over in the same order and no
// other row takes part (the same arithmetic in the same order).
TEST(MultiBodyPatches, RigidStackAmongLinksMovesAsInAnOrdinaryWorld) {
  const btVector3 lowerHalf = bt(0.1, 0.1, 0.05), upperHalf = bt(0.05, 0.05, 0.03);
  Scene plain(kG);
  MultiBodyScene among(kG, 10, true);
  plain.addGroundPlane(1.0);
  among.addGroundPlane(1.0);
  btRigidBody* bodies[2][2] = {{plain.addBox(lowerHalf, 1.0, bt(0, 0, 0.05), 0.5),
                                plain.addBox(upperHalf, 2.0, bt(0, 0, 0.13), 0.5)},
                               {among.addBox(lowerHalf, 1.0, bt(0, 0, 0.05), 0.5),
                                among.addBox(upperHalf, 2.0, bt(0, 0, 0.13), 0.5)}};
  for (btRigidBody* b : bodies[0]) plain.solver().enablePatchFriction(b, {Model::Exact});
  for (btRigidBody* b : bodies[1]) among.solver().enablePatchFriction(b, {Model::Exact});
  for (int w = 0; w < 2; ++w) {
    bodies[w][1]->setLinearVelocity(bt(0.3, 0, 0));
    bodies[w][1]->setAngularVelocity(bt(0, 0, 4.0));
  }
  double worst = 0.0;
  long holds = 0;
  for (int k = 0; k < int(1.0 / kDt); ++k) {
    plain.step(kDt);
    among.step(kDt);
    holds += among.solver().stats().stackHolds;
    for (int i = 0; i < 2; ++i)
      worst = std::max(worst, double((bodies[0][i]->getWorldTransform().getOrigin() -
                                      bodies[1][i]->getWorldTransform().getOrigin())
                                         .length()));
  }
  std::printf("[rigid stack, %s] largest position difference %.3e m, stack holds %ld\n",
              kDouble ? "double" : "float", worst, holds);
  EXPECT_GT(holds, 0);
  EXPECT_EQ(worst, 0.0);
}

// A floating-base multibody coin (no links, its base collider a cylinder)
// slides and spins to rest as the rigid coin under PatchFrictionSolver:
// the same law through the base's Jacobian instead of the solver body.
// Tolerances: the (stop time 2 %, ratio 0.03) between the two; to
// the closed form, simulate_test's (2 %, 0.01 plus the 0.2 % pressure
// tilt of the 0.2 mm coin, which the 0.03 covers).
TEST(MultiBodyPatches, FloatingBaseCoinStopsAsTheRigidCoin) {
  const DiskLimit d = diskLimit();
  const double tClosed = d.stopCoefficient * kR * kOmega0 / (kMu * kG);
  const CoinRun mb = multiBodyCoin(d.eps, true);
  const CoinRun rb = rigidCoin(d.eps, true);
  const CoinRun stock = multiBodyCoin(d.eps, false);
  std::printf(
      "[coin, %s] multibody t_stop %.4f s eps %.4f; rigid t_stop %.4f s eps %.4f; closed form "
      "%.4f s eps %.4f; stock multibody: %s after 3 s (eps %.4f)\n",
      kDouble ? "double" : "float", mb.tStop, mb.eps, rb.tStop, rb.eps, tClosed, d.eps,
      stock.stopped ? "stopped" : "still moving", stock.eps);
  ASSERT_TRUE(mb.stopped);
  ASSERT_TRUE(rb.stopped);
  EXPECT_NEAR(mb.tStop, rb.tStop, 0.02 * rb.tStop);
  EXPECT_NEAR(mb.eps, rb.eps, 0.03);
  EXPECT_NEAR(mb.tStop, tClosed, 0.02 * tClosed);
  EXPECT_NEAR(mb.eps, d.eps, 0.03);
}

// ---- a box on a platform link driven by a prismatic joint ----------------
// The platform (a 1 x 0.6 x 0.04 m box link, 2 kg) slides along x at
// V = 1 m/s, held there by its velocity motor (at most 200 N against the
// box's 4.9 N); a 1 kg box (mu = 0.5) set on it at rest slips, is
// accelerated at mu g until it has the platform's speed at t* = V / (mu g),
// and then rides along without creeping. Box: a rigid body (patch between
// a rigid body and a link) or a floating-base multibody (two links).
constexpr double kV = 1.0, kBoxMu = 0.5;
const btVector3 kBoxHalf(btScalar(0.05), btScalar(0.04), btScalar(0.03));

struct PlatformRun {
  double vHalf = 0.0;     // box speed at t* / 2 [m/s]
  double vEnd = 0.0;      // box speed 0.1 s after t*
  double creep = 0.0;     // box's drift relative to the platform over 1 s after that [m]
  double reportPz = 0.0;  // the box's patch's normal load at the end [N]
  bool reportOnPlatform = false;
};

PlatformRun runPlatform(bool patch, bool boxIsMultiBody) {
  MultiBodyScene scene(kG, 10, patch);
  const MultiBodyScene::Prismatic platform =
      scene.addPrismaticBox(bt(0.5, 0.3, 0.02), 2.0, bt(0, 0, -0.02), 1.0, kV, 200.0);
  btRigidBody* rigid = nullptr;
  btMultiBody* based = nullptr;
  const btVector3 start = bt(0, 0, double(kBoxHalf.z()));
  btCollisionObject* box;
  if (boxIsMultiBody) {
    based = scene.addBoxBase(kBoxHalf, 1.0, start, kBoxMu);
    box = based->getBaseCollider();
  } else {
    rigid = scene.addBox(kBoxHalf, 1.0, start, kBoxMu);
    box = rigid;
  }
  if (patch) scene.solver().enablePatchFriction(box, {Model::Exact});
  auto boxX = [&] {
    return double(rigid ? rigid->getWorldTransform().getOrigin().x() : based->getBasePos().x());
  };
  auto boxV = [&] {
    return double(rigid ? rigid->getLinearVelocity().x() : based->getBaseVel().x());
  };
  const double tStar = kV / (kBoxMu * kG);
  const int half = int(std::lround(0.5 * tStar / kDt));
  const int settled = int(std::lround((tStar + 0.1) / kDt));
  PlatformRun run;
  double rel0 = 0.0;
  for (int k = 1; k <= settled + int(1.0 / kDt); ++k) {
    scene.step(kDt);
    if (k == half) run.vHalf = boxV();
    if (k == settled) {
      run.vEnd = boxV();
      rel0 = boxX() - double(platform.body->getJointPos(0));
    }
  }
  run.creep = std::abs(boxX() - double(platform.body->getJointPos(0)) - rel0);
  if (patch) {
    const PatchReport* r = scene.solver().findPatchReport(box);
    if (r) {
      run.reportPz = r->loads.Pz;
      run.reportOnPlatform = r->other == MultiBodyScene::collider(platform.body, 0);
    }
  }
  return run;
}

// The box's speed while it slips is mu g t (2 %: the implicit step's first
// order error over ~25 steps is below 0.5 %); afterwards it has the
// platform's, and its drift on the platform over 1 s stays below the creep
// bound of bullet_scenes.hpp (1e-5 m float, 1e-6 m double).
void expectRidesAlong(const PlatformRun& run, const char* what) {
  const double tStar = kV / (kBoxMu * kG);
  const double tHalf = std::lround(0.5 * tStar / kDt) * kDt;
  EXPECT_NEAR(run.vHalf, kBoxMu * kG * tHalf, 0.02 * kBoxMu * kG * tHalf) << what;
  EXPECT_NEAR(run.vEnd, kV, 1e-4) << what;
  EXPECT_LT(run.creep, kDouble ? 1e-6 : 1e-5) << what;
  EXPECT_TRUE(run.reportOnPlatform) << what;
  EXPECT_NEAR(run.reportPz, 1.0 * kG, 1e-3 * kG) << what;
}

TEST(MultiBodyPatches, RigidBoxRidesAPrismaticPlatform) {
  const PlatformRun patch = runPlatform(true, false);
  const PlatformRun stock = runPlatform(false, false);
  std::printf(
      "[rigid box on platform, %s] v(t*/2) %.5f (closed form %.5f), v_end %.6f, creep %.2e m, "
      "Pz %.5f N; stock: v(t*/2) %.5f, v_end %.6f, creep %.2e m\n",
      kDouble ? "double" : "float", patch.vHalf,
      kBoxMu * kG * std::lround(0.5 * kV / (kBoxMu * kG) / kDt) * kDt, patch.vEnd, patch.creep,
      patch.reportPz, stock.vHalf, stock.vEnd, stock.creep);
  expectRidesAlong(patch, "rigid box");
}

TEST(MultiBodyPatches, MultiBodyBoxRidesAPrismaticPlatform) {
  const PlatformRun patch = runPlatform(true, true);
  const PlatformRun stock = runPlatform(false, true);
  std::printf(
      "[multibody box on platform, %s] v(t*/2) %.5f, v_end %.6f, creep %.2e m, Pz %.5f N; "
      "stock: v(t*/2) %.5f, v_end %.6f, creep %.2e m\n",
      kDouble ? "double" : "float", patch.vHalf, patch.vEnd, patch.creep, patch.reportPz,
      stock.vHalf, stock.vEnd, stock.creep);
  expectRidesAlong(patch, "multibody box");
}

// Two links of one multibody: a block (1 kg, on a spherical joint on a
// 0.1 kg vertical slider: it may sink, tilt and turn, not slide) stands on
// a table link (on a carriage along y) that a motor drives along x at
// 1 m/s; block friction 0.5, table 1. The block's patch on the table takes
// both links' rows, J_A - J_B of one multibody: it carries the block and
// slider, Pz = 1.1 g, and
// rubs with the kinetic friction mu Pz against the slip (1e-3 relative:
// a steady slide, the law's force exactly mu Pz).
TEST(MultiBodyPatches, BlockSlidesOnATableLinkOfItsOwnMultiBody) {
  MultiBodyScene scene(kG, 10, true);
  btMultiBody* body =
      scene.addBlockOverTable(bt(0.5, 0.3, 0.02), 2.0, kBoxHalf, 1.0, 0.1, kV, 200.0, 1.0);
  btMultiBodyLinkCollider* block = MultiBodyScene::collider(body, 3);
  btMultiBodyLinkCollider* table = MultiBodyScene::collider(body, 1);
  block->setFriction(btScalar(kBoxMu));
  scene.solver().enablePatchFriction(block, {Model::Exact});
  // (0.2 s: the table moves 0.2 m, the block stays 0.25 m off its edge)
  for (int k = 0; k < int(0.2 / kDt); ++k) scene.step(kDt);
  const PatchReport* r = scene.solver().findPatchReport(block);
  ASSERT_NE(r, nullptr);
  const double friction = std::hypot(r->Q.x(), r->Q.y());
  std::printf(
      "[block on its own table, %s] Pz %.5f N (1.1 g = %.5f), friction %.5f N "
      "(mu Pz %.5f), sticking %d, table at %.4f m\n",
      kDouble ? "double" : "float", r->loads.Pz, 1.1 * kG, friction, kBoxMu * r->loads.Pz,
      int(r->sticking), double(body->getJointPos(1)));
  EXPECT_EQ(r->other, table);
  EXPECT_FALSE(r->sticking);
  EXPECT_NEAR(r->loads.Pz, 1.1 * kG, 1e-3 * kG);
  EXPECT_NEAR(friction, kBoxMu * r->loads.Pz, 1e-3 * kBoxMu * r->loads.Pz);
  // on the block, against its slip over the table (-x): along +x
  const btVector3 force = btScalar(r->Q.x()) * r->xAxis + btScalar(r->Q.y()) * r->yAxis;
  EXPECT_NEAR(double(force.x()), kBoxMu * r->loads.Pz, 1e-3 * kBoxMu * r->loads.Pz);
}

// The opt-in of a link collider: kept until disabled; an
// object that is neither a rigid body nor a link collider is refused.
// The platform, opted in, slides on the ground and carries a box: its
// patch with the box acts through its joint (the box moves along the
// normal), while its contact with the ground cannot be a patch, as the
// link cannot move along that normal nor tilt (singular blocks): counted
// as such, and left to Bullet's rows.
TEST(MultiBodyPatches, OptInOfALinkCollider) {
  MultiBodyScene scene(kG, 10, true);
  scene.addGroundPlane(1.0);
  const MultiBodyScene::Prismatic platform =
      scene.addPrismaticBox(bt(0.5, 0.3, 0.02), 2.0, bt(0, 0, 0.02), 1.0, kV, 200.0);
  btRigidBody* box = scene.addBox(kBoxHalf, 1.0, bt(0, 0, 0.04 + double(kBoxHalf.z())), kBoxMu);
  btMultiBodyLinkCollider* link = MultiBodyScene::collider(platform.body, 0);
  PatchMultiBodySolver& solver = scene.solver();
  EXPECT_FALSE(solver.isPatchFrictionEnabled(link));
  solver.enablePatchFriction(link, {Model::Exact});
  EXPECT_TRUE(solver.isPatchFrictionEnabled(link));
  EXPECT_FALSE(solver.isPatchFrictionEnabled(box));
  btCollisionObject plain;
  EXPECT_THROW(solver.enablePatchFriction(&plain), Error);
  EXPECT_THROW(solver.enablePatchFriction(nullptr), Error);
  for (int k = 0; k < 120; ++k) scene.step(kDt);
  const NotPatchedCounts* counts = solver.notPatchedOf(link);
  ASSERT_NE(counts, nullptr);
  EXPECT_GT(counts->singularBlocks, 0);
  EXPECT_EQ(counts->total(), counts->singularBlocks);
  EXPECT_EQ(solver.stats().notPatched.singularBlocks, counts->singularBlocks);
  const PatchReport* r = solver.findPatchReport(link);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->other, box);
  EXPECT_NEAR(r->loads.Pz, 1.0 * kG, 1e-3 * kG);
  solver.disablePatchFriction(link);
  EXPECT_FALSE(solver.isPatchFrictionEnabled(link));
}

// ---- the two-finger gripper of the issue ----------------------------------
// A 6 cm, 1 kg cube (friction 0.5) squeezed with N = 20 N by two fingers
// whose 4 x 4 cm pads (friction 1: mu = 0.5) are opted in; no gravity, so
// that the pads' friction only resists the twist tau about the grasp axis
// y. The pad lies within the cube face's inscribed circle at any turn, so
// each patch is the pad's square, under uniform pressure (no moment of the
// normal load about the grasp axis): it holds while tau < 2 mu N dbar and
// slips at the friction torque mu N dbar per pad above, dbar the mean
// distance of the square from its centre.
constexpr double kCubeHalf = 0.03, kCubeMass = 1.0, kSqueeze = 20.0, kPadHalf = 0.02;
constexpr double kGripMu = 0.5;

struct GripRun {
  double rotation = 0.0;  // cube's turn over the twist, folded into [0, pi] [rad]
  double torque = 0.0;    // friction torque per pad, tau - J alpha over the window, / 2 [N m]
  int reports = 0;        // patches reported at the end
};

// Settles the grasp for 0.25 s, then twists for `seconds`; alpha from the
// spin at 0.1 s and at the end of the twist.
GripRun runGripper(bool patch, double tau, double seconds) {
  scenes::GraspSpec spec;  // (pads 4 x 4 x 2 cm, 0.1 kg, starting 1 mm off the cube)
  spec.cubeHalf = kCubeHalf;
  spec.cubeMass = kCubeMass;
  spec.mu = kGripMu;
  spec.padHalf = kPadHalf;
  spec.squeeze = kSqueeze;
  scenes::Grasp grasp(scenes::GraspWorld::MultiBody, spec,
                      patch ? std::optional<Model>(Model::Exact) : std::nullopt);
  btRigidBody* cube = grasp.cube();
  for (int k = 0; k < int(0.25 / kDt); ++k) grasp.step(kDt, 0.0);
  const btQuaternion q0 = cube->getWorldTransform().getRotation();
  const double J = kCubeMass * (2 * kCubeHalf) * (2 * kCubeHalf) / 6.0;
  const int k0 = int(std::lround(0.1 / kDt)), k1 = int(std::lround(seconds / kDt));
  double w0 = 0.0;
  for (int k = 1; k <= k1; ++k) {
    grasp.step(kDt, tau);
    if (k == k0) w0 = double(cube->getAngularVelocity().y());
  }
  const double w1 = double(cube->getAngularVelocity().y());
  GripRun run;
  run.rotation = scenes::foldedTurnAngle(cube->getWorldTransform().getRotation(), q0);
  run.torque = 0.5 * (tau - J * (w1 - w0) / ((k1 - k0) * kDt));
  run.reports = grasp.reportCount();
  return run;
}

TEST(MultiBodyPatches, GripperHoldsBelowTheTwistLimitAndSlipsAtItAbove) {
  const double dbar = testing::rectangleMeanDistance(kPadHalf, kPadHalf);
  // (closed form of dbar: h (sqrt 2 + asinh 1) / 3, to the quadrature's 1e-5)
  EXPECT_NEAR(dbar, kPadHalf * (std::sqrt(2.0) + std::asinh(1.0)) / 3.0, 1e-5 * kPadHalf);
  const double limit = kGripMu * kSqueeze * dbar;           // per pad
  const GripRun hold = runGripper(true, limit, 2.0);        // half the grasp's limit
  const GripRun slip = runGripper(true, 2.5 * limit, 0.4);  // 1.25 x the grasp's limit
  const GripRun stockHold = runGripper(false, limit, 2.0);
  const GripRun stockSlip = runGripper(false, 2.5 * limit, 0.4);
  std::printf(
      "[gripper, %s] limit per pad mu N dbar = %.5f N m; tau = %.4f N m: patch turns %.2e rad "
      "in 2 s (stock %.2e rad); tau = %.4f N m: patch friction torque per pad %.5f N m "
      "(%.3f %% off; turned %.3f rad in 0.4 s), stock %.5f N m\n",
      kDouble ? "double" : "float", limit, limit, hold.rotation, stockHold.rotation, 2.5 * limit,
      slip.torque, 100.0 * (slip.torque / limit - 1.0), slip.rotation, stockSlip.torque);
  EXPECT_EQ(hold.reports, 2);
  EXPECT_LT(hold.rotation, 1e-4);  // the bound
  EXPECT_EQ(slip.reports, 2);
  EXPECT_NEAR(slip.torque, limit, 0.02 * limit);  // the 2 %
  // (it slipped: (tau - 2 mu N dbar) / J over 0.4 s turns it by ~10 rad,
  // which rotation folds into [0, pi])
  EXPECT_GT(slip.rotation, 0.1);
}

// ---- a flat foot ----------------------------------------------------------
// A leg (a 2 kg shin on a 1 kg foot link of 16 x 8 cm, fixed to it) stands
// on the ground (mu = 0.6), its weight straight over the sole's centre:
// uniform pressure, so under a yaw torque tau the foot holds while
// tau < mu M g dbar and spins with the friction torque mu M g dbar above
// (dbar of the sole's rectangle by quadrature, testing::rectangleMeanDistance).
constexpr double kFootMu = 0.6, kFootMass = 1.0, kShinMass = 2.0;
const btVector3 kFootHalf(btScalar(0.08), btScalar(0.04), btScalar(0.01));
const btVector3 kShinHalf(btScalar(0.03), btScalar(0.03), btScalar(0.1));

struct FootRun {
  double rotation = 0.0;  // yaw turn over the torque, folded into [0, pi] [rad]
  double torque = 0.0;    // friction torque, tau - J alpha [N m]
  bool patch = false;     // the foot has a patch at the end
};

FootRun runFoot(bool patch, double tau, double seconds) {
  MultiBodyScene scene(kG, 10, patch);
  scene.addGroundPlane(1.0);
  btMultiBody* leg = scene.addLeg(kFootHalf, kFootMass, kShinHalf, kShinMass,
                                  bt(0, 0, double(kFootHalf.z())), kFootMu);
  btMultiBodyLinkCollider* foot = MultiBodyScene::collider(leg, 0);
  if (patch) scene.solver().enablePatchFriction(foot, {Model::Exact});
  for (int k = 0; k < int(0.25 / kDt); ++k) scene.step(kDt);
  const btQuaternion q0 = leg->getWorldToBaseRot();
  auto izz = [](double m, const btVector3& h) {
    return m * 4.0 * double(h.x() * h.x() + h.y() * h.y()) / 12.0;
  };
  const double J = izz(kFootMass, kFootHalf) + izz(kShinMass, kShinHalf);
  const int k0 = int(std::lround(0.1 / kDt)), k1 = int(std::lround(seconds / kDt));
  double w0 = 0.0;
  for (int k = 1; k <= k1; ++k) {
    leg->addLinkTorque(0, bt(0, 0, tau));
    scene.step(kDt);
    if (k == k0) w0 = double(leg->getBaseOmega().z());
  }
  FootRun run;
  run.rotation = scenes::foldedTurnAngle(leg->getWorldToBaseRot(), q0);
  run.torque = tau - J * (double(leg->getBaseOmega().z()) - w0) / ((k1 - k0) * kDt);
  if (patch) run.patch = scene.solver().findPatchReport(foot) != nullptr;
  return run;
}

// Below the limit: the 1e-4 rad over 2 s; above, the friction
// torque within 2 % (the gripper tolerance).
TEST(MultiBodyPatches, FlatFootDoesNotSpinBelowItsYawLimit) {
  const double limit = kFootMu * (kFootMass + kShinMass) * kG *
                       testing::rectangleMeanDistance(double(kFootHalf.x()), double(kFootHalf.y()));
  const FootRun hold = runFoot(true, 0.8 * limit, 2.0);
  const FootRun spin = runFoot(true, 1.25 * limit, 0.4);
  const FootRun stockHold = runFoot(false, 0.8 * limit, 2.0);
  std::printf(
      "[foot, %s] yaw limit mu M g dbar = %.5f N m; at 0.8 x: patch turns %.2e rad in 2 s "
      "(stock %.2e rad); at 1.25 x: friction torque %.5f N m (%.3f %% off; turned %.3f rad)\n",
      kDouble ? "double" : "float", limit, hold.rotation, stockHold.rotation, spin.torque,
      100.0 * (spin.torque / limit - 1.0), spin.rotation);
  EXPECT_TRUE(hold.patch);
  EXPECT_LT(hold.rotation, 1e-4);
  EXPECT_TRUE(spin.patch);
  EXPECT_NEAR(spin.torque, limit, 0.02 * limit);
  EXPECT_GT(spin.rotation, 0.1);
}

}  // namespace
}  // namespace patchspin::bullet
