// The core benchmarks' command line (bench_admissible, bench_exact_arc_region,
// bench_friction_patch_arc_region): `--count=SPEC` runs one fixed batch of
// calls bracketed by callgrind's instrumentation toggles (under `valgrind
// --tool=callgrind --instr-atstart=no` its totals are the same on every run),
// anything else goes to Google Benchmark.
#pragma once

#include <benchmark/benchmark.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define PATCHSPIN_HAVE_CALLGRIND 1
#else
#define PATCHSPIN_HAVE_CALLGRIND 0
// (no toggles to bracket with: countedRunPossible refuses the counted run)
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace patchspin::bench {

// Reads SPEC as `n` integers separated by ':' into `values`, each in
// [0, max[i]]; false (nothing said) if it is not that.
inline bool parseCountSpec(const char* spec, std::size_t n, const int* max, int* values) {
  const char* p = spec;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && *p++ != ':') return false;
    char* end = nullptr;
    const long v = std::strtol(p, &end, 10);
    if (end == p || v < 0 || v > max[i]) return false;
    values[i] = static_cast<int>(v);
    p = end;
  }
  return true;
}

// True where the program was built with callgrind's toggles; else says so
// on stderr.
inline bool countedRunPossible(const char* program) {
  if (PATCHSPIN_HAVE_CALLGRIND) return true;
  std::fprintf(stderr, "%s: built without valgrind/callgrind.h\n", program);
  return false;
}

// `countOne(SPEC)` for the first --count=SPEC, else Google Benchmark on argv.
inline int runCountedOrBenchmarks(int argc, char** argv, int (*countOne)(const char* spec)) {
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--count=", 8) == 0) return countOne(argv[i] + 8);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace patchspin::bench
