// Patch position correction (internal), stage 4 of both patch solvers: each
// patch between solver bodies solves its normal block on Bullet's pseudo
// velocities (push / turn), which move the bodies but never enter their
// real velocities, so a patch pushed out of penetration does not rock. A
// patch on a Featherstone link (PatchConstraint::articulated) has its
// position error in its velocity target instead, as Bullet's multibody
// contacts do, and is skipped here. Determinism.* pins the arithmetic.
#pragma once

#include "solver_data.hpp"

#include <vector>

namespace patchspin::bullet::internal {

// kPushIterations sweeps over `patches`, their bodies in `pool`.
void pushPatches(std::vector<PatchConstraint>& patches, btAlignedObjectArray<btSolverBody>& pool);

}  // namespace patchspin::bullet::internal
