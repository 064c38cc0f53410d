// disk_torque (issue 5, demo 4): Sect. 6.3, Case 4. A thin disk under a
// constant in-plane force F along +x and an in-plane couple T parallel to it,
// zeta = T / (m g R) (default 0.15), with F below
//   F_crit^{4/6} = mu m g 16 zeta^2 / sqrt(1 + 144 zeta^2)  (0.175 mu m g here).
// One disk per model (ellipsoidal, exact) side by side, each through
// patchspin::scenes::simulate (demo_common.hpp). The couple is physical (as
// Bullet's applyTorque and patchspin::FlatBody::torque; the paper's Eq. (3)
// sign flips T, see analysis.hpp).
#include "demo_common.hpp"
#include "disk_args.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

constexpr unsigned kDiskOptions = demos::kDiskHeight | demos::kDiskV0Angle;

struct Args {
  demos::DiskArgs disk;  // (its defaults: 5 cm, 5 mm, 30 g, mu 0.3, 0.5 m/s at 90 deg, 20 rad/s)
  double zeta = 0.15;    // T / (m g R)
  double force = 0.1;    // F / (mu m g)
};

int run(const Args& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  const demos::DiskArgs& d = a.disk;
  demos::requireDiskArgs(d, kDiskOptions, false);
  const double fCrit = 16 * a.zeta * a.zeta / std::sqrt(1 + 144 * a.zeta * a.zeta);  // / (mu m g)
  demos::DemoConfig config;
  config.name = "disk_torque";
  char title[220];
  std::snprintf(
      title, sizeof title,
      "disk with torque (Sect. 6.3, Case 4) R = %g cm, zeta = T/(mgR) = %g, F = %g mu m g "
      "(F_crit = %.3g mu m g)",
      100 * d.radius, a.zeta, a.force, fCrit);
  config.title = title;
  config.caption =
      "paper (Case 4): force and parallel in-plane torque; see sphere_*.png for the limit "
      "directions";
  for (const std::string& model : demos::modelsToShow(c.model, false)) {
    demos::DemoBody b;
    b.key = model;
    b.label = model;
    b.colour = demos::rowColour(model);
    b.spec = demos::diskSpec(d, model);
    b.spec.force = Vec2(a.force * d.mu * d.mass * d.g, 0.0);
    b.spec.torque = Vec3(a.zeta * d.mass * d.g * d.radius, 0.0, 0.0);
    config.bodies.push_back(b);
  }
  return demos::runDemo(config, c);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  demos::CommonArgs c;
  c.out = "demo-out/disk_torque";
  c.model = "all";
  CLI::App app{
      "disk_torque: a thin disk under an in-plane force and a parallel in-plane torque, Case 4 of "
      "Sect. 6.3; ellipsoidal and exact side by side (headless, PNG frames)"};
  bool noPlot = false, quiet = false;
  demos::addCommonOptions(app, c, &noPlot, &quiet);
  demos::addDiskOptions(app, a.disk, kDiskOptions);
  app.add_option("--zeta", a.zeta, "torque T / (m g R), about +x")->capture_default_str();
  app.add_option("--force", a.force, "force F / (mu m g) along +x")->capture_default_str();
  return demos::runMain(app, argc, argv, "disk_torque", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
