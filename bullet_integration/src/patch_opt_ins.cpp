// Patch opt-ins (patch_opt_ins.hpp).
#include "patch_opt_ins.hpp"

#include <atomic>
#include <string>

namespace patchspin::bullet::internal {
namespace {

// Tags 1 .. kMaxTag, in the order the solvers are made (a body opted in by
// one solver is not opted in for another, unless 2047 solvers apart).
int nextTag() {
  static std::atomic<unsigned> counter{0};
  return int(counter.fetch_add(1, std::memory_order_relaxed) % unsigned(PatchOptIns::kMaxTag)) + 1;
}

}  // namespace

PatchOptIns::PatchOptIns() : tag_(nextTag()) {}

PatchOptIns::Key PatchOptIns::keyOf(const PatchOptions& o) {
  return {int(o.model),      o.mu.has_value(),    o.mu.value_or(0.0),
          o.rho.has_value(), o.rho.value_or(0.0), o.flatnessTolerance};
}

int PatchOptIns::slotOf(const PatchOptions& options) {
  const Key key = keyOf(options);
  auto it = slots_.find(key);
  if (it == slots_.end()) {
    if (options_.size() >= kMaxOptions)
      throw Error("enablePatchFriction: more than " + std::to_string(kMaxOptions) +
                  " distinct PatchOptions in one solver");
    options_.push_back(options);
    it = slots_.emplace(key, int(options_.size())).first;
  }
  return it->second;
}

void PatchOptIns::enable(btRigidBody& body, const PatchOptions& options) {
  const int slot = slotOf(options);
  if (!optionsOf(&body)) ++optedIn_;
  body.m_frictionSolverType = (tag_ << kIndexBits) | slot;
}

void PatchOptIns::enable(btMultiBodyLinkCollider& collider, const PatchOptions& options) {
  // a code has a tag in 1 .. kMaxTag: anything else non-null is not ours
  const int code = codeOf(collider);
  if (code != 0 && (code < 0 || (code >> kIndexBits) < 1))
    throw Error(
        "enablePatchFriction: the link collider's extension pointer "
        "(btCollisionObject::internalSetExtensionPointer) is in use; patch friction keeps its "
        "opt-in there");
  const int slot = slotOf(options);
  if (!optionsOf(&collider)) ++optedIn_;
  collider.internalSetExtensionPointer(
      reinterpret_cast<void*>(std::uintptr_t(unsigned((tag_ << kIndexBits) | slot))));
}

void PatchOptIns::disable(btMultiBodyLinkCollider& collider) {
  if (!optionsOf(&collider)) return;
  collider.internalSetExtensionPointer(nullptr);
  --optedIn_;
}

void PatchOptIns::disable(btRigidBody& body) {
  if (!optionsOf(&body)) return;
  body.m_frictionSolverType = 0;
  --optedIn_;
}

}  // namespace patchspin::bullet::internal
