// Patch opt-ins (internal): which bodies a PatchFrictionSolver gives patch
// friction, and with which options. The opt-in is kept in the body itself,
// in btRigidBody::m_frictionSolverType (declared "for experimental
// overriding of friction/contact solver func", zeroed by btRigidBody's
// constructor and read nowhere else in Bullet), as
//   m_frictionSolverType = tag << kIndexBits | (index + 1)
// with `tag` this table's (one per solver) and `index` the options' slot in
// it. The table holds each distinct PatchOptions value once, so it grows
// with the distinct options enabled, never with the bodies: a body's opt-in
// ends with the body, and a new body (at any address) starts with 0, not
// opted in (BodyLifetime.*).
// A btMultiBodyLinkCollider (PatchMultiBodySolver) has no such field: its
// opt-in is kept in this table, by address, until disable (a collider must
// be opted out before it is deleted; MultiBodyPatches.OptInOfALinkCollider).
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>

#include <deque>
#include <map>
#include <tuple>
#include <unordered_map>

namespace patchspin::bullet::internal {

class PatchOptIns {
 public:
  PatchOptIns();

  // Opts `body` in with `options` (interned); throws Error when the table
  // holds kMaxOptions distinct values already.
  void enable(btRigidBody& body, const PatchOptions& options);
  // Opts `body` out if this table opted it in (else leaves it alone).
  void disable(btRigidBody& body);
  // The same for a collision object that is not a btRigidBody (a link
  // collider), kept by address.
  void enableObject(const btCollisionObject& o, const PatchOptions& options);
  void disableObject(const btCollisionObject& o);
  // The options of `o` if this table opted it in, else null (any other
  // object type, another solver's opt-in, or none). The pointer is stable
  // for the table's life.
  const PatchOptions* optionsOf(const btCollisionObject* o) const {
    const btRigidBody* rb = btRigidBody::upcast(o);
    if (!rb) return objects_.empty() ? nullptr : objectOptionsOf(o);
    const int code = rb->m_frictionSolverType;
    if (code <= 0 || (code >> kIndexBits) != tag_) return nullptr;
    const std::size_t slot = std::size_t(code & kIndexMask);
    return slot >= 1 && slot <= options_.size() ? &options_[slot - 1] : nullptr;
  }
  // False while no body was opted in, or since every body opted in was
  // opted out again (a body deleted while opted in keeps this true: the
  // solver then merely looks at its manifolds).
  bool any() const { return optedIn_ > 0; }

  // 31 bits of a non-negative int: 11 of tag (2047 solvers before a tag
  // is reused), 20 of slot (1048575 distinct options per solver).
  static constexpr int kIndexBits = 20;
  static constexpr int kIndexMask = (1 << kIndexBits) - 1;
  static constexpr int kMaxTag = (1 << (31 - kIndexBits)) - 1;
  static constexpr std::size_t kMaxOptions = std::size_t(kIndexMask);

 private:
  using Key = std::tuple<int, bool, double, bool, double, double>;
  static Key keyOf(const PatchOptions& o);
  int slotOf(const PatchOptions& options);  // interned, 1-based
  const PatchOptions* objectOptionsOf(const btCollisionObject* o) const;
  std::unordered_map<const btCollisionObject*, int> objects_;  // non-rigid opt-ins -> slot
  int tag_;
  std::deque<PatchOptions> options_;  // slot - 1 -> options (deque: stable addresses)
  std::map<Key, int> slots_;          // options -> slot
  long optedIn_ = 0;                  // enable of a body not opted in minus disable of one
};

}  // namespace patchspin::bullet::internal
