// Patch selection (internal): which manifolds of opted-in bodies become
// flat patches in a step, with their state across steps (persistence,
// hysteresis, tip cooldown) and the per-body options. Bullet's manifolds in,
// Candidates out; the rest of the solver never looks at a manifold's points.
#pragma once

#include "patch_opt_ins.hpp"
#include "solver_data.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace patchspin::bullet::internal {

class PatchSelection {
 public:
  PatchSelection();

  // Options (PatchFrictionSolver's enable/disable), kept in the bodies
  // (patch_opt_ins.hpp).
  PatchOptIns& optIns() { return optIns_; }
  const PatchOptIns& optIns() const { return optIns_; }

  // Contacts left to Bullet (PatchFrictionSolver::notPatchedOf and
  // setUnsupportedShapeCallback).
  const NotPatchedCounts* notPatchedOf(const btCollisionObject* body) const;
  void setUnsupportedShapeCallback(UnsupportedShapeCallback callback) {
    unsupported_ = std::move(callback);
  }

  // A candidate whose constraint could not be set up (singular blocks).
  void countSingular(const Candidate& c, PatchSolverStats& stats) {
    countNotPatched(c.A, c.B, &NotPatchedCounts::singularBlocks, stats);
  }

  // Start of a world step (after the last one's end); the world is known
  // at its first island solve (enterWorld).
  void beginStep();
  // The world (its dispatcher) whose step this is, at each island solve: a
  // solver that steps several worlds keeps each world's manifold states,
  // step count and flat filter apart, swapped in when its world steps (one
  // world: never swapped). The first call of a step counts the world's step.
  // (SharedSolver.*)
  void enterWorld(const void* world) {
    if (world != world_) swapWorld(world);
    if (!begun_) beginWorldStep();
  }
  // The step count of the world in hand.
  long step() const { return step_; }
  // The manifold becomes a patch (a Candidate appended to `out`) or is left
  // to Bullet (false). `dt` [s] is the step.
  // (Inline: the pile's many empty manifolds, which had no patch in the last
  // step and have no static plane, box or cylinder to probe, leave here
  // without a call; selectCandidate tests the same first.)
  bool select(btPersistentManifold* m, int index, double dt, PatchSolverStats& stats,
              std::vector<Candidate>& out) {
    if (m->getNumContacts() == 0 && !mayHaveBeenFlat(m) && !probeable(*m)) return false;
    return selectCandidate(m, index, dt, stats, out);
  }
  // A manifold handed back to Bullet's rows (not a patch in this step):
  // if the last step wrote a patch's impulses onto its points, they are
  // cleared, and Bullet's rows start from zero as they would have without
  // that record (warm-starting them from the patch's impulses was measured
  // to inject energy: docs/notes/2026-11-28-contact-features.md).
  void handBack(btPersistentManifold* m) {
    if (m->getNumContacts() > 0 && mayHaveBeenFlat(m)) clearWrittenImpulses(m);
  }
  // The step's patch impulses were written onto m's points (stage 6).
  void markWritten(PatchState& st) { st.pointsWritten = step_; }
  // Forgets manifolds not seen for a while (they may have been deleted);
  // every kSweepSteps steps of the world in hand.
  void endStep();

 private:
  void clearWrittenImpulses(btPersistentManifold* m);
  // A contact of A (opted in) with B left to Bullet for `reason`; the shapes
  // that touch (a compound's child) name the pair of types told to the
  // unsupported-shape callback (null: the objects' own).
  void countNotPatched(const btCollisionObject* A, const btCollisionObject* B,
                       long NotPatchedCounts::*reason, PatchSolverStats& stats,
                       const btCollisionShape* shapeA = nullptr,
                       const btCollisionShape* shapeB = nullptr);
  bool selectCandidate(btPersistentManifold* m, int index, double dt, PatchSolverStats& stats,
                       std::vector<Candidate>& out);
  // An empty manifold between a dynamic body and a static or kinematic plane,
  // box or cylinder: the support's faces are probed (probeSupportFace).
  static bool probeable(const btPersistentManifold& m) {
    const btCollisionObject* o0 = m.getBody0();
    const btCollisionObject* o1 = m.getBody1();
    const bool support0 = o0->isStaticOrKinematicObject();
    if (support0 == o1->isStaticOrKinematicObject()) return false;
    const int type = (support0 ? o0 : o1)->getCollisionShape()->getShapeType();
    return type == STATIC_PLANE_PROXYTYPE || type == BOX_SHAPE_PROXYTYPE ||
           type == CYLINDER_SHAPE_PROXYTYPE;
  }
  const PatchOptions* dynamicOptions(const btCollisionObject* o);
  PatchShape shapeOf(const internal::PatchOutline& outline);
  // the flat filter: the manifolds that had a patch in a step, as bits by
  // address (flatFilter_[step & 1] is written in step `step`, the other read)
  static constexpr int kFlatFilterLog2 = 16;
  // (inline: asked for every empty manifold of an opted-in body's pairs)
  static std::size_t flatBit(const btPersistentManifold* m) {
    return std::size_t(
        (std::uint64_t(reinterpret_cast<std::uintptr_t>(m)) * 0x9E3779B97F4A7C15ull) >>
        (64 - kFlatFilterLog2));
  }
  void markFlat(const btPersistentManifold* m) {
    const std::size_t bit = flatBit(m);
    std::uint64_t& word = flatFilter_[step_ & 1][bit >> 6];
    if (word == 0) flatWords_[step_ & 1].push_back(bit >> 6);
    word |= std::uint64_t(1) << (bit & 63);
  }
  bool mayHaveBeenFlat(const btPersistentManifold* m) const {
    const std::size_t bit = flatBit(m);
    return (flatFilter_[(step_ - 1) & 1][bit >> 6] >> (bit & 63)) & 1;
  }
  void clearFlatFilter(int k);
  void swapWorld(const void* world);
  void beginWorldStep();

  PatchOptIns optIns_;
  std::unordered_map<const btPersistentManifold*, PatchState> states_;
  long step_ = 0;
  std::unordered_map<const btCollisionObject*, NotPatchedCounts> notPatched_;  // this step's
  UnsupportedShapeCallback unsupported_;
  std::vector<std::pair<int, int>> reportedShapePairs_;  // told to unsupported_ already
  std::vector<std::uint64_t> flatFilter_[2];
  std::vector<std::size_t> flatWords_[2];  // the words of flatFilter_[k] that are not zero
  // the other worlds' states_, step_ and flat filter (swapWorld)
  struct WorldRecord {
    std::unordered_map<const btPersistentManifold*, PatchState> states;
    long step = 0;
    std::vector<std::uint64_t> flatFilter[2];
    std::vector<std::size_t> flatWords[2];
  };
  std::unordered_map<const void*, WorldRecord> worlds_;
  const void* world_ = nullptr;  // whose states are in hand
  bool begun_ = false;           // the world in hand has begun this step
  // the two faces of the manifold in hand, kept for their vertex storage
  internal::Face faceA_, faceB_;
  // disk shapes already built, by radius (a pile of equal coins builds one)
  static constexpr std::size_t kDiskShapeCache = 8;
  std::vector<std::pair<double, PatchShape>> diskShapes_;
  std::size_t diskShapeNext_ = 0;
  long shapeCount_ = 0;
};

}  // namespace patchspin::bullet::internal
