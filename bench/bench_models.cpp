// Cost of one friction-law evaluation (issue: core friction models).
//   BM_EllipsoidalQ      Q = -mu Pz Pi w with Pi cached, Eq. (41)
//   BM_PiUpdateFromLoads loads -> (p0, cx, cy) -> Pi, Eq. (94), (36), (40)
//   BM_ExactQ/<shape>    Eq. (16) at full accuracy, with and without Jacobian
// Each iteration evaluates one w from a fixed, seeded sample of the sphere.
#include <patchspin/models.hpp>

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using namespace patchspin;

const std::vector<Vec3>& sampleDirections() {
  static const std::vector<Vec3> dirs = [] {
    std::mt19937 rng(20261122);
    std::normal_distribution<double> n;
    std::vector<Vec3> out;
    for (int i = 0; i < 1024; ++i) out.push_back(Vec3(n(rng), n(rng), n(rng)).normalized());
    return out;
  }();
  return dirs;
}

PatchShape shapeByIndex(int index) {
  switch (index) {
    case 0:
      return PatchShape::disk(0.05);
    case 1:
      return PatchShape::rectangle(0.08, 0.04);
    default:
      return PatchShape::regularPolygon(8, 0.05);
  }
}

const char* shapeName(int index) {
  return index == 0 ? "disk" : index == 1 ? "rectangle" : "8-gon";
}

FrictionPatch tiltedPatch(int index) {
  const PatchShape shape = shapeByIndex(index);
  // a tipping load well inside the admissible set: linear pressure, full Pi
  return FrictionPatch(shape, LinearPressure::fromLoads(shape, {10.0, 0.02, -0.015}), 0.5);
}

void BM_EllipsoidalQ(benchmark::State& state) {
  const FrictionPatch patch = tiltedPatch(int(state.range(0)));
  const auto& dirs = sampleDirections();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(patch.ellipsoidalQ(dirs[i++ & 1023]));
  }
  state.SetLabel(shapeName(int(state.range(0))));
}
BENCHMARK(BM_EllipsoidalQ)->DenseRange(0, 2);

void BM_PiUpdateFromLoads(benchmark::State& state) {
  FrictionPatch patch = tiltedPatch(int(state.range(0)));
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-6;
    patch.setLoads({10.0, 0.02 + t * 1e-3, -0.015});
    benchmark::DoNotOptimize(patch.Pi());
  }
  state.SetLabel(shapeName(int(state.range(0))));
}
BENCHMARK(BM_PiUpdateFromLoads)->DenseRange(0, 2);

void BM_ExactQ(benchmark::State& state) {
  const FrictionPatch patch = tiltedPatch(int(state.range(0)));
  const bool jacobian = state.range(1) != 0;
  const auto& dirs = sampleDirections();
  std::size_t i = 0;
  Mat3 J;
  for (auto _ : state) {
    benchmark::DoNotOptimize(patch.exactQ(dirs[i++ & 1023], jacobian ? &J : nullptr));
  }
  state.SetLabel(std::string(shapeName(int(state.range(0)))) + (jacobian ? " +jacobian" : ""));
}
BENCHMARK(BM_ExactQ)->ArgsProduct({{0, 1, 2}, {0, 1}});

}  // namespace

BENCHMARK_MAIN();
