// The clock of the world benchmarks' episodes: CPU time of this thread
// (what the other agents on a shared machine take is not counted), and,
// where valgrind's header is installed, callgrind's instrumentation
// toggles around the same stretch, so that under
// `valgrind --tool=callgrind --instr-atstart=no` the totals are the
// episode's instructions alone (scripts/count_instructions.sh).
#pragma once

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define PATCHSPIN_HAVE_CALLGRIND 1
#else
#define PATCHSPIN_HAVE_CALLGRIND 0
#endif

#include <time.h>

namespace patchspin::bench {

inline double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Times the stretch between start() and stop(); with `countInstructions`,
// callgrind instruments exactly that stretch.
class EpisodeClock {
 public:
  explicit EpisodeClock(bool countInstructions) : count_(countInstructions) {}
  void start() {
#if PATCHSPIN_HAVE_CALLGRIND
    if (count_) CALLGRIND_START_INSTRUMENTATION;
#endif
    t0_ = threadSeconds();
  }
  // Seconds since start().
  double stop() {
    const double s = threadSeconds() - t0_;
#if PATCHSPIN_HAVE_CALLGRIND
    if (count_) CALLGRIND_STOP_INSTRUMENTATION;
#endif
    return s;
  }

 private:
  bool count_;
  double t0_ = 0.0;
};

}  // namespace patchspin::bench
