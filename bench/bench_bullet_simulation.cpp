// Per simulation: error against run time for the scenes of the validation
// tests (tests/bullet/simulate_test.cpp), run in Bullet by
// patchspin::scenes::simulate for each model and time step (issue 6):
//
//   coin         free thin disk (R 5 cm, H 0.2 mm, 1 kg, mu 0.3, omega0 60 rad/s)
//                (a) "coin from 0.653": started at v/(R omega) = 0.6530, the
//                ratio the exact law keeps (closed form, infinitely thin disk:
//                stops at t = 1.0600 R omega0 / (mu g)); (b) "coin from 1":
//                started at v = R omega0, so the ratio has to fall toward it.
//                Measured: stopping time, terminal v/(R omega) (at r = 1 % r0).
//   pushed disk  Sect. 6.1, Case 3 (F = 0.05 mu m g < mu m g / 9): 30 g disk,
//                R 5 cm, H 5 mm, v0 = 0.5 m/s across F, omega0 20 rad/s; it
//                stops sliding and spinning. Measured: stopping time, terminal
//                slip direction w (at r = 1 % r0; |w - w_ref|).
//   box spin-down  10 x 6 x 4 cm box, 1 kg, mu 0.3, spinning in place at
//                20 rad/s. Measured: stopping time, terminal w (pure spin).
//
// Reference: the core's reference dynamics (simulateReference, adaptive
// Dormand-Prince 5(4), relTol 1e-10) of the same SimulationSpec with the
// EXACT law: the physics the models approximate. Errors: |t - t_ref| / t_ref
// for the stopping time, |eps - eps_ref| / eps_ref for the coin's terminal
// ratio, |w - w_ref| for a terminal direction. The ellipsoidal model is also
// compared with its own reference dynamics (columns "*_own": the time-step
// error alone, without the model error).
//
// Cost: CPU time per simulated second = time of one simulate() call
// (world set-up included), measured as the thread's CPU time (the machine is
// shared; a run is single-threaded, so this is its wall time on an idle
// core), the fastest of kRunsPerSetting runs, / simulated time (the
// stopping time, or tMax = 3 t_ref for a run that does not stop). Stock
// Bullet runs with Bullet's own point friction (model "stock"). Also listed:
// the reference integrator itself ("reference", adaptive step) for both laws.
//
// Output: Google Benchmark's table, a table per scene in the spirit of "which
// model and step should I use", and with --csv=PATH the rows as CSV
// (docs/bench/simulation_error.csv): scene,model,dt,cpu_per_sim_s,
// err_tstop,err_terminal,err_tstop_own,err_terminal_own,stopped,t_stop,
// terminal,t_ref,terminal_ref,terminal_kind (terminal: v/(R omega), or w3 of
// the terminal w). Empty fields: not applicable
// (no own reference for stock; no stop).
#include <patchspin/analysis.hpp>
#include <patchspin/scenes/simulate.hpp>

#include <benchmark/benchmark.h>

#include "episode_clock.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace patchspin;

// thresholds of the recommendation: the paper-level accuracy of the
// validation tests (simulate_test.cpp: 2 % stopping time, 0.01 in w / ratio)
constexpr double kGoodStop = 0.02;
constexpr double kGoodTerminal = 0.01;
constexpr int kRunsPerSetting = 3;  // run time: the fastest of these

struct Scene {
  std::string name;
  SimulationSpec spec;
  bool ratio;  // terminal quantity: v/(R omega) (coin) or w
};

std::vector<Scene> simulationScenes() {
  std::vector<Scene> out;
  // the thin coin of the validation tests, started on the exact law's limit
  // ratio (where it stays) and from v = R omega (where it must turn toward it)
  for (double ratio : {0.6530, 1.0}) {
    SimulationSpec coin;
    coin.shape = SimulationSpec::Shape::Cylinder;
    coin.R = 0.05;
    coin.H = 2e-4;
    coin.mass = 1.0;
    coin.mu = 0.3;
    coin.omega0 = 60.0;
    coin.v0 = Vec2(ratio * coin.R * coin.omega0, 0.0);
    out.push_back({ratio < 1.0 ? "coin from 0.653" : "coin from 1", coin, true});
  }

  SimulationSpec pushed;
  pushed.shape = SimulationSpec::Shape::Cylinder;
  pushed.R = 0.05;
  pushed.H = 0.005;
  pushed.mass = 0.03;
  pushed.mu = 0.3;
  pushed.v0 = Vec2(0.0, 0.5);
  pushed.omega0 = 20.0;
  pushed.force = Vec2(0.05 * pushed.mu * pushed.mass * pushed.g, 0.0);
  out.push_back({"pushed disk", pushed, false});

  SimulationSpec box;
  box.shape = SimulationSpec::Shape::Box;
  box.LX = 0.1;
  box.LY = 0.06;
  box.LZ = 0.04;
  box.mass = 1.0;
  box.mu = 0.3;
  box.omega0 = 20.0;
  out.push_back({"box spin-down", box, false});
  return out;
}

struct Steps {
  const char* label;
  double dt;
};
const Steps kSteps[] = {{"1/30", 1.0 / 30},    {"1/60", 1.0 / 60},   {"1/120", 1.0 / 120},
                        {"1/240", 1.0 / 240},  {"1/500", 1.0 / 500}, {"1/1000", 1.0 / 1000},
                        {"1/2000", 1.0 / 2000}};

double terminalOf(const Scene& s, const SimulationResult& r) {
  return s.ratio ? r.epsStop.value_or(std::nan("")) : r.wStop.z();
}

// error of the terminal quantity of `r` against `ref`
double terminalError(const Scene& s, const SimulationResult& r, const SimulationResult& ref) {
  if (s.ratio) {
    const double eps = r.epsStop.value_or(NAN), epsRef = ref.epsStop.value_or(NAN);
    return std::abs(eps - epsRef) / epsRef;  // NaN if either never recorded
  }
  if (r.wStop.squaredNorm() == 0.0) return std::nan("");  // never recorded
  return (r.wStop - ref.wStop).norm();
}

struct Row {
  std::string scene, model, dt;
  double cpuPerSimS = 0;
  double errStop = NAN, errTerminal = NAN, errStopOwn = NAN, errTerminalOwn = NAN;
  bool stopped = false;
  double tStop = 0, terminal = NAN, tRef = 0, terminalRef = NAN;
  bool ratio = false;
};
std::vector<Row> gRows;

struct References {
  SimulationResult exact, ellipsoidal;
};

SimulationResult runReference(SimulationSpec spec, const std::string& model) {
  spec.engine = "reference";
  spec.model = model;
  return simulateReference(spec);
}

// one setting: runs kRunsPerSetting times (the benchmark's iterations), keeps
// the fastest run time and the (deterministic) result
void runSetting(benchmark::State& state, const Scene& scene, const References& refs,
                const std::string& model, const Steps* step) {
  SimulationSpec spec = scene.spec;
  spec.model = model;
  spec.tMax = 3.0 * refs.exact.tStop;
  if (step) {
    spec.engine = "bullet";
    spec.precision = patchspin::scenes::buildPrecision();
    spec.dt = step->dt;
  }
  std::vector<SimulationResult> runs;
  double best = INFINITY;
  for (auto _ : state) {
    const double t0 = patchspin::bench::threadSeconds();
    runs.push_back(step ? patchspin::scenes::simulate(spec) : runReference(spec, model));
    best = std::min(best, patchspin::bench::threadSeconds() - t0);
  }
  const SimulationResult& result = runs.back();
  Row row;
  row.scene = scene.name;
  row.model = step ? model : "reference " + model;
  row.dt = step ? step->label : "adaptive";
  row.stopped = result.stopped;
  row.tStop = result.tStop;
  row.ratio = scene.ratio;
  row.terminal = terminalOf(scene, result);
  row.tRef = refs.exact.tStop;
  row.terminalRef = terminalOf(scene, refs.exact);
  const double simulated = result.stopped ? result.tStop : spec.tMax;
  row.cpuPerSimS = best / simulated;
  if (result.stopped) row.errStop = std::abs(result.tStop - refs.exact.tStop) / refs.exact.tStop;
  row.errTerminal = terminalError(scene, result, refs.exact);
  if (model == "ellipsoidal") {
    if (result.stopped)
      row.errStopOwn = std::abs(result.tStop - refs.ellipsoidal.tStop) / refs.ellipsoidal.tStop;
    row.errTerminalOwn = terminalError(scene, result, refs.ellipsoidal);
  } else if (model == "exact") {
    row.errStopOwn = row.errStop;
    row.errTerminalOwn = row.errTerminal;
  }
  state.counters["cpu_per_sim_s"] = row.cpuPerSimS;
  state.counters["err_tstop"] = row.errStop;
  state.counters["err_terminal"] = row.errTerminal;
  gRows.push_back(row);
}

std::string fmt(double x, const char* f = "%.3g") {
  if (std::isnan(x)) return "";
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

void printTables(const std::vector<Scene>& all, const std::map<std::string, References>& refs) {
  std::printf(
      "\nPer simulation: error against the exact law's reference dynamics, and run time per "
      "simulated\n"
      "second (CPU ms of the run per simulated s; Bullet %s precision, 10 solver iterations, one "
      "body; fastest of %d runs).\n",
      patchspin::scenes::buildPrecision(), kRunsPerSetting);
  for (const Scene& s : all) {
    const References& r = refs.at(s.name);
    std::printf("\n%s: reference (exact law) t_stop = %.5f s, terminal %s = %s", s.name.c_str(),
                r.exact.tStop, s.ratio ? "v/(R omega)" : "w",
                s.ratio
                    ? fmt(*r.exact.epsStop, "%.4f").c_str()
                    : ("(" + fmt(r.exact.wStop.x(), "%.3f") + ", " +
                       fmt(r.exact.wStop.y(), "%.3f") + ", " + fmt(r.exact.wStop.z(), "%.3f") + ")")
                          .c_str());
    if (s.name == "coin from 0.653")
      std::printf(" (closed form, infinitely thin: %.5f s, 0.6530)",
                  1.0600 * s.spec.R * s.spec.omega0 / (s.spec.mu * s.spec.g));
    std::printf("\n%-22s %-8s %14s %11s %12s %11s %12s\n", "model", "dt [s]", "CPU ms per s",
                "err t_stop", s.ratio ? "err v/(Rw)" : "err |w|", "own t_stop", "own term.");
    for (const Row& row : gRows) {
      if (row.scene != s.name) continue;
      std::printf("%-22s %-8s %14.3f %11s %12s %11s %12s\n", row.model.c_str(), row.dt.c_str(),
                  1e3 * row.cpuPerSimS, row.stopped ? fmt(row.errStop).c_str() : "no stop",
                  fmt(row.errTerminal).c_str(), fmt(row.errStopOwn).c_str(),
                  fmt(row.errTerminalOwn).c_str());
    }
    // recommendation: cheapest Bullet setting per model within the validation tests' accuracy
    std::printf("cheapest step within %.0f %% (t_stop) and %.2f (terminal) of the exact physics:\n",
                100 * kGoodStop, kGoodTerminal);
    for (const char* model : {"exact", "ellipsoidal", "stock"}) {
      const Row* best = nullptr;
      for (const Row& row : gRows)
        if (row.scene == s.name && row.model == model && row.errStop <= kGoodStop &&
            row.errTerminal <= kGoodTerminal && (!best || row.cpuPerSimS < best->cpuPerSimS))
          best = &row;
      if (best)
        std::printf("  %-12s dt = %-7s (%.3f ms per simulated s)\n", model, best->dt.c_str(),
                    1e3 * best->cpuPerSimS);
      else
        std::printf("  %-12s none of the steps\n", model);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string csvPath;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--csv=", 6) == 0)
      csvPath = argv[i] + 6;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;

  static const std::vector<Scene> all = simulationScenes();
  static std::map<std::string, References> refs;
  for (const Scene& s : all) {
    refs[s.name] = References{runReference(s.spec, "exact"), runReference(s.spec, "ellipsoidal")};
    if (!refs[s.name].exact.stopped) {
      std::fprintf(stderr, "bench_bullet_simulation: the reference run of %s does not stop\n",
                   s.name.c_str());
      return 1;
    }
  }
  for (const Scene& s : all) {
    for (const char* model : {"ellipsoidal", "exact"}) {
      const std::string name = s.name + "/reference/" + model;
      benchmark::RegisterBenchmark(
          name.c_str(),
          [&s, model](benchmark::State& st) { runSetting(st, s, refs.at(s.name), model, nullptr); })
          ->Iterations(kRunsPerSetting)
          ->Unit(benchmark::kMillisecond);
    }
    for (const char* model : {"ellipsoidal", "exact", "stock"}) {
      for (const Steps& step : kSteps) {
        const std::string name = s.name + "/" + model + "/dt:" + step.label;
        benchmark::RegisterBenchmark(name.c_str(),
                                     [&s, model, &step](benchmark::State& st) {
                                       runSetting(st, s, refs.at(s.name), model, &step);
                                     })
            ->Iterations(kRunsPerSetting)
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printTables(all, refs);

  if (!csvPath.empty()) {
    std::ofstream f(csvPath);
    if (!f) {
      std::fprintf(stderr, "bench_bullet_simulation: cannot write %s\n", csvPath.c_str());
      return 1;
    }
    f << "scene,model,dt,cpu_per_sim_s,err_tstop,err_terminal,err_tstop_own,err_terminal_own,"
         "stopped,t_stop,"
         "terminal,t_ref,terminal_ref,terminal_kind\n";
    for (const Row& r : gRows) {
      f << '"' << r.scene << "\",\"" << r.model << "\"," << r.dt << ',' << fmt(r.cpuPerSimS, "%.6g")
        << ',' << fmt(r.errStop, "%.6g") << ',' << fmt(r.errTerminal, "%.6g") << ','
        << fmt(r.errStopOwn, "%.6g") << ',' << fmt(r.errTerminalOwn, "%.6g") << ','
        << (r.stopped ? 1 : 0) << ',' << fmt(r.tStop, "%.6g") << ',' << fmt(r.terminal, "%.6g")
        << ',' << fmt(r.tRef, "%.6g") << ',' << fmt(r.terminalRef, "%.6g") << ','
        << (r.ratio ? "ratio" : "w") << '\n';
    }
    std::printf("\nwrote %s\n", csvPath.c_str());
  }
  return 0;
}
