// Patch shapes, area moments, rho (11) and the moment table of Eq. (36).
// (Arc regions: their polynomial rows by Green's theorem, arc_regions.cpp;
// their rows with r from the exact law at pure spin about O, Eq. (39):
// k = (-y/r, x/r, r/rho), so F = ∫ phi (-y/r, x/r, r/rho) dA; checked
// against brute-force quadrature in arc_regions_test.cpp.)
//
// The moment table is computed here by its own method (closed-form edge
// integrals for polygons, a fixed Gauss rule over triangles about the vertex
// mean for the rows with r of a polygon far from O, adaptive quadrature in
// polar coordinates about O for disks), independently of the exact model's
// code; the tests compare the two (pure spin about O, Eq. (39)).
#include <patchspin/geometry.hpp>

#include "arc_region_numerics.hpp"
#include "polygon_edge_moments.hpp"
#include "quadrature.hpp"

#include <patchspin/internal/exact.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace patchspin {

using internal::formatDouble;

namespace {

constexpr double kPi = 3.14159265358979323846;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

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

// Largest distance between two of the points: over the pairs i < j, as
// squared norms with one square root at the end (the same value as the
// largest (u - v).norm() over all ordered pairs: sqrt is monotonic, and
// |u - v| and |v - u| round alike), a quarter of the square roots' cost;
// a 64-gon patch (a clipped coin) has 2016 pairs.
double largestDistance(const std::vector<Vec2>& v) {
  double best2 = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      best2 = std::max(best2, (v[j] - v[i]).squaredNorm());
  return std::sqrt(best2);
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

// Beyond this many diameters from O (max|r| > kFarRowsOffset diameter, so
// every patch point is at least 3 diameters from O) a polygon's rows with r
// come from quadrature over triangles fanned out from its vertex mean
// (farPolygonRRows): the closed-form edge integrals below sum triangles
// (O, a, b) about O, whose terms reach ~max|r|^2 L each and cancel to the
// patch's, so they lose ~eps offset^2 to eps offset^3 of the rows' scale
// (offset = max|r| / diameter; the second round's open item and the tenth
// round's far sliver, fuzz/README.md item 65). Measured against the same
// closed form in 50 digits, on 200 polygons per offset (3-10 vertices, aspect
// 1 to 1e-8), in units of eps A max|f| max|phi| max(1, diameter^2 / A):
// closed form 3 to 15 at 3-4 diameters, 770 at 16, 4e4 at 100, 1.5e8 at
// 3560; the fan's 8 x 8 rule at most 4.1 from 3 diameters on (below 1.0
// with its nodes in long double; 4.6 on the second round's far heptagon;
// at 2 diameters its 8-point rule has not converged: 1.5e4). Patches about a point inside them
// (the Bullet layer's, about their centroid: max|r| <= diameter) never get
// here: one comparison.
constexpr double kFarRowsOffset = 4.0;

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

}  // namespace

Mat3 AreaMoments::loadMatrix() const {
  Mat3 G;
  G << area, first.x(), first.y(),  //
      first.x(), xx, xy,            //
      first.y(), xy, yy;
  return G;
}

PatchShape PatchShape::disk(double radius, const Vec2& centre) {
  internal::requirePositive(radius, "disk radius R");
  internal::requireFinite(centre, "disk centre");
  PatchShape shape;
  shape.kind_ = Kind::Disk;
  shape.radius_ = radius;
  shape.centre_ = centre;
  shape.finish();
  return shape;
}

PatchShape PatchShape::polygon(std::vector<Vec2> vertices) {
  if (vertices.size() < 3) {
    throw Error("polygon needs at least 3 vertices: got " + std::to_string(vertices.size()));
  }
  double scale = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    // (the name is built only for the message: a shape rebuild in the
    // Bullet layer passes here for every vertex of every patch)
    if (!vertices[i].allFinite())
      internal::requireFinite(vertices[i], ("polygon vertex " + std::to_string(i)).c_str());
    scale = std::max(scale, vertices[i].cwiseAbs().maxCoeff());
  }
  // repeated vertices
  const double kSameVertex = 1e-12 * std::max(scale, 1e-300);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::size_t j = (i + 1) % vertices.size();
    if ((vertices[i] - vertices[j]).norm() <= kSameVertex) {
      throw Error("polygon has repeated vertex " + std::to_string(j) + " (same as vertex " +
                  std::to_string(i) + ")");
    }
  }
  // signed area (clockwise / zero area)
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    twiceArea += cross(vertices[i], vertices[(i + 1) % vertices.size()]);
  const double diameter = largestDistance(vertices);
  // relative zero-area threshold: area below 1e-12 of the diameter squared
  if (std::abs(twiceArea) <= 2e-12 * diameter * diameter) {
    throw Error("polygon has zero area (degenerate or collinear vertices)");
  }
  if (twiceArea < 0.0) {
    throw Error("polygon vertices are clockwise: give them counter-clockwise");
  }
  // drop collinear vertices, then require strictly left turns (convexity)
  const double kCollinear = 1e-12;
  std::vector<Vec2> kept;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = vertices[(i + n - 1) % n];
    const Vec2& cur = vertices[i];
    const Vec2& next = vertices[(i + 1) % n];
    const Vec2 e1 = cur - prev, e2 = next - cur;
    const double turn = cross(e1, e2) / (e1.norm() * e2.norm());
    if (std::abs(turn) <= kCollinear && e1.dot(e2) > 0.0) continue;  // collinear, straight on
    if (turn <= kCollinear) {
      throw Error("polygon is not convex (turns right or folds back at vertex " +
                  std::to_string(i) + ")");
    }
    kept.push_back(cur);
  }
  // all left turns: the total turning must be one full turn (rules out stars)
  double turning = 0.0;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Vec2 e1 = kept[i] - kept[(i + kept.size() - 1) % kept.size()];
    const Vec2 e2 = kept[(i + 1) % kept.size()] - kept[i];
    turning += std::atan2(cross(e1, e2), e1.dot(e2));
  }
  if (kept.size() < 3 || std::abs(turning - 2.0 * kPi) > 1e-6) {
    throw Error("polygon is not convex (self-intersecting, total turning " +
                formatDouble(turning / (2.0 * kPi)) + " turns)");
  }
  PatchShape shape;
  shape.kind_ = Kind::Polygon;
  shape.vertices_ = std::move(kept);
  shape.finish();
  return shape;
}

PatchShape PatchShape::rectangle(double lx, double ly, const Vec2& centre, double angle) {
  internal::requirePositive(lx, "rectangle side LX");
  internal::requirePositive(ly, "rectangle side LY");
  internal::requireFinite(centre, "rectangle centre");
  internal::requireFinite(angle, "rectangle angle");
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> v;
  const double hx = lx / 2.0, hy = ly / 2.0;
  for (const Vec2& corner : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}) {
    v.emplace_back(centre.x() + c * corner.x() - s * corner.y(),
                   centre.y() + s * corner.x() + c * corner.y());
  }
  return polygon(std::move(v));
}

PatchShape PatchShape::regularPolygon(int n, double circumradius, const Vec2& centre,
                                      double angle) {
  if (n < 3) throw Error("regular polygon needs n >= 3: got " + std::to_string(n));
  internal::requirePositive(circumradius, "regular polygon circumradius");
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    const double a = angle + 2.0 * kPi * i / n;
    v.emplace_back(centre.x() + circumradius * std::cos(a),
                   centre.y() + circumradius * std::sin(a));
  }
  return polygon(std::move(v));
}

PatchShape PatchShape::arcRegion(std::vector<BoundaryPiece> boundary) {
  using Piece = BoundaryPiece;
  if (boundary.empty()) throw Error("arc region has no boundary pieces");
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const Piece& p = boundary[i];
    const std::string name = "arc region piece " + std::to_string(i);
    if (p.kind == Piece::Kind::Segment) {
      if (!p.a.allFinite() || !p.b.allFinite())
        throw Error(name + ": segment end points must be finite");
    } else {
      if (!p.centre.allFinite() || !std::isfinite(p.radius) || !std::isfinite(p.angle0) ||
          !std::isfinite(p.angle1))
        throw Error(name + ": arc centre, radius and angles must be finite");
      if (!(p.radius > 0.0)) throw Error(name + ": arc radius must be > 0");
      if (!(p.angle1 > p.angle0))
        throw Error(name + ": arc angles must increase (counter-clockwise, angle1 > angle0)");
      if (p.angle1 - p.angle0 > 2.0 * kPi * (1.0 + 1e-12))
        throw Error(name + ": arc spans more than a full turn");
    }
  }
  // the region's size: extent of the pieces' points about the first start
  const Vec2 s0 = boundary[0].start();
  double size = 0.0;
  for (const Piece& p : boundary) {
    size = std::max(size, (p.start() - s0).norm());
    if (p.kind == Piece::Kind::Arc)
      size = std::max(size, std::min(2.0, p.angle1 - p.angle0) * p.radius);
  }
  // pieces shorter than 1e-12 of it (rounding) are dropped
  const double kShortPiece = 1e-12 * size;
  auto length = [](const Piece& p) {
    return p.kind == Piece::Kind::Segment ? (p.b - p.a).norm() : p.radius * (p.angle1 - p.angle0);
  };
  std::vector<Piece> kept;
  for (const Piece& p : boundary)
    if (length(p) > kShortPiece) kept.push_back(p);
  if (kept.empty()) throw Error("arc region has zero area (every piece has zero length)");
  // a single full arc is a disk
  if (kept.size() == 1) {
    const Piece& p = kept[0];
    if (p.kind == Piece::Kind::Arc && p.angle1 - p.angle0 >= 2.0 * kPi * (1.0 - 1e-12))
      return disk(p.radius, p.centre);
    throw Error("arc region is not closed: a single piece that is not a full circle");
  }
  // closed: each piece ends where the next starts (to 1e-9 of the size)
  const std::size_t n = kept.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double gap = (kept[i].end() - kept[(i + 1) % n].start()).norm();
    if (!(gap <= 1e-9 * size)) {
      throw Error("arc region is not closed: piece " + std::to_string(i) + " ends " +
                  formatDouble(gap) + " m from where piece " + std::to_string((i + 1) % n) +
                  " starts");
    }
  }
  // segments join their neighbouring arcs' end points exactly
  for (std::size_t i = 0; i < n; ++i) {
    Piece& p = kept[i];
    if (p.kind != Piece::Kind::Segment) continue;
    const Piece& prev = kept[(i + n - 1) % n];
    const Piece& next = kept[(i + 1) % n];
    if (prev.kind == Piece::Kind::Arc) p.a = prev.end();
    if (next.kind == Piece::Kind::Arc) p.b = next.start();
  }
  bool anyArc = false;
  for (const Piece& p : kept) anyArc = anyArc || p.kind == Piece::Kind::Arc;
  if (!anyArc) {
    std::vector<Vec2> v;
    for (const Piece& p : kept) v.push_back(p.a);
    return polygon(std::move(v));
  }
  // orientation and area
  const AreaMoments m = internal::areaMomentsAbout(kept, internal::startPointMean(kept));
  if (std::abs(m.area) <= 1e-12 * size * size)
    throw Error("arc region has zero area (degenerate pieces)");
  if (m.area < 0.0) throw Error("arc region is clockwise: give its pieces counter-clockwise");
  // convexity: turning >= 0 at every joint, arcs bulge outward (they turn
  // left by their span), and one full turn in all
  auto tangentIn = [](const Piece& p) -> Vec2 {
    if (p.kind == Piece::Kind::Segment) return (p.b - p.a).normalized();
    return Vec2(-std::sin(p.angle0), std::cos(p.angle0));
  };
  auto tangentOut = [](const Piece& p) -> Vec2 {
    if (p.kind == Piece::Kind::Segment) return (p.b - p.a).normalized();
    return Vec2(-std::sin(p.angle1), std::cos(p.angle1));
  };
  constexpr double kTurnSlack = 1e-9;
  double turning = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 t1 = tangentOut(kept[i]), t2 = tangentIn(kept[(i + 1) % n]);
    const double turn = std::atan2(cross(t1, t2), t1.dot(t2));
    if (turn < -kTurnSlack || turn > kPi - kTurnSlack) {
      throw Error("arc region is not convex (turns right or folds back where piece " +
                  std::to_string((i + 1) % n) + " starts)");
    }
    turning += turn;
    if (kept[i].kind == Piece::Kind::Arc) turning += kept[i].angle1 - kept[i].angle0;
  }
  if (std::abs(turning - 2.0 * kPi) > 1e-6) {
    throw Error("arc region is not convex (self-intersecting, total turning " +
                formatDouble(turning / (2.0 * kPi)) + " turns)");
  }
  PatchShape shape;
  shape.kind_ = Kind::ArcRegion;
  shape.boundary_ = std::move(kept);
  shape.finish();
  return shape;
}

void PatchShape::throwNotA(const char* what) {
  throw Error(what);
}

const std::vector<Vec2>& PatchShape::vertices() const {
  if (kind_ != Kind::Polygon) throw Error("vertices() asked of a patch that is not a polygon");
  return vertices_;
}

const std::vector<BoundaryPiece>& PatchShape::boundary() const {
  if (kind_ != Kind::ArcRegion)
    throw Error("boundary() asked of a patch that is not an arc region");
  return boundary_;
}

void PatchShape::finish() {
  // extent first: refuse what cannot be represented before any integral
  if (kind_ == Kind::Disk) {
    max_distance_ = centre_.norm() + radius_;
    diameter_ = 2.0 * radius_;
  } else if (kind_ == Kind::ArcRegion) {
    max_distance_ = internal::arcRegionMaxDistance(boundary_);
    diameter_ = internal::arcRegionDiameter(boundary_);
  } else {
    max_distance_ = 0.0;
    for (const Vec2& v : vertices_) max_distance_ = std::max(max_distance_, v.norm());
    diameter_ = largestDistance(vertices_);
  }
  // a linear pressure about O, p0 + cx x + cy y, loses (distance / size)^2
  // digits to cancellation on the patch (Eq. (94) has that condition): far
  // beyond kMaxOffset diameters nothing is left of Pi (found by fuzzing)
  constexpr double kMaxOffset = 1e4;
  if (!(max_distance_ <= kMaxOffset * diameter_)) {
    throw Error("patch too small for its distance from O: diameter " + formatDouble(diameter_) +
                " m, farthest point " + formatDouble(max_distance_) +
                " m from O (at most 1e4 diameters); put O near the patch");
  }
  // the moments reach |r|^5 and the inverse 1/|r|^4: sizes beyond ~1e60 m
  // or below ~1e-75 m over- or underflow double
  // (`complete` false: only the closed-form rows, no 1/r moments, no rho)
  auto takeTable = [&](const MomentTable& table, bool complete) {
    table_ = table;
    const auto& m = table_.m;
    moments_.area = m(MomentTable::kOne, 0);
    moments_.first = Vec2(m(MomentTable::kOne, 1), m(MomentTable::kOne, 2));
    moments_.xx = m(MomentTable::kX, 1);
    moments_.xy = m(MomentTable::kX, 2);
    moments_.yy = m(MomentTable::kY, 2);
    // G is SPD for any patch of positive area (Gram matrix of 1, x, y)
    if (loads_about_mean_) {
      // G^-1 = U^T G'^-1 U with U = [[1, 0, 0], [-g_x, 1, 0], [-g_y, 0, 1]]
      // (G = U^-1 G' U^-T), as a matrix for loadMatrixInverse(); solves go
      // through solveLoadMatrix, which applies the factors
      Mat3 U = Mat3::Identity();
      U(1, 0) = -load_origin_.x();
      U(2, 0) = -load_origin_.y();
      load_inverse_ = U.transpose() * local_load_inverse_ * U;
    } else {
      load_inverse_ = moments_.loadMatrix().inverse();
    }
    if (!table_.m.allFinite() || !(moments_.area > 0.0) || !load_inverse_.allFinite() ||
        !local_load_inverse_.allFinite() || !std::isfinite(max_distance_) ||
        !std::isfinite(diameter_) || !(!complete || defaultRho() > 0.0)) {
      throw Error("patch size out of range: its area moments over- or underflow double (diameter " +
                  formatDouble(diameter_) + " m, farthest point " + formatDouble(max_distance_) +
                  " m from O)");
    }
  };
  if (kind_ == Kind::Disk) {
    // the closed-form rows first: a disk out of range is refused before the
    // quadrature, which on its underflowing integrand would spend its whole
    // split budget first (0.25 s per refused R = 1e-105 disk; fuzz finding)
    takeTable(diskPolynomialMoments(centre_, radius_), false);
    takeTable(diskMomentTable(centre_, radius_), true);
  } else if (kind_ == Kind::ArcRegion) {
    // the polynomial rows about the start points' mean g where O lies
    // outside the patch (as for polygons), shifted to O
    loads_about_mean_ = max_distance_ > diameter_;
    load_origin_ = internal::startPointMean(boundary_);
    const AreaMoments local = internal::areaMomentsAbout(boundary_, load_origin_);
    if (loads_about_mean_) local_load_inverse_ = local.loadMatrix().inverse();
    const AreaMoments about = areaMomentsOf(boundary_);
    MomentTable table;
    auto& m = table.m;
    m(MomentTable::kOne, 0) = about.area;
    m(MomentTable::kOne, 1) = m(MomentTable::kX, 0) = about.first.x();
    m(MomentTable::kOne, 2) = m(MomentTable::kY, 0) = about.first.y();
    m(MomentTable::kX, 1) = about.xx;
    m(MomentTable::kX, 2) = m(MomentTable::kY, 1) = about.xy;
    m(MomentTable::kY, 2) = about.yy;
    takeTable(table, false);
    // rows with r: the exact law at pure spin about O (file comment)
    const double rho = diameter_;
    internal::ExactBasis basis;
    internal::exactArcRegionBasis(boundary_, rho, Vec3(0.0, 0.0, 1.0), false, basis);
    for (int k = 0; k < 3; ++k) {
      m(MomentTable::kXOverR, k) = basis.F(1, k);
      m(MomentTable::kYOverR, k) = -basis.F(0, k);
      m(MomentTable::kR, k) = rho * basis.F(2, k);
    }
    takeTable(table, true);
  } else {
    // the polynomial rows about the vertex mean where O lies outside the
    // patch (max|r| > diameter); about O itself they round to ~eps max|r|^2
    // / A <= eps diameter^2 / A there, a sliver's own round-off, and a patch
    // expressed about a point inside it (Bullet's: its centroid) keeps the
    // sums it always had
    loads_about_mean_ = max_distance_ > diameter_;
    // and the rows with r by quadrature about it where O is far (item 65)
    const bool farRows = max_distance_ > kFarRowsOffset * diameter_;
    const MomentTable table = polygonMomentTable(vertices_, loads_about_mean_, farRows,
                                                 local_load_inverse_, load_origin_);
    takeTable(table, true);
  }
}

Vec3 PatchShape::solveLoadMatrix(const Vec3& rhs) const {
  if (!loads_about_mean_) return load_inverse_ * rhs;
  // rhs about g (the moments of p shifted: ∫x' p = ∫x p - g_x Pz), G'^-1,
  // then p0 = p0' - g_x cx - g_y cy: the coefficients about O stay
  // consistent with each other, where G^-1 rhs as one matrix product
  // rounds them independently, each by eps (max|r| / size)^2 of the
  // pressure on the patch
  // (at unit scale, a power of two: g_x Pz and G'^-1 rhs' overflowed for
  // loads ~1e300 whose pressure is in range; found by fuzzing)
  const double largest = rhs.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return load_inverse_ * rhs;  // zero (or not finite)
  const int e = std::ilogb(largest);
  const Vec3 unit = rhs.unaryExpr([e](double x) { return std::ldexp(x, -e); });
  const Vec2& g = load_origin_;
  const Vec3 local =
      local_load_inverse_ * Vec3(unit[0], unit[1] - g.x() * unit[0], unit[2] - g.y() * unit[0]);
  const Vec3 c(local[0] - (g.x() * local[1] + g.y() * local[2]), local[1], local[2]);
  return c.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

bool PatchShape::contains(const Vec2& point, double tol) const {
  if (kind_ == Kind::Disk) return (point - centre_).norm() <= radius_ + tol;
  if (kind_ == Kind::ArcRegion) return internal::arcRegionContains(boundary_, point, tol);
  // edge by edge (no modulo, and an edge's length only where the point is
  // on its outer side: the Bullet layer tests every visit's centre of
  // pressure, nearly always inside)
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0, prev = n - 1; i < n; prev = i++) {
    const Vec2 e = vertices_[i] - vertices_[prev];
    const double c = cross(e, point - vertices_[prev]);
    if (c < 0.0 && c < -tol * e.norm()) return false;
  }
  return true;
}

PatchShape PatchShape::inFrame(const Vec2& newOrigin, double angle) const {
  internal::requireFinite(newOrigin, "new origin");
  internal::requireFinite(angle, "frame angle");
  const double c = std::cos(angle), s = std::sin(angle);
  auto map = [&](const Vec2& p) {
    const Vec2 q = p - newOrigin;
    return Vec2(c * q.x() + s * q.y(), -s * q.x() + c * q.y());
  };
  if (kind_ == Kind::Disk) return disk(radius_, map(centre_));
  if (kind_ == Kind::ArcRegion) {
    std::vector<BoundaryPiece> mapped = boundary_;
    for (BoundaryPiece& p : mapped) {
      p.a = map(p.a), p.b = map(p.b), p.centre = map(p.centre);
      p.angle0 -= angle, p.angle1 -= angle;
    }
    return arcRegion(std::move(mapped));
  }
  std::vector<Vec2> v;
  for (const Vec2& p : vertices_) v.push_back(map(p));
  return polygon(std::move(v));
}

std::string PatchShape::describe() const {
  std::ostringstream out;
  if (kind_ == Kind::Disk) {
    out << "disk R=" << radius_ << " m centred at (" << centre_.x() << ", " << centre_.y() << ")";
  } else if (kind_ == Kind::ArcRegion) {
    std::size_t arcs = 0;
    for (const BoundaryPiece& p : boundary_) arcs += p.kind == BoundaryPiece::Kind::Arc ? 1 : 0;
    out << "region of " << boundary_.size() << " pieces (" << arcs << " arcs)";
  } else {
    out << vertices_.size() << "-gon";
  }
  out << ", area " << moments_.area << " m^2, rho(11) " << defaultRho() << " m";
  return out.str();
}

}  // namespace patchspin
