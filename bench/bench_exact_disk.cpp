// Cost of the exact model (16) on a disk (internal/exact.hpp).
//   BM_ExactDiskBasis/<jac>        centred disk, basis F (linear pressure), one w
//                                  per iteration from a fixed seeded sample of
//                                  the sphere; jac = 1 also computes dF
//   BM_ExactDiskBasisTol/<-log10>  the same with the tolerance knob; counter
//                                  max_rel_err = worst deviation from full
//                                  accuracy over the sample (column-scaled)
//   BM_ExactDiskBasisRegion/<r>    w restricted to one branch: 0 ICR near the
//                                  centre (series), 1 ICR in the rim band
//                                  (elliptic K, E), 2 ICR far (series)
//   BM_ExactDiskHertz/<jac>        Hertz pressure (57)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <patchspin/internal/exact.hpp>
#include <random>
#include <vector>

namespace {

using namespace patchspin;

constexpr double kR = 0.05;
constexpr double kRho = 2.0 * kR / 3.0;  // Eq. (47)
constexpr std::size_t kSample = 1024;

const std::vector<Vec3>& sampleDirections() {
  static const std::vector<Vec3> dirs = [] {
    std::mt19937 rng(20261122);
    std::normal_distribution<double> n;
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < kSample; ++i)
      out.push_back(Vec3(n(rng), n(rng), n(rng)).normalized());
    return out;
  }();
  return dirs;
}

// directions whose ICR lies at distance in [lo, hi) R from the centre
std::vector<Vec3> regionDirections(double lo, double hi) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < kSample; ++i) {
    const double f = lo + (hi - lo) * u(rng), phi = 6.283185307179586 * u(rng);
    const double s = u(rng) < 0.5 ? 1.0 : -1.0;
    const double cx = f * kR * std::cos(phi), cy = f * kR * std::sin(phi);
    out.push_back(Vec3(cy * s / kRho, -cx * s / kRho, s).normalized());
  }
  return out;
}

void BM_ExactDiskBasis(benchmark::State& state) {
  const bool jac = state.range(0) != 0;
  const auto& dirs = sampleDirections();
  internal::ExactBasis out;
  std::size_t i = 0;
  for (auto _ : state) {
    internal::exactDiskBasis(Vec2::Zero(), kR, kRho, dirs[i++ & (kSample - 1)], jac, out);
    benchmark::DoNotOptimize(out);
  }
  state.SetLabel(jac ? "with jacobian" : "value only");
}
BENCHMARK(BM_ExactDiskBasis)->Arg(0)->Arg(1);

void BM_ExactDiskBasisTol(benchmark::State& state) {
  const double tol = std::pow(10.0, -double(state.range(0)));
  const auto& dirs = sampleDirections();
  // measured error of this setting against full accuracy, relative to the
  // column scale of the tests (pi R^2 max|phi_k| (1 + R/rho))
  double worst = 0.0;
  for (const Vec3& w : dirs) {
    internal::ExactBasis full, fast;
    internal::exactDiskBasis(Vec2::Zero(), kR, kRho, w, false, full);
    internal::exactDiskBasis(Vec2::Zero(), kR, kRho, w, false, fast, tol);
    for (int k = 0; k < 3; ++k) {
      const double scale = 3.141592653589793 * kR * kR * (k == 0 ? 1.0 : kR) * (1.0 + kR / kRho);
      worst = std::max(worst, (full.F.col(k) - fast.F.col(k)).cwiseAbs().maxCoeff() / scale);
    }
  }
  internal::ExactBasis out;
  std::size_t i = 0;
  for (auto _ : state) {
    internal::exactDiskBasis(Vec2::Zero(), kR, kRho, dirs[i++ & (kSample - 1)], false, out, tol);
    benchmark::DoNotOptimize(out);
  }
  state.counters["max_rel_err"] = worst;
}
BENCHMARK(BM_ExactDiskBasisTol)->Arg(4)->Arg(7)->Arg(10);

void BM_ExactDiskBasisRegion(benchmark::State& state) {
  static const std::vector<Vec3> regions[3] = {
      regionDirections(0.0, 0.31), regionDirections(0.32, 3.1), regionDirections(3.2, 50.0)};
  const auto& dirs = regions[state.range(0)];
  internal::ExactBasis out;
  std::size_t i = 0;
  for (auto _ : state) {
    internal::exactDiskBasis(Vec2::Zero(), kR, kRho, dirs[i++ & (kSample - 1)], false, out);
    benchmark::DoNotOptimize(out);
  }
  const char* names[3] = {"ICR near centre (series)", "ICR in rim band (K, E)", "ICR far (series)"};
  state.SetLabel(names[state.range(0)]);
}
BENCHMARK(BM_ExactDiskBasisRegion)->DenseRange(0, 2);

void BM_ExactDiskHertz(benchmark::State& state) {
  const bool jac = state.range(0) != 0;
  const auto& dirs = sampleDirections();
  Mat3 J;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(internal::exactDiskHertz(
        Vec2::Zero(), kR, kRho, dirs[i++ & (kSample - 1)], jac ? &J : nullptr));
    benchmark::ClobberMemory();
  }
  state.SetLabel(jac ? "with jacobian" : "value only");
}
BENCHMARK(BM_ExactDiskHertz)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
