// Tests of the friction block part (parts/friction_block_part.hpp): its
// work-saving rules (quick stick, reuse, deferred refresh) return what a
// plain block solve with the refreshed law returns; a refresh sets the law's
// pressure to the normal block's loads; a refused input keeps the impulse.
#include <patchspin/friction_block.hpp>
#include <patchspin/parts/friction_block_part.hpp>

#include "patch_test_bodies.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <random>

namespace patchspin::parts {
namespace {

// The block solver's own accuracy (1e-12 relative) and a 3x3 inverse.
constexpr double kBlockTol = 1e-9;

struct PatchBlock {
  PatchShape shape = PatchShape::rectangle(0.08, 0.05);
  FrictionPatch law{shape, LinearPressure::uniform(shape, 1.0), 0.5};
  PatchOutlineSummary outline = summarizeOutline(shape);
  PatchBlocks k;
  FrictionBlockState fb;
  StickCertificates certs;
  explicit PatchBlock(std::mt19937& rng, Model model) {
    const PatchBody a = testing::randomBody(rng), ground;
    EXPECT_TRUE(
        makePatchBlocks(patchEffectiveMass(a, ground, testing::randomRotation(rng), 0.03), k));
    fb.model = model;
    fb.mu = 0.5;
    fb.rho = law.rho();
    fb.dt = 0.01;
    fb.law.pressureCop = shape.centroid();
  }
};

// The reference: the law refreshed with the loads, then one block solve.
FrictionBlockResult reference(const PatchBlock& s, Model model, const Vec3& slip,
                              const Vec3& lamN) {
  FrictionPatch law = s.law;
  const PatchLoads raw = toLoads(lamN);
  const PatchLoads loads = nearestAdmissibleLoads(law.shape(), raw, law.rho());
  law.setLoads(PatchLoads{loads.Pz / s.fb.dt, loads.Tx / s.fb.dt, loads.Ty / s.fb.dt});
  FrictionBlockInput in;
  in.b = slip;
  in.K = s.k.Ks;
  in.L = s.fb.mu * lamN[0];
  return solveFrictionBlock(law, model, in);
}

TEST(FrictionBlockPart, WorkSavingRulesReturnThePlainSolve) {
  for (const Model model : {Model::Ellipsoidal, Model::Exact}) {
    std::mt19937 rng(61);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int sticks = 0, slips = 0;
    for (int trial = 0; trial < 100; ++trial) {
      PatchBlock s(rng, model);
      const Vec3 lamN(0.1, 0.002 * u(rng), 0.002 * u(rng));  // N s; centre of pressure inside
      const Vec3 slip(0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng));
      const FrictionBlockResult expected = reference(s, model, slip, lamN);
      FrictionPartSettings settings;
      FrictionPartCounters counters;
      bool refreshed = false;
      // two visits with the same input: the second is reused or quick
      Vec3 lamF = Vec3::Zero();
      for (int visit = 0; visit < 2; ++visit) {
        lamF =
            solveFrictionVelocity(s.fb, s.law, s.certs, s.outline, s.k, true, slip + s.k.Ks * lamF,
                                  lamF, lamN, 0, settings, counters, refreshed);
        EXPECT_EQ(refreshed, visit == 0);
        EXPECT_EQ(s.fb.sticking, expected.sticking) << "trial " << trial << " visit " << visit;
        EXPECT_LT((lamF - expected.impulse).norm(), kBlockTol * (1.0 + expected.impulse.norm()));
      }
      expected.sticking ? ++sticks : ++slips;
      EXPECT_EQ(counters.pressureRefreshes, 1);
      EXPECT_LE(counters.blockSolves, 2);
    }
    EXPECT_GT(sticks, 10);
    EXPECT_GT(slips, 10);
  }
}

// A refresh sets the law to the linear pressure of the loads, Eq. (94) (a
// centre of pressure in the rectangle's kern: the pressure is >= 0).
TEST(FrictionBlockPart, RefreshSetsTheLawsPressureFromTheLoads) {
  std::mt19937 rng(62);
  PatchBlock s(rng, Model::Ellipsoidal);
  const Vec3 lamN(0.1, 0.0003, -0.0004);  // centre of pressure (4, 3) mm
  FrictionPartCounters counters;
  bool refreshed = false;
  solveFrictionVelocity(s.fb, s.law, s.certs, s.outline, s.k, true, Vec3(0.1, 0.0, 0.0),
                        Vec3::Zero(), lamN, 0, FrictionPartSettings(), counters, refreshed);
  ASSERT_TRUE(refreshed);
  const PatchLoads l = toLoads(lamN);
  const FrictionPatch expected(
      s.shape, LinearPressure::fromLoads(s.shape, {l.Pz / 0.01, l.Tx / 0.01, l.Ty / 0.01}), 0.5);
  EXPECT_LT((s.law.Pi() - expected.Pi()).norm(), 1e-12);
  EXPECT_EQ(s.fb.law.pressureCop, Vec2(l.Ty / l.Pz, -l.Tx / l.Pz));
  // the quick test after the refresh uses the new law's Pi^-1
  EXPECT_LT((s.fb.law.piInv * expected.Pi() - Mat3::Identity()).norm(), 1e-12);
}

// A block that refuses its input (here: a non-finite slip) keeps its impulse
// and marks the patch failed.
TEST(FrictionBlockPart, RefusedInputKeepsTheImpulse) {
  std::mt19937 rng(63);
  PatchBlock s(rng, Model::Exact);
  FrictionPartCounters counters;
  bool refreshed = false;
  const Vec3 before(0.01, -0.02, 0.0);
  const Vec3 lamF =
      solveFrictionVelocity(s.fb, s.law, s.certs, s.outline, s.k, true, Vec3(NAN, 0.0, 0.0), before,
                            Vec3(0.1, 0.0, 0.0), 0, FrictionPartSettings(), counters, refreshed);
  EXPECT_EQ(lamF, before);
  EXPECT_TRUE(s.fb.failed);
  EXPECT_EQ(counters.blockErrors, 1);
}

TEST(FrictionBlockPart, NoNormalImpulseNoFriction) {
  std::mt19937 rng(64);
  PatchBlock s(rng, Model::Ellipsoidal);
  FrictionPartCounters counters;
  bool refreshed = true;
  const Vec3 lamF = solveFrictionVelocity(s.fb, s.law, s.certs, s.outline, s.k, true,
                                          Vec3(0.1, 0.0, 0.0), Vec3(0.3, 0.0, 0.0), Vec3::Zero(), 0,
                                          FrictionPartSettings(), counters, refreshed);
  EXPECT_EQ(lamF, Vec3::Zero());
  EXPECT_FALSE(refreshed);
}

// The support of a stacked patch can take a share while its impulse stays
// inside its ellipsoidal limit set L Pi B, and not beyond.
TEST(FrictionBlockPart, SupportTakesAShareOnlyInsideItsLimitSet) {
  std::mt19937 rng(65);
  PatchBlock s(rng, Model::Ellipsoidal);
  const Vec3 lamN(0.1, 0.0, 0.0);  // L = 0.05 N s, uniform pressure: Pi of the rectangle
  const Vec3 inside = 0.9 * 0.05 * (s.law.Pi() * Vec3(1.0, 0.0, 0.0));
  EXPECT_TRUE(frictionCanTake(s.fb, s.law, lamN, inside, Vec6::Zero()));
  Vec6 share = Vec6::Zero();
  share.tail<3>() = 0.2 * inside;
  EXPECT_FALSE(frictionCanTake(s.fb, s.law, lamN, inside, share));
}

}  // namespace
}  // namespace patchspin::parts
