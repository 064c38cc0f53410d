// curling (issue 34, item 4): the curling puzzle on a thick disk. A disk
// sliding along +x and spinning presses its front edge harder (friction acts
// at the ground, below the centre of mass: the tipping couples of Eq. (94)-
// (96) tilt the linear pressure forward). Counter-clockwise spin makes the
// front slide to the left, so the pressed front's friction pushes the disk
// to the right: under the exact law the disk drifts sideways opposite to the
// sense of its spin (a curling rock is seen to curl the other way; its
// pivot-slide mechanism, a few asperities on a thin running band, is not a
// linear pressure over a flat patch and is not modelled). The exact law,
// the ellipsoidal law and stock Bullet side by side, each through
// patchspin::scenes::simulate (demo_common.hpp); track.png shows the ground
// tracks with the reference dynamics (Eq. (93)) of each patch law dashed.
// The patch is a disk: annuli (a rock's running band, an upturned glass)
// are not supported by the patch shapes.
#include "demo_common.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

struct Args {
  double radius = 0.15, height = 0.12, mass = 1.0, mu = 0.5, v0 = 2.0, omega0 = 15.0, g = 9.81;
};

int run(const Args& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  if (!(a.radius > 0 && a.height > 0 && a.mass > 0 && a.g > 0 && a.mu > 0 && a.v0 > 0))
    throw CLI::ValidationError("parameters", "need radius, height, mass, g, mu, v0 > 0");
  demos::DemoConfig config;
  config.name = "curling";
  char title[200];
  std::snprintf(title, sizeof title, "curling: R %g cm, H %g cm, mu %g, v0 %g m/s, spin %+g rad/s",
                100 * a.radius, 100 * a.height, a.mu, a.v0, a.omega0);
  config.title = title;
  config.caption = "patch laws: the pressed front drifts the disk against its spin (track.png)";
  config.trackPlot = true;
  for (const char* model : {"exact", "ellipsoidal", "stock"}) {
    if (c.model != "all" && c.model != model) continue;
    demos::DemoBody b;
    b.key = model;
    b.label = model;
    b.colour = demos::rowColour(model);
    SimulationSpec& s = b.spec;
    s.model = model;
    s.shape = SimulationSpec::Shape::Cylinder;
    s.R = a.radius;
    s.H = a.height;
    s.mass = a.mass;
    s.mu = a.mu;
    s.g = a.g;
    s.v0 = Vec2(a.v0, 0.0);
    s.omega0 = a.omega0;
    config.bodies.push_back(b);
  }
  return demos::runDemo(config, c);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  demos::CommonArgs c;
  c.out = "demo-out/curling";
  c.model = "all";
  c.rate = 960.0;
  c.tMax = 1.0;
  CLI::App app{
      "curling: a thick disk sliding and spinning drifts sideways against its spin under the "
      "patch laws (pressure from the tipping couples); exact, ellipsoidal and stock Bullet side "
      "by side (headless, PNG frames, sphere_*.png, track.png)"};
  bool noPlot = false, quiet = false;
  demos::addCommonOptions(app, c, &noPlot, &quiet);
  app.add_option("--radius", a.radius, "disk radius R [m] (default 0.15)");
  app.add_option("--height", a.height, "disk height H [m] (default 0.12: h/R = 0.4)");
  app.add_option("--mass", a.mass, "mass [kg] (default 1)");
  app.add_option("--mu", a.mu, "friction coefficient (default 0.5)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  app.add_option("--v0", a.v0, "initial speed along +x [m/s] (default 2)");
  app.add_option("--omega0", a.omega0,
                 "initial spin [rad/s], > 0 counter-clockwise seen from above (default 15)");
  return demos::runMain(app, argc, argv, "curling", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
