// pushed_disk (issue 5, demo 2): a thin disk under a constant in-plane force
// F along +x in each of the cases of Sect. 6.1, side by side:
//   Case 1  F = 1.2 mu m g  (|F| > mu m g: sticking unrealizable)
//   Case 2  F = 0.5 mu m g  (mu m g > |F| > mu m g / 9: stops in pure sliding)
//   Case 3  F = 0.05 mu m g (|F| < mu m g / 9: stops sliding and spinning)
// Each disk runs through patchspin::scenes::simulate (demo_common.hpp).
#include "demo_common.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

struct Args {
  double radius = 0.05, height = 0.005, mass = 0.03, mu = 0.3, v0 = 0.5, v0Angle = 90.0,
         omega0 = 20.0;
  double g = 9.81;
  double case1 = 1.2, case2 = 0.5, case3 = 0.05;  // F / (mu m g)
};

int run(const Args& a, const demos::CommonArgs& c) {
  demos::validateCommonArgs(c);
  if (c.model == "all")
    throw CLI::ValidationError("--model", "must be exact, ellipsoidal or stock");
  if (!(a.radius > 0 && a.height > 0 && a.mass > 0 && a.g > 0 && a.mu >= 0))
    throw CLI::ValidationError("parameters", "need radius, height, mass, g > 0, mu >= 0");
  demos::DemoConfig config;
  config.name = "pushed_disk";
  char title[200];
  std::snprintf(title, sizeof title,
                "pushed disk (Sect. 6.1) R = %g cm, H = %g mm, mu = %g, v0 = %g m/s at %g deg, "
                "omega0 = %g rad/s",
                100 * a.radius, 1000 * a.height, a.mu, a.v0, a.v0Angle, a.omega0);
  config.title = title;
  config.caption =
      "paper: Case 1 never sticks; Case 2 stops sliding along F (w1); Case 3 stops in slip and "
      "spin (w3, w4)";
  const double pi = std::acos(-1.0);
  const double angle = a.v0Angle * pi / 180.0;
  const double factors[3] = {a.case1, a.case2, a.case3};
  const render::Rgb colours[3] = {{0.85, 0.30, 0.25}, {0.25, 0.50, 0.90}, {0.90, 0.60, 0.15}};
  for (int i = 0; i < 3; ++i) {
    demos::DemoBody b;
    b.key = "case" + std::to_string(i + 1);
    char label[80];
    std::snprintf(label, sizeof label, "Case %d: F = %g mu m g", i + 1, factors[i]);
    b.label = label;
    b.colour = colours[i];
    SimulationSpec& s = b.spec;
    s.model = c.model;
    s.shape = SimulationSpec::Shape::Cylinder;
    s.R = a.radius;
    s.H = a.height;
    s.mass = a.mass;
    s.mu = a.mu;
    s.g = a.g;
    s.force = Vec2(factors[i] * a.mu * a.mass * a.g, 0.0);
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
  c.out = "demo-out/pushed_disk";
  CLI::App app{
      "pushed_disk: a thin disk under a constant in-plane force, Cases 1-3 of Sect. 6.1 side by "
      "side "
      "(headless, PNG frames)"};
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
  app.add_option("--case1", a.case1, "Case 1 force F / (mu m g) (default 1.2)");
  app.add_option("--case2", a.case2, "Case 2 force F / (mu m g) (default 0.5)");
  app.add_option("--case3", a.case3, "Case 3 force F / (mu m g) (default 0.05)");
  return demos::runMain(app, argc, argv, "pushed_disk", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
