// thick_disk (issue 5, demo 3): Sect. 6.2. A thick disk (centre of mass
// h = H/2 above the patch, default mu h / R = 0.2) pushed by a constant force
// F along +x below the critical force of Eq. (127),
//   F_crit^{2/4} = mu m g / 9 (1 + (4 mu h / R)^2)   (0.182 mu m g here),
// turns away from the force direction as it stops (Fig. 11, right). One disk
// per model (ellipsoidal, exact) side by side, each through
// patchspin::scenes::simulate (demo_common.hpp).
#include "demo_common.hpp"
#include "disk_args.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

struct Args {
  demos::DiskArgs disk = thickDisk();  // its height derived from muHOverR
  double muHOverR = 0.2;               // mu h / R, h = H / 2 [-]
  double force = 0.1;                  // F / (mu m g)
  static demos::DiskArgs thickDisk() {
    demos::DiskArgs d;
    d.mass = 0.3, d.v0 = 0.3, d.omega0 = 15.0;
    return d;
  }
};

int run(const Args& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  if (!(a.muHOverR > 0)) throw CLI::ValidationError("--mu-h-over-r", "must be > 0");
  demos::DiskArgs d = a.disk;
  demos::requireDiskArgs(d, demos::kDiskV0Angle, false);
  const double h = a.muHOverR * d.radius / d.mu;  // centre of mass height [m]
  d.height = 2.0 * h;
  const double fCrit = (1.0 + std::pow(4.0 * a.muHOverR, 2)) / 9.0;  // Eq. (127) / (mu m g)
  demos::DemoConfig config;
  config.name = "thick_disk";
  char title[220];
  std::snprintf(title, sizeof title,
                "thick disk (Sect. 6.2) R = %g cm, H = %.3g cm (mu h/R = %g), F = %g mu m g "
                "(F_crit = %.3g mu m g)",
                100 * d.radius, 200 * h, a.muHOverR, a.force, fCrit);
  config.title = title;
  config.caption =
      "paper: below F_crit the thick disk stops in slip and spin, its path turned away from F";
  for (const std::string& model : demos::modelsToShow(c.model, false)) {
    demos::DemoBody b;
    b.key = model;
    b.label = model;
    b.colour = demos::rowColour(model);
    b.spec = demos::diskSpec(d, model);
    b.spec.force = Vec2(a.force * d.mu * d.mass * d.g, 0.0);
    config.bodies.push_back(b);
  }
  return demos::runDemo(config, c);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  demos::CommonArgs c;
  c.out = "demo-out/thick_disk";
  c.model = "all";
  CLI::App app{
      "thick_disk: a thick disk pushed below the critical force of Eq. (127) turns away from the "
      "force "
      "as it stops; ellipsoidal and exact side by side (headless, PNG frames)"};
  bool noPlot = false, quiet = false;
  demos::addCommonOptions(app, c, &noPlot, &quiet);
  demos::addDiskOptions(app, a.disk, demos::kDiskV0Angle);
  app.add_option("--mu-h-over-r", a.muHOverR, "mu h / R, h = H/2 the height of the centre of mass")
      ->capture_default_str();
  app.add_option("--force", a.force, "force F / (mu m g) along +x")->capture_default_str();
  return demos::runMain(app, argc, argv, "thick_disk", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
