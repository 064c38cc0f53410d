// Plain description of a single-body run ("patchspin simulate") shared by the
// reference dynamics (analysis) and the Bullet engine. No Bullet types here.
//
// Ground frame: x, y horizontal, z up. The body stands on its flat face on a
// horizontal plane: a cylinder (radius R, height H, centre of mass H/2 above
// the patch, J_z = m R^2 / 2) or a box (LX x LY face down, height LZ, uniform
// density). The force acts at the centre of mass and is constant in the
// ground frame; the torque is a constant couple. SI units throughout.
#pragma once

#include <patchspin/types.hpp>

#include <optional>
#include <string>
#include <vector>

namespace patchspin {

struct SimulationSpec {
  enum class Shape { Cylinder, Box };
  Shape shape = Shape::Cylinder;
  double R = 0.05, H = 0.01;             // cylinder [m]
  double LX = 0.1, LY = 0.1, LZ = 0.05;  // box [m]
  std::string model = "exact";           // "ellipsoidal" | "exact" | "stock" (bullet only)
  std::string engine = "reference";      // "reference" | "bullet"
  std::string precision = "double";      // bullet only: "float" | "double"
  double mass = 1.0;                     // [kg]
  double mu = 0.3;                       // [-]
  double g = 9.81;                       // [m/s^2]
  Vec2 force = Vec2::Zero();             // horizontal force at the centre of mass [N]
  Vec3 torque = Vec3::Zero();            // couple [N m]
  Vec2 v0 = Vec2::Zero();                // initial velocity of the patch centre [m/s]
  double omega0 = 0.0;                   // initial spin about z [rad/s]
  double dt = 1.0 / 240.0;               // time step [s]
  double tMax = 10.0;                    // time limit [s]
  double recordAt = 0.01;                // record w when r first falls below recordAt * r0
  bool keepTrajectory = false;           // fill SimulationResult::trajectory
};

struct SimulationSample {
  double t = 0.0;                // [s]
  Vec2 position = Vec2::Zero();  // patch centre in the ground plane [m]
  double psi = 0.0;              // rotation about z [rad]
  Vec2 velocity = Vec2::Zero();  // patch-centre velocity [m/s]
  double omega = 0.0;            // spin [rad/s]
  Vec3 w = Vec3::Zero();         // slip direction in the force-aligned frame
  double r = 0.0;                // slip magnitude [m/s]
  double tilt = 0.0;             // |tilt rate| [rad/s] (Bullet only; 0 for reference)
};

struct SimulationResult {
  bool stopped = false;
  double tStop = 0.0;                // [s]
  Vec3 wStop = Vec3::Zero();         // w when r first fell below recordAt * r0
  std::optional<double> epsStop;     // |v| / (R |omega|) at that instant (cylinders)
  Vec2 displacement = Vec2::Zero();  // [m]
  double rotation = 0.0;             // [rad]
  // turn of the slip velocity's direction (ground frame, unwrapped step by
  // step, > 0 counter-clockwise) from the start until w is recorded (r first
  // below recordAt r0) [rad]; on a limit cycle, -turn / decades of r fallen
  // approaches LimitCycle::turnPerDecade over whole periods
  double turn = 0.0;
  std::vector<SimulationSample> trajectory;
};

}  // namespace patchspin
