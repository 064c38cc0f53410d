// Benchmarks of the exact model on cut disks, Eq. (16): the closed form on
// regions bounded by segments and arcs (internal::exactArcRegionBasis)
// against the polygon law (internal::exactPolygonBasis) on the 32- and
// 64-gon of the same region (how cut disks are stored today), and against
// the disk law on the uncut disk, value alone and with the Jacobian.
// Shapes: a coin of radius 0.5 overhanging a box edge (disk cut at 0.2 from
// its centre) and a lens of two such coins 0.6 apart. Directions: a fixed
// seeded set of 1024 w uniform on the sphere (and, for the arc law, sets
// with only near-branch or only far-branch ICRs); rho = 0.35 (about the
// mean distance from the centre) for every shape.
//
//   bench_exact_arc_region --count=SHAPE:JACOBIAN:SAMPLE
//     the arc law on SHAPE (0 disk segment, 1 lens), F (JACOBIAN 0) or F and
//     dF (1), over the 1024 directions of SAMPLE (0 uniform, 1 near branch
//     only, 2 far only): one pass to build the Gauss tables, then one pass
//     bracketed by callgrind's instrumentation toggles; under `valgrind
//     --tool=callgrind --instr-atstart=no` totals / 1024 is the instruction
//     count per evaluation, the same on every run.
#include <patchspin/internal/exact.hpp>

#include "counted_runs.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace {

using patchspin::Vec2;
using patchspin::Vec3;
using patchspin::internal::BoundaryPiece;
using patchspin::internal::ExactBasis;

constexpr int kDirections = 1024;
constexpr double kRho = 0.35;
constexpr double kRadius = 0.5;

Vec2 onCircle(const Vec2& o, double r, double t) {
  return o + r * Vec2(std::cos(t), std::sin(t));
}

// Disk at the origin, the part x <= 0.2 kept.
std::vector<BoundaryPiece> diskSegment() {
  const double alpha = std::acos(0.2 / kRadius);
  return {BoundaryPiece::arc(Vec2::Zero(), kRadius, alpha, 2.0 * M_PI - alpha),
          BoundaryPiece::segment(onCircle(Vec2::Zero(), kRadius, -alpha),
                                 onCircle(Vec2::Zero(), kRadius, alpha))};
}

// Disks at (-0.3, 0) and (0.3, 0): arcs of half-angle acos(0.3 / R) each.
std::vector<BoundaryPiece> lens() {
  const double a = std::acos(0.3 / kRadius);
  return {BoundaryPiece::arc(Vec2(-0.3, 0.0), kRadius, -a, a),
          BoundaryPiece::arc(Vec2(0.3, 0.0), kRadius, M_PI - a, M_PI + a)};
}

// n vertices in all, spread over the arcs by angle (chords as they are).
std::vector<Vec2> polygonOf(const std::vector<BoundaryPiece>& region, int n) {
  double total = 0.0;
  for (const BoundaryPiece& p : region)
    if (p.kind == BoundaryPiece::Kind::Arc) total += p.angle1 - p.angle0;
  std::vector<Vec2> poly;
  for (const BoundaryPiece& p : region) {
    if (p.kind == BoundaryPiece::Kind::Segment) continue;  // its ends are arc ends
    const double span = p.angle1 - p.angle0;
    const int m = static_cast<int>(std::lround(n * span / total));
    const bool closedByChord = region.size() > 1 && region[0].kind != region[1].kind;
    for (int i = 0; i < m; ++i) {
      const double s =
          closedByChord ? static_cast<double>(i) / (m - 1) : static_cast<double>(i) / m;
      poly.push_back(onCircle(p.centre, p.radius, p.angle0 + s * span));
    }
  }
  return poly;
}

// 0: uniform on the sphere; 1 / 2: only ICRs within / beyond 8 coin radii of
// the coin's centre (about the law's branch switch at 8 region radii).
std::vector<Vec3> directions(int sample = 0) {
  std::mt19937 rng(20261129);
  std::normal_distribution<double> normal;
  std::vector<Vec3> ws;
  while (static_cast<int>(ws.size()) < kDirections) {
    Vec3 w(normal(rng), normal(rng), normal(rng));
    if (sample == 2) w.z() *= 0.05;
    w.normalize();
    const bool far = kRho * std::hypot(w.x(), w.y()) > 8.0 * kRadius * std::abs(w.z());
    if ((sample == 1 && far) || (sample == 2 && !far)) continue;
    ws.push_back(w);
  }
  return ws;
}

template <class Law>
void run(benchmark::State& state, Law&& law, int sample = 0) {
  const std::vector<Vec3> ws = directions(sample);
  const bool jacobian = state.range(0) != 0;
  ExactBasis out;
  std::size_t i = 0;
  for (auto _ : state) {
    law(ws[i], jacobian, out);
    benchmark::DoNotOptimize(out);
    if (++i == ws.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

const std::vector<BoundaryPiece>& shape(int which) {
  static const std::vector<BoundaryPiece> segment = diskSegment(), lensShape = lens();
  return which == 0 ? segment : lensShape;
}

// range(0): Jacobian; range(1): 0 = disk segment, 1 = lens
void BM_ArcRegionLaw(benchmark::State& state) {
  const auto& region = shape(static_cast<int>(state.range(1)));
  run(state, [&](const Vec3& w, bool jac, ExactBasis& out) {
    patchspin::internal::exactArcRegionBasis(region, kRho, w, jac, out);
  });
}
BENCHMARK(BM_ArcRegionLaw)->ArgsProduct({{0, 1}, {0, 1}})->ArgNames({"jacobian", "lens"});

// range(2): 1 = near-branch directions only, 2 = far only
void BM_ArcRegionLawByBranch(benchmark::State& state) {
  const auto& region = shape(static_cast<int>(state.range(1)));
  run(
      state,
      [&](const Vec3& w, bool jac, ExactBasis& out) {
        patchspin::internal::exactArcRegionBasis(region, kRho, w, jac, out);
      },
      static_cast<int>(state.range(2)));
}
BENCHMARK(BM_ArcRegionLawByBranch)
    ->ArgsProduct({{0, 1}, {0, 1}, {1, 2}})
    ->ArgNames({"jacobian", "lens", "branch"});

// range(2): vertices of the polygon
void BM_PolygonLawOnCutDisk(benchmark::State& state) {
  const std::vector<Vec2> poly =
      polygonOf(shape(static_cast<int>(state.range(1))), static_cast<int>(state.range(2)));
  run(state, [&](const Vec3& w, bool jac, ExactBasis& out) {
    patchspin::internal::exactPolygonBasis(poly, kRho, w, jac, out);
  });
}
BENCHMARK(BM_PolygonLawOnCutDisk)
    ->ArgsProduct({{0, 1}, {0, 1}, {32, 64}})
    ->ArgNames({"jacobian", "lens", "vertices"});

void BM_DiskLawUncut(benchmark::State& state) {
  run(state, [&](const Vec3& w, bool jac, ExactBasis& out) {
    patchspin::internal::exactDiskBasis(Vec2::Zero(), kRadius, kRho, w, jac, out);
  });
}
BENCHMARK(BM_DiskLawUncut)->Arg(0)->Arg(1)->ArgName("jacobian");

// --count=SHAPE:JACOBIAN:SAMPLE: 1024 evaluations under callgrind's toggles
int countOne(const char* text) {
  const int max[3] = {1, 1, 2};
  int spec[3];
  if (!patchspin::bench::parseCountSpec(text, 3, max, spec)) {
    std::fprintf(stderr, "bench_exact_arc_region: --count=SHAPE:JACOBIAN:SAMPLE (0-1, 0-1, 0-2)\n");
    return 2;
  }
  if (!patchspin::bench::countedRunPossible("bench_exact_arc_region")) return 2;
  const int which = spec[0], jacobian = spec[1], sample = spec[2];
  const auto& region = shape(which);
  const std::vector<Vec3> ws = directions(sample);
  ExactBasis out;
  double sink = 0.0;
  for (const Vec3& w : ws) {  // the Gauss tables' one-time set-up, not counted
    patchspin::internal::exactArcRegionBasis(region, kRho, w, jacobian != 0, out);
    sink += out.F(0, 0);
  }
  CALLGRIND_START_INSTRUMENTATION;
  for (const Vec3& w : ws) {
    patchspin::internal::exactArcRegionBasis(region, kRho, w, jacobian != 0, out);
    sink += out.F(0, 0) + out.dF[0](0, 0);
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  std::printf("%.17g\n", sink);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return patchspin::bench::runCountedOrBenchmarks(argc, argv, countOne);
}
