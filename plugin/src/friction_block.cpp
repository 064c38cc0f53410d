// solveFrictionBlock: validation, the block's domain in the patch, scaling to
// unit size and dispatch to the two laws' solvers (friction_block.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <patchspin/friction_block.hpp>

#include "friction_block_solvers.hpp"
#include "spd3.hpp"

namespace patchspin {

namespace {

using internal::inverseOf;
using internal::requirePositiveDefinite;
using internal::requirePositiveDefiniteFactor;
using internal::requireVerifiedExactSlip;
using internal::solveEllipsoidal;
using internal::solveExact;
using internal::solveExactRecentred;

void validate(const FrictionBlockInput& in) {
  // (the finiteness tests inline, the calls that build the message only
  // where one fails: five calls cost ~2.5 % of a block solve)
  if (!in.b.allFinite()) internal::requireFinite(in.b, "friction block free slip b");
  if (!in.warmSlip.allFinite())
    internal::requireFinite(in.warmSlip, "friction block warm-start slip");
  if (!in.warmGauge.allFinite())
    internal::requireFinite(in.warmGauge, "friction block warm-start gauge slip");
  if (!in.K.allFinite()) throw Error("friction block matrix K must be finite");
  // K symmetric (SPD, as documented), to kSymmetryTol of its largest entry:
  // both blocks work with its symmetric part. 1e-10 leaves room for a K
  // assembled in floating point (a few ulps of asymmetry) and keeps the stick
  // residual of the asymmetric part, |K - K^T| |lambda| / 2, at 1e-10 of
  // |K| |lambda| (FrictionBlock.RefusesAnAsymmetricK).
  constexpr double kSymmetryTol = 1e-10;
  if (!((in.K - in.K.transpose()).cwiseAbs().maxCoeff() <=
        kSymmetryTol * in.K.cwiseAbs().maxCoeff()))
    throw Error("friction block matrix K must be symmetric (positive definite)");
  // K's diagonal spanning at most kMaxDiagonalSpan: beyond ~1e36 both blocks
  // lose every digit (measured: docs/notes/friction-block-measurements.md).
  // K's diagonal holds the slip mobilities of the force rows (1/m and r^2/I
  // terms) and of the spin row (rho^2/I terms) of the same two bodies, so
  // its span is a ratio of lengths squared: within the lever domain it stays
  // below ~1e20 even for a body 1e5 times larger than its patch. 1e30 leaves
  // a margin of 1e6 below the onset. (Non-positive diagonals are left to the
  // positive definiteness checks.)
  // Guarded by FrictionBlock.RefusesAKDiagonalSpanningMoreThan1e30.
  constexpr double kMaxDiagonalSpan = 1e30;
  const Vec3 kd = in.K.diagonal();
  if (kd.minCoeff() > 0.0 && !(kd.maxCoeff() <= kMaxDiagonalSpan * kd.minCoeff()))
    throw Error("friction block out of range: the diagonal of K spans more than 1e30 (" +
                internal::formatDouble(kd.minCoeff()) + " to " +
                internal::formatDouble(kd.maxCoeff()) + ")");
  if (!std::isfinite(in.L)) internal::requireFinite(in.L, "friction block bound L");
  if (in.L < 0.0)
    throw Error("friction block bound L must be >= 0: got " + internal::formatDouble(in.L));
  if (!std::isfinite(in.tolerance))
    internal::requireFinite(in.tolerance, "friction block tolerance");
  if (in.tolerance < 0.0 || in.tolerance >= 1.0)
    throw Error("friction block tolerance must lie in [0, 1): got " +
                internal::formatDouble(in.tolerance));
}

// An answer that overflows double is refused, never returned as inf or NaN
// (DoubleRange.ExtremeInputsGiveAnErrorOrAFiniteAnswer).
FrictionBlockResult requireFiniteResult(const FrictionBlockResult& r) {
  if (!r.impulse.allFinite() || !r.slip.allFinite())
    throw Error("friction block out of range: the impulse overflows double (K, b or L too large)");
  return r;
}

// The block after validation, at the scale it is given.
FrictionBlockResult solveModel(const FrictionPatch& patch, Model model,
                               const FrictionBlockInput& input) {
  if (model == Model::Ellipsoidal) {
    // K positive definite, as documented and as the exact path checks
    // (FrictionBlock.RefusesBadInputAndFallsBackWithoutFriction)
    requirePositiveDefinite(input.K);
    return requireFiniteResult(solveEllipsoidal(patch.Pi(), input));
  }
  // (K's plain condition number, as solveExact computed it; for a
  // recentred block, K's own, for the verification about O)
  double cond = 0.0;
  FrictionBlockResult r;
  if (solveExactRecentred(patch, input, r)) {
    const Mat3 Ksym = 0.5 * (input.K + input.K.transpose());
    cond = Ksym.norm() * inverseOf(requirePositiveDefiniteFactor(Ksym)).norm();
  } else {
    r = solveExact(patch, input, &cond);
  }
  return requireVerifiedExactSlip(patch, input, requireFiniteResult(r), cond);
}

// The block's domain in the patch (friction_block.hpp), both laws; a patch
// outside it is refused whatever b, K and L are.
//  * pressure >= 0 on the patch, to kNegativePressureTol of the mean
//    pressure Pz / A: both blocks rest on a convex limit set (the exact one
//    on maximum dissipation, the ellipsoidal one on an SPD Pi), which a
//    pressure with negative parts does not give. 1e-6 is
//    nearestAdmissibleLoads' own acceptance of its projection, so every
//    pressure it returns, the Bullet integration's, is inside
//    (FrictionBlock.RefusesANegativePressure).
//  * lever max|r| / rho within [kMinLever, kMaxLever]: the law turns from
//    force to torque across |w_z| / |w_xy| ~ 1 / lever, which the blocks
//    resolve to ~1e-14 lever (long) and ~1e-13 / lever (short) of the set,
//    and to nothing far beyond (docs/notes/friction-block-measurements.md).
//    Eq. (11) gives 1 to ~3; rho is a coordinate scale that does not change
//    the physics, so only a rho chosen more than 1e5 times off the patch's
//    size is refused (FrictionBlock.RefusesALeverOutsideItsDomain,
//    FrictionBlock.IsTheLawAtItsSlipAcrossTheLeverDomain).
constexpr double kNegativePressureTol = 1e-6;
constexpr double kMinLever = 1e-5, kMaxLever = 1e5;

// The exact law sums the pressure's terms about O, each up to A |c_k|
// max|r|^k / Pz of the unit law, over kernel integrals that cancel by
// diameter^2 / A on a sliver: its round-off is ~kTermsUlps eps times
// max(1, diameter^2 / A) times those terms (the fuzz targets' model). Where
// that reaches kLawNoDigits of the unit force the law has lost its digits,
// and the block's answer with it; ordinary patches are ~1e4 and more below
// it (a 1 m x 1 mm face with terms 10 times Pz: 1.4e-10)
// (ExactBlock.RefusesALawWithoutDigits). A polygon's Pz keeps
// these digits far from O, its area moments summed about the vertex mean
// (ExactModel.PolygonFarFromOKeepsPzAndItsBlockIsTheLaw).
constexpr double kTermsUlps = 64.0, kLawNoDigits = 1e-6;
void requireExactLawDigits(const FrictionPatch& patch) {
  const PatchShape& shape = patch.shape();
  const LinearPressure& p = patch.pressure();
  const double rmax = shape.maxDistanceFromOrigin();
  const double terms =
      shape.area() * (std::abs(p.p0) + (std::abs(p.cx) + std::abs(p.cy)) * rmax) / patch.Pz();
  const double sliver = std::max(1.0, shape.diameter() / shape.area() * shape.diameter());
  const double roundOff = kTermsUlps * std::numeric_limits<double>::epsilon() * sliver * terms;
  if (!(roundOff <= kLawNoDigits)) {
    throw Error(
        "friction block: the exact law has no digits for this pressure and patch (round-off ~" +
        internal::formatDouble(roundOff) + " of its force: terms about O " +
        internal::formatDouble(terms) + " times Pz on a patch of diameter^2 / area " +
        internal::formatDouble(sliver) + ")");
  }
}

void requireBlockDomain(const FrictionPatch& patch, Model model) {
  const PatchShape& shape = patch.shape();
  const double lever = shape.maxDistanceFromOrigin() / patch.rho();
  if (!(lever >= kMinLever && lever <= kMaxLever)) {
    throw Error("friction block out of range: the patch's lever max|r| / rho = " +
                internal::formatDouble(lever) +
                " lies outside [1e-5, 1e5] (rho = " + internal::formatDouble(patch.rho()) +
                " m); choose rho within 1e5 of the patch's size (default: Eq. (11))");
  }
  if (patch.isHertz()) return;  // the Hertz pressure (57) is >= 0
  const double meanPressure = patch.Pz() / shape.area();
  const double lowest = minPressure(shape, patch.pressure());
  if (!(lowest >= -kNegativePressureTol * meanPressure)) {
    throw Error("friction block: the pressure is negative on the patch (min p = " +
                internal::formatDouble(lowest) + " Pa against a mean of " +
                internal::formatDouble(meanPressure) +
                " Pa); the block needs p >= 0 (use nearestAdmissibleLoads)");
  }
  if (model == Model::Exact) requireExactLawDigits(patch);
}

}  // namespace

FrictionBlockResult solveFrictionBlock(const FrictionPatch& patch, Model model,
                                       const FrictionBlockInput& input) {
  validate(input);
  requireBlockDomain(patch, model);
  FrictionBlockResult out;
  if (input.L == 0.0) {  // no normal impulse: no friction
    out.slip = input.b;
    out.sticking = input.b.isZero(0.0);  // not |b|^2 == 0: that underflows for b ~ 1e-160
    return out;
  }
  if (input.b.isZero(0.0)) {  // already at rest: stick with zero impulse
    out.sticking = true;
    return out;
  }
  // The block is homogeneous: K -> a K, b -> c b, L -> (c / a) L (and the
  // warm start with b) give s -> c s, lambda -> (c / a) lambda. Far from unit
  // scale it is solved at |K| ~ 1 and |b| ~ 1, with a and c powers of two,
  // so the scaling is exact and no square under- or overflows
  // (FrictionBlockScale.FarFromUnitScaleIsTheLaw). An L beyond 2^kMaxLeverage
  // there (|L K Pi|^2 would overflow) is tried at that bound: a block that
  // sticks with it sticks with any larger L; one that slips is left to the
  // plain path, as is an L that underflows. One range check on the common
  // path.
  {
    const double bMax = input.b.cwiseAbs().maxCoeff(), kMax = input.K.cwiseAbs().maxCoeff();
    // (unit scale from 1e40 on: the ellipsoidal root search squares |N(r)| ~
    // |b|^3, which overflows for |b| > 1e51;
    // FrictionBlockScale.HugeFreeSlipIsTheLawAtItsSlip)
    constexpr double kLow = 1e-40, kHigh = 1e40;
    constexpr int kMaxLeverage = 300;
    // (a K whose diagonal spans more than kMaxSpread keeps its scale: its
    // determinant leaves double's range at any scale, refused below)
    constexpr double kMaxSpread = 1e100;
    const bool spreadOk = input.K.diagonal().cwiseAbs().minCoeff() > kMax / kMaxSpread;
    if (!(bMax > kLow && bMax < kHigh && kMax > kLow && kMax < kHigh) && bMax > 0.0 && kMax > 0.0 &&
        spreadOk) {
      const int ek = std::ilogb(kMax), es = std::ilogb(bMax);
      auto times2To = [](auto v, int e) {
        return decltype(v)(v.unaryExpr([e](double x) { return std::ldexp(x, e); }));
      };
      FrictionBlockInput unit = input;
      unit.b = times2To(input.b, -es);
      unit.K = times2To(input.K, -ek);
      unit.warmSlip = times2To(input.warmSlip, -es);
      // (a warm start far smaller or larger than b keeps its direction, the
      // exact block's only use of it: its squares would under- or overflow)
      const double warmMax = unit.warmSlip.cwiseAbs().maxCoeff();
      if (input.warmSlip.cwiseAbs().maxCoeff() > 0.0 && !(warmMax > kLow && warmMax < kHigh))
        unit.warmSlip = times2To(input.warmSlip, -std::ilogb(input.warmSlip.cwiseAbs().maxCoeff()));
      // (the ellipsoidal A = L K Pi counts Pi's size too, or a tiny b against
      // a huge Pi overflows L K Pi at unit scale;
      // FrictionBlock.EllipsoidalRefusesAHugePiOutsideTheDomain)
      const double piMax = patch.Pi().cwiseAbs().maxCoeff();
      const bool piCounts = model == Model::Ellipsoidal && piMax > 0.0 && std::isfinite(piMax);
      const int ePi = piCounts ? std::max(0, std::ilogb(piMax)) : 0;
      const bool clamped = std::ilogb(input.L) + ek - es + ePi > kMaxLeverage;
      unit.L = clamped ? std::ldexp(1.0, kMaxLeverage - ePi) : std::ldexp(input.L, ek - es);
      if (unit.L >= std::numeric_limits<double>::min()) {
        FrictionBlockResult r = solveModel(patch, model, unit);
        if (!clamped || r.sticking) {
          r.impulse = times2To(r.impulse, es - ek);
          r.slip = times2To(r.slip, es);
          return requireFiniteResult(r);
        }
      } else {
        // L |K| below 2^-1022 of |b|: the impulse cannot move the slip off b
        // by one ulp and -K^-1 b is far outside L E, so the block slips
        // along b with the law there (FrictionBlockScale.FarFromUnitScaleIsTheLaw).
        // K must still be positive definite, checked at unit scale, where its
        // minors are in range
        // (FrictionBlock.WithNegligibleFrictionRefusesAnIndefiniteK).
        requirePositiveDefinite(unit.K);
        FrictionBlockResult r;
        r.impulse = input.L * patch.unitQ(model, unit.b);
        r.slip = input.b + input.K * r.impulse;
        r.iterations = 1;
        return requireFiniteResult(r);
      }
    }
  }
  return solveModel(patch, model, input);
}

}  // namespace patchspin
