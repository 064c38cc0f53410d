// Brute-force quadrature oracles, see oracle.hpp.
#include "oracle.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

namespace patchspin::testing {
namespace {

template <int N>
using VecN = Eigen::Matrix<double, N, 1>;

constexpr double kPi = 3.14159265358979323846;
// Panel budget per adaptive integral. A kink or jump of the integrand on a
// panel boundary needs ~20-40 bisections to reach 1e-13; smooth pieces need a
// handful. The cap only guards against a runaway (reported as `capped`).
constexpr int kMaxPanels = 3000;
// A panel whose |K15 - G7| is at round-off level of its own |f| integral
// cannot improve by splitting: 64 ulps of the panel's L1 mass.
constexpr double kRoundOffPanel = 64.0 * std::numeric_limits<double>::epsilon();
// Grid for the rough size of ∫ |g| dA, and the share of relTol granted to
// all inner integrals together (see integratePolygon).
constexpr int kGrid = 16;
constexpr double kInnerShare = 1e-3;

// Gauss-Kronrod G7-K15 nodes from Boost.Math (abscissae >= 0, 0 first). The
// Gauss nodes are the Kronrod nodes with even index; checked once.
struct GkNodes {
  std::array<double, 8> x{};
  std::array<double, 8> wk{};
  std::array<double, 4> wg{};
};

const GkNodes& gkNodes() {
  static const GkNodes nodes = [] {
    GkNodes n;
    const auto& kx = boost::math::quadrature::gauss_kronrod<double, 15>::abscissa();
    const auto& kw = boost::math::quadrature::gauss_kronrod<double, 15>::weights();
    const auto& gx = boost::math::quadrature::gauss<double, 7>::abscissa();
    const auto& gw = boost::math::quadrature::gauss<double, 7>::weights();
    if (kx.size() != 8 || gx.size() != 4) throw std::logic_error("unexpected G7-K15 layout");
    for (int i = 0; i < 8; ++i) {
      n.x[i] = kx[i];
      n.wk[i] = kw[i];
    }
    for (int j = 0; j < 4; ++j) {
      if (std::abs(gx[j] - kx[2 * j]) > 1e-15) throw std::logic_error("G7 nodes not in K15");
      n.wg[j] = gw[j];
    }
    return n;
  }();
  return nodes;
}

template <int N>
struct Panel {
  double a = 0.0;
  double b = 0.0;
  VecN<N> value = VecN<N>::Zero();
  double err = 0.0;  // |K15 - G7| (max norm), 0 once at round-off level
  double l1 = 0.0;   // K15 estimate of ∫ |f|_max over the panel
  bool operator<(const Panel& other) const { return err < other.err; }
};

template <int N, class F>
Panel<N> evaluatePanel(const F& f, double a, double b, long& evaluations) {
  const GkNodes& n = gkNodes();
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  const VecN<N> f0 = f(mid);
  VecN<N> kron = n.wk[0] * f0;
  VecN<N> gauss = n.wg[0] * f0;
  double l1 = n.wk[0] * f0.cwiseAbs().maxCoeff();
  for (int i = 1; i < 8; ++i) {
    const VecN<N> fl = f(mid - half * n.x[i]);
    const VecN<N> fr = f(mid + half * n.x[i]);
    kron += n.wk[i] * (fl + fr);
    if (i % 2 == 0) gauss += n.wg[i / 2] * (fl + fr);
    l1 += n.wk[i] * (fl.cwiseAbs().maxCoeff() + fr.cwiseAbs().maxCoeff());
  }
  evaluations += 15;
  Panel<N> p;
  p.a = a;
  p.b = b;
  p.value = half * kron;
  p.l1 = std::abs(half) * l1;
  p.err = (half * (kron - gauss)).cwiseAbs().maxCoeff();
  if (p.err <= kRoundOffPanel * p.l1) p.err = 0.0;
  return p;
}

// Globally adaptive G7-K15 (QUADPACK QAG style) of a vector function over the
// union of [breaks[i], breaks[i+1]]: always bisect the panel with the largest
// error estimate until  sum err <= max(relTol * sum l1, absTol).
template <int N, class F>
VecN<N> integrateAdaptive(const F& f, const std::vector<double>& breaks, double relTol,
                          double absTol, QuadratureReport* report) {
  long evaluations = 0;
  std::priority_queue<Panel<N>> heap;
  VecN<N> done = VecN<N>::Zero();
  double sumErr = 0.0;
  double sumL1 = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    if (!(breaks[i + 1] > breaks[i])) continue;
    Panel<N> p = evaluatePanel<N>(f, breaks[i], breaks[i + 1], evaluations);
    sumErr += p.err;
    sumL1 += p.l1;
    heap.push(p);
  }
  bool capped = false;
  int panels = static_cast<int>(heap.size());
  while (!heap.empty() && sumErr > std::max(relTol * sumL1, absTol)) {
    if (panels >= kMaxPanels) {
      capped = true;
      break;
    }
    Panel<N> worst = heap.top();
    heap.pop();
    const double mid = 0.5 * (worst.a + worst.b);
    if (!(mid > worst.a && mid < worst.b)) {  // cannot split further
      done += worst.value;
      sumErr -= worst.err;
      sumL1 -= worst.l1;
      capped = true;
      continue;
    }
    Panel<N> left = evaluatePanel<N>(f, worst.a, mid, evaluations);
    Panel<N> right = evaluatePanel<N>(f, mid, worst.b, evaluations);
    sumErr += left.err + right.err - worst.err;
    sumL1 += left.l1 + right.l1 - worst.l1;
    heap.push(left);
    heap.push(right);
    ++panels;
    // the running sums lose digits by cancellation: recompute now and then
    if (panels % 256 == 0) {
      auto copy = heap;
      sumErr = 0.0;
      sumL1 = 0.0;
      while (!copy.empty()) {
        sumErr += copy.top().err;
        sumL1 += copy.top().l1;
        copy.pop();
      }
    }
  }
  VecN<N> total = done;
  double errTotal = 0.0;
  while (!heap.empty()) {
    total += heap.top().value;
    errTotal += heap.top().err;
    heap.pop();
  }
  if (report != nullptr) {
    report->evaluations += evaluations;
    report->errorEstimate = std::max(report->errorEstimate, errTotal);
    report->capped = report->capped || capped;
  }
  return total;
}

// y-range of the convex polygon on the vertical line at x (interior x only).
void polygonChains(const std::vector<Vec2>& v, double x, double& ylo, double& yhi) {
  ylo = std::numeric_limits<double>::infinity();
  yhi = -std::numeric_limits<double>::infinity();
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = v[i];
    const Vec2& q = v[(i + 1) % n];
    const double lo = std::min(p.x(), q.x());
    const double hi = std::max(p.x(), q.x());
    if (!(hi > lo) || x < lo || x > hi) continue;  // vertical edges: only at break points
    const double t = (x - p.x()) / (q.x() - p.x());
    const double y = p.y() + t * (q.y() - p.y());
    ylo = std::min(ylo, y);
    yhi = std::max(yhi, y);
  }
}

// ∫ g dA over a convex polygon, special point s on panel boundaries.
template <int N, class G>
VecN<N> integratePolygon(const std::vector<Vec2>& v, const G& g, const Vec2* special, double relTol,
                         QuadratureReport* report) {
  if (v.size() < 3) throw std::invalid_argument("oracle: polygon needs 3 vertices");
  std::vector<double> xs;
  for (const Vec2& p : v) xs.push_back(p.x());
  std::sort(xs.begin(), xs.end());
  if (special != nullptr && special->x() > xs.front() && special->x() < xs.back()) {
    xs.push_back(special->x());
    std::sort(xs.begin(), xs.end());
  }
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  const double width = xs.back() - xs.front();
  // Rough size S0 of ∫ |g| dA (midpoint rule on a kGrid^2 grid). An inner
  // integral needs no better absolute accuracy than kInnerShare relTol S0 /
  // width: its error, integrated over the outer range, stays below
  // kInnerShare relTol S0. Without this floor, inner integrals over tiny
  // ranges next to the ICR (where v = O(1) - O(1) carries round-off of
  // relative size eps / |v|) chase round-off noise until the panel cap.
  double s0 = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const double x = xs.front() + (i + 0.5) / kGrid * width;
    double ylo = 0.0;
    double yhi = 0.0;
    polygonChains(v, x, ylo, yhi);
    if (!(yhi > ylo)) continue;
    for (int j = 0; j < kGrid; ++j) {
      const double y = ylo + (j + 0.5) / kGrid * (yhi - ylo);
      s0 += g(Vec2(x, y)).cwiseAbs().maxCoeff() * (width / kGrid) * ((yhi - ylo) / kGrid);
    }
  }
  const double innerAbsTol = kInnerShare * relTol * s0 / width;
  QuadratureReport inner;
  auto outer = [&](double x) -> VecN<N> {
    double ylo = 0.0;
    double yhi = 0.0;
    polygonChains(v, x, ylo, yhi);
    if (!(yhi > ylo)) return VecN<N>::Zero();
    std::vector<double> ys{ylo, yhi};
    if (special != nullptr && special->y() > ylo && special->y() < yhi)
      ys = {ylo, special->y(), yhi};
    return integrateAdaptive<N>([&](double y) -> VecN<N> { return g(Vec2(x, y)); }, ys, relTol,
                                innerAbsTol, &inner);
  };
  VecN<N> result = integrateAdaptive<N>(outer, xs, relTol, 0.0, report);
  if (report != nullptr) {
    report->evaluations += inner.evaluations;
    report->capped = report->capped || inner.capped;
  }
  return result;
}

// ∫ g dA over a disk: P = C + R sin(t) (cos phi, sin phi), dA = R^2 sin t cos t dt dphi,
// t in [0, pi/2] (the substitution s = R sin t makes sqrt(1 - s^2/R^2) = cos t
// smooth). Angle outer from the special point's angle, t inner split at it.
template <int N, class G>
VecN<N> integrateDisk(const Vec2& centre, double radius, const G& g, const Vec2* special,
                      double relTol, QuadratureReport* report) {
  if (!(radius > 0.0)) throw std::invalid_argument("oracle: disk radius must be > 0");
  double phi0 = 0.0;
  double tSpecial = -1.0;
  if (special != nullptr) {
    const Vec2 d = *special - centre;
    const double s = d.norm();
    if (s > 0.0 && s < radius) {
      phi0 = std::atan2(d.y(), d.x());
      tSpecial = std::asin(s / radius);
    }
  }
  const double halfPi = 0.5 * kPi;
  auto integrand = [&](double t, const Vec2& dir) -> VecN<N> {
    const double st = std::sin(t);
    const double ct = std::cos(t);
    return (radius * radius * st * ct) * g(Vec2(centre + radius * st * dir));
  };
  // rough size of ∫ |g| dA and the inner absolute floor, as for polygons
  double s0 = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const double phi = phi0 + (i + 0.5) / kGrid * 2.0 * kPi;
    const Vec2 dir(std::cos(phi), std::sin(phi));
    for (int j = 0; j < kGrid; ++j)
      s0 += integrand((j + 0.5) / kGrid * halfPi, dir).cwiseAbs().maxCoeff() * (2.0 * kPi / kGrid) *
            (halfPi / kGrid);
  }
  const double innerAbsTol = kInnerShare * relTol * s0 / (2.0 * kPi);
  QuadratureReport inner;
  auto outer = [&](double phi) -> VecN<N> {
    const Vec2 dir(std::cos(phi), std::sin(phi));
    std::vector<double> ts{0.0, halfPi};
    if (tSpecial > 0.0 && tSpecial < halfPi) ts = {0.0, tSpecial, halfPi};
    return integrateAdaptive<N>([&](double t) { return integrand(t, dir); }, ts, relTol,
                                innerAbsTol, &inner);
  };
  VecN<N> result =
      integrateAdaptive<N>(outer, std::vector<double>{phi0, phi0 + 2.0 * kPi}, relTol, 0.0, report);
  if (report != nullptr) {
    report->evaluations += inner.evaluations;
    report->capped = report->capped || inner.capped;
  }
  return result;
}

}  // namespace

Vec3 frictionKernel(const Vec3& w, double rho, const Vec2& point) {
  const double x = point.x();
  const double y = point.y();
  const double vx = w.x() - w.z() * y / rho;
  const double vy = w.y() + w.z() * x / rho;
  const double speed = std::hypot(vx, vy);
  if (speed == 0.0) return Vec3::Zero();
  return Vec3(vx, vy, (x * vy - y * vx) / rho) / speed;
}

bool instantaneousCentre(const Vec3& w, double rho, Vec2& centre) {
  if (w.z() == 0.0) return false;
  centre = rho * Vec2(-w.y(), w.x()) / w.z();
  return std::isfinite(centre.x()) && std::isfinite(centre.y());
}

Vec3 bruteForceQPolygon(const std::vector<Vec2>& vertices, const ScalarField& pressure, double mu,
                        double rho, const Vec3& w, double relTol, QuadratureReport* report) {
  Vec2 c;
  const bool hasCentre = instantaneousCentre(w, rho, c);
  auto g = [&](const Vec2& p) -> Vec3 { return pressure(p) * frictionKernel(w, rho, p); };
  return -mu * integratePolygon<3>(vertices, g, hasCentre ? &c : nullptr, relTol, report);
}

Vec3 bruteForceQDisk(const Vec2& centre, double radius, const ScalarField& pressure, double mu,
                     double rho, const Vec3& w, double relTol, QuadratureReport* report) {
  Vec2 c;
  const bool hasCentre = instantaneousCentre(w, rho, c);
  auto g = [&](const Vec2& p) -> Vec3 { return pressure(p) * frictionKernel(w, rho, p); };
  return -mu * integrateDisk<3>(centre, radius, g, hasCentre ? &c : nullptr, relTol, report);
}

double bruteForceIntegralPolygon(const std::vector<Vec2>& vertices, const ScalarField& f,
                                 double relTol, QuadratureReport* report) {
  const Vec2 origin = Vec2::Zero();
  auto g = [&](const Vec2& p) -> VecN<1> { return VecN<1>(f(p)); };
  return integratePolygon<1>(vertices, g, &origin, relTol, report)(0);
}

double bruteForceIntegralDisk(const Vec2& centre, double radius, const ScalarField& f,
                              double relTol, QuadratureReport* report) {
  const Vec2 origin = Vec2::Zero();
  auto g = [&](const Vec2& p) -> VecN<1> { return VecN<1>(f(p)); };
  return integrateDisk<1>(centre, radius, g, &origin, relTol, report)(0);
}

Vec3 bruteForceQ(const PatchShape& shape, const ScalarField& pressure, double mu, double rho,
                 const Vec3& w, double relTol, QuadratureReport* report) {
  if (shape.isDisk())
    return bruteForceQDisk(shape.centre(), shape.radius(), pressure, mu, rho, w, relTol, report);
  return bruteForceQPolygon(shape.vertices(), pressure, mu, rho, w, relTol, report);
}

double bruteForceIntegral(const PatchShape& shape, const ScalarField& f, double relTol,
                          QuadratureReport* report) {
  if (shape.isDisk())
    return bruteForceIntegralDisk(shape.centre(), shape.radius(), f, relTol, report);
  return bruteForceIntegralPolygon(shape.vertices(), f, relTol, report);
}

Vec3 bruteForceLineQ(double x0, double x1, double Pz, double mu, double rho, const Vec3& w,
                     double relTol) {
  std::vector<double> xs{x0, x1};
  Vec2 c;
  if (instantaneousCentre(w, rho, c) && c.x() > x0 && c.x() < x1) xs = {x0, c.x(), x1};
  auto g = [&](double x) -> Vec3 { return frictionKernel(w, rho, Vec2(x, 0.0)); };
  return -mu * Pz / (x1 - x0) * integrateAdaptive<3>(g, xs, relTol, 0.0, nullptr);
}

AreaMoments bruteForceAreaMoments(const PatchShape& shape, double relTol) {
  AreaMoments m;
  m.area = bruteForceIntegral(
      shape, [](const Vec2&) { return 1.0; }, relTol);
  m.first.x() = bruteForceIntegral(
      shape, [](const Vec2& p) { return p.x(); }, relTol);
  m.first.y() = bruteForceIntegral(
      shape, [](const Vec2& p) { return p.y(); }, relTol);
  m.xx = bruteForceIntegral(
      shape, [](const Vec2& p) { return p.x() * p.x(); }, relTol);
  m.xy = bruteForceIntegral(
      shape, [](const Vec2& p) { return p.x() * p.y(); }, relTol);
  m.yy = bruteForceIntegral(
      shape, [](const Vec2& p) { return p.y() * p.y(); }, relTol);
  return m;
}

namespace {
// f of the moment table rows, MomentTable::Row order; 0 at O for x/r, y/r.
double tableRow(int row, const Vec2& p) {
  const double r = p.norm();
  switch (row) {
    case MomentTable::kOne:
      return 1.0;
    case MomentTable::kX:
      return p.x();
    case MomentTable::kY:
      return p.y();
    case MomentTable::kR:
      return r;
    case MomentTable::kXOverR:
      return r > 0.0 ? p.x() / r : 0.0;
    case MomentTable::kYOverR:
      return r > 0.0 ? p.y() / r : 0.0;
    default:
      return 0.0;
  }
}
double tableColumn(int col, const Vec2& p) {
  return col == 0 ? 1.0 : (col == 1 ? p.x() : p.y());
}
}  // namespace

MomentTable bruteForceMomentTable(const PatchShape& shape, double relTol) {
  MomentTable t;
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 3; ++col)
      t.m(row, col) = bruteForceIntegral(
          shape, [&](const Vec2& p) { return tableRow(row, p) * tableColumn(col, p); }, relTol);
  return t;
}

PiMoments bruteForcePiMoments(const PatchShape& shape, const ScalarField& pressure, double relTol) {
  PiMoments m;
  m.Pz = bruteForceIntegral(shape, pressure, relTol);
  auto average = [&](int row) {
    return bruteForceIntegral(
               shape, [&](const Vec2& p) { return pressure(p) * tableRow(row, p); }, relTol) /
           m.Pz;
  };
  m.pi_x = average(MomentTable::kX);
  m.pi_y = average(MomentTable::kY);
  m.pi_x0 = average(MomentTable::kXOverR);
  m.pi_y0 = average(MomentTable::kYOverR);
  m.pi_xy = average(MomentTable::kR);
  return m;
}

ScalarField linearField(const LinearPressure& pressure) {
  return
      [pressure](const Vec2& p) { return pressure.p0 + pressure.cx * p.x() + pressure.cy * p.y(); };
}

ScalarField hertzField(const Vec2& centre, double radius, double Pz) {
  return [centre, radius, Pz](const Vec2& p) {
    const double s2 = (p - centre).squaredNorm() / (radius * radius);
    return s2 >= 1.0 ? 0.0 : 3.0 * Pz / (2.0 * kPi * radius * radius) * std::sqrt(1.0 - s2);
  };
}

double rectangleMeanDistance(double a, double b) {
  constexpr int k = 400;
  double sum = 0.0;
  for (int i = 0; i < 2 * k; ++i)
    for (int j = 0; j < k; ++j)
      sum += std::hypot(((i + 0.5) / (2 * k) * 2 - 1) * a, ((j + 0.5) / k * 2 - 1) * b);
  return sum / (2.0 * k * k);
}

}  // namespace patchspin::testing
