// pushed_disk (issue 5, demo 2): a thin disk under a constant in-plane force
// F along +x in each of the cases of Sect. 6.1, side by side:
//   Case 1  F = 1.2 mu m g  (|F| > mu m g: sticking unrealizable)
//   Case 2  F = 0.5 mu m g  (mu m g > |F| > mu m g / 9: stops in pure sliding)
//   Case 3  F = 0.05 mu m g (|F| < mu m g / 9: stops sliding and spinning)
// Each disk runs through patchspin::scenes::simulate (demo_common.hpp).
#include "demo_common.hpp"
#include "disk_args.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace patchspin;

constexpr unsigned kDiskOptions = demos::kDiskHeight | demos::kDiskV0Angle;

struct Args {
  demos::DiskArgs disk;  // (its defaults: 5 cm, 5 mm, 30 g, mu 0.3, 0.5 m/s at 90 deg, 20 rad/s)
  double case1 = 1.2, case2 = 0.5, case3 = 0.05;  // F / (mu m g)
};

int run(const Args& a, const demos::CommonArgs& c) {
  demos::validateCommonArgs(c);
  if (c.model == "all")
    throw CLI::ValidationError("--model", "must be exact, ellipsoidal or stock");
  const demos::DiskArgs& d = a.disk;
  demos::requireDiskArgs(d, kDiskOptions, true);
  demos::DemoConfig config;
  config.name = "pushed_disk";
  char title[200];
  std::snprintf(title, sizeof title,
                "pushed disk (Sect. 6.1) R = %g cm, H = %g mm, mu = %g, v0 = %g m/s at %g deg, "
                "omega0 = %g rad/s",
                100 * d.radius, 1000 * d.height, d.mu, d.v0, d.v0Angle, d.omega0);
  config.title = title;
  config.caption =
      "paper: Case 1 never sticks; Case 2 stops sliding along F (w1); Case 3 stops in slip and "
      "spin (w3, w4)";
  const double factors[3] = {a.case1, a.case2, a.case3};
  const render::Rgb colours[3] = {{0.85, 0.30, 0.25}, {0.25, 0.50, 0.90}, {0.90, 0.60, 0.15}};
  for (int i = 0; i < 3; ++i) {
    demos::DemoBody b;
    b.key = "case" + std::to_string(i + 1);
    char label[80];
    std::snprintf(label, sizeof label, "Case %d: F = %g mu m g", i + 1, factors[i]);
    b.label = label;
    b.colour = colours[i];
    b.spec = demos::diskSpec(d, c.model);
    b.spec.force = Vec2(factors[i] * d.mu * d.mass * d.g, 0.0);
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
  demos::addDiskOptions(app, a.disk, kDiskOptions);
  app.add_option("--case1", a.case1, "Case 1 force F / (mu m g)")->capture_default_str();
  app.add_option("--case2", a.case2, "Case 2 force F / (mu m g)")->capture_default_str();
  app.add_option("--case3", a.case3, "Case 3 force F / (mu m g)")->capture_default_str();
  return demos::runMain(app, argc, argv, "pushed_disk", [&] {
    c.plot = !noPlot;
    c.progress = !quiet;
    return run(a, c);
  });
}
