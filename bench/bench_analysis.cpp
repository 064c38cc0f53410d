// Limit directions (linear Pi: eigenproblem (111); Pi(w): sphere solver; exact
// law) and reference-dynamics steps per second.
#include <benchmark/benchmark.h>

#include <patchspin/analysis.hpp>

namespace {

using namespace patchspin;

FlatBody disk(double xi, double height) {
  FlatBody body;
  body.shape = PatchShape::disk(0.1);
  body.mass = 2.0;
  body.Jz = 0.01;
  body.com = Vec3(0.0, 0.0, height);
  body.mu = 0.3;
  body.force = Vec2(xi * 0.3 * 2.0 * 9.81, 0.0);
  body.torque = Vec3(0.1 * 2.0 * 9.81 * 0.1, 0.0, 0.0);
  return body;
}

// Sect. 6.3, Case 4: six limit directions from the 6x6 eigenproblem
void BM_LimitDirectionsLinear(benchmark::State& state) {
  const FlatBodyModel model(disk(0.02, 0.0), Model::Ellipsoidal);
  for (auto _ : state) benchmark::DoNotOptimize(findLimitDirections(model));
}
BENCHMARK(BM_LimitDirectionsLinear)->Unit(benchmark::kMicrosecond);

// thick disk (eta = 0.2): Pi(w), Newton on the sphere from range(0) seeds
void BM_LimitDirectionsPiOfW(benchmark::State& state) {
  const FlatBodyModel model(disk(0.05, 0.2 * 0.1 / 0.3), Model::Ellipsoidal);
  LimitOptions options;
  options.seeds = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(findLimitDirections(model, options));
}
BENCHMARK(BM_LimitDirectionsPiOfW)->Arg(150)->Arg(600)->Unit(benchmark::kMillisecond);

// exact law (16) on a thick disk and on a rectangle
void BM_LimitDirectionsExactDisk(benchmark::State& state) {
  const FlatBodyModel model(disk(0.05, 0.2 * 0.1 / 0.3), Model::Exact);
  LimitOptions options;
  options.seeds = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(findLimitDirections(model, options));
}
BENCHMARK(BM_LimitDirectionsExactDisk)->Arg(150)->Arg(600)->Unit(benchmark::kMillisecond);

void BM_LimitDirectionsExactRectangle(benchmark::State& state) {
  FlatBody body = disk(0.1, 0.02);
  body.shape = PatchShape::rectangle(0.15, 0.08);
  const FlatBodyModel model(body, Model::Exact);
  LimitOptions options;
  options.seeds = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(findLimitDirections(model, options));
}
BENCHMARK(BM_LimitDirectionsExactRectangle)->Arg(150)->Arg(600)->Unit(benchmark::kMillisecond);

// reference dynamics of a spinning, sliding thick disk until it sticks
void referenceRun(benchmark::State& state, Model law) {
  FlatBody body = disk(0.0, 0.01);
  body.torque.setZero();
  const FlatBodyModel model(body, law);
  BodyState start;
  start.x = Vec3(0.5, 0.1, model.rho() * 20.0);
  ReferenceOptions options;
  options.recordAt = 1e-4;
  long steps = 0;
  for (auto _ : state) {
    const ReferenceRun run = integrateReference(model, start, options);
    steps += run.steps;
    benchmark::DoNotOptimize(run.final.position);
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["steps/run"] =
      static_cast<double>(steps) / static_cast<double>(state.iterations());
}
void BM_ReferenceDynamicsEllipsoidal(benchmark::State& state) {
  referenceRun(state, Model::Ellipsoidal);
}
void BM_ReferenceDynamicsExact(benchmark::State& state) {
  referenceRun(state, Model::Exact);
}
BENCHMARK(BM_ReferenceDynamicsEllipsoidal)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReferenceDynamicsExact)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
