// Stack links (internal), stage 3 of both patch solvers: which patches
// between solver bodies stand on one another (parts::linkStackedPatches),
// so that a stack is solved with its support or load held. A patch on a
// Featherstone link (PatchConstraint::articulated) takes no part, and its
// bodies count as in other rows; a soft patch (compliance > 0) is solved on
// its own, as the held blocks fold K6 without its compliance
// (SoftContact.StackOfSoftBoxes, MultiBodyPatches.*).
#pragma once

#include "solver_data.hpp"

#include <patchspin/parts/stack_hold.hpp>

#include <vector>

namespace patchspin::bullet::internal {

struct StackScratch {
  std::vector<parts::StackPatchView> views;
  std::vector<parts::StackLinks> links;
  std::vector<int> patchOfView;
};

// Sets each patch's `stack` and fills `holds`. `otherRows` (by solver body
// id, numBodies of them): 1 for a body in one of Bullet's rows, filled by
// the caller; the articulated patches' bodies are marked here.
void linkPatchStacks(std::vector<PatchConstraint>& patches, int numBodies,
                     std::vector<char>& otherRows, StackScratch& scratch,
                     std::vector<parts::StackHold>& holds);

}  // namespace patchspin::bullet::internal
