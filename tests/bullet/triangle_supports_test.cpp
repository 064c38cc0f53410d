// Patches on triangle meshes and heightfields (concave_support.hpp): a face
// on coplanar triangles behaves as on the plane they sample, whatever the
// triangle count; a crease, the mesh's edge or a bad mesh is counted, never
// silent, and never puts a NaN in the world. The plane is the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/terrain.hpp>
#include <string>

#include "bullet_scenes.hpp"

namespace patchspin::bullet {
namespace {

using scenes::CoinSpec;
using scenes::Friction;
using scenes::Ground;
using scenes::GroundSpec;
using scenes::MeshDefect;

// ---- the coin of the issue, sliding and spinning to rest ------------------------------
// The stop follows scenes::simulate: slip r = |(v_x, v_y, rho w_z)|, rho =
// 2R/3; the ratio v/(R omega) is taken when r first falls below 1 % of r0;
// stopped below 1e-5 r0.
struct CoinRun {
  double tStop = -1.0, ratio = -1.0, travel = 0.0;
  double maxHeightOff = 0.0;  // largest |z - H/2| of the centre while sliding [m]
  long steps = 0, stepsWithPatch = 0;
  NotPatchedCounts notPatched;
  bool finite = true;
};

CoinRun runCoin(const GroundSpec& ground, Friction f = Friction::Exact, double tMax = 1.0) {
  CoinSpec spec;
  spec.ground = ground;
  btRigidBody* coin = nullptr;
  auto scene = scenes::makeCoin(spec, f, &coin);
  const double rho = 2.0 * spec.radius / 3.0;
  auto slip = [&] {
    const btVector3 v = coin->getLinearVelocity(), w = coin->getAngularVelocity();
    return std::sqrt(double(v.x() * v.x() + v.y() * v.y()) + std::pow(rho * double(w.z()), 2));
  };
  const double r0 = slip();
  const btVector3 start = coin->getWorldTransform().getOrigin();
  CoinRun run;
  for (double t = kDt; t <= tMax; t += kDt) {
    scene->step(kDt);
    ++run.steps;
    if (f != Friction::Stock) {
      const NotPatchedCounts& np = scene->solver().stats().notPatched;
      run.notPatched.crease += np.crease;
      run.notPatched.badMesh += np.badMesh;
      run.notPatched.unsupportedShape += np.unsupportedShape;
      if (scene->solver().findPatchReport(coin)) ++run.stepsWithPatch;
    }
    const btVector3 p = coin->getWorldTransform().getOrigin();
    if (!std::isfinite(double(p.x() + p.y() + p.z()))) {
      run.finite = false;
      break;
    }
    const double r = slip();
    run.maxHeightOff = std::max(run.maxHeightOff, std::abs(double(p.z()) - spec.height / 2));
    if (run.ratio < 0 && r < 0.01 * r0) {
      const btVector3 v = coin->getLinearVelocity();
      run.ratio = double(btSqrt(v.x() * v.x() + v.y() * v.y())) /
                  (spec.radius * std::abs(double(coin->getAngularVelocity().z())));
    }
    if (r < 1e-5 * r0) {
      run.tStop = t;
      run.travel = double((p - start).length());
      break;
    }
  }
  return run;
}

void print(const char* label, const CoinRun& r) {
  std::printf("  %-28s t_stop %.4f s  ratio %.4f  travel %.5f m  |dz| %.2e m  patched %ld/%ld\n",
              label, r.tStop, r.ratio, r.travel, r.maxHeightOff, r.stepsWithPatch, r.steps);
}

// Stop time, stop ratio and travel agree with the plane's within 1 %, the
// issue's bound: the patch over coplanar triangles is the plane's patch (the
// same disk, normal and height to the triangles' float round-off), so the
// runs differ only by round-off of the support's point and Bullet's
// contact points on the triangles, which the patch replaces.
constexpr double kSameAsPlane = 0.01;
// The centre's height stays within this of H/2 while sliding across the
// triangles' edges [m]: Bullet's contact slop (the plane run's is the
// same order); a bump at an edge would be millimetres.
constexpr double kNoBump = 2e-4;

TEST(TriangleSupports, CoinStopsOnATriangleMeshAndAHeightfieldAsOnThePlane) {
  const CoinRun plane = runCoin({});
  GroundSpec mesh;
  mesh.kind = Ground::TriangleMesh;
  GroundSpec field;
  field.kind = Ground::Heightfield;
  GroundSpec scaled = mesh;
  scaled.meshScale = 2.5;
  GroundSpec fine = mesh;  // ~2,500 triangles under the coin
  fine.spacing = 0.0025;
  const CoinRun onMesh = runCoin(mesh), onField = runCoin(field), onScaled = runCoin(scaled),
                onFine = runCoin(fine);
  const CoinRun stock = runCoin(mesh, Friction::Stock);
  std::printf("exact law, coin R 5 cm at 0.5 m/s and 20 rad/s (%s):\n", scenes::precisionName());
  print("plane", plane);
  print("mesh (1 cm grid, 5000 tri.)", onMesh);
  print("heightfield (1 cm grid)", onField);
  print("scaled mesh (x 2.5)", onScaled);
  print("mesh, 2.5 mm grid (80k tri.)", onFine);
  print("stock Bullet on the mesh", stock);
  ASSERT_GT(plane.tStop, 0.0);
  for (const CoinRun* r : {&onMesh, &onField, &onScaled, &onFine}) {
    ASSERT_TRUE(r->finite);
    ASSERT_GT(r->tStop, 0.0);
    EXPECT_NEAR(r->tStop, plane.tStop, kSameAsPlane * plane.tStop);
    EXPECT_NEAR(r->ratio, plane.ratio, kSameAsPlane * plane.ratio);
    EXPECT_NEAR(r->travel, plane.travel, kSameAsPlane * plane.travel);
    EXPECT_LT(r->maxHeightOff, kNoBump);
    // a patch in every step, nothing left to Bullet
    EXPECT_EQ(r->stepsWithPatch, r->steps);
    EXPECT_EQ(r->notPatched.crease + r->notPatched.badMesh + r->notPatched.unsupportedShape, 0);
  }
}

// ---- a block's face: a polygon on the triangles ------------------------------------------
// A 10 x 6 x 4 cm block (1 kg, mu 0.3) launched at (0.4, 0.1) m/s spinning
// at 10 rad/s on the ground, exact law, until it stops (|v| < 1e-5 m/s and
// |w| < 1e-4 rad/s): stop time, travel and final yaw as on the plane.
struct BlockRun {
  double tStop = -1.0, travel = 0.0, yaw = 0.0;
  long steps = 0, stepsWithPatch = 0;
};

BlockRun runBlock(const GroundSpec& ground) {
  Scene scene(kG);
  scenes::addGround(scene, ground, 1.0);
  btRigidBody* block = scene.addBox(btVector3(0.05f, 0.03f, 0.02f), 1.0,
                                    btVector3(0, 0, btScalar(0.02 - 1e-5)), 0.3);
  scenes::optIn(scene, block, Friction::Exact);
  block->setLinearVelocity(btVector3(0.4f, 0.1f, 0));
  block->setAngularVelocity(btVector3(0, 0, 10));
  const btVector3 start = block->getWorldTransform().getOrigin();
  BlockRun run;
  for (double t = kDt; t <= 1.0; t += kDt) {
    scene.step(kDt);
    ++run.steps;
    if (scene.solver().findPatchReport(block)) ++run.stepsWithPatch;
    if (block->getLinearVelocity().length() < 1e-5 && block->getAngularVelocity().length() < 1e-4) {
      run.tStop = t;
      break;
    }
  }
  const btTransform& tr = block->getWorldTransform();
  run.travel = double((tr.getOrigin() - start).length());
  const btVector3 x = tr.getBasis().getColumn(0);
  run.yaw = std::atan2(double(x.y()), double(x.x()));
  return run;
}

TEST(TriangleSupports, BlockSlidesAndSpinsToRestOnTrianglesAsOnThePlane) {
  const BlockRun plane = runBlock({});
  GroundSpec mesh;
  mesh.kind = Ground::TriangleMesh;
  GroundSpec field;
  field.kind = Ground::Heightfield;
  std::printf("block 10 x 6 x 4 cm, exact law (%s):\n", scenes::precisionName());
  std::printf("  plane        t_stop %.4f s travel %.5f m yaw %.5f rad\n", plane.tStop,
              plane.travel, plane.yaw);
  ASSERT_GT(plane.tStop, 0.0);
  for (const GroundSpec* g : {&mesh, &field}) {
    const BlockRun r = runBlock(*g);
    std::printf("  %-12s t_stop %.4f s travel %.5f m yaw %.5f rad patched %ld/%ld\n",
                g == &mesh ? "mesh" : "heightfield", r.tStop, r.travel, r.yaw, r.stepsWithPatch,
                r.steps);
    EXPECT_NEAR(r.tStop, plane.tStop, kSameAsPlane * plane.tStop);
    EXPECT_NEAR(r.travel, plane.travel, kSameAsPlane * plane.travel);
    EXPECT_NEAR(r.yaw, plane.yaw, kSameAsPlane * std::abs(plane.yaw));
    EXPECT_EQ(r.stepsWithPatch, r.steps);
  }
}

// ---- a block on an incline -----------------------------------------------------------
// A 10 cm block (1 kg, half height 2.5 cm, mu 0.3) set down flat on the
// slope z = x tan(alpha): below the friction angle it stays; above, it
// slides down with a = g (sin alpha - mu cos alpha) (the patch's friction is
// mu N opposing a pure translation, for either law).
constexpr double kBlockMu = 0.3;

struct SlopeRun {
  double downhill = 0.0;  // displacement down the slope after tMax [m]
  double speed = 0.0;     // speed down the slope at tMax [m/s]
  long stepsWithPatch = 0, steps = 0;
  long notPatched = 0;
};

SlopeRun runSlope(const GroundSpec& ground, double tMax, Friction f = Friction::Exact) {
  Scene scene(kG);
  scenes::addGround(scene, ground, 1.0);
  btRigidBody* block = scenes::addBlockOnSlope(scene, ground, 0.1, 0.025, 1.0, kBlockMu, 1e-5);
  scenes::optIn(scene, block, f);
  const btVector3 down(btScalar(-std::cos(ground.slope)), 0, btScalar(-std::sin(ground.slope)));
  const btVector3 start = block->getWorldTransform().getOrigin();
  SlopeRun run;
  for (double t = kDt; t <= tMax + 1e-9; t += kDt) {
    scene.step(kDt);
    ++run.steps;
    if (f != Friction::Stock) {
      if (scene.solver().findPatchReport(block)) ++run.stepsWithPatch;
      run.notPatched += scene.solver().stats().notPatched.total();
    }
  }
  run.downhill = double((block->getWorldTransform().getOrigin() - start).dot(down));
  run.speed = double(block->getLinearVelocity().dot(down));
  return run;
}

// Sliding: the speed after 0.5 s is a t within 1 % (the bound; Bullet's
// step integrates a constant acceleration exactly, the first step's
// set-down aside). Holding: the block moves less than kHoldDrift in 1 s
// (the plane's own drift is ~1e-7 m: split-impulse round-off).
constexpr double kSlideRel = 0.01;
constexpr double kHoldDrift = 1e-5;

TEST(TriangleSupports, BlockOnASlopeHoldsBelowTheFrictionAngleAndSlidesAbove) {
  const double holdAngle = 0.5 * std::atan(kBlockMu), slideAngle = std::atan(2 * kBlockMu);
  std::printf("block on a slope, mu %.1f (%s): hold at %.3f rad, slide at %.3f rad\n", kBlockMu,
              scenes::precisionName(), holdAngle, slideAngle);
  struct Case {
    const char* label;
    Ground kind;
    bool inTransform;
  };
  for (const Case& c : {Case{"plane", Ground::Plane, false},
                        Case{"mesh, sloped heights", Ground::TriangleMesh, false},
                        Case{"mesh, tilted body", Ground::TriangleMesh, true},
                        Case{"heightfield, sloped heights", Ground::Heightfield, false},
                        Case{"heightfield, tilted body", Ground::Heightfield, true}}) {
    SCOPED_TRACE(c.label);
    GroundSpec g;
    g.kind = c.kind;
    g.halfSize = 0.5;  // the block slides 0.32 m in 0.5 s
    g.slopeInTransform = c.inTransform;
    g.slope = holdAngle;
    const SlopeRun hold = runSlope(g, 1.0);
    g.slope = slideAngle;
    const double tSlide = 0.5;
    const SlopeRun slide = runSlope(g, tSlide);
    const double a = kG * (std::sin(slideAngle) - kBlockMu * std::cos(slideAngle));
    std::printf("  %-28s hold: moved %.2e m; slide: v %.5f m/s (a t = %.5f), patched %ld/%ld\n",
                c.label, hold.downhill, slide.speed, a * tSlide,
                hold.stepsWithPatch + slide.stepsWithPatch, hold.steps + slide.steps);
    EXPECT_LT(std::abs(hold.downhill), kHoldDrift);
    EXPECT_NEAR(slide.speed, a * tSlide, kSlideRel * a * tSlide);
    EXPECT_EQ(hold.stepsWithPatch, hold.steps);
    EXPECT_EQ(slide.stepsWithPatch, slide.steps);
    EXPECT_EQ(hold.notPatched + slide.notPatched, 0);
  }
}

// ---- what stays on Bullet's points, counted ---------------------------------------------
// The coin (R 5 cm) launched along x from x = 0 meets a crease at x = 6 cm
// (its rim reaches it after 1 cm): a ramp rising at 0.1 rad, and a drop
// falling at 0.1 rad; and it slides off the edge of a small heightfield
// (|x| <= 6 cm). While its face meets the ramp, hangs over the crease or
// over the edge, the contact is Bullet's, counted as a crease; before that
// it is a patch; the world stays finite.
TEST(TriangleSupports, CreasesAndMeshEdgesAreCountedAndLeftToBullet) {
  struct Case {
    const char* label;
    GroundSpec ground;
  };
  std::vector<Case> cases(3);
  cases[0].label = "into a ramp";
  cases[0].ground.kind = Ground::TriangleMesh;
  cases[0].ground.crease = true;
  cases[0].ground.creaseX = 0.06;
  cases[0].ground.slope = 0.1;
  cases[1] = cases[0];
  cases[1].label = "over a drop";
  cases[1].ground.slope = -0.1;
  cases[2].label = "off a small heightfield";
  cases[2].ground.kind = Ground::Heightfield;
  cases[2].ground.halfSize = 0.06;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const CoinRun r = runCoin(c.ground);
    print(c.label, r);
    EXPECT_TRUE(r.finite);
    EXPECT_GT(r.notPatched.crease, 0);
    EXPECT_GT(r.stepsWithPatch, 0);
    EXPECT_LT(r.stepsWithPatch, r.steps);
  }
}

// Bad meshes: either winding and zero-area triangles are geometry the
// patch takes as it is (the run is the plane's); overlapping (duplicated)
// triangles are counted as a bad mesh and left to Bullet; a NaN vertex
// at the grid's corner, away from the coin, leaves the world finite.
TEST(TriangleSupports, BadMeshesAreTakenOrCountedNeverANaN) {
  const CoinRun plane = runCoin({});
  for (MeshDefect d : {MeshDefect::AlternateWinding, MeshDefect::Degenerate}) {
    GroundSpec g;
    g.kind = Ground::TriangleMesh;
    g.defect = d;
    const CoinRun r = runCoin(g);
    print(d == MeshDefect::AlternateWinding ? "alternate winding" : "degenerate triangles", r);
    EXPECT_TRUE(r.finite);
    EXPECT_NEAR(r.tStop, plane.tStop, kSameAsPlane * plane.tStop);
    EXPECT_NEAR(r.ratio, plane.ratio, kSameAsPlane * plane.ratio);
    EXPECT_EQ(r.stepsWithPatch, r.steps);
  }
  GroundSpec dup;
  dup.kind = Ground::TriangleMesh;
  dup.defect = MeshDefect::Duplicate;
  const CoinRun d = runCoin(dup);
  print("duplicated triangles", d);
  EXPECT_TRUE(d.finite);
  EXPECT_GT(d.notPatched.badMesh, 0);
  EXPECT_EQ(d.stepsWithPatch, 0);
  GroundSpec nan;
  nan.kind = Ground::TriangleMesh;
  nan.defect = MeshDefect::NaNVertex;
  const CoinRun n = runCoin(nan);
  print("a NaN vertex, far", n);
  EXPECT_TRUE(n.finite);
  nan.defect = MeshDefect::NaNVertexAtOrigin;
  const CoinRun under = runCoin(nan);
  print("a NaN vertex under the coin", under);
  EXPECT_TRUE(under.finite);
  EXPECT_GT(under.notPatched.badMesh, 0);
}

// A contact left to Bullet's points is stock Bullet's: the terrain demo's
// crease coin (exact law) meets the ramp and is handed back; from the step
// after the hand-back (whose cleared point impulses stock Bullet never
// wrote), its run is bit for bit that of the same world with the coin opted
// out, for as long as the coin has no patch again. (In double that run
// sinks the coin through the mesh at the crease: Bullet's own contact, as
// the opted-out twin shows; a fresh manifold at the same state does not.)
TEST(TriangleSupports, ContactLeftToBulletAtACreaseIsStockBullet) {
  const scenes::TerrainSpec spec;
  const std::vector<scenes::TerrainBody> defs = scenes::terrainBodies(spec);
  std::size_t crease = defs.size();
  for (std::size_t i = 0; i < defs.size(); ++i)
    if (defs[i].region == "crease") crease = i;
  ASSERT_LT(crease, defs.size());
  constexpr int kSteps = 240;
  std::vector<btTransform> poses;
  std::vector<bool> patched;
  int handBack = -1;
  {
    std::vector<btRigidBody*> bodies;
    auto scene = scenes::makeTerrain(spec, Friction::Exact, &bodies);
    btRigidBody* coin = bodies[crease];
    for (int k = 0; k < kSteps; ++k) {
      scene->step(kDt);
      patched.push_back(scene->solver().findPatchReport(coin) != nullptr);
      poses.push_back(coin->getWorldTransform());
      const NotPatchedCounts* np = scene->solver().notPatchedOf(coin);
      if (handBack < 0 && k > 0 && patched[std::size_t(k - 1)] && np && np->crease > 0)
        handBack = k;
    }
  }
  ASSERT_GT(handBack, 0) << "the coin reaches the crease on a patch";
  std::vector<btRigidBody*> bodies;
  auto twin = scenes::makeTerrain(spec, Friction::Exact, &bodies);
  btRigidBody* coin = bodies[crease];
  int compared = 0;
  for (int k = 0; k < kSteps; ++k) {
    if (k == handBack + 1) twin->solver().disablePatchFriction(coin);
    twin->step(kDt);
    if (k <= handBack) continue;
    if (patched[std::size_t(k)]) break;  // a patch again: no longer Bullet's alone
    ASSERT_EQ(coin->getWorldTransform().getOrigin(), poses[std::size_t(k)].getOrigin())
        << "step " << k << " (hand-back at " << handBack << ")";
    ASSERT_EQ(coin->getWorldTransform().getRotation(), poses[std::size_t(k)].getRotation())
        << "step " << k;
    ++compared;
  }
  std::printf("crease coin: handed back at step %d, %d steps equal to stock Bullet's (%s)\n",
              handBack, compared, scenes::precisionName());
  EXPECT_GE(compared, 100);
}

}  // namespace
}  // namespace patchspin::bullet
