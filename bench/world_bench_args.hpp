// The world benchmarks' own flags (bench_bullet_speed_matrix,
// bench_bullet_multibody), split from Google Benchmark's:
//   --markdown=FILE             also write the result table to FILE
//   --count=CELL --variant=V    one episode under callgrind's toggles
//                               (scripts/count_instructions.sh)
//   --precision                 print Bullet's precision (float or double)
#pragma once

#include <LinearMath/btScalar.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace patchspin::bench {

struct WorldBenchArgs {
  std::string markdown, count, variant;
  std::vector<char*> benchmarkArgs;  // the rest, argv[0] first, for Google Benchmark
};

// Parses argv into `out`. Returns the exit code of a run that ends here
// (--precision printed: 0; --count without --variant or the other way
// round: 2, said on stderr), else -1.
inline int parseWorldBenchArgs(const char* program, int argc, char** argv, WorldBenchArgs& out) {
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--markdown=", 11) == 0) {
      out.markdown = argv[i] + 11;
    } else if (std::strncmp(argv[i], "--count=", 8) == 0) {
      out.count = argv[i] + 8;
    } else if (std::strncmp(argv[i], "--variant=", 10) == 0) {
      out.variant = argv[i] + 10;
    } else if (std::strcmp(argv[i], "--precision") == 0) {
      std::printf("%s\n", sizeof(btScalar) == 8 ? "double" : "float");
      return 0;
    } else {
      out.benchmarkArgs.push_back(argv[i]);
    }
  }
  if (out.count.empty() != out.variant.empty()) {
    std::fprintf(stderr, "%s: --count and --variant go together\n", program);
    return 2;
  }
  return -1;
}

}  // namespace patchspin::bench
