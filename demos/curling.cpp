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
#include "disk_args.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

// a thick disk (h / R = 0.4) launched along +x
demos::DiskArgs curlingDisk() {
  demos::DiskArgs d;
  d.radius = 0.15, d.height = 0.12, d.mass = 1.0, d.mu = 0.5, d.v0 = 2.0, d.v0Angle = 0.0,
  d.omega0 = 15.0;
  return d;
}

int run(const demos::DiskArgs& a, demos::CommonArgs c) {
  demos::validateCommonArgs(c);
  demos::requireDiskArgs(a, demos::kDiskHeight, false);
  if (!(a.v0 > 0)) throw CLI::ValidationError("--v0", "must be > 0");
  demos::DemoConfig config;
  config.name = "curling";
  char title[200];
  std::snprintf(title, sizeof title, "curling: R %g cm, H %g cm, mu %g, v0 %g m/s, spin %+g rad/s",
                100 * a.radius, 100 * a.height, a.mu, a.v0, a.omega0);
  config.title = title;
  config.caption = "patch laws: the pressed front drifts the disk against its spin (track.png)";
  config.trackPlot = true;
  for (const std::string& model : demos::modelsToShow(c.model, true)) {
    demos::DemoBody b;
    b.key = model;
    b.label = model;
    b.colour = demos::rowColour(model);
    b.spec = demos::diskSpec(a, model);
    config.bodies.push_back(b);
  }
  return demos::runDemo(config, c);
}

}  // namespace

int main(int argc, char** argv) {
  demos::DiskArgs a = curlingDisk();
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
  demos::addDiskOptions(app, a, demos::kDiskHeight);  // (launched along +x)
  return demos::runMain(app, argc, argv, "curling", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
