// Drop-in replacement for btSequentialImpulseConstraintSolver that gives
// opted-in bodies the coupled slip-spin friction of flat contact patches
// (Antali & Varkonyi; DESIGN items 2, 4 and 5).
//
//   patchspin::bullet::PatchFrictionSolver solver;
//   btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
//   solver.enablePatchFriction(body, {patchspin::Model::Ellipsoidal});
//
// For every contact manifold that involves an opted-in body and whose two
// touching faces are parallel (a cylinder cap, a box face or a convex-hull
// face against a static plane, a box face or another such face), Bullet's own
// contact and friction rows for that manifold are replaced by two 3-DOF blocks
// at the patch reference point O (the centroid of the face overlap):
//   normal block    (normal velocity, two tilt rates) held exactly while the
//                   centre of pressure of its impulse lies on the patch (a
//                   rigid contact carries any p >= 0); its impulses are the
//                   Pz, Tx, Ty of Eq. (94)-(96);
//   friction block  the implicit slip-spin step of friction_block.hpp, its pressure
//                   set from the normal block every iteration: the linear
//                   pressure of Eq. (94), or the nearest admissible linear
//                   one (pressure.hpp) while the centre of pressure lies
//                   outside the kern where a linear p would turn negative.
// When the centre of pressure would leave the patch the body tips, and the
// contact goes back to Bullet's point handling (for a few steps, then again
// whenever the faces are parallel).
// Both run inside Bullet's solver iterations, after Bullet's own rows, so
// patch bodies interact with joints, other contacts and stacks. Everything
// else (other bodies, non-flat contacts, tipping bodies) goes through stock
// Bullet untouched.
// In btDiscreteDynamicsWorldMt, use PatchSolverPoolMt
// (patch_solver_pool_mt.hpp), whose solvers are PatchFrictionSolvers
// sharing one state.
#pragma once

#include <patchspin/models.hpp>
#include <patchspin/parts/friction_block_part.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>

#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace patchspin::bullet {

class PatchSolverPoolMt;
namespace internal {
struct PatchSolverShared;
}

// The largest PatchOptions::flatnessTolerance [rad], pi/8: a patch ends at
// twice the tolerance (hysteresis), which then stays within the 45 degrees
// beyond which the selection never takes a face for the contact's anyway,
// and a box landing on an edge (both faces 45 degrees from the support) is
// never snapped flat (BadInput.FlatnessToleranceAbovePiOver8IsRefused).
inline constexpr double kMaxFlatnessTolerance = 0.39269908169872415;
// PatchOptions::rho [m] outside [kMinRho, kMaxRho] can never make a patch:
// the friction block takes a lever max|r| / rho in [1e-5, 1e5] only, where
// max|r| (the patch's farthest point from O) is below 1e6 m, as Bullet takes
// a moving body out of the simulation when its bounding box's diagonal
// reaches 1e6 m (btCollisionWorld::updateSingleAabb), and at least
// sqrt(4.9e-324 / pi) = 1.25e-162 m, for the patch's area (at most
// pi max|r|^2) to be a positive double (BadInput.RhoThatCanNeverMakeAPatchIsRefused).
inline constexpr double kMinRho = 1.25e-167;
inline constexpr double kMaxRho = 1e11;

// Per-body options of the patch friction law.
struct PatchOptions {
  PatchOptions() = default;
  // Implicit, so that {Model::Exact} or {Model::Exact, 0.4} reads naturally.
  PatchOptions(Model model_, std::optional<double> mu_ = std::nullopt,
               std::optional<double> rho_ = std::nullopt, double flatnessTolerance_ = 0.02)
      : model(model_), mu(mu_), rho(rho_), flatnessTolerance(flatnessTolerance_) {}

  // Model::Ellipsoidal or Model::Exact (any other value: Error).
  Model model = Model::Ellipsoidal;
  // Friction coefficient [-]; default: Bullet's combined friction of the pair.
  std::optional<double> mu;
  // Length scale rho [m] of the slip state (u_x, u_y, rho w_z); default
  // Eq. (11) about O (mean distance of the patch from O). The friction block
  // accepts a lever max|r| / rho in [1e-5, 1e5] only (friction_block.hpp): a patch
  // whose rho is set beyond that from its size goes to Bullet's point
  // contacts, counted in stats().blockErrors. Outside [kMinRho, kMaxRho]
  // no patch can ever have such a lever: Error.
  std::optional<double> rho;
  // Faces count as parallel (a flat patch) once the angle between them falls
  // below this [rad]; they stay a patch until it exceeds twice this
  // (hysteresis). In (0, kMaxFlatnessTolerance].
  double flatnessTolerance = 0.02;
};

// State of one active patch after a step, for the application to read.
// Patch frame: origin O, z = normal (into `body`), x, y in the contact plane.
struct PatchReport {
  const btCollisionObject* body = nullptr;   // opted-in body (z points into it)
  const btCollisionObject* other = nullptr;  // body it stands on
  // the child of body's / other's btCompoundShape whose face the patch is
  // on (-1: the shape is not a compound); a body standing on several faces
  // has one report per face
  int bodyChild = -1, otherChild = -1;
  btVector3 origin{0, 0, 0};  // O, world [m]
  btVector3 normal{0, 0, 1};  // z axis, world
  btVector3 xAxis{1, 0, 0};   // x axis, world
  btVector3 yAxis{0, 1, 0};   // y axis, world
  // overlap of the two faces, patch frame [m] (always set in a report): a
  // disk, a polygon, or a region bounded by segments and arcs
  // (PatchShape::Kind::ArcRegion: a coin over an edge, two coins' lens)
  std::optional<PatchShape> shape;
  Model model = Model::Ellipsoidal;
  double mu = 0.0;           // [-]
  double rho = 0.0;          // [m]
  PatchLoads loads;          // Pz [N], Tx, Ty [N m] = normal impulses / dt
  LinearPressure pressure;   // p0 [Pa], cx, cy [Pa/m] carrying `loads`
  Vec3 Q = Vec3::Zero();     // friction wrench (P_x, P_y, T_z / rho) [N]
  Vec3 slip = Vec3::Zero();  // x_o = (u_x, u_y, rho w_z) after the step [m/s]
  double r = 0.0;            // |x_o| [m/s]
  Vec3 w = Vec3::Zero();     // x_o / r (zero while sticking)
  bool sticking = false;     // friction block in its stick branch
};

// Work-saving rules of the solver, exposed so that their effect can be
// measured (bench_bullet_world) and, if ever needed, switched off.
struct PatchSolverSettings {
  // Pi (and the exact law's pressure) is refreshed when the centre of
  // pressure has moved by more than this fraction of the patch diameter
  // since the last refresh; 0 refreshes on every change.
  double pressureRefreshTolerance = 1e-6;
  // A patch whose last visit changed nothing is skipped while neither of its
  // bodies' velocities has changed since.
  bool skipSettledPatches = true;
  // A second or later refresh in the same step needs a move beyond this
  // (larger) fraction of the diameter. Each refresh is followed by a new
  // friction block solve, and the friction impulse moves the centre of
  // pressure (its moment about the centre of mass tilts the load) by a
  // shrinking amount in every iteration: with one tolerance for all, a
  // sliding coin refreshed and re-solved ~2.6 times per step. With this
  // rule it refreshes once, at its first visit, and the law's centre of
  // pressure lags the step's final one by ~1e-5 of the diameter while
  // sliding (PatchSolverStats::maxPressureLag); a step that changes the
  // load more (a stop, an impact) still refreshes again, so the lag stays
  // below this tolerance. The validation scenes' errors against the
  // reference dynamics do not grow (bench_bullet_simulation). Set it to
  // pressureRefreshTolerance for the single-tolerance rule.
  double pressureLagTolerance = 1e-3;
  // A friction block whose sticking impulse -K^-1 b lies inside a known
  // part of the limit set sticks without a block solve: the ellipsoid
  // L Pi B for the ellipsoidal law (its exact stick test), the bicone over
  // the translation ellipse, L Pi {|(z1, z2)| + |z3| <= 1}, for the exact
  // law (a sufficient test; the rest go to the solver).
  bool quickStick = true;
  // A patch whose lower body stands on a sticking patch of its own (a
  // stack) is solved with that support held (the support's effective mass
  // folded in, and the support given the impulse that keeps it in place),
  // instead of plain Gauss-Seidel over the two, which converges like the
  // mass ratio.
  bool supportedStacks = true;
  // A refresh that falls due while the patch sticks (at its last visit or
  // at the end of the last step) with its stick impulse inside half of the
  // quick test's set, and with the centre of pressure within 1e-2 of the
  // diameter of the last refresh's, is deferred: the stick impulse does not
  // depend on the law, and a move that small changes Pi by a few percent
  // at most, so the stick test decides as with the refreshed law. Such a
  // patch's law lags its centre of pressure by up to 1e-2 of the diameter
  // while it sticks (maxPressureLag).
  bool deferStickingRefresh = true;
  // Float Bullet: a visit whose impulse change lies within the friction
  // block's own relative precision (1e-9) of the patch's normal impulse,
  // for its couples times the patch's diameter, is round-off: it is not
  // applied and the patch settles. A sliding coin otherwise takes a third
  // visit per step to chase a change of ~1e-12 of its impulse. (Double
  // Bullet: no effect; only an exactly zero change settles, which keeps
  // the world frame invariant to round-off.)
  bool settleOnRoundOff = true;
};

// Contacts of opted-in bodies (manifolds with Bullet's points) that did not
// become patches, by reason; they went to Bullet's point contacts.
struct NotPatchedCounts {
  long unsupportedShape = 0;  // a shape without flat faces: sphere, capsule (either body;
                              // for a compound, the touching child), a triangle mesh or
                              // heightfield as the body, or a compound with a compound child
  long sideContact = 0;       // the contact normal is more than 45 degrees off both faces
                              // (a rim, an edge, a side)
  long notFlat = 0;           // faces further apart than the flatness tolerance
  long offFaces = 0;          // contact points off the faces' planes (rim to rim)
  long tipCooldown = 0;       // within 10 steps of its friction block failing
  long noOverlap = 0;         // the faces' overlap is empty or degenerate
  long lawRefused = 0;        // the friction law refused the overlap or mu
  long sliver = 0;            // the overlap is a sliver (an edge on a face:
                              // diameter^2 / area > kMaxSliverRatio)
  long singularBlocks = 0;    // the patch's effective-mass blocks are singular (a body
                              // whose rotation is locked, setAngularFactor(0))
  long crease = 0;            // on a triangle mesh or heightfield, the face is not on one
                              // plane of triangles: it hangs over a crease or the mesh's
                              // edge, or a triangle rises under it
  long badMesh = 0;           // a non-finite vertex or overlapping coplanar triangles
                              // under the face
  long total() const {
    return unsupportedShape + sideContact + notFlat + offFaces + tipCooldown + noOverlap +
           lawRefused + sliver + singularBlocks + crease + badMesh;
  }
  // Adds c's counts field by field (a pool's solvers, a run's steps).
  NotPatchedCounts& operator+=(const NotPatchedCounts& c) {
    unsupportedShape += c.unsupportedShape;
    sideContact += c.sideContact;
    notFlat += c.notFlat;
    offFaces += c.offFaces;
    tipCooldown += c.tipCooldown;
    noOverlap += c.noOverlap;
    lawRefused += c.lawRefused;
    sliver += c.sliver;
    singularBlocks += c.singularBlocks;
    crease += c.crease;
    badMesh += c.badMesh;
    return *this;
  }
};

// What the solver did in the last step (all islands), for profiling. The
// friction block's counters (blockSolves, pressureRefreshes,
// deferredRefreshes, quickSticks, blockErrors) are those of
// parts::FrictionPartCounters: block solves (the others reused the last
// solution or stuck by the quick test), Pi / exact-law pressure refreshes,
// visits whose due refresh was deferred (deferStickingRefresh), visits that
// stuck by the quick test, and visits whose law or block refused its input
// (patchspin::Error: the patch kept its impulse and its manifold went to
// Bullet's contacts).
struct PatchSolverStats : parts::FrictionPartCounters {
  long patches = 0;        // active patches
  long visits = 0;         // patch visits in the solver iterations
  long skippedVisits = 0;  // visits skipped (settled patch, bodies untouched)
  long shapeRebuilds = 0;  // patch shapes and friction laws built anew (outline changed)
  // patches solved with their support or their load held (supportedStacks;
  // only where the held body is in no other contact or joint)
  long stackHolds = 0;
  // largest distance, relative to the patch diameter, between a patch's
  // centre of pressure at the end of the step and the one its friction law
  // was last refreshed with [-]
  double maxPressureLag = 0.0;
  // patches whose manifold had no points to carry their impulses (a patch
  // kept or found without Bullet's contact points): their PatchReport is
  // the only record of their force
  long patchesWithoutPoints = 0;
  // contacts of opted-in bodies left to Bullet, by reason (notPatchedOf: per body)
  NotPatchedCounts notPatched;
};

// Called once per pair of shape types (the opted-in body's, the other's;
// for a compound, the touching child's) for which a contact could not become a patch because a
// shape has no flat faces (setUnsupportedShapeCallback).
using UnsupportedShapeCallback =
    std::function<void(const btCollisionObject* body, const btCollisionObject* other)>;

class PatchFrictionSolver : public btSequentialImpulseConstraintSolver {
 public:
  PatchFrictionSolver();
  ~PatchFrictionSolver() override;
  PatchFrictionSolver(const PatchFrictionSolver&) = delete;
  PatchFrictionSolver& operator=(const PatchFrictionSolver&) = delete;

  // Opts `body` in (or replaces its options). Throws Error for a null body,
  // a model outside the enum, mu < 0 or not finite, rho outside [kMinRho,
  // kMaxRho] or a flatness tolerance outside (0, kMaxFlatnessTolerance].
  // Only dynamic bodies (inverse mass > 0) get patches; a static or
  // kinematic body opted in is ignored (what stands on it decides), and so is
  // a body with negative mass, which Bullet accepts: it keeps stock Bullet's
  // friction. Where two opted-in bodies touch, the patch is the upper one's
  // (the normal enters it against its gravity).
  //
  // Lifetime: the opt-in is kept in the body itself, in
  // btRigidBody::m_frictionSolverType (a field Bullet zeroes in the body's
  // constructor and never reads; do not write it yourself), as a code naming
  // this solver and its copy of the options. So it lasts exactly as long as
  // the body object, until disablePatchFriction:
  //  * deleting an opted-in body needs no disablePatchFriction; nothing of
  //    it stays in the solver, and a new body, at any address (the deleted
  //    one's included), is not opted in until enabled;
  //  * removing a body from the world and adding it again (to this world or
  //    another one stepped by this solver) keeps its options;
  //  * a body opted in by another PatchFrictionSolver is not opted in for
  //    this one (disablePatchFriction leaves it alone);
  //  * the solver keeps one copy of each distinct PatchOptions value it was
  //    given (not one per body): a spawn/despawn loop with the same options
  //    does not grow it. More than 2^20 - 1 distinct values: Error.
  // (BodyLifetime.*)
  void enablePatchFriction(btRigidBody* body, const PatchOptions& options = PatchOptions());
  // Opts `body` out (null, or a body not opted in by this solver: no-op).
  void disablePatchFriction(btRigidBody* body);
  // `body` must be alive (it is read).
  bool isPatchFrictionEnabled(const btCollisionObject* body) const;

  void setSettings(const PatchSolverSettings& settings);
  const PatchSolverSettings& settings() const;
  const PatchSolverStats& stats() const;

  // Patches that were active in the last step (all islands). Between steps
  // only (not from inside a solve).
  //
  // Lifetime: the reports are filled in place from the solver's record of a
  // step at the first call (to either function) after it, so a step that
  // nobody asks about does not pay for them. The reference and the pointer
  // returned are valid from that call until the world's next step (or the
  // solver's destruction), and must not be used after it: the first call
  // after that step refills the same storage, where a kept pointer then
  // dangles if the number of patches grew, or shows another body's report.
  // To keep a report across steps, keep a copy (patchReportOf).
  // (PatchReports.*)
  const std::vector<PatchReport>& patchReports() const;
  // The report of the patch under `body` in the last step, or null; valid
  // until the next step, as above. A body on several faces (a table on its
  // legs, a compound's children) has several reports: this is the first in
  // patchReports()' order; the others follow it there.
  const PatchReport* findPatchReport(const btCollisionObject* body) const;
  // The same report by value (a copy, its own for as long as it is kept),
  // or none.
  std::optional<PatchReport> patchReportOf(const btCollisionObject* body) const;

  // The opted-in body's contacts that were left to Bullet in the last step,
  // by reason, or null if there were none; valid until the next step.
  const NotPatchedCounts* notPatchedOf(const btCollisionObject* body) const;
  // Told once per pair of shape types that cannot make a patch (a sphere, a
  // mesh...; for a compound, its touching child's type), the first time an
  // opted-in body touches one; nothing is reported without a callback
  // (null: none).
  void setUnsupportedShapeCallback(UnsupportedShapeCallback callback);

  // btConstraintSolver hooks called once per world step.
  void prepareSolve(int numBodies, int numManifolds) override;
  void allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
  // Each island solve: the patch states of its world (by its dispatcher)
  // are the ones in hand. One solver may step several worlds, one after
  // the other (not at once): each world moves as with a solver of its own,
  // and the reports and stats are those of the last world step
  // (SharedSolver.*).
  btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                      int numManifolds, btTypedConstraint** constraints, int numConstraints,
                      const btContactSolverInfo& info, btIDebugDraw* debugDrawer,
                      btDispatcher* dispatcher) override;

 protected:
  void convertContacts(btPersistentManifold** manifolds, int numManifolds,
                       const btContactSolverInfo& info) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifolds, int numManifolds,
                                btTypedConstraint** constraints, int numConstraints,
                                const btContactSolverInfo& info,
                                btIDebugDraw* debugDrawer) override;
  void solveGroupCacheFriendlySplitImpulseIterations(
      btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
      btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
      btIDebugDraw* debugDrawer) override;
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                         const btContactSolverInfo& info) override;

 private:
  friend class PatchSolverPoolMt;
  static std::shared_ptr<internal::PatchSolverShared> makeShared();
  // A solver of a PatchSolverPoolMt: options, states, settings, stats and
  // reports are the pool's (`shared`), its island scratch its own.
  explicit PatchFrictionSolver(std::shared_ptr<internal::PatchSolverShared> shared);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace patchspin::bullet
