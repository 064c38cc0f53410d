// Grasp (grasp.hpp).
#include <patchspin/scenes/grasp.hpp>

namespace patchspin::scenes {

Grasp::Grasp(GraspWorld world, const GraspSpec& spec, std::optional<Model> model)
    : world_(world), spec_(spec), patch_(model.has_value()) {
  const btVector3 padHalf = bt(spec.padHalf, spec.padHalfDepth, spec.padHalf);
  const btVector3 cubeHalf = bt(spec.cubeHalf, spec.cubeHalf, spec.cubeHalf);
  const double gap = spec.cubeHalf + spec.clearance;  // pad face from the x-z plane
  if (world == GraspWorld::MultiBody) {
    multiBody_ = std::make_unique<MultiBodyScene>(0.0, spec.iterations, patch_);
    const MultiBodyScene::Gripper gripper =
        multiBody_->addGripper(padHalf, spec.padMass, gap, spec.squeeze, 1.0);
    cube_ = multiBody_->addBox(cubeHalf, spec.cubeMass, bt(0, 0, 0), spec.mu);
    for (int i = 0; i < 2; ++i) {
      pads_[i] = MultiBodyScene::collider(gripper.body, i);
      if (patch_) multiBody_->solver().enablePatchFriction(pads_[i], {*model});
    }
    return;
  }
  rigid_ =
      std::make_unique<Scene>(0.0, spec.iterations, patch_ ? SolverKind::Patch : SolverKind::Stock);
  const double offset = gap + spec.padHalfDepth;
  for (int i = 0; i < 2; ++i) {
    btRigidBody* p =
        rigid_->addBox(padHalf, spec.padMass, bt(0, i == 0 ? -offset : offset, 0), 1.0);
    p->setLinearFactor(bt(0, 1, 0));
    p->setAngularFactor(0);
    rigidPads_[i] = p;
    pads_[i] = p;
  }
  cube_ = rigid_->addBox(cubeHalf, spec.cubeMass, bt(0, 0, 0), spec.mu);
  if (patch_)
    for (btRigidBody* p : rigidPads_) rigid_->solver().enablePatchFriction(p, {*model});
}

Grasp::~Grasp() = default;

void Grasp::step(double dt, double tau) {
  cube_->applyTorque(bt(0, tau, 0));
  if (rigid_) {
    rigidPads_[0]->applyCentralForce(bt(0, spec_.squeeze, 0));
    rigidPads_[1]->applyCentralForce(bt(0, -spec_.squeeze, 0));
    rigid_->step(dt);
  } else {
    multiBody_->step(dt);
  }
}

btTransform Grasp::padPose(int i) const {
  return pads_[i]->getWorldTransform();
}

const bullet::PatchReport* Grasp::report(int i) const {
  if (!patch_) return nullptr;
  return rigid_ ? rigid_->solver().findPatchReport(pads_[i])
                : multiBody_->solver().findPatchReport(pads_[i]);
}

int Grasp::reportCount() const {
  if (!patch_) return 0;
  return int(rigid_ ? rigid_->solver().patchReports().size()
                    : multiBody_->solver().patchReports().size());
}

}  // namespace patchspin::scenes
