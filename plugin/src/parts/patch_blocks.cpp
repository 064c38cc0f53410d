// Effective-mass blocks of a patch (patch_blocks.hpp; docs/solver.md (S2), (S3), (S15)).
#include <patchspin/parts/patch_blocks.hpp>

#include <Eigen/Dense>

#include <limits>

namespace patchspin::parts {

bool makePatchBlocks(const Mat6& K6, PatchBlocks& b) {
  const Mat3 W = K6.topLeftCorner<3, 3>();
  if (!(W(0, 0) > 0.0 && W.topLeftCorner<2, 2>().determinant() > 0.0 && W.determinant() > 0.0))
    return false;
  b.Winv = W.inverse();  // 3x3 SPD: cofactors
  b.Knf = K6.topRightCorner<3, 3>();
  b.Kff = K6.bottomRightCorner<3, 3>();
  b.G = b.Winv * b.Knf;
  b.Ks = b.Kff - b.Knf.transpose() * b.G;
  b.Ks = 0.5 * (b.Ks + b.Ks.transpose());
  const Vec3 d = b.Ks.diagonal();
  if (!(d.minCoeff() > 0.0)) return false;
  // det(D Ks D) = det(Ks) / (d0 d1 d2): no square roots or divisions, unless
  // that product leaves the normal range
  const double dProduct = d[0] * d[1] * d[2];
  if (dProduct >= std::numeric_limits<double>::min() &&
      dProduct <= std::numeric_limits<double>::max()) {
    if (!(b.Ks.determinant() > kMinUnitDet * dProduct)) return false;
  } else {
    const Vec3 s = d.cwiseSqrt().cwiseInverse();
    if (!((s.asDiagonal() * b.Ks * s.asDiagonal()).determinant() > kMinUnitDet)) return false;
  }
  b.KsInv = b.Ks.inverse();
  return true;
}

template <int N>
void foldHeldDofs(const Mat6& K, const Mat6& Kh, const Eigen::Matrix<double, 6, N>& C,
                  HeldBlocks& h) {
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(Kh.template topLeftCorner<N, N>());
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
  const Eigen::Matrix<double, N, 6> KhInvCt = ldlt.solve(C.transpose());
  const Mat6 Kf = K - C * KhInvCt;
  if (!makePatchBlocks(0.5 * (Kf + Kf.transpose()), h)) return;
  h.gain.setZero();
  h.gain.template topRows<N>() = -KhInvCt;
  h.valid = h.Winv.allFinite() && h.KsInv.allFinite() && h.gain.allFinite();
}

template void foldHeldDofs<3>(const Mat6&, const Mat6&, const Eigen::Matrix<double, 6, 3>&,
                              HeldBlocks&);
template void foldHeldDofs<6>(const Mat6&, const Mat6&, const Eigen::Matrix<double, 6, 6>&,
                              HeldBlocks&);

}  // namespace patchspin::parts
