// MultiBodyScene: a small owning btMultiBodyDynamicsWorld with the
// PatchMultiBodySolver or stock Bullet's btMultiBodyConstraintSolver, in the
// precision of this build's btScalar: the multibody counterpart of Scene
// (scene.hpp), with the same conventions (z up, no sleeping, no damping, no
// restitution, exact inertia, margins given). Not installed.
#pragma once

#include <patchspin/bullet/patch_multibody_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <memory>
#include <vector>

namespace patchspin::scenes {

class MultiBodyScene {
 public:
  // Gravity -g z [m/s^2]; `iterations` solver iterations per step; patch:
  // PatchMultiBodySolver, else btMultiBodyConstraintSolver.
  explicit MultiBodyScene(double g = 9.81, int iterations = 10, bool patch = true);
  ~MultiBodyScene();
  MultiBodyScene(const MultiBodyScene&) = delete;
  MultiBodyScene& operator=(const MultiBodyScene&) = delete;

  btMultiBodyDynamicsWorld& world() { return *world_; }
  bool patch() const { return patch_ != nullptr; }
  // The patch solver; throws Error in a stock scene.
  bullet::PatchMultiBodySolver& solver();

  // Static plane z = 0 (a btRigidBody), friction as Scene::addGroundPlane.
  btRigidBody* addGroundPlane(double friction = 1.0);
  // A rigid body: a solid box with half extents `half` [m], exact inertia.
  btRigidBody* addBox(const btVector3& half, double mass, const btVector3& position,
                      double friction, double margin = 1e-3);
  // A rigid body: a solid cylinder along z (radius R, height H), exact
  // inertia.
  btRigidBody* addCylinder(double R, double H, double mass, const btVector3& position,
                           double friction, double margin = 1e-3);
  // A floating-base multibody without links whose base collider is a
  // solid cylinder along z (radius R, height H), exact inertia.
  btMultiBody* addCylinderBase(double R, double H, double mass, const btVector3& position,
                               double friction, double margin = 1e-3);
  // A floating-base multibody without links whose base collider is a box.
  btMultiBody* addBoxBase(const btVector3& half, double mass, const btVector3& position,
                          double friction, double margin = 1e-3);
  // A fixed-base multibody whose one link, a box with half extents `half`,
  // slides along x on a prismatic joint (its origin at `position` for
  // joint position 0; no collision with the base), moving at `speed` [m/s],
  // with a velocity motor (target `speed`, at most maxForce [N]).
  struct Prismatic {
    btMultiBody* body = nullptr;
    btMultiBodyJointMotor* motor = nullptr;
  };
  Prismatic addPrismaticBox(const btVector3& half, double mass, const btVector3& position,
                            double friction, double speed, double maxForce, double margin = 1e-3);
  // A two-finger gripper: a fixed base (no collider) at `origin` and two
  // finger links, boxes with half extents `pad`, on prismatic joints along
  // y, their inner faces (the pads, normal +-y) `gap` [m] from the x-z
  // plane; each finger's velocity motor closes at 0.05 m/s with at most
  // `squeeze` [N], so a finger blocked by an object presses on it with
  // exactly that force. Link 0 is on the -y side (y and the x-z plane
  // relative to `origin`).
  struct Gripper {
    btMultiBody* body = nullptr;
    btMultiBodyJointMotor* motors[2] = {nullptr, nullptr};
  };
  Gripper addGripper(const btVector3& pad, double fingerMass, double gap, double squeeze,
                     double friction, double margin = 1e-3,
                     const btVector3& origin = btVector3(0, 0, 0));
  // A short leg: a floating base, a box `shin` (no collider), and fixed
  // below it link 0, the foot, a box with half extents `foot`, its centre
  // at `footCentre`, the shin's centre straight above it.
  btMultiBody* addLeg(const btVector3& foot, double footMass, const btVector3& shin,
                      double shinMass, const btVector3& footCentre, double friction,
                      double margin = 1e-3);
  // One multibody whose links touch each other (self-collision on): a fixed
  // base at the origin; link 0, a carriage (no collider, mass sliderMass)
  // on a prismatic joint along y; link 1 on it, a table (box, half extents
  // `table`, top at z = 0) on a prismatic joint along x, moving at `speed`
  // with a velocity motor of at most maxForce [N]; link 2, a slider (no
  // collider, sliderMass) on a prismatic joint along z; link 3, a block
  // (box, half extents `block`) on a spherical joint at its centre on the
  // slider, standing on the table: it may sink, tilt and turn, not slide.
  btMultiBody* addBlockOverTable(const btVector3& table, double tableMass, const btVector3& block,
                                 double blockMass, double sliderMass, double speed, double maxForce,
                                 double friction, double margin = 1e-3);
  // The collider of link `link` (-1: the base).
  static btMultiBodyLinkCollider* collider(btMultiBody* body, int link);

  // One world step of exactly dt [s] (stepSimulation(dt, 0)); the motors'
  // impulse limits follow dt.
  void step(double dt);

 private:
  btRigidBody* addRigid(std::unique_ptr<btCollisionShape> shape, double mass,
                        const btVector3& inertia, const btVector3& position, double friction);
  btMultiBodyLinkCollider* addCollider(btMultiBody* body, int link,
                                       std::unique_ptr<btCollisionShape> shape,
                                       const btTransform& pose, double friction, bool isStatic);
  btMultiBody* addMultiBody(std::unique_ptr<btMultiBody> body);
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btMultiBodyConstraintSolver> solver_;
  bullet::PatchMultiBodySolver* patch_ = nullptr;  // solver_, when it is one
  std::unique_ptr<btMultiBodyDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btMultiBody>> multiBodies_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;
  struct Motor {
    std::unique_ptr<btMultiBodyJointMotor> motor;
    double maxForce;
  };
  std::vector<Motor> motors_;
};

}  // namespace patchspin::scenes
