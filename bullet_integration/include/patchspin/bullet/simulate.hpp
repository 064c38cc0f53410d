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
#pragma once

#include <patchspin/simulation.hpp>

namespace patchspin::bullet {

// Throws Error for an invalid spec (unknown model or shape, non-positive
// sizes, mass, dt, mu < 0, precision not matching the build).
SimulationResult simulate(const SimulationSpec& spec);

// "float" or "double": the precision of this build's btScalar.
const char* buildPrecision();

}  // namespace patchspin::bullet
