// The data of PatchFrictionSolver (internal): per-manifold state across
// steps, per-patch constraints within an island solve, and the solver's
// Impl. Shared by the solver's stages (patch_friction_solver.cpp), patch
// selection (patch_selection.cpp), constraint set-up (patch_constraint.cpp)
// and reports (patch_reports.cpp).
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/parts/friction_block_part.hpp>
#include <patchspin/parts/normal_block.hpp>
#include <patchspin/parts/patch_blocks.hpp>
#include <patchspin/parts/patch_body.hpp>
#include <patchspin/parts/stack_hold.hpp>
#include <patchspin/parts/stick_certificates.hpp>

#include "patch_detection.hpp"

#include <BulletDynamics/ConstraintSolver/btSolverBody.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

class btPersistentManifold;

namespace patchspin::bullet::internal {

using parts::Mat6;
using parts::Vec6;

inline Vec3 toEigen(const btVector3& v) {
  return Vec3(double(v.x()), double(v.y()), double(v.z()));
}
// Double -> btScalar with values below the smallest normal btScalar flushed
// to zero: subnormal operands slow float arithmetic ~100x, and a patch that
// holds a body flat leaves such crumbs in its velocity changes.
inline btScalar flushed(double x) {
  return std::abs(x) < double(std::numeric_limits<btScalar>::min()) ? btScalar(0) : btScalar(x);
}
inline btVector3 toBt(const Vec3& v) {
  return btVector3(flushed(v.x()), flushed(v.y()), flushed(v.z()));
}

// Steps a contact whose friction block failed stays with Bullet before it
// may become a patch again (a tipping patch stays a patch: pivoting).
constexpr long kTipCooldownSteps = 10;
// Steps between sweeps of the stale states.
constexpr long kSweepSteps = 16;

// One body's side of a patch: the body part plus where its velocity lives.
struct BodyTerms {
  int id = -1;  // solver body id
  // the solver body's velocity and spin plus the step's external impulses
  // (Bullet adds those only at write-back); the iterations add the solver
  // body's delta velocities to them
  btVector3 v0{0, 0, 0}, w0{0, 0, 0};
  parts::PatchBody body;
};
// Bullet applies Delta v = invMass (x) linearFactor, Delta omega =
// (I^-1 (tau (x) angularFactor)) (x) angularFactor.
BodyTerms makeBodyTerms(const btSolverBody& sb, int id, const Vec3& r);

// Per-manifold memory across steps: warm start and hysteresis (a node of
// the states' hash map: what every step reads and writes first).
struct PatchState {
  const btCollisionObject* body = nullptr;
  const btCollisionObject* other = nullptr;
  // the compound children of body and other whose faces make the patch
  // (-1: not a compound); an empty manifold's persisting patch keeps them,
  // as its manifold has no points to tag them (compound_children.hpp)
  int bodyChild = -1, otherChild = -1;
  long lastSeen = std::numeric_limits<long>::min() / 2;
  long tipStep = std::numeric_limits<long>::min() / 2;
  bool flat = false;
  // the last step ended clamped at the patch's edge (tipping): the patch is
  // kept up to the facing limit, with no tilt correction, and starts the
  // step clamped (HandBack.*)
  bool pivoting = false;
  bool pivotOnly = false;     // this step: pivoting past twice the flatness tolerance
  bool sticking = false;      // the friction block stuck at the end of the last step
  bool overlapValid = false;  // see overlapPose
  // the faces' kinds when geometry's overlap was last clipped (see overlapPose)
  internal::Face::Kind overlapKinds[2] = {internal::Face::Kind::Polygon,
                                          internal::Face::Kind::Polygon};
  long pointsWritten = -1;     // step whose patch impulses are on the manifold's points
  double pendingBounce = 0.0;  // owed by a landing in step pendingBounceStep [m/s]
  long pendingBounceStep = -1;
  long shapeId = 0;           // unique per built `friction`
  double innerRadius2 = 0.0;  // parts::PatchOutlineSummary::innerRadius2 of `friction`
  bool sliver = false;        // `friction`'s shape is beyond kMaxSliverRatio
  parts::PressureRecord law;  // the pressure `friction` was last refreshed with
  // warm start in world axes (the patch frame turns with the body): normal
  // impulse, tilt couple, tangential friction impulse and slip, spin parts
  double normal = 0.0, frictionSpin = 0.0, slipSpin = 0.0;
  Vec3 couple = Vec3::Zero(), frictionT = Vec3::Zero(), slipT = Vec3::Zero();
  // relative pose of the touching shapes (B's leaf in A's leaf's frame: the
  // bodies', or their compound children's) when geometry's overlap was last
  // clipped
  btTransform overlapPose = btTransform::getIdentity();
  internal::DetectedPatch geometry;               // this step's patch
  std::optional<internal::PatchOutline> outline;  // shape of `friction`
  std::optional<FrictionPatch> friction;
  parts::StickCertificates certs;  // exact law only
};

// A state not seen since the cooldown of a tip: its manifold may have been
// deleted (and its address reused). Checked at the end of step `step`.
inline bool isStale(const PatchState& st, long step) {
  return st.lastSeen < step - kTipCooldownSteps - 1;
}

// One flat patch of one manifold, for one island solve. Every iteration
// streams over all of them, so what a visit reads lies together, copied in
// from the PatchState (shape, fb.law).
struct PatchConstraint {
  // read by every visit, a skipped one included
  bool settled =
      false;  // the last visit changed nothing, and no body velocity changed since (snapshot)
  bool interior = true;  // centre of pressure on the patch: normal block bilateral
  bool tipping = false;
  // past twice the flatness tolerance while pivoting the normal block is its
  // pivot edge's rows only (never interior): the edge nearest pivotCop, a
  // point far beyond the edge of the last step's centre of pressure
  bool pivotOnly = false;
  Vec2 pivotCop = Vec2::Zero();
  PatchState* state = nullptr;
  parts::StackLinks stack;  // indices in the island's patches and Impl::holds
  int ids[2] = {-1, -1};    // a.id, b.id
  btVector3 snapshot[4];    // delta linear / angular velocity of a, then b
  BodyTerms a, b;
  Mat3 F = Mat3::Identity();  // columns ex, ey, n (world)
  Vec3 lamN = Vec3::Zero(), targetN = Vec3::Zero(), lamF = Vec3::Zero();
  parts::PatchOutlineSummary shape;
  parts::FrictionBlockState fb;
  // the normal block's compliance (S23): > 0 for a soft contact, whose
  // normal row converges to c_n = t_n - compliance Lambda_z; added to K6(0, 0)
  double compliance = 0.0;
  parts::PatchBlocks k;
  // read outside the iterations only
  Vec3 lamPush = Vec3::Zero(), targetPush = Vec3::Zero();
  btPersistentManifold* manifold = nullptr;  // whose points get the impulses (stage 6)
  // PatchMultiBodySolver: index of the patch's multibody terms (a side on
  // a Featherstone link), -1 for a patch between solver bodies
  int articulated = -1;
};

// What a PatchReport is made of, kept at the end of the step.
struct ReportSource {
  const PatchState* state = nullptr;
  Model model = Model::Ellipsoidal;
  bool sticking = false;
  double mu = 0.0, rho = 0.0, dt = 0.0;
  Vec3 lamN = Vec3::Zero(), lamF = Vec3::Zero();
  Vec3 slip = Vec3::Zero();  // x_o at the end of the step
};

// A manifold whose patch is selected, its solver rows pending.
struct Candidate {
  int index;
  PatchState* state;
  const PatchOptions* options;
  const btCollisionObject* A;
  const btCollisionObject* B;
  double mu;
  double restitution;  // Bullet's combined restitution of the pair
  bool wasFlat;
};

}  // namespace patchspin::bullet::internal
