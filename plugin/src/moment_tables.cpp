// The moment tables of Eq. (36) of polygons and disks (PatchShape::finish;
// arc regions: patch_shape_arc_region.cpp).
//
// The moment table is computed here by its own method (closed-form edge
// integrals for polygons, a fixed Gauss rule over triangles about the vertex
// mean for the rows with r of a polygon far from O, adaptive quadrature in
// polar coordinates about O for disks), independently of the exact model's
// code; the tests compare the two (pure spin about O, Eq. (39)).
#include "moment_tables.hpp"

#include "planar.hpp"
#include "polygon_edge_moments.hpp"
#include "quadrature.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace patchspin::internal {

namespace {

// The rows with r of a table from the eight integrals
// (r, r x, r y, x/r, x^2/r, xy/r, y/r, y^2/r); xy/r fills two entries.
void setRRows(const Eigen::Matrix<double, 8, 1>& sum, MomentTable& table) {
  auto& m = table.m;
  m(MomentTable::kR, 0) = sum[0];
  m(MomentTable::kR, 1) = sum[1];
  m(MomentTable::kR, 2) = sum[2];
  m(MomentTable::kXOverR, 0) = sum[3];
  m(MomentTable::kXOverR, 1) = sum[4];
  m(MomentTable::kXOverR, 2) = sum[5];
  m(MomentTable::kYOverR, 0) = sum[6];
  m(MomentTable::kYOverR, 1) = sum[5];
  m(MomentTable::kYOverR, 2) = sum[7];
}

// asinh(u) - asinh(v) without cancellation when u and v share a sign:
//   asinh(u) - asinh(v) = asinh((u - v)(u + v) / (u sqrt(1+v^2) + v sqrt(1+u^2)))  (u, v > 0)
double asinhDifference(double u, double v) {
  if (u > 0.0 && v > 0.0) {
    const double den = u * std::sqrt(1.0 + v * v) + v * std::sqrt(1.0 + u * u);
    return std::asinh((u - v) * (u + v) / den);
  }
  if (u < 0.0 && v < 0.0) return -asinhDifference(-u, -v);
  return std::asinh(u) - std::asinh(v);
}

// (tau r - d^2 asinh(tau / d)) / 2 between tau = ta and tb for an edge far
// from O, |tau| <= d / 100: there the closed form cancels to (tau/d)^2 eps.
// With u = tau / d it is d^2 (h(ub) - h(ua)) / 2, h(u) = u sqrt(1 + u^2) -
// asinh(u) = 2/3 u^3 - 1/5 u^5 + 3/28 u^7 - 5/72 u^9 + 35/704 u^11 - ...
// (truncation < 1e-17 relative at |u| = 0.01), each power difference
// factored as (ub - ua) (ub^(k-1) + ... + ua^(k-1)) with ub - ua = L / d.
double farEdgeJm2(double ua, double ub, double L, double d) {
  constexpr double kCoefficients[5] = {2.0 / 3.0, -1.0 / 5.0, 3.0 / 28.0, -5.0 / 72.0,
                                       35.0 / 704.0};
  // sums[k] = ub^k + ub^(k-1) ua + ... + ua^k by sums[k] = ub sums[k-1] + ua^k
  double sum = 1.0, uaPower = 1.0, total = 0.0;
  for (int k = 1; k <= 10; ++k) {
    uaPower *= ua;
    sum = ub * sum + uaPower;
    if (k % 2 == 0) total += kCoefficients[k / 2 - 1] * sum;
  }
  return 0.5 * d * d * (L / d) * total;
}

// Moment table of a convex polygon about O (the origin).
//
// Signed triangles (O, a, b) over the edges. For g homogeneous of degree k,
//   ∫_tri g dA = cross(a, b) / (k + 2) ∫_0^1 g(a + t (b - a)) dt.
// Along the edge e(tau) = F + tau t^ (F the foot point of O, d = |F|,
// r = sqrt(tau^2 + d^2), dt = dtau / L) the needed 1-D integrals are
//   Jm0 = ∫ 1/r = asinh(tau/d)      Jm1 = ∫ tau/r = r
//   Jm2 = ∫ tau^2/r = (tau r - d^2 asinh(tau/d)) / 2
//   J10 = ∫ r = (tau r + d^2 asinh(tau/d)) / 2      J11 = ∫ tau r = r^3 / 3.
// The polynomial rows (1, x, y times 1, x, y: A, the first and the second
// area moments) of a convex polygon by the exact triangle formulas over the
// edges, (O, a, b) signed. The products reach |a| |b|, so about a far O
// they round to ~eps max|r|^2 / A of the area (found by fuzzing: Pz 1.1e-7
// off on a 23-gon 900 diameters from O, 1.45e-4 on a sliver 9.6e9 m from
// O, so the exact unit law in pure translation had a force of 1 + that).
// With `aboutVertexMean` they are summed about the vertex mean g instead,
// the frame and the very vertices P - g in which exact_polygon.cpp
// integrates the law, and shifted to O by the parallel-axis relations
// (each term rounded once, no cancellation: A g_x^2 + 2 g_x Sx' + Ixx', ...).
// There `localInverse` gets G'^-1, the inverse of Eq. (94)'s load matrix
// about g, and `g` the vertex mean (PatchShape::solveLoadMatrix).
void addPolygonPolynomialRows(const std::vector<Vec2>& v, bool aboutVertexMean, MomentTable& table,
                              Mat3& localInverse, Vec2& g) {
  auto& m = table.m;
  const std::size_t n = v.size();
  g = Vec2::Zero();
  if (aboutVertexMean) {
    // (summed and divided as exact_polygon.cpp does: the same bits of g)
    for (const Vec2& p : v) g += p;
    g /= static_cast<double>(n);
  }
  internal::PolygonMomentSums sum;
  for (std::size_t i = 0; i < n; ++i) sum.addEdge(v[i] - g, v[(i + 1) % n] - g);
  double area = sum.area, sx = sum.sx, sy = sum.sy, ixx = sum.ixx, ixy = sum.ixy, iyy = sum.iyy;
  if (aboutVertexMean) {
    const double gx = g.x(), gy = g.y();
    Mat3 local;
    local << area, sx, sy,  //
        sx, ixx, ixy,       //
        sy, ixy, iyy;
    localInverse = local.inverse();
    ixx = (area * gx * gx + 2.0 * gx * sx) + ixx;
    iyy = (area * gy * gy + 2.0 * gy * sy) + iyy;
    ixy = (area * gx * gy + (gx * sy + gy * sx)) + ixy;
    sx = area * gx + sx;
    sy = area * gy + sy;
  }
  m(MomentTable::kOne, 0) = area;
  m(MomentTable::kOne, 1) = m(MomentTable::kX, 0) = sx;
  m(MomentTable::kOne, 2) = m(MomentTable::kY, 0) = sy;
  m(MomentTable::kX, 1) = ixx;
  m(MomentTable::kX, 2) = m(MomentTable::kY, 1) = ixy;
  m(MomentTable::kY, 2) = iyy;
}

// The rows with r (r, x/r, y/r times 1, x, y) of a convex polygon with O far
// outside it, by a fixed Gauss rule over the triangles (g, a, b) fanned out
// from the vertex mean g (inside the polygon: every triangle positive). On a
// triangle, P = g + s ((1 - t) (a - g) + t (b - g)), s, t in [0, 1],
// dA = cross(a - g, b - g) s ds dt, with 8-point Gauss-Legendre in s and t
// (exact for degree 15 in t and 14 in s): with O at least 3 diameters away,
// the integrands are analytic over the triangle with their singularities
// (r = 0, complex) 3 diameters off, and the rule reaches round-off (measured
// above). Every point is formed as g + its local offset and every integrand
// is evaluated there, so nothing cancels: each entry is a sum of positive
// weights times its integrand, to ~eps of the integral of |f phi| (and of a
// sliver's area, rounded ~eps diameter^2 / A by the vertex differences, as
// the polynomial rows are).
void farPolygonRRows(const std::vector<Vec2>& v, const Vec2& g, MomentTable& table) {
  struct Rule {
    double node[8];
    double weight[8];
  };
  static const Rule rule = [] {
    const internal::GaussRule gl = internal::gaussLegendre(8);
    Rule r{};
    for (int i = 0; i < 8; ++i) {
      r.node[i] = 0.5 * (1.0 + gl.nodes[i]);  // on [0, 1]
      r.weight[i] = 0.5 * gl.weights[i];
    }
    return r;
  }();
  using V8 = Eigen::Matrix<double, 8, 1>;
  // r, r x, r y, x/r, x^2/r, xy/r, y/r, y^2/r
  V8 sum = V8::Zero();
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = v[i] - g;
    const Vec2 b = v[(i + 1) % n] - g;
    const double twiceArea = cross(a, b);
    V8 triangle = V8::Zero();
    for (int k = 0; k < 8; ++k) {
      const double t = rule.node[k];
      const Vec2 w = (1.0 - t) * a + t * b;
      for (int j = 0; j < 8; ++j) {
        const double s = rule.node[j];
        const double x = g.x() + s * w.x(), y = g.y() + s * w.y();
        const double r = std::sqrt(x * x + y * y);
        const double xr = x / r, yr = y / r;
        const double weight = rule.weight[j] * rule.weight[k] * s;
        V8 f;
        f << r, r * x, r * y, xr, xr * x, xr * y, yr, yr * y;
        triangle += weight * f;
      }
    }
    sum += twiceArea * triangle;
  }
  setRRows(sum, table);
}

}  // namespace

MomentTable polygonMomentTable(const std::vector<Vec2>& v, bool aboutVertexMean, bool farRows,
                               Mat3& localInverse, Vec2& g) {
  MomentTable table;
  auto& m = table.m;
  addPolygonPolynomialRows(v, aboutVertexMean, table, localInverse, g);
  if (farRows) {
    // (far implies aboutVertexMean: g is the vertex mean)
    farPolygonRRows(v, g, table);
    return table;
  }
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    const double c = cross(a, b);
    if (c == 0.0) continue;  // O on the edge line: zero-area triangle

    // rows with r: closed-form edge integrals
    const Vec2 e = b - a;
    const double L = e.norm();
    const Vec2 t = e / L;
    const double ta = a.dot(t), tb = b.dot(t);
    const Vec2 F = a - ta * t;
    const double d = std::abs(c) / L;
    const double ra = std::hypot(ta, d), rb = std::hypot(tb, d);
    const double jm0 = asinhDifference(tb / d, ta / d);
    // differences of r in factored form: rb - ra = (tb^2 - ta^2) / (rb + ra)
    // with tb - ta = L. Subtracted directly, an edge far from O (d >> L)
    // kept none of its digits (found by fuzzing: on a 1.8e9 m sliver the
    // 1 m end edges gave rb - ra = 1e-8 +- 1e-7, and ∫xy/r was 4x off)
    const double jm1 = L * (ta + tb) / (ra + rb);
    const double trDiff = L * rb + ta * jm1;  // tb rb - ta ra
    constexpr double kFarEdge = 0.01;         // |tau| / d below which jm2 takes the series
    const double jm2 = std::max(std::abs(ta), std::abs(tb)) <= kFarEdge * d
                           ? farEdgeJm2(ta / d, tb / d, L, d)
                           : 0.5 * (trDiff - d * d * jm0);
    const double j10 = 0.5 * (trDiff + d * d * jm0);
    const double j11 = jm1 * (rb * rb + ra * rb + ra * ra) / 3.0;
    const double s0 = c / (2.0 * L);  // degree 0: cross / (0 + 2), and 1/L from dt
    const double s1 = c / (3.0 * L);  // degree 1
    const double s2 = c / (4.0 * L);  // degree 2
    const double fx = F.x(), fy = F.y(), tx = t.x(), ty = t.y();
    // r * {1, x, y}
    m(MomentTable::kR, 0) += s1 * j10;
    m(MomentTable::kR, 1) += s2 * (fx * j10 + tx * j11);
    m(MomentTable::kR, 2) += s2 * (fy * j10 + ty * j11);
    // x/r * {1, x, y}, y/r * {1, x, y}
    const double xOverR = fx * jm0 + tx * jm1;
    const double yOverR = fy * jm0 + ty * jm1;
    const double xxOverR = fx * fx * jm0 + 2.0 * fx * tx * jm1 + tx * tx * jm2;
    const double yyOverR = fy * fy * jm0 + 2.0 * fy * ty * jm1 + ty * ty * jm2;
    const double xyOverR = fx * fy * jm0 + (fx * ty + fy * tx) * jm1 + tx * ty * jm2;
    m(MomentTable::kXOverR, 0) += s0 * xOverR;
    m(MomentTable::kXOverR, 1) += s1 * xxOverR;
    m(MomentTable::kXOverR, 2) += s1 * xyOverR;
    m(MomentTable::kYOverR, 0) += s0 * yOverR;
    m(MomentTable::kYOverR, 1) += s1 * xyOverR;
    m(MomentTable::kYOverR, 2) += s1 * yyOverR;
  }
  return table;
}

// The closed-form rows of a disk's table: 1, x and y times (1, x, y).
MomentTable diskPolynomialMoments(const Vec2& centre, double R) {
  MomentTable table;
  auto& m = table.m;
  const double A = kPi * R * R;
  const double cx = centre.x(), cy = centre.y();
  m(MomentTable::kOne, 0) = A;
  m(MomentTable::kOne, 1) = m(MomentTable::kX, 0) = A * cx;
  m(MomentTable::kOne, 2) = m(MomentTable::kY, 0) = A * cy;
  m(MomentTable::kX, 1) = A * (cx * cx + R * R / 4.0);
  m(MomentTable::kX, 2) = m(MomentTable::kY, 1) = A * cx * cy;
  m(MomentTable::kY, 2) = A * (cy * cy + R * R / 4.0);
  return table;
}

// Moment table of a disk (centre C, radius R) about O, in polar coordinates
// (s, alpha) about O. For an integrand s^k T(alpha) the radial integral is
//   ∫_{s1}^{s2} s^k s ds = (s2^{k+2} - s1^{k+2}) / (k + 2),
// with the ray/circle intersections s = delta cos(phi) +- sqrt(R^2 - delta^2 sin^2 phi),
// phi = alpha - beta, (delta, beta) the polar coordinates of C.
MomentTable diskMomentTable(const Vec2& centre, double R) {
  MomentTable table = diskPolynomialMoments(centre, R);
  const double cx = centre.x(), cy = centre.y();

  const double delta = centre.norm();
  const double beta = std::atan2(cy, cx);
  using V8 = Eigen::Matrix<double, 8, 1>;
  // entries: r, r x, r y, x/r, x^2/r, xy/r, y/r, y^2/r (with their s-powers)
  // ds = s2 - s1 is passed in exact form: far from O, s1 and s2 are both ~delta
  // and s2^n - s1^n would lose delta / R digits (noise the adaptive rule could
  // never converge below); factored, no cancellation:
  //   s2^n - s1^n = ds (s2^(n-1) + ... + s1^(n-1))
  // (ca, sa) = (cos, sin) of the ray's polar angle alpha about O
  auto angular = [&](double ca, double sa, double s1, double s2, double ds) {
    const double s22 = s2 * s2, s12 = s1 * s1;
    const double d2 = ds * (s2 + s1) / 2.0;                // k = 0
    const double d3 = ds * (s22 + s1 * s2 + s12) / 3.0;    // k = 1
    const double d4 = ds * (s2 + s1) * (s22 + s12) / 4.0;  // k = 2
    V8 out;
    out << d3, d4 * ca, d4 * sa, d2 * ca, d3 * ca * ca, d3 * ca * sa, d2 * sa, d3 * sa * sa;
    return out;
  };
  constexpr double kRelTol = 1e-15;
  V8 sum = V8::Zero();
  // the ray's direction from (beta, phi) by the addition theorem, not
  // cos(beta + phi): far from O, phi is small and cos(beta + phi) may be
  // near zero, where rounding beta + phi would leave only ~eps / phi digits
  const double cb = std::cos(beta), sb = std::sin(beta);
  if (delta < R) {
    // O inside: s from 0 to delta cos(phi) + S(phi), phi over the full turn.
    // S is smallest (near-singular as delta -> R) at phi = +-pi/2, so the turn
    // is cut into four quarters measured from there, phi = s1 pi/2 + s2 t,
    // t in [0, pi/2]: nodes near the cut keep full relative precision in t
    // (in phi, their rounding, eps |phi| |f'|, is noise the adaptive rule can
    // never converge below). With sin phi = s1 cos t, cos phi = -s1 s2 sin t,
    //   S^2 = (R - delta cos t)(R + delta cos t),
    //   R - delta cos t = (R - delta) + 2 delta sin^2(t/2)   (no cancellation)
    // and behind O (cos phi < 0) s2 = (R^2 - delta^2) / (S - delta cos phi).
    for (const double s1 : {-1.0, 1.0}) {
      for (const double s2 : {-1.0, 1.0}) {
        auto f = [&](double t) {
          const double ct = std::cos(t), st = std::sin(t), ht = std::sin(0.5 * t);
          const double sphi = s1 * ct, cphi = -s1 * s2 * st;
          const double S =
              std::sqrt(std::max(0.0, ((R - delta) + 2.0 * delta * ht * ht) * (R + delta * ct)));
          const double outer =
              cphi >= 0.0 ? delta * cphi + S : (R - delta) * (R + delta) / (S - delta * cphi);
          // alpha = beta + phi
          return angular(cb * cphi - sb * sphi, sb * cphi + cb * sphi, 0.0, outer, outer);
        };
        sum += internal::adaptiveGauss<8>(f, 0.0, kPi / 2.0, kRelTol);
      }
    }
  } else {
    // O on or outside the rim: sin(phi) = k sin(psi), k = R / delta, removes
    // the square-root end singularities; dphi = k cos(psi) / cos(phi) dpsi.
    const double k = R / delta;
    auto f = [&](double psi) {
      const double sphi = k * std::sin(psi);
      const double cphi = std::sqrt(std::max(0.0, 1.0 - sphi * sphi));
      const double S = R * std::cos(psi);
      const double jac = cphi > 0.0 ? k * std::cos(psi) / cphi : 1.0;
      return V8(jac * angular(cb * cphi - sb * sphi, sb * cphi + cb * sphi, delta * cphi - S,
                              delta * cphi + S, 2.0 * S));
    };
    sum += internal::adaptiveGauss<8>(f, -kPi / 2.0, 0.0, kRelTol);
    sum += internal::adaptiveGauss<8>(f, 0.0, kPi / 2.0, kRelTol);
  }
  setRRows(sum, table);
  return table;
}

}  // namespace patchspin::internal
