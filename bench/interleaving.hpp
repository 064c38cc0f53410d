// Google Benchmark's set-up for the world benchmarks: their repetitions are
// interleaved in random order (the work is deterministic, so what varies
// between repetitions is the machine), unless the command line says
// otherwise.
#pragma once

#include <benchmark/benchmark.h>

#include <cstring>
#include <vector>

namespace patchspin::bench {

// benchmark::Initialize on `args` (argv, possibly filtered by the caller)
// with --benchmark_enable_random_interleaving=true added unless given;
// false if arguments are left that Google Benchmark does not know.
inline bool initializeInterleaved(std::vector<char*>& args) {
  bool given = false;
  for (const char* a : args)
    if (std::strncmp(a, "--benchmark_enable_random_interleaving", 38) == 0) given = true;
  static char interleave[] = "--benchmark_enable_random_interleaving=true";
  if (!given) args.push_back(interleave);
  int nArgs = int(args.size());
  benchmark::Initialize(&nArgs, args.data());
  return !benchmark::ReportUnrecognizedArguments(nArgs, args.data());
}

}  // namespace patchspin::bench
