// Patch body part: effective mass, rows and velocity of a patch's six DOFs
// (patch_body.hpp; docs/solver.md, Eqs. (S1)-(S2)).
#include <patchspin/parts/patch_body.hpp>

namespace patchspin::parts {

// K6 = J M^-1 J^T with, in the patch frame (primes), linear rows S (the
// selection of u' components) and angular rows
//   Ja' = [r' x e_z; e_x; e_y; r' x e_x; r' x e_y; rho e_z].
// The angular rows are sparse (three are axes, the others have a zero), so
// K_ang(i, j) = Ja_i . (invI' Ja_j) is written out term by term: the same
// products summed in the same order as the dense 3-vector products, without
// the products by zero and one (patch_body_test checks it against the dense
// J M^-1 J^T).
Mat6 patchEffectiveMass(const PatchBody& t, const Mat3& F, double rho) {
  Mat6 K;
  if (!t.dynamic) return Mat6::Zero();
  const Vec3 r = F.transpose() * t.r;
  // F^T diag(invM) F: (1/m) I for the usual isotropic linear factor
  const Mat3 invM = t.invM.x() == t.invM.y() && t.invM.y() == t.invM.z()
                        ? Mat3(t.invM.x() * Mat3::Identity())
                        : Mat3(F.transpose() * t.invM.asDiagonal() * F);
  const Mat3 I = F.transpose() * t.invI * F;  // invI', symmetric
  // x_j = invI' Ja_j (columns c0, c1, c2 of invI')
  const double rx = r.x(), ry = r.y(), rz = r.z();
  Vec3 x[6];
  for (int k = 0; k < 3; ++k) {
    x[0][k] = I(k, 0) * ry + I(k, 1) * -rx;  // Ja_0 = (ry, -rx, 0)
    x[1][k] = I(k, 0);                       // Ja_1 = e_x
    x[2][k] = I(k, 1);                       // Ja_2 = e_y
    x[3][k] = I(k, 1) * rz + I(k, 2) * -ry;  // Ja_3 = (0, rz, -ry)
    x[4][k] = I(k, 0) * -rz + I(k, 2) * rx;  // Ja_4 = (-rz, 0, rx)
    x[5][k] = I(k, 2) * rho;                 // Ja_5 = (0, 0, rho)
  }
  // Ja_i . x_j for j >= i
  auto row = [&](int i, const Vec3& xj) {
    switch (i) {
      case 0:
        return ry * xj[0] + -rx * xj[1];
      case 1:
        return xj[0];
      case 2:
        return xj[1];
      case 3:
        return rz * xj[1] + -ry * xj[2];
      case 4:
        return -rz * xj[0] + rx * xj[2];
      default:
        return rho * xj[2];
    }
  };
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) K(i, j) = K(j, i) = row(i, x[j]);
  // linear part: rows 0, 3, 4 select u'_z, u'_x, u'_y
  constexpr int kSel[3] = {0, 3, 4}, kComp[3] = {2, 0, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      K(kSel[i], kSel[j]) = invM(kComp[i], kComp[j]) + K(kSel[i], kSel[j]);
  return K;
}

Mat6 patchEffectiveMass(const PatchBody& a, const PatchBody& b, const Mat3& F, double rho) {
  if (!b.dynamic) return patchEffectiveMass(a, F, rho);
  if (!a.dynamic) return patchEffectiveMass(b, F, rho);
  return patchEffectiveMass(a, F, rho) + patchEffectiveMass(b, F, rho);
}

// c = J [v; omega], J = [[S F^T, S F^T [r]x^T]] in the DOF order (S1).
Mat6 patchBodyRows(const PatchBody& t, const Mat3& F, double rho) {
  Mat6 J = Mat6::Zero();
  Mat3 rx;  // [r]x, rx w = r x w
  rx << 0.0, -t.r.z(), t.r.y(), t.r.z(), 0.0, -t.r.x(), -t.r.y(), t.r.x(), 0.0;
  const Mat3 lin = F.transpose(), ang = F.transpose() * rx.transpose();
  constexpr int kLinRow[3] = {3, 4, 0};  // u'_x, u'_y, u'_z
  for (int k = 0; k < 3; ++k) {
    J.block<1, 3>(kLinRow[k], 0) = lin.row(k);
    J.block<1, 3>(kLinRow[k], 3) = ang.row(k);
  }
  J.block<1, 3>(1, 3) = F.col(0).transpose();
  J.block<1, 3>(2, 3) = F.col(1).transpose();
  J.block<1, 3>(5, 3) = rho * F.col(2).transpose();
  return J;
}

}  // namespace patchspin::parts
