// The disk demos' shared parameters (disk_args.hpp).
#include "disk_args.hpp"

#include <cmath>

namespace patchspin::demos {

void addDiskOptions(CLI::App& app, DiskArgs& a, unsigned optional) {
  app.add_option("--radius", a.radius, "disk radius R [m]")->capture_default_str();
  if (optional & kDiskHeight)
    app.add_option("--height", a.height, "disk thickness H [m]")->capture_default_str();
  app.add_option("--mass", a.mass, "mass [kg]")->capture_default_str();
  app.add_option("--mu", a.mu, "friction coefficient")->capture_default_str();
  app.add_option("--g", a.g, "gravity [m/s^2]")->capture_default_str();
  app.add_option("--v0", a.v0, "initial speed [m/s]")->capture_default_str();
  if (optional & kDiskV0Angle)
    app.add_option("--v0-angle", a.v0Angle, "angle of v0 from +x, the force's direction [deg]")
        ->capture_default_str();
  app.add_option("--omega0", a.omega0,
                 "initial spin [rad/s], > 0 counter-clockwise seen from above")
      ->capture_default_str();
}

void requireDiskArgs(const DiskArgs& a, unsigned optional, bool muMayBeZero) {
  const bool height = (optional & kDiskHeight) != 0;
  for (const double v :
       {a.radius, height ? a.height : 1.0, a.mass, a.mu, a.g, a.v0, a.v0Angle, a.omega0})
    if (!std::isfinite(v)) throw CLI::ValidationError("parameters", "must be finite");
  if (!(a.radius > 0 && a.mass > 0 && a.g > 0))
    throw CLI::ValidationError("parameters", "need radius, mass, g > 0");
  if (height && !(a.height > 0)) throw CLI::ValidationError("--height", "must be > 0");
  if (muMayBeZero ? !(a.mu >= 0) : !(a.mu > 0))
    throw CLI::ValidationError("--mu", muMayBeZero ? "must be >= 0" : "must be > 0");
}

SimulationSpec diskSpec(const DiskArgs& a, const std::string& model) {
  SimulationSpec s;
  s.model = model;
  s.shape = SimulationSpec::Shape::Cylinder;
  s.R = a.radius;
  s.H = a.height;
  s.mass = a.mass;
  s.mu = a.mu;
  s.g = a.g;
  const double angle = a.v0Angle * std::acos(-1.0) / 180.0;
  s.v0 = a.v0 * Vec2(std::cos(angle), std::sin(angle));
  s.omega0 = a.omega0;
  return s;
}

std::vector<std::string> modelsToShow(const std::string& model, bool stockInAll) {
  if (model != "all") return {model};
  if (stockInAll) return {"exact", "ellipsoidal", "stock"};
  return {"ellipsoidal", "exact"};
}

}  // namespace patchspin::demos
