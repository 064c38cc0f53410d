// thick_disk (issue 5, demo 3): Sect. 6.2. A thick disk (centre of mass
// h = H/2 above the patch, default mu h / R = 0.2) pushed by a constant force
// F along +x below the critical force of Eq. (127),
//   F_crit^{2/4} = mu m g / 9 (1 + (4 mu h / R)^2)   (0.182 mu m g here),
// turns away from the force direction as it stops (Fig. 11, right). One disk
// per model (ellipsoidal, exact) side by side, each through
// patchspin::scenes::simulate (demo_common.hpp).
#include "demo_common.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

struct Args {
  double radius = 0.05, muHOverR = 0.2, mass = 0.3, mu = 0.3, v0 = 0.3, v0Angle = 90.0,
         omega0 = 15.0;
  double g = 9.81;
  double force = 0.1;  // F / (mu m g)
};

int run(const Args& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  if (!(a.radius > 0 && a.muHOverR > 0 && a.mass > 0 && a.g > 0 && a.mu > 0))
    throw CLI::ValidationError("parameters", "need radius, mu-h-over-r, mass, g, mu > 0");
  const double h = a.muHOverR * a.radius / a.mu;                     // centre of mass height [m]
  const double fCrit = (1.0 + std::pow(4.0 * a.muHOverR, 2)) / 9.0;  // Eq. (127) / (mu m g)
  demos::DemoConfig config;
  config.name = "thick_disk";
  char title[220];
  std::snprintf(title, sizeof title,
                "thick disk (Sect. 6.2) R = %g cm, H = %.3g cm (mu h/R = %g), F = %g mu m g "
                "(F_crit = %.3g mu m g)",
                100 * a.radius, 200 * h, a.muHOverR, a.force, fCrit);
  config.title = title;
  config.caption =
      "paper: below F_crit the thick disk stops in slip and spin, its path turned away from F";
  const double angle = a.v0Angle * std::acos(-1.0) / 180.0;
  struct M {
    const char* model;
    render::Rgb colour;
  };
  for (const M& m : {M{"ellipsoidal", {0.25, 0.50, 0.90}}, M{"exact", {0.90, 0.60, 0.15}},
                     M{"stock", {0.60, 0.60, 0.62}}}) {
    if (c.model == "all" ? std::string(m.model) == "stock" : c.model != m.model) continue;
    demos::DemoBody b;
    b.key = m.model;
    b.label = m.model;
    b.colour = m.colour;
    SimulationSpec& s = b.spec;
    s.model = m.model;
    s.shape = SimulationSpec::Shape::Cylinder;
    s.R = a.radius;
    s.H = 2.0 * h;
    s.mass = a.mass;
    s.mu = a.mu;
    s.g = a.g;
    s.force = Vec2(a.force * a.mu * a.mass * a.g, 0.0);
    s.v0 = a.v0 * Vec2(std::cos(angle), std::sin(angle));
    s.omega0 = a.omega0;
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
  app.add_option("--radius", a.radius, "disk radius R [m] (default 0.05)");
  app.add_option("--mu-h-over-r", a.muHOverR,
                 "mu h / R, h = H/2 the height of the centre of mass (default 0.2)");
  app.add_option("--mass", a.mass, "mass [kg] (default 0.3)");
  app.add_option("--mu", a.mu, "friction coefficient (default 0.3)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  app.add_option("--v0", a.v0, "initial speed [m/s] (default 0.3)");
  app.add_option("--v0-angle", a.v0Angle, "angle of v0 from the force [deg] (default 90)");
  app.add_option("--omega0", a.omega0, "initial spin [rad/s] (default 15)");
  app.add_option("--force", a.force, "force F / (mu m g) along +x (default 0.1)");
  return demos::runMain(app, argc, argv, "thick_disk", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
