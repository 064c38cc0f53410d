// Sliver overlaps (issue 31, finding 8a/8g): in Bullet's BasicExample the
// boxes' faces meet their diagonal neighbours' along an edge, overlaps of
// d^2 / A ~ 1e6. Such a sliver is left to Bullet's points at selection
// (NotPatchedCounts::sliver, kMaxSliverRatio), before any law is built on
// it: no block refuses its input (blockErrors) and nothing is thrown on the
// hot path.
//
// Independent check: stock Bullet's run of the same scene (finite, as the
// patch runs must stay).
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
  }
  return out;
}

// Both laws: no block error in 2 s (float, before the rule: exact 353,
// ellipsoidal 1, both on slivers), patches formed, every body finite. The
// slivers are float's: its round-off leaves the diagonal neighbours' faces
// overlapping by ~1e-7 m, counted here; in double they meet exactly along
// the edge (no overlap, measured 0 slivers). (The heap's own motion is
// chaotic and not judged: measured at 2 s, float: patch at rest, lowest box
// centre 0.0997-0.0999 m, stock Bullet's fastest box 3.5 m/s; double: a
// box still tumbling at 1.9-2.4 m/s with either law.)
TEST(Slivers, BulletsBasicExampleHasNoBlockErrors) {
  const Outcome stock = runBasicExample(Friction::Stock);
  EXPECT_TRUE(stock.finite);
  for (const Friction f : {Friction::Exact, Friction::Ellipsoidal}) {
    const Outcome o = runBasicExample(f);
    EXPECT_EQ(o.blockErrors, 0) << scenes::toString(f);
    if (!scenes::kDoublePrecision) {
      EXPECT_GT(o.slivers, 0) << scenes::toString(f);
    }
    EXPECT_GT(o.patches, 0) << scenes::toString(f);
    EXPECT_TRUE(o.finite) << scenes::toString(f);
  }
}

}  // namespace
}  // namespace patchspin::bullet
