// The exact friction block of a small patch, solved about its own centre
// (friction_block_solvers.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "friction_block_solvers.hpp"

namespace patchspin::internal {

// The exact block of a patch much smaller than rho, solved in the frame of
// the patch's own centre g with rho' of Eq. (11) about g. The law turns as
// the ICR crosses the patch, across a change of w_xy / w_z of ~diameter /
// rho, so in O's coordinates the iteration's round-off (1e-14 of the slip
// scale) reaches the law magnified by rho / diameter, whatever max|r| / rho
// is; about g the law resolves at unit scale
// (ExactBlock.TinyDiskFarFromOSpinningAboutItsRimIsTheLaw). Slip and
// impulse map as
//   s' = T s,  lambda = T^T lambda',  T = [[1, 0, -g_y / rho], [0, 1, g_x / rho], [0, 0, rho' /
//   rho]]
// (the velocity at g, and the torque about g: power s.lambda is kept), so
// K' = T K T^T, b' = T b, and the law of the recentred patch is the one about
// O up to its normalisation: q_O(s) = (Pz' / Pz) T^T q'(T s), which L' = L
// Pz' / Pz carries. Only below kRecentreBelow (Bullet's patches are
// expressed about their centroid: diameter / rho ~ 1); costs a FrictionPatch
// there. Where the recentred patch or block is refused (its K' can be worse
// conditioned, T shears by g / rho), the block is solved about O instead.
constexpr double kRecentreBelow = 1e-2;
bool solveExactRecentred(const FrictionPatch& patch, const FrictionBlockInput& in,
                         FrictionBlockResult& out) {
  const PatchShape& shape = patch.shape();
  if (!(shape.diameter() < kRecentreBelow * patch.rho())) return false;
  try {
    Vec2 g = Vec2::Zero();
    if (shape.isDisk()) {
      g = shape.centre();
    } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
      g = shape.centroid();
    } else {
      for (const Vec2& v : shape.vertices()) g += v;
      g /= static_cast<double>(shape.vertices().size());
    }
    const PatchShape local = shape.inFrame(g, 0.0);
    const LinearPressure& p = patch.pressure();
    // (with mu = 1: the block solves the unit law q = Q / (mu Pz), which mu
    // does not enter, and the patch's own mu times the recentred pressure
    // may overflow the constructor's scale check where the patch's did not;
    // ExactBlock.TinyDiskWithAHugeMuIsTheLaw)
    const FrictionPatch recentred =
        patch.isHertz()
            ? FrictionPatch(local, HertzPressure{patch.Pz()}, 1.0)
            : FrictionPatch(local, LinearPressure{p.p0 + p.cx * g.x() + p.cy * g.y(), p.cx, p.cy},
                            1.0);
    const double rho = patch.rho();
    Mat3 T = Mat3::Identity();
    T(0, 2) = -g.y() / rho;
    T(1, 2) = g.x() / rho;
    T(2, 2) = recentred.rho() / rho;
    FrictionBlockInput localIn = in;
    localIn.b = T * in.b;
    localIn.K = T * in.K * T.transpose();
    localIn.warmSlip = T * in.warmSlip;
    localIn.warmGauge = T * in.warmGauge;
    localIn.piInverse = nullptr;  // (the recentred patch's Pi is not the caller's)
    const double pzRatio = recentred.Pz() / patch.Pz();
    localIn.L = in.L * pzRatio;
    if (!localIn.b.allFinite() || !localIn.K.allFinite() || !std::isfinite(localIn.L)) return false;
    double localCond = 0.0;
    FrictionBlockResult r = solveExact(recentred, localIn, &localCond);
    // The iteration stops at tol of the block's slip scale |b'| + L' |K'|.
    // About g a slip with the ICR inside the patch is mostly spin with rho'
    // ~ diameter, and |s'| can be far below that scale (b' and L' K' lambda'
    // cancel), its direction then fixed to tol |scale| / |s'| only. Such a
    // slip is polished from where it stopped with the tolerance relative to
    // |s'| itself; the iteration ends where double gives no more progress
    // (ExactBlock.TinyDiskFarFromOSpinningAboutAPointInsideIsTheLaw).
    const double localScale = localIn.b.norm() + localIn.L * localIn.K.norm();
    const double localTol = in.tolerance > 0.0 ? in.tolerance : kRelativeTolerance;
    constexpr double kTinyTolerance = 1e-300;  // > 0: 0 would select the default
    if (!r.sticking && r.slip.norm() < kResolvedSlip * localScale) {
      FrictionBlockInput polish = localIn;
      polish.warmSlip = r.slip;
      polish.tolerance = std::max(localTol * r.slip.norm() / localScale, kTinyTolerance);
      r = solveExact(recentred, polish, &localCond);
    }
    out = r;
    out.impulse = T.transpose() * r.impulse;
    out.slip = r.sticking ? Vec3::Zero() : Vec3(in.b + in.K * out.impulse);
    if (r.gaugeSlip.cwiseAbs().maxCoeff() > 0.0) {
      const Mat3 Tinv = T.inverse();
      out.gaugeSlip = Vec3(Tinv * r.gaugeSlip).normalized();
      out.gaugeValue = (1.0 / pzRatio) * (T.transpose() * r.gaugeValue);
    }
    return out.impulse.allFinite() && out.slip.allFinite();
  } catch (const Error&) {
    return false;
  }
}

}  // namespace patchspin::internal
