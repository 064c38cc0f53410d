// Exact model, Eq. (16), on a convex polygon with linear pressure basis
// (1, x, y): see patchspin/internal/exact.hpp for the definitions of F, dF.
// exactPolygonLaw integrates one linear pressure the same way, with that
// pressure as the only function (the near branch also sums phi = 1, which
// its derivative needs), instead of the three basis functions.
//
// Two branches, both evaluated in the frame centred at the vertex mean g
// (P' = P - g), then moved to O:
//  * near: the ICR c is within kFarRatio circumradii of g. Closed form as a
//    sum over edges of signed triangles (c, edge), polar about c
//    (exact_edge_integrals.hpp, DESIGN item 3); its derivative in c from the
//    same closed forms (a boundary integral, plus two terms of the sums
//    themselves) and the chain rule through c(w).
//  * far (includes pure translation w3 = 0): the integrand is analytic on the
//    polygon, so a tensor Gauss-Legendre rule on a fan of quadrilaterals
//    (and one triangle for odd vertex counts) from vertex 0, with the order
//    chosen from the distance ratio; v is computed from w directly.
//
// Accuracy (normwise per column, relative to area * max|phi_k| *
// (1 + max|P|/rho), see exact_polygon_basis_test.cpp): <= 1e-13 measured against a
// brute-force oracle over the sphere (ICR on edges and vertices, w3 -> 0,
// w3 = 0); dF to ~1e-11 (worst measured 1.4e-10, elongated patch with small
// rho, at the branch switch; the edge-integral derivative agreed with the
// former dual-number one to 1.6e-10 of |dF| over 2000 random polygons and
// 40000 directions, ICRs on vertices and edges included). `tolerance` > 0 lowers only the far
// branch's order (measured error <= 0.02 tolerance); the edge sum has no knob. The polygon must be
// convex (the far rule fans from vertex 0); this is not checked here (PatchShape::polygon checks
// it).
#include "exact_area_rule.hpp"
#include "exact_edge_integrals.hpp"
#include "gauss_tables.hpp"

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace patchspin::internal {
namespace {

// ICR farther than this many circumradii from g -> quadrature branch. The
// edge sum loses about kappa^3 eps to cancellation (triangles of area kappa
// times the polygon's, lever arm kappa; measured 6e-13 for F at kappa = 8),
// its derivative in c about kappa^2 more through dc/dw; the rule needs
// fewer nodes for larger kappa (order 8 at kappa = 8, 4 beyond ~200, 3 beyond
// ~1e4; with the Jacobian one more).
constexpr double kFarRatio = 8.0;
// Default target of the far branch's quadrature error (relative to the scale
// of F); well below the 1e-10 contract.
constexpr double kDefaultQuadratureTol = 1e-13;
// |delta| below this times the edge length is rounding noise of an ICR on the
// edge's line (e.g. exactly on a vertex).
constexpr double kDeltaZeroRel = 1e-15;
// Polygons up to this many vertices are handled without heap allocation.
constexpr std::size_t kStackVertices = 32;

[[noreturn]] void fail(const std::string& what) {
  throw Error("exactPolygonBasis: " + what);
}

// Accumulated F' (g-frame) and dF'/dw', one column per integrated function:
// the basis (1, x, y) (M = 3) or one linear pressure (M = 1).
template <int M>
struct Accumulator {
  Eigen::Matrix<double, 3, M> F = Eigen::Matrix<double, 3, M>::Zero();
  std::array<Mat3, M> dF;
  Accumulator() {
    for (Mat3& d : dF) d.setZero();
  }
};

// The functions' weights at P (g-frame): the basis (1, x, y), or the linear
// pressure p' (p0', px, py) of the g-frame.
template <int M>
Eigen::Matrix<double, M, 1> weightsAt(const Vec2& P, const Vec3& pressure) {
  if constexpr (M == 3) {
    (void)pressure;
    return Vec3(1.0, P.x(), P.y());
  } else {
    return Eigen::Matrix<double, 1, 1>(pressure[0] + pressure[1] * P.x() + pressure[2] * P.y());
  }
}

// ---- far branch ----
//
// Quadrilateral (p0, p1, p2, p3) (a triangle when p3 = p0), bilinear map
//   P(s, t) = (1-s)(1-t) p0 + s(1-t) p1 + s t p2 + (1-s) t p3,  s, t in [0, 1]
//   dA = det[dP/ds, dP/dt] ds dt  (linear in s, t);
// at each node the kernel of addKernelNode (exact_area_rule.hpp).
template <bool kJacobian, int M>
void addQuadRule(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, int n,
                 const Vec3& w, double rho, const Vec3& pressure, Accumulator<M>& acc) {
  const GaussTables& g = gaussTables();
  const double inv = 1.0 / rho;
  const Vec2 e01 = p1 - p0, e32 = p2 - p3;
  for (int i = 0; i < n; ++i) {
    const double s = g.x[n][i];
    const Vec2 a = (1.0 - s) * p0 + s * p1, b = (1.0 - s) * p3 + s * p2;
    const Vec2 dPdt = b - a;
    for (int j = 0; j < n; ++j) {
      const double t = g.x[n][j];
      const Vec2 P = a + t * dPdt;
      const Vec2 dPds = (1.0 - t) * e01 + t * e32;
      const double det = dPds.x() * dPdt.y() - dPds.y() * dPdt.x();
      const double wt = g.w[n][i] * g.w[n][j] * det;
      addKernelNode<kJacobian, M>(P, wt * weightsAt<M>(P, pressure), w, inv, acc.F, acc.dF.data());
    }
  }
}

template <bool kJacobian, int M>
void farBranch(const Vec2* v, std::size_t N, const Vec3& w, double rho, int n, const Vec3& pressure,
               Accumulator<M>& acc) {
  std::size_t i = 1;
  for (; i + 2 < N; i += 2)
    addQuadRule<kJacobian>(v[0], v[i], v[i + 1], v[i + 2], n, w, rho, pressure, acc);
  if (i + 1 < N) addQuadRule<kJacobian>(v[0], v[i], v[i + 1], v[0], n, w, rho, pressure, acc);
}

// ---- near branch ----
template <int E>
void nearBranch(const Vec2* v, std::size_t N, double cx, double cy, double deltaZeroRel,
                const LinearFunctions<E>& phi, EdgeSums<E>& sums, EdgeSumsGradient<E>* gradient,
                int firstGradient) {
  sums = EdgeSums<E>{};
  if (gradient) *gradient = EdgeSumsGradient<E>{};
  auto dist = [&](const Vec2& p) {
    const double dx = p.x() - cx, dy = p.y() - cy;
    return std::sqrt(dx * dx + dy * dy);
  };
  const double R0 = dist(v[0]);
  double Ra = R0;
  for (std::size_t i = 0; i < N; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[i + 1 == N ? 0 : i + 1];
    const double Rb = i + 1 == N ? R0 : dist(b);
    const double L = (b - a).norm();
    if (L > 0.0) {  // a repeated vertex adds no triangle
      addSignedTriangle(a.x(), a.y(), b.x(), b.y(), L, cx, cy, Ra, Rb, deltaZeroRel * L, phi, sums,
                        gradient, firstGradient);
    }
    Ra = Rb;
  }
}

// The near branch for M output columns: the basis (M = 3, edge functions
// 1, x, y) or one linear pressure (M = 1, edge functions 1 and p').
// dG/dc (exact_edge_integrals.hpp): the edge terms, d phi_k / dc_j = g_k,j
// times the phi = 1 column, and the torque's (G_y, -G_x); then
// dc'/dw' = (rho/w3) [[0, -1, w2/w3], [1, 0, -w1/w3]].
template <int M>
void nearColumns(const Vec2* v, std::size_t N, const Vec3& wl, double rho, bool wantJacobian,
                 const Vec3& pressure, Accumulator<M>& acc) {
  constexpr int E = M == 3 ? 3 : 2;  // edge functions
  constexpr int kFirst = E - M;      // the first edge function that is an output column
  const double sgn = wl.z() > 0.0 ? 1.0 : -1.0;
  const double cx = -rho * wl.y() / wl.z(), cy = rho * wl.x() / wl.z();
  LinearFunctions<E> phi{};
  if constexpr (M == 3) {
    phi.pc[1] = cx, phi.gx[1] = 1.0, phi.gy[1] = 0.0;
    phi.pc[2] = cy, phi.gx[2] = 0.0, phi.gy[2] = 1.0;
  } else {
    phi.pc[1] = pressure[0] + pressure[1] * cx + pressure[2] * cy;
    phi.gx[1] = pressure[1], phi.gy[1] = pressure[2];
  }
  EdgeSums<E> sums;
  EdgeSumsGradient<E> edge;
  nearBranch(v, N, cx, cy, kDeltaZeroRel, phi, sums, wantJacobian ? &edge : nullptr, kFirst);
  const double scale[3] = {sgn, sgn, sgn / rho};
  for (int k = kFirst; k < E; ++k) {
    acc.F(0, k - kFirst) = scale[0] * sums.fx[k];
    acc.F(1, k - kFirst) = scale[1] * sums.fy[k];
    acc.F(2, k - kFirst) = scale[2] * sums.tz[k];
  }
  if (!wantJacobian) return;
  Eigen::Matrix<double, 2, 3> dc;
  dc << 0.0, -1.0, wl.y() / wl.z(), 1.0, 0.0, -wl.x() / wl.z();
  dc *= rho / wl.z();
  for (int k = kFirst; k < E; ++k) {
    Eigen::Matrix<double, 3, 2> dGdc;
    for (int j = 0; j < 2; ++j) {
      const double gj = k == 0 ? 0.0 : j == 0 ? phi.gx[k] : phi.gy[k];
      dGdc(0, j) = edge.fx[k][j] + gj * sums.fx[0];
      dGdc(1, j) = edge.fy[k][j] + gj * sums.fy[0];
      dGdc(2, j) = edge.tz[k][j] + gj * sums.tz[0] + (j == 0 ? sums.fy[k] : -sums.fx[k]);
    }
    const Eigen::Matrix<double, 3, 2> dFdc = Vec3(scale[0], scale[1], scale[2]).asDiagonal() * dGdc;
    acc.dF[k - kFirst] = dFdc * dc;
  }
}

// Checks, the g-frame and both branches: F', dF' of the M columns in the
// g-frame (pressure: the law's coefficients about O, used when M = 1), with
// S and the w scale for the way back to O.
template <int M>
void evaluateInFrame(const std::vector<Vec2>& vertices, double rho, const Vec3& w,
                     bool wantJacobian, double tolerance, const Vec3& pressure, Accumulator<M>& acc,
                     Vec2& g, RegionFrame& frame) {
  const std::size_t N = vertices.size();
  if (N < 3) fail("need at least 3 vertices, got " + std::to_string(N));
  if (!(rho > 0.0) || !std::isfinite(rho)) fail("rho must be finite and > 0");
  if (!w.allFinite() || w.cwiseAbs().maxCoeff() == 0.0) fail("w must be finite and nonzero");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) fail("tolerance must be finite and >= 0");

  // centre frame: P' = P - g, w' = S w (Eq. (1) about g)
  g = Vec2::Zero();
  for (const Vec2& p : vertices) {
    if (!p.allFinite()) fail("vertices must be finite");
    g += p;
  }
  g /= static_cast<double>(N);
  // vertices in the g-frame; no allocation up to kStackVertices
  std::array<Vec2, kStackVertices> stackBuffer;
  std::vector<Vec2> heapBuffer;
  if (N > kStackVertices) heapBuffer.resize(N);
  Vec2* local = N > kStackVertices ? heapBuffer.data() : stackBuffer.data();
  double radiusSq = 0.0, twiceArea = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    local[i] = vertices[i] - g;
    radiusSq = std::max(radiusSq, local[i].squaredNorm());
  }
  for (std::size_t i = 0; i < N; ++i) {
    const Vec2& a = local[i];
    const Vec2& b = local[i + 1 == N ? 0 : i + 1];
    twiceArea += a.x() * b.y() - a.y() * b.x();
  }
  if (!(twiceArea > 0.0)) fail("polygon must be counter-clockwise with positive area");
  // the pressure about g: p = p0 + px (gx + x') + py (gy + y')
  const Vec3 localPressure(pressure[0] + pressure[1] * g.x() + pressure[2] * g.y(), pressure[1],
                           pressure[2]);

  // g's frame (exact_area_rule.hpp); kappa in circumradii
  frame = RegionFrame(g, rho, w);
  const Vec3& wl = frame.wl;
  if (frame.far(kFarRatio, radiusSq)) {
    const double kappaSq = frame.kappaSq(radiusSq);
    const double tol = tolerance > 0.0 ? std::max(tolerance, 1e-15) : kDefaultQuadratureTol;
    const int n = farOrder(kappaSq, tol, wantJacobian);
    if (wantJacobian) {
      farBranch<true>(local, N, wl, rho, n, localPressure, acc);
    } else {
      farBranch<false>(local, N, wl, rho, n, localPressure, acc);
    }
  } else {
    nearColumns(local, N, wl, rho, wantJacobian, localPressure, acc);
  }
}

}  // namespace

void exactPolygonBasis(const std::vector<Vec2>& vertices, double rho, const Vec3& w,
                       bool wantJacobian, ExactBasis& out, double tolerance) {
  Accumulator<3> acc;
  Vec2 g;
  RegionFrame frame;
  evaluateInFrame(vertices, rho, w, wantJacobian, tolerance, Vec3::Zero(), acc, g, frame);
  basisAtO(acc.F, acc.dF, g, frame, wantJacobian, out);
}

Vec3 exactPolygonLaw(const std::vector<Vec2>& vertices, double rho, const Vec3& w,
                     const Vec3& pressure, Mat3* jacobian, double tolerance) {
  if (!pressure.allFinite()) fail("pressure coefficients must be finite");
  Accumulator<1> acc;
  Vec2 g;
  RegionFrame frame;
  evaluateInFrame(vertices, rho, w, jacobian != nullptr, tolerance, pressure, acc, g, frame);
  // back to O: torque about O = T k', T = S^T; d/dw through w' = S w / wScale
  const Mat3 T = frame.S.transpose();
  if (jacobian) jacobian->noalias() = T * acc.dF[0] * (frame.S / frame.wScale);
  return T * acc.F.col(0);
}

}  // namespace patchspin::internal
