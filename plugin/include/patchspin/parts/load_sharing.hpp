// Load sharing part (docs/solver.md, Eq. (S25)): the normal loads of one
// body's patches on static supports, shared as one linear pressure over
// their union. A rigid body on several faces is statically indeterminate;
// Gauss-Seidel over the patches' 3-DOF normal blocks leaves the split of
// its visit order (6.67 : 2.25 N for a symmetric block bridging two boxes,
// each centre of pressure at its face's edge, beyond the kern), which
// turns the body through unequal friction. The split of a rigid body on a
// thin elastic layer of uniform stiffness (Winkler) has the layer's sink,
// hence its pressure, linear in position over all the faces:
//   p(r) = p0 + g . r  over the union,                            (S25)
// with p0, g from the body's total normal impulse and couple. Shared loads
// leave the body's velocity unchanged (the supports are static), so the
// share can be taken between iterations. Guarded by load_sharing_test (a
// brute-force quadrature of the shared pressure over each patch) and
// CompoundShapes.BlockBridging* (the block holds and slides as on one box).
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/types.hpp>

#include <vector>

namespace patchspin::parts {

// One patch of the group, in a reference frame in the patches' common plane.
struct SharedPatch {
  Mat2 R = Mat2::Identity();          // the patch's x, y axes in reference coordinates (columns)
  Vec2 origin = Vec2::Zero();         // its O in reference coordinates [m]
  const PatchShape* shape = nullptr;  // patch frame about O
  // normal impulses (Lambda_z, couple about x, couple about y) as in the
  // normal block (toLoads: Pz = l0, Tx = -l1, Ty = -l2), in and out
  Vec3 lamN = Vec3::Zero();
};

// Replaces every lamN by its share of (S25) carrying the group's total
// impulse and couple. False, nothing changed: fewer than two patches, a
// total normal impulse <= 0, a singular union (all patches' area on one
// line), or a shared pressure negative somewhere on a patch (a vertex, or a
// disk's rim), where the rigid body on a layer would lift off a part:
// Gauss-Seidel's split is kept.
bool shareLoads(std::vector<SharedPatch>& patches);

}  // namespace patchspin::parts
