// The disk's pressure bounds take |grad p| = |(cx, cy)| as sqrt(cx^2 + cy^2)
// where that sum of squares is a normal double and fall back to a scaled
// hypot where it under- or overflows (issue 6, speed). These tests drive
// both paths of minPressure and of the FrictionPatch overflow check against
// an independent long double computation (its exponent range holds the
// squares of every double, so it needs no scaling).
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace patchspin {
namespace {

// minPressure = p(C) - R |grad p|: the gradient's norm to ~2 ulps on the fast
// path (two squares, a sum and a sqrt) and ~1 ulp from hypot, then one
// product and one difference; 8 eps relative to |p(C)| + R |grad p| (the
// terms' own size, the cancellation's scale) leaves a margin of 2.
constexpr double kMinPressureRelTol = 8.0 * std::numeric_limits<double>::epsilon();

// The reference: p(C) - R |grad p| in long double.
long double referenceMin(const PatchShape& disk, const LinearPressure& p) {
  const long double cx = p.cx, cy = p.cy;
  const long double pc =
      static_cast<long double>(p.p0) + cx * disk.centre().x() + cy * disk.centre().y();
  return pc - static_cast<long double>(disk.radius()) * std::sqrt(cx * cx + cy * cy);
}

void expectMinPressure(const PatchShape& disk, const LinearPressure& p) {
  const long double ref = referenceMin(disk, p);
  const long double pc = static_cast<long double>(p.p0) +
                         static_cast<long double>(p.cx) * disk.centre().x() +
                         static_cast<long double>(p.cy) * disk.centre().y();
  const long double size =
      std::fabs(pc) +
      disk.radius() * std::hypot(static_cast<long double>(p.cx), static_cast<long double>(p.cy));
  const double got = minPressure(disk, p);
  EXPECT_LE(std::fabs(static_cast<long double>(got) - ref), kMinPressureRelTol * size)
      << "p0 " << p.p0 << " cx " << p.cx << " cy " << p.cy << ": got " << got << ", expected "
      << static_cast<double>(ref);
}

// Gradients whose squares underflow (sum below the smallest normal double):
// the plain sqrt would return 0 and minPressure p(C) itself, 100 % off here.
TEST(PressureGradientRange, MinPressureWithUnderflowingGradientSquares) {
  const PatchShape disk = PatchShape::disk(1.0);
  expectMinPressure(disk, LinearPressure{1e-169, 3e-170, 4e-170});
  expectMinPressure(disk, LinearPressure{1e-300, -6e-301, 8e-301});
  expectMinPressure(disk, LinearPressure{1e-320, 0.0, 5e-321});  // subnormal coefficients
}

// Gradients whose squares overflow: the plain sqrt would return inf and
// minPressure refuse a finite pressure as not finite.
TEST(PressureGradientRange, MinPressureWithOverflowingGradientSquares) {
  const PatchShape disk = PatchShape::disk(1.0);
  expectMinPressure(disk, LinearPressure{1e161, 3e160, 4e160});
  expectMinPressure(disk, LinearPressure{1e300, -3e299, -4e299});
}

// A zero gradient gives p(C) exactly.
TEST(PressureGradientRange, MinPressureWithZeroGradientIsTheCentrePressure) {
  const PatchShape disk = PatchShape::disk(0.02, Vec2(0.3, -0.1));
  EXPECT_EQ(minPressure(disk, LinearPressure{1234.5, 0.0, 0.0}), 1234.5);
}

// The fast path over ordinary magnitudes (seeded), off-centre disks included.
TEST(PressureGradientRange, MinPressureOnTheFastPathMatchesLongDouble) {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), decade(-6.0, 6.0);
  for (int k = 0; k < 2000; ++k) {
    const PatchShape disk =
        PatchShape::disk(std::pow(10.0, decade(rng) / 3.0), Vec2(unit(rng), unit(rng)));
    const double scale = std::pow(10.0, decade(rng));
    expectMinPressure(
        disk, LinearPressure{scale * (2.0 + unit(rng)), scale * unit(rng), scale * unit(rng)});
  }
}

// FrictionPatch refuses a pressure whose bound mu ∫|p| (1 + max|r| / rho)
// overflows; a gradient whose squares overflow but whose norm does not must
// still be accepted, with Pi from its moments (the bound is 1.5e161 here).
TEST(PressureGradientRange, FrictionPatchAcceptsAGradientWhoseSquaresOverflow) {
  const PatchShape disk = PatchShape::disk(1.0);
  const LinearPressure p{1e161, 3e160, 4e160};
  FrictionPatch patch(disk, p, 0.5);
  EXPECT_GT(patch.Pz(), 0.0);
  EXPECT_TRUE(patch.Pi().allFinite());
}

}  // namespace
}  // namespace patchspin
