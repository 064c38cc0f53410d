// Patch selection (patch_selection.hpp): manifold -> candidate patch.
#include "patch_selection.hpp"

#include "compound_children.hpp"
#include "concave_support.hpp"

#include <patchspin/friction_block.hpp>

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <cmath>

namespace patchspin::bullet::internal {
namespace {

// A body that gets patches of its own: a rigid body with a positive inverse
// mass, or a Featherstone link collider (PatchMultiBodySolver) of a link or
// of a floating base that is neither static nor kinematic.
bool isDynamicObject(const btCollisionObject* o) {
  if (const btRigidBody* rb = btRigidBody::upcast(o)) return rb->getInvMass() > 0;
  if (const btMultiBodyLinkCollider* c = btMultiBodyLinkCollider::upcast(o))
    return c->m_multiBody && (c->m_link >= 0 || !c->m_multiBody->hasFixedBase()) &&
           !o->isStaticOrKinematicObject();
  return false;
}

// A face takes part in a patch only while the contact normal is within 45
// degrees of its normal (cosine): between the faces' own flatness (<= 2 x
// 0.02 rad by default) and a rim contact (~90 degrees) any cut separates them.
constexpr double kFacingAngle = 0.78539816339744831;  // pi/4
constexpr double kFacingCos = 0.70710678118654752;    // cos(kFacingAngle)
// a patch ends (2 x the flatness tolerance) before its faces stop facing
static_assert(2.0 * kMaxFlatnessTolerance <= kFacingAngle);
// A contact point lies on a face when it is within this many times the two
// shapes' summed collision margins of the face's plane: box and cylinder
// points lie within 0.05 of the summed margins, a hull's one margin outside
// (1.0); rim and side contacts lie at 1.86 and beyond (the pour and ConvexHull
// tests; docs/notes/solver-work-saving.md).
constexpr double kOnFaceMargins = 1.5;
// ... plus this many ulps of Bullet's scalar times the coordinates' size
// (two boxes with zero margins touch to ~1e-8 m in float).
constexpr double kOnFaceRoundOffUlps = 64.0;
// A patch outline within this fraction of its size of the outline its shape
// and law were built from keeps them (the law is then off by ~1e-4 relative at
// most, ten times below pressureLagTolerance); compared with the last
// rebuild's outline, so the drift does not accumulate
// (PatchShapeIsRebuiltOnlyWhenTheOutlineChanges).
constexpr double kOutlineRelTol = 1e-4;
// Bodies that moved relative to each other by less than this (translation
// relative to the patch size, rotation in radians) since their overlap was
// clipped keep that overlap (outline and O; ten times below kOutlineRelTol);
// the frame, gap and tilt are recomputed every step.
constexpr double kOverlapRelTol = 1e-5;
// The triangle under a contact point is looked for within the summed
// margins and the contact's depth, plus this [m]: with zero margins and a
// contact exactly on the triangle, Bullet's point is within float round-off
// of its plane (1e-6 m is ~100 ulps at 1 m).
constexpr double kTriangleSearchFloor = 1e-6;

// Every point of the manifold lies on both faces (A's point on A's face
// plane, B's on B's) to within kOnFaceMargins times the summed margins of
// the two leaf shapes: a contact anywhere else (a rim, a side) is not the
// faces touching.
bool contactOnFaces(const btPersistentManifold& m, bool aIs0, const internal::Face& faceA,
                    const internal::Face& faceB, btScalar margins) {
  const btScalar tol = btScalar(kOnFaceMargins) * margins;
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

}  // namespace

PatchSelection::PatchSelection() {
  for (auto& filter : flatFilter_) filter.assign(std::size_t(1) << (kFlatFilterLog2 - 6), 0);
}

// The options of an opted-in dynamic body (a static or kinematic body opted
// in has no patch of its own: what stands on it decides).
const PatchOptions* PatchSelection::dynamicOptions(const btCollisionObject* o) {
  if (!isDynamicObject(o)) return nullptr;
  return optIns_.optionsOf(o);
}

// PatchShape::disk is a function of the radius: a copy is the shape it would
// build; at most kDiskShapeCache are kept, the oldest replaced.
PatchShape PatchSelection::shapeOf(const internal::PatchOutline& outline) {
  if (!outline.isDisk()) return outline.toShape();
  for (const auto& entry : diskShapes_)
    if (entry.first == outline.radius) return entry.second;
  PatchShape shape = outline.toShape();
  if (diskShapes_.size() < kDiskShapeCache) {
    diskShapes_.emplace_back(outline.radius, shape);
  } else {
    diskShapes_[diskShapeNext_] = {outline.radius, shape};
    diskShapeNext_ = (diskShapeNext_ + 1) % kDiskShapeCache;
  }
  return shape;
}

// (cleared word by word where it was written, not as an 8 KB fill)
void PatchSelection::clearFlatFilter(int k) {
  for (const std::size_t word : flatWords_[k]) flatFilter_[k][word] = 0;
  flatWords_[k].clear();
}

const NotPatchedCounts* PatchSelection::notPatchedOf(const btCollisionObject* body) const {
  const auto it = notPatched_.find(body);
  return it == notPatched_.end() ? nullptr : &it->second;
}

void PatchSelection::countNotPatched(const btCollisionObject* A, const btCollisionObject* B,
                                     long NotPatchedCounts::*reason, PatchSolverStats& stats,
                                     const btCollisionShape* shapeA,
                                     const btCollisionShape* shapeB) {
  ++(stats.notPatched.*reason);
  ++(notPatched_[A].*reason);
  if (reason != &NotPatchedCounts::unsupportedShape || !unsupported_) return;
  const std::pair<int, int> types((shapeA ? shapeA : A->getCollisionShape())->getShapeType(),
                                  (shapeB ? shapeB : B->getCollisionShape())->getShapeType());
  if (std::find(reportedShapePairs_.begin(), reportedShapePairs_.end(), types) !=
      reportedShapePairs_.end())
    return;
  reportedShapePairs_.push_back(types);
  unsupported_(A, B);
}

void PatchSelection::beginStep() {
  notPatched_.clear();
  begun_ = false;
}

void PatchSelection::beginWorldStep() {
  ++step_;
  clearFlatFilter(int(step_ & 1));
  begun_ = true;
}

void PatchSelection::swapWorld(const void* world) {
  auto swapWith = [&](WorldRecord& r) {
    std::swap(r.states, states_);
    std::swap(r.step, step_);
    for (int k = 0; k < 2; ++k) {
      std::swap(r.flatFilter[k], flatFilter_[k]);
      std::swap(r.flatWords[k], flatWords_[k]);
    }
  };
  swapWith(worlds_[world_]);  // the world in hand put away
  WorldRecord& next = worlds_[world];
  for (int k = 0; k < 2; ++k)
    if (next.flatFilter[k].empty())
      next.flatFilter[k].assign(std::size_t(1) << (kFlatFilterLog2 - 6), 0);
  swapWith(next);
  world_ = world;
}

void PatchSelection::clearWrittenImpulses(btPersistentManifold* m) {
  const auto it = states_.find(m);
  if (it == states_.end() || it->second.pointsWritten != step_ - 1) return;
  for (int k = 0; k < m->getNumContacts(); ++k) {
    btManifoldPoint& p = m->getContactPoint(k);
    p.m_appliedImpulse = p.m_appliedImpulseLateral1 = p.m_appliedImpulseLateral2 = 0;
  }
}

void PatchSelection::endStep() {
  if (!begun_ || step_ % kSweepSteps != 0) return;
  for (auto it = states_.begin(); it != states_.end();) {
    if (isStale(it->second, step_))
      it = states_.erase(it);
    else
      ++it;
  }
}

bool PatchSelection::selectCandidate(btPersistentManifold* m, int index, double dt,
                                     PatchSolverStats& stats, std::vector<Candidate>& out) {
  // Empty manifolds (the broadphase keeps one for every pair whose bounding
  // boxes overlap, ~10 per touching one in a pile) become patches two ways:
  // a patch that ended the last step flat outlives an empty manifold while
  // its faces still touch (persistence), and a body opted in on a static or
  // kinematic plane, box or cylinder gets its patch without Bullet's contact
  // (probe: float Bullet misses a coin on a long box face or a large
  // cylinder cap until ~2.3 mm in; CoinHasItsPatchWhereBulletMissesTheContact).
  const bool empty = m->getNumContacts() == 0;
  const btCollisionObject* o0 = m->getBody0();
  const btCollisionObject* o1 = m->getBody1();
  PatchState* persisting = nullptr;
  bool probed = false;  // an empty manifold whose faces touch (probeSupportFace)
  btVector3 probeNormal(0, 0, 0);
  if (empty) {
    // one body static or kinematic, a plane, a box or a cylinder: its faces
    // are probed below (most empty manifolds of a pile are dynamic pairs)
    probed = probeable(*m);
    if (!probed) {
      if (!mayHaveBeenFlat(m)) return false;
      const auto it = states_.find(m);
      // (the same pair: a manifold deleted in this step's broadphase may
      // have been reused for another)
      if (it == states_.end() || !it->second.flat || it->second.lastSeen != step_ - 1 ||
          !((it->second.body == o0 && it->second.other == o1) ||
            (it->second.body == o1 && it->second.other == o0)))
        return false;
      persisting = &it->second;
    }
  }
  const PatchOptions* opt0 = dynamicOptions(o0);
  const PatchOptions* opt1 = dynamicOptions(o1);
  if (!opt0 && !opt1) return false;
  // a persisting patch stays the same body's, with the last step's normal
  if (persisting) {
    const bool body0 = persisting->body == o0;
    (body0 ? opt1 : opt0) = nullptr;
    if (!(body0 ? opt0 : opt1)) return false;  // no longer opted in
  }
  // an empty manifold's patch: the furthest its low side may be above the
  // other face (Bullet's contact-breaking distance)
  double reach = empty ? double(m->getContactBreakingThreshold()) : 0.0;
  if (probed) {
    // the support's face that the body's centre is outside of, and the
    // body's lowest point within that distance (either side), or one it
    // closes in this step at its present speed (a speculative contact)
    double clearance = 0.0;
    btVector3 lowest;
    const btCollisionObject* body = opt0 ? o0 : o1;
    const btCollisionObject* support = opt0 ? o1 : o0;
    if (!internal::probeSupportFace(*body, *support, &probeNormal, &clearance, &lowest))
      return false;
    auto pointVelocity = [&](const btCollisionObject* o) {
      const btRigidBody* rb = btRigidBody::upcast(o);
      return rb ? rb->getVelocityInLocalPoint(lowest - o->getWorldTransform().getOrigin())
                : btVector3(0, 0, 0);
    };
    const double approach =
        std::max(0.0, -double(probeNormal.dot(pointVelocity(body) - pointVelocity(support))));
    if (!(clearance >= -reach && clearance <= reach + approach * dt)) return false;
    reach += approach * dt;
  }
  // both opted in (a stack): the patch is the upper body's, the one the
  // normal enters against its gravity; without gravity, body0's. Manifold
  // normal: from body1 to body0.
  if (opt0 && opt1) {
    const btVector3 nInto0 = m->getContactPoint(0).m_normalWorldOnB;
    // (a link has no gravity of its own: the rigid body's, else body0's patch)
    const btRigidBody* rb0 = btRigidBody::upcast(o0);
    const btRigidBody* rb1 = btRigidBody::upcast(o1);
    const btVector3 g = rb0 ? rb0->getGravity() : rb1 ? rb1->getGravity() : btVector3(0, 0, 0);
    if (nInto0.dot(g) > 0)
      opt0 = nullptr;  // body0 is underneath
    else
      opt1 = nullptr;
  }
  const bool aIs0 = opt0 != nullptr;
  const PatchOptions& opt = aIs0 ? *opt0 : *opt1;
  const btCollisionObject* A = aIs0 ? o0 : o1;
  const btCollisionObject* B = aIs0 ? o1 : o0;
  // the compound children that touch: tagged on the points, or, without
  // points, those of the persisting patch (-1: not a compound)
  const int childA = persisting                 ? persisting->bodyChild
                     : internal::isCompound(*A) ? internal::taggedChild(*m, aIs0)
                                                : -1;
  const int childB = persisting                 ? persisting->otherChild
                     : internal::isCompound(*B) ? internal::taggedChild(*m, !aIs0)
                                                : -1;
  PatchState& st = states_[m];
  if (st.body != A || st.other != B || st.bodyChild != childA || st.otherChild != childB ||
      isStale(st, step_ - 1)) {
    st = PatchState();
    st.body = A;
    st.other = B;
    st.bodyChild = childA;
    st.otherChild = childB;
  }
  const bool wasFlat = st.flat && st.lastSeen >= step_ - 1;
  if (!wasFlat) st.pivoting = st.pivotOnly = false;
  st.lastSeen = step_;
  // A patch of the last step keeps its normal: Bullet's contact normal may
  // be spurious for a step (double hull on hull: one point with a sideways
  // normal, SupportMatrix.*; on triangles, a single triangle's edge: normals
  // sideways or reversed while a coin slides across a 1 cm grid). On
  // triangles the faces must also touch by their clearance, not by the
  // points (TriangleSupports.*).
  const bool onTriangles = internal::isTriangleSupport(*B->getCollisionShape());
  btVector3 nIntoA = persisting ? persisting->geometry.normal
                     : wasFlat  ? st.geometry.normal
                     : probed   ? probeNormal
                     : aIs0     ? m->getContactPoint(0).m_normalWorldOnB
                                : -m->getContactPoint(0).m_normalWorldOnB;
  // a new contact on triangles: the normal of the triangle under Bullet's
  // first point (within the summed margins plus the contact's depth)
  if (onTriangles && !wasFlat && !persisting && !empty) {
    const btManifoldPoint& p = m->getContactPoint(0);
    const double tol =
        double(A->getCollisionShape()->getMargin() + B->getCollisionShape()->getMargin()) +
        std::abs(double(p.getDistance())) + kTriangleSearchFloor;
    btVector3 n;
    if (internal::triangleNormalAt(*B->getCollisionShape(), B->getWorldTransform(),
                                   aIs0 ? p.m_positionWorldOnB : p.m_positionWorldOnA,
                                   A->getWorldTransform().getOrigin(), tol, &n))
      nIntoA = n;
  }
  if (onTriangles && !empty) reach = double(m->getContactBreakingThreshold());

  // faces and flatness, with hysteresis (B's face is looked up whenever A
  // has one: for a convex hull that builds the polyhedral features Bullet's
  // own contact clipping then uses)
  // (a compound's faces are its touching child's, at object x child pose)
  double cosA = 0.0, cosB = 0.0;
  internal::LeafShape leafA, leafB;
  const bool haveLeaves =
      internal::resolveLeaf(*A, childA, leafA) && internal::resolveLeaf(*B, childB, leafB);
  bool haveFaces =
      haveLeaves && internal::findFaceAlong(*leafA.shape, leafA.transform, -nIntoA, &cosA, faceA_);
  // on a triangle mesh or heightfield the support is the plane of the
  // triangles under A's facing face (concave_support.hpp), or a reason
  long NotPatchedCounts::*supportReason = nullptr;
  if (haveFaces && onTriangles) {
    cosB = 1.0;  // the plane's normal is A's face's, up to the flatness test
    if (cosA >= kFacingCos) {
      const double slack = double(m->getContactBreakingThreshold());
      switch (internal::findSupportPlane(*leafB.shape, leafB.transform, faceA_, slack, faceB_)) {
        case internal::SupportPlane::Found:
          cosB = double(faceB_.normal.dot(nIntoA));
          break;
        case internal::SupportPlane::BadMesh:
          supportReason = &NotPatchedCounts::badMesh;
          break;
        case internal::SupportPlane::Crease:
        case internal::SupportPlane::NoTriangle:
          supportReason = &NotPatchedCounts::crease;
          break;
      }
    }
  } else if (haveFaces) {
    haveFaces = internal::findFaceAlong(*leafB.shape, leafB.transform, nIntoA, &cosB, faceB_);
  }
  bool flat = false;
  long NotPatchedCounts::*reason = haveFaces ? nullptr : &NotPatchedCounts::unsupportedShape;
  std::optional<internal::DetectedPatch> geo;
  bool kept = false;  // st.geometry is this step's patch (geo unset)
  if (haveFaces && isDynamicObject(A)) {
    const double c = std::clamp(-double(faceA_.normal.dot(faceB_.normal)), -1.0, 1.0);
    // (a patch pivoting on a polygon's edge stays one up to the facing
    // limit; a disk's or a cut disk's pivot is a point of its rim, where the
    // face's law would resist the spin and the rolling of a coin on its rim
    // that a point contact does not: those go back to Bullet's points past
    // the flatness tolerance, as before)
    const bool pivoting = wasFlat && st.pivoting && st.friction &&
                          st.friction->shape().kind() == PatchShape::Kind::Polygon;
    const double tol = pivoting  ? kFacingAngle
                       : wasFlat ? 2.0 * opt.flatnessTolerance
                                 : opt.flatnessTolerance;
    st.pivotOnly = pivoting && !(std::acos(c) < 2.0 * opt.flatnessTolerance);
    // the faces must face the contact, and the contact must be on them (two
    // coins side by side touch rim to rim); the angle between the faces
    // last of the cheap tests: acos
    // (the first test that fails is the reason it is not a patch)
    reason = !(cosA >= kFacingCos && cosB >= kFacingCos) ? &NotPatchedCounts::sideContact
             : !(step_ - st.tipStep > kTipCooldownSteps) ? &NotPatchedCounts::tipCooldown
             : supportReason                             ? supportReason
             : !(std::acos(c) < tol)                     ? &NotPatchedCounts::notFlat
             : !(onTriangles || contactOnFaces(*m, aIs0, faceA_, faceB_,
                                               leafA.shape->getMargin() + leafB.shape->getMargin()))
                 ? &NotPatchedCounts::offFaces
                 : nullptr;
    flat = reason == nullptr;
    // x axis fixed in the moving body: a box spinning on a plane keeps the
    // same outline, and its cached shape, in this frame
    if (flat) {
      const btTransform rel = leafA.transform.inverseTimes(leafB.transform);
      bool keep = wasFlat && st.overlapValid && faceA_.kind == st.overlapKinds[0] &&
                  faceB_.kind == st.overlapKinds[1] &&
                  double((rel.getOrigin() - st.overlapPose.getOrigin()).length()) <=
                      kOverlapRelTol * st.geometry.outline.size();
      for (int row = 0; keep && row < 3; ++row)
        keep = double((rel.getBasis()[row] - st.overlapPose.getBasis()[row]).length()) <=
               kOverlapRelTol;
      // a disk on an infinite plane is its whole face wherever it stands:
      // the same outline (the radius, centred on O) at any relative pose
      // (DiskOnAPlaneKeepsItsOverlapWhileItSlides)
      keep = keep || (wasFlat && st.overlapValid && faceA_.kind == internal::Face::Kind::Disk &&
                      faceB_.kind == internal::Face::Kind::Plane &&
                      st.overlapKinds[0] == internal::Face::Kind::Disk &&
                      st.overlapKinds[1] == internal::Face::Kind::Plane &&
                      st.geometry.outline.isDisk() && st.geometry.outline.radius == faceA_.radius);
      // a kept overlap is updated in place (no copy of its outline)
      const btVector3 xHint = A->getWorldTransform().getBasis().getColumn(0);
      if (keep) {
        internal::refreshFrame(faceA_, faceB_, xHint, st.geometry);
        kept = true;
      } else {
        geo = internal::buildPatch(faceA_, faceB_, xHint);
      }
      if (geo) {
        st.overlapPose = rel;
        st.overlapKinds[0] = faceA_.kind;
        st.overlapKinds[1] = faceB_.kind;
        st.overlapValid = true;
      }
    }
  }
  st.flat = flat && (kept || geo.has_value());
  if (flat && !st.flat) reason = &NotPatchedCounts::noOverlap;
  // without Bullet's contact, or on triangles, the faces themselves must touch
  if (st.flat && (empty || onTriangles) && !((kept ? st.geometry : *geo).clearance <= reach)) {
    st.flat = false;
    reason = &NotPatchedCounts::offFaces;
  }
  if (!st.flat) {
    st.pivoting = st.pivotOnly = false;
    if (!empty && reason)
      countNotPatched(A, B, reason, stats, haveLeaves ? leafA.shape : nullptr,
                      haveLeaves ? leafB.shape : nullptr);
    return false;
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
      const PatchShape shape = shapeOf(outline);
      st.friction.emplace(shape, LinearPressure::uniform(shape, 1.0), mu, opt.rho ? *opt.rho : 0.0);
      st.outline = outline;
      st.law.pressureCop = shape.centroid();  // uniform pressure
      st.law.piInvValid = false;
      st.certs.invalidate();
      st.shapeId = ++shapeCount_;
      st.innerRadius2 = parts::innerRadiusSquared(shape);
      st.sliver = sliverRatio(shape) > kMaxSliverRatio;
      ++stats.shapeRebuilds;
    } catch (const Error&) {
      st.flat = false;  // degenerate overlap: leave it to Bullet
      st.friction.reset();
      st.outline.reset();
      if (!empty) countNotPatched(A, B, &NotPatchedCounts::lawRefused, stats);
      return false;
    }
  }
  if (st.friction->mu() != mu) {
    try {
      st.friction->setMu(mu);
    } catch (const Error&) {
      st.flat = false;  // a coefficient the law cannot take (mu Pz overflows): Bullet's contact
      st.friction.reset();
      st.outline.reset();
      if (!empty) countNotPatched(A, B, &NotPatchedCounts::lawRefused, stats);
      return false;
    }
  }
  // a sliver (an edge on a face): the exact law may have no digits on it,
  // nor the pressure's projection (nearestAdmissibleLoads); decided here,
  // before either, for both laws (Slivers.*)
  if (st.sliver) {
    st.flat = false;
    if (!empty) countNotPatched(A, B, &NotPatchedCounts::sliver, stats);
    return false;
  }
  // Bullet's rows of this manifold are replaced: start them from zero if the
  // contact goes back to Bullet later (after a step that ended flat they are
  // zero already)
  if (!wasFlat) {
    for (int k = 0; k < m->getNumContacts(); ++k) {
      btManifoldPoint& p = m->getContactPoint(k);
      p.m_appliedImpulse = p.m_appliedImpulseLateral1 = p.m_appliedImpulseLateral2 = 0;
    }
  }
  // (and its combined restitution, alike)
  const double restitution = empty ? double(gCalculateCombinedRestitutionCallback(o0, o1))
                                   : double(m->getContactPoint(0).m_combinedRestitution);
  out.push_back({index, &st, &opt, A, B, mu, restitution, wasFlat});
  markFlat(m);
  return true;
}

}  // namespace patchspin::bullet::internal
