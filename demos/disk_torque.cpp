// disk_torque (issue 5, demo 4): Sect. 6.3, Case 4. A thin disk under a
// constant in-plane force F along +x and an in-plane couple T parallel to it,
// zeta = T / (m g R) (default 0.15), with F below
//   F_crit^{4/6} = mu m g 16 zeta^2 / sqrt(1 + 144 zeta^2)  (0.175 mu m g here).
// One disk per model (ellipsoidal, exact) side by side, each through
// patchspin::scenes::simulate (demo_common.hpp). The couple is physical (as
// Bullet's applyTorque and patchspin::FlatBody::torque; the paper's Eq. (3)
// sign flips T, see analysis.hpp).
#include "demo_common.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

struct Args {
  double radius = 0.05, height = 0.005, mass = 0.03, mu = 0.3, v0 = 0.5, v0Angle = 90.0,
         omega0 = 20.0;
  double g = 9.81;
  double zeta = 0.15;  // T / (m g R)
  double force = 0.1;  // F / (mu m g)
};

int run(const Args& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  if (!(a.radius > 0 && a.height > 0 && a.mass > 0 && a.g > 0 && a.mu > 0))
    throw CLI::ValidationError("parameters", "need radius, height, mass, g, mu > 0");
  const double fCrit = 16 * a.zeta * a.zeta / std::sqrt(1 + 144 * a.zeta * a.zeta);  // / (mu m g)
  demos::DemoConfig config;
  config.name = "disk_torque";
  char title[220];
  std::snprintf(
      title, sizeof title,
      "disk with torque (Sect. 6.3, Case 4) R = %g cm, zeta = T/(mgR) = %g, F = %g mu m g "
      "(F_crit = %.3g mu m g)",
      100 * a.radius, a.zeta, a.force, fCrit);
  config.title = title;
  config.caption =
      "paper (Case 4): force and parallel in-plane torque; see sphere_*.png for the limit "
      "directions";
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
    s.H = a.height;
    s.mass = a.mass;
    s.mu = a.mu;
    s.g = a.g;
    s.force = Vec2(a.force * a.mu * a.mass * a.g, 0.0);
    s.torque = Vec3(a.zeta * a.mass * a.g * a.radius, 0.0, 0.0);
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
  c.out = "demo-out/disk_torque";
  c.model = "all";
  CLI::App app{
      "disk_torque: a thin disk under an in-plane force and a parallel in-plane torque, Case 4 of "
      "Sect. 6.3; ellipsoidal and exact side by side (headless, PNG frames)"};
  bool noPlot = false, quiet = false;
  demos::addCommonOptions(app, c, &noPlot, &quiet);
  app.add_option("--radius", a.radius, "disk radius R [m] (default 0.05)");
  app.add_option("--height", a.height, "disk thickness H [m] (default 0.005)");
  app.add_option("--mass", a.mass, "mass [kg] (default 0.03)");
  app.add_option("--mu", a.mu, "friction coefficient (default 0.3)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  app.add_option("--v0", a.v0, "initial speed [m/s] (default 0.5)");
  app.add_option("--v0-angle", a.v0Angle, "angle of v0 from the force [deg] (default 90)");
  app.add_option("--omega0", a.omega0, "initial spin [rad/s] (default 20)");
  app.add_option("--zeta", a.zeta, "torque T / (m g R), about +x (default 0.15)");
  app.add_option("--force", a.force, "force F / (mu m g) along +x (default 0.1)");
  return demos::runMain(app, argc, argv, "disk_torque", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
