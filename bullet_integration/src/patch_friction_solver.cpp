// PatchFrictionSolver: Bullet's sequential-impulse solver with a normal block
// and a slip-spin friction block per flat contact patch (DESIGN items 2, 4, 5).
//
// Stages per island (Box2D-style explicit list):
//   convertContacts   manifolds of opted-in bodies with a flat patch become a
//                     PatchConstraint (Jacobians, effective masses, warm start);
//                     all other manifolds go to stock Bullet
//   split iterations  stock split impulses, then the patch's position
//                     correction (gap and tilt) on the pseudo velocities
//   iterations        stock rows, then per patch: normal block, friction block
//   finish            warm-start cache and what the reports are made of
//                     (filled when asked for), then stock write-back
#include <patchspin/bullet/patch_friction_solver.hpp>

#include "patch_detection.hpp"

#include <patchspin/friction_block.hpp>

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace patchspin::bullet {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Distance of the centre of pressure beyond the patch, relative to the
// patch diameter, at the end of a step beyond which the body counts as
// tipping and the contact goes back to Bullet's point handling; small
// against 1, large against round-off.
constexpr double kTipRelTol = 1e-3;
// Steps a tipped contact stays with Bullet before it may become a patch again.
constexpr long kTipCooldownSteps = 10;
// A face takes part in a patch only while the contact normal is within 45
// degrees of its normal (cosine): a contact across the face's plane is on
// the rim or the side. Between the faces' own flatness (<= 2 x 0.02 rad by
// default) and a rim contact (~90 degrees) any cut separates them.
constexpr double kFacingCos = 0.70710678118654752;
// A contact point lies on a face when it is within this many times the two
// shapes' summed collision margins of the face's plane. Box and cylinder
// faces include the margin: in the 100-coin pour their points lie within
// 0.05 (float) and 0.02 (double) of the summed margins of the faces. A
// convex hull's faces are its points and Bullet's contact lies one margin
// outside (1.0: the ConvexHull test's prism). Off the faces, the same pour
// has a coin's bottom rim on another's side at 1.86 and rim contacts at 4.1
// and (two coins side by side) ~10.
constexpr double kOnFaceMargins = 1.5;
// ... plus this many ulps of Bullet's scalar times the coordinates' size:
// two boxes with zero margins touch on their faces to ~1e-8 m in float
// (measured, 10 cm boxes near the origin), which 1.5 x 0 refused.
constexpr double kOnFaceRoundOffUlps = 64.0;
// Closing a patch's gap may take the low side of a face tilted on the other
// (within the flatness tolerance) this far into it, relative to the patch
// size, no further. Closing the whole gap at O in one step, as the flat
// model would, took a coin tilted 0.015 rad on a neighbour 0.2 mm deep at
// its rim and the patch then tipped back to Bullet, whose contacts pushed
// it out again: a cycle of ~11 steps that kept a 1000-coin pile boiling
// (scratch trace, coin 916 on 616). Left to reach b exactly (0), the low
// side of two boxes, one sliding on the other with a tilt of 1e-7 rad, kept
// no overlap, so Bullet's box-box test gave no contact points and the patch
// was lost (PatchShapeIsRebuiltOnlyWhenTheOutlineChanges); 1e-3 of the size
// is the sink of a tilt of 1e-3 rad, a twentieth of the default flatness
// tolerance.
constexpr double kLowSideSinkRelTol = 1e-3;
// Pseudo-velocity iterations of the patch position correction per step.
constexpr int kPushIterations = 4;
// A patch outline whose vertices (or radius) are within this fraction of its
// size of the outline its PatchShape and FrictionPatch were built from keeps
// them (moment tables are the expensive part, ~35k instructions); the drift
// does not accumulate, since the comparison is with the outline of the last
// rebuild. The law is then off by ~1e-4 relative at most, ten times below
// the centre-of-pressure lag allowed within a step
// (PatchSolverSettings::pressureLagTolerance, 1e-3 of the diameter). The
// earlier 1e-6 sat at the round-off of float transforms (~6e-8 m at 1 m, 1e-6
// of a 5 cm patch): a resting pile rebuilt 6x as many shapes
// (bench_bullet_scale, N = 100 / 1000: 4.6 / 71 per step against 0.7 / 13).
constexpr double kOutlineRelTol = 1e-4;
// A patch whose two bodies have moved relative to each other by less than
// this (translation relative to the patch size, rotation in radians) since
// its overlap was clipped keeps that overlap (outline and O); the frame, gap
// and tilt are recomputed from the faces every step. The outline is then
// off by ~1e-5 of its size at most, ten times below kOutlineRelTol. Clipping
// two coins' faces (64-gons) costs ~20k instructions; in a resting pile of
// 1000 bodies about half the patches keep their overlap from step to step.
constexpr double kOverlapRelTol = 1e-5;
// Within a step, a slipping friction block whose input (b, L, loads) changed
// by less than this, relative, since its last solve keeps that solution: the
// solve would return it up to round-off (float: velocities carry ~6e-8).
constexpr double kReuseRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-6;
// A pressure refresh that falls due while the patch sticks deep inside its
// limit set is deferred: the stick impulse -K^-1 b does not depend on the
// law, only the stick test does, and with the centre of pressure moved by at
// most kDeferMove of the diameter since the last refresh, Pi changes by at
// most ~8 kDeferMove relative (measured over disks and 1:1 to 10:1
// rectangles, admissible and projected pressures: ||Pi_new^-1 Pi_old - I||
// <= 4.4 to 8.0 times the move), far inside the margin 1 - kDeferStick: the
// test decides as the refreshed law would. A resting pile's patches
// otherwise refreshed ~2.3 times per step, their normal impulses shifting
// between Gauss-Seidel iterations by more than pressureLagTolerance.
constexpr double kDeferMove = 1e-2;
constexpr double kDeferStick = 0.5;
// Relative residual at which a friction block solve stops: far below the
// precision of the velocities it is computed from (single precision carries
// ~6e-8), instead of the core's default 1e-14.
constexpr double kBlockRelTol = sizeof(btScalar) == sizeof(double) ? 1e-12 : 1e-9;
// Warm start of the patch blocks: the full impulses of the last step, not
// Bullet's m_warmstartingFactor (0.85 by default), which damps its scalar
// rows. Each patch block is solved directly (3x3 normal block, implicit
// friction block), so a full warm start lets a steadily sliding or resting
// patch converge in one visit and then be skipped (measured: 1.2x -> 1.09x
// stock for the ellipsoidal coins, 2.5x -> 1.9x for the exact law, in
// instructions); the validation tests (no creep, stacks, energy) hold.
constexpr double kPatchWarmStartFactor = 1.0;

Vec3 toEigen(const btVector3& v) { return Vec3(double(v.x()), double(v.y()), double(v.z())); }
// Double -> btScalar with values below the smallest normal btScalar flushed
// to zero: subnormal operands slow every float operation on them down by
// ~100x, and the velocity changes of a patch that holds a body flat carry
// such crumbs (tilt rates of ~1e-40 in single precision).
btScalar flushed(double x) {
  return std::abs(x) < double(std::numeric_limits<btScalar>::min()) ? btScalar(0) : btScalar(x);
}
btVector3 toBt(const Vec3& v) { return btVector3(flushed(v.x()), flushed(v.y()), flushed(v.z())); }

// Normal impulses (Lambda_z, couple about x, couple about y) on the moving
// body <-> loads of Eq. (94): the pressure's couple on the body is
// (∫ y p, -∫ x p) = (-Tx, -Ty) with Tx = -∫ y p, Ty = ∫ x p (Eq. (3)).
PatchLoads toLoads(const Vec3& lamN) { return PatchLoads{lamN[0], -lamN[1], -lamN[2]}; }

// One body's side of a patch: what the six patch DOFs need of it. The DOFs,
// in the patch frame F = [ex ey n] at O (relative velocity of A over B):
//   0: n.u(O)      1: ex.omega     2: ey.omega       (normal block)
//   3: ex.u(O)     4: ey.u(O)      5: rho n.omega    (friction block: x_o)
// with u(O) = v + omega x r, r = O - centre of mass. Kept small (no 6x3
// Jacobians): the iterations stream over every patch ten times per step.
struct BodyTerms {
  int id = -1;
  bool dynamic = false;
  // the solver body's velocity and spin plus the step's external impulses
  // (Bullet adds those only at write-back): fixed during the iterations,
  // which add the solver body's delta velocities to them (velocityOf)
  btVector3 v0{0, 0, 0}, w0{0, 0, 0};
  Vec3 r = Vec3::Zero();     // lever O - centre of mass, world [m]
  Vec3 invM = Vec3::Zero();  // inverse mass (x) linear factor [1/kg]
  Mat3 invI = Mat3::Zero();  // world inverse inertia with the angular factor [1/(kg m^2)]
};

// The blocks of a patch's 6x6 effective mass K6 = [[W, Knf], [Knf^T, Kff]]
// the iterations use: W^-1, Ks = Kff - Knf^T W^-1 Knf, G = W^-1 Knf, and
// Ks^-1 for the quick stick test (Kff^-1, for a patch off its interior, is
// rare and computed on demand).
struct Blocks {
  Mat3 Winv, Knf, G, Ks, KsInv;
  Mat3 Kff;  // last: read only off the interior (see PatchConstraint's layout)
};
// A stacked patch's blocks with its support held (the blocks of
// K6 - K_PS K_S^-1 K_SP over the held DOFs) and the support's response
// dlambda_S = gain d.
struct HeldBlocks : Blocks {
  bool valid = false;
  Mat6 gain = Mat6::Zero();
};
struct StackHold {
  HeldBlocks all, normal;  // support sticking: all six DOFs held; slipping: its normal block
};

// The friction block's K must be well inside the positive definite cone for
// the core's block solvers, which refuse a K whose unit-diagonal form has a
// condition number of 1e10 or more: det(D K D) > kMinUnitDet with D =
// diag(K)^-1/2 bounds that condition number by 27 / kMinUnitDet (3x3, unit
// diagonal: lambda_max <= 3, lambda_min >= det / 9).
constexpr double kMinUnitDet = 1e-8;

// The blocks of K6 (false if its normal block W is not positive definite,
// by Sylvester's criterion, e.g. a body with locked rotation, or if the
// friction block Ks is not safely so, e.g. spin about the normal locked
// with setAngularFactor(1, 1, 0): its spin DOF has no effective mass).
bool makeBlocks(const Mat6& K6, Blocks& b) {
  const Mat3 W = K6.topLeftCorner<3, 3>();
  if (!(W(0, 0) > 0.0 && W.topLeftCorner<2, 2>().determinant() > 0.0 && W.determinant() > 0.0)) return false;
  b.Winv = W.inverse();  // 3x3 SPD: cofactors
  b.Knf = K6.topRightCorner<3, 3>();
  b.Kff = K6.bottomRightCorner<3, 3>();
  b.G = b.Winv * b.Knf;
  b.Ks = b.Kff - b.Knf.transpose() * b.G;
  b.Ks = 0.5 * (b.Ks + b.Ks.transpose());
  const Vec3 d = b.Ks.diagonal();
  if (!(d.minCoeff() > 0.0)) return false;
  // det(D Ks D) = det(Ks) / (d0 d1 d2): no square roots or divisions (they
  // were a third of this function's time, which runs for every patch in
  // every step), unless that product leaves the normal range
  const double dProduct = d[0] * d[1] * d[2];
  if (dProduct >= std::numeric_limits<double>::min() && dProduct <= std::numeric_limits<double>::max()) {
    if (!(b.Ks.determinant() > kMinUnitDet * dProduct)) return false;
  } else {
    const Vec3 s = d.cwiseSqrt().cwiseInverse();
    if (!((s.asDiagonal() * b.Ks * s.asDiagonal()).determinant() > kMinUnitDet)) return false;
  }
  b.KsInv = b.Ks.inverse();
  return true;
}

// One flat patch of one manifold, for one island solve. Every solver
// iteration streams over all of them: in a pile of 1000 bodies they fill the
// L2 cache many times over, so a visit's fields lie together, in about the
// order the visit reads them, the rarely read ones at the end, and the visit
// reads nothing of the PatchState: what it needs of the state and of the
// friction law's shape is copied in (ShapeSummary, LawCache).
struct PatchState;
// What a visit reads of the friction law's shape (fixed within the step).
struct ShapeSummary {
  bool disk = true;
  Vec2 centre = Vec2::Zero();
  double radius = 0.0, diameter = 0.0;
  double innerRadius2 = 0.0;  // PatchState::innerRadius2
};
// The state's record of the friction law's pressure, read and changed
// during the visits; written back to the PatchState at the end of the step.
// Not rolled back with a stacked patch's redone visit: the law it describes
// is not either.
struct LawCache {
  Vec2 pressureCop = Vec2::Zero();   // PatchState::pressureCop
  bool piInvValid = false;           // PatchState::piInvValid
  Mat3 piInv = Mat3::Identity();     // PatchState::piInv
};
struct PatchConstraint {
  // read by every visit, a skipped one included
  bool settled = false;  // see snapshot
  bool interior = true;  // centre of pressure on the patch: normal block bilateral
  bool tipping = false;
  bool sticking = false;
  bool failed = false;  // the law or block refused its input in this step (see blockErrors)
  bool fanRefine = true;  // exactFanSticks may refine (until a refinement fails in this step)
  bool haveLast = false;  // see last
  bool stateSticking = false;  // PatchState::sticking (the end of the last step)
  Model model = Model::Ellipsoidal;
  int refreshes = 0;  // pressure refreshes in this step
  PatchState* state = nullptr;
  // supporting patch (the lower body's own patch: index in the island's
  // patches, or -1) and the blocks with it held (index in Impl::holds);
  // for a support on a static body, its load: the patch standing on it,
  // and the support's blocks with that load held
  int support = -1, hold = -1;
  int load = -1, loadHold = -1;
  int ids[2] = {-1, -1};  // a.id, b.id (a skipped visit reads this line and the snapshot only)
  double mu = 0.0, rho = 0.0;
  // converged: the last visit changed nothing, and while neither body's
  // velocity has changed since (snapshot), a visit would change nothing again
  btVector3 snapshot[4];  // delta linear / angular velocity of a, then b
  BodyTerms a, b;
  Mat3 F = Mat3::Identity();  // columns ex, ey, n (world)
  Vec3 lamN = Vec3::Zero(), targetN = Vec3::Zero(), lamF = Vec3::Zero();
  Vec3 warmSlip = Vec3::Zero();
  ShapeSummary shape;
  LawCache law;
  // last friction solve of this step, reused while its input stays put
  int lastHeld = 0;
  double lastL = 0.0;
  Vec3 lastB = Vec3::Zero();
  struct {
    Vec3 impulse = Vec3::Zero(), slip = Vec3::Zero();
    bool sticking = false;
  } last;  // what the visits use of its FrictionBlockResult
  Blocks k;  // effective-mass blocks (Kff, at the end, rarely read)
  // read outside the iterations only
  double dt = 0.0;
  Vec3 lamPush = Vec3::Zero(), targetPush = Vec3::Zero();
};

// Per-manifold memory across steps: warm start and hysteresis. A node of
// the states' hash map, looked up for every touching manifold of an
// opted-in body in every step: what every step reads and writes lies at the
// start (the line of the map's key), the exact law's certificates at the end.
struct PatchState {
  const btCollisionObject* body = nullptr;
  const btCollisionObject* other = nullptr;
  long lastSeen = std::numeric_limits<long>::min() / 2;
  long tipStep = std::numeric_limits<long>::min() / 2;
  bool flat = false;
  bool sticking = false;  // the friction block stuck at the end of the last step
  bool overlapValid = false;  // see overlapPose
  bool piInvValid = false;    // see piInv
  // the faces' kinds when geometry's overlap was last clipped (see overlapPose)
  internal::Face::Kind overlapKinds[2] = {internal::Face::Kind::Polygon,
                                          internal::Face::Kind::Polygon};
  long shapeId = 0;                               // unique per built `friction`
  // squared radius of the largest disk about O inside a polygon patch: a
  // centre of pressure within it is on the patch without the edge tests
  // (patches of overlapping coins are clipped 64-gons)
  double innerRadius2 = 0.0;
  // centre of pressure of the pressure `friction` was last refreshed with
  Vec2 pressureCop = Vec2::Zero();
  // warm start in world axes (the patch frame turns with the body): normal
  // impulse, tilt couple, tangential friction impulse and slip, spin parts
  double normal = 0.0, frictionSpin = 0.0, slipSpin = 0.0;
  Vec3 couple = Vec3::Zero(), frictionT = Vec3::Zero(), slipT = Vec3::Zero();
  // Pi^-1 of `friction` (quick stick test), valid until the next refresh
  Mat3 piInv = Mat3::Identity();
  // relative pose of the bodies (B in A's frame) when geometry's overlap was
  // last clipped (see kOverlapRelTol)
  btTransform overlapPose = btTransform::getIdentity();
  internal::DetectedPatch geometry;               // this step's patch
  std::optional<internal::PatchOutline> outline;  // shape of `friction`
  std::optional<FrictionPatch> friction;
  // the exact law's stick certificates (untouched by ellipsoidal patches):
  // a value q(w) of the exact law (a point on the boundary of its limit set),
  // its slip w and the direction of lambda0 / L it was taken for: see
  // exactHullSticks
  Vec3 hullPoint = Vec3::Zero(), hullSlip = Vec3::Zero(), hullDirection = Vec3::Zero();
  bool hullValid = false;
  // the slip where the exact block's last stick test met its limit set's
  // boundary (FrictionBlockResult::gaugeSlip): the next test starts there
  Vec3 gaugeSlip = Vec3::Zero();
  // three more law values around hullPoint (see exactHullSticks), valid
  // under the same rules, for the direction fanDirection
  Vec3 fanCentre = Vec3::Zero();  // q(w*): the hull point the fan was built around
  Vec3 fan[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Mat3 fanInv[3];  // inverses of [fanCentre, fan[k], fan[k+1]]
  Vec3 fanDirection = Vec3::Zero(), fanSlip = Vec3::Zero();  // fanSlip: fanCentre's w*
  bool fanValid = false;
};

// A state not seen since the cooldown of a tip: its manifold may have been
// deleted (and its address reused). Checked at the end of step `step`.
bool isStale(const PatchState& st, long step) {
  return st.lastSeen < step - kTipCooldownSteps - 1;
}
// Steps between sweeps of the stale states.
constexpr long kSweepSteps = 16;

// What a PatchReport is made of, kept at the end of the step; the state
// (geometry, shape) stays as it is until the next step's convertContacts.
struct ReportSource {
  const PatchState* state = nullptr;
  Model model = Model::Ellipsoidal;
  bool sticking = false;
  double mu = 0.0, rho = 0.0, dt = 0.0;
  Vec3 lamN = Vec3::Zero(), lamF = Vec3::Zero();
  Vec3 slip = Vec3::Zero();  // x_o at the end of the step
};

}  // namespace

struct PatchFrictionSolver::Impl {
  std::unordered_map<const btCollisionObject*, PatchOptions> options;
  std::unordered_map<const btPersistentManifold*, PatchState> states;
  // The manifolds that had a patch in a step, as bits of a filter by
  // address (flatFilter[step & 1] is written in step `step`, the other one
  // read): an empty manifold (see convertContacts) is looked up in `states`
  // only when its bit is set (and the state then says whether the patch
  // ended the step flat). Empty manifolds outnumber touching ones ~10 to
  // 1 in a pile, and a lookup is a cache miss or two. A filter is cleared
  // word by word where it was written (flatWords): clearing all 8 KB in
  // every step would be ~1000 stores, against ~10 words written by a
  // 10-coin scene (whose whole step is ~135k instructions).
  static constexpr int kFlatFilterLog2 = 16;
  std::vector<std::uint64_t> flatFilter[2] = {
      std::vector<std::uint64_t>(std::size_t(1) << (kFlatFilterLog2 - 6)),
      std::vector<std::uint64_t>(std::size_t(1) << (kFlatFilterLog2 - 6))};
  std::vector<std::size_t> flatWords[2];  // the words of flatFilter[k] that are not zero
  void clearFlatFilter(int k) {
    for (const std::size_t word : flatWords[k]) flatFilter[k][word] = 0;
    flatWords[k].clear();
  }
  static std::size_t flatBit(const btPersistentManifold* m) {
    return std::size_t(
        (std::uint64_t(reinterpret_cast<std::uintptr_t>(m)) * 0x9E3779B97F4A7C15ull) >>
        (64 - kFlatFilterLog2));
  }
  void markFlat(const btPersistentManifold* m) {
    const std::size_t bit = flatBit(m);
    std::uint64_t& word = flatFilter[step & 1][bit >> 6];
    if (word == 0) flatWords[step & 1].push_back(bit >> 6);
    word |= std::uint64_t(1) << (bit & 63);
  }
  bool mayHaveBeenFlat(const btPersistentManifold* m) const {
    const std::size_t bit = flatBit(m);
    return (flatFilter[(step - 1) & 1][bit >> 6] >> (bit & 63)) & 1;
  }
  std::vector<PatchConstraint> patches;  // current island
  std::vector<StackHold> holds;          // stacked patches of the current island
  PatchConstraint retry;                 // a stacked patch's state before its visit
  // reports of the whole step: what they are made of (the first
  // reportCount sources), and the reports themselves, filled from them
  // when first asked for after the step (fillReports): a step writes ~100
  // bytes per patch instead of a 624-byte PatchReport that nobody may read
  std::vector<ReportSource> reportSources;
  size_t reportCount = 0;
  bool reportsFilled = true;
  bool inStep = false;  // between prepareSolve and allSolved: the sources are being written
  std::vector<PatchReport> reports;
  PatchSolverSettings settings;
  PatchSolverStats stats;
  std::vector<long> reportShapeIds;  // shapeId of each report's shape (copied only when it changes)
  long shapeCount = 0;
  std::vector<btRigidBody*> flushBodies;  // bodies of this island's patches
  long step = 0;

  void fillReports();
  const PatchOptions* optionsOf(const btCollisionObject* o) const {
    auto it = options.find(o);
    return it == options.end() ? nullptr : &it->second;
  }
  std::vector<int> ownPatch, patchesAbove;  // scratch of linkStackedPatches
  std::vector<char> otherRows;              // by solver body id: in one of Bullet's rows
  // a manifold whose patch is detected, its solver rows pending (convertContacts)
  struct Candidate {
    int index;
    PatchState* state;
    const PatchOptions* options;
    const btCollisionObject* A;
    const btCollisionObject* B;
    double mu;
    bool wasFlat;
  };
  std::vector<Candidate> candidates;
  // the two faces of the manifold in hand (convertContacts), kept for their
  // vertex storage
  internal::Face faceA, faceB;
  // disk shapes already built, by radius (PatchShape::disk is a function of
  // it: a copy is the shape it would build; a pile of equal coins builds
  // one), at most kDiskShapeCache of them, the oldest replaced
  static constexpr std::size_t kDiskShapeCache = 8;
  std::vector<std::pair<double, PatchShape>> diskShapes;
  std::size_t diskShapeNext = 0;
  PatchShape shapeOf(const internal::PatchOutline& outline) {
    if (!outline.disk) return outline.toShape();
    for (const auto& entry : diskShapes)
      if (entry.first == outline.radius) return entry.second;
    PatchShape shape = outline.toShape();
    if (diskShapes.size() < kDiskShapeCache) {
      diskShapes.emplace_back(outline.radius, shape);
    } else {
      diskShapes[diskShapeNext] = {outline.radius, shape};
      diskShapeNext = (diskShapeNext + 1) % kDiskShapeCache;
    }
    return shape;
  }
  // options of the island's bodies by solver body id (convertBodies has
  // numbered them before convertContacts), looked up once per body and
  // solve: a manifold's two lookups are then array reads (in a pile, ~4
  // touching manifolds per body)
  std::vector<const PatchOptions*> optionsById;
  std::vector<char> optionsKnown;
  // ... and those lookups go through a table by the object's index in its
  // world's collision-object array, kept across steps: the hash map (a
  // bucket and a node, two cache misses per body in a large pile) is asked
  // only when an entry is missing or stale. An entry holds for the same
  // object (address) while the options are unchanged (optionsVersion:
  // enablePatchFriction and disablePatchFriction advance it).
  struct OptionsEntry {
    const btCollisionObject* object = nullptr;
    const PatchOptions* options = nullptr;
    long version = -1;
  };
  std::vector<OptionsEntry> optionsByIndex;
  long optionsVersion = 0;
  const PatchOptions* cachedOptionsOf(const btCollisionObject* o) {
    const int ix = o->getWorldArrayIndex();
    if (ix < 0) return optionsOf(o);
    if (std::size_t(ix) >= optionsByIndex.size()) optionsByIndex.resize(std::size_t(ix) + 1);
    OptionsEntry& e = optionsByIndex[std::size_t(ix)];
    if (e.object != o || e.version != optionsVersion) {
      e.object = o;
      e.options = optionsOf(o);
      e.version = optionsVersion;
    }
    return e.options;
  }
};

namespace {

// Velocity of a patch's dynamic body during the iterations: its fixed part
// (BodyTerms::v0, w0) plus the solver body's delta velocities, the only part
// of the solver body read (the line Bullet's own rows read and write).
void velocityOf(const BodyTerms& t, const btSolverBody& sb, Vec3& v, Vec3& w) {
  v = toEigen(t.v0 + sb.m_deltaLinearVelocity);
  w = toEigen(t.w0 + sb.m_deltaAngularVelocity);
}

// The point of the patch nearest to p (p itself if inside).
Vec2 nearestPointOn(const PatchShape& shape, const Vec2& p) {
  if (shape.isDisk()) {
    const Vec2 d = p - shape.centre();
    const double n = d.norm();
    return n <= shape.radius() ? p : Vec2(shape.centre() + d * (shape.radius() / n));
  }
  if (shape.contains(p)) return p;
  const auto& v = shape.vertices();
  Vec2 best = v[0];
  double bestDist = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], e = v[(i + 1) % v.size()] - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec2 q = a + t * e;
    if ((q - p).norm() < bestDist) {
      bestDist = (q - p).norm();
      best = q;
    }
  }
  return best;
}

// Squared distance from O to the nearest edge line of a polygon patch, with
// a relative margin of 1e-9 for round-off (0 if O is not inside; disks: 0).
double innerRadiusSquared(const PatchShape& shape) {
  if (shape.isDisk()) return 0.0;
  const auto& v = shape.vertices();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, prev = v.size() - 1; i < v.size(); prev = i++) {
    const Vec2 e = v[i] - v[prev];
    const double len = e.norm();
    if (!(len > 0.0)) continue;
    // signed distance of O from the edge line, > 0 on the inner side (counter-clockwise)
    const double d = (e.x() * -v[prev].y() - e.y() * -v[prev].x()) / len;
    best = std::min(best, d);
  }
  if (!(best > 0.0) || !std::isfinite(best)) return 0.0;
  const double r = best * (1.0 - 1e-9);
  return r * r;
}

// Velocity of the patch DOFs from per-body (v, omega) read by `get`.
template <class Get>
Vec6 patchVelocity(const PatchConstraint& pc, Get get) {
  Vec3 u = Vec3::Zero(), w = Vec3::Zero();
  Vec3 v, om;
  if (pc.a.dynamic) {
    get(pc.a, v, om);
    u += v + om.cross(pc.a.r);
    w += om;
  }
  if (pc.b.dynamic) {
    get(pc.b, v, om);
    u -= v + om.cross(pc.b.r);
    w -= om;
  }
  const Vec3 uf = pc.F.transpose() * u, wf = pc.F.transpose() * w;
  Vec6 c;
  c << uf.z(), wf.x(), wf.y(), uf.x(), uf.y(), pc.rho * wf.z();
  return c;
}

Vec6 constraintVelocity(const PatchConstraint& pc, const btAlignedObjectArray<btSolverBody>& pool) {
  return patchVelocity(pc,
                       [&](const BodyTerms& t, Vec3& v, Vec3& w) { velocityOf(t, pool[t.id], v, w); });
}

// Generalised impulse lam of the six DOFs -> world force f at O and couple m
// on A (B gets -f, -m): f = F (l3, l4, l0), m = F (l1, l2, rho l5).
template <class Add>
void applyPatchImpulse(const PatchConstraint& pc, const Vec6& lam, Add add) {
  const Vec3 f = pc.F * Vec3(lam[3], lam[4], lam[0]);
  const Vec3 m = pc.F * Vec3(lam[1], lam[2], pc.rho * lam[5]);
  if (pc.a.dynamic) add(pc.a.id, pc.a.invM.cwiseProduct(f), pc.a.invI * (m + pc.a.r.cross(f)));
  if (pc.b.dynamic) add(pc.b.id, -pc.b.invM.cwiseProduct(f), -(pc.b.invI * (m + pc.b.r.cross(f))));
}

void applyImpulse(const PatchConstraint& pc, btAlignedObjectArray<btSolverBody>& pool, const Vec6& lam) {
  applyPatchImpulse(pc, lam, [&](int id, const Vec3& dv, const Vec3& dw) {
    pool[id].m_deltaLinearVelocity += toBt(dv);
    pool[id].m_deltaAngularVelocity += toBt(dw);
  });
}

// What the DOFs need of one body. Bullet applies Delta v = invMass (x)
// linearFactor, Delta omega = (I^-1 (tau (x) angularFactor)) (x) angularFactor.
BodyTerms makeBodyTerms(const btSolverBody& sb, int id, const Vec3& r) {
  BodyTerms t;
  t.id = id;
  t.dynamic = sb.m_originalBody != nullptr;
  if (!t.dynamic) return t;
  t.v0 = sb.m_linearVelocity + sb.m_externalForceImpulse;
  t.w0 = sb.m_angularVelocity + sb.m_externalTorqueImpulse;
  t.r = r;
  t.invM = toEigen(sb.m_invMass).cwiseProduct(toEigen(sb.m_linearFactor));
  const btMatrix3x3& I = sb.m_originalBody->getInvInertiaTensorWorld();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) t.invI(i, k) = double(I[i][k]);
  const Vec3 af = toEigen(sb.m_angularFactor);
  if (!(af.x() == 1.0 && af.y() == 1.0 && af.z() == 1.0))  // (times 1: unchanged)
    t.invI = af.asDiagonal() * t.invI * af.asDiagonal();
  return t;
}

// Effective mass of the six DOFs for one body: K6 = J M^-1 J^T with, in the
// patch frame (primes), linear rows S (selection of u' components) and
// angular rows Ja' = [r' x e_z; e_x; e_y; r' x e_x; r' x e_y; rho e_z].
// The angular rows are sparse (three are axes, the others have a zero), so
// K_ang(i, j) = Ja_i . (invI' Ja_j) is written out term by term: the same
// products summed in the same order as the dense 3-vector products, without
// the products by zero and one (the dense form cost ~700 instructions per
// body and step, 8 % of the patch code's time on the sliding coins).
Mat6 effectiveMass(const BodyTerms& t, const Mat3& F, double rho) {
  Mat6 K;
  if (!t.dynamic) return Mat6::Zero();
  const Vec3 r = F.transpose() * t.r;
  // F^T diag(invM) F: (1/m) I for the usual isotropic linear factor
  const Mat3 invM = t.invM.x() == t.invM.y() && t.invM.y() == t.invM.z()
                        ? Mat3(t.invM.x() * Mat3::Identity())
                        : Mat3(F.transpose() * t.invM.asDiagonal() * F);
  const Mat3 I = F.transpose() * t.invI * F;  // invI', symmetric
  // x_j = invI' Ja_j (columns c0, c1, c2 of invI')
  const double rx = r.x(), ry = r.y(), rz = r.z();
  Vec3 x[6];
  for (int k = 0; k < 3; ++k) {
    x[0][k] = I(k, 0) * ry + I(k, 1) * -rx;   // Ja_0 = (ry, -rx, 0)
    x[1][k] = I(k, 0);                        // Ja_1 = e_x
    x[2][k] = I(k, 1);                        // Ja_2 = e_y
    x[3][k] = I(k, 1) * rz + I(k, 2) * -ry;   // Ja_3 = (0, rz, -ry)
    x[4][k] = I(k, 0) * -rz + I(k, 2) * rx;   // Ja_4 = (-rz, 0, rx)
    x[5][k] = I(k, 2) * rho;                  // Ja_5 = (0, 0, rho)
  }
  // Ja_i . x_j for j >= i
  auto row = [&](int i, const Vec3& xj) {
    switch (i) {
      case 0: return ry * xj[0] + -rx * xj[1];
      case 1: return xj[0];
      case 2: return xj[1];
      case 3: return rz * xj[1] + -ry * xj[2];
      case 4: return -rz * xj[0] + rx * xj[2];
      default: return rho * xj[2];
    }
  };
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) K(i, j) = K(j, i) = row(i, x[j]);
  // linear part: rows 0, 3, 4 select u'_z, u'_x, u'_y
  constexpr int kSel[3] = {0, 3, 4}, kComp[3] = {2, 0, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) K(kSel[i], kSel[j]) = invM(kComp[i], kComp[j]) + K(kSel[i], kSel[j]);
  return K;
}
// Both bodies' sum (a static body adds nothing).
Mat6 effectiveMass(const BodyTerms& a, const BodyTerms& b, const Mat3& F, double rho) {
  if (!b.dynamic) return effectiveMass(a, F, rho);
  if (!a.dynamic) return effectiveMass(b, F, rho);
  return effectiveMass(a, F, rho) + effectiveMass(b, F, rho);
}

// The patch DOFs' rows for one body (A's side; B enters with a minus):
// c = J [v; omega], J = [[S F^T, S F^T [r]x^T]] with the DOF order of
// patchVelocity (u_z, w_x, w_y, u_x, u_y, rho w_z), u = v + omega x r.
Mat6 bodyRows(const BodyTerms& t, const Mat3& F, double rho) {
  Mat6 J = Mat6::Zero();
  Mat3 rx;  // [r]x, rx w = r x w
  rx << 0.0, -t.r.z(), t.r.y(), t.r.z(), 0.0, -t.r.x(), -t.r.y(), t.r.x(), 0.0;
  const Mat3 lin = F.transpose(), ang = F.transpose() * rx.transpose();
  constexpr int kLinRow[3] = {3, 4, 0};  // u'_x, u'_y, u'_z
  for (int k = 0; k < 3; ++k) {
    J.block<1, 3>(kLinRow[k], 0) = lin.row(k);
    J.block<1, 3>(kLinRow[k], 3) = ang.row(k);
  }
  J.block<1, 3>(1, 3) = F.col(0).transpose();
  J.block<1, 3>(2, 3) = F.col(1).transpose();
  J.block<1, 3>(5, 3) = rho * F.col(2).transpose();
  return J;
}

// Every point of the manifold lies on both faces (A's point on A's face
// plane, B's on B's) to within kOnFaceMargins times the sum of the two
// shapes' collision margins: a contact anywhere else (a rim, a side) is not
// the faces touching.
bool contactOnFaces(const btPersistentManifold& m, bool aIs0, const internal::Face& faceA,
                    const internal::Face& faceB) {
  const btScalar tol = btScalar(kOnFaceMargins) * (m.getBody0()->getCollisionShape()->getMargin() +
                                                   m.getBody1()->getCollisionShape()->getMargin());
  // plus the round-off of the distances themselves (shapes with zero
  // margins touch on their faces to that round-off only)
  const btScalar ulps = btScalar(kOnFaceRoundOffUlps) * SIMD_EPSILON;
  for (int k = 0; k < m.getNumContacts(); ++k) {
    const btManifoldPoint& p = m.getContactPoint(k);
    const btVector3& onA = aIs0 ? p.m_positionWorldOnA : p.m_positionWorldOnB;
    const btVector3& onB = aIs0 ? p.m_positionWorldOnB : p.m_positionWorldOnA;
    if (btFabs(faceA.normal.dot(onA - faceA.centre)) >
            tol + ulps * (onA.length() + faceA.centre.length()) ||
        btFabs(faceB.normal.dot(onB - faceB.centre)) >
            tol + ulps * (onB.length() + faceB.centre.length()))
      return false;
  }
  return true;
}

// A patch holds its body flat: the tilt rates it leaves are round-off crumbs
// (~1e-18 rad/s beside a spin of rad/s), and the orientation's tilt
// components shrink to ~1e-21. Their products are subnormal in single
// precision, and every float operation on a subnormal is ~100x slower:
// Bullet's own integration of such a body took 2.4x the time of a rocking
// stock body (measured), the patch scene ran 26% faster with the CPU set to
// flush subnormals. So, after the write-back, components far below the
// precision of their vector (1e-12 of its length; float resolves 6e-8) or
// whose square is subnormal are set to exactly zero. Nothing representable
// changes: such a component is lost in any sum with the others.
void flushCrumbs(btRigidBody& body) {
  const btScalar tiny = std::sqrt(std::numeric_limits<btScalar>::min());
  auto flushVector = [&](const btVector3& v) {
    const btScalar cut = std::max(tiny, btScalar(1e-12) * v.length());
    btVector3 out = v;
    bool changed = false;
    for (int i = 0; i < 3; ++i)
      if (out[i] != 0 && std::abs(out[i]) < cut) out[i] = 0, changed = true;
    return std::make_pair(out, changed);
  };
  const auto w = flushVector(body.getAngularVelocity());
  if (w.second) body.setAngularVelocity(w.first);
  const auto v = flushVector(body.getLinearVelocity());
  if (v.second) body.setLinearVelocity(v.first);
  btTransform tr = body.getWorldTransform();
  btMatrix3x3& basis = tr.getBasis();
  bool changed = false;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (basis[i][k] != 0 && std::abs(basis[i][k]) < tiny) basis[i][k] = 0, changed = true;
  if (changed) {
    body.setWorldTransform(tr);
    body.setInterpolationWorldTransform(tr);
  }
}

// The exact law's quick stick beyond the bicone. Its limit set E (unit mu Pz)
// is convex and odd, and every law value q(w) lies in it (on its boundary),
// so E contains conv(B u {+-q*}) for the bicone B = Pi {|(z1, z2)| + |z3| <=
// 1} and any q* = q(w). With q* taken along the ellipsoidal inverse of the
// direction of x = lambda0 / L (w = -Pi^-1 x: the ellipsoidal law's q(w) is
// parallel to x), x = a q* + (1 - a) b with b in B certifies x in E, i.e. the
// block sticks, as the block's own gauge test would decide (a tried on a
// grid in [0, 1]). After a block solve that stuck, q* is the solve's own
// boundary point along lambda0 (FrictionBlockResult::gaugeValue), and the
// next solve's gauge search starts at its slip (warmGauge): a patch
// sticking near its limit then passes this test in the next iterations, or
// re-solves in one or two law evaluations instead of three or four (landing
// 10-body exact pile: -22 % instructions).
// q* costs one evaluation of the law and is kept while the
// law's pressure and shape stay and x turns by less than kHullTurnCos; a
// resting exact patch then no longer re-solves its block in every
// iteration when x lies between the bicone and E's boundary (a rectangle:
// most resting boxes). Tried only for a patch that stuck at its last solve
// or at the end of the last step: for a sliding one the evaluation is
// wasted (sliding exact coins cost 22 % more instructions when every visit
// tried it).
constexpr double kHullTurnCos = 0.999;  // ~2.6 degrees

// The next certificate, for x close to E's boundary (a patch at rest near
// its friction limit: 57 % of the exact block solves in a resting 100-body
// pile ended in a stick that the tests above could not certify). Three more
// law values q_k = q(w_k) around q* = q(w*), w_k = w* turned by kFanSpread
// towards three directions 120 degrees apart, make a fan of tetrahedra
// conv{0, q*, q_k, q_k+1}, each inside E (0 and the law values are);
// x = a q* + b q_k + c q_k+1 with a, b, c >= 0 and a + b + c <= 1 lies in
// one. Between its corners E bulges beyond a flat face by up to ~kFanSpread^2
// / 8 (2 %) of its size: for x in a cone but beyond its face by less than
// kFanBulge, one more law value, at x's barycentric mix of the corners'
// slips, splits the cone into three whose faces lie nearer the boundary.
// Every certificate is x in conv{0, three law values}, so the fan never
// sticks a block that slips; the rules below only decide when the
// evaluations are worth it (measured on the piles of bench_bullet_scale:
// resting, -7 % instructions at N = 100; landing, where sticks turn into
// slips, +0.5 % at N = 10).
constexpr double kFanSpread = 0.4;
// slack for the law's own accuracy (1e-12 relative) and the 3x3 solves
constexpr double kFanSlack = 1e-9;
// x beyond 1.2 of the ellipsoid Pi B: not tried (a heuristic: the exact set
// and the ellipsoid agree on pure translation and pure spin)
constexpr double kFanGate = 1.2;
constexpr double kFanBulge = 1.03;
// The slip of the fan's k-th law value: w* turned by kFanSpread.
Vec3 fanSlip(const Vec3& ws, int k) {
  const Vec3 u = ws.unitOrthogonal(), v = ws.cross(u);
  const double angle = 2.0943951023931957 * k;  // 2 pi / 3
  return (ws + kFanSpread * (std::cos(angle) * u + std::sin(angle) * v)).normalized();
}
bool exactFanSticks(PatchState& st, const Mat3& piInv, bool sticking, const FrictionPatch& friction,
                    const Vec3& x, const Vec3& direction, bool& refine) {
  if ((piInv * x).norm() > kFanGate) return false;
  if (!st.fanValid || direction.dot(st.fanDirection) < kHullTurnCos) {
    st.fanValid = false;
    // three evaluations: only for a patch that ended the last step stuck
    // (in a landing pile the others mostly slip: the fan cost 4 % there)
    if (!sticking || st.hullDirection.dot(direction) < kHullTurnCos) return false;
    // hullPoint = q(w*) with w* = hullSlip
    st.fanCentre = st.hullPoint;
    const Vec3& ws = st.hullSlip;
    for (int k = 0; k < 3; ++k) {
      st.fan[k] = friction.unitQ(Model::Exact, fanSlip(ws, k));
      if (!st.fan[k].allFinite()) return false;
    }
    for (int k = 0; k < 3; ++k) {
      Mat3 M;
      M << st.fanCentre, st.fan[k], st.fan[(k + 1) % 3];
      st.fanInv[k] = M.inverse();
      if (!st.fanInv[k].allFinite()) return false;
    }
    st.fanDirection = st.hullDirection;
    st.fanSlip = ws;
    st.fanValid = true;
  }
  const double sign = st.fanCentre.dot(x) >= 0.0 ? 1.0 : -1.0;  // E is odd
  // x in conv{0, p0, p1, p2}: barycentric a = [p0 p1 p2]^-1 x >= 0, sum <= 1
  // (a singular or ill-conditioned corner gives a non-finite or useless a)
  auto coordinates = [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec3& a) {
    Mat3 M;
    M << p0, p1, p2;
    a = M.inverse() * x;
    return a.allFinite() && a.minCoeff() >= 0.0;
  };
  const Vec3& ws = st.fanSlip;
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = sign * (st.fanInv[k] * x);  // the fan's corners are cached
    if (!a.allFinite() || a.minCoeff() < 0.0) continue;
    if (a.sum() <= 1.0 - kFanSlack) return true;
    // beyond what E bulges out there, or a patch that slipped at the end of
    // the last step: most likely a slip, not worth one more evaluation
    if (a.sum() > kFanBulge || !sticking || !refine) return false;
    const Vec3 p[3] = {sign * st.fanCentre, sign * st.fan[k], sign * st.fan[(k + 1) % 3]};
    // x lies in this cone, beyond the flat face: one more law value inside
    // the face's corner directions, at the slips' mix with x's barycentric
    // weights, splits the cone into three with faces nearer E's boundary
    const Vec3 wsK = fanSlip(ws, k), wsK1 = fanSlip(ws, (k + 1) % 3);
    const Vec3 wr = (a[0] * ws + a[1] * wsK + a[2] * wsK1).normalized();
    const Vec3 r = sign * friction.unitQ(Model::Exact, wr);
    if (!r.allFinite()) return false;
    for (int j = 0; j < 3; ++j) {
      Vec3 b;
      if (coordinates(r, p[j], p[(j + 1) % 3], b) && b.sum() <= 1.0 - kFanSlack) return true;
    }
    refine = false;  // failed once: not again in this step (the patch most likely slips)
    return false;
  }
  return false;
}
// (piInv: Pi^-1 of `friction`; sticking: the block stuck at the end of the last step)
[[gnu::noinline]] bool exactHullSticks(PatchState& st, const Mat3& piInv, bool sticking,
                                       const FrictionPatch& friction, const Vec3& lambda0, double L,
                                       bool& refine) {
  const Vec3 x = lambda0 / L;
  const double xNorm = x.norm();
  if (!(xNorm > 0.0) || !std::isfinite(xNorm)) return false;
  const Vec3 direction = x / xNorm;
  if (!st.hullValid || direction.dot(st.hullDirection) < kHullTurnCos) {
    const Vec3 w = -(piInv * direction);
    const double wNorm = w.norm();
    if (!(wNorm > 0.0) || !std::isfinite(wNorm)) return false;
    st.hullSlip = w / wNorm;
    st.hullPoint = friction.unitQ(Model::Exact, st.hullSlip);
    st.hullDirection = direction;
    st.hullValid = st.hullPoint.allFinite();
    if (!st.hullValid) return false;
  }
  const Vec3 q = st.hullPoint.dot(x) >= 0.0 ? st.hullPoint : Vec3(-st.hullPoint);
  auto inHull = [&](double a) {
    const Vec3 z = piInv * (x - a * q);
    return std::hypot(z.x(), z.y()) + std::abs(z.z()) <= 1.0 - a;
  };
  // the projection of x on q, and a grid in [0, 1]
  const double along = std::clamp(x.dot(q) / q.squaredNorm(), 0.0, 1.0);
  if (inHull(along) || inHull(0.9375 * along)) return true;
  for (int k = 1; k < 8; ++k)
    if (inHull(k / 8.0)) return true;
  return exactFanSticks(st, piInv, sticking, friction, x, direction, refine);
}

// Whether the support of a stacked patch keeps its friction impulse inside
// its limit set after taking the share ds (the quick stick test's sets:
// L Pi B, or the exact law's bicone); kept out of line, off the hot path.
[[gnu::noinline]] bool supportCanTake(PatchConstraint& sup, const Vec6& ds) {
  const Vec3 lamS = sup.lamF + ds.tail<3>();
  const double Ls = sup.mu * (sup.lamN[0] + ds[0]);
  LawCache& law = sup.law;
  if (!law.piInvValid) {
    law.piInv = sup.state->friction->Pi().inverse();
    law.piInvValid = true;
  }
  const Vec3 z = law.piInv * lamS;
  const double size = sup.model == Model::Ellipsoidal ? z.norm() : std::hypot(z.x(), z.y()) + std::abs(z.z());
  return size <= Ls;
}

// The blocks of a patch with the first N DOFs of another patch held:
// K - C Kh^-1 C^T over the 6 DOFs, with Kh the held DOFs' effective mass and
// C the coupling (rows: this patch's DOFs, columns: the held ones); the held
// patch takes dlambda_h = -Kh^-1 C^T d (the gain's first N rows).
template <int N>
void foldHeld(const Mat6& K, const Mat6& K6held, const Eigen::Matrix<double, 6, N>& C,
              HeldBlocks& h) {
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(K6held.topLeftCorner<N, N>());
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
  const Eigen::Matrix<double, N, 6> KhInvCt = ldlt.solve(C.transpose());
  const Mat6 Kf = K - C * KhInvCt;
  if (!makeBlocks(0.5 * (Kf + Kf.transpose()), h)) return;
  h.gain.setZero();
  h.gain.template topRows<N>() = -KhInvCt;
  h.valid = h.Winv.allFinite() && h.KsInv.allFinite() && h.gain.allFinite();
}

// `own` and `above` are scratch, indexed by solver body id (numBodies of
// them); `otherRows` marks the bodies in one of Bullet's rows (its point
// contacts and joints), by the same id.
[[gnu::noinline]] void linkStackedPatches(std::vector<PatchConstraint>& patches,
                                          std::vector<StackHold>& holds, int numBodies,
                                          std::vector<int>& own, std::vector<int>& above,
                                          const std::vector<char>& otherRows) {
  // supported patches (a stack): the lower body B of patch P stands on a
  // patch S of its own. Gauss-Seidel over P and S converges like the mass
  // ratio (a heavy body on a light one never gets its weight to the
  // ground in 10 iterations), so P is solved with S held: K_P - K_PS
  // K_S^-1 K_SP, and S takes the impulse that keeps its DOFs where they
  // were, dlambda_S = -K_S^-1 K_SP d: all six while S sticks (and can take
  // the share), its normal block while it slips (see solveSingleIteration).
  if (std::any_of(patches.begin(), patches.end(), [](const PatchConstraint& pc) { return pc.b.dynamic; })) {
    // by solver body id (a patch's body a is dynamic, so its id is its own):
    // own: the body's single patch (kNone: none, kSeveral: more than one);
    // above: how many patches stand on the body
    constexpr int kNone = -2, kSeveral = -1;
    own.assign(std::size_t(numBodies), kNone);
    above.assign(std::size_t(numBodies), 0);
    for (int i = 0; i < int(patches.size()); ++i) {
      int& o = own[std::size_t(patches[std::size_t(i)].a.id)];
      o = o == kNone ? i : kSeveral;
    }
    for (const PatchConstraint& pc : patches)
      if (pc.b.dynamic) ++above[std::size_t(pc.b.id)];
    for (PatchConstraint& pc : patches) {
      // a simple stack only: the upper body stands on this patch alone, and
      // the lower body carries nothing else and stands on one patch. Nothing
      // else includes Bullet's rows: the fold below takes the lower body to
      // move only as the held patch lets it, and the support's share is not
      // projected onto its limits, so with another contact on the lower body
      // the held iterations need not converge (the 1000-coin pour in double
      // Bullet, two friction directions and 50 iterations: a coin between
      // two patches and a neighbour's point contact was thrown out at 62 m/s
      // and 2085 rad/s in one step, and 174 coins left the box).
      if (!pc.b.dynamic || above[std::size_t(pc.b.id)] != 1 || own[std::size_t(pc.a.id)] < 0 ||
          otherRows[std::size_t(pc.b.id)])
        continue;
      const int support = own[std::size_t(pc.b.id)];
      if (support < 0) continue;
      const PatchConstraint& sp = patches[std::size_t(support)];
      if (&sp == &pc || sp.a.id != pc.b.id) continue;
      // K_PS = -J_{P,b} M_L^-1 J_{S,a}^T (the lower body L is P's b, S's a)
      const Mat6 JPb = bodyRows(pc.b, pc.F, pc.rho), JSa = bodyRows(sp.a, sp.F, sp.rho);
      Mat6 MinvJSaT;
      MinvJSaT.topRows<3>() = pc.b.invM.asDiagonal() * JSa.leftCols<3>().transpose();
      MinvJSaT.bottomRows<3>() = pc.b.invI * JSa.rightCols<3>().transpose();
      const Mat6 Kps = -JPb * MinvJSaT;
      // fold the held DOFs (the support's first n) into P's blocks
      const Mat6 K6p = effectiveMass(pc.a, pc.b, pc.F, pc.rho);
      const Mat6 K6s = effectiveMass(sp.a, sp.b, sp.F, sp.rho);
      StackHold sh;
      foldHeld<6>(K6p, K6s, Kps.leftCols<6>(), sh.all);
      foldHeld<3>(K6p, K6s, Kps.leftCols<3>(), sh.normal);
      if (!sh.all.valid && !sh.normal.valid) continue;
      pc.support = support;
      pc.hold = int(holds.size());
      holds.push_back(sh);
      // and the other way round: a support on a static body (the bottom of
      // the stack) is solved with its load P held, K_S - K_SP K_P^-1 K_PS,
      // P taking dlambda_P = -K_P^-1 K_PS d: all six DOFs while P sticks
      // (the two bodies move as one: the floor feels the heavy body's
      // inertia), its normal block while P slips. Without it a light
      // support under a heavy body stops on the floor at each visit while
      // the body above keeps sliding, and the iterations end with the two
      // slipping against each other while P reports a stick (1000:1 stack)
      if (sp.b.dynamic || sp.load >= 0 || otherRows[std::size_t(pc.a.id)]) continue;
      StackHold lh;
      foldHeld<6>(K6s, K6p, Kps.topRows<6>().transpose(), lh.all);
      foldHeld<3>(K6s, K6p, Kps.topRows<3>().transpose(), lh.normal);
      if (!lh.all.valid && !lh.normal.valid) continue;
      PatchConstraint& spm = patches[std::size_t(support)];
      spm.load = int(&pc - patches.data());
      spm.loadHold = int(holds.size());
      holds.push_back(lh);
    }
  }
}

}  // namespace

PatchFrictionSolver::PatchFrictionSolver() : impl_(std::make_unique<Impl>()) {}
PatchFrictionSolver::~PatchFrictionSolver() = default;

void PatchFrictionSolver::enablePatchFriction(btRigidBody* body, const PatchOptions& options) {
  if (!body) throw Error("enablePatchFriction: body is null");
  if (options.mu) {
    patchspin::internal::requireFinite(*options.mu, "PatchOptions::mu");
    if (*options.mu < 0.0) throw Error("PatchOptions::mu must be >= 0: got " + patchspin::internal::formatDouble(*options.mu));
  }
  if (options.rho) patchspin::internal::requirePositive(*options.rho, "PatchOptions::rho");
  patchspin::internal::requirePositive(options.flatnessTolerance, "PatchOptions::flatnessTolerance");
  impl_->options[body] = options;
  ++impl_->optionsVersion;
}

void PatchFrictionSolver::disablePatchFriction(btRigidBody* body) {
  impl_->options.erase(body);
  ++impl_->optionsVersion;
}

bool PatchFrictionSolver::isPatchFrictionEnabled(const btCollisionObject* body) const {
  return impl_->optionsOf(body) != nullptr;
}

const std::vector<PatchReport>& PatchFrictionSolver::patchReports() const {
  impl_->fillReports();
  return impl_->reports;
}

// The reports of the last step from their sources, once per step (reports
// are overwritten in place: no allocation once the vector and the shapes'
// storage have grown).
void PatchFrictionSolver::Impl::fillReports() {
  if (reportsFilled || inStep) return;
  reportsFilled = true;
  if (reports.size() < reportCount) {
    reports.resize(reportCount);
    reportShapeIds.resize(reportCount, 0);
  }
  for (size_t slot = 0; slot < reportCount; ++slot) {
    const ReportSource& src = reportSources[slot];
    const PatchState& st = *src.state;
    PatchReport& r = reports[slot];
    r.body = st.body;
    r.other = st.other;
    r.origin = st.geometry.origin;
    r.normal = st.geometry.normal;
    r.xAxis = st.geometry.xAxis;
    r.yAxis = st.geometry.yAxis;
    const PatchShape& shape = st.friction->shape();
    if (reportShapeIds[slot] != st.shapeId || !r.shape) {
      r.shape = shape;
      reportShapeIds[slot] = st.shapeId;
    }
    r.model = src.model;
    r.mu = src.mu;
    r.rho = src.rho;
    const PatchLoads l = toLoads(src.lamN);
    r.loads = PatchLoads{l.Pz / src.dt, l.Tx / src.dt, l.Ty / src.dt};
    r.pressure = r.loads.Pz > 0.0 ? LinearPressure::fromLoads(shape, r.loads) : LinearPressure();
    r.Q = src.lamF / src.dt;
    r.slip = src.slip;
    r.r = r.slip.norm();
    r.sticking = src.sticking;
    r.w = src.sticking || r.r == 0.0 ? Vec3::Zero() : Vec3(r.slip / r.r);
  }
  reports.resize(reportCount);
  reportShapeIds.resize(reportCount);
}

void PatchFrictionSolver::setSettings(const PatchSolverSettings& settings) {
  patchspin::internal::requireFinite(settings.pressureRefreshTolerance, "PatchSolverSettings::pressureRefreshTolerance");
  if (settings.pressureRefreshTolerance < 0.0)
    throw Error("PatchSolverSettings::pressureRefreshTolerance must be >= 0: got " +
                patchspin::internal::formatDouble(settings.pressureRefreshTolerance));
  patchspin::internal::requireFinite(settings.pressureLagTolerance, "PatchSolverSettings::pressureLagTolerance");
  if (settings.pressureLagTolerance < 0.0)
    throw Error("PatchSolverSettings::pressureLagTolerance must be >= 0: got " +
                patchspin::internal::formatDouble(settings.pressureLagTolerance));
  impl_->settings = settings;
}
const PatchSolverSettings& PatchFrictionSolver::settings() const { return impl_->settings; }
const PatchSolverStats& PatchFrictionSolver::stats() const { return impl_->stats; }

const PatchReport* PatchFrictionSolver::findPatchReport(const btCollisionObject* body) const {
  impl_->fillReports();
  for (const PatchReport& r : impl_->reports)
    if (r.body == body) return &r;
  return nullptr;
}

void PatchFrictionSolver::prepareSolve(int numBodies, int numManifolds) {
  btSequentialImpulseConstraintSolver::prepareSolve(numBodies, numManifolds);
  ++impl_->step;
  impl_->clearFlatFilter(int(impl_->step & 1));
  impl_->reportCount = 0;
  impl_->reportsFilled = false;
  impl_->inStep = true;
  impl_->stats = PatchSolverStats();
}

void PatchFrictionSolver::allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btSequentialImpulseConstraintSolver::allSolved(info, debugDrawer);
  impl_->inStep = false;
  // forget manifolds not seen for a while (they may have been deleted).
  // The sweep walks every state (a node of a hash map: a cache miss each in
  // a large pile), so it runs every kSweepSteps steps; a state found stale
  // before its sweep is reset when it is looked up (convertContacts), which
  // is what the sweep would have done
  if (impl_->step % kSweepSteps == 0) {
    for (auto it = impl_->states.begin(); it != impl_->states.end();) {
      if (isStale(it->second, impl_->step))
        it = impl_->states.erase(it);
      else
        ++it;
    }
  }
}

void PatchFrictionSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                          const btContactSolverInfo& info) {
  Impl& im = *impl_;
  im.patches.clear();
  im.holds.clear();
  // no opted-in body: stock Bullet, stock cost
  if (im.options.empty()) {
    btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
    return;
  }
  const double dt = double(info.m_timeStep);
  im.optionsById.assign(std::size_t(m_tmpSolverBodyPool.size()), nullptr);
  im.optionsKnown.assign(std::size_t(m_tmpSolverBodyPool.size()), 0);
  // In chunks of manifolds: first the detection of the chunk's patches
  // (faces, flatness, overlap, friction law: nothing of the solver bodies),
  // then, in the manifolds' order, Bullet's contacts and the patches' solver
  // rows (solver bodies, effective masses, warm starts), exactly as one pass
  // would have made them. The two passes keep each one's code in the
  // instruction cache, instead of alternating between the patch detection
  // and Bullet's convertContact for every manifold (resting 1000-body pile:
  // 8.26M -> 6.56M instruction-cache misses in 40 steps, stock 5.29M). A
  // chunk of 256 manifolds stays in the L2 cache between the passes (1024:
  // 6.41M, but +1.4 % L2 misses; 48: 7.05M).
  constexpr int kChunk = 256;
  for (int begin = 0; begin < numManifolds; begin += kChunk) {
    const int end = std::min(numManifolds, begin + kChunk);
    im.candidates.clear();
    for (int i = begin; i < end; ++i) {
      btPersistentManifold* m = manifolds[i];
      // Empty manifolds first: the broadphase keeps one for every pair whose
      // bounding boxes overlap (~10 per touching one in a pile). Every
      // manifold that is not a candidate goes to Bullet in the second pass.
      // A patch that ended the last step flat outlives an empty manifold
      // while its faces still touch (below), and a body opted in on a static
      // or kinematic plane, box or cylinder gets its patch there without
      // Bullet's contact: float Bullet's convex test finds no contact between
      // a coin and a box face longer than wide, or a cylinder's cap of radius
      // 0.2 m and more, until the coin is ~2.3 mm in (reproduced with plain
      // Bullet), and drops the one point it then finds as soon as the coin
      // is lifted out.
      const bool empty = m->getNumContacts() == 0;
      const btCollisionObject* o0 = m->getBody0();
      const btCollisionObject* o1 = m->getBody1();
      PatchState* persisting = nullptr;
      bool probed = false;  // an empty manifold whose faces touch (probeSupportFace)
      btVector3 probeNormal(0, 0, 0);
      if (empty) {
        // one body static or kinematic, a plane, a box or a cylinder: its
        // faces are probed below (flag and type tests: most empty manifolds
        // of a pile are between two dynamic bodies)
        const bool support0 = o0->isStaticOrKinematicObject();
        if (support0 != o1->isStaticOrKinematicObject()) {
          const int type = (support0 ? o0 : o1)->getCollisionShape()->getShapeType();
          probed = type == STATIC_PLANE_PROXYTYPE || type == BOX_SHAPE_PROXYTYPE ||
                   type == CYLINDER_SHAPE_PROXYTYPE;
        }
        if (!probed) {
          if (!im.mayHaveBeenFlat(m)) continue;
          const auto it = im.states.find(m);
          // (the same pair: a manifold deleted in this step's broadphase may
          // have been reused for another)
          if (it == im.states.end() || !it->second.flat || it->second.lastSeen != im.step - 1 ||
              !((it->second.body == o0 && it->second.other == o1) ||
                (it->second.body == o1 && it->second.other == o0)))
            continue;
          persisting = &it->second;
        }
      }
      // the patch belongs to an opted-in dynamic body (a static or kinematic
      // body opted in has no patch of its own: what stands on it decides)
      auto dynamicOptions = [&](const btCollisionObject* o) -> const PatchOptions* {
        const btRigidBody* rb = btRigidBody::upcast(o);
        if (!rb || !(rb->getInvMass() > 0)) return nullptr;
        const int id = o->getCompanionId();
        if (id < 0 || std::size_t(id) >= im.optionsById.size()) return im.cachedOptionsOf(o);
        if (!im.optionsKnown[std::size_t(id)]) {
          im.optionsById[std::size_t(id)] = im.cachedOptionsOf(o);
          im.optionsKnown[std::size_t(id)] = 1;
        }
        return im.optionsById[std::size_t(id)];
      };
      const PatchOptions* opt0 = dynamicOptions(o0);
      const PatchOptions* opt1 = dynamicOptions(o1);
      if (!opt0 && !opt1) {
        continue;  // stock (pass 2)
      }
      // a persisting patch stays the same body's, with the last step's normal
      if (persisting) {
        const bool body0 = persisting->body == o0;
        (body0 ? opt1 : opt0) = nullptr;
        if (!(body0 ? opt0 : opt1)) continue;  // no longer opted in
      }
      // a probed one: the support's face that the body's centre is outside
      // of, and the body's lowest point within the distance at which Bullet
      // keeps a contact point of it (either side), or one it would close in
      // this step at its present speed (a landing: the patch is then a
      // speculative contact and stops the fall at the face)
      // an empty manifold's patch: the furthest its low side may be above the
      // other face
      double reach = empty ? double(m->getContactBreakingThreshold()) : 0.0;
      if (probed) {
        double clearance = 0.0;
        btVector3 lowest;
        const btCollisionObject* body = opt0 ? o0 : o1;
        const btCollisionObject* support = opt0 ? o1 : o0;
        if (!internal::probeSupportFace(*body, *support, &probeNormal, &clearance, &lowest))
          continue;
        auto pointVelocity = [&](const btCollisionObject* o) {
          const btRigidBody* rb = btRigidBody::upcast(o);
          return rb ? rb->getVelocityInLocalPoint(lowest - o->getWorldTransform().getOrigin())
                    : btVector3(0, 0, 0);
        };
        const double approach =
            std::max(0.0, -double(probeNormal.dot(pointVelocity(body) - pointVelocity(support))));
        if (!(clearance >= -reach && clearance <= reach + approach * dt)) continue;
        reach += approach * dt;
      }
      // both opted in (a stack): the patch is the upper body's, the one the
      // normal enters against its gravity (findPatchReport(upper) then finds
      // it); without gravity, body0's. Manifold normal: from body1 to body0.
      if (opt0 && opt1) {
        const btVector3 nInto0 = m->getContactPoint(0).m_normalWorldOnB;
        const btVector3 g = btRigidBody::upcast(o0)->getGravity();
        if (nInto0.dot(g) > 0) opt0 = nullptr;  // body0 is underneath
        else opt1 = nullptr;
      }
      const bool aIs0 = opt0 != nullptr;
      const PatchOptions& opt = aIs0 ? *opt0 : *opt1;
      const btCollisionObject* A = aIs0 ? o0 : o1;
      const btCollisionObject* B = aIs0 ? o1 : o0;
      // manifold normal points from body1 to body0
      const btVector3 nIntoA = persisting ? persisting->geometry.normal
                               : probed   ? probeNormal
                               : aIs0     ? m->getContactPoint(0).m_normalWorldOnB
                                          : -m->getContactPoint(0).m_normalWorldOnB;
      PatchState& st = im.states[m];
      if (st.body != A || st.other != B || isStale(st, im.step - 1)) {
        st = PatchState();
        st.body = A;
        st.other = B;
      }
      const bool wasFlat = st.flat && st.lastSeen >= im.step - 1;
      st.lastSeen = im.step;

      // faces and flatness, with hysteresis
      double cosA = 0.0, cosB = 0.0;
      internal::Face* const faceA = &im.faceA;
      internal::Face* const faceB = &im.faceB;
      // (B's face is looked up whenever A has one, even when A's face alone
      // rules a patch out, as before: for a convex hull that lookup builds
      // the polyhedral features Bullet's own contact clipping then uses, so
      // skipping it could change a hull scene's contacts)
      const bool haveFaces = internal::findFaceAlong(*A, -nIntoA, &cosA, *faceA) &&
                             internal::findFaceAlong(*B, nIntoA, &cosB, *faceB);
      bool flat = false;
      std::optional<internal::DetectedPatch> geo;
      bool kept = false;  // st.geometry is this step's patch (geo unset)
      if (haveFaces && btRigidBody::upcast(A) && btRigidBody::upcast(A)->getInvMass() > 0) {
        const double c = std::clamp(-double(faceA->normal.dot(faceB->normal)), -1.0, 1.0);
        const double tol = wasFlat ? 2.0 * opt.flatnessTolerance : opt.flatnessTolerance;
        // the faces must also face the contact, and the contact must be on
        // them: two coins side by side touch rim to rim, with a normal across
        // their (parallel) faces or, from Bullet's convex test near the rim,
        // along them at a point one coin thickness off the other's face
        // (the angle between the faces last of the cheap tests: acos)
        flat = cosA >= kFacingCos && cosB >= kFacingCos && im.step - st.tipStep > kTipCooldownSteps &&
               std::acos(c) < tol && contactOnFaces(*m, aIs0, *faceA, *faceB);
        // x axis fixed in the moving body: a box spinning on a plane keeps
        // the same outline, and its cached shape, in this frame
        if (flat) {
          const btTransform rel = A->getWorldTransform().inverseTimes(B->getWorldTransform());
          bool keep = wasFlat && st.overlapValid && faceA->kind == st.overlapKinds[0] &&
                      faceB->kind == st.overlapKinds[1] &&
                      double((rel.getOrigin() - st.overlapPose.getOrigin()).length()) <=
                          kOverlapRelTol * st.geometry.outline.size();
          for (int row = 0; keep && row < 3; ++row)
            keep = double((rel.getBasis()[row] - st.overlapPose.getBasis()[row]).length()) <=
                   kOverlapRelTol;
          // a kept overlap is updated in place (no copy of its outline)
          const btVector3 xHint = A->getWorldTransform().getBasis().getColumn(0);
          if (keep) {
            internal::refreshFrame(*faceA, *faceB, xHint, st.geometry);
            kept = true;
          } else {
            geo = internal::buildPatch(*faceA, *faceB, xHint);
          }
          if (geo) {
            st.overlapPose = rel;
            st.overlapKinds[0] = faceA->kind;
            st.overlapKinds[1] = faceB->kind;
            st.overlapValid = true;
          }
        }
      }
      st.flat = flat && (kept || geo.has_value());
      // without Bullet's contact, the faces themselves must touch: the
      // patch's low side no further above the other face than the distance
      // at which Bullet drops a contact point (and, for a first contact,
      // what the body closes in this step)
      if (st.flat && empty && !((kept ? st.geometry : *geo).clearance <= reach)) st.flat = false;
      // (the warm start is read only after a step that ended flat, whose end
      // wrote it: a contact that is not flat leaves it as it is)
      if (!st.flat) {
        continue;  // stock (pass 2)
      }
      // stock rows of this manifold are replaced: start them from zero if
      // the contact goes back to Bullet later. After a step that ended flat
      // they are zero already (Bullet's write-back skipped this manifold, and
      // the points it adds or replaces carry zero or the old zero impulses).
      if (!wasFlat) {
        for (int k = 0; k < m->getNumContacts(); ++k) {
          btManifoldPoint& p = m->getContactPoint(k);
          p.m_appliedImpulse = p.m_appliedImpulseLateral1 = p.m_appliedImpulseLateral2 = 0;
        }
      }

      if (!kept) st.geometry = std::move(*geo);
      // (Bullet's combined friction of the pair, as its contact points get it)
      const double mu = opt.mu  ? *opt.mu
                        : empty ? double(gCalculateCombinedFrictionCallback(o0, o1))
                                : double(m->getContactPoint(0).m_combinedFriction);
      // shape and friction law: rebuilt only when the outline changes
      const internal::PatchOutline& outline = st.geometry.outline;
      const double size = outline.size();
      if (!st.friction || !st.outline || !st.outline->matches(outline, kOutlineRelTol * size) ||
          (opt.rho && st.friction->rho() != *opt.rho)) {
        try {
          const PatchShape shape = im.shapeOf(outline);
          st.friction.emplace(shape, LinearPressure::uniform(shape, 1.0), mu,
                              opt.rho ? *opt.rho : 0.0);
          st.outline = outline;
          st.pressureCop = shape.centroid();  // uniform pressure
          st.piInvValid = false;
          st.hullValid = false;
          st.fanValid = false;
          st.shapeId = ++im.shapeCount;
          st.innerRadius2 = innerRadiusSquared(shape);
          ++im.stats.shapeRebuilds;
        } catch (const Error&) {
          st.flat = false;  // degenerate overlap: leave it to Bullet
          st.friction.reset();
          st.outline.reset();
          continue;  // stock (pass 2)
        }
      }
      if (st.friction->mu() != mu) {
        try {
          st.friction->setMu(mu);
        } catch (const Error&) {
          st.flat = false;  // a coefficient the law cannot take (mu Pz overflows): Bullet's contact
          st.friction.reset();
          st.outline.reset();
          continue;  // stock (pass 2)
        }
      }
      im.candidates.push_back({i, &st, &opt, A, B, mu, wasFlat});
      im.markFlat(m);
    }
    std::size_t next = 0;
    for (int i = begin; i < end; ++i) {
      btPersistentManifold* m = manifolds[i];
      if (next == im.candidates.size() || im.candidates[next].index != i) {
        convertContact(m, info);
        continue;
      }
      const Impl::Candidate& cand = im.candidates[next++];
      PatchState& st = *cand.state;
      const PatchOptions& opt = *cand.options;
      const btCollisionObject* A = cand.A;
      const btCollisionObject* B = cand.B;
      const double mu = cand.mu;
      const bool wasFlat = cand.wasFlat;
      im.patches.emplace_back();
      PatchConstraint& pc = im.patches.back();
      pc.state = &st;
      pc.model = opt.model;
      pc.dt = dt;
      pc.mu = mu;
      pc.rho = st.friction->rho();
      pc.stateSticking = st.sticking;
      const PatchShape& patchShape = st.friction->shape();
      pc.shape.disk = patchShape.isDisk();
      if (pc.shape.disk) {
        pc.shape.centre = patchShape.centre();
        pc.shape.radius = patchShape.radius();
      }
      pc.shape.diameter = patchShape.diameter();
      pc.shape.innerRadius2 = st.innerRadius2;
      pc.law.pressureCop = st.pressureCop;
      pc.law.piInvValid = st.piInvValid;
      if (st.piInvValid) pc.law.piInv = st.piInv;
      const int idA = getOrInitSolverBody(*const_cast<btCollisionObject*>(A), info.m_timeStep);
      const int idB = getOrInitSolverBody(*const_cast<btCollisionObject*>(B), info.m_timeStep);
      const Vec3 O = toEigen(st.geometry.origin);
      const Vec3 ex = toEigen(st.geometry.xAxis);
      const Vec3 ey = toEigen(st.geometry.yAxis);
      pc.F.col(0) = ex;
      pc.F.col(1) = ey;
      pc.F.col(2) = toEigen(st.geometry.normal);
      const btSolverBody& sbA = m_tmpSolverBodyPool[idA];
      const btSolverBody& sbB = m_tmpSolverBodyPool[idB];
      pc.a = makeBodyTerms(sbA, idA, O - toEigen(sbA.m_worldTransform.getOrigin()));
      pc.b = makeBodyTerms(sbB, idB, O - toEigen(sbB.m_worldTransform.getOrigin()));
      pc.ids[0] = idA;
      pc.ids[1] = idB;

      // effective masses of the 6 DOFs and the friction block's Schur
      // complement (normal block held bilateral): Blocks
      if (!makeBlocks(effectiveMass(pc.a, pc.b, pc.F, pc.rho), pc.k)) {
        im.patches.pop_back();
        st.flat = false;  // e.g. a body with locked rotation: leave it to Bullet
        convertContact(m, info);
        continue;
      }

      // position error: gap at O (< 0 penetrating) and tilt of the face
      //   split impulse:  pseudo velocities target (-gap, tilt) * erp / dt
      //   otherwise:      Baumgarte with erp2 in the velocity target
      const double gap = st.geometry.gap;
      const Vec3 tilt = toEigen(st.geometry.tilt);
      const Vec3 tiltRate(0.0, tilt.dot(ex), tilt.dot(ey));
      if (gap > 0.0) {
        // may close the gap in one step, no more; where a is tilted on b,
        // only until its low side is kLowSideSinkRelTol of the patch size
        // into b (the tilt itself is corrected by the push below)
        const double sink = kLowSideSinkRelTol * st.geometry.outline.size();
        pc.targetN = Vec3(-std::clamp(st.geometry.clearance + sink, 0.0, gap) / dt, 0.0, 0.0);
      } else if (info.m_splitImpulse) {
        pc.targetPush = (Vec3(-gap, 0.0, 0.0) + tiltRate) * double(info.m_erp) / dt;
      } else {
        pc.targetN = (Vec3(-gap, 0.0, 0.0) + tiltRate) * double(info.m_erp2) / dt;
      }
      if (gap > 0.0 && info.m_splitImpulse) pc.targetPush = tiltRate * double(info.m_erp) / dt;

      // warm start from the previous step
      if ((info.m_solverMode & SOLVER_USE_WARMSTARTING) && wasFlat) {
        const double f = kPatchWarmStartFactor;
        pc.lamN = f * Vec3(st.normal, st.couple.dot(ex), st.couple.dot(ey));
        pc.lamF = f * Vec3(st.frictionT.dot(ex), st.frictionT.dot(ey), st.frictionSpin);
        pc.warmSlip = Vec3(st.slipT.dot(ex), st.slipT.dot(ey), st.slipSpin);
        Vec6 lam;
        lam << pc.lamN, pc.lamF;
        applyImpulse(pc, m_tmpSolverBodyPool, lam);
      }
    }
  }

  if (im.settings.supportedStacks && !im.patches.empty()) {
    // the bodies in Bullet's rows (joints are converted before the contacts)
    im.otherRows.assign(std::size_t(m_tmpSolverBodyPool.size()), 0);
    for (const btConstraintArray* pool :
         {&m_tmpSolverContactConstraintPool, &m_tmpSolverNonContactConstraintPool})
      for (int i = 0; i < pool->size(); ++i) {
        im.otherRows[std::size_t((*pool)[i].m_solverBodyIdA)] = 1;
        im.otherRows[std::size_t((*pool)[i].m_solverBodyIdB)] = 1;
      }
    linkStackedPatches(im.patches, im.holds, m_tmpSolverBodyPool.size(), im.ownPatch,
                       im.patchesAbove, im.otherRows);
  }
}

btScalar PatchFrictionSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                                   btPersistentManifold** manifolds, int numManifolds,
                                                   btTypedConstraint** constraints, int numConstraints,
                                                   const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  if (iteration >= info.m_numIterations) return residual;
  double worst = 0.0;
  auto snapshotOf = [&](const PatchConstraint& pc, btVector3* out) {
    const btSolverBody& a = m_tmpSolverBodyPool[pc.ids[0]];
    const btSolverBody& b = m_tmpSolverBodyPool[pc.ids[1]];
    out[0] = a.m_deltaLinearVelocity;
    out[1] = a.m_deltaAngularVelocity;
    out[2] = b.m_deltaLinearVelocity;
    out[3] = b.m_deltaAngularVelocity;
  };
  PatchSolverStats& stats = impl_->stats;
  const PatchSolverSettings& settings = impl_->settings;
  for (PatchConstraint& pc : impl_->patches) {
    ++stats.visits;
    if (pc.settled) {
      btVector3 now[4];
      snapshotOf(pc, now);
      if (now[0] == pc.snapshot[0] && now[1] == pc.snapshot[1] && now[2] == pc.snapshot[2] &&
          now[3] == pc.snapshot[3]) {
        ++stats.skippedVisits;
        continue;  // same input, same (zero) change: skip
      }
      pc.settled = false;
    }
    FrictionPatch& friction = *pc.state->friction;
    const ShapeSummary& shape = pc.shape;
    // a patch on a body that stands on a patch of its own (a simple stack) is
    // solved with that support held (see convertContacts): all six DOFs
    // while the support sticks and can take the share without slipping,
    // else its normal block only
    // (a support on a static body is solved with its load held instead)
    PatchConstraint* sup = nullptr;
    const StackHold* stackHold = nullptr;
    if (pc.hold >= 0) {
      sup = &impl_->patches[std::size_t(pc.support)];
      stackHold = &impl_->holds[std::size_t(pc.hold)];
    } else if (pc.loadHold >= 0) {
      sup = &impl_->patches[std::size_t(pc.load)];
      stackHold = &impl_->holds[std::size_t(pc.loadHold)];
    }
    // one visit with the given support hold (0 none, 1 normal, 2 all);
    // false: the support cannot take its share, the visit is to be redone
    auto visit = [&](const HeldBlocks* hold, int held) -> bool {
    const Blocks& k = hold ? static_cast<const Blocks&>(*hold) : pc.k;
    const Mat3& Winv = k.Winv;
    const Mat3& Knf = k.Knf;
    const Mat3& G = k.G;
    // normal block: y = lamN - W^-1 (c_n - target), held exactly while its
    // centre of pressure lies on the patch (a rigid contact can carry any
    // p >= 0, not only a linear one); otherwise the centre of pressure is
    // clamped to the patch and the body is tipping (back to Bullet next step)
    Vec6 c = constraintVelocity(pc, m_tmpSolverBodyPool);
    const Vec3 y = pc.lamN - Winv * (c.head<3>() - pc.targetN);
    Vec3 lamN = Vec3::Zero();
    pc.interior = false;
    pc.tipping = false;
    if (y[0] > 0.0) {
      // centre of pressure (Ty / Pz, -Tx / Pz) = (-y2 / y0, y1 / y0)
      const Vec2 cop(-y[2] / y[0], y[1] / y[0]);
      const bool onPatch =
          shape.disk ? (cop - shape.centre).squaredNorm() <= shape.radius * shape.radius
                     : cop.squaredNorm() <= shape.innerRadius2 || friction.shape().contains(cop);
      if (onPatch) {
        lamN = y;
        pc.interior = true;
      } else {
        const Vec2 clamped = nearestPointOn(friction.shape(), cop);
        lamN = Vec3(y[0], y[0] * clamped.y(), -y[0] * clamped.x());
        pc.tipping = (cop - clamped).norm() > kTipRelTol * shape.diameter;
      }
    }
    Vec6 d = Vec6::Zero();
    d.head<3>() = lamN - pc.lamN;
    pc.lamN = lamN;

    // friction block on the slip x_o, with the normal block held (Schur
    // complement Ks) while it is inside the admissible set
    const Vec3 s = c.tail<3>() + Knf.transpose() * d.head<3>();
    const double L = pc.mu * pc.lamN[0];
    Vec3 lamF = Vec3::Zero();
    bool refreshed = false;  // the pressure of the friction law changed in this visit
    if (L > 0.0) {
      try {
        const Mat3& K = pc.interior ? k.Ks : k.Kff;
        FrictionBlockInput in;
        in.b = s - K * pc.lamF;
        in.K = K;
        in.L = L;
        in.warmSlip = pc.warmSlip;
        if (pc.model == Model::Exact) in.warmGauge = pc.state->gaugeSlip;
        in.tolerance = kBlockRelTol;
        // friction pressure: the linear pressure of Eq. (94) carrying the loads,
        // or, when that would be negative somewhere (centre of pressure outside
        // the kern), the nearest admissible linear one (DESIGN item 2);
        // refreshed only when its centre of pressure moves (see below)
        const PatchLoads raw = toLoads(pc.lamN);
        const Vec2 cop(raw.Ty / raw.Pz, -raw.Tx / raw.Pz);
        // The friction law for unit mu Pz (Pi of Eq. (40), the exact law's
        // integrals) depends on the linear pressure only through its shape,
        // i.e. the centre of pressure (Ty, -Tx) / Pz: refreshed when that point
        // has moved by more than settings.pressureRefreshTolerance (default
        // 1e-6) of the diameter, so that Pi changes by ~1e-6 relative at most,
        // while a body at rest or sliding steadily never pays for a refresh
        // and a centred symmetric patch keeps Pi = I.
        const double moved = (cop - pc.law.pressureCop).norm() / shape.diameter;
        // the quick stick test's measure of lambda0 = -K^-1 b against the
        // law's Pi (see below): <= L sticks
        auto stickSize = [&](Vec3& lambda0) {
          LawCache& law = pc.law;
          if (!law.piInvValid) {
            law.piInv = friction.Pi().inverse();
            law.piInvValid = true;
          }
          lambda0 = -(pc.interior ? Vec3(k.KsInv * in.b) : Vec3(k.Kff.inverse() * in.b));
          const Vec3 unitLoad = law.piInv * lambda0;
          const double size = pc.model == Model::Ellipsoidal
                                  ? unitLoad.norm()
                                  : std::hypot(unitLoad.x(), unitLoad.y()) + std::abs(unitLoad.z());
          return lambda0.allFinite() && unitLoad.allFinite() ? size : INFINITY;
        };
        // (computed once per visit unless a refresh changes Pi in between)
        Vec3 lambda0;
        double size = NAN;
        bool refreshDue = moved > (pc.refreshes == 0 ? settings.pressureRefreshTolerance
                                                     : settings.pressureLagTolerance);
        if (refreshDue && settings.deferStickingRefresh && moved <= kDeferMove &&
            (pc.stateSticking || (pc.haveLast && pc.last.sticking))) {
          size = stickSize(lambda0);
          if (size <= kDeferStick * L) {
            refreshDue = false;
            ++stats.deferredRefreshes;
          }
        }
        if (refreshDue) {
          ++stats.pressureRefreshes;
          ++pc.refreshes;
          PatchLoads loads = raw;
          // a disk's linear pressure is >= 0 iff the centre of pressure lies in
          // its kern, |cop - C| <= I / (A R) = R / 4; a polygon's admissibility
          // test is nearestAdmissibleLoads' own first step (admissible loads
          // come back unchanged)
          if (!shape.disk ||
              (cop - shape.centre).squaredNorm() > 0.0625 * shape.radius * shape.radius)
            loads = nearestAdmissibleLoads(friction.shape(), loads, pc.rho);
          friction.setLoads(PatchLoads{loads.Pz / pc.dt, loads.Tx / pc.dt, loads.Ty / pc.dt});
          pc.law.pressureCop = cop;
          pc.law.piInvValid = false;  // Pi and the law changed (also for supportCanTake)
          pc.state->hullValid = false;
          pc.state->fanValid = false;
          refreshed = true;
          size = NAN;
        }
        // quick stick: the impulse that stops the slip, lambda0 = -K^-1 b,
        // with z = Pi^-1 lambda0, inside L times the ellipsoid Pi B (the
        // ellipsoidal law's limit set: |z| <= L, exactly the block's own test)
        // or, for the exact law, inside L times the bicone |(z1, z2)| + |z3|
        // <= 1 that its limit set contains (every pure translation u gives
        // q = -Pi (u, 0), and q(e3) = -Pi e3: the fitting motions of Eq.
        // (37)-(39); step_test.cpp checks it against the law's support
        // function). Resting bodies, most of a pile, then cost two 3x3
        // products instead of a block solve.
        // A slipping block whose input has not changed since its last solve
        // keeps that solution (reuseSlip, below) without the quick test: the
        // solve found lambda0 outside the limit set for the same input, so
        // the test would fail (1000 sliding coins: ~1.3 of 3.6 visits per
        // patch and step; the others are settled skips, solves and sticks).
        // A patch that ended the last step sticking keeps the test (for the
        // exact law, with its hull test), as before.
        const bool stuckBefore = pc.stateSticking || (pc.haveLast && pc.last.sticking);
        const bool reuseSlip = pc.haveLast && !refreshed && !pc.last.sticking &&
                               held == pc.lastHeld &&
                               (in.b - pc.lastB).norm() <= kReuseRelTol * in.b.norm() &&
                               std::abs(L - pc.lastL) <= kReuseRelTol * L;
        bool quick = false;
        if (settings.quickStick && !(reuseSlip && !pc.stateSticking)) {
          if (std::isnan(size)) size = stickSize(lambda0);
          if (std::isfinite(size) &&
              (size <= L || (pc.model == Model::Exact && stuckBefore &&
                             exactHullSticks(*pc.state, pc.law.piInv, pc.stateSticking, friction,
                                             lambda0, L, pc.fanRefine)))) {
            quick = true;
            ++stats.quickSticks;
            pc.last.impulse = lambda0;
            pc.last.slip.setZero();
            pc.last.sticking = true;
            pc.haveLast = true;
            pc.lastHeld = held;
            pc.lastB = in.b;
            pc.lastL = L;
          }
        }
        const bool reuse = quick || reuseSlip;
        if (!reuse) {
          ++stats.blockSolves;
          const FrictionBlockResult solved = solveFrictionBlock(friction, pc.model, in);
          pc.last.impulse = solved.impulse;
          pc.last.slip = solved.slip;
          pc.last.sticking = solved.sticking;
          if (pc.model == Model::Exact && !solved.gaugeSlip.isZero(0.0)) {
            PatchState& st = *pc.state;
            st.gaugeSlip = solved.gaugeSlip;
            // a stick's boundary point along lambda0 is the hull test's best
            // q* for the next visits (lambda0 turns little between them)
            if (solved.sticking && solved.gaugeValue.allFinite()) {
              st.hullSlip = solved.gaugeSlip;
              st.hullPoint = solved.gaugeValue;
              st.hullDirection = solved.gaugeValue.normalized();
              st.hullValid = true;
              st.fanValid = false;
            }
          }
          pc.haveLast = true;
          pc.lastHeld = held;
          pc.lastB = in.b;
          pc.lastL = L;
        }
        const auto& res = pc.last;
        lamF = res.impulse;
        pc.sticking = res.sticking;
        pc.warmSlip = res.slip;
      } catch (const Error&) {
        // the law or the block refused its input (e.g. the pressure of a
        // patch at the edge of double range): this visit keeps the friction
        // impulse it had, and the manifold goes to Bullet's point contacts
        // for kTipCooldownSteps (as a tipping patch); the world keeps running
        ++stats.blockErrors;
        pc.failed = true;
        lamF = pc.lamF;
      }
    }
    d.tail<3>() = lamF - pc.lamF;
    pc.lamF = lamF;
    if (pc.interior) {
      // the normal block follows the friction impulse: W dN = -Knf dF
      const Vec3 dn = -G * d.tail<3>();
      d.head<3>() += dn;
      pc.lamN += dn;
    }
    if (held == 2 && !supportCanTake(*sup, hold->gain * d)) return false;
    applyImpulse(pc, m_tmpSolverBodyPool, d);
    worst = std::max(worst, d.squaredNorm());
    if (hold && !d.isZero(0.0)) {
      // the support takes what keeps its held DOFs where they were
      const Vec6 ds = hold->gain * d;
      sup->lamN += ds.head<3>();
      sup->lamF += ds.tail<3>();
      sup->settled = false;
      sup->haveLast = false;
      applyImpulse(*sup, m_tmpSolverBodyPool, ds);
      worst = std::max(worst, ds.squaredNorm());
    }
    if (settings.skipSettledPatches && d.isZero(0.0) && !refreshed) {
      pc.settled = true;
      snapshotOf(pc, pc.snapshot);
    }
    return true;
    };
    if (!stackHold || !sup->interior) {
      visit(nullptr, 0);
    } else if (sup->sticking && stackHold->all.valid) {
      PatchConstraint& before = impl_->retry;
      before = pc;
      if (!visit(&stackHold->all, 2)) {
        const LawCache law = pc.law;  // the law is not rolled back: nor is its record
        pc = before;
        pc.law = law;
        visit(stackHold->normal.valid ? &stackHold->normal : nullptr, stackHold->normal.valid ? 1 : 0);
      }
    } else {
      visit(stackHold->normal.valid ? &stackHold->normal : nullptr, stackHold->normal.valid ? 1 : 0);
    }
  }
  return std::max(residual, btScalar(worst));
}

void PatchFrictionSolver::solveGroupCacheFriendlySplitImpulseIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
    btIDebugDraw* debugDrawer) {
  btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySplitImpulseIterations(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  if (!info.m_splitImpulse) return;
  // position correction on Bullet's pseudo velocities (push / turn), which
  // move the bodies but never enter their real velocities: no rocking
  for (int it = 0; it < kPushIterations; ++it) {
    for (PatchConstraint& pc : impl_->patches) {
      if (pc.targetPush.isZero()) continue;
      auto& pool = m_tmpSolverBodyPool;
      const Vec3 c = patchVelocity(pc, [&](const BodyTerms& t, Vec3& v, Vec3& w) {
                       v = toEigen(pool[t.id].m_pushVelocity);
                       w = toEigen(pool[t.id].m_turnVelocity);
                     }).head<3>();
      Vec3 lam = pc.lamPush - pc.k.Winv * (c - pc.targetPush);
      if (lam[0] < 0.0) lam.setZero();  // pushes only apart
      Vec6 d = Vec6::Zero();
      d.head<3>() = lam - pc.lamPush;
      pc.lamPush = lam;
      applyPatchImpulse(pc, d, [&](int id, const Vec3& dv, const Vec3& dw) {
        pool[id].m_pushVelocity += toBt(dv);
        pool[id].m_turnVelocity += toBt(dw);
      });
    }
  }
}

btScalar PatchFrictionSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                            const btContactSolverInfo& info) {
  Impl& im = *impl_;
  im.stats.patches += long(im.patches.size());
  for (PatchConstraint& pc : im.patches) {
    im.stats.stackHolds += pc.hold >= 0 || pc.loadHold >= 0;
    PatchState& st = *pc.state;
    const Vec6 c = constraintVelocity(pc, m_tmpSolverBodyPool);
    const Vec3 ex = pc.F.col(0), ey = pc.F.col(1);
    st.normal = pc.lamN[0];
    st.couple = pc.lamN[1] * ex + pc.lamN[2] * ey;
    st.frictionT = pc.lamF[0] * ex + pc.lamF[1] * ey;
    st.frictionSpin = pc.lamF[2];
    st.slipT = c[3] * ex + c[4] * ey;
    st.slipSpin = c[5];
    st.sticking = pc.sticking;
    st.pressureCop = pc.law.pressureCop;
    st.piInvValid = pc.law.piInvValid;
    if (pc.law.piInvValid) st.piInv = pc.law.piInv;
    if (pc.tipping || pc.failed) {
      st.tipStep = im.step;
      st.flat = false;
    }
    // the report's sources (the report is filled when asked for: fillReports)
    if (im.reportCount == im.reportSources.size()) im.reportSources.emplace_back();
    ReportSource& r = im.reportSources[im.reportCount++];
    r.state = &st;
    r.model = pc.model;
    r.sticking = pc.sticking;
    r.mu = pc.mu;
    r.rho = pc.rho;
    r.dt = pc.dt;
    r.lamN = pc.lamN;
    r.lamF = pc.lamF;
    r.slip = c.tail<3>();
    const PatchLoads l = toLoads(pc.lamN);
    if (l.Pz > 0.0 && pc.mu > 0.0) {
      const Vec2 cop(l.Ty / l.Pz, -l.Tx / l.Pz);
      im.stats.maxPressureLag =
          std::max(im.stats.maxPressureLag, (cop - pc.law.pressureCop).norm() / pc.shape.diameter);
    }
  }
  im.flushBodies.clear();
  for (const PatchConstraint& pc : im.patches)
    if (btRigidBody* body = btRigidBody::upcast(const_cast<btCollisionObject*>(pc.state->body)))
      im.flushBodies.push_back(body);
  im.patches.clear();
  const btScalar out = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
  for (btRigidBody* body : im.flushBodies) flushCrumbs(*body);
  return out;
}

}  // namespace patchspin::bullet
