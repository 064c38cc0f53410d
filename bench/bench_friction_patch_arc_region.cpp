// The exact law (16) of a FrictionPatch on a cut disk stored exactly
// (PatchShape::arcRegion) against the same cut disk as a clipped 64-gon
// (the Bullet layer's former patch), and the shapes' construction (the
// adapter builds one per clip). Shapes, about their centroid as the adapter
// puts them: a coin of radius 2 cm over a box edge (its centre 0.5 R inside
// the edge) and a lens of two such coins 1.2 R apart. Directions: a fixed
// seeded set of 1024 w uniform on the sphere; rho Eq. (11); a tilted linear
// pressure carrying (Pz, Tx, Ty) = (10 N, 0.01 N m, -0.02 N m).
//
//   bench_friction_patch_arc_region --count=SHAPE:KIND:WHAT
//     SHAPE 0 coin over an edge, 1 lens; KIND 0 arc region, 1 64-gon;
//     WHAT 0 exactQ, 1 exactQ with its Jacobian, 2 the PatchShape's
//     construction, 3 (arc region only) the clip: diskPolygonIntersection
//     or diskDiskIntersection and areaMomentsOf of its result, 4
//     nearestAdmissibleLoads of 1024 seeded inadmissible loads (Pz = 10 N,
//     |Tx|, |Ty| < 0.3 N m) (1024 calls each): one pass unmeasured, then
//     one bracketed
//     by callgrind's toggles; under `valgrind --tool=callgrind
//     --instr-atstart=no` totals / 1024 is the count per call.
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include "clip_polygon.hpp"
#include "counted_runs.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace {

using namespace patchspin;
using patchspin::testing::clipPolygon;

constexpr double kR = 0.02;
constexpr int kDirections = 1024;

std::vector<Vec2> ngon(const Vec2& c, double r, int n) {
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    v.push_back(c + r * Vec2(std::cos(t), std::sin(t)));
  }
  return v;
}

// the box's top face and the coins' centres, in the box frame
struct Scene {
  std::vector<Vec2> box = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  Vec2 c1 = Vec2(0.1 - 0.5 * kR, 0.03);
  Vec2 c2 = c1 + Vec2(1.2 * kR, 0.0);
};

// the clip: the coin over the edge (which 0) or the lens (1), exactly
std::vector<BoundaryPiece> clipped(const Scene& sc, int which) {
  return which == 0 ? diskPolygonIntersection(sc.c1, kR, sc.box)
                    : diskDiskIntersection(sc.c1, kR, sc.c2, kR);
}

// the region's boundary pieces and the 64-gon's vertices, about the region's centroid
struct Shapes {
  std::vector<BoundaryPiece> pieces;
  std::vector<Vec2> polygon;
};

Shapes shapes(int which) {
  const Scene sc;
  Shapes s;
  s.pieces = clipped(sc, which);
  s.polygon = clipPolygon(ngon(sc.c1, kR, 64), which == 0 ? sc.box : ngon(sc.c2, kR, 64));
  const AreaMoments m = areaMomentsOf(s.pieces);
  const Vec2 g = m.first / m.area;
  for (BoundaryPiece& p : s.pieces) p.a -= g, p.b -= g, p.centre -= g;
  for (Vec2& v : s.polygon) v -= g;
  return s;
}

PatchShape makeShape(const Shapes& s, int kind) {
  return kind == 0 ? PatchShape::arcRegion(s.pieces) : PatchShape::polygon(s.polygon);
}

std::vector<Vec3> directions() {
  std::mt19937 rng(2026);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Vec3> ws;
  for (int i = 0; i < kDirections; ++i) ws.emplace_back(n(rng), n(rng), n(rng));
  return ws;
}

FrictionPatch patchOf(const PatchShape& shape) {
  return FrictionPatch(shape, LinearPressure::fromLoads(shape, PatchLoads{10.0, 0.01, -0.02}), 0.5);
}

void BM_ExactQ(benchmark::State& state) {
  const PatchShape shape = makeShape(shapes(state.range(1)), state.range(2));
  const FrictionPatch patch = patchOf(shape);
  const std::vector<Vec3> ws = directions();
  const bool jac = state.range(0) != 0;
  std::size_t i = 0;
  Mat3 J;
  for (auto _ : state) {
    benchmark::DoNotOptimize(patch.exactQ(ws[i++ % ws.size()], jac ? &J : nullptr));
  }
}
BENCHMARK(BM_ExactQ)
    ->ArgsProduct({{0, 1}, {0, 1}, {0, 1}})
    ->ArgNames({"jacobian", "lens", "polygon64"});

int countOne(const char* text) {
  const int max[3] = {1, 1, 4};
  int spec[3];
  if (!bench::parseCountSpec(text, 3, max, spec) || (spec[2] == 3 && spec[1] != 0)) {
    std::fprintf(stderr,
                 "bench_friction_patch_arc_region: --count=SHAPE:KIND:WHAT (0-1, 0-1, 0-4; 3 only "
                 "with KIND 0)\n");
    return 2;
  }
  if (!bench::countedRunPossible("bench_friction_patch_arc_region")) return 2;
  const int which = spec[0], kind = spec[1], what = spec[2];
  const Shapes s = shapes(which);
  const PatchShape shape = makeShape(s, kind);
  const FrictionPatch patch = patchOf(shape);
  const std::vector<Vec3> ws = directions();
  double sink = 0.0;
  Mat3 J = Mat3::Zero();
  const Scene sc;
  std::vector<PatchLoads> inadmissible;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (what == 4 && inadmissible.size() < kDirections) {
    const PatchLoads l{10.0, 0.3 * u(rng), 0.3 * u(rng)};
    if (!isAdmissible(shape, l, 0.0)) inadmissible.push_back(l);
  }
  const double rho = shape.defaultRho();
  auto pass = [&] {
    if (what == 4) {
      for (const PatchLoads& l : inadmissible) sink += nearestAdmissibleLoads(shape, l, rho).Pz;
      return;
    }
    if (what == 3) {
      for (int i = 0; i < kDirections; ++i) sink += areaMomentsOf(clipped(sc, which)).area;
      return;
    }
    if (what == 2) {
      for (int i = 0; i < kDirections; ++i) sink += makeShape(s, kind).area();
      return;
    }
    for (const Vec3& w : ws) sink += patch.exactQ(w, what == 1 ? &J : nullptr)[0] + J(0, 0);
  };
  pass();  // one-time tables, not counted
  CALLGRIND_START_INSTRUMENTATION;
  pass();
  CALLGRIND_STOP_INSTRUMENTATION;
  std::printf("%.17g\n", sink);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return patchspin::bench::runCountedOrBenchmarks(argc, argv, countOne);
}
