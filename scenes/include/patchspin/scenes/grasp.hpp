// Grasp: the twisted grasp of issue 33. A solid cube is squeezed with the
// force N between two flat pads, normal +-y; a twist torque tau about the
// grasp axis y acts on the cube. No gravity, so that the pads' friction only
// resists the twist. The grasp is built in either world:
//   MultiBody  a MultiBodyScene (btMultiBodyDynamicsWorld) with
//              MultiBodyScene::addGripper: two finger links on prismatic
//              joints along y whose velocity motors press with at most N;
//              PatchMultiBodySolver or stock btMultiBodyConstraintSolver
//   Rigid      a Scene (btDiscreteDynamicsWorld): each pad a rigid box that
//              can only slide along y (linear factor (0, 1, 0), angular
//              factor 0), pushed towards the cube with the force N every
//              step; PatchFrictionSolver or stock Bullet
// The cube (a btRigidBody in both) has friction mu, the pads 1 (Bullet
// multiplies the two: the pair's mu). With a patch law the pads are opted
// in. The pads start `clearance` off the cube and close on it.
// Used by tests/bullet/multibody_patches_test.cpp and demos/grasp.cpp.
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/multibody_scene.hpp>
#include <patchspin/scenes/scene.hpp>

#include <memory>
#include <optional>

namespace patchspin::scenes {

struct GraspSpec {
  double cubeHalf = 0.03;      // half side of the cube [m]
  double cubeMass = 1.0;       // [kg]
  double mu = 0.5;             // the cube's friction (the pads' is 1) [-]
  double padHalf = 0.02;       // half side of the square pad face [m]
  double padHalfDepth = 0.01;  // half thickness of a pad along y [m]
  double padMass = 0.1;        // [kg]
  double squeeze = 20.0;       // N, each pad's pressing force [N]
  double clearance = 1e-3;     // gap between each pad and the cube at the start [m]
  int iterations = 10;         // solver iterations per step
};

enum class GraspWorld { MultiBody, Rigid };

class Grasp {
 public:
  // model: the patch law of the pads, or none for stock Bullet.
  Grasp(GraspWorld world, const GraspSpec& spec, std::optional<Model> model);
  ~Grasp();
  Grasp(const Grasp&) = delete;
  Grasp& operator=(const Grasp&) = delete;

  // Applies the twist tau [N m] about +y to the cube (and, in the Rigid
  // world, the squeeze to the pads), then steps the world by dt [s].
  void step(double dt, double tau);

  GraspWorld world() const { return world_; }
  bool patch() const { return patch_; }
  btRigidBody* cube() const { return cube_; }
  // The collision object of pad i (0: on the -y side, 1: +y) and its pose.
  btCollisionObject* pad(int i) const { return pads_[i]; }
  btTransform padPose(int i) const;
  // The patch report of pad i after the last step, or nullptr (stock, or
  // no patch).
  const bullet::PatchReport* report(int i) const;
  // Number of patch reports after the last step (0 in a stock world).
  int reportCount() const;

 private:
  GraspWorld world_;
  GraspSpec spec_;
  bool patch_;
  std::unique_ptr<MultiBodyScene> multiBody_;
  std::unique_ptr<Scene> rigid_;
  btRigidBody* cube_ = nullptr;
  btCollisionObject* pads_[2] = {nullptr, nullptr};
  btRigidBody* rigidPads_[2] = {nullptr, nullptr};
};

}  // namespace patchspin::scenes
