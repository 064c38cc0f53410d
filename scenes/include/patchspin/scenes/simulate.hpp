// `patchspin simulate --engine bullet`: the single-body run of simulation.hpp
// in a Bullet world (static ground plane z = 0, gravity -g z, one body on its
// flat face), with the same result semantics as the reference engine.
//
//   model "ellipsoidal" | "exact"   PatchFrictionSolver with that law
//   model "stock"                   Bullet's own point friction (for comparison)
//   precision "float" | "double"    must match the Bullet build (btScalar);
//                                   Error otherwise
//
// Bullet settings: one step of spec.dt per stepSimulation call, the solver's
// default 10 iterations, no sleeping (the run itself detects the stop),
// collision margin 1 mm (below Bullet's 4 cm default, which is larger than a
// coin: the patch uses the real face geometry either way).
//
// Stopping: a run started with slip r0 > 0 has stopped once r < 1e-5 r0; the
// instant is extrapolated within that step from the previous decrement, and
// the run ends there. A run started at rest runs to tMax; it reports
// stopped = (r <= 1e-6 m/s at the end) and tStop = the last time r exceeded
// 1e-6 m/s (0 if never). w_stop, eps_stop, turn as in simulation.hpp (turn
// summed over the steps up to the recorded one); the tilt of each
// trajectory sample is |(omega_x, omega_y)| of the body.
#pragma once

#include <patchspin/simulation.hpp>

namespace patchspin::scenes {

// Throws Error for an invalid spec (unknown model or shape, non-positive
// sizes, mass, dt, mu < 0, precision not matching the build). The world is
// a Scene (scene.hpp).
SimulationResult simulate(const SimulationSpec& spec);

// "float" or "double": the precision of this build's btScalar.
const char* buildPrecision();

}  // namespace patchspin::scenes
