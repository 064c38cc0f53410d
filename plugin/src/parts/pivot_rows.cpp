// Pivot rows part (pivot_rows.hpp; docs/solver.md (S26)-(S27)).
#include <patchspin/parts/pivot_rows.hpp>

#include <Eigen/Cholesky>

namespace patchspin::parts {

namespace {
using RowsH = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6>;
using SmallM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using SmallV = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
}  // namespace

PivotRows pivotRowsOf(const PatchShape& shape, const Vec3& lamN) {
  PivotRows rows;
  if (!(lamN[0] > 0.0)) return rows;
  const Vec2 cop(-lamN[2] / lamN[0], lamN[1] / lamN[0]);
  Vec2 p[2];
  rows.n = pivotPoints(shape, cop, p);
  for (int k = 0; k < rows.n; ++k) rows.a[k] = pivotRow(p[k]);
  return rows;
}

bool pivotsPush(const PivotRows& r, const Vec3& lamN) {
  const double tol = 1e-9 * lamN.norm();
  if (r.n == 1) return r.a[0].dot(lamN) >= -tol;
  if (r.n != 2) return false;
  Eigen::Matrix<double, 3, 2> A;
  A << r.a[0], r.a[1];
  const Vec2 z = (A.transpose() * A).ldlt().solve(A.transpose() * lamN);
  return z[0] >= -tol && z[1] >= -tol;
}

bool solvePivotsWithFriction(const Mat6& K6, const PivotRows& rows, const Vec3& lamN, const Vec6& r,
                             Vec6& d) {
  if (rows.n < 1 || rows.n > 2) return false;
  RowsH H = RowsH::Zero(rows.n + 3, 6);
  for (int k = 0; k < rows.n; ++k) H.block<1, 3>(k, 0) = rows.a[k].transpose();
  H.block<3, 3>(rows.n, 3).setIdentity();
  Vec6 lam0 = Vec6::Zero();
  lam0.head<3>() = lamN;
  const SmallM A = H * K6 * H.transpose();
  const Eigen::LDLT<SmallM> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  const SmallV z = ldlt.solve(H * (r + K6 * lam0));
  if (!z.allFinite()) return false;
  for (int k = 0; k < rows.n; ++k)
    if (z[k] < 0.0) return false;
  d = H.transpose() * z - lam0;
  return true;
}

void foldHeldRows(const Mat6& K, const Mat6& Kh, const Mat6& C, const RowsH& H, HeldBlocks& h) {
  h.valid = false;
  const SmallM A = H * Kh * H.transpose();
  const Eigen::LDLT<SmallM> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
  const Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> CHt = C * H.transpose();
  const RowsH Z = ldlt.solve(CHt.transpose());
  const Mat6 Kf = K - CHt * Z;
  if (!makePatchBlocks(0.5 * (Kf + Kf.transpose()), h)) return;
  h.gain = -H.transpose() * Z;
  h.valid = h.Winv.allFinite() && h.KsInv.allFinite() && h.gain.allFinite();
}

}  // namespace patchspin::parts
