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
// code is kept in btCollisionObject::m_extensionPointer instead (zeroed by
// the constructor and read nowhere in Bullet), as the same int converted to
// a pointer; enable refuses a collider whose pointer is set to anything
// else. So a link collider's opt-in ends with the collider too
// (LinkColliderLifetime.*).
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>

#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <cstdint>
#include <deque>
#include <map>
#include <tuple>

namespace patchspin::bullet::internal {

class PatchOptIns {
 public:
  PatchOptIns();

  // Opts `body` in with `options` (interned); throws Error when the table
  // holds kMaxOptions distinct values already.
  void enable(btRigidBody& body, const PatchOptions& options);
  // Opts `body` out if this table opted it in (else leaves it alone).
  void disable(btRigidBody& body);
  // The same for a link collider, its code in the extension pointer.
  // Throws Error when that pointer holds something that is not an opt-in's
  // code (a user's or an extension's pointer: left as it is).
  void enable(btMultiBodyLinkCollider& collider, const PatchOptions& options);
  void disable(btMultiBodyLinkCollider& collider);
  // The options of `o` if this table opted it in, else null (any other
  // object type, another solver's opt-in, or none). The pointer is stable
  // for the table's life.
  const PatchOptions* optionsOf(const btCollisionObject* o) const {
    if (const btRigidBody* rb = btRigidBody::upcast(o))
      return optionsOfCode(rb->m_frictionSolverType);
    if (const btMultiBodyLinkCollider* c = btMultiBodyLinkCollider::upcast(o))
      return optionsOfCode(codeOf(*c));
    return nullptr;
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
  const PatchOptions* optionsOfCode(int code) const {
    if (code <= 0 || (code >> kIndexBits) != tag_) return nullptr;
    const std::size_t slot = std::size_t(code & kIndexMask);
    return slot >= 1 && slot <= options_.size() ? &options_[slot - 1] : nullptr;
  }
  // A collider's code: its extension pointer as an int, or -1 when the
  // pointer is set and not in the codes' range (0 .. INT32_MAX).
  static int codeOf(const btMultiBodyLinkCollider& c) {
    const std::uintptr_t v = reinterpret_cast<std::uintptr_t>(c.internalGetExtensionPointer());
    return v <= std::uintptr_t(INT32_MAX) ? int(v) : -1;
  }
  int tag_;
  std::deque<PatchOptions> options_;  // slot - 1 -> options (deque: stable addresses)
  std::map<Key, int> slots_;          // options -> slot
  long optedIn_ = 0;                  // enable of a body not opted in minus disable of one
};

}  // namespace patchspin::bullet::internal
