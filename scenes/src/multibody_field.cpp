// MultiBodyField (multibody_field.hpp).
#include <patchspin/scenes/mean_distance.hpp>
#include <patchspin/scenes/multibody_field.hpp>
#include <patchspin/scenes/turn_angle.hpp>

#include <algorithm>
#include <cmath>

namespace patchspin::scenes {
namespace {

// gripper: the gripper test's (tests/bullet/multibody_patches_test.cpp)
constexpr double kCubeHalf = 0.03, kCubeMass = 1.0, kSqueeze = 20.0, kPadHalf = 0.02;
constexpr double kPadThickness = 0.01, kFingerMass = 0.1, kGripMu = 0.5, kGripSpacing = 0.3;
// foot: the flat-foot test's
constexpr double kG = 9.81, kFootMu = 0.6, kFootMass = 1.0, kShinMass = 2.0, kFootSpacing = 0.4;
const btVector3 kFootHalf(btScalar(0.08), btScalar(0.04), btScalar(0.01));
const btVector3 kShinHalf(btScalar(0.03), btScalar(0.03), btScalar(0.1));

// Grid point i of a square grid of n points, `spacing` apart, in z = 0.
btVector3 gridPoint(int i, int n, double spacing) {
  const int side = int(std::ceil(std::sqrt(double(n))));
  return bt(spacing * (i % side), spacing * (i / side), 0.0);
}

}  // namespace

const char* toString(MultiBodyFieldKind k) {
  return k == MultiBodyFieldKind::Grippers ? "grippers" : "feet";
}

MultiBodyFieldKind multiBodyFieldKindFromString(const std::string& name) {
  if (name == "grippers") return MultiBodyFieldKind::Grippers;
  if (name == "feet") return MultiBodyFieldKind::Feet;
  throw Error("multibody field must be grippers or feet: got " + name);
}

MultiBodyField::MultiBodyField(MultiBodyFieldKind kind, int n, SpeedVariant variant)
    : kind_(kind), n_(n) {
  if (n < 1) throw Error("MultiBodyField: n must be positive");
  const bool stock = variant == SpeedVariant::Stock || variant == SpeedVariant::StockControl;
  const bool grippers = kind == MultiBodyFieldKind::Grippers;
  scene_ = std::make_unique<MultiBodyScene>(grippers ? 0.0 : kG, 10, !stock);
  if (grippers) {
    const btVector3 pad = bt(kPadHalf, kPadThickness, kPadHalf);
    for (int i = 0; i < n; ++i) {
      const btVector3 c = gridPoint(i, n, kGripSpacing);
      // the fingers start 1 mm off the cube and close on it
      const MultiBodyScene::Gripper g =
          scene_->addGripper(pad, kFingerMass, kCubeHalf + 1e-3, kSqueeze, 1.0, 1e-3, c);
      cubes_.push_back(scene_->addBox(bt(kCubeHalf, kCubeHalf, kCubeHalf), kCubeMass, c, kGripMu));
      for (int link = 0; link < 2; ++link) opted_.push_back(MultiBodyScene::collider(g.body, link));
    }
    limit_ = 2 * kGripMu * kSqueeze * meanDistanceOfRectangle(kPadHalf, kPadHalf);
    twist_ = 0.5 * limit_;
  } else {
    scene_->addGroundPlane(1.0);
    for (int i = 0; i < n; ++i) {
      const btVector3 c = gridPoint(i, n, kFootSpacing) + bt(0, 0, double(kFootHalf.z()));
      legs_.push_back(scene_->addLeg(kFootHalf, kFootMass, kShinHalf, kShinMass, c, kFootMu));
      opted_.push_back(MultiBodyScene::collider(legs_.back(), 0));
    }
    limit_ = kFootMu * (kFootMass + kShinMass) * kG *
             meanDistanceOfRectangle(double(kFootHalf.x()), double(kFootHalf.y()));
    twist_ = 0.8 * limit_;
  }
  if (variant == SpeedVariant::Ellipsoidal || variant == SpeedVariant::Exact) {
    const Model model = variant == SpeedVariant::Exact ? Model::Exact : Model::Ellipsoidal;
    for (btMultiBodyLinkCollider* c : opted_) scene_->solver().enablePatchFriction(c, {model});
  }
}

btQuaternion MultiBodyField::orientation(int i) const {
  return kind_ == MultiBodyFieldKind::Grippers ? cubes_[std::size_t(i)]->getOrientation()
                                               : legs_[std::size_t(i)]->getWorldToBaseRot();
}

void MultiBodyField::step() {
  if (steps_ == kSettleSteps) {
    for (int i = 0; i < n_; ++i) atTwist_.push_back(orientation(i));
    for (btRigidBody* cube : cubes_) cubeAtTwist_.push_back(cube->getWorldTransform().getOrigin());
  }
  if (steps_ >= kSettleSteps) {
    for (btRigidBody* cube : cubes_) cube->applyTorque(bt(0, twist_, 0));
    for (btMultiBody* leg : legs_) leg->addLinkTorque(0, bt(0, 0, twist_));
  }
  scene_->step(kDt);
  ++steps_;
}

double MultiBodyField::largestTurn() const {
  double turn = 0.0;
  for (std::size_t i = 0; i < atTwist_.size(); ++i)
    turn = std::max(turn, foldedTurnAngle(orientation(int(i)), atTwist_[i]));
  return turn;
}

double MultiBodyField::largestSlip() const {
  double slip = 0.0;
  for (std::size_t i = 0; i < cubeAtTwist_.size(); ++i) {
    const btVector3 d = cubes_[i]->getWorldTransform().getOrigin() - cubeAtTwist_[i];
    slip = std::max(slip, std::hypot(double(d.x()), double(d.z())));
  }
  return slip;
}

}  // namespace patchspin::scenes
