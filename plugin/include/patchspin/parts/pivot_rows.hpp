// Pivot rows part: a patch whose centre of pressure is clamped to its
// boundary (normal_block.hpp, (S6)) pushes only at its pivot points, the
// corners of the edge it tips over (or the one nearest point). Each is a
// unilateral row on the patch's normal DOFs, row(p) = (1, p_y, -p_x): the
// normal velocity at p is row(p) . c_n, and a force P there is the impulse
// P row(p) (docs/solver.md (S4)-(S6), (S26)-(S27)). Guarded by
// pivot_rows_test and HandBack.*.
#pragma once

#include <patchspin/parts/normal_block.hpp>
#include <patchspin/parts/patch_blocks.hpp>

namespace patchspin::parts {

struct PivotRows {
  int n = 0;  // 1 or 2
  Vec3 a[2];
};

inline Vec3 pivotRow(const Vec2& p) {
  return Vec3(1.0, p.y(), -p.x());
}

// The pivot rows of a normal impulse whose centre of pressure is on (or
// beyond) the patch's boundary, as pivotPoints takes them; n = 0 if the
// impulse does not push (lamN_z <= 0).
PivotRows pivotRowsOf(const PatchShape& shape, const Vec3& lamN);

// Whether lamN (in the span of the rows) is a combination of them with
// every impulse >= 0, up to a relative 1e-9 of |lamN| (round-off).
bool pivotsPush(const PivotRows& rows, const Vec3& lamN);

// A clamped patch that sticks: its pivot rows and its three friction DOFs
// held together,                                                          (S26)
//   H K6 H^T z = H (r + K6 (lamN, 0)),   H = [pivot rows 0; 0 I3],
// z = (the pivots' impulses, the friction impulse change), with r =
// (target_n - c_n, -c_f) the six DOFs' velocity residual before, K6 the
// patch's (or its held) effective mass and lamN its normal impulse before;
// d = H^T z - (lamN, 0) the impulse change: the normal impulse becomes the
// pivots' alone. (Solving the normal rows and then the friction block
// apart converges like the mass ratio on a light box pivoting under a
// heavy one.) False if the system is singular or a pivot pulls (z_i < 0).
bool solvePivotsWithFriction(const Mat6& K6, const PivotRows& rows, const Vec3& lamN, const Vec6& r,
                             Vec6& d);

// The blocks of K with a held patch's constraints H (m x 6, rows on its
// DOFs; m <= 6) held: Kh its K6, C the velocity of this patch's DOFs per
// impulse on its DOFs; the held patch takes dlambda_h = gain d,
// gain = -H^T (H Kh H^T)^-1 H C^T. With H the first N unit rows it is
// foldHeldDofs<N>.                                                        (S27)
void foldHeldRows(const Mat6& K, const Mat6& Kh, const Mat6& C,
                  const Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6>& H, HeldBlocks& held);

}  // namespace patchspin::parts
