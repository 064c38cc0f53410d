// Tests of the load sharing part (parts/load_sharing.hpp, Eq. (S25)): the
// shared loads are those of one linear pressure over the union of the
// patches carrying the group's total impulse and couple, checked against a
// brute-force quadrature over a grid (each patch sampled in the reference
// frame through its own rotation and offset; the field fitted to the
// sampled union moments, its loads summed per patch), not the part's
// closed-form moments.
#include <patchspin/parts/load_sharing.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

namespace patchspin::parts {
namespace {

// Midpoint rule on an n x n grid over each patch's bounding box: the sums
// converge like h (cells cut by the boundary); n = 800 on 10 cm patches
// gives the loads to ~2e-4 of their size. Totals are sums of the part's own
// numbers: round-off only.
constexpr int kGrid = 800;
constexpr double kQuadratureRel = 2e-3;
constexpr double kTotalsRel = 1e-12;

Mat2 rotation(double a) {
  Mat2 r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// (Pz, first moment about the reference origin) of the group
Vec3 totals(const std::vector<SharedPatch>& ps) {
  Vec3 t = Vec3::Zero();
  for (const SharedPatch& p : ps) {
    t[0] += p.lamN[0];
    t.tail<2>() += p.lamN[0] * p.origin + p.R * Vec2(-p.lamN[2], p.lamN[1]);
  }
  return t;
}

// The shared impulses by quadrature: sample points of each patch (reference
// frame) with their cell area; fit p0 + g . r to the totals; integrate.
std::vector<Vec3> quadratureShare(const std::vector<SharedPatch>& ps) {
  struct Sample {
    std::size_t patch;
    Vec2 local, ref;
    double dA;
  };
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const PatchShape& s = *ps[i].shape;
    const double r = s.maxDistanceFromOrigin();
    const double h = 2 * r / kGrid;
    for (int a = 0; a < kGrid; ++a)
      for (int b = 0; b < kGrid; ++b) {
        const Vec2 q(-r + (a + 0.5) * h, -r + (b + 0.5) * h);
        if (s.contains(q)) samples.push_back({i, q, ps[i].origin + ps[i].R * q, h * h});
      }
  }
  Mat3 m = Mat3::Zero();
  for (const Sample& s : samples) {
    const Vec3 phi(1.0, s.ref.x(), s.ref.y());
    m += s.dA * phi * phi.transpose();
  }
  const Vec3 field = m.fullPivLu().solve(totals(ps));
  std::vector<Vec3> out(ps.size(), Vec3::Zero());
  for (const Sample& s : samples) {
    const double p = field[0] + field[1] * s.ref.x() + field[2] * s.ref.y();
    out[s.patch] += s.dA * p * Vec3(1.0, s.local.y(), -s.local.x());
  }
  return out;
}

TEST(LoadSharing, SharesOneLinearPressureOverTheUnion) {
  // a 10 x 20 cm rectangle, a disk R 6 cm and a turned hexagon, at offsets
  // and rotations in the reference plane; Gauss-Seidel-like uneven loads
  const PatchShape rect = PatchShape::rectangle(0.1, 0.2);
  const PatchShape disk = PatchShape::disk(0.06);
  const PatchShape hex = PatchShape::regularPolygon(6, 0.05);
  std::vector<SharedPatch> ps(3);
  ps[0].shape = &rect;
  ps[0].lamN = Vec3(6.67, 0.01, -0.33);
  ps[1].shape = &disk;
  ps[1].origin = Vec2(0.2, 0.05);
  ps[1].R = rotation(0.7);
  ps[1].lamN = Vec3(2.25, -0.02, 0.05);
  ps[2].shape = &hex;
  ps[2].origin = Vec2(0.05, 0.3);
  ps[2].R = rotation(-1.9);
  ps[2].lamN = Vec3(1.1, 0.0, 0.01);
  const Vec3 before = totals(ps);
  const std::vector<Vec3> expected = quadratureShare(ps);
  ASSERT_TRUE(shareLoads(ps));
  const Vec3 after = totals(ps);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(after[k], before[k], kTotalsRel * before.cwiseAbs().maxCoeff()) << k;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double scale = ps[i].lamN[0] * ps[i].shape->maxDistanceFromOrigin();
    EXPECT_NEAR(ps[i].lamN[0], expected[i][0], kQuadratureRel * ps[i].lamN[0]) << i;
    EXPECT_NEAR(ps[i].lamN[1], expected[i][1], kQuadratureRel * scale) << i;
    EXPECT_NEAR(ps[i].lamN[2], expected[i][2], kQuadratureRel * scale) << i;
  }
}

// The bridge of CompoundShapes.BlockBridging*: two equal faces symmetric
// about the body's centre share its weight equally, each centre of pressure
// at its face's centre across the gap (x), both shifted alike along y.
TEST(LoadSharing, SymmetricBridgeSplitsEvenly) {
  const PatchShape face = PatchShape::rectangle(0.1, 0.2);
  std::vector<SharedPatch> ps(2);
  for (SharedPatch& p : ps) p.shape = &face;
  ps[0].origin = Vec2(-0.1, 0.0);
  ps[1].origin = Vec2(0.1, 0.0);
  // 6.67 : 2.25 N as Gauss-Seidel leaves it (BlockBridging*), the first
  // face's centre of pressure at its inner edge (x = 0.05 about its O), the
  // second's where the total is under the body's centre (x = 0), near its
  // outer edge; a couple about x (the slope's tilt load), all on the first
  const double cop1 = (6.67 * 0.1 - 6.67 * 0.05 - 2.25 * 0.1) / 2.25;
  ps[0].lamN = Vec3(6.67, 0.1, -6.67 * 0.05);
  ps[1].lamN = Vec3(2.25, 0.0, -2.25 * cop1);
  const Vec3 before = totals(ps);
  ASSERT_TRUE(shareLoads(ps));
  EXPECT_NEAR(ps[0].lamN[0], 0.5 * before[0], 1e-12);
  EXPECT_NEAR(ps[1].lamN[0], 0.5 * before[0], 1e-12);
  EXPECT_NEAR(ps[0].lamN[2], 0.0, 1e-12);  // no couple across the gap
  EXPECT_NEAR(ps[0].lamN[1], ps[1].lamN[1], 1e-12);
  EXPECT_NEAR(ps[0].lamN[1] + ps[1].lamN[1], 0.1, 1e-12);
}

// Where the shared pressure would be negative on a patch (the body's weight
// far off the union's centre) nothing changes; nor for one patch or no load.
TEST(LoadSharing, RefusesLiftOffOnePatchAndNoLoad) {
  const PatchShape face = PatchShape::rectangle(0.1, 0.1);
  std::vector<SharedPatch> ps(2);
  for (SharedPatch& p : ps) p.shape = &face;
  ps[1].origin = Vec2(1.0, 0.0);
  // all the weight at the first face's far edge: p < 0 on the second
  ps[0].lamN = Vec3(1.0, 0.0, 1.0 * 0.05);
  ps[1].lamN = Vec3(0.0, 0.0, 0.0);
  std::vector<SharedPatch> copy = ps;
  EXPECT_FALSE(shareLoads(ps));
  EXPECT_EQ(ps[0].lamN, copy[0].lamN);
  EXPECT_EQ(ps[1].lamN, copy[1].lamN);
  std::vector<SharedPatch> one(1, copy[0]);
  EXPECT_FALSE(shareLoads(one));
  ps = copy;
  ps[0].lamN.setZero();
  EXPECT_FALSE(shareLoads(ps));
}

}  // namespace
}  // namespace patchspin::parts
