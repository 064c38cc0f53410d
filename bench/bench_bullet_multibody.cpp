// The multibody world benchmark (issue 33's speed goal: the multibody world
// step with every link opted in costs at most 1.2x stock
// btMultiBodyConstraintSolver on a scene of 100 grippers or feet): the
// fields of scenes/multibody_field.hpp, 100 twisted grasps and 100 twisted
// feet, each held below its limit.
//
// Each repetition of a field runs every variant once, in a shuffled order,
// as the speed matrix does (bench_bullet_speed_matrix.cpp): stock, stock
// again (the A/A control), the patch solver with nothing opted in, every
// pad or foot ellipsoidal, exact. Each run builds a fresh world (not timed)
// and steps it through the whole episode (0.25 s closing or standing, 0.5 s
// twisted; timed: CPU time of this thread); the ratios are taken inside the
// repetition against its stock run, and the table gives their median and
// range over the repetitions.
//
//   bench_bullet_multibody [--markdown=FILE] [gbench flags]
//     PATCHSPIN_MULTIBODY_N=100            grippers or feet (default 100)
//     PATCHSPIN_MULTIBODY_REPETITIONS=7    repetitions per field (default 7)
//   bench_bullet_multibody --count=FIELD:N --variant=V
//     one run, its stepping bracketed by callgrind's instrumentation
//     toggles (scripts/count_instructions.sh); FIELD grippers or feet, V
//     a speed-matrix variant name (stock, none-opted-in, ellipsoidal, exact)
//   bench_bullet_multibody --precision     prints float or double
#include <patchspin/scenes/multibody_field.hpp>

#include <benchmark/benchmark.h>

#include "capturing_reporter.hpp"
#include "episode_clock.hpp"
#include "interleaving.hpp"
#include "repetition_stats.hpp"
#include "world_bench_args.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace patchspin::scenes;
using patchspin::bench::median;
using patchspin::bench::ratioCell;

constexpr const char* kProgram = "bench_bullet_multibody";
constexpr SpeedVariant kVariants[] = {SpeedVariant::Stock, SpeedVariant::StockControl,
                                      SpeedVariant::NoneOptedIn, SpeedVariant::Ellipsoidal,
                                      SpeedVariant::Exact};
constexpr MultiBodyFieldKind kKinds[] = {MultiBodyFieldKind::Grippers, MultiBodyFieldKind::Feet};

struct RunResult {
  double seconds = 0.0;
  double turn = 0.0;  // largest turn of a cube or foot under the twist [rad]
};

// One run of the field under v: build (untimed), then the whole episode.
RunResult runEpisode(MultiBodyFieldKind kind, int n, SpeedVariant v,
                     bool countInstructions = false) {
  MultiBodyField field(kind, n, v);
  patchspin::bench::EpisodeClock clock(countInstructions);
  clock.start();
  for (int k = 0; k < MultiBodyField::episodeSteps(); ++k) field.step();
  RunResult r;
  r.seconds = clock.stop();
  r.turn = field.largestTurn();
  return r;
}

std::string fieldName(MultiBodyFieldKind kind, int n) {
  return std::string("MultiBody/") + toString(kind) + "/N:" + std::to_string(n);
}

// Each repetition (one benchmark iteration) runs every variant once.
void BM_Field(benchmark::State& state, MultiBodyFieldKind kind, int n) {
  static unsigned shuffleSeed = 1;
  for (auto _ : state) {
    std::vector<SpeedVariant> order(std::begin(kVariants), std::end(kVariants));
    std::shuffle(order.begin(), order.end(), std::mt19937(shuffleSeed++));
    std::map<SpeedVariant, RunResult> runs;
    for (SpeedVariant v : order) runs[v] = runEpisode(kind, n, v);
    const double stock = runs[SpeedVariant::Stock].seconds;
    state.SetIterationTime(stock);
    state.counters["stock_ms_per_step"] = 1e3 * stock / MultiBodyField::episodeSteps();
    state.counters["aa"] = runs[SpeedVariant::StockControl].seconds / stock;
    state.counters["none"] = runs[SpeedVariant::NoneOptedIn].seconds / stock;
    state.counters["ellipsoidal"] = runs[SpeedVariant::Ellipsoidal].seconds / stock;
    state.counters["exact"] = runs[SpeedVariant::Exact].seconds / stock;
    state.counters["turn_stock"] = runs[SpeedVariant::Stock].turn;
    state.counters["turn_exact"] = runs[SpeedVariant::Exact].turn;
  }
}

// Per field, every repetition's counters.
std::map<std::string, std::map<std::string, std::vector<double>>> gSamples;

int writeMarkdown(const std::string& path, int n, int repetitions) {
  std::ofstream out(path);
  if (!out) {
    std::fprintf(stderr, "%s: cannot write %s\n", kProgram, path.c_str());
    return 1;
  }
  out << "Bullet in " << (sizeof(btScalar) == 8 ? "double" : "float")
      << "; CPU time of whole episodes (" << MultiBodyField::episodeSteps()
      << " steps of 1/240 s, 10 iterations), each ratio against stock "
         "btMultiBodyConstraintSolver's run in the same repetition: median (range) over "
      << repetitions
      << " repetitions. A/A: stock against itself. Largest turn: of any cube or foot over the "
         "0.5 s twist, stock / exact.\n\n";
  out << "| field | N | stock [ms/step] | A/A | none opted in | ellipsoidal | exact | largest "
         "turn [rad] |\n|---|---|---|---|---|---|---|---|\n";
  double worst = 0;
  for (MultiBodyFieldKind kind : kKinds) {
    const auto it = gSamples.find(fieldName(kind, n));
    if (it == gSamples.end()) continue;
    auto& m = it->second;
    char ms[32], turn[64];
    std::snprintf(ms, sizeof ms, "%.3g", median(m["stock_ms_per_step"]));
    std::snprintf(turn, sizeof turn, "%.2g / %.2g", median(m["turn_stock"]),
                  median(m["turn_exact"]));
    out << "| " << toString(kind) << " | " << n << " | " << ms << " | " << ratioCell(m["aa"])
        << " | " << ratioCell(m["none"]) << " | " << ratioCell(m["ellipsoidal"]) << " | "
        << ratioCell(m["exact"]) << " | " << turn << " |\n";
    worst = std::max({worst, median(m["ellipsoidal"]), median(m["exact"])});
  }
  char line[160];
  std::snprintf(line, sizeof line,
                "\nWorst median: %.2fx stock. Goal (issue 33): every link opted in <= 1.2x.\n",
                worst);
  out << line;
  std::printf("%s", line);
  return 0;
}

// --count mode: one run under callgrind's toggles.
int countOne(const std::string& fieldText, const std::string& variantText) {
#if !PATCHSPIN_HAVE_CALLGRIND
  std::fprintf(stderr, "%s: built without <valgrind/callgrind.h>: --count cannot bracket the run\n",
               kProgram);
  return 2;
#else
  try {
    const std::size_t colon = fieldText.find(':');
    if (colon == std::string::npos) throw patchspin::Error("--count wants FIELD:N");
    const MultiBodyFieldKind kind = multiBodyFieldKindFromString(fieldText.substr(0, colon));
    const int n = std::stoi(fieldText.substr(colon + 1));
    const SpeedVariant v = speedVariantFromString(variantText);
    const RunResult r = runEpisode(kind, n, v, true);
    std::printf("%s %s: %d steps, largest turn %.3g rad\n", fieldText.c_str(), variantText.c_str(),
                MultiBodyField::episodeSteps(), r.turn);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", kProgram, e.what());
    return 2;
  }
#endif
}

}  // namespace

int main(int argc, char** argv) {
  patchspin::bench::WorldBenchArgs a;
  if (const int code = patchspin::bench::parseWorldBenchArgs(kProgram, argc, argv, a); code >= 0)
    return code;
  if (!a.count.empty()) return countOne(a.count, a.variant);
  if (!patchspin::bench::initializeInterleaved(a.benchmarkArgs)) return 1;
  const int n = patchspin::bench::envInt(kProgram, "PATCHSPIN_MULTIBODY_N", 100, 1, 10000);
  const int repetitions =
      patchspin::bench::envInt(kProgram, "PATCHSPIN_MULTIBODY_REPETITIONS", 7, 1, 100);
  for (MultiBodyFieldKind kind : kKinds)
    benchmark::RegisterBenchmark(fieldName(kind, n).c_str(),
                                 [kind, n](benchmark::State& st) { BM_Field(st, kind, n); })
        ->Iterations(1)
        ->Repetitions(repetitions)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  patchspin::bench::CapturingReporter reporter([](const benchmark::BenchmarkReporter::Run& r) {
    for (const auto& [name, counter] : r.counters)
      gSamples[r.run_name.function_name][name].push_back(counter.value);
  });
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return a.markdown.empty() ? 0 : writeMarkdown(a.markdown, n, repetitions);
}
