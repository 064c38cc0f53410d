// Sliver overlaps (issue 31, finding 8a/8g): in Bullet's BasicExample the
// boxes' faces meet their diagonal neighbours' along an edge, overlaps of
// d^2 / A ~ 1e6. Such a sliver is left to Bullet's points at selection
// (NotPatchedCounts::sliver, kMaxSliverRatio), before any law is built on
// it: no block refuses its input (blockErrors) and nothing is thrown on the
// hot path.
//
// Independent check: the end state against the geometry (a box resting on
// a face has its centre at its half size) and stock Bullet's run.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/friction_block.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace patchspin::bullet {
namespace {

using scenes::Friction;

struct Outcome {
  long blockErrors = 0, slivers = 0, patches = 0;
  double maxSpeed = 0.0;  // at the end [m/s]
  double lowest = 1e300;  // lowest box centre at the end [m]
  bool finite = true;
};

Outcome runBasicExample(Friction f) {
  const scenes::CatalogueEntry& e = scenes::findScene("basic-example");
  std::unique_ptr<scenes::Scene> scene = e.build(f);
  Outcome out;
  const int steps = int(std::lround(e.duration / e.dt));
  for (int i = 0; i < steps; ++i) {
    scene->step(e.dt);
    if (f != Friction::Stock) {
      const PatchSolverStats& s = scene->solver().stats();
      out.blockErrors += s.blockErrors;
      out.slivers += s.notPatched.sliver;
      out.patches += s.patches;
    }
  }
  for (const btRigidBody* b : scene->bodies()) {
    if (b->getInvMass() == 0) continue;
    const btVector3 x = b->getWorldTransform().getOrigin();
    out.finite = out.finite && std::isfinite(double(x.length())) &&
                 std::isfinite(double(b->getLinearVelocity().length()));
    out.maxSpeed = std::max(out.maxSpeed, double(b->getLinearVelocity().length()));
    out.lowest = std::min(out.lowest, double(x.z()));
  }
  return out;
}

// Both laws: no block error in 2 s (exact: 353 before the rule, ellipsoidal
// 1, both slivers), slivers counted, patches formed; the block lands and
// rests on the ground: the lowest box centre within 1 cm of the half size
// 0.1 m (measured 0.0997-0.0999; stock Bullet's 0.080: its points let the
// bottom layer sink 2 cm under the columns at 1/60 s), speeds below 0.1 m/s.
TEST(Slivers, BulletsBasicExampleHasNoBlockErrors) {
  const Outcome stock = runBasicExample(Friction::Stock);
  EXPECT_TRUE(stock.finite);  // (its fastest box at 2 s: 3.5 m/s, still falling apart)
  for (const Friction f : {Friction::Exact, Friction::Ellipsoidal}) {
    const Outcome o = runBasicExample(f);
    EXPECT_EQ(o.blockErrors, 0) << scenes::toString(f);
    EXPECT_GT(o.slivers, 0) << scenes::toString(f);
    EXPECT_GT(o.patches, 0) << scenes::toString(f);
    EXPECT_TRUE(o.finite) << scenes::toString(f);
    EXPECT_NEAR(o.lowest, 0.1, 0.01) << scenes::toString(f);
    EXPECT_LT(o.maxSpeed, 0.1) << scenes::toString(f);
  }
}

}  // namespace
}  // namespace patchspin::bullet
