// Slivers (friction_block.hpp, kMaxSliverRatio): on a patch centred at its
// centroid with d^2 / A <= kMaxSliverRatio, the exact law keeps its digits
// for every admissible pressure, so adapters that leave wider slivers to
// point contacts never meet the law's "no digits" refusal.
//
// Independent checks: the pressures are the extreme admissible ones
// (nearestAdmissibleLoads of a centre of pressure far outside, so the
// pressure vanishes on the boundary), on triangles (where the centroid is
// nearest a side, a third of the height) and rectangles, turned at random;
// the terms of the round-off model are recomputed from the pressure's
// coefficients against the bound 1 + 3 sqrt(2) d^2 / A.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace patchspin {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLong = 0.2;  // the sliver's length [m]

// A triangle (apex over the base's middle) or a rectangle of length kLong
// and d^2 / A = ratio, turned by `angle`, with its centroid at O.
PatchShape sliver(bool triangle, double ratio, double angle) {
  std::vector<Vec2> v;
  if (triangle) {
    const double h = 2.0 * kLong / ratio;  // A = kLong h / 2, d = kLong
    v = {{-kLong / 2, -h / 3}, {kLong / 2, -h / 3}, {0.0, 2.0 * h / 3}};
  } else {
    const double w = kLong / ratio;  // d^2 = kLong^2 + w^2: ratio to 1 / ratio^2
    v = {{-kLong / 2, -w / 2}, {kLong / 2, -w / 2}, {kLong / 2, w / 2}, {-kLong / 2, w / 2}};
  }
  const double c = std::cos(angle), s = std::sin(angle);
  for (Vec2& p : v) p = Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return PatchShape::polygon(v);
}

// The extreme admissible loads of `shape`: the nearest to a centre of
// pressure 10 diameters out at angle phi (the pressure vanishes on an edge
// or at a vertex).
PatchLoads extremeLoads(const PatchShape& shape, double phi) {
  const double far = 10.0 * shape.diameter();
  const Vec2 cop(far * std::cos(phi), far * std::sin(phi));
  // centre of pressure (Ty / Pz, -Tx / Pz)
  return nearestAdmissibleLoads(shape, {1.0, -cop.y(), cop.x()}, shape.defaultRho());
}

double terms(const FrictionPatch& patch) {
  const LinearPressure& p = patch.pressure();
  return patch.shape().area() *
         (std::abs(p.p0) +
          (std::abs(p.cx) + std::abs(p.cy)) * patch.shape().maxDistanceFromOrigin()) /
         patch.Pz();
}

// Every extreme pressure on slivers up to the bound: terms within 1 + 3
// sqrt(2) d^2 / A, and the exact block solves (no "no digits" refusal).
TEST(FrictionBlockSlivers, ExactLawKeepsItsDigitsUpToTheSliverBound) {
  std::mt19937 rng(20261128u);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), unit(-1.0, 1.0);
  int solved = 0;
  for (const bool triangle : {true, false})
    for (const double ratio : {50.0, 500.0, 2000.0, 0.999 * kMaxSliverRatio}) {
      const PatchShape shape = sliver(triangle, ratio, angle(rng));
      ASSERT_LE(sliverRatio(shape), kMaxSliverRatio);
      ASSERT_LE(shape.centroid().norm(), 1e-12 * kLong);
      for (int i = 0; i < 48; ++i) {
        const PatchLoads loads = extremeLoads(shape, 2.0 * kPi * i / 48.0);
        const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), 0.5);
        const std::string what = std::string(triangle ? "triangle" : "rectangle") +
                                 " d^2/A=" + std::to_string(ratio) + " i=" + std::to_string(i);
        EXPECT_LE(terms(patch), 1.0 + 3.0 * std::sqrt(2.0) * sliverRatio(shape)) << what;
        FrictionBlockInput in;
        in.K = Vec3(2.0, 3.0, 1.5).asDiagonal();
        in.b = Vec3(unit(rng), unit(rng), unit(rng));
        in.L = 0.5 * patch.Pz() * 0.1;
        EXPECT_NO_THROW(solveFrictionBlock(patch, Model::Exact, in)) << what;
        ++solved;
      }
    }
  EXPECT_EQ(solved, 2 * 4 * 48);
}

// Beyond the bound the rule is needed: on a triangle ten times thinner than
// kMaxSliverRatio some extreme admissible pressure leaves the exact law
// without digits (the block refuses it, naming that).
TEST(FrictionBlockSlivers, BeyondTheBoundAnAdmissiblePressureLosesTheDigits) {
  const PatchShape shape = sliver(true, 10.0 * kMaxSliverRatio, 0.3);
  int refused = 0;
  for (int i = 0; i < 48; ++i) {
    const PatchLoads loads = extremeLoads(shape, 2.0 * kPi * i / 48.0);
    const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), 0.5);
    FrictionBlockInput in;
    in.b = Vec3(0.3, -0.2, 0.1);
    in.L = 0.05 * patch.Pz();
    try {
      solveFrictionBlock(patch, Model::Exact, in);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no digits"), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace patchspin
