// Brute-force oracle of the exact model on convex polygons, Eq. (16), with
// the linear pressure basis (1, x, y): nested adaptive Gauss-Kronrod in
// Cartesian coordinates (no polar sums about the ICR), independent of
// exact_polygon.cpp; with the test polygons and slip directions that cover
// the sphere's special places. Used by exact_polygon_basis_test and
// exact_polygon_law_test.
#pragma once

#include <patchspin/internal/exact.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace patchspin::testing::exact_polygon {

using Polygon = std::vector<Vec2>;
using Vec9 = Eigen::Matrix<double, 9, 1>;

// The contract: relative error <= 1e-10 everywhere on the sphere of w.
// Errors are normwise per column: |F.col(k) - oracle.col(k)|_inf / scale_k,
// scale_k = area * max|phi_k| * (1 + max|P| / rho), an upper bound of every
// entry of F.col(k) (|v/|v|| = 1 and |P x v/|v|| <= |P|). The oracle is run to
// kOracleTol (1e-12 per entry, as |K15 - G7|, which overestimates the K15
// error by orders of magnitude), the implementation is expected near 1e-13 (rounding of
// the edge sum grows like kappa^3 eps up to the branch switch at kappa = 8,
// measured <= 3e-13), so the 1e-10 contract is checked with a wide margin.
constexpr double kContractTol = 1e-10;
constexpr double kOracleTol = 1e-12;

// ---- oracle ----

// Unit friction kernel of Eq. (1), (16) as defined in exact.hpp; 0 where v = 0:
//   v = (w1 - w3 y / rho, w2 + w3 x / rho) = (w3 / rho) (-(y - cy), x - cx).
// The second form (used when w3 != 0) avoids the cancellation of the first
// near the ICR, which would make the kernel noisy there (relative noise
// eps |w| / |v|) and stall the adaptive quadrature.
inline Vec3 kernel(const Vec3& w, double rho, double x, double y) {
  double vx, vy;
  if (w.z() != 0.0) {
    const double cx = -rho * w.y() / w.z(), cy = rho * w.x() / w.z();
    vx = -(w.z() / rho) * (y - cy);
    vy = (w.z() / rho) * (x - cx);
  } else {
    vx = w.x();
    vy = w.y();
  }
  const double n = std::hypot(vx, vy);
  if (n == 0.0) return Vec3::Zero();
  return Vec3(vx / n, vy / n, (x * vy - y * vx) / (rho * n));
}

// G7-K15 on [a, b] for a 9-vector integrand; err = |K15 - G7| per entry.
template <class F>
Vec9 gaussKronrod15(F& f, double a, double b, Vec9& err) {
  using boost::math::quadrature::gauss;
  using boost::math::quadrature::gauss_kronrod;
  const auto& xk = gauss_kronrod<double, 15>::abscissa();
  const auto& wk = gauss_kronrod<double, 15>::weights();
  const auto& wg = gauss<double, 7>::weights();
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  Vec9 f0 = f(mid);
  Vec9 kron = wk[0] * f0, gs = wg[0] * f0;
  for (std::size_t i = 1; i < xk.size(); ++i) {
    const Vec9 pair = f(mid - half * xk[i]) + f(mid + half * xk[i]);
    kron += wk[i] * pair;
    // the 7 Gauss nodes are the Kronrod nodes of even index (0, 2, 4, 6)
    if (i % 2 == 0) gs += wg[i / 2] * pair;
  }
  err = half * (kron - gs).cwiseAbs();
  return half * kron;
}

// Number of oracle integrals that stopped at kMaxPanels before meeting their
// tolerance; the oracle tests require 0.
inline int gOracleCapped = 0;

// Globally adaptive G7-K15 over [a, b], split first at the breakpoints
// inside (a, b): bisect the panel with the largest error estimate until the
// summed |K15 - G7| is <= tol in every entry (kMaxPanels bounds the work;
// the kernel's jump lies on panel ends, so refinement is only needed at the
// log-type endpoint singularities, a few panels per binary digit).
template <class F>
Vec9 integrateSplit(F& f, double a, double b, std::vector<double> breaks, const Vec9& tol) {
  constexpr std::size_t kMaxPanels = 4000;
  struct Panel {
    double a, b, score;
    Vec9 value, err;
  };
  std::vector<Panel> panels;
  auto makePanel = [&](double lo, double hi) {
    Panel p{lo, hi, 0.0, Vec9::Zero(), Vec9::Zero()};
    p.value = gaussKronrod15(f, lo, hi, p.err);
    p.score = (p.err.array() / tol.array()).maxCoeff();
    return p;
  };
  auto byScore = [](const Panel& x, const Panel& y) { return x.score < y.score; };
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    if (hi > lo) panels.push_back(makePanel(lo, hi));
  }
  std::make_heap(panels.begin(), panels.end(), byScore);
  while (!panels.empty()) {
    Vec9 total = Vec9::Zero();
    for (const Panel& p : panels) total += p.err;
    if ((total.array() <= tol.array()).all()) break;
    if (panels.size() >= kMaxPanels) {
      ++gOracleCapped;
      break;
    }
    std::pop_heap(panels.begin(), panels.end(), byScore);
    const Panel worst = panels.back();
    panels.pop_back();
    const double m = 0.5 * (worst.a + worst.b);
    if (!(m > worst.a && m < worst.b)) {  // cannot split further: keep it
      panels.push_back(worst);
      panels.back().score = 0.0;
      std::push_heap(panels.begin(), panels.end(), byScore);
      continue;
    }
    for (const Panel& half : {makePanel(worst.a, m), makePanel(m, worst.b)}) {
      panels.push_back(half);
      std::push_heap(panels.begin(), panels.end(), byScore);
    }
  }
  Vec9 sum = Vec9::Zero();
  for (const Panel& p : panels) sum += p.value;
  return sum;
}

// y-range of the convex polygon on the vertical line at x.
inline void chordAt(const Polygon& poly, double x, double& lo, double& hi) {
  lo = INFINITY;
  hi = -INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    if (a.x() == b.x()) continue;  // vertical edge: its neighbours give the range
    const double t = (x - a.x()) / (b.x() - a.x());
    if (t < 0.0 || t > 1.0) continue;
    const double y = a.y() + t * (b.y() - a.y());
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
}

inline double maxAbsPhi(const Polygon& poly, int k) {
  double m = 0.0;
  for (const Vec2& p : poly) m = std::max(m, k == 0 ? 1.0 : std::abs(p[k - 1]));
  return m;
}

inline double polygonArea(const Polygon& poly) {
  double a2 = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    a2 += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * a2;
}

// Column scales (see kContractTol).
inline Vec3 columnScales(const Polygon& poly, double rho) {
  double rmax = 0.0;
  for (const Vec2& p : poly) rmax = std::max(rmax, p.norm());
  Vec3 s;
  for (int k = 0; k < 3; ++k) s[k] = polygonArea(poly) * maxAbsPhi(poly, k) * (1.0 + rmax / rho);
  return s;
}

// F by brute force over the region between the chords chordAt(x, lo, hi),
// x in [xmin, xmax]: x outer, split at xbreaks and the ICR's x; y inner,
// split at the ICR's y, so that the kernel's only discontinuity (the ICR)
// lies on panel boundaries. Per-entry tolerance kOracleTol * scale_k; the
// inner integrals get 1e-2 of it per unit length so that their error is
// smooth noise far below the outer panels' tolerance.
template <class ChordAt>
Mat3 oracleFBetweenChords(const ChordAt& chordAt, double xmin, double xmax,
                          std::vector<double> xbreaks, const Vec3& scale, double rho,
                          const Vec3& w) {
  const bool hasIcr = w.z() != 0.0;
  const double cx = hasIcr ? -rho * w.y() / w.z() : 0.0, cy = hasIcr ? rho * w.x() / w.z() : 0.0;
  if (hasIcr) xbreaks.push_back(cx);
  Vec9 tol;
  for (int k = 0; k < 3; ++k) tol.segment<3>(3 * k).setConstant(kOracleTol * scale[k]);
  const Vec9 innerTol = 1e-2 * tol / (xmax - xmin);
  auto inner = [&](double x) -> Vec9 {
    double lo, hi;
    chordAt(x, lo, hi);
    if (!(hi > lo)) return Vec9::Zero();
    auto fy = [&](double y) -> Vec9 {
      const Vec3 k = kernel(w, rho, x, y);
      Vec9 out;
      out << k, x * k, y * k;
      return out;
    };
    std::vector<double> ybreaks;
    if (hasIcr) ybreaks.push_back(cy);
    return integrateSplit(fy, lo, hi, ybreaks, innerTol);
  };
  const Vec9 v = integrateSplit(inner, xmin, xmax, xbreaks, tol);
  Mat3 F;
  F.col(0) = v.segment<3>(0);
  F.col(1) = v.segment<3>(3);
  F.col(2) = v.segment<3>(6);
  return F;
}

// F by brute force on a convex polygon, x split at its vertices.
inline Mat3 oracleF(const Polygon& poly, double rho, const Vec3& w) {
  double xmin = INFINITY, xmax = -INFINITY;
  std::vector<double> xbreaks;
  for (const Vec2& p : poly) {
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    xbreaks.push_back(p.x());
  }
  return oracleFBetweenChords([&](double x, double& lo, double& hi) { chordAt(poly, x, lo, hi); },
                              xmin, xmax, std::move(xbreaks), columnScales(poly, rho), rho, w);
}

// max over columns of the normwise relative error
inline double relativeError(const Mat3& F, const Mat3& ref, const Vec3& scale) {
  double e = 0.0;
  for (int k = 0; k < 3; ++k)
    e = std::max(e, (F.col(k) - ref.col(k)).cwiseAbs().maxCoeff() / scale[k]);
  return e;
}

// w whose ICR c = rho (-w2, w1) / w3 is the given point, spin sign s.
inline Vec3 wForIcr(const Vec2& c, double rho, double s) {
  return Vec3(s * c.y(), -s * c.x(), s * rho).normalized();
}

// ---- shapes ----

inline Polygon translated(Polygon p, const Vec2& t) {
  for (Vec2& v : p) v += t;
  return p;
}
inline Polygon unitSquare() {
  return {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
}
inline Polygon rectangle() {
  return {{-1.0, -0.25}, {1.0, -0.25}, {1.0, 0.25}, {-1.0, 0.25}};
}
inline Polygon triangle() {
  return {{0.1, -0.3}, {1.1, 0.0}, {0.3, 0.8}};
}
inline Polygon irregularPentagon() {
  return {{-0.6, -0.4}, {0.3, -0.55}, {0.8, 0.1}, {0.35, 0.6}, {-0.5, 0.45}};
}
inline Polygon regularOctagon() {
  Polygon p;
  for (int i = 0; i < 8; ++i) {
    const double a = 2.0 * M_PI * i / 8.0 + 0.2;
    p.emplace_back(0.1 + 0.6 * std::cos(a), -0.05 + 0.6 * std::sin(a));
  }
  return p;
}

struct NamedPolygon {
  std::string name;
  Polygon poly;
  double rho;
};

inline std::vector<NamedPolygon> testPolygons() {
  return {
      {"square, O at centre", unitSquare(), 0.38},
      {"rectangle 2x0.5, O at centre", rectangle(), 0.5},
      {"triangle, O outside", triangle(), 0.6},
      {"irregular pentagon, O inside", irregularPentagon(), 0.4},
      {"octagon, O inside off-centre", regularOctagon(), 0.3},
      {"square, O far outside", translated(unitSquare(), Vec2(2.5, -1.5)), 0.4},
      {"square, O at a vertex", translated(unitSquare(), Vec2(0.5, 0.5)), 0.5},
      {"rectangle, O on an edge", translated(rectangle(), Vec2(0.3, 0.25)), 0.6},
      {"pentagon, O 50 sizes away", translated(irregularPentagon(), Vec2(40.0, -25.0)), 0.45},
  };
}

// Slip directions covering the sphere's special places for a polygon.
inline std::vector<std::pair<std::string, Vec3>> testDirections(const Polygon& poly, double rho) {
  std::vector<std::pair<std::string, Vec3>> ws;
  ws.push_back({"pure spin +", Vec3(0, 0, 1)});
  ws.push_back({"pure spin -", Vec3(0, 0, -1)});
  ws.push_back({"translation x", Vec3(1, 0, 0)});
  ws.push_back({"translation oblique", Vec3(-0.6, 0.8, 0)});
  const Vec2 dir = Vec2(0.8, -0.6);
  for (double w3 : {1e-3, 1e-6, 1e-9, -1e-9}) {
    const double s = std::sqrt(1.0 - w3 * w3);
    ws.push_back({"w3 = " + std::to_string(w3), Vec3(s * dir.x(), s * dir.y(), w3)});
  }
  const Vec2& a = poly[0];
  const Vec2& b = poly[1];
  const Vec2 mid = 0.5 * (a + b);
  const Vec2 e = (b - a).normalized();
  const Vec2 n(-e.y(), e.x());  // inward normal of edge 0
  const double L = (b - a).norm();
  ws.push_back({"ICR at vertex", wForIcr(a, rho, 1.0)});
  ws.push_back({"ICR at vertex, spin -", wForIcr(poly[2], rho, -1.0)});
  ws.push_back({"ICR on edge", wForIcr(mid, rho, 1.0)});
  ws.push_back({"ICR on edge line outside", wForIcr(b + 0.3 * L * e, rho, 1.0)});
  ws.push_back({"ICR just inside edge", wForIcr(mid + 1e-9 * L * n, rho, 1.0)});
  ws.push_back({"ICR just outside edge", wForIcr(mid - 1e-9 * L * n, rho, -1.0)});
  ws.push_back({"ICR just off vertex", wForIcr(a + 1e-8 * L * Vec2(0.6, -0.8), rho, 1.0)});
  Vec2 centroid = Vec2::Zero();
  for (const Vec2& p : poly) centroid += p;
  centroid /= static_cast<double>(poly.size());
  ws.push_back({"ICR at vertex mean", wForIcr(centroid, rho, 1.0)});
  ws.push_back({"ICR at 3 L outside", wForIcr(mid - 3.0 * L * n, rho, 1.0)});
  ws.push_back({"ICR at 30 L outside", wForIcr(mid - 30.0 * L * n, rho, -1.0)});
  std::mt19937 rng(12345);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 3; ++i) {
    Vec3 w(normal(rng), normal(rng), normal(rng));
    ws.push_back({"random " + std::to_string(i), w.normalized()});
  }
  return ws;
}

}  // namespace patchspin::testing::exact_polygon
