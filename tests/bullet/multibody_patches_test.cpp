// PatchMultiBodySolver in a btMultiBodyDynamicsWorld (issue 33): patches
// on Featherstone links against the ground, a rigid body and another link,
// each against an independent prediction and, where there is one, the
// rigid-body twin under PatchFrictionSolver; stock Bullet's figure printed
// beside ours. Scenes: scenes/multibody_scene.hpp.
#include <patchspin/bullet/patch_multibody_solver.hpp>
#include <patchspin/scenes/multibody_scene.hpp>
#include <patchspin/scenes/scene.hpp>

#include "closed_forms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

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

// The opt-in of a link collider: kept by the solver until disabled; an
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

}  // namespace
}  // namespace patchspin::bullet
