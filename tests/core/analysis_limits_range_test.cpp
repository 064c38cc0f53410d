// The limit-direction analysis (analysis_limits.cpp) and FlatBodyModel
// (analysis_body.cpp) at the ends of their range: fields of 1e-301 to 1e154,
// tiny mu against huge weights, no friction, overflowing couples, denormal
// parameters. Each direction is checked as a fixed point of the limit field
// itself, or against the same body at unit scale.
#include <patchspin/analysis.hpp>
#include <patchspin/models.hpp>

#include <gtest/gtest.h>

#include "error_matchers.hpp"
#include "fuzz_inputs.hpp"
#include "oracle.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::refusedAsNotFinite;
using testing::throwsNaming;

constexpr double kMax = std::numeric_limits<double>::max();

// Largest |F_o| over the axes and the given directions: the field's own scale.
double fieldScaleOf(const FlatBodyModel& model, const std::vector<LimitDirection>& directions) {
  double scale = 0.0;
  for (const Vec3& w : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY()), Vec3(Vec3::UnitZ())})
    scale = std::max(scale, model.limitField(w).norm());
  for (const LimitDirection& d : directions) scale = std::max(scale, model.limitField(d.w).norm());
  return scale;
}

// fuzz round 2, item 20
// The eigenvalues are homogeneous of degree 1 in the field: a field of ~1e154
// has those of the same body at g times 1e-140, times 1e140, to kScaleTol.
TEST(LimitDirections, EigenvaluesOfAHugeFieldScaleWithIt) {
  FlatBody body;
  body.shape = PatchShape::disk(1.0, Vec2(1.0, -1.0));
  body.mass = 1.0;
  body.Jz = 1.0;
  body.Jxz = 1.0;
  body.Jyz = 1.0;
  body.com = Vec3(1.0, 1.0, 1.0);
  body.mu = 2039552.0;
  body.g = 1.3078516774228077e+148;
  FlatBody scaled = body;
  scaled.g = body.g * 1e-140;
  LimitOptions options;
  options.seeds = 20;
  const LimitAnalysis huge = findLimitDirections(FlatBodyModel(body, Model::Exact), options);
  const LimitAnalysis reference = findLimitDirections(FlatBodyModel(scaled, Model::Exact), options);
  ASSERT_FALSE(huge.directions.empty());
  ASSERT_EQ(huge.directions.size(), reference.directions.size());
  // the solver's own tolerances are relative to the field scale, so the two
  // runs agree to its polish (1e-11 of the scale): checked to 1e-8
  constexpr double kScaleTol = 1e-8;
  for (std::size_t i = 0; i < huge.directions.size(); ++i) {
    const LimitDirection& d = huge.directions[i];
    EXPECT_TRUE(d.eigenvalues.allFinite());
    for (int k = 0; k < 2; ++k) {
      const std::complex<double> expected = reference.directions[i].eigenvalues[k] * 1e140;
      EXPECT_LE(std::abs(d.eigenvalues[k] - expected),
                kScaleTol * (std::abs(expected) + std::abs(d.rdot)));
    }
  }
}

// fuzz round 3, item 30
// Couples of 6.8e283: each direction is a fixed point of the limit field
// (F_o parallel to w) to kFixedPointTol of |F_o(w)|, with finite rate,
// eigenvalues and residual; or an Error naming the range.
TEST(LimitDirections, HugeTippingCoupleGivesFixedPointsOrAnError) {
  FlatBody body;
  body.shape = PatchShape::disk(0.5, Vec2(0.5, -5.0497563083659848e-195));
  body.mass = 0.5;
  body.Jz = 0.5;
  body.Jxz = 0.5;
  body.Jyz = 0.5;
  body.com = Vec3(0.5, 0.5, 0.5);
  body.mu = 0.5;
  body.g = 0.5;
  body.force = Vec2(0.5, 0.5);
  body.torque = Vec3(6.782694702302148e+283, 0.0, 0.0);
  const FlatBodyModel model(body, Model::Ellipsoidal);
  LimitOptions options;
  options.seeds = 20;
  constexpr double kFixedPointTol = 1e-8;
  try {
    const LimitAnalysis result = findLimitDirections(model, options);
    for (const LimitDirection& d : result.directions) {
      EXPECT_TRUE(std::isfinite(d.residual));
      EXPECT_TRUE(std::isfinite(d.rdot));
      EXPECT_TRUE(d.eigenvalues.allFinite());
      const Vec3 F = model.limitField(d.w);
      ASSERT_TRUE(F.allFinite());
      EXPECT_LE((F - d.w.dot(F) * d.w).stableNorm(), kFixedPointTol * F.stableNorm());
    }
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("range"), std::string::npos) << e.what();
  }
}

// fuzz round 3, item 36
// mu = 2.6e-231 with g = 4e289 (friction dominates), and a spin couple against
// Jz = 1e300: each direction is a fixed point of the limit field, relative to
// the field's scale.
TEST(LimitDirections, TinyMuAgainstAHugeWeightGivesFixedPoints) {
  FlatBody body;
  body.shape = PatchShape::disk(0.5, Vec2(0.5, 0.5));
  body.mass = 0.5;
  body.Jz = 0.5;
  body.Jxz = 0.5;
  body.Jyz = 0.5;
  body.com = Vec3(1.0, 2.5865632706146919e-231, 2.5865632706146919e-231);
  body.mu = 2.5865632706146919e-231;
  body.g = 4.0161949803506898e+289;
  body.force = Vec2(2.0000028348584991, 0.5);
  body.torque = Vec3(0.5, 0.5, 113080.0);
  body.rho = 0.5;
  const FlatBodyModel model(body, Model::Ellipsoidal);
  LimitOptions options;
  options.seeds = 20;
  const LimitAnalysis result = findLimitDirections(model, options);
  ASSERT_FALSE(result.directions.empty());
  // the solver polishes to 1e-11 of its field scale
  constexpr double kFixedPointTol = 1e-8;
  for (const LimitDirection& d : result.directions) {
    const Vec3 F = model.limitField(d.w);
    EXPECT_LE((F - d.w.dot(F) * d.w).norm(), kFixedPointTol * F.norm());
  }

  // a spin couple T_z = 1.9e185 against Jz = 1e300 (a field part of 1e-115)
  // set the unit scale, while friction's part was 1e8: directions off by
  // 4e-4 of the field (found by fuzzing); the parts are now weighed
  // through M^-1
  FlatBody frozen;
  frozen.shape = PatchShape::polygon({{1.4387912809451864, -0.7602872306978985},
                                      {0.7602872306978985, -0.56120871905481362},
                                      {0.56120871905481362, -1.2397127693021015},
                                      {1.2397127693021015, -1.4387912809451864}});
  frozen.mass = 1.0;
  frozen.Jz = 1e300;
  frozen.Jxz = 1.0;
  frozen.Jyz = 7.3555384005885571e-09;
  frozen.com = Vec3(0.5, 0.5, 0.5);
  frozen.mu = 0.5;
  frozen.g = 0.5;
  frozen.force = Vec2(0.5, 0.5);
  frozen.torque = Vec3(0.5, -851968.0, 1.9035990625065692e+185);
  const FlatBodyModel frozenModel(frozen, Model::Exact);
  // this body's field has a zero, w = (-0.411, 0.911, -5.4e-6) (|F| = 7.7e-10
  // there against ~0.1 at 1e-6 from it in w_z, both components changing
  // sign): F = 0 is parallel to w, a limit direction, where a bound relative
  // to |F(w)| cannot hold. The bound is relative to the field's scale: the
  // largest |F| over w and the three axes.
  double fieldScale = 0.0;
  for (int i = 0; i < 3; ++i)
    fieldScale = std::max(fieldScale, frozenModel.limitField(Vec3::Unit(i)).norm());
  for (const LimitDirection& d : findLimitDirections(frozenModel, options).directions) {
    const Vec3 F = frozenModel.limitField(d.w);
    EXPECT_LE((F - d.w.dot(F) * d.w).norm(), kFixedPointTol * std::max(F.norm(), fieldScale));
  }
}

// fuzz round 3, items 31 and 33
// The field is linear in the loads: every load times 2^-1000 gives the same
// directions, with rates times 2^-1000, to the solver's polish.
TEST(LimitDirections, TinyFieldHasTheDirectionsOfTheUnscaledBody) {
  FlatBody body;
  body.shape = PatchShape::rectangle(0.4, 0.2);
  body.com = Vec3(0.02, -0.01, 0.3);
  body.mu = 0.4;
  body.force = Vec2(0.5, -0.2);
  body.torque = Vec3(0.01, 0.02, 0.05);
  FlatBody tiny = body;
  const double c = std::ldexp(1.0, -1000);
  tiny.g = body.g * c;
  tiny.force = body.force * c;
  tiny.torque = body.torque * c;
  constexpr double kDirectionTol = 1e-8;
  for (Model m : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(m));
    LimitOptions options;
    options.seeds = 20;
    const LimitAnalysis reference = findLimitDirections(FlatBodyModel(body, m), options);
    const LimitAnalysis scaled = findLimitDirections(FlatBodyModel(tiny, m), options);
    ASSERT_FALSE(reference.directions.empty());
    ASSERT_EQ(scaled.directions.size(), reference.directions.size());
    double rateScale = 0.0;  // the field's size along its fixed points
    for (const LimitDirection& d : reference.directions)
      rateScale = std::max(rateScale, std::abs(d.rdot));
    for (std::size_t i = 0; i < reference.directions.size(); ++i) {
      EXPECT_LT((scaled.directions[i].w - reference.directions[i].w).norm(), kDirectionTol);
      EXPECT_NEAR(std::ldexp(scaled.directions[i].rdot, 1000), reference.directions[i].rdot,
                  kDirectionTol * rateScale);
    }
  }
}

// fuzz round 3, item 31
// mu = 0: the field is the constant c = M^-1 Q_e, whose fixed points are
// w = +-c / |c| with rate +-|c|; with no load either, the sphere continuum
// with rate 0.
TEST(LimitDirections, WithoutFrictionFollowTheExternalWrench) {
  FlatBody body;
  body.shape = PatchShape::disk(0.3);
  body.com = Vec3(0.05, 0.0, 0.2);
  body.mu = 0.0;
  body.force = Vec2(1.0, 2.0);
  body.torque = Vec3(0.0, 0.0, 0.5);
  constexpr double kTol = 1e-12;
  for (Model m : {Model::Ellipsoidal, Model::Exact}) {
    SCOPED_TRACE(toString(m));
    const FlatBodyModel model(body, m);
    const Vec3 c = model.massMatrix().inverse() * model.externalWrench(model.bodyLoads());
    LimitOptions options;
    options.seeds = 20;
    const LimitAnalysis result = findLimitDirections(model, options);
    ASSERT_EQ(result.directions.size(), 2u);
    EXPECT_TRUE(result.continua.empty());
    for (const LimitDirection& d : result.directions) {
      const double sign = d.w.dot(c) > 0.0 ? 1.0 : -1.0;
      EXPECT_LT((d.w - sign * c.normalized()).norm(), kTol);
      EXPECT_NEAR(d.rdot, sign * c.norm(), kTol * c.norm());
    }
    FlatBody still = body;
    still.force.setZero();
    still.torque.setZero();
    const LimitAnalysis none = findLimitDirections(FlatBodyModel(still, m), options);
    EXPECT_TRUE(none.directions.empty());
    ASSERT_EQ(none.continua.size(), 1u);
    EXPECT_TRUE(none.continua[0].sphere);
    EXPECT_EQ(none.continua[0].rdot, 0.0);
  }
}

// fuzz round 4, item 42
// A centre of mass 9e117 m off O: finite rates, residuals and eigenvalues, or
// an Error naming the overflow or the mass matrix.
TEST(LimitDirections, OverflowingFieldGivesFiniteOutputOrAnError) {
  FlatBody body;
  body.shape = PatchShape::polygon({{0.52408846025116795, 0.51315958581171628},
                                    {0.51428142560970502, 0.52344076574181153},
                                    {0.50064769450935642, 0.5274410114214213},
                                    {0.48684041418828378, 0.52408846025116795},
                                    {0.47655923425818847, 0.51428142560970502},
                                    {0.47255898857857875, 0.50064769450935642},
                                    {0.47591153974883205, 0.48684041418828378},
                                    {0.48571857439029498, 0.47655923425818847},
                                    {0.49935230549064352, 0.47255898857857875},
                                    {0.51315958581171628, 0.47591153974883205},
                                    {0.52344076574181153, 0.48571857439029498},
                                    {0.5274410114214213, 0.49935230549064352}});
  body.mass = 8647606272.0;
  body.Jz = 1.9010683772582826e+215;
  body.com = Vec3(-8.9595518175365068e+117, 1.0, 1.0);
  body.mu = 1.0;
  body.g = 1.0;
  for (bool sphere : {false, true}) {
    SCOPED_TRACE(sphere ? "sphere solver" : "linear solver");
    LimitOptions options;
    options.seeds = 20;
    options.sphereSolver = sphere;
    try {
      const LimitAnalysis result = findLimitDirections(FlatBodyModel(body, Model::Exact), options);
      for (const LimitDirection& d : result.directions) {
        EXPECT_TRUE(std::isfinite(d.rdot));
        EXPECT_TRUE(std::isfinite(d.residual));
        EXPECT_TRUE(d.eigenvalues.allFinite());
      }
      for (const LimitContinuum& c : result.continua) EXPECT_TRUE(std::isfinite(c.rdot));
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("overflows") != std::string::npos ||
                  what.find("mass matrix") != std::string::npos)
          << what;
    }
  }
}

// fuzz round 7, item 54
// mu = 1.7e-279, g = 4.3e300, z_c = 1.7e266 m (z_c enters the pressure, not
// the field's scale): with both solvers, each direction is a fixed point of
// limitField (Eq. (98)) to kFixedPoint of the field's scale.
TEST(LimitDirections, HighCentreOfMassWithTinyMuGivesFixedPoints) {
  FlatBody body;
  body.shape = PatchShape::disk(0.5, Vec2(0.5, 0.5));
  body.mass = 0.5;
  body.Jz = 57853952.0;
  body.Jxz = 0.5;
  body.Jyz = 0.5;
  body.com = Vec3(6.7815618489184211e-310, 2.2250738585072014e-308, 1.7108663708439404e+266);
  body.mu = 1.707867266264823e-279;
  body.g = 4.2576413334806225e+300;
  body.force = Vec2(0.5, 1.3202896917249277e-192);
  body.torque = Vec3(1.7078672649790534e-279, 9.2708718708331899e-313, 0.0);
  const FlatBodyModel model(body, Model::Ellipsoidal);
  // the fuzz target's slack: the polish reaches 1e-11 of the field
  // (kResidualTol; measured here 2.5e-17, M being diagonal to round-off with
  // x_c, y_c denormal); 1e-6 is the target's limit, far above both
  constexpr double kFixedPoint = 1e-6;
  for (bool sphere : {false, true}) {
    LimitOptions options;
    options.sphereSolver = sphere;
    const LimitAnalysis result = findLimitDirections(model, options);
    ASSERT_FALSE(result.directions.empty()) << (sphere ? "sphere solver" : "(111)");
    const double scale = fieldScaleOf(model, result.directions);
    for (const LimitDirection& d : result.directions) {
      const Vec3 F = model.limitField(d.w);
      EXPECT_NEAR(d.w.norm(), 1.0, 1e-12);
      EXPECT_LT((F - d.w.dot(F) * d.w).norm(), kFixedPoint * scale)
          << (sphere ? "sphere solver" : "(111)") << ", direction " << d.w.transpose();
    }
  }
}

// fuzz round 9, item 63 (the fuzz input)
// A tipping couple beyond double (com 113,080 m from O under g = DBL_MAX): the
// rest pressure is refused as not finite, and the body by findLimitDirections.
TEST(FlatBodyModel, RefusesARestContactWithAnOverflowingCouple) {
  FlatBody body;
  body.shape = testing::ilogbQuadrilateral();
  body.mass = 0.5;
  body.Jz = 0.5;
  body.Jxz = 0.5;
  body.Jyz = 0.5;
  body.com = Vec3(113080.0, 0.5, 0.5);
  body.mu = 2.5810746893922954e-189;
  body.g = kMax;
  body.force = Vec2(1e-300, 0.0);
  const long double couple = 113080.0L * 0.5L * static_cast<long double>(kMax);
  ASSERT_GT(couple, static_cast<long double>(kMax));  // the couple is not a double
  for (const Model model : {Model::Ellipsoidal, Model::Exact}) {
    const FlatBodyModel flat(body, model);
    EXPECT_TRUE(refusedAsNotFinite([&] { flat.contactAtRest(Vec3::Zero(), flat.bodyLoads()); }));
    EXPECT_THROW(findLimitDirections(flat, LimitOptions{}), Error);
  }
}

// fuzz round 5, item 46
// A denormal mu or g is refused by name; mu = 0 and the smallest normal mu and
// g are accepted.
TEST(FlatBodyModel, RefusesADenormalMuOrG) {
  FlatBody body;
  body.shape = PatchShape::disk(0.5, Vec2(0.5, 1.0));
  body.mass = 0.5;
  body.Jz = 0.5;
  body.com = Vec3(5928648704.0, 6.5947378298252455e-96, 6.5947378298252455e-96);
  body.mu = 2.7421503123034312e-310;
  body.g = 8496.0;
  body.force = Vec2(2.5303451915533642e-306, 0.0);
  EXPECT_TRUE(throwsNaming([&] { FlatBodyModel(body, Model::Exact); }, {"mu"}));
  FlatBody heavy;
  heavy.shape = PatchShape::disk(0.5, Vec2(1.0, 1.0));
  heavy.mass = 0.5;
  heavy.Jz = 16911433728.0;
  heavy.com = Vec3(0.0, -1.0, 0.0);
  heavy.mu = 2.627630884498734e+256;
  heavy.g = 1.8280428896126122e-322;
  EXPECT_TRUE(throwsNaming([&] { FlatBodyModel(heavy, Model::Ellipsoidal); }, {"gravity"}));
  FlatBody edge;
  edge.mu = 0.0;
  EXPECT_NO_THROW(FlatBodyModel(edge, Model::Ellipsoidal));
  edge.mu = std::numeric_limits<double>::min();
  edge.g = std::numeric_limits<double>::min();
  EXPECT_NO_THROW(FlatBodyModel(edge, Model::Ellipsoidal));
}

}  // namespace
}  // namespace patchspin
