// patchspin simulate: one body sliding and spinning on a plane until it
// sticks, by the reference dynamics (analysis) or by Bullet.
#include <patchspin/analysis.hpp>
#include <patchspin/simulation.hpp>

#include "tool_common.hpp"

#ifdef PATCHSPIN_HAS_BULLET
#include <patchspin/scenes/simulate.hpp>
#endif

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

namespace patchspin::tool {
namespace {

struct SimulateArgs {
  std::string engine = "reference", model = "exact", shape, force = "0,0", v0 = "0,0",
              torque = "0,0,0";
  std::string precision;  // empty: the precision of the Bullet build
  double mass = 1.0, mu = 0.3, g = 9.81, omega0 = 0.0, dt = 1.0 / 240.0, tMax = 10.0,
         recordAt = 0.01;
  bool json = false;
};

SimulationSpec makeSpec(const SimulateArgs& a) {
  SimulationSpec spec;
  if (a.engine != "reference" && a.engine != "bullet") {
    throw UsageError("--engine must be reference or bullet: got '" + a.engine + "'");
  }
  if (a.model != "ellipsoidal" && a.model != "exact" && a.model != "stock") {
    throw UsageError("--model must be ellipsoidal, exact or stock: got '" + a.model + "'");
  }
  if (!a.precision.empty() && a.precision != "float" && a.precision != "double") {
    throw UsageError("--precision must be float or double: got '" + a.precision + "'");
  }
  const auto colon = a.shape.find(':');
  const std::string kind = a.shape.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : a.shape.substr(colon + 1);
  if (kind == "cylinder" && colon != std::string::npos) {
    const auto v = parseNumbers(rest, "--shape cylinder:R,H", 2);
    spec.shape = SimulationSpec::Shape::Cylinder;
    spec.R = v[0];
    spec.H = v[1];
    if (!(spec.R > 0.0 && spec.H > 0.0)) throw UsageError("--shape cylinder:R,H needs R, H > 0");
  } else if (kind == "box" && colon != std::string::npos) {
    const auto v = parseNumbers(rest, "--shape box:LX,LY,LZ", 3);
    spec.shape = SimulationSpec::Shape::Box;
    spec.LX = v[0];
    spec.LY = v[1];
    spec.LZ = v[2];
    if (!(spec.LX > 0.0 && spec.LY > 0.0 && spec.LZ > 0.0))
      throw UsageError("--shape box:LX,LY,LZ needs sizes > 0");
  } else {
    throw UsageError("--shape must be cylinder:R,H or box:LX,LY,LZ: got '" + a.shape + "'");
  }
  spec.engine = a.engine;
  spec.model = a.model;
  spec.precision = a.precision;
#ifdef PATCHSPIN_HAS_BULLET
  if (spec.precision.empty()) spec.precision = scenes::buildPrecision();
#else
  if (spec.precision.empty()) spec.precision = "double";
#endif
  spec.mass = a.mass;
  spec.mu = a.mu;
  spec.g = a.g;
  const auto f = parseNumbers(a.force, "--force", 2);
  spec.force = Vec2(f[0], f[1]);
  const auto v = parseNumbers(a.v0, "--v0", 2);
  spec.v0 = Vec2(v[0], v[1]);
  const auto t = parseNumbers(a.torque, "--torque", 3);
  spec.torque = Vec3(t[0], t[1], t[2]);
  spec.omega0 = a.omega0;
  spec.dt = a.dt;
  spec.tMax = a.tMax;
  spec.recordAt = a.recordAt;
  if (!(spec.mass > 0.0) || !std::isfinite(spec.mass)) throw UsageError("--mass must be positive");
  if (!(spec.mu >= 0.0) || !std::isfinite(spec.mu)) throw UsageError("--mu must be >= 0");
  if (!(spec.g > 0.0) || !std::isfinite(spec.g)) throw UsageError("--g must be positive");
  if (!(spec.dt > 0.0) || !std::isfinite(spec.dt)) throw UsageError("--dt must be positive");
  if (!(spec.tMax > 0.0) || !std::isfinite(spec.tMax)) throw UsageError("--t-max must be positive");
  if (!(spec.recordAt > 0.0 && spec.recordAt < 1.0))
    throw UsageError("--record-at must lie in (0, 1)");
  if (!std::isfinite(spec.omega0)) throw UsageError("--omega0 must be finite");
  return spec;
}

nlohmann::json finiteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

void run(const SimulateArgs& a) {
  const SimulationSpec spec = makeSpec(a);
  SimulationResult result;
  if (spec.engine == "reference") {
    if (spec.model == "stock") {
      throw UsageError("--model stock is Bullet's own friction: it needs --engine bullet");
    }
    result = simulateReference(spec);
  } else {
#ifdef PATCHSPIN_HAS_BULLET
    result = scenes::simulate(spec);
#else
    throw UsageError(
        "--engine bullet: this patchspin was built without Bullet (PATCHSPIN_BUILD_BULLET=OFF)");
#endif
  }
  const bool recorded = result.wStop.norm() > 0.0;
  if (a.json) {
    nlohmann::json out;
    out["stopped"] = result.stopped;
    out["t_stop"] = result.tStop;
    out["w_stop"] = recorded ? nlohmann::json{result.wStop.x(), result.wStop.y(), result.wStop.z()}
                             : nlohmann::json(nullptr);
    out["eps_stop"] = result.epsStop ? finiteOrNull(*result.epsStop) : nlohmann::json(nullptr);
    out["displacement"] = {result.displacement.x(), result.displacement.y()};
    out["rotation"] = result.rotation;
    out["turn"] = result.turn;
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("engine    %s, model %s\n", spec.engine.c_str(), spec.model.c_str());
  std::printf("stopped   %s at t = %.9g s\n", result.stopped ? "yes" : "no (time limit)",
              result.tStop);
  if (recorded) {
    std::printf("w_stop    (%+.6f, %+.6f, %+.6f)   at r = %g r0; x along the force (or v0), z up\n",
                result.wStop.x(), result.wStop.y(), result.wStop.z(), spec.recordAt);
  }
  if (result.epsStop) std::printf("eps_stop  |v|/(R|w|) = %.6g\n", *result.epsStop);
  if (recorded) {
    std::printf(
        "turn      %+.6g deg of the slip velocity's direction until r = %g r0 "
        "(%+.6g deg per decade; + counter-clockwise)\n",
        result.turn * 180.0 / std::acos(-1.0), spec.recordAt,
        result.turn * 180.0 / std::acos(-1.0) / -std::log10(spec.recordAt));
  }
  std::printf("moved     (%.6g, %.6g) m, turned %.6g rad\n", result.displacement.x(),
              result.displacement.y(), result.rotation);
}

const RegisterCommand registration([](CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  CLI::App* cmd =
      app.add_subcommand("simulate", "Slide and spin one body on a plane until it sticks");
  cmd->add_option("--engine", a->engine, "reference (Eq. (93), adaptive) | bullet");
  cmd->add_option("--model", a->model, "ellipsoidal | exact | stock (bullet only)");
  cmd->add_option("--shape", a->shape, "cylinder:R,H | box:LX,LY,LZ [m], standing on its flat face")
      ->required();
  cmd->add_option("--mass", a->mass, "mass [kg] (default 1)");
  cmd->add_option("--mu", a->mu, "friction coefficient (default 0.3)");
  cmd->add_option("--g", a->g, "gravity [m/s^2] (default 9.81)");
  cmd->add_option("--force", a->force,
                  "FX,FY: horizontal force at the centre of mass, ground frame [N]");
  cmd->add_option("--v0", a->v0, "VX,VY: initial velocity [m/s]");
  cmd->add_option("--omega0", a->omega0, "WZ: initial spin [rad/s]");
  cmd->add_option("--torque", a->torque, "TX,TY,TZ: constant couple, ground frame [N m]");
  cmd->add_option("--dt", a->dt, "time step [s] (bullet; reference: trajectory sampling)");
  cmd->add_option("--t-max", a->tMax, "time limit [s] (default 10)");
  cmd->add_option("--record-at", a->recordAt,
                  "record w when r first falls below FRAC r0 (default 0.01)");
  cmd->add_option(
      "--precision", a->precision,
      "float | double (bullet only; default: the precision patchspin::bullet was built with)");
  cmd->add_flag(
      "--json", a->json,
      "print {stopped, t_stop, w_stop, eps_stop, displacement, rotation, turn} as one JSON "
      "object");
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace patchspin::tool
