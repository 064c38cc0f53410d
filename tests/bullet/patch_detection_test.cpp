// Patches from shapes: the overlap geometry of coins, boxes, convex hulls and
// cylinders with another up axis, and when a patch is rebuilt. Moved from
// patch_friction_solver_test.cpp.
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <patchspin/scenes/inertia.hpp>
#include <string>
#include <vector>

#include "bullet_scenes.hpp"

namespace patchspin::bullet {
namespace {

// ---- patches from shapes: overlap geometry ---------------------------------------
// A coin on a static box (a table) lies fully inside the top face: an exact
// disk. Moved so that its centre is d inside the table's edge, the patch is
// the disk minus a circular segment, an arc region (PatchShape::Kind::ArcRegion):
//   A = pi R^2 - (R^2 acos(d/R) - d sqrt(R^2 - d^2)).
// Tolerance: float Bullet's positions (the coin's centre and the box's edge
// to ~1e-8 m) and one step's motion move the cut by ~1e-7 R; dA/dd =
// 2 sqrt(R^2 - d^2) < 0.1 m, so 1e-8 m^2 of area (2e-6 of it).
constexpr double kCutDiskAreaTol = 1e-8;  // [m^2]

TEST(PatchFrictionSolver, CoinOnTableIsADiskAndOverTheEdgeACutDisk) {
  for (double d : {1.0, 0.4}) {  // in units of R: fully inside, then cut
    Scene scene(kG);
    const btVector3 half(0.2f, 0.2f, 0.05f);
    scene.addStaticBox(half, btVector3(0, 0, -0.05f), 1.0);
    const double x = 0.2 - d * kR + (d >= 1.0 ? -0.05 : 0.0);
    btRigidBody* coin =
        scene.addCylinder(kR, kH, kMass, btVector3(btScalar(x), 0, btScalar(kH / 2)), kMu);
    scene.solver().enablePatchFriction(coin, {Model::Exact});
    scene.step(kDt);
    const PatchReport* rep = scene.solver().findPatchReport(coin);
    ASSERT_NE(rep, nullptr) << "d = " << d;
    if (d >= 1.0) {
      ASSERT_TRUE(rep->shape->isDisk());
      EXPECT_NEAR(rep->shape->radius(), kR, 1e-6);
    } else {
      ASSERT_EQ(rep->shape->kind(), PatchShape::Kind::ArcRegion);
      const double dd = d * kR;
      const double expected =
          M_PI * kR * kR - (kR * kR * std::acos(dd / kR) - dd * std::sqrt(kR * kR - dd * dd));
      EXPECT_NEAR(rep->shape->area(), expected, kCutDiskAreaTol);
      // O at the region's centroid (the solver's frame): its first moment vanishes
      EXPECT_LT(rep->shape->areaMoments().first.norm(), 1e-12 * kR * expected);
    }
    EXPECT_NEAR(rep->loads.Pz, kMass * kG, 1e-3 * kMass * kG) << "d = " << d;
  }
}

// A coin resting on another coin, off-centre by d: their overlap is a lens
// (two arcs) of area 2 R^2 acos(d / 2R) - (d / 2) sqrt(4 R^2 - d^2), and
// the upper coin's whole weight stands on it. Tolerance as above.
TEST(PatchFrictionSolver, CoinOffCentreOnACoinStandsOnTheLens) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  const double d = 0.6 * kR;
  btRigidBody* lower =
      scene.addCylinder(kR, kH, 10.0 * kMass, btVector3(0, 0, btScalar(kH / 2)), kMu);
  btRigidBody* upper = scene.addCylinder(
      kR, kH, kMass, btVector3(btScalar(d), 0, btScalar(1.5 * kH - kSetDownDepth)), kMu);
  scene.solver().enablePatchFriction(lower, {Model::Exact});
  scene.solver().enablePatchFriction(upper, {Model::Exact});
  for (int k = 0; k < 5; ++k) scene.step(kDt);
  const PatchReport* rep = scene.solver().findPatchReport(upper);
  ASSERT_NE(rep, nullptr);
  ASSERT_EQ(rep->other, lower);
  ASSERT_EQ(rep->shape->kind(), PatchShape::Kind::ArcRegion);
  const double expected =
      2.0 * kR * kR * std::acos(d / (2.0 * kR)) - 0.5 * d * std::sqrt(4.0 * kR * kR - d * d);
  EXPECT_NEAR(rep->shape->area(), expected, kCutDiskAreaTol);
  EXPECT_NEAR(rep->loads.Pz, kMass * kG, 1e-3 * kMass * kG);
}

// A coin tilted on a table by less than the flatness tolerance is a patch,
// and closing the patch's gap must not drive its low rim into the table.
// The coin (R = 5 cm, tilted 0.015 rad, pressed down at 0.2 m/s, as by a
// pile above it) starts with its low rim touching; its face centre is then
// R sin(0.015) = 0.75 mm above the table. Closing that gap at O in one step,
// as the patch did before it knew the face's clearance, took the rim
// 0.73 mm deep in the first step (measured in this test), and the tilt
// correction lifted it by 2 % a step (0.28 mm deep after 48 steps). The
// patch may now take the rim kLowSideSinkRelTol R = 0.05 mm in (the
// solver's constant); the depth is the shape's own geometry (lowest point
// of the rim, or of the box), not Bullet's contact distance. A box of the
// coin's size, a polygon patch whose clearance is taken at the outline's
// vertices, may sink 1e-3 of its half diagonal, 0.071 mm. Bound: the coin's
// sink doubled, 0.1 mm (measured: coin 0.044 mm, box 0.065 mm; before, the
// box too went 0.73 mm deep).
constexpr double kTiltedCoinTilt = 0.015, kTiltedCoinPress = 0.2;
constexpr double kTiltedCoinSinkBound = 2 * 1e-3 * kR;

TEST(PatchFrictionSolver, TiltedPatchDoesNotDriveItsLowEdgeIn) {
  // the coin, and a box of the coin's size (a polygon patch: its clearance
  // is taken at the outline's vertices); half extents of the box
  const btVector3 half{btScalar(kR), btScalar(kR), btScalar(kH / 2)};
  for (bool box : {false, true}) {
    Scene scene(kG);
    scene.addStaticBox(btVector3(0.2f, 0.2f, 0.05f), btVector3(0, 0, -0.05f), 1.0);
    const double th = kTiltedCoinTilt;
    const double z0 = kH / 2 * std::cos(th) + kR * std::sin(th);  // low rim (edge) at z = 0
    btRigidBody* body = box ? scene.addBox(half, kMass, btVector3(0, 0, btScalar(z0)), kMu)
                            : scene.addCylinder(kR, kH, kMass, btVector3(0, 0, btScalar(z0)), kMu);
    btTransform t = body->getWorldTransform();
    t.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(th)));
    body->setWorldTransform(t);
    body->setLinearVelocity(btVector3(0, 0, btScalar(-kTiltedCoinPress)));
    scene.solver().enablePatchFriction(body, {Model::Ellipsoidal});
    auto depth = [&] {  // of the lowest point below the table, from the shape's geometry
      const btTransform& tr = body->getWorldTransform();
      const btVector3 az = tr.getBasis().getRow(2);  // world z in body axes
      double low = double(tr.getOrigin().z());
      if (box) {
        for (int i = 0; i < 3; ++i) low -= double(half[i]) * std::abs(double(az[i]));
      } else {
        const double c = std::abs(double(az.z()));
        low -= kH / 2 * c + kR * std::sqrt(std::max(0.0, 1 - c * c));
      }
      return -low;
    };
    double deepest = 0.0;
    int patchSteps = 0;
    for (int k = 0; k < 48; ++k) {
      scene.step(kDt);
      deepest = std::max(deepest, depth());
      patchSteps += scene.solver().findPatchReport(body) != nullptr;
    }
    const double tilt = std::acos(
        std::min(1.0, std::abs(double(body->getWorldTransform().getBasis().getColumn(2).z()))));
    const char* what = box ? "box" : "coin";
    std::printf(
        "[tilted %s] deepest edge %.3e m (centre gap at the start %.3e m), %d of 48 steps a patch, "
        "tilt at the end %.2e rad\n",
        what, deepest, kR * std::sin(th), patchSteps, tilt);
    EXPECT_EQ(patchSteps, 48) << what;  // a patch from the first step on
    EXPECT_LT(deepest, kTiltedCoinSinkBound) << what;
    EXPECT_LT(tilt, th) << what;  // the tilt correction goes on (2 % a step, as before)
  }
}

// Box on an offset box: the patch is the rectangle where the faces overlap,
// x in [-0.05, 0.1], y in [-0.07, 0.1]: 0.15 x 0.17, centroid (0.025, 0.015).
// The upper box's centre of mass (0.05, 0.03) lies (0.025, 0.015) off it, so
// at rest the loads are Pz = m g and |T| = m g |(0.025, 0.015)|.
TEST(PatchFrictionSolver, BoxOnOffsetBoxPatchIsTheFaceOverlap) {
  Scene scene(kG);
  const auto [lower, upper] =
      addBlockOnBlock(scene, btVector3(0.1f, 0.1f, 0.05f), 5.0, btVector3(0.1f, 0.1f, 0.05f), 1.0,
                      btVector3(0.05f, 0.03f, 0.15f));
  // Bullet's box-box test reports the exactly touching faces once they
  // overlap by round-off: a few steps of settling
  for (int k = 0; k < 5; ++k) scene.step(kDt);
  const PatchReport* top = nullptr;
  for (const PatchReport& r : scene.solver().patchReports())
    if ((r.body == upper && r.other == lower) || (r.body == lower && r.other == upper)) top = &r;
  for (const PatchReport& r : scene.solver().patchReports())
    std::printf("[box on box] patch area %.5f Pz %.4f\n", r.shape->area(), r.loads.Pz);
  ASSERT_NE(top, nullptr);
  EXPECT_NEAR(top->shape->area(), 0.15 * 0.17, 1e-6);
  EXPECT_NEAR(top->loads.Pz, 1.0 * kG, 1e-3 * kG);
  EXPECT_NEAR(std::hypot(top->loads.Tx, top->loads.Ty), kG * std::hypot(0.025, 0.015),
              1e-3 * kG * 0.03);
}

// Two coins lying side by side touch rim to rim: their faces are parallel
// (both flat on the floor) but the contact normal runs across them, so the
// pair is not a patch; each coin stands on its floor patch and rests. Before
// the faces had to face the contact (kFacingCos), the rim contact became a
// patch between one coin's bottom and the other's top, a "gap" of -H that
// its position correction pushed apart (the hovering coin of the pour).
// Rows of three coins, 0.5 mm overlap (Bullet's rim contact pushes them
// apart), tilted about the row by 0 and 0.01 rad (inside the flatness
// tolerance). Bounds: at rest, |v| + R |w| below 1 mm/s after 1 s (the
// rim contacts' push ends within ~0.2 s); heights within 0.5 mm of H/2
// (the coins' 0.5 mm margin: a hop as in the pour lifted a coin 0.25 mm
// per hop and let it fall at g dt).
constexpr double kSideBySideRestSpeed = 1e-3;
constexpr double kSideBySideHeightTol = 5e-4;

TEST(PatchFrictionSolver, CoinsSideBySideTouchRimToRimAndAreNoPatch) {
  for (double tilt : {0.0, 0.01}) {
    Scene scene(kG);
    scene.addGroundPlane(1.0);
    std::vector<btRigidBody*> coins;
    for (int i = 0; i < 3; ++i) {
      const double x = (i - 1) * (2 * kR - 5e-4);
      btRigidBody* c =
          scene.addCylinder(kR, kH, kMass, btVector3(btScalar(x), 0, btScalar(kH / 2)), kMu, 5e-4);
      btTransform t = c->getWorldTransform();
      t.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(tilt)));
      c->setWorldTransform(t);
      scene.solver().enablePatchFriction(c, {i == 1 ? Model::Exact : Model::Ellipsoidal});
      coins.push_back(c);
    }
    auto isCoin = [&](const btCollisionObject* o) {
      return std::find(coins.begin(), coins.end(), o) != coins.end();
    };
    int coinPatches = 0;
    for (int k = 0; k < 240; ++k) {
      scene.step(kDt);
      for (const PatchReport& r : scene.solver().patchReports())
        if (isCoin(r.body) && isCoin(r.other)) ++coinPatches;
    }
    EXPECT_EQ(coinPatches, 0) << "tilt " << tilt;
    for (btRigidBody* c : coins) {
      const double speed =
          double(c->getLinearVelocity().length()) + kR * double(c->getAngularVelocity().length());
      EXPECT_LT(speed, kSideBySideRestSpeed) << "tilt " << tilt;
      EXPECT_NEAR(double(c->getWorldTransform().getOrigin().z()), kH / 2, kSideBySideHeightTol)
          << "tilt " << tilt;
      EXPECT_NE(scene.solver().findPatchReport(c), nullptr) << "tilt " << tilt;
    }
  }
}

// Shapes with zero collision margins touch on their faces only to the
// round-off of the contact points (~1e-8 m in float): the on-face test
// (kOnFaceMargins x 0 margins) must leave them their patch. A 10 x 10 x 4 cm
// box on a 20 x 20 x 10 cm box, both margin 0, 2 m from the origin, on a
// static box: the patch is the upper box's bottom face, area 0.01 m^2,
// carrying its weight.
TEST(PatchFrictionSolver, BoxesWithZeroMarginsStillMakeAPatch) {
  Scene scene(kG);
  scene.addStaticBox(btVector3(5, 5, 0.5f), btVector3(0, 0, -0.5f), 1.0);
  // (off the origin, where the coordinates carry round-off)
  btRigidBody* upper =
      scene.addBox(btVector3(0.05f, 0.05f, 0.02f), 0.3, btVector3(0.3f, -2.0f, 0.12f), 0.5, 0.0);
  btRigidBody* lower =
      scene.addBox(btVector3(0.1f, 0.1f, 0.05f), 1.0, btVector3(0.3f, -2.0f, 0.05f), 0.5, 0.0);
  scene.solver().enablePatchFriction(lower, {Model::Ellipsoidal});
  scene.solver().enablePatchFriction(upper, {Model::Exact});
  int steps = 0;
  for (int k = 0; k < 60; ++k) {
    scene.step(kDt);
    for (const PatchReport& r : scene.solver().patchReports())
      if (r.body == upper && r.other == lower) ++steps;
  }
  EXPECT_EQ(steps, 60);
  const PatchReport* top = nullptr;
  for (const PatchReport& r : scene.solver().patchReports())
    if (r.body == upper && r.other == lower) top = &r;
  ASSERT_NE(top, nullptr);
  EXPECT_NEAR(top->shape->area(), 0.01, 1e-6);
  EXPECT_NEAR(top->loads.Pz, 0.3 * kG, 1e-3 * 0.3 * kG);
}

// The shape and friction law of a patch are rebuilt only when its outline
// changes (kOutlineRelTol in the solver, 1e-4 of the size), not with the
// round-off of the transforms:
// a box resting on an offset box (a clipped overlap, whose vertices carry
// float round-off of both transforms) keeps its shape step after step, and
// the same box sliding off the edge at 0.3 m/s (1.25 mm, 1 % of the overlap,
// per step) gets a new one nearly every step.
TEST(PatchFrictionSolver, PatchShapeIsRebuiltOnlyWhenTheOutlineChanges) {
  for (bool sliding : {false, true}) {
    Scene scene(kG);
    const auto [lower, upper] =
        addBlockOnBlock(scene, btVector3(0.1f, 0.1f, 0.05f), 5.0, btVector3(0.1f, 0.1f, 0.05f), 1.0,
                        btVector3(0.05f, 0.03f, 0.15f));
    for (int k = 0; k < 120; ++k) scene.step(kDt);  // settled (see the test above)
    constexpr int kSteps = 20;  // sliding: the centre of mass stays over the lower box
    long rebuilds = 0;
    for (int k = 0; k < kSteps; ++k) {
      // friction would stop the slide: keep the velocity (a pushed box)
      if (sliding) upper->setLinearVelocity(btVector3(0.3f, 0, 0));
      scene.step(kDt);
      rebuilds += scene.solver().stats().shapeRebuilds;
      ASSERT_EQ(scene.solver().stats().patches, 2) << "sliding " << sliding << " step " << k;
    }
    std::printf("[shape reuse] %s: %ld shape rebuilds in %d steps\n",
                sliding ? "sliding" : "at rest", rebuilds, kSteps);
    if (sliding)
      EXPECT_GE(rebuilds,
                kSteps - 2);  // every step but where a step's change falls below the tolerance
    else
      EXPECT_EQ(rebuilds, 0);
  }
}

// A coin sliding and spinning on a plane keeps its overlap from step to step
// (the whole cap, a disk of its radius, at any relative pose): its patch is
// that disk, O is the cap's centre projected onto the plane at every step,
// where the step finds the faces, not where the overlap was first clipped
// (the coin moves 1.25 mm a step, so a stale O would be off by that much
// and more), and the shape is never
// rebuilt. Tolerance: float Bullet's positions, ~1e-7 m at 1 m; 1e-6 m.
constexpr double kKeptOriginTol = 1e-6;  // [m]

TEST(PatchFrictionSolver, DiskOnAPlaneKeepsItsOverlapWhileItSlides) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  btRigidBody* coin =
      scene.addCylinder(kR, kH, kMass, btVector3(0.3f, -0.2f, btScalar(kH / 2)), kMu);
  scene.solver().enablePatchFriction(coin, {Model::Exact});
  scene.step(kDt);
  long rebuilds = 0;
  for (int k = 0; k < 40; ++k) {
    // friction would stop the slide: keep it (a pushed, spinning coin)
    coin->setLinearVelocity(btVector3(0.3f, 0.1f, coin->getLinearVelocity().z()));
    coin->setAngularVelocity(btVector3(0, 0, 8));
    // the lower cap's centre (the coin's axis is its local z) where the step
    // finds the faces, before it moves the coin; onto z = 0
    const btTransform t = coin->getWorldTransform();
    const btVector3 cap = t.getOrigin() - t.getBasis().getColumn(2) * btScalar(kH / 2);
    scene.step(kDt);
    rebuilds += scene.solver().stats().shapeRebuilds;
    const PatchReport* rep = scene.solver().findPatchReport(coin);
    ASSERT_NE(rep, nullptr) << "step " << k;
    ASSERT_TRUE(rep->shape->isDisk());
    EXPECT_NEAR(rep->shape->radius(), kR, 1e-6);
    EXPECT_NEAR(rep->origin.x(), cap.x(), kKeptOriginTol) << "step " << k;
    EXPECT_NEAR(rep->origin.y(), cap.y(), kKeptOriginTol) << "step " << k;
    EXPECT_NEAR(rep->origin.z(), 0.0, kKeptOriginTol) << "step " << k;
  }
  EXPECT_EQ(rebuilds, 0);
  EXPECT_GT(coin->getWorldTransform().getOrigin().x(), 0.3f + 0.04f);  // it did slide
}

// ---- other shapes: convex hull faces, cylinders with another up axis ---------------
// A hexagonal prism built as a btConvexHullShape (circumradius a = 5 cm,
// 2 cm high) stands on its hexagon: the patch is the hexagon, area
// (3 sqrt(3) / 2) a^2, from Bullet's polyhedral features. Spun in place it
// stops at t = omega0 J_z / (mu m g mean|r|) (same derivation as the box in
// simulate_test.cpp), mean|r| over the hexagon by a brute-force grid
// (2000^2 cells: boundary cells err by ~1/2000, hence kHullStopTol = 1 %).
constexpr double kHullStopTol = 0.01;

TEST(PatchFrictionSolver, ConvexHullPrismGivesAHexagonPatchAndSpinsDownOnTime) {
  const double a = 0.05, h = 0.02, m = 1.0, omega0 = 20.0;
  auto hull = std::make_unique<btConvexHullShape>();
  for (int k = 0; k < 6; ++k)
    for (double z : {-h / 2, h / 2})
      hull->addPoint(btVector3(btScalar(a * std::cos(k * M_PI / 3)),
                               btScalar(a * std::sin(k * M_PI / 3)), btScalar(z)),
                     false);
  hull->recalcLocalAabb();
  hull->setMargin(btScalar(1e-3));
  // hexagon: J_z = (5/12) m a^2 (solid regular hexagonal prism), the prediction's J_z
  const double jz = 5.0 / 12.0 * m * a * a;
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  btTransform start;
  start.setIdentity();
  start.setOrigin(btVector3(0, 0, btScalar(h / 2)));
  btRigidBody* body =
      scene.addBody(std::move(hull), m, scenes::hexagonalPrismInertia(m, a, h), start, kMu);
  scene.solver().enablePatchFriction(body, {Model::Exact});
  scene.step(kDt);
  const PatchReport* rep = scene.solver().findPatchReport(body);
  ASSERT_NE(rep, nullptr);
  ASSERT_FALSE(rep->shape->isDisk());
  EXPECT_EQ(rep->shape->vertices().size(), 6u);
  EXPECT_NEAR(rep->shape->area(), 1.5 * std::sqrt(3.0) * a * a, 1e-5 * a * a);

  // spin-down
  constexpr int kN = 2000;
  double sum = 0;
  long inside = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const double x = a * (2.0 * (i + 0.5) / kN - 1), y = a * (2.0 * (j + 0.5) / kN - 1);
      bool in = true;
      for (int k = 0; k < 6 && in; ++k) {
        const double t = (k + 0.5) * M_PI / 3;  // edge normals of the hexagon
        in = x * std::cos(t) + y * std::sin(t) <= a * std::cos(M_PI / 6);
      }
      if (in) {
        sum += std::hypot(x, y);
        ++inside;
      }
    }
  const double meanR = sum / double(inside);
  const double tPredicted = omega0 * jz / (kMu * m * kG * meanR);
  body->setAngularVelocity(btVector3(0, 0, btScalar(omega0)));
  double t = 0, worstTilt = 0;
  // until the friction block sticks (omega_z is then zero up to round-off)
  for (bool stuck = false; t < 2 * tPredicted && !stuck;) {
    scene.step(kDt);
    t += kDt;
    const PatchReport* now = scene.solver().findPatchReport(body);
    stuck = now && now->sticking;
    worstTilt = std::max(worstTilt, std::hypot(double(body->getAngularVelocity().x()),
                                               double(body->getAngularVelocity().y())));
  }
  std::printf(
      "[hull] hexagon patch area %.6e, spin stopped after %.4f s (predicted %.4f s, step %.4f s)\n",
      rep->shape->area(), t, tPredicted, kDt);
  EXPECT_NEAR(t, tPredicted, kHullStopTol * tPredicted + kDt);
  EXPECT_LT(worstTilt, kTiltBound);
}

// btCylinderShape (y up) turned so that its y axis is vertical: the patch is
// its cap, an exact disk of its radius.
TEST(PatchFrictionSolver, CylinderWithYUpAxisRestsOnItsCap) {
  Scene scene(kG);
  scene.addGroundPlane(1.0);
  auto shape =
      std::make_unique<btCylinderShape>(btVector3(btScalar(kR), btScalar(kH / 2), btScalar(kR)));
  shape->setMargin(btScalar(1e-3));
  btTransform start;
  start.setIdentity();
  start.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(M_PI / 2)));
  start.setOrigin(btVector3(0, 0, btScalar(kH / 2)));
  // any inertia: the body only rests
  btRigidBody* body =
      scene.addBody(std::move(shape), kMass, btVector3(1e-3f, 1e-3f, 1e-3f), start, 0.5);
  scene.solver().enablePatchFriction(body, {Model::Ellipsoidal});
  for (int k = 0; k < 10; ++k) scene.step(kDt);
  const PatchReport* rep = scene.solver().findPatchReport(body);
  ASSERT_NE(rep, nullptr);
  ASSERT_TRUE(rep->shape->isDisk());
  EXPECT_NEAR(rep->shape->radius(), kR, 1e-6);
  EXPECT_NEAR(rep->loads.Pz, kMass * kG, 1e-3 * kMass * kG);
}

}  // namespace
}  // namespace patchspin::bullet
