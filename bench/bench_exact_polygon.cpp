// Benchmarks of the exact model on convex polygons, Eq. (16):
// internal::exactPolygonBasis for a 1 x 0.6 rectangle and a regular 8-gon,
// with and without the Jacobian, over a fixed seeded set of w on the unit
// sphere (uniform, so ~95 % of the calls take the closed-form edge sum and
// the rest, ICR farther than 8 circumradii, the Gauss-Legendre branch).
// Separate runs time each branch alone, and the tolerance knob on the far
// branch reports its measured error against tolerance 0 next to the time.
// BM_ExactPolygonLaw times internal::exactPolygonLaw, the one-pass integral
// of a single linear pressure that FrictionPatch uses, on the same shapes
// and directions (to compare with the basis, which integrates three).
// BM_EllipsoidalReference times the ellipsoidal law (41) on the same
// rectangle and directions, for the exact / ellipsoidal ratio.
#include <patchspin/internal/exact.hpp>
#include <patchspin/models.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

using patchspin::Mat3;
using patchspin::Vec2;
using patchspin::Vec3;
using patchspin::internal::ExactBasis;
using patchspin::internal::exactPolygonBasis;
using patchspin::internal::exactPolygonLaw;

constexpr int kDirections = 1024;

std::vector<Vec2> rectangle() {
  return {{-0.5, -0.3}, {0.5, -0.3}, {0.5, 0.3}, {-0.5, 0.3}};
}

std::vector<Vec2> octagon() {
  std::vector<Vec2> p;
  for (int i = 0; i < 8; ++i) {
    const double a = 2.0 * M_PI * (i + 0.5) / 8.0;
    p.emplace_back(0.5 * std::cos(a), 0.5 * std::sin(a));
  }
  return p;
}

// rho of Eq. (11) about O (mean distance from O), by a midpoint grid over
// the bounding box (setup only, not timed; 1e-4 accuracy is plenty here).
double meanDistance(const std::vector<Vec2>& poly) {
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const Vec2& p : poly) {
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  constexpr int kGrid = 400;
  double sum = 0.0, count = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 q(xmin + (i + 0.5) * (xmax - xmin) / kGrid,
                   ymin + (j + 0.5) * (ymax - ymin) / kGrid);
      bool inside = true;
      for (std::size_t k = 0; k < poly.size() && inside; ++k) {
        const Vec2 e = poly[(k + 1) % poly.size()] - poly[k];
        const Vec2 r = q - poly[k];
        inside = e.x() * r.y() - e.y() * r.x() >= 0.0;
      }
      if (inside) {
        sum += q.norm();
        count += 1.0;
      }
    }
  }
  return sum / count;
}

enum class Sample { Sphere, NearOnly, FarOnly };

// Fixed seeded directions: uniform on the sphere, or only those whose ICR is
// within / beyond 8 circumradii of the vertex mean (the branch switch).
std::vector<Vec3> directions(const std::vector<Vec2>& poly, double rho, Sample sample) {
  Vec2 g = Vec2::Zero();
  for (const Vec2& p : poly) g += p;
  g /= static_cast<double>(poly.size());
  double R = 0.0;
  for (const Vec2& p : poly) R = std::max(R, (p - g).norm());
  std::mt19937 rng(20240611);
  std::normal_distribution<double> normal;
  std::vector<Vec3> ws;
  while (static_cast<int>(ws.size()) < kDirections) {
    Vec3 w(normal(rng), normal(rng), normal(rng));
    if (sample == Sample::FarOnly) w.z() *= 0.05;
    w.normalize();
    const Vec2 planar = rho * Vec2(-w.y(), w.x()) - w.z() * g;  // w3 (c - g)
    const bool far = planar.norm() > 8.0 * R * std::abs(w.z());
    if ((sample == Sample::NearOnly && far) || (sample == Sample::FarOnly && !far)) continue;
    ws.push_back(w);
  }
  return ws;
}

void runBasis(benchmark::State& state, const std::vector<Vec2>& poly, Sample sample, bool jacobian,
              double tolerance) {
  const double rho = meanDistance(poly);
  const std::vector<Vec3> ws = directions(poly, rho, sample);
  // error of this tolerance against tolerance 0, normwise per column
  // relative to area * max|phi_k| * (1 + max|P| / rho) (as in the tests)
  double maxErr = 0.0;
  if (tolerance > 0.0) {
    double area2 = 0.0, rmax = 0.0, xmax = 0.0, ymax = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2& a = poly[i];
      const Vec2& b = poly[(i + 1) % poly.size()];
      area2 += a.x() * b.y() - a.y() * b.x();
      rmax = std::max(rmax, a.norm());
      xmax = std::max(xmax, std::abs(a.x()));
      ymax = std::max(ymax, std::abs(a.y()));
    }
    const double s = 0.5 * area2 * (1.0 + rmax / rho);
    const Vec3 scale(s, s * xmax, s * ymax);
    for (const Vec3& w : ws) {
      ExactBasis fast, ref;
      exactPolygonBasis(poly, rho, w, false, fast, tolerance);
      exactPolygonBasis(poly, rho, w, false, ref, 0.0);
      for (int k = 0; k < 3; ++k) {
        maxErr = std::max(maxErr, (fast.F.col(k) - ref.F.col(k)).cwiseAbs().maxCoeff() / scale[k]);
      }
    }
  }
  ExactBasis out;
  std::size_t i = 0;
  for (auto _ : state) {
    exactPolygonBasis(poly, rho, ws[i], jacobian, out, tolerance);
    benchmark::DoNotOptimize(out);
    i = (i + 1) % ws.size();
  }
  state.SetItemsProcessed(state.iterations());
  if (tolerance > 0.0) state.counters["max_rel_err"] = maxErr;
}

// Arguments: shape (0 rectangle, 1 octagon), Jacobian (0/1).
void BM_ExactPolygonBasis(benchmark::State& state) {
  runBasis(state, state.range(0) == 0 ? rectangle() : octagon(), Sample::Sphere,
           state.range(1) != 0, 0.0);
}
BENCHMARK(BM_ExactPolygonBasis)
    ->ArgNames({"octagon", "jacobian"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1});

// Closed-form edge sum only (ICR within 8 circumradii).
void BM_ExactPolygonBasisNearBranch(benchmark::State& state) {
  runBasis(state, state.range(0) == 0 ? rectangle() : octagon(), Sample::NearOnly,
           state.range(1) != 0, 0.0);
}
BENCHMARK(BM_ExactPolygonBasisNearBranch)
    ->ArgNames({"octagon", "jacobian"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1});

// Gauss-Legendre branch only (ICR beyond 8 circumradii), full accuracy and
// with the tolerance knob 1e-9, 1e-6 (argument 2: -log10 tolerance, 0 = full).
void BM_ExactPolygonBasisFarBranch(benchmark::State& state) {
  const double tolerance = state.range(2) == 0 ? 0.0 : std::pow(10.0, -double(state.range(2)));
  runBasis(state, state.range(0) == 0 ? rectangle() : octagon(), Sample::FarOnly,
           state.range(1) != 0, tolerance);
}
BENCHMARK(BM_ExactPolygonBasisFarBranch)
    ->ArgNames({"octagon", "jacobian", "tol_exp"})
    ->Args({0, 0, 0})
    ->Args({0, 0, 9})
    ->Args({0, 0, 6})
    ->Args({0, 1, 0})
    ->Args({1, 0, 0})
    ->Args({1, 0, 9})
    ->Args({1, 0, 6})
    ->Args({1, 1, 0});

// One linear pressure (tilted: 1 + 0.4 x - 0.3 y, positive on both shapes)
// in one pass. Arguments: shape (0 rectangle, 1 octagon), Jacobian (0/1).
void BM_ExactPolygonLaw(benchmark::State& state) {
  const std::vector<Vec2> poly = state.range(0) == 0 ? rectangle() : octagon();
  const double rho = meanDistance(poly);
  const std::vector<Vec3> ws = directions(poly, rho, Sample::Sphere);
  const Vec3 pressure(1.0, 0.4, -0.3);
  Mat3 jac;
  Mat3* jacobian = state.range(1) != 0 ? &jac : nullptr;
  std::size_t i = 0;
  for (auto _ : state) {
    Vec3 q = exactPolygonLaw(poly, rho, ws[i], pressure, jacobian);
    benchmark::DoNotOptimize(q);
    benchmark::DoNotOptimize(jac);
    i = (i + 1) % ws.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ExactPolygonLaw)
    ->ArgNames({"octagon", "jacobian"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1});

// Reference for the ratio: the ellipsoidal law (41) of the same rectangle
// (uniform pressure, same rho and directions) through FrictionPatch.
void BM_EllipsoidalReference(benchmark::State& state) {
  const std::vector<Vec2> poly = rectangle();
  const double rho = meanDistance(poly);
  const patchspin::PatchShape shape = patchspin::PatchShape::polygon(poly);
  const patchspin::FrictionPatch patch(shape, patchspin::LinearPressure::uniform(shape, 1.0), 0.5,
                                       rho);
  const std::vector<Vec3> ws = directions(poly, rho, Sample::Sphere);
  Mat3 jac;
  std::size_t i = 0;
  for (auto _ : state) {
    Vec3 q = patch.ellipsoidalQ(ws[i], state.range(0) != 0 ? &jac : nullptr);
    benchmark::DoNotOptimize(q);
    benchmark::DoNotOptimize(jac);
    i = (i + 1) % ws.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EllipsoidalReference)->ArgNames({"jacobian"})->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
