// Stack hold part (docs/solver.md, Eqs. (S15)-(S16)): a patch P whose lower body
// stands on a patch S of its own is solved with S held, with the blocks of
// K_P - K_PS K_S^-1 K_SP, and S takes the impulse that keeps its DOFs where
// they were, dlambda_S = -K_S^-1 K_SP d: all six while S sticks, its normal
// block while it slips. Plain Gauss-Seidel over P and S converges like the
// mass ratio (a heavy body on a light one never gets its weight to the
// ground in 10 iterations). A support on a static body is likewise solved
// with its load P held. Guarded by stack_hold_test (the fold against a
// dense Schur complement) and the Bullet stack tests (1000:1).
#pragma once

#include <patchspin/parts/patch_blocks.hpp>

#include <vector>

namespace patchspin::parts {

// What linking reads of one patch of an island.
struct StackPatchView {
  int bodyA = -1, bodyB = -1;  // the adapter's body ids (A is dynamic)
  const PatchBody* a = nullptr;
  const PatchBody* b = nullptr;
  const Mat3* F = nullptr;  // patch frame [ex ey n]
  double rho = 0.0;
};

struct StackHold {
  HeldBlocks all, normal;  // support sticking: all six DOFs held; slipping: its normal block
  // the velocity of this patch's DOFs per impulse on the held patch's DOFs
  // (K_PS), and the held patch's K6: a support clamped at its edge is held
  // by its pivot rows instead (foldHeldRows, pivot_rows.hpp)
  Mat6 coupling = Mat6::Zero(), heldK = Mat6::Zero();
};

// Per patch: its support (index of the patch under its lower body, or -1)
// and the blocks with it held (index in `holds`); for a support on a static
// body, its load (the patch standing on it) and the blocks with that held.
struct StackLinks {
  int support = -1, hold = -1;
  int load = -1, loadHold = -1;
};

// Links the simple stacks of an island: the upper body stands on this patch
// alone, the lower body carries nothing else, stands on one patch and is in
// none of the adapter's other rows (otherRows, by body id: point contacts,
// joints), since the support's share is not projected onto its limits.
// `links` is resized to the patches; `holds` gets the held blocks.
void linkStackedPatches(const std::vector<StackPatchView>& patches, int numBodies,
                        const std::vector<char>& otherRows, std::vector<StackLinks>& links,
                        std::vector<StackHold>& holds);

}  // namespace patchspin::parts
