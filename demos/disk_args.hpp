// The disk demos' shared parameters (pushed_disk, thick_disk, disk_torque,
// curling): a cylinder on a plane launched with a speed at an angle and a
// spin, each demo adding its own loads. Units: metres, kilograms, seconds,
// radians per second, degrees for the launch angle.
#pragma once

#include <patchspin/simulation.hpp>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace patchspin::demos {

struct DiskArgs {
  double radius = 0.05;   // R [m]
  double height = 0.005;  // H [m]
  double mass = 0.03;     // [kg]
  double mu = 0.3;        // friction coefficient [-]
  double g = 9.81;        // gravity [m/s^2]
  double v0 = 0.5;        // launch speed [m/s]
  double v0Angle = 90.0;  // launch direction from +x (the demos' force) [deg]
  double omega0 = 20.0;   // spin about +z [rad/s], > 0 counter-clockwise seen from above
};

// Which of the optional ones addDiskOptions adds (a demo may derive the
// height or fix the launch direction).
enum DiskOption : unsigned { kDiskHeight = 1u, kDiskV0Angle = 2u };

// --radius, --mass, --mu, --g, --v0, --omega0 and those of `optional`,
// each with its unit; the defaults shown are `a`'s values.
void addDiskOptions(CLI::App& app, DiskArgs& a, unsigned optional);

// CLI::ValidationError unless every value is finite, radius, mass, g (and
// the height, if among `optional`: a demo that derives it checks it) are
// > 0 and mu is > 0 (>= 0 with `muMayBeZero`).
void requireDiskArgs(const DiskArgs& a, unsigned optional, bool muMayBeZero);

// The disk as a SimulationSpec under `model` (cylinder, launched), with no
// force or torque.
SimulationSpec diskSpec(const DiskArgs& a, const std::string& model);

// The models a side-by-side demo shows for --model: exact and ellipsoidal
// for "all", plus stock Bullet if `stockInAll`; otherwise that one model.
std::vector<std::string> modelsToShow(const std::string& model, bool stockInAll);

}  // namespace patchspin::demos
