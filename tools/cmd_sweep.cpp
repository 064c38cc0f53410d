// patchspin sweep: number and types of the limit directions over a range of
// the force F (along x) or over the (F, T) plane (T: couple about x, parallel
// to F) -- the data behind the paper's Fig. 11 and Fig. 13 -- and the limit
// cycles of the fast dynamics at each point (limit_cycles.hpp). Where the
// number of attracting cycles changes between neighbouring forces of a row,
// the bifurcation is located and classified (cycle_bifurcation.hpp). CSV
// (the bifurcations as text beside it) or --json.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <patchspin/analysis.hpp>
#include <patchspin/cycle_bifurcation.hpp>
#include <sstream>
#include <thread>

#include "tool_common.hpp"

namespace patchspin::tool {

// cmd_limits.cpp
std::function<FlatBody()> addBodyOptions(CLI::App* cmd, bool withLoads);
nlohmann::json limitsToJson(const LimitAnalysis& a);
nlohmann::json cyclesToJson(const CycleAnalysis& c, int seeds);

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
  int threads = 0, seeds = 300, cycleSeeds = 16;
  bool scaled = false, quiet = false, json = false;
};

// One grid point: its fixed points and cycles.
struct Point {
  double F = 0.0, T = 0.0;  // in the sweep's units
  LimitAnalysis fixed;
  CycleAnalysis cycles;
};

int attractingCycles(const CycleAnalysis& c) {
  int n = 0;
  for (const LimitCycle& y : c.cycles) n += y.attracting;
  return n;
}

// One entry per cycle, '|'-separated: "attracting|repelling period multiplier
// turn_per_decade_deg w1min w1max w2min w2max w3min w3max angle_min angle_max",
// the ranges over its orbit, angle = atan2(w3, w1) [deg] (the bifurcation
// plot's default axis; a cycle crossing w3 = 0 at w1 < 0 wraps it)
std::string cycleCells(const CycleAnalysis& c) {
  int attracting = 0;
  std::ostringstream list;
  list.precision(9);
  for (const LimitCycle& y : c.cycles) {
    attracting += y.attracting;
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    double angleLo = 1e9, angleHi = -1e9;
    for (const Vec3& w : y.orbit) {
      lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
      const double angle = std::atan2(w.z(), w.x()) * 180.0 / M_PI;
      angleLo = std::min(angleLo, angle), angleHi = std::max(angleHi, angle);
    }
    // w3's extremes between the samples (limit_cycles.hpp)
    lo.z() = y.w3Min, hi.z() = y.w3Max;
    if (list.tellp() > 0) list << '|';
    list << (y.attracting ? "attracting" : "repelling") << ' ' << y.period << ' ' << y.multiplier
         << ' ' << y.turnPerDecade * 180.0 / M_PI;
    for (int k = 0; k < 3; ++k) list << ' ' << lo[k] << ' ' << hi[k];
    list << ' ' << angleLo << ' ' << angleHi;
  }
  std::ostringstream row;
  row << ',' << attracting << ',' << c.cycles.size() - static_cast<std::size_t>(attracting) << ','
      << (c.searched ? (c.complete() ? "1" : "0") : "") << ",\"" << list.str() << '"';
  return row.str();
}

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
      << (a.indexConsistent ? 1 : 0) << ",\"" << dirs.str() << '"';
  return row.str();
}

// Runs job(k) for k = 0 .. total-1 on `threads` workers; the first error is
// rethrown. Progress on stderr unless quiet.
void parallelFor(int total, int threads, bool quiet, const char* what,
                 const std::function<void(int)>& job) {
  std::atomic<int> next{0}, done{0};
  std::mutex errorMutex;
  std::string firstError;
  auto worker = [&] {
    for (int k = next++; k < total; k = next++) {
      try {
        job(k);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (firstError.empty()) firstError = e.what();
      }
      ++done;
    }
  };
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min(threads, total));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  while (!quiet && done.load() < total) {
    std::fprintf(stderr, "\rsweep: %d/%d %s (%d%%)", done.load(), total, what,
                 100 * done.load() / total);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  for (std::thread& t : pool) t.join();
  if (!quiet && total > 0) std::fprintf(stderr, "\rsweep: %d/%d %s (100%%)\n", total, total, what);
  if (!firstError.empty()) throw Error(firstError);
}

// A change of the number of attracting cycles between neighbouring forces
// of one row: the bifurcation of one cycle (each cycle of the side with
// more, located apart: mirror-image cycles give the same force).
struct Change {
  int with = 0, without = 0;  // grid indices
  double T = 0.0;             // the row's couple (sweep units)
  const LimitCycle* cycle = nullptr;
  CycleBifurcation result;
};

void printBifurcations(std::FILE* to, const std::vector<Change>& changes, double fUnit,
                       const char* unit) {
  if (changes.empty()) return;
  std::fprintf(to, "cycle bifurcations (located to 1e-5 mu m g):\n");
  for (const Change& c : changes) {
    const CycleBifurcation& b = c.result;
    std::fprintf(to, "  T = %g: the attracting cycle w3 in [%+.4f, %+.4f] ", c.T, c.cycle->w3Min,
                 c.cycle->w3Max);
    std::fprintf(to, "%s between F = %.6g and %.6g %s: ",
                 b.withCycle < b.withoutCycle ? "dies (F growing)" : "is born (F growing)",
                 b.withCycle / fUnit, b.withoutCycle / fUnit, unit);
    if (b.kind == CycleBifurcation::Unclassified) {
      std::fprintf(to, "unclassified (no node born on its track): not located\n");
      continue;
    }
    std::fprintf(to,
                 "%s at F* = %.7f +- %.1e %s\n"
                 "    node and saddle born at w = (%+.4f, %+.4f, %+.4f), %.1e from the cycle; at "
                 "separation %.2g their eigenvalues %.3g, %+.3g m/s^2 -> 0\n",
                 toString(b.kind), b.force / fUnit, b.forceError / fUnit, unit, b.point.x(),
                 b.point.y(), b.point.z(), b.distanceToCycle, b.pairSeparation, b.nodeEigenvalue,
                 b.saddleEigenvalue);
    for (const CycleBifurcation::Sample& s : b.approach) {
      std::fprintf(to,
                   "    F = %.6g: period %.5g s^2/m (x |F - F*|^1/2 = %.4g), w3 in [%+.4f, %+.4f], "
                   "multiplier %.2g\n",
                   s.force / fUnit, s.period,
                   s.period * std::sqrt(std::abs(s.force - b.force) / fUnit), s.w3Min, s.w3Max,
                   s.multiplier);
    }
  }
}

void run(const SweepArgs& a, const FlatBody& base) {
  const Model law = modelFromString(a.model);
  const Range F = parseRange(a.F, "--F"), T = parseRange(a.T, "--T");
  if (a.cycleSeeds != 0 && a.cycleSeeds < 2)
    throw UsageError("--cycle-seeds must be 0 (no search) or at least 2");
  const int total = F.n * T.n;
  // scaled: F in units of mu m g, T in units of m g L (L: patch extent from O)
  const double fUnit = a.scaled ? base.mu * base.mass * base.g : 1.0;
  const double tUnit = a.scaled ? base.mass * base.g * base.shape.maxDistanceFromOrigin() : 1.0;
  auto bodyAt = [&](double force, double torque) {
    FlatBody body = base;
    body.force.x() = force;
    body.torque.x() = torque;
    return body;
  };
  std::vector<Point> points(static_cast<std::size_t>(total));
  parallelFor(total, a.threads, a.quiet, "points", [&](int k) {
    const int i = k / T.n, j = k % T.n;
    Point& p = points[static_cast<std::size_t>(k)];
    p.F = F.at(i), p.T = T.at(j);
    const FlatBodyModel model(bodyAt(p.F * fUnit, p.T * tUnit), law);
    LimitOptions options;
    options.seeds = a.seeds;
    p.fixed = findLimitDirections(model, options);
    if (a.cycleSeeds > 0) {
      CycleOptions cycleOptions;
      cycleOptions.seeds = a.cycleSeeds;
      p.cycles = findLimitCycles(model, p.fixed, cycleOptions);
    }
  });

  // changes of the attracting-cycle count along F, in each row of T
  std::vector<Change> changes;
  for (int j = 0; j < T.n && a.cycleSeeds > 0; ++j) {
    for (int i = 0; i + 1 < F.n; ++i) {
      const int k0 = i * T.n + j, k1 = (i + 1) * T.n + j;
      const int n0 = attractingCycles(points[static_cast<std::size_t>(k0)].cycles);
      const int n1 = attractingCycles(points[static_cast<std::size_t>(k1)].cycles);
      if (n0 == n1) continue;
      const int with = n0 > n1 ? k0 : k1, without = n0 > n1 ? k1 : k0;
      // each attracting cycle of the side with more that has no counterpart
      // (an attracting cycle through a point near its orbit) on the other
      const CycleAnalysis& other = points[static_cast<std::size_t>(without)].cycles;
      for (const LimitCycle& y : points[static_cast<std::size_t>(with)].cycles.cycles) {
        bool persists = false;
        for (const LimitCycle& z : other.cycles) {
          for (const Vec3& w : y.orbit)
            persists = persists || (z.attracting && (z.point - w).norm() < 0.05);
        }
        if (y.attracting && !persists)
          changes.push_back(
              {with, without, points[static_cast<std::size_t>(with)].T, &y, CycleBifurcation()});
      }
    }
  }
  const double mumg = base.mu * base.mass * base.g;
  parallelFor(static_cast<int>(changes.size()), a.threads, a.quiet, "cycle bifurcations",
              [&](int k) {
                Change& c = changes[static_cast<std::size_t>(k)];
                const Point& p = points[static_cast<std::size_t>(c.with)];
                const Point& q = points[static_cast<std::size_t>(c.without)];
                // a failure here (e.g. a body that tips inside the bracket) leaves
                // this change unclassified rather than failing the sweep
                c.result.withCycle = p.F * fUnit, c.result.withoutCycle = q.F * fUnit;
                c.result.force = 0.5 * (p.F + q.F) * fUnit;
                try {
                  c.result = locateCycleBifurcation(bodyAt(0.0, p.T * tUnit), law, p.F * fUnit,
                                                    q.F * fUnit, *c.cycle, 1e-5 * mumg,
                                                    {1e-2 * mumg, 3e-3 * mumg, 1e-3 * mumg});
                } catch (const Error&) {
                }
              });

  std::ofstream file;
  if (!a.out.empty()) {
    file.open(a.out);
    if (!file) throw UsageError("--out: cannot write '" + a.out + "'");
  }
  std::ostream& out = a.out.empty() ? std::cout : file;
  if (a.json) {
    nlohmann::json j = {{"points", nlohmann::json::array()},
                        {"cycle_bifurcations", nlohmann::json::array()}};
    for (const Point& p : points) {
      nlohmann::json point = limitsToJson(p.fixed);
      if (a.cycleSeeds > 0) point.update(cyclesToJson(p.cycles, a.cycleSeeds));
      point["F"] = p.F;
      point["T"] = p.T;
      j["points"].push_back(point);
    }
    for (const Change& c : changes) {
      const CycleBifurcation& b = c.result;
      nlohmann::json approach = nlohmann::json::array();
      for (const CycleBifurcation::Sample& s : b.approach) {
        approach.push_back({{"F", s.force / fUnit},
                            {"period", s.period},
                            {"w3", {s.w3Min, s.w3Max}},
                            {"multiplier", s.multiplier}});
      }
      j["cycle_bifurcations"].push_back(
          {{"T", c.T},
           {"cycle_w3", {c.cycle->w3Min, c.cycle->w3Max}},
           {"F_with_cycle", b.withCycle / fUnit},
           {"F_without_cycle", b.withoutCycle / fUnit},
           {"kind", b.kind == CycleBifurcation::SaddleNodeOnCycle ? "saddle_node_on_cycle"
                                                                  : "unclassified"},
           {"located", b.kind != CycleBifurcation::Unclassified},
           {"F", b.force / fUnit},
           {"F_error", b.forceError / fUnit},
           {"point", {b.point.x(), b.point.y(), b.point.z()}},
           {"pair_separation", b.pairSeparation},
           {"node_eigenvalue", b.nodeEigenvalue},
           {"saddle_eigenvalue", b.saddleEigenvalue},
           {"distance_to_cycle", b.distanceToCycle},
           {"approach", approach}});
    }
    out << j.dump(2) << "\n";
    return;
  }
  out << "F,T,n_directions,n_attracting,n_attracting_dominant,n_dominant,n_isolated,n_saddle,n_"
         "nonhyperbolic,"
         "n_continua,tipping,index_consistent,directions";
  if (a.cycleSeeds > 0) out << ",n_cycles_attracting,n_cycles_repelling,cycles_complete,cycles";
  out << "\n";
  for (const Point& p : points) {
    out << csvRow(p.F, p.T, p.fixed);
    if (a.cycleSeeds > 0) out << cycleCells(p.cycles);
    out << "\n";
  }
  // the located bifurcations as text: on stdout beside a CSV file, else on stderr
  printBifurcations(a.out.empty() ? stderr : stdout, changes, fUnit, a.scaled ? "mu m g" : "N");
}

const RegisterCommand registration([](CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Number and types of limit directions and limit cycles over F (along x) or the (F, T) "
      "plane (T about x), and where cycles are born or die; CSV or JSON");
  auto body = addBodyOptions(cmd, false);
  cmd->add_option("--model", a->model, "ellipsoidal | exact");
  cmd->add_option("--F", a->F, "A:B:N  force along x [N] (or [mu m g] with --scaled)")->required();
  cmd->add_option("--T", a->T, "A:B:N  couple about x [N m] (or [m g L] with --scaled); default 0");
  cmd->add_flag("--scaled", a->scaled,
                "F in units of mu m g, T in units of m g L (L: farthest patch point from O)");
  cmd->add_option("--threads", a->threads, "worker threads (default: all cores)");
  cmd->add_option("--seeds", a->seeds, "seed points of the sphere solver for Pi(w) (default 300)");
  cmd->add_option("--cycle-seeds", a->cycleSeeds,
                  "seeds of the limit-cycle search at each point (default 16; 0: no cycles, no "
                  "bifurcations)");
  cmd->add_flag("--json", a->json,
                "print one JSON object {points: [limits --json of each point, with F, T], "
                "cycle_bifurcations}");
  cmd->add_option("--out", a->out, "CSV (or JSON) file (default: standard output)");
  cmd->add_flag("--quiet", a->quiet, "no progress indicator");
  cmd->callback([a, body] { run(*a, body()); });
});

}  // namespace
}  // namespace patchspin::tool
