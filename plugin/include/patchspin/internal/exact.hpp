// Building blocks of the exact model, Eq. (16), for unit pressure fields.
//
// For a slip direction w (any nonzero 3-vector; the integrand is homogeneous
// of degree 0 in w, so only its direction matters) and a length scale rho,
// the local slip velocity at (x, y) is, Eq. (1) with x_o = w:
//     v(x, y) = (w1 - w3 y / rho, w2 + w3 x / rho)
// and the unit friction kernel is
//     k(w; x, y) = (v_x, v_y, (x v_y - y v_x) / rho) / |v|.
// The instantaneous centre of rotation is c = rho (-w2, w1) / w3 (w3 != 0);
// w3 = 0 is pure translation (c at infinity).
//
// ExactBasis::F has one column per pressure basis function phi = (1, x, y):
//     F.col(k) = ∫_A phi_k(x, y) k(w; x, y) dA,
// so that for p = p0 + cx x + cy y the exact wrench (16) is
//     Q = -mu F (p0, cx, cy)^T.
// dF[k] = d F.col(k) / dw (3x3) of the degree-0 homogeneous function, so
// dF[k] w = 0. Filled only when wantJacobian is true.
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/types.hpp>

#include <array>
#include <vector>

namespace patchspin::internal {

struct ExactBasis {
  Mat3 F = Mat3::Zero();
  std::array<Mat3, 3> dF{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
};

// Convex polygon, counter-clockwise vertices in the patch frame (O = origin,
// which may lie anywhere). tolerance: 0 = full accuracy.
void exactPolygonBasis(const std::vector<Vec2>& vertices, double rho, const Vec3& w,
                       bool wantJacobian, ExactBasis& out, double tolerance = 0.0);

// The law's integral for one linear pressure p = p0 + cx x + cy y,
// pressure = (p0, cx, cy): returns F (p0, cx, cy)^T = ∫_A p k dA and, if
// jacobian is not null, its d/dw = sum_k pressure_k dF[k]; the same
// polygon, rho, w and tolerance as exactPolygonBasis, in one pass over the
// single function p (about half the basis' work with the Jacobian).
Vec3 exactPolygonLaw(const std::vector<Vec2>& vertices, double rho, const Vec3& w,
                     const Vec3& pressure, Mat3* jacobian, double tolerance = 0.0);

// Disk of radius R centred at `centre` (patch frame).
void exactDiskBasis(const Vec2& centre, double R, double rho, const Vec3& w, bool wantJacobian,
                    ExactBasis& out, double tolerance = 0.0);

// Hertz pressure (57) with unit total load on a disk of radius R centred at
// `centre`:  ∫_A p1(x, y) k(w; x, y) dA  with  p1 = 3/(2 pi R^2) sqrt(1 - |P-C|^2/R^2).
// Q = -mu Pz * result. `jacobian` (if not null) receives d result / dw.
Vec3 exactDiskHertz(const Vec2& centre, double R, double rho, const Vec3& w, Mat3* jacobian,
                    double tolerance = 0.0);

// The boundary piece type is public (patchspin/geometry.hpp); this alias keeps
// the older spelling.
using BoundaryPiece = patchspin::BoundaryPiece;

// Convex region bounded by segments and circular arcs (a disk segment, a
// lens, a disk cut by lines), in the patch frame: the same F and dF as
// exactPolygonBasis.
void exactArcRegionBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                         bool wantJacobian, ExactBasis& out);

}  // namespace patchspin::internal
