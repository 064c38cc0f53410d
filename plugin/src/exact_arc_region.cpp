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
// Far branch (includes w3 = 0): in complex form the kernel and dF's
// integrand are products of a holomorphic and an antiholomorphic function,
// and Green's theorem turns them into one boundary integral
// (exact_far_green.hpp), integrated by Gauss-Legendre on each piece with
// orders that target kQuadratureTol (farOrder on segments, arcSpanOrder on
// arcs). Both branches in the frame centred at g (P' = P - g), moved back to
// O as in exact_polygon.cpp. Guarded by exact_arc_region_test.cpp
// (FarBranchMatchesOracleAcrossKappa for the far branch).
#include "arc_region_numerics.hpp"
#include "exact_area_rule.hpp"
#include "exact_boundary_moments.hpp"
#include "exact_far_green.hpp"
#include "gauss_tables.hpp"
#include "planar.hpp"

#include <patchspin/internal/exact.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>

namespace patchspin::internal {

namespace {

// Far branch beyond this many region radii (as the polygon's kFarRatio).
constexpr double kFarRatio = 8.0;
// Relative gap between consecutive pieces accepted as closed (rounding of the
// arcs' end points).
constexpr double kClosureRel = 1e-9;
constexpr double kDeltaZeroRel = 1e-15;
// Arcs of radius above this many region sizes make the far branch an area
// rule (farAreaRule).
constexpr double kFlatRadius = 16.0;
// Target of the far rule's quadrature error relative to F's scale, well
// below the 1e-10 contract (as the polygon law's default).
constexpr double kQuadratureTol = 1e-13;

[[noreturn]] void fail(const std::string& what) {
  throw Error("exactArcRegionBasis: " + what);
}

// A piece moved into the g-frame.
BoundaryPiece shifted(const BoundaryPiece& p, const Vec2& g) {
  BoundaryPiece q = p;
  q.a -= g, q.b -= g, q.centre -= g;
  return q;
}

// A flat arc's boundary moments (exact_boundary_moments.hpp's N1, M, N3, Q,
// U) by Gauss-Legendre in the arc's chord frame (arcChord; g-frame points
// P = mid + R' ((cos th - cos h) n + sin th e), normal cos th n + sin th e,
// ds = R' dth): about its centre the arc's points carry ~eps R, eps / h^2
// of a cap's height, and the elliptic forms of addArcMoments cancel with
// them. The integrands are analytic but at P = c, so th is split at the
// ICR's foot th_f and each side in panels [th_f + x q, th_f + x], q = 1/4,
// from the side's end down to the ICR's distance / R' (or 1e-17 of the
// span), order 20 (Bernstein ellipse 3 for the singularity at the panel's
// near end: 3^-40). Guarded by FlatCapsNearBranchMatchOracle.
void addFlatArcMoments(const BoundaryPiece& arc, const Vec2& g, const Vec2& c, bool withGradient,
                       BoundaryMoments& acc) {
  const GaussTables& gt = gaussTables();
  constexpr int kOrder = 20;
  constexpr double kGrade = 0.25;
  const ArcChord ch = arcChord(arc);
  if (!(ch.radius > 0.0)) return;
  const double h = ch.half, Rp = ch.radius;
  const Vec2 mid = ch.mid - g;
  auto pointAt = [&](double th) {
    const double bulge = 2.0 * std::sin(0.5 * (h - th)) * std::sin(0.5 * (h + th));
    return Vec2(mid + Rp * (bulge * ch.n + std::sin(th) * ch.e));
  };
  // the ICR's foot: its angle about the centre (mid - R' cos h n), clamped
  const Vec2 cm = c - mid;
  const double thf = std::clamp(std::atan2(cm.dot(ch.e), cm.dot(ch.n) + Rp * std::cos(h)), -h, h);
  const double dist = (pointAt(thf) - c).norm() / Rp;
  auto panel = [&](double a, double b) {
    for (int i = 0; i < kOrder; ++i) {
      const double th = a + gt.x[kOrder][i] * (b - a);
      const Vec2 P = pointAt(th);
      const Vec2 nrm = std::cos(th) * ch.n + std::sin(th) * ch.e;
      const double wt = gt.w[kOrder][i] * std::abs(b - a) * Rp;
      const Vec2 r = P - c;
      const double rc = r.norm();
      acc.N1 += (wt * rc) * nrm;
      acc.M += (wt * rc) * r * nrm.transpose();
      acc.N3 += (wt * rc * rc * rc) * nrm;
      if (!withGradient || !(rc > 0.0)) continue;
      acc.Q += (wt / rc) * r * nrm.transpose();
      const Mat2 rr = (wt / rc) * r * r.transpose();
      acc.U[0] += nrm.x() * rr;
      acc.U[1] += nrm.y() * rr;
    }
  };
  const double smallest = std::max(dist, 1e-17 * h);
  for (const double end : {-h, h}) {
    double x = std::abs(end - thf);
    if (!(x > 0.0)) continue;
    const double sgn = end > thf ? 1.0 : -1.0;
    while (x > smallest) {
      panel(thf + sgn * kGrade * x, thf + sgn * x);
      x *= kGrade;
    }
    panel(thf, thf + sgn * x);
  }
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
      if (p.radius > kFlatRadius * size)
        addFlatArcMoments(piece, g, c, wantJacobian, mom);
      else
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

// Order of the far rule on one arc span [tm - H, tm + H] (of the circle
// (o, r), g-frame; cm, sm = cos, sin tm), for the target tol relative to F's
// scale; zetaO = ICR - o
// (ignored for translation, finite = false). In t the boundary integrand
// (exact_far_green.hpp) is a trigonometric polynomial (frequencies up to
// kFreq = 2 for F, 4 with dF; coefficients up to (r/size)^kFreq of the
// scale) times a function whose only singularity is the ICR, at
// t* = arg(zetaO) - i ln(|zetaO| / r). Gauss-Legendre's error is
//  * for e^(ikt): c_n (kH)^(2n), c_n = 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^3);
//  * for the singular factor: ~ rhoB^(-2n), rhoB the Bernstein ellipse of
//    [tm - H, tm + H] through t* (nearest of its 2 pi images), plus
//    kSingularExtra orders for the polynomial factor and the kernel's growth
//    (dF's kernel has conj(h)^-3).
// The order is the larger of the two. kSingularExtra was fitted on the test
// regions at 1e-13 (largest excess over 0.5 ln(1/tol)/ln rhoB at kappa = 8:
// 1.7 for F, 3.6 with dF) and is checked by FarBranchMatchesOracleAcrossKappa.
int arcSpanOrder(double H, double cm, double sm, const Cx& zetaO, bool finite, double r,
                 double size, bool jacobian, double tol) {
  static const std::array<double, kGaussMaxOrder + 1> logC = [] {
    std::array<double, kGaussMaxOrder + 1> t{};
    for (int n = 1; n <= kGaussMaxOrder; ++n)
      t[n] = (2 * n + 1) * std::log(2.0) + 4.0 * std::lgamma(n + 1.0) - std::log(2.0 * n + 1.0) -
             3.0 * std::lgamma(2.0 * n + 1.0);
    return t;
  }();
  const double kFreq = jacobian ? 4.0 : 2.0;
  const double kSingularExtra = jacobian ? 4.0 : 2.0;
  const double logTol = std::log(tol);
  const double logAmp = r > size ? kFreq * std::log(r / size) : 0.0;
  const double logX = std::log(kFreq * H);
  int n = 2;
  while (n <= kGaussMaxOrder && logAmp + logC[n] + 2.0 * n * logX > logTol) ++n;
  if (!finite) return n;
  // the ICR at the circle's centre (|zetaO / r|^2 zero, or out of range):
  // the singular factor is constant on the arc, the integrand a
  // trigonometric polynomial (IcrAtAnArcsCentreMatchesOracle; the log below
  // was -inf and the order NaN converted to int, found by the pi and step
  // fuzz targets under UBSan)
  const double zeta2 = (zetaO.re * zetaO.re + zetaO.im * zetaO.im) / (r * r);
  if (!(zeta2 > 0.0) || !std::isfinite(zeta2)) return n;
  // K = (t* - tm) / H; t*'s 2 pi images have the same imaginary part and a
  // larger real one, so a larger ellipse; rhoB = |K + sqrt(K^2 - 1)| on the
  // branch with |.| >= 1
  const double im = -0.5 * std::log(zeta2) / H;
  const double re = std::atan2(cm * zetaO.im - sm * zetaO.re, cm * zetaO.re + sm * zetaO.im) / H;
  // sqrt(K^2 - 1) = sqrt(a + i b), principal
  const double a = re * re - im * im - 1.0, b = 2.0 * re * im;
  const double m = std::sqrt(a * a + b * b);
  const double sr = std::sqrt(0.5 * (m + a)), si = std::copysign(std::sqrt(0.5 * (m - a)), b);
  const double p2 = (re + sr) * (re + sr) + (im + si) * (im + si);
  const double q2 = (re - sr) * (re - sr) + (im - si) * (im - si);
  const double rhoB = std::sqrt(std::max(p2, q2));
  const double nSingular = kSingularExtra - 0.5 * logTol / std::log(rhoB);
  if (std::isnan(nSingular)) return n;  // (an ellipse out of double's range)
  return std::max(n, static_cast<int>(std::min(std::ceil(nSingular), kGaussMaxOrder + 1.0)));
}

// Far branch: Green's theorem turns F and dF into one boundary integral
// (exact_far_green.hpp): Gauss-Legendre of order n (farOrder) on each
// segment; each arc in the fewest equal spans whose orders (arcSpanOrder)
// stay within the tables, the nodes in pairs symmetric about a span's middle
// (one cosine and sine per pair).
void farBranch(const std::vector<BoundaryPiece>& pieces, const Vec2& g, const Vec3& wl, double rho,
               int n, double size, bool wantJacobian, ExactBasis& acc) {
  const GaussTables& gt = gaussTables();
  // lambda = -i beta / omega, beta = w'3 / rho; the ICR zeta = 1 / lambda
  const double omSq = wl.x() * wl.x() + wl.y() * wl.y();
  const double beta = wl.z() / rho;
  const Cx lambda{-beta * wl.y() / omSq, -beta * wl.x() / omSq};
  const bool finite = beta != 0.0;
  const Vec2 zeta = finite ? Vec2(-wl.y() / beta, wl.x() / beta) : Vec2::Zero();
  FarGreenSums sums;
  auto node = [&](Cx z, Cx W) {
    if (wantJacobian)
      addFarGreenNode<true>(z, W, lambda, sums);
    else
      addFarGreenNode<false>(z, W, lambda, sums);
  };
  for (const BoundaryPiece& piece : pieces) {
    const BoundaryPiece p = shifted(piece, g);
    if (p.kind == BoundaryPiece::Kind::Segment) {
      const Vec2 d = p.b - p.a;
      const Cx dz2i{0.5 * d.y(), -0.5 * d.x()};  // (b - a) / (2i)
      for (int i = 0; i < n; ++i) {
        const Vec2 x = p.a + gt.x[n][i] * d;
        node(Cx{x.x(), x.y()}, gt.w[n][i] * dz2i);
      }
      continue;
    }
    const Cx zetaO{zeta.x() - p.centre.x(), zeta.y() - p.centre.y()};
    const double span = p.angle1 - p.angle0;
    constexpr int kMaxParts = 64;
    std::array<int, kMaxParts> orders{};
    std::array<double, kMaxParts> cms{}, sms{};
    int parts = 1;
    for (;; ++parts) {
      const double H = 0.5 * span / parts;
      bool fits = true;
      for (int q = 0; q < parts && fits; ++q) {
        const double tm = p.angle0 + (2 * q + 1) * H;
        cms[q] = std::cos(tm), sms[q] = std::sin(tm);
        orders[q] = arcSpanOrder(H, cms[q], sms[q], zetaO, finite, p.radius, size, wantJacobian,
                                 kQuadratureTol);
        fits = orders[q] <= kGaussMaxOrder;
      }
      if (fits) break;
      if (parts == kMaxParts) {  // not reached for ICRs beyond kFarRatio
        orders.fill(kGaussMaxOrder);
        break;
      }
    }
    const double H = 0.5 * span / parts;
    for (int q = 0; q < parts; ++q) {
      const int nt = orders[q];
      const double cm = cms[q], sm = sms[q];
      // t = tm + delta, z = o + r e^(it), dz/(2i) = (r H w / 2) e^(it) per node (weights on [0, 1])
      for (int i = 0; i < (nt + 1) / 2; ++i) {
        const double delta = (2.0 * gt.x[nt][i] - 1.0) * H;
        const double cd = std::cos(delta), sd = std::sin(delta);
        const double wr = gt.w[nt][i] * p.radius * H;
        for (int side = 0; side < (2 * i + 1 == nt ? 1 : 2); ++side) {
          const double s = side == 0 ? sd : -sd;
          const double ct = cm * cd - sm * s, st = sm * cd + cm * s;
          node(Cx{p.centre.x() + p.radius * ct, p.centre.y() + p.radius * st},
               Cx{wr * ct, wr * st});
        }
      }
    }
  }
  farGreenBasis(sums, wl, rho, wantJacobian, acc);
}

// Far branch on a region with a flat arc (radius above kFlatRadius region
// sizes): an area rule, since Green's theorem on a thin region (a cap of
// half-angle h: boundary terms of size^2 for an area of ~size^2 h / 1.5)
// cancels to eps / h, and an arc's points about its centre carry ~eps R,
// eps / h^2 of the cap's height. The chord polygon (the pieces' start
// points) in fan triangles from the first, as the polygon's far branch
// (exact_polygon.cpp: bilinear map, order n both ways); each arc's circular
// segment in rays from its chord's midpoint (arcChord):
//   P(th, s) = mid + s R' ((cos th - cos h) n + sin th e),  th in [-h, h], s in [0, 1],
//   dA = s R'^2 (1 - cos h cos th) ds dth,
// with cos th - cos h = 2 sin((h - th)/2) sin((h + th)/2) and 1 - cos h cos th
// = 2 sin^2(th/2) + 2 cos th sin^2(h/2) (no cancellation). Order n in s
// (the integrand's polynomial part has the fan's degree there: 3, 4 with
// dF); in th, where P is quadratic in th / h (the bulge), that part has
// twice the degree (6, 8), so n + 2 (farOrder's 0.5 degree grows by 1.5,
// 2), or the arc's trigonometric order if larger (arcSpanOrder without the
// ICR), in the fewest equal parts that fit the tables (n alone in th: 1e-10
// of F on a cap of h = 1.7e-4). Guarded by FlatCapsMatchChordQuadrature.
template <bool kJacobian>
void farAreaRule(const std::vector<BoundaryPiece>& pieces, const Vec2& g, const Vec3& wl,
                 double rho, int n, double size, ExactBasis& acc) {
  const GaussTables& gt = gaussTables();
  const double inv = 1.0 / rho;
  auto add = [&](const Vec2& P, double wt) {
    addKernelNode<kJacobian, 3>(P, Vec3(wt, wt * P.x(), wt * P.y()), wl, inv, acc.F, acc.dF.data());
  };
  const std::size_t N = pieces.size();
  const Vec2 p0 = pieces[0].start() - g;
  for (std::size_t k = 1; k + 1 < N; ++k) {
    // triangle (p0, p1, p2): the quadrilateral (p0, p1, p2, p0)
    const Vec2 p1 = pieces[k].start() - g, p2 = pieces[k + 1].start() - g;
    const Vec2 e01 = p1 - p0, e32 = p2 - p0;
    for (int i = 0; i < n; ++i) {
      const double s = gt.x[n][i];
      const Vec2 a = (1.0 - s) * p0 + s * p1, b = (1.0 - s) * p0 + s * p2;
      const Vec2 dPdt = b - a;
      for (int j = 0; j < n; ++j) {
        const double t = gt.x[n][j];
        const Vec2 dPds = (1.0 - t) * e01 + t * e32;
        const double det = dPds.x() * dPdt.y() - dPds.y() * dPdt.x();
        add(a + t * dPdt, gt.w[n][i] * gt.w[n][j] * det);
      }
    }
  }
  for (const BoundaryPiece& p : pieces) {
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    const ArcChord ch = arcChord(p);
    if (!(ch.radius > 0.0)) continue;
    const double h = ch.half, Rp = ch.radius;
    const Vec2 mid = ch.mid - g;
    const double sh2 = std::sin(0.5 * h);
    int parts = 1, nt = n;
    for (;; ++parts) {
      const double H = h / parts;
      nt = std::max(n + 2,
                    arcSpanOrder(H, 1.0, 0.0, Cx{}, false, Rp, size, kJacobian, kQuadratureTol));
      if (nt <= kGaussMaxOrder || parts == 64) break;
    }
    nt = std::min(nt, kGaussMaxOrder);
    const double H = h / parts;
    for (int q = 0; q < parts; ++q) {
      for (int i = 0; i < nt; ++i) {
        const double th = -h + (2.0 * q + 2.0 * gt.x[nt][i]) * H;
        const double sth = std::sin(th), cth = std::cos(th), st2 = std::sin(0.5 * th);
        const double bulge = 2.0 * std::sin(0.5 * (h - th)) * std::sin(0.5 * (h + th));
        const double jac = Rp * Rp * 2.0 * (st2 * st2 + cth * sh2 * sh2);
        const Vec2 Q = Rp * (bulge * ch.n + sth * ch.e);
        const double wth = 2.0 * H * gt.w[nt][i] * jac;
        for (int j = 0; j < n; ++j) {
          const double sr = gt.x[n][j];
          add(mid + sr * Q, wth * gt.w[n][j] * sr);
        }
      }
    }
  }
}

// Order of the far rule on segments: exact_area_rule.hpp's farOrder at
// kQuadratureTol (its model, a polynomial of degree 3 (4 with dF) times a
// function analytic up to the ICR, fits the boundary integrand as it fitted
// the area rule's radial direction), at least 3.
int arcFarOrder(double kappaSq, bool jacobian) {
  return std::max(3, farOrder(kappaSq, kQuadratureTol, jacobian));
}

}  // namespace

namespace {

void regionBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                 bool wantJacobian, ExactBasis& out, bool mayDecompose);

// A thin region (area below kThinRatio size^2): both branches sum boundary
// terms of ~size^2 for a result of ~area (the near branch's moments, the far
// one's Green's theorem) and lose eps size^2 / area (the pi fuzz target's
// 1.04 m x 1e-9 m sliver with a 1e-9 rad arc, pure spin about O on its
// edge: |∫x (x/r)| = 1.5 ∫x). It is evaluated as its chord polygon (the
// pieces' start points; the polygon law, whose near branch takes slivers
// and whose far branch is an area rule) plus each arc's circular segment
// (the arc closed by its chord, on its own). Guarded by
// ThinRegionsMatchPolygonLaw.
constexpr double kThinRatio = 1e-3;

void decomposedBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                     bool wantJacobian, ExactBasis& out, bool withPolygon) {
  out = ExactBasis{};
  if (withPolygon) {
    std::vector<Vec2> chord;
    for (const BoundaryPiece& p : boundary) chord.push_back(p.start());
    try {
      exactPolygonBasis(chord, rho, w, wantJacobian, out);
    } catch (const Error&) {
      // its area, positive about g here, not about the vertex mean (rounding)
      out = ExactBasis{};
    }
  }
  for (const BoundaryPiece& p : boundary) {
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    const std::vector<BoundaryPiece> cap = {p, BoundaryPiece::segment(p.end(), p.start())};
    ExactBasis part;
    regionBasis(cap, rho, w, wantJacobian, part, false);
    out.F += part.F;
    if (wantJacobian)
      for (int k = 0; k < 3; ++k) out.dF[k] += part.dF[k];
  }
}

void regionBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                 bool wantJacobian, ExactBasis& out, bool mayDecompose) {
  const std::size_t N = boundary.size();
  if (N < 1) fail("need at least 1 boundary piece");
  if (!(rho > 0.0) || !std::isfinite(rho)) fail("rho must be finite and > 0");
  if (!w.allFinite() || w.cwiseAbs().maxCoeff() == 0.0) fail("w must be finite and nonzero");
  // the pieces' end points, once each (an arc's cost a cosine and a sine)
  constexpr std::size_t kStackPieces = 16;
  std::array<Vec2, 2 * kStackPieces> stackEnds;
  std::vector<Vec2> heapEnds;
  Vec2* ends = stackEnds.data();  // start, end of piece i at 2i, 2i + 1
  if (N > kStackPieces) {
    heapEnds.resize(2 * N);
    ends = heapEnds.data();
  }
  // frame centre g: mean of the pieces' start points and arc mid points;
  // size: a bound of |P - g| over the region
  Vec2 g = Vec2::Zero();
  int count = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const BoundaryPiece& p = boundary[i];
    if (p.kind == BoundaryPiece::Kind::Arc) {
      if (!(p.radius > 0.0) || !(p.angle1 > p.angle0) || !(p.angle1 - p.angle0 <= 2.0 * M_PI))
        fail("an arc needs radius > 0 and 0 < angle1 - angle0 <= 2 pi");
      const double tm = 0.5 * (p.angle0 + p.angle1);
      g += p.centre + p.radius * Vec2(std::cos(tm), std::sin(tm));
      ++count;
    }
    ends[2 * i] = p.start();
    ends[2 * i + 1] = p.end();
    g += ends[2 * i];
    ++count;
  }
  g /= count;
  if (!g.allFinite()) fail("pieces must be finite");
  // size = max |P - g| on the boundary: a piece's ends, or an arc's point
  // farthest from g (direction g -> centre) when the arc contains it
  double size = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    const BoundaryPiece& p = boundary[i];
    size = std::max({size, (ends[2 * i] - g).norm(), (ends[2 * i + 1] - g).norm()});
    if (p.kind == BoundaryPiece::Kind::Arc) {
      const Vec2 away = p.centre - g;
      const double t = std::atan2(away.y(), away.x());
      const double k = std::floor((t - p.angle0) / (2.0 * M_PI));
      if (t - 2.0 * M_PI * k <= p.angle1) size = std::max(size, away.norm() + p.radius);
    }
  }
  for (std::size_t i = 0; i < N; ++i) {
    if ((ends[2 * i + 1] - ends[2 * ((i + 1) % N)]).norm() > kClosureRel * size)
      fail("piece " + std::to_string(i) + " does not end where the next starts");
  }

  if (mayDecompose && N >= 3) {
    // area: the chord polygon (g-frame) and the circular segments
    double twiceChord = 0.0, segments = 0.0;
    for (std::size_t i = 0; i < N; ++i)
      twiceChord += cross(Vec2(ends[2 * i] - g), Vec2(ends[2 * ((i + 1) % N)] - g));
    for (const BoundaryPiece& p : boundary) {
      if (p.kind != BoundaryPiece::Kind::Arc) continue;
      const ArcChord ch = arcChord(p);
      segments += ch.radius * ch.radius * circularSegmentMoments(ch.half).area;
    }
    if (0.5 * twiceChord + segments < kThinRatio * size * size) {
      // (a chord polygon of no positive area, rounding, is left out)
      decomposedBasis(boundary, rho, w, wantJacobian, out, twiceChord > 0.0);
      return;
    }
  }

  // g's frame (exact_area_rule.hpp), kappa in units of size
  const RegionFrame frame(g, rho, w);
  ExactBasis l;  // g-frame
  if (frame.far(kFarRatio, size * size)) {
    bool flat = false;
    for (const BoundaryPiece& p : boundary)
      flat = flat || (p.kind == BoundaryPiece::Kind::Arc && p.radius > kFlatRadius * size);
    if (flat) {
      const int n = farOrder(frame.kappaSq(size * size), kQuadratureTol, wantJacobian);
      if (wantJacobian)
        farAreaRule<true>(boundary, g, frame.wl, rho, n, size, l);
      else
        farAreaRule<false>(boundary, g, frame.wl, rho, n, size, l);
    } else {
      const int n = arcFarOrder(frame.kappaSq(size * size), wantJacobian);
      farBranch(boundary, g, frame.wl, rho, n, size, wantJacobian, l);
    }
  } else {
    nearBranch(boundary, g, frame.wl, rho, size, wantJacobian, l);
  }
  basisAtO(l.F, l.dF, g, frame, wantJacobian, out);
}

}  // namespace

void exactArcRegionBasis(const std::vector<BoundaryPiece>& boundary, double rho, const Vec3& w,
                         bool wantJacobian, ExactBasis& out) {
  regionBasis(boundary, rho, w, wantJacobian, out, true);
}

}  // namespace patchspin::internal
