// patchspin limits: all limit directions of a flat body on a plane, their
// rate R* and type (Sect. 3.3, 5.5-5.6). Also exports the body options and
// the JSON forms of an analysis and of its cycles to `patchspin sweep`
// (cmd_sweep.cpp).
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <patchspin/analysis.hpp>
#include <patchspin/limit_cycles.hpp>

#include "tool_common.hpp"

namespace patchspin::tool {

namespace {

struct BodyArgs {
  std::string patch, inertia, com = "0,0,0", force = "0,0", torque = "0,0,0";
  double mass = 1.0, mu = 0.3, g = 9.81, rho = 0.0;
};

FlatBody makeBody(const BodyArgs& a) {
  FlatBody body;
  body.shape = parsePatch(a.patch);
  body.mass = a.mass;
  if (!(a.mass > 0.0) || !std::isfinite(a.mass)) throw UsageError("--mass must be positive");
  if (!(a.g > 0.0) || !std::isfinite(a.g)) throw UsageError("--g must be positive");
  if (!(a.mu >= 0.0) || !std::isfinite(a.mu)) throw UsageError("--mu must be >= 0");
  if (a.rho < 0.0 || !std::isfinite(a.rho)) throw UsageError("--rho must be positive");
  const auto J = parseNumbers(a.inertia, "--inertia");
  if (J.size() != 1 && J.size() != 3) throw UsageError("--inertia needs Jz or Jz,Jxz,Jyz");
  if (!(J[0] > 0.0)) throw UsageError("--inertia: Jz must be positive");
  body.Jz = J[0];
  if (J.size() == 3) body.Jxz = J[1], body.Jyz = J[2];
  const auto c = parseNumbers(a.com, "--com", 3);
  body.com = Vec3(c[0], c[1], c[2]);
  const auto f = parseNumbers(a.force, "--force", 2);
  body.force = Vec2(f[0], f[1]);
  const auto t = parseNumbers(a.torque, "--torque", 3);
  body.torque = Vec3(t[0], t[1], t[2]);
  body.mu = a.mu;
  body.g = a.g;
  body.rho = a.rho;
  return body;
}

nlohmann::json vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

// Adds the flat-body options to `cmd`; the returned function builds the body
// once the command line is parsed. withLoads: also --force and --torque.
std::function<FlatBody()> addBodyOptions(CLI::App* cmd, bool withLoads) {
  auto a = std::make_shared<BodyArgs>();
  cmd->add_option(
         "--patch", a->patch,
         "disk:R | rect:LX,LY | poly:x1,y1,x2,y2,... | cut:R,D | lens:R1,R2,D  [m], patch frame")
      ->required();
  cmd->add_option("--mass", a->mass, "mass m [kg]")->required();
  cmd->add_option("--inertia", a->inertia,
                  "Jz[,Jxz,Jyz] about the centre of mass [kg m^2]; L = w_z (Jxz, Jyz, Jz)")
      ->required();
  cmd->add_option("--com", a->com,
                  "xc,yc,zc: centre of mass in the patch frame [m] (default 0,0,0)");
  cmd->add_option("--mu", a->mu, "friction coefficient (default 0.3)");
  cmd->add_option("--g", a->g,
                  "gravity [m/s^2] (default 9.81); the normal force is -m g at the centre of mass");
  if (withLoads) {
    cmd->add_option("--force", a->force, "Fx,Fy: horizontal force at the centre of mass [N]");
    cmd->add_option("--torque", a->torque, "Tx,Ty,Tz: external couple [N m]");
  }
  cmd->add_option("--rho", a->rho, "length scale rho of x_o [m] (default Eq. (11) about O)");
  return [a] { return makeBody(*a); };
}

nlohmann::json limitsToJson(const LimitAnalysis& a) {
  nlohmann::json out;
  out["limit_directions"] = nlohmann::json::array();
  for (const LimitDirection& d : a.directions) {
    out["limit_directions"].push_back({{"w", vec(d.w)},
                                       {"rdot", d.rdot},
                                       {"attracting", d.attracting},
                                       {"type", toString(d.type)},
                                       {"eigenvalues",
                                        {{d.eigenvalues[0].real(), d.eigenvalues[0].imag()},
                                         {d.eigenvalues[1].real(), d.eigenvalues[1].imag()}}},
                                       {"min_pressure", d.minPressure}});
  }
  if (a.continua.empty()) {
    out["continuum"] = nullptr;
  } else {
    // a circle {normal . w = offset} on the sphere (Prop. 3), or the whole sphere
    nlohmann::json sets = nlohmann::json::array();
    for (const LimitContinuum& c : a.continua) {
      if (c.sphere) {
        sets.push_back({{"kind", "sphere"}, {"rdot", c.rdot}, {"attracting", c.attracting}});
      } else {
        sets.push_back({{"kind", "circle"},
                        {"normal", vec(c.normal)},
                        {"offset", c.offset},
                        {"centre", vec(c.centre())},
                        {"radius", c.radius()},
                        {"rdot", c.rdot},
                        {"attracting", c.attracting}});
      }
    }
    out["continuum"] = {{"sets", sets}};
  }
  out["tipping"] = a.tipping;
  return out;
}

namespace {

// +inf (a cycle crossing w3 = 0) as JSON null
nlohmann::json finiteOrNull(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

}  // namespace

// The periodic orbits of the fast dynamics and where each seed ended (also
// used by `patchspin sweep --json`).
nlohmann::json cyclesToJson(const CycleAnalysis& c, int seeds) {
  nlohmann::json cycles = nlohmann::json::array();
  for (const LimitCycle& y : c.cycles) {
    cycles.push_back({{"point", vec(y.point)},
                      {"period", y.period},
                      {"multiplier", y.multiplier},
                      {"return_map_slope", y.returnMapSlope},
                      {"attracting", y.attracting},
                      {"w3", {y.w3Min, y.w3Max}},
                      {"slip_ratio", {finiteOrNull(y.slipRatioMin), finiteOrNull(y.slipRatioMax)}},
                      {"mean_rdot", y.meanRdot},
                      {"turn", y.turn},
                      {"turn_per_decade", y.turnPerDecade}});
  }
  auto ends = [](const std::vector<SeedEnd>& list, const std::vector<Vec3>& unresolved) {
    int fixed = 0, cycle = 0, continuum = 0;
    for (const SeedEnd& e : list) {
      fixed += e.kind == SeedEnd::FixedPoint ? 1 : 0;
      cycle += e.kind == SeedEnd::Cycle ? 1 : 0;
      continuum += e.kind == SeedEnd::Continuum ? 1 : 0;
    }
    nlohmann::json none = nlohmann::json::array();
    for (const Vec3& w : unresolved) none.push_back(vec(w));
    return nlohmann::json{
        {"fixed_point", fixed}, {"cycle", cycle}, {"continuum", continuum}, {"unresolved", none}};
  };
  return {{"limit_cycles", cycles},
          {"cycle_search",
           {{"seeds", seeds},
            {"forward", ends(c.forward, c.unresolvedForward)},
            {"backward", ends(c.backward, c.unresolvedBackward)},
            {"complete", c.complete()},
            {"searched", c.searched}}}};
}

namespace {

void printCycles(const CycleAnalysis& c, int seeds) {
  std::printf(
      "\nlimit cycles of the fast dynamics w' = V*(w), Eq. (27) (%d seeds, forward and "
      "backward in the fast time tau, dt = r dtau):\n",
      seeds);
  if (!c.searched) {
    std::printf("no search: every direction is a fixed point (or F_o = 0)\n");
    return;
  }
  if (c.cycles.empty()) std::printf("none\n");
  for (const LimitCycle& y : c.cycles) {
    const double deg = 180.0 / M_PI;
    std::printf(
        "%-10s T = %.6g s^2/m, multiplier %.3g, w3 in [%+.6f, %+.6f], v/(R w) in [%.5g, %.5g], "
        "mean R* = %.6g m/s^2\n"
        "           velocity direction turns %+.4g deg per period, %+.4g deg per decade of slip "
        "(%s)\n",
        y.attracting ? "attracting" : "repelling", y.period, y.multiplier, y.w3Min, y.w3Max,
        y.slipRatioMin, y.slipRatioMax, y.meanRdot, y.turn * deg, y.turnPerDecade * deg,
        y.turnPerDecade < 0.0 ? "clockwise" : "counter-clockwise");
  }
  auto report = [](const char* dir, const char* what, const std::vector<SeedEnd>& list,
                   const std::vector<Vec3>& unresolved) {
    int fixed = 0, cycle = 0, continuum = 0;
    for (const SeedEnd& e : list) {
      fixed += e.kind == SeedEnd::FixedPoint ? 1 : 0;
      cycle += e.kind == SeedEnd::Cycle ? 1 : 0;
      continuum += e.kind == SeedEnd::Continuum ? 1 : 0;
    }
    std::printf("%s: %d seeds end at a fixed point, %d on a cycle", dir, fixed, cycle);
    if (continuum > 0) std::printf(", %d on a continuum", continuum);
    if (unresolved.empty()) {
      std::printf("\n");
      return;
    }
    std::printf("; %zu reach no %s within the budget:\n", unresolved.size(), what);
    for (const Vec3& w : unresolved)
      std::printf("  seed (%+.6f, %+.6f, %+.6f)\n", w.x(), w.y(), w.z());
  };
  report("forward ", "attractor", c.forward, c.unresolvedForward);
  if (!c.backward.empty()) report("backward", "repeller", c.backward, c.unresolvedBackward);
  if (!c.complete())
    std::printf("\nwarning: the search is incomplete: how those seeds' bodies stop is not known\n");
}

struct LimitsArgs {
  std::string model = "ellipsoidal";
  bool json = false;
  int seeds = 600;
  int cycleSeeds = 64;
};

void run(const LimitsArgs& a, const FlatBody& body) {
  const Model law = modelFromString(a.model);
  if (a.seeds < 20) throw UsageError("--seeds must be at least 20");
  const FlatBodyModel model(body, law);
  LimitOptions options;
  options.seeds = a.seeds;
  const LimitAnalysis an = findLimitDirections(model, options);
  if (a.cycleSeeds != 0 && a.cycleSeeds < 2)
    throw UsageError("--cycle-seeds must be 0 (no search) or at least 2");
  CycleOptions cycleOptions;
  cycleOptions.seeds = a.cycleSeeds;
  const CycleAnalysis cycles =
      a.cycleSeeds > 0 ? findLimitCycles(model, an, cycleOptions) : CycleAnalysis();
  if (a.json) {
    nlohmann::json out = limitsToJson(an);
    if (a.cycleSeeds > 0) {
      out.update(cyclesToJson(cycles, a.cycleSeeds));
    } else {
      out["limit_cycles"] = nullptr;
      out["cycle_search"] = nullptr;
    }
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("body      %s, m = %g kg, Jz = %g kg m^2, r_c = (%g, %g, %g) m\n",
              body.shape.describe().c_str(), body.mass, body.Jz, body.com.x(), body.com.y(),
              body.com.z());
  std::printf(
      "model     %s, mu = %g, rho = %.6g m; %s\n", toString(law), body.mu, model.rho(),
      an.linear ? "linear Pi: eigenproblem (111)" : "Pi(w): Newton on the sphere from a seed grid");
  std::printf("\n%-38s %12s  %-10s %-14s %s\n", "w = (u_x, u_y, rho w_z)/r", "R* [m/s^2]", "",
              "type", "eigenvalues of (31) [1/s]");
  auto complexText = [](std::complex<double> z) {
    char buf[64];
    if (z.imag() == 0.0) {
      std::snprintf(buf, sizeof buf, "%.6g", z.real());
    } else {
      std::snprintf(buf, sizeof buf, "%.6g%+.6gi", z.real(), z.imag());
    }
    return std::string(buf);
  };
  for (const LimitDirection& d : an.directions) {
    std::printf("(%+.6f, %+.6f, %+.6f)  %12.6g  %-10s %-14s %s, %s\n", d.w.x(), d.w.y(), d.w.z(),
                d.rdot, d.attracting ? "attracting" : "repelling", toString(d.type),
                complexText(d.eigenvalues[0]).c_str(), complexText(d.eigenvalues[1]).c_str());
  }
  for (const LimitContinuum& c : an.continua) {
    if (c.sphere) {
      std::printf("continuum: every direction, R* = %.6g m/s^2\n", c.rdot);
    } else {
      std::printf(
          "continuum: circle n.w = %.6f, n = (%+.6f, %+.6f, %+.6f), radius %.6f, R* = %.6g m/s^2 "
          "(%s)\n",
          c.offset, c.normal.x(), c.normal.y(), c.normal.z(), c.radius(), c.rdot,
          c.attracting ? "attracting" : "repelling");
    }
  }
  if (an.tipping)
    std::printf("\nwarning: the pressure turns negative on the patch (the body would tip)\n");
  if (!an.indexConsistent)
    std::printf("\nwarning: the index sum is not 2: a limit direction may be missing\n");
  if (a.cycleSeeds > 0) printCycles(cycles, a.cycleSeeds);
}

const RegisterCommand registration([](CLI::App& app) {
  auto args = std::make_shared<LimitsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "limits", "Limit directions of a flat body on a plane (Sect. 5, Eq. (106))");
  auto body = addBodyOptions(cmd, true);
  cmd->add_option("--model", args->model, "ellipsoidal (Eq. 41) | exact (Eq. 16)");
  cmd->add_option("--seeds", args->seeds,
                  "seed points of the sphere solver for Pi(w) (default 600)");
  cmd->add_option("--cycle-seeds", args->cycleSeeds,
                  "seeds of the limit-cycle search, each integrated forward and backward in the "
                  "fast time (default 64; 0: no search)");
  cmd->add_flag("--json", args->json,
                "print one JSON object {limit_directions, continuum, tipping, limit_cycles, "
                "cycle_search}");
  cmd->callback([args, body] { run(*args, body()); });
});

}  // namespace
}  // namespace patchspin::tool
