// patchspin friction: evaluate the ellipsoidal (41) or exact (16) friction law
// of one patch for one slip direction.
#include "tool_common.hpp"

#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

namespace patchspin::tool {
namespace {

struct FrictionArgs {
  std::string patch, model = "exact", loads, pressure, w;
  double hertz = 0.0, mu = 1.0, rho = 0.0;
  bool json = false;
};

void run(const FrictionArgs& a, const CLI::App& cmd) {
  const PatchShape shape = parsePatch(a.patch);
  const Model model = modelFromString(a.model);
  const auto w = parseNumbers(a.w, "--w", 3);
  const Vec3 wv(w[0], w[1], w[2]);
  if (!(wv.norm() > 0.0))
    throw UsageError("--w must be nonzero (w = 0 is sticking: the wrench is set-valued)");
  const int pressureFlags =
      int(cmd.count("--loads")) + int(cmd.count("--pressure")) + int(cmd.count("--hertz"));
  if (pressureFlags > 1) throw UsageError("give at most one of --loads, --pressure, --hertz");
  if (a.rho < 0.0 || !std::isfinite(a.rho)) throw UsageError("--rho must be positive");

  std::unique_ptr<FrictionPatch> patch;
  std::string pressureText;
  if (cmd.count("--hertz")) {
    if (!shape.isDisk()) throw UsageError("--hertz (Eq. (57)) needs a disk patch");
    patch = std::make_unique<FrictionPatch>(shape, HertzPressure{a.hertz}, a.mu, a.rho);
    pressureText = "Hertz (57), Pz = " + std::to_string(a.hertz) + " N";
  } else {
    LinearPressure p = LinearPressure::uniform(shape, 1.0);
    if (cmd.count("--loads")) {
      const auto l = parseNumbers(a.loads, "--loads", 3);
      const PatchLoads loads{l[0], l[1], l[2]};
      if (!isAdmissible(shape, loads)) {
        const PatchLoads near = nearestAdmissibleLoads(shape, loads, shape.defaultRho());
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "--loads not carried by a non-negative pressure (the patch would tip); "
                      "nearest admissible: "
                      "%.6g,%.6g,%.6g",
                      near.Pz, near.Tx, near.Ty);
        throw UsageError(buf);
      }
      p = LinearPressure::fromLoads(shape, loads);
    } else if (cmd.count("--pressure")) {
      const auto c = parseNumbers(a.pressure, "--pressure", 3);
      p = LinearPressure{c[0], c[1], c[2]};
      if (minPressure(shape, p) < 0.0)
        throw UsageError("--pressure is negative somewhere on the patch");
    }
    patch = std::make_unique<FrictionPatch>(shape, p, a.mu, a.rho);
    char buf[160];
    std::snprintf(buf, sizeof buf, "linear p = %.6g + %.6g x + %.6g y  [Pa, Pa/m]", p.p0, p.cx,
                  p.cy);
    pressureText = buf;
  }
  const Vec3 wn = wv.normalized();
  const Vec3 Q = patch->Q(model, wn) + Vec3::Zero();  // + 0: no "-0" in the table
  const Mat3& Pi = patch->Pi();

  if (a.json) {
    nlohmann::json out;
    out["Q"] = {Q[0], Q[1], Q[2]};
    out["Pi"] = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) out["Pi"].push_back({Pi(i, 0), Pi(i, 1), Pi(i, 2)});
    out["rho"] = patch->rho();
    out["Pz"] = patch->Pz();
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("patch     %s\n", shape.describe().c_str());
  std::printf("pressure  %s\n", pressureText.c_str());
  std::printf("model     %s (%s), mu = %g, rho = %.6g m, Pz = %.6g N\n", toString(model),
              model == Model::Exact ? "Coulomb friction integrated over the patch, Eq. (16)"
                                    : "Q = -mu Pz Pi w, Eq. (41)",
              patch->mu(), patch->rho(), patch->Pz());
  std::printf("w         (%.6f, %.6f, %.6f)   slip direction (u_x, u_y, rho w_z) / r\n", wn[0],
              wn[1], wn[2]);
  std::printf("\nfriction wrench about O (patch frame):\n");
  std::printf("  Px      = %14.8g N\n", Q[0]);
  std::printf("  Py      = %14.8g N\n", Q[1]);
  std::printf("  Tz      = %14.8g N m\n", Q[2] * patch->rho());
  std::printf("  Tz/rho  = %14.8g N       (third component of Q)\n", Q[2]);
  std::printf("\nPi of Eq. (40) for this pressure (Q = -mu Pz Pi w in the ellipsoidal model):\n");
  for (int i = 0; i < 3; ++i)
    std::printf("  [%12.8f %12.8f %12.8f]\n", Pi(i, 0), Pi(i, 1), Pi(i, 2));
}

const RegisterCommand registration([](CLI::App& app) {
  auto args = std::make_shared<FrictionArgs>();
  CLI::App* cmd = app.add_subcommand(
      "friction", "Friction wrench Q = (Px, Py, Tz/rho) of a patch for a slip direction w");
  cmd->add_option(
         "--patch", args->patch,
         "disk:R | rect:LX,LY | poly:x1,y1,x2,y2,... | cut:R,D | lens:R1,R2,D  [m], patch frame")
      ->required();
  cmd->add_option("--model", args->model, "ellipsoidal (Eq. 41) | exact (Eq. 16)")
      ->check(CLI::IsMember({"ellipsoidal", "exact"}));
  cmd->add_option("--loads", args->loads,
                  "Pz,Tx,Ty [N, N m]: linear pressure from the loads, Eq. (94)");
  cmd->add_option("--pressure", args->pressure, "p0,cx,cy [Pa, Pa/m]: p = p0 + cx x + cy y");
  cmd->add_option("--hertz", args->hertz, "Pz [N]: Hertz pressure (57) on a disk");
  cmd->add_option("--mu", args->mu, "friction coefficient (default 1)");
  cmd->add_option("--rho", args->rho, "length scale rho [m] (default Eq. (11) about O)");
  cmd->add_option("--w", args->w, "w1,w2,w3: slip direction (normalised by the tool)")->required();
  cmd->add_flag("--json", args->json, "print one JSON object {Q, Pi, rho, Pz}");
  cmd->footer("Without --loads/--pressure/--hertz the pressure is uniform with Pz = 1 N.");
  cmd->callback([args, cmd] { run(*args, *cmd); });
});

}  // namespace
}  // namespace patchspin::tool
