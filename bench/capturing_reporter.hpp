// Google Benchmark's console table, with every finished repetition (not
// the aggregates, not a failed run) also handed to the program, which
// builds its own summary tables from them after the run.
#pragma once

#include <benchmark/benchmark.h>

#include <unistd.h>
#include <functional>
#include <utility>
#include <vector>

namespace patchspin::bench {

class CapturingReporter : public benchmark::ConsoleReporter {
 public:
  using OnRun = std::function<void(const Run&)>;
  explicit CapturingReporter(OnRun onRun)
      : ConsoleReporter(isatty(1) ? OO_ColorTabular : OO_Tabular), onRun_(std::move(onRun)) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs)
      if (r.run_type == Run::RT_Iteration && !r.error_occurred) onRun_(r);
    ConsoleReporter::ReportRuns(runs);
  }

 private:
  OnRun onRun_;
};

}  // namespace patchspin::bench
