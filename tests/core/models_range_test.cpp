// FrictionPatch and the two laws (models.cpp) at the ends of their range:
// bad parameters and slip directions are refused by name, a tiny mu scales
// the law, extreme inputs give an Error or a finite answer, and the exact
// polygon law far from O keeps its normalisation.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include "error_matchers.hpp"
#include "oracle.hpp"
#include "vertex_mean_loads.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace patchspin {
namespace {

using testing::loadsAboutVertexMean;
using testing::LongLoads;
using testing::throwsNaming;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The exact law's round-off model of friction_block.cpp (requireExactLawDigits)
// without its constant: eps max(1, diameter^2 / A) times the pressure's
// terms about O over Pz.
double lawModel(const PatchShape& shape, const LinearPressure& p, double Pz) {
  const double terms =
      shape.area() *
      (std::abs(p.p0) + (std::abs(p.cx) + std::abs(p.cy)) * shape.maxDistanceFromOrigin()) / Pz;
  return kEps * std::max(1.0, shape.diameter() / shape.area() * shape.diameter()) * terms;
}

std::vector<Vec2> far23gon() {
  return {{0.99330679445895709, -0.51251019147067856}, {0.99328221757588198, -0.51258869994415635},
          {0.99327973340295261, -0.51267092787417023}, {0.99329952617991091, -0.51275077679131864},
          {0.99334012796703552, -0.51282232466670141}, {0.99339852751551672, -0.51288026512171103},
          {0.99347039359800327, -0.51292030097785934}, {0.99355039623592289, -0.51293946295884774},
          {0.9936326019996089, -0.51293632990820637},  {0.99371091406363488, -0.51291113418996881},
          {0.99377952438046591, -0.51286574445529398}, {0.99383334443677396, -0.51280352705315835},
          {0.99386838264519284, -0.51272909636365238}, {0.99388204038209371, -0.51264797257051975},
          {0.99387330471561031, -0.51256617225437973}, {0.9938428235301624, -0.51248976217046915},
          {0.99379285747583324, -0.51242440930515909}, {0.99372711230629251, -0.51237496058149945},
          {0.99365046404000079, -0.51234508338511164}, {0.99356859732822678, -0.51233699357097273},
          {0.9934875838504672, -0.51235129112358868},  {0.9934134320057556, -0.51238691565888916},
          {0.993351641297192, -0.51244122506806211}};
}

// The 37-gon of diameter 4e-4 m about (0.5, 1), 2,800 diameters from O
// (fuzz corpus: refused-exact-far-37gon-pz-no-digits-denormal-L).
std::vector<Vec2> far37gon() {
  return {{0.5001983642578125, 1.0000000000019837},   {0.50019551096820902, 1.0000335237242479},
          {0.50018703318401625, 1.0000660830300021},  {0.5001731747956496, 1.0000967412473003},
          {0.50015433448371083, 1.0001246163950499},  {0.50013105424967164, 1.0001489065560023},
          {0.50010400382347941, 1.0001689129464522},  {0.50007396139664484, 1.0001840600189718},
          {0.50004179123509007, 1.0001939120198624},  {0.50000841881579083, 1.0001981855249966},
          {0.49997480420248935, 1.0001967575934121},  {0.49994191442640845, 1.0001896693041008},
          {0.49991069566652357, 1.0001771245742404},  {0.49988204602971686, 1.0001594842928692},
          {0.49985678971387693, 1.0001372559387642},  {0.49983565329722646, 1.0001110789812024},
          {0.4998192448359895, 1.0000817064835925},   {0.499808036371721, 1.000049983439212},
          {0.49980235035153081, 1.0000168224622903},  {0.49980235035186726, 0.99998317753375676},
          {0.49980803637272064, 0.99995001655694871}, {0.49981924483762363, 0.99991829351279249},
          {0.49983565329944801, 0.99988892101551063}, {0.49985678971662206, 0.9998627440583715},
          {0.49988204603290654, 0.99984051570477184}, {0.49991069567006607, 0.99982287542397352},
          {0.49994191443020181, 0.99981033069473757}, {0.49997480420642454, 0.99980324240608398},
          {0.50000841881975455, 0.9998018144751718},  {0.5000417912389683, 0.99980608798097337},
          {0.50007396140032612, 0.99981593998250762}, {0.5001040038268576, 0.99983108705562784},
          {0.50013105425264981, 0.99985109344661871}, {0.50015433448620317, 0.99987538360803685},
          {0.5001731747975845, 0.99990325875616326},  {0.50018703318533786, 0.99993391697373857},
          {0.5001955109688796, 0.99996647627966229}};
}

// fuzz round 1, item 3
// A negative, NaN or infinite mu, rho more than 1e12 off Eq. (11), mu Pz
// overflowing, a denormal Pz, non-finite or non-positive loads: an Error naming
// the parameter; rho <= 0 selects Eq. (11) (documented fallback).
TEST(FrictionPatch, RefusesBadParametersByName) {
  const PatchShape disk = PatchShape::disk(0.05);
  const LinearPressure p = LinearPressure::uniform(disk, 10.0);
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, -0.3); }, {"mu"}));
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, kNan); }, {"mu"}));
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, kInf); }, {"mu"}));
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, 0.3, kInf); }, {"rho"}));
  // rho more than 1e12 off Eq. (11) (found by fuzzing: rho = 1e-300 gave NaN)
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, 0.3, 1e-300); }, {"rho"}));
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, 0.3, 1e20); }, {"rho"}));
  // documented fallback: rho <= 0 selects Eq. (11)
  EXPECT_EQ(FrictionPatch(disk, p, 0.3, -1.0).rho(), disk.defaultRho());
  EXPECT_EQ(FrictionPatch(disk, p, 0.3, 0.0).rho(), disk.defaultRho());
  // mu Pz overflowing (found by fuzzing: mu = 1e300 gave Q = inf)
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, p, 1e308); }, {"out of range"}));
  FrictionPatch patch(disk, p, 0.3);
  EXPECT_TRUE(throwsNaming([&] { patch.setMu(1e308); }, {"out of range"}));
  EXPECT_EQ(patch.mu(), 0.3);  // a refused update changes nothing
  // a denormal normal force (found by fuzzing: the unit law divided by it)
  EXPECT_TRUE(throwsNaming([&] { FrictionPatch(disk, HertzPressure{5e-324}, 0.3); }, {"pz"}));
  // non-finite or non-positive loads
  EXPECT_TRUE(throwsNaming([&] { patch.setLoads({kInf, 0.0, 0.0}); }, {"pz"}));
  EXPECT_TRUE(throwsNaming([&] { patch.setLoads({-1.0, 0.0, 0.0}); }, {"pz", "normal force"}));
  EXPECT_TRUE(throwsNaming([&] { patch.setLoads({0.0, 0.0, 0.0}); }, {"pz", "normal force"}));
  EXPECT_TRUE(throwsNaming([&] { patch.setLoads({1.0, kNan, 0.0}); }, {"tx"}));
}

// fuzz round 1, items 4 and 6
// A NaN, infinite or zero w is refused (zero slip through QofSlip: sticking);
// a denormal w gives the law at w / |w|, its Jacobian an Error; a bad accuracy
// tolerance is refused.
TEST(FrictionPatch, RefusesBadSlipDirections) {
  const PatchShape square = PatchShape::rectangle(0.1, 0.1);
  const FrictionPatch patch(square, LinearPressure::fromLoads(square, {10.0, 0.05, -0.02}), 0.4);
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    EXPECT_TRUE(throwsNaming([&] { patch.Q(model, Vec3(kNan, 0.0, 0.0)); }, {"w"}));
    EXPECT_TRUE(throwsNaming([&] { patch.Q(model, Vec3(0.0, kInf, 0.0)); }, {"w"}));
    EXPECT_TRUE(throwsNaming([&] { patch.Q(model, Vec3::Zero()); }, {"w"}));
    // zero slip: the documented fallback is "sticking", std::nullopt
    EXPECT_FALSE(patch.QofSlip(model, Vec3::Zero()).has_value());
    EXPECT_FALSE(patch.QofSlip(model, -Vec3::Zero()).has_value());
  }
  // a denormal w: Q depends on the direction only, so it is that of w / |w|;
  // its Jacobian (~1/|w|) does not fit a double: Error, not inf / NaN
  const Vec3 tiny(5e-324, 0.0, 0.0);
  EXPECT_EQ(patch.exactQ(tiny), patch.exactQ(Vec3::UnitX()));
  EXPECT_EQ(patch.ellipsoidalQ(tiny), patch.ellipsoidalQ(Vec3::UnitX()));
  Mat3 J;
  EXPECT_TRUE(throwsNaming([&] { patch.exactQ(tiny, &J); }, {"dq/dw"}));
  // an infinite accuracy tolerance (the polygon path accepted it)
  EXPECT_TRUE(throwsNaming([&] { patch.exactQ(Vec3::UnitX(), nullptr, ExactAccuracy{kInf}); },
                           {"tolerance"}));
  EXPECT_TRUE(throwsNaming([&] { patch.exactQ(Vec3::UnitX(), nullptr, ExactAccuracy{-1.0}); },
                           {"tolerance"}));
}

// fuzz round 1, item 5
// Q = mu (Q at mu = 1) while Q is a normal double (mu = 1e-305), to round-off.
TEST(FrictionPatch, TinyMuScalesTheLawWithoutEarlyUnderflow) {
  const PatchShape square = PatchShape::rectangle(1e-5, 1e-5, Vec2(2e-6, 1e-6));
  const LinearPressure p = LinearPressure::fromLoads(square, {1.0, 1e-6, -2e-6});
  const double mu = 1e-305;
  const FrictionPatch tiny(square, p, mu), unit(square, p, 1.0);
  // both sides are normal doubles computed from the same basis: round-off
  constexpr double kRoundOff = 1e-14;
  for (const Vec3& w : {Vec3(0.3, -0.4, 0.8), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0)}) {
    const Vec3 expected = unit.exactQ(w);
    const Vec3 got = tiny.exactQ(w) / mu;
    EXPECT_LT((got - expected).norm(), kRoundOff * expected.norm()) << w.transpose();
  }
}

// fuzz rounds 1-2, items 13, 14 and 16
// An SPD K whose products overflow, projections of torques 1e300 and 1e154
// times Pz rho, a sliver 1e8 m long, an exact Q whose sum overflows, a tiny
// disk's unit law: an Error naming the problem, or a finite answer that is
// admissible, no farther than the uniform pressure, or inside the set.
TEST(DoubleRange, ExtremeInputsGiveAnErrorOrAFiniteAnswer) {
  // an SPD K whose products overflow: Error, not a NaN impulse
  const PatchShape small = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  const FrictionPatch patch(small, LinearPressure::fromLoads(small, {1.3e7, -0.12, 0.16}), 1e-8,
                            1e-8);
  FrictionBlockInput in;
  in.b = Vec3(1e-8, 1e-8, 0.5);
  in.L = 0.5;
  in.K = Vec3(1e300, 1e-8, 1e-8).asDiagonal();
  in.warmSlip = Vec3(0.5, 0.5, 0.5);
  EXPECT_TRUE(
      throwsNaming([&] { solveFrictionBlock(patch, Model::Ellipsoidal, in); }, {"out of range"}));

  // torques 1e300 times Pz rho: the projection used to return inadmissible
  // loads (min pressure -7e300); now an Error, or admissible loads
  const PatchShape quad = PatchShape::polygon({{-1.0, -1.0}, {0.5, -1.0}, {0.5, 0.5}, {-1.0, 0.5}});
  try {
    const PatchLoads near = nearestAdmissibleLoads(quad, {0.5, 1e300, 0.0}, 0.64625715426275077);
    EXPECT_TRUE(isAdmissible(quad, near, 1e-6));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }

  // torques 1e154 times Pz rho on a 2e-8 m pentagon: the projection returned
  // Pz = -4.9e138 (round-off of the scaled torque) and the admissibility
  // check skipped it for Pz <= 0; now an Error, or admissible loads
  const PatchShape pentagon =
      PatchShape::polygon({{2e-08, 2.2204460492503131e-16},
                           {1.3090169943749475e-08, 9.5105653849961402e-09},
                           {1.9098300562505273e-09, 5.8778527449693373e-09},
                           {1.9098300562505239e-09, -5.8778523008801258e-09},
                           {1.3090169943749473e-08, -9.510564940906932e-09}});
  try {
    const PatchLoads near = nearestAdmissibleLoads(pentagon, {0.5, 3.7921287488073376e+146, 0.5},
                                                   1.1015169678871499e-08);
    EXPECT_GE(near.Pz, 0.0);
    EXPECT_TRUE(isAdmissible(pentagon, near, 1e-6));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }

  // a sliver triangle 1e8 m long: every face and edge candidate of the
  // projection failed its round-off test and the answer fell back to the zero
  // load; now no farther than the uniform pressure with the same Pz (the
  // distance of the metric: (Pz, Tx / rho, Ty / rho))
  const PatchShape sliver = PatchShape::polygon({{-0.54133991607464249, -0.84080474295608298},
                                                 {0.84147099322260643, -0.54030231127116257},
                                                 {72192825.424791902, 112433663.98123373}});
  const PatchLoads skewed{0.0012331008911132812, -0.0194091796875, -0.0094013214111328125};
  const double rhoSliver = sliver.defaultRho();
  const PatchLoads nearSliver = nearestAdmissibleLoads(sliver, skewed, rhoSliver);
  auto distance = [&](const PatchLoads& l) {
    return Vec3(l.Pz - skewed.Pz, (l.Tx - skewed.Tx) / rhoSliver, (l.Ty - skewed.Ty) / rhoSliver)
        .norm();
  };
  const PatchLoads uniformLoads = loadsOf(sliver, LinearPressure::uniform(sliver, skewed.Pz));
  // round-off of the distances themselves: a few ulps of |y| ~ 1e-3
  constexpr double kDistanceRoundOff = 1e-12;
  EXPECT_LE(distance(nearSliver), distance(uniformLoads) * (1.0 + kDistanceRoundOff));
  EXPECT_GT(nearSliver.Pz, 0.0);

  // exact Q whose bound mu ∫|p| (1 + max|r| / rho) = 4.7e307 passes the
  // up-front range check but whose sum overflowed: Tz/rho was inf, now an
  // Error (or a finite Q)
  const PatchShape huge = PatchShape::disk(3536977920.0, Vec2(1e-08, 11597774848.0));
  const FrictionPatch steep(
      huge,
      LinearPressure{2.5967856829092717e-312, 2.0722615146145237e-315, 3.0266876757588627e+267},
      0.088134765625, 0.051469802856445312);
  const double big = std::numeric_limits<double>::max();
  try {
    EXPECT_TRUE(steep.exactQ(Vec3(big, big, big)).allFinite());
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("overflows"), std::string::npos) << e.what();
  }

  // a tiny disk with a tiny pressure: the unit law's Jacobian is finite
  // (-1/Pz times 1/|w| overflowed on its own before the product)
  const double e = 2.2204460492503131e-16;
  const PatchShape speck = PatchShape::disk(e, Vec2(e, e));
  const FrictionPatch tiny(speck, LinearPressure{8.3e-275, 8.3e-275, 8.3e-275}, e, e);
  Mat3 J;
  const Vec3 q = tiny.unitQ(Model::Exact, Vec3(e, 0.0, 0.0), &J);
  EXPECT_TRUE(q.allFinite());
  EXPECT_TRUE(J.allFinite());
  // the unit law's force part is at most ∫|p| / Pz = 1 here (p > 0 on the disk)
  ASSERT_GT(minPressure(speck, tiny.pressure()), 0.0);
  EXPECT_LE(std::hypot(q.x(), q.y()), 1.0 + 1e-12);
}

// fuzz round 8, item 58
// Polygons 900 to 8,800 diameters from O: Pz against long double sums about
// the vertex mean and the unit force in pure translation, to kPz times the
// law's round-off model; the block slipping about the vertex mean is L q(s^)
// by brute-force quadrature of Eq. (16), to kLaw of L.
TEST(ExactModel, PolygonFarFromOKeepsPzAndItsBlockIsTheLaw) {
  struct Case {
    const char* name;
    std::vector<Vec2> vertices;
    PatchLoads loads;
    double rho;
  };
  const std::vector<Case> cases = {
      {"23-gon 900 diameters from O",
       far23gon(),
       {0.044933735669085033, 0.023031487191871106, 0.04464514278227618},
       0.0},
      {"37-gon 2,800 diameters from O",
       far37gon(),
       {104871.91672465707, -104874.82550656002, 52431.654679402403},
       0.5},
      {"1.2e-8 m quadrilateral 8,800 diameters from O",
       {{5.7509619923003298e-06, -0.00010628063654460903},
        {5.7627784805965424e-06, -0.00010628032686178125},
        {5.7627784807117414e-06, -0.00010626880698244775},
        {5.7558854282998356e-06, -0.00010626880698237882}},
       {382.34459070385174, 0.040633901886729266, 0.0022021178888884077},
       0.5}};
  constexpr double kPz = 8.0, kLaw = 1e-6;
  for (const Case& c : cases) {
    const PatchShape shape = PatchShape::polygon(c.vertices);
    const LinearPressure p = LinearPressure::fromLoads(shape, c.loads);
    ASSERT_GE(minPressure(shape, p), -1e-6 * c.loads.Pz / shape.area()) << c.name;
    const double rho = c.rho > 0.0 ? c.rho : shape.defaultRho();
    const FrictionPatch patch(shape, p, 0.5, rho);
    const double model = lawModel(shape, p, patch.Pz());
    const LongLoads ref = loadsAboutVertexMean(shape.vertices(), p);
    EXPECT_LT(std::abs(static_cast<double>((patch.Pz() - ref.Pz) / ref.Pz)), kPz * model) << c.name;
    const Vec3 q = patch.unitQ(Model::Exact, Vec3::UnitX());
    EXPECT_LT(std::abs(std::hypot(q.x(), q.y()) - 1.0), kPz * model) << c.name;

    // the block: K = I, b with its ICR rho (-b_y, b_x) / b_z at the vertex
    // mean g, L small enough to slip
    Vec2 g = Vec2::Zero();
    for (const Vec2& v : shape.vertices()) g += v;
    g /= static_cast<double>(shape.vertices().size());
    FrictionBlockInput in;
    in.b = Vec3(g.y() / rho, -g.x() / rho, 1.0);
    in.L = 0.1;
    FrictionBlockResult r;
    ASSERT_NO_THROW(r = solveFrictionBlock(patch, Model::Exact, in)) << c.name;
    ASSERT_FALSE(r.sticking) << c.name;
    const Vec3 Q = patchspin::testing::bruteForceQ(shape, patchspin::testing::linearField(p), 1.0,
                                                   rho, r.slip, 1e-12);
    const double pz =
        patchspin::testing::bruteForceIntegral(shape, patchspin::testing::linearField(p), 1e-13);
    EXPECT_LT((r.impulse - in.L * (Q / pz)).norm(), kLaw * in.L)
        << c.name << ": impulse " << r.impulse.transpose() << ", L q "
        << (in.L * Q / pz).transpose();
  }
}

}  // namespace
}  // namespace patchspin
