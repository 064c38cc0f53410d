// The blocks of a patch's 6x6 effective mass that the normal and friction
// block parts use (docs/solver.md, Eqs. (S2), (S3), (S15)):
//   K6 = [[W, Knf], [Knf^T, Kff]]   (normal DOFs 0-2, friction DOFs 3-5)
//   Ks = Kff - Knf^T W^-1 Knf       (friction block with the normal held)  (S3)
//   G  = W^-1 Knf                   (the normal block's follow-up)
// and, for a stacked patch, the same blocks with another patch's DOFs held
//   K' = K6 - C Kh^-1 C^T,  dlambda_h = -Kh^-1 C^T d                       (S15)
#pragma once

#include <patchspin/parts/patch_body.hpp>

namespace patchspin::parts {

struct PatchBlocks {
  Mat3 Winv, Knf, G, Ks, KsInv;
  Mat3 Kff;  // read only while the centre of pressure is off the patch
};

// A patch's blocks with (some of) another patch's DOFs held, and that
// patch's response dlambda_h = gain d to an impulse change d of this one.
struct HeldBlocks : PatchBlocks {
  bool valid = false;
  Mat6 gain = Mat6::Zero();
};

// The friction block's K must be well inside the positive definite cone for
// the core's block solvers, which refuse a K whose unit-diagonal form has a
// condition number of 1e10 or more: det(D K D) > kMinUnitDet with D =
// diag(K)^-1/2 bounds that condition number by 27 / kMinUnitDet (3x3, unit
// diagonal: lambda_max <= 3, lambda_min >= det / 9).
constexpr double kMinUnitDet = 1e-8;

// The blocks of K6. False if W is not positive definite (Sylvester's
// criterion; e.g. a body with locked rotation) or if Ks is not safely so
// (det(D Ks D) <= kMinUnitDet; e.g. spin about the normal locked). Guarded by
// patch_blocks_test.
bool makePatchBlocks(const Mat6& K6, PatchBlocks& blocks);

// The blocks of K with the first N DOFs of another patch held: Kh is that
// patch's K6 (its top-left N x N block is used), C the coupling (rows: this
// patch's DOFs, columns: the held ones). `held.valid` says whether it worked.
template <int N>
void foldHeldDofs(const Mat6& K, const Mat6& Kh, const Eigen::Matrix<double, 6, N>& C,
                  HeldBlocks& held);

extern template void foldHeldDofs<3>(const Mat6&, const Mat6&, const Eigen::Matrix<double, 6, 3>&,
                                     HeldBlocks&);
extern template void foldHeldDofs<6>(const Mat6&, const Mat6&, const Eigen::Matrix<double, 6, 6>&,
                                     HeldBlocks&);

}  // namespace patchspin::parts
