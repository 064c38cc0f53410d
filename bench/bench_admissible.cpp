// Cost of the pressure's projection onto the admissible loads (issue 35
// item 3), beside an ellipsoidal friction block solve on the same patch.
//   BM_NearestAdmissible/<shape>/<regime>  nearestAdmissibleLoads per call
//     shapes: 0 disk about its centre (the Bullet layer's disks), 1 disk off
//     O, 2 rectangle, 3 hexagon, 4 cut disk (64-gon)
//     regimes: centre of pressure 0.05 (0, inside the kern), 0.6 (1, outside
//     the kern, on or near the patch) or 1.5 (2, beyond the patch) times
//     half the diameter from the centroid
//   BM_EllipsoidalBlock/<shape>            solveFrictionBlock, slipping
// Each iteration takes the next of 8 loads around the patch.
//
//   bench_admissible --count=SHAPE:REGIME   (REGIME 3: the block solve)
//     1024 calls bracketed by callgrind's instrumentation toggles: under
//     `valgrind --tool=callgrind --instr-atstart=no` totals / 1024 is the
//     instruction count per call, the same on every run.
#include <patchspin/friction_block.hpp>
#include <patchspin/pressure.hpp>

#include "counted_runs.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace patchspin;

constexpr double kPi = 3.14159265358979323846;
constexpr int kShapes = 5;
const char* const kShapeNames[kShapes] = {"disk", "disk off O", "rectangle", "hexagon",
                                          "cut disk 64-gon"};
const char* const kRegimeNames[3] = {"in kern", "out of kern", "beyond patch"};

PatchShape shapeByIndex(int index) {
  switch (index) {
    case 0:
      return PatchShape::disk(0.05);
    case 1:
      return PatchShape::disk(0.05, Vec2(0.01, -0.02));
    case 2:
      return PatchShape::rectangle(0.08, 0.04);
    case 3:
      return PatchShape::regularPolygon(6, 0.05);
    default: {
      // a disk of radius 0.05 cut by the chord x = 0.02, as 64 vertices
      std::vector<Vec2> v;
      const double a = std::acos(0.4);
      for (int i = 0; i < 64; ++i) {
        const double th = a + (2.0 * kPi - 2.0 * a) * i / 63.0;
        v.push_back(0.05 * Vec2(std::cos(th), std::sin(th)));
      }
      return PatchShape::polygon(v);
    }
  }
}

// 8 loads (Pz = 10 N) whose centres of pressure lie at `reach` times half
// the patch's diameter from its centroid, around it
std::vector<PatchLoads> loadsAround(const PatchShape& shape, int regime) {
  const double reach = regime == 0 ? 0.05 : regime == 1 ? 0.6 : 1.5;
  const double r = reach * 0.5 * shape.diameter();
  std::vector<PatchLoads> out;
  for (int k = 0; k < 8; ++k) {
    const double th = 0.3 + 2.0 * kPi * k / 8.0;
    const Vec2 cop = shape.centroid() + Vec2(r * std::cos(th), r * std::sin(th));
    out.push_back(PatchLoads{10.0, -10.0 * cop.y(), 10.0 * cop.x()});  // (Ty, -Tx) = Pz cop
  }
  return out;
}

struct BlockCase {
  FrictionPatch patch;
  std::vector<FrictionBlockInput> inputs;
};

BlockCase blockCase(int shapeIndex) {
  const PatchShape shape = shapeByIndex(shapeIndex);
  const PatchLoads load = loadsAround(shape, 0)[0];
  BlockCase c{FrictionPatch(shape, LinearPressure::fromLoads(shape, load), 0.5), {}};
  Mat3 K;
  K << 2.0, 0.3, 0.1,  //
      0.3, 1.5, -0.2,  //
      0.1, -0.2, 1.2;
  for (int k = 0; k < 8; ++k) {
    const double th = 2.0 * kPi * k / 8.0;
    FrictionBlockInput in;
    in.b = Vec3(std::cos(th), std::sin(th), 0.4 * std::cos(3.0 * th));
    in.K = K;
    in.L = 0.1;  // slipping: |K^-1 b| is well above L
    c.inputs.push_back(in);
  }
  return c;
}

void BM_NearestAdmissible(benchmark::State& state) {
  const PatchShape shape = shapeByIndex(int(state.range(0)));
  const std::vector<PatchLoads> loads = loadsAround(shape, int(state.range(1)));
  const double rho = shape.defaultRho();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(nearestAdmissibleLoads(shape, loads[i++ & 7], rho));
  state.SetLabel(std::string(kShapeNames[state.range(0)]) + ", " + kRegimeNames[state.range(1)]);
}
BENCHMARK(BM_NearestAdmissible)->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1, 2}});

void BM_EllipsoidalBlock(benchmark::State& state) {
  const BlockCase c = blockCase(int(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(solveFrictionBlock(c.patch, Model::Ellipsoidal, c.inputs[i++ & 7]));
  state.SetLabel(kShapeNames[state.range(0)]);
}
BENCHMARK(BM_EllipsoidalBlock)->DenseRange(0, 4);

// --count=SHAPE:REGIME: 1024 calls under callgrind's toggles
int countOne(const char* text) {
  const int max[2] = {kShapes - 1, 3};
  int spec[2];
  if (!bench::parseCountSpec(text, 2, max, spec)) {
    std::fprintf(stderr, "bench_admissible: --count=SHAPE:REGIME, SHAPE 0-4, REGIME 0-3\n");
    return 2;
  }
  if (!bench::countedRunPossible("bench_admissible")) return 2;
  const int shapeIndex = spec[0], regime = spec[1];
  double sink = 0.0;
  if (regime == 3) {
    const BlockCase c = blockCase(shapeIndex);
    CALLGRIND_START_INSTRUMENTATION;
    for (int i = 0; i < 1024; ++i)
      sink += solveFrictionBlock(c.patch, Model::Ellipsoidal, c.inputs[i & 7]).impulse[0];
    CALLGRIND_STOP_INSTRUMENTATION;
  } else {
    const PatchShape shape = shapeByIndex(shapeIndex);
    const std::vector<PatchLoads> loads = loadsAround(shape, regime);
    const double rho = shape.defaultRho();
    CALLGRIND_START_INSTRUMENTATION;
    for (int i = 0; i < 1024; ++i) sink += nearestAdmissibleLoads(shape, loads[i & 7], rho).Pz;
    CALLGRIND_STOP_INSTRUMENTATION;
  }
  std::printf("%.17g\n", sink);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return patchspin::bench::runCountedOrBenchmarks(argc, argv, countOne);
}
