// Exact model, Eq. (16), on a convex region bounded by segments and circular
// arcs (exactArcRegionBasis; F, dF as in patchspin/internal/exact.hpp).
//
// Near branch (ICR c within kFarRatio region radii of the frame centre g):
// with u = (P - c)/|P - c| = grad rho_c, the unit kernel is
// k = sgn(w3) (perp(u), (P.u)/rho) (Eq. (1): v = (w3/rho) perp(P - c)), and
// for phi = phi_c + q.(P - c) the divergence theorem turns
// G = ∫_A phi (perp(u), P.u) dA into boundary moments (exact_boundary_moments.hpp):
//   V = ∫ phi u dA = ∮ phi rho_c n - q ∫ rho_c dA = phi_c N1 + M^T q - q tr(M)/3
//       (∫ rho_c dA = ∮ rho_c r.n / 3, div(r rho_c) = 3 rho_c)
//   force = perp(V),
//   torque = ∫ phi (c.u + rho_c) dA = c.V + phi_c tr(M)/3 + q.N3/3
//       (grad rho_c^3 = 3 rho_c r);
// F.col = sgn(w3) (force, torque / rho). The moments of a segment are
// elementary, those of an arc incomplete elliptic integrals (ibid.). Rounding
// grows like kappa^3 eps (moments of size kappa^3, result of size 1), as the
// polygon's edge sum.
//
// Far branch (includes w3 = 0): tensor Gauss-Legendre on the fan from g to
// each piece (arcs split into spans <= pi/2), P = g + l (x(s) - g),
// dA = l ((x - g) x x'(s)) dl ds; the integrand is analytic there.
// Both in the frame centred at g (P' = P - g), moved back to O as in
// exact_polygon.cpp. Guarded by exact_arc_region_test.cpp.
#include "exact_area_rule.hpp"
#include "exact_boundary_moments.hpp"
#include "gauss_tables.hpp"

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace patchspin::internal {

Vec2 BoundaryPiece::start() const {
  return kind == Kind::Segment ? a : centre + radius * Vec2(std::cos(angle0), std::sin(angle0));
}
Vec2 BoundaryPiece::end() const {
  return kind == Kind::Segment ? b : centre + radius * Vec2(std::cos(angle1), std::sin(angle1));
}

namespace {

// Far branch beyond this many region radii (as the polygon's kFarRatio).
constexpr double kFarRatio = 8.0;
// Relative gap between consecutive pieces accepted as closed (rounding of the
// arcs' end points).
constexpr double kClosureRel = 1e-9;
constexpr double kDeltaZeroRel = 1e-15;
constexpr int kArcOrder = 10;

[[noreturn]] void fail(const std::string& what) {
  throw Error("exactArcRegionBasis: " + what);
}

// A piece moved into the g-frame.
BoundaryPiece shifted(const BoundaryPiece& p, const Vec2& g) {
  BoundaryPiece q = p;
  q.a -= g, q.b -= g, q.centre -= g;
  return q;
}

// Near branch: F' (g-frame) from the boundary moments about c, and dF'/dw'
// through c. With d rho_c/dc = -u (exact_boundary_moments.hpp) and
// tr_j = tr(dM/dc_j) = -sum_i U[i](i, j) - N1_j:
//   dV/dc_j = -phi_c Q(j, :) - (U[k](., j).q)_k - q tr_j / 3
//   dtorque/dc_j = V_j + c.dV/dc_j + q_j tr(M)/3 + phi_c tr_j/3 - q.M(j, :)
// (the q_j N1 of d phi_c/dc cancels), then dc'/dw' = (rho/w3) [[0, -1, w2/w3], [1, 0, -w1/w3]].
void nearBranch(const std::vector<BoundaryPiece>& pieces, const Vec2& g, const Vec3& wl, double rho,
                double size, bool wantJacobian, ExactBasis& acc) {
  const double sgn = wl.z() > 0.0 ? 1.0 : -1.0;
  const Vec2 c(-rho * wl.y() / wl.z(), rho * wl.x() / wl.z());
  BoundaryMoments mom;
  for (const BoundaryPiece& piece : pieces) {
    const BoundaryPiece p = shifted(piece, g);
    if (p.kind == BoundaryPiece::Kind::Segment) {
      addSegmentMoments(p.a, p.b, c, kDeltaZeroRel * size, wantJacobian, mom);
    } else {
      addArcMoments(p.centre, p.radius, p.angle0, p.angle1, c, wantJacobian, mom);
    }
  }
  const double trM = mom.M.trace();
  Eigen::Matrix<double, 2, 3> dc;
  dc << 0.0, -1.0, wl.y() / wl.z(), 1.0, 0.0, -wl.x() / wl.z();
  dc *= rho / wl.z();
  const Vec3 scale(sgn, sgn, sgn / rho);
  for (int k = 0; k < 3; ++k) {
    const double phic = k == 0 ? 1.0 : c[k - 1];
    const Vec2 q = k == 0 ? Vec2(Vec2::Zero()) : Vec2(Vec2::Unit(k - 1));
    const Vec2 V = phic * mom.N1 + mom.M.transpose() * q - q * (trM / 3.0);
    const double torque = c.dot(V) + phic * trM / 3.0 + q.dot(mom.N3) / 3.0;
    acc.F.col(k) = scale.cwiseProduct(Vec3(-V.y(), V.x(), torque));
    if (!wantJacobian) continue;
    Eigen::Matrix<double, 3, 2> dG;
    for (int j = 0; j < 2; ++j) {
      const double trj = -(mom.U[0](0, j) + mom.U[1](1, j)) - mom.N1[j];
      const Vec2 dV = -phic * mom.Q.row(j).transpose() -
                      Vec2(mom.U[0].col(j).dot(q), mom.U[1].col(j).dot(q)) - q * (trj / 3.0);
      const double dT =
          V[j] + c.dot(dV) + q[j] * trM / 3.0 + phic * trj / 3.0 - q.dot(mom.M.row(j));
      dG.col(j) = Vec3(-dV.y(), dV.x(), dT);
    }
    acc.dF[k] = scale.asDiagonal() * dG * dc;
  }
}

// Far branch: fan rule of order n from the g-frame origin, the kernel at each
// node by addKernelNode (exact_area_rule.hpp).
void farBranch(const std::vector<BoundaryPiece>& pieces, const Vec2& g, const Vec3& wl, double rho,
               int n, bool wantJacobian, ExactBasis& acc) {
  const GaussTables& gt = gaussTables();
  const double inv = 1.0 / rho;
  // order along the piece: n, at least kArcOrder on arcs (trigonometric in t)
  auto addSpan = [&](auto&& point, auto&& tangent, double length, int nt) {
    for (int i = 0; i < nt; ++i) {
      const double s = gt.x[nt][i];
      const Vec2 x = point(s), dx = tangent(s) * length;
      const double jac = x.x() * dx.y() - x.y() * dx.x();
      for (int j = 0; j < n; ++j) {
        const double l = gt.x[n][j];
        const Vec2 P = l * x;
        const double wt = gt.w[nt][i] * gt.w[n][j] * l * jac;
        const Vec3 phi = wt * Vec3(1.0, P.x(), P.y());
        if (wantJacobian)
          addKernelNode<true, 3>(P, phi, wl, inv, acc.F, acc.dF.data());
        else
          addKernelNode<false, 3>(P, phi, wl, inv, acc.F, nullptr);
      }
    }
  };
  for (const BoundaryPiece& piece : pieces) {
    const BoundaryPiece p = shifted(piece, g);
    if (p.kind == BoundaryPiece::Kind::Segment) {
      addSpan([&](double s) -> Vec2 { return p.a + s * (p.b - p.a); },
              [&](double) -> Vec2 { return p.b - p.a; }, 1.0, n);
      continue;
    }
    const double span = p.angle1 - p.angle0;
    const int parts = std::max(1, static_cast<int>(std::ceil(span / (0.5 * M_PI))));
    const double h = span / parts;
    for (int q = 0; q < parts; ++q) {
      const double t0 = p.angle0 + q * h;
      addSpan(
          [&](double s) -> Vec2 {
            return p.centre + p.radius * Vec2(std::cos(t0 + s * h), std::sin(t0 + s * h));
          },
          [&](double s) -> Vec2 {
            return p.radius * Vec2(-std::sin(t0 + s * h), std::cos(t0 + s * h));
          },
          h, std::max(n, kArcOrder));
    }
  }
}

// Order of the far rule (exact_area_rule.hpp's farOrder at 1e-13, well below
// the 1e-10 contract), at least 3. Along arcs at least kArcOrder (the area
// element is trigonometric in t; order 6 lost 1.6e-10 on the thin segment's
// arc, whose area is 1/10 of a^2 times its span).
constexpr double kQuadratureTol = 1e-13;
int arcFarOrder(double kappaSq, bool jacobian) {
  return std::max(3, farOrder(kappaSq, kQuadratureTol, jacobian));
}

}  // namespace

void exactArcRegionBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                         bool wantJacobian, ExactBasis& out) {
  const std::size_t N = boundary.size();
  if (N < 1) fail("need at least 1 boundary piece");
  if (!(rho > 0.0) || !std::isfinite(rho)) fail("rho must be finite and > 0");
  if (!w.allFinite() || w.cwiseAbs().maxCoeff() == 0.0) fail("w must be finite and nonzero");
  // frame centre g: mean of the pieces' start points and arc mid points;
  // size: a bound of |P - g| over the region
  Vec2 g = Vec2::Zero();
  int count = 0;
  for (const BoundaryPiece& p : boundary) {
    if (p.kind == BoundaryPiece::Kind::Arc) {
      if (!(p.radius > 0.0) || !(p.angle1 > p.angle0) || !(p.angle1 - p.angle0 <= 2.0 * M_PI))
        fail("an arc needs radius > 0 and 0 < angle1 - angle0 <= 2 pi");
      const double tm = 0.5 * (p.angle0 + p.angle1);
      g += p.centre + p.radius * Vec2(std::cos(tm), std::sin(tm));
      ++count;
    }
    g += p.start();
    ++count;
  }
  g /= count;
  if (!g.allFinite()) fail("pieces must be finite");
  // size = max |P - g| on the boundary: a piece's ends, or an arc's point
  // farthest from g (direction g -> centre) when the arc contains it
  double size = 0.0;
  for (const BoundaryPiece& p : boundary) {
    size = std::max({size, (p.start() - g).norm(), (p.end() - g).norm()});
    if (p.kind == BoundaryPiece::Kind::Arc) {
      const Vec2 away = p.centre - g;
      const double t = std::atan2(away.y(), away.x());
      const double k = std::floor((t - p.angle0) / (2.0 * M_PI));
      if (t - 2.0 * M_PI * k <= p.angle1) size = std::max(size, away.norm() + p.radius);
    }
  }
  for (std::size_t i = 0; i < N; ++i) {
    if ((boundary[i].end() - boundary[(i + 1) % N].start()).norm() > kClosureRel * size)
      fail("piece " + std::to_string(i) + " does not end where the next starts");
  }

  // g's frame (exact_area_rule.hpp), kappa in units of size
  const RegionFrame frame(g, rho, w);
  ExactBasis l;  // g-frame
  if (frame.far(kFarRatio, size * size)) {
    const int n = arcFarOrder(frame.kappaSq(size * size), wantJacobian);
    farBranch(boundary, g, frame.wl, rho, n, wantJacobian, l);
  } else {
    nearBranch(boundary, g, frame.wl, rho, size, wantJacobian, l);
  }
  basisAtO(l.F, l.dF, g, frame, wantJacobian, out);
}

}  // namespace patchspin::internal
