// Reported impulses (internal): a patch's impulse written back onto the
// points of its Bullet manifold at the end of the step, as Bullet's own
// rows write theirs (m_appliedImpulse, m_appliedImpulseLateral1/2 along
// m_lateralFrictionDir1/2), spread by parts::spreadPatchImpulse. What
// reads contact forces the Bullet way (impact sounds, sensors, callbacks)
// sees the patch's force. A contact handed back to Bullet's rows starts them
// from zero, as before (PatchSelection::handBack).
#pragma once

#include "solver_data.hpp"

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace patchspin::bullet::internal {

// Writes pc's accumulated impulses onto m's points; false if m has none
// (an empty manifold's patch: its report is the only record).
bool writeManifoldImpulses(const PatchConstraint& pc, btPersistentManifold& m);

}  // namespace patchspin::bullet::internal
