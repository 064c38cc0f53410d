// patchspin sweep: number and types of the limit directions over a range of
// the force F (along x) or over the (F, T) plane (T: couple about x, parallel
// to F) -- the data behind the paper's Fig. 11 and Fig. 13. CSV output.
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <patchspin/analysis.hpp>
#include <sstream>
#include <thread>

#include "tool_common.hpp"

namespace patchspin::tool {

// cmd_limits.cpp
std::function<FlatBody()> addBodyOptions(CLI::App* cmd, bool withLoads);

namespace {

struct Range {
  double lo = 0.0, hi = 0.0;
  int n = 1;
  double at(int i) const { return n == 1 ? lo : lo + (hi - lo) * i / (n - 1); }
};

// "a:b:n" -> n points from a to b; "a" -> one point.
Range parseRange(const std::string& text, const char* what) {
  Range r;
  std::vector<std::string> parts;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ':')) parts.push_back(item);
  if (parts.size() == 1) {
    r.lo = r.hi = parseNumbers(parts[0], what, 1)[0];
    return r;
  }
  if (parts.size() != 3)
    throw UsageError(std::string(what) + " must be A:B:N or A: got '" + text + "'");
  r.lo = parseNumbers(parts[0], what, 1)[0];
  r.hi = parseNumbers(parts[1], what, 1)[0];
  const double n = parseNumbers(parts[2], what, 1)[0];
  if (!(n >= 1.0 && n <= 1e6) || n != std::floor(n))
    throw UsageError(std::string(what) + ": N must be 1..1e6");
  r.n = static_cast<int>(n);
  return r;
}

struct SweepArgs {
  std::string model = "ellipsoidal", F = "0", T = "0", out;
  int threads = 0, seeds = 300;
  bool scaled = false, quiet = false;
};

std::string csvRow(double F, double T, const LimitAnalysis& a) {
  int attracting = 0, dominant = 0, isolated = 0, saddle = 0, nonhyperbolic = 0,
      attractingDominant = 0;
  std::ostringstream dirs;
  dirs.precision(9);
  for (const LimitDirection& d : a.directions) {
    attracting += d.attracting;
    dominant += d.type == LimitType::Dominant;
    isolated += d.type == LimitType::Isolated;
    saddle += d.type == LimitType::Saddle;
    nonhyperbolic += d.type == LimitType::Nonhyperbolic;
    attractingDominant += d.attracting && d.type == LimitType::Dominant;
    if (dirs.tellp() > 0) dirs << '|';
    dirs << d.w.x() << ' ' << d.w.y() << ' ' << d.w.z() << ' ' << d.rdot << ' '
         << (d.attracting ? "attracting" : "repelling") << ' ' << toString(d.type);
  }
  std::ostringstream row;
  row.precision(12);
  row << F << ',' << T << ',' << a.directions.size() << ',' << attracting << ','
      << attractingDominant << ',' << dominant << ',' << isolated << ',' << saddle << ','
      << nonhyperbolic << ',' << a.continua.size() << ',' << (a.tipping ? 1 : 0) << ','
      << (a.indexConsistent ? 1 : 0) << ",\"" << dirs.str() << "\"\n";
  return row.str();
}

void run(const SweepArgs& a, const FlatBody& base) {
  const Model law = modelFromString(a.model);
  const Range F = parseRange(a.F, "--F"), T = parseRange(a.T, "--T");
  const int total = F.n * T.n;
  // scaled: F in units of mu m g, T in units of m g L (L: patch extent from O)
  const double fUnit = a.scaled ? base.mu * base.mass * base.g : 1.0;
  const double tUnit = a.scaled ? base.mass * base.g * base.shape.maxDistanceFromOrigin() : 1.0;
  std::vector<std::string> rows(static_cast<std::size_t>(total));
  std::atomic<int> next{0}, done{0};
  std::mutex errorMutex;
  std::string firstError;
  auto worker = [&] {
    for (int k = next++; k < total; k = next++) {
      const int i = k / T.n, j = k % T.n;
      FlatBody body = base;
      body.force.x() = F.at(i) * fUnit;
      body.torque.x() = T.at(j) * tUnit;
      try {
        LimitOptions options;
        options.seeds = a.seeds;
        rows[static_cast<std::size_t>(k)] =
            csvRow(F.at(i), T.at(j), findLimitDirections(FlatBodyModel(body, law), options));
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (firstError.empty()) firstError = e.what();
      }
      ++done;
    }
  };
  int threads = a.threads > 0 ? a.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min(threads, total));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  // progress on stderr while the workers run
  while (!a.quiet && done.load() < total) {
    std::fprintf(stderr, "\rsweep: %d/%d points (%d%%)", done.load(), total,
                 100 * done.load() / total);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  for (std::thread& t : pool) t.join();
  if (!a.quiet) std::fprintf(stderr, "\rsweep: %d/%d points (100%%)\n", total, total);
  if (!firstError.empty()) throw Error(firstError);

  std::ofstream file;
  if (!a.out.empty()) {
    file.open(a.out);
    if (!file) throw UsageError("--out: cannot write '" + a.out + "'");
  }
  std::ostream& out = a.out.empty() ? std::cout : file;
  out << "F,T,n_directions,n_attracting,n_attracting_dominant,n_dominant,n_isolated,n_saddle,n_"
         "nonhyperbolic,"
         "n_continua,tipping,index_consistent,directions\n";
  for (const std::string& row : rows) out << row;
}

const RegisterCommand registration([](CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Number and types of limit directions over F (along x) or the (F, T) plane (T about x); CSV");
  auto body = addBodyOptions(cmd, false);
  cmd->add_option("--model", a->model, "ellipsoidal | exact");
  cmd->add_option("--F", a->F, "A:B:N  force along x [N] (or [mu m g] with --scaled)")->required();
  cmd->add_option("--T", a->T, "A:B:N  couple about x [N m] (or [m g L] with --scaled); default 0");
  cmd->add_flag("--scaled", a->scaled,
                "F in units of mu m g, T in units of m g L (L: farthest patch point from O)");
  cmd->add_option("--threads", a->threads, "worker threads (default: all cores)");
  cmd->add_option("--seeds", a->seeds, "seed points of the sphere solver for Pi(w) (default 300)");
  cmd->add_option("--out", a->out, "CSV file (default: standard output)");
  cmd->add_flag("--quiet", a->quiet, "no progress indicator");
  cmd->callback([a, body] { run(*a, body()); });
});

}  // namespace
}  // namespace patchspin::tool
