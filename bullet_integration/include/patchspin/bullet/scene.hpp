// A small owning Bullet world with a PatchFrictionSolver, shared by the
// tests, the benchmarks and anyone who wants a quick scene (Box2D-style
// scene builders in one place). Ground frame: z up.
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

namespace patchspin::bullet {

class Scene {
 public:
  // Gravity -g z [m/s^2]; `iterations` solver iterations per step.
  explicit Scene(double g = 9.81, int iterations = 10);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  btDiscreteDynamicsWorld& world() { return *world_; }
  PatchFrictionSolver& solver() { return *solver_; }

  // Static plane z = 0 with the given friction (Bullet multiplies the two
  // bodies' frictions: 1 leaves the body's own).
  btRigidBody* addGroundPlane(double friction = 1.0);
  // Solid cylinder (radius R, height H [m]) with its axis along z, exact
  // inertia; centre of mass at `position`. Margin [m] of the collision shape.
  btRigidBody* addCylinder(double R, double H, double mass, const btVector3& position,
                           double friction, double margin = 1e-3);
  // Solid box with half extents `half` [m], exact inertia.
  btRigidBody* addBox(const btVector3& half, double mass, const btVector3& position,
                      double friction, double margin = 1e-3);
  btRigidBody* addSphere(double radius, double mass, const btVector3& position, double friction);
  // A static box (mass 0).
  btRigidBody* addStaticBox(const btVector3& half, const btVector3& position, double friction);

  // One world step of exactly dt [s] (stepSimulation(dt, 0)).
  void step(double dt);

  // Total kinetic energy of the dynamic bodies [J].
  double kineticEnergy() const;

 private:
  btRigidBody* addBody(std::unique_ptr<btCollisionShape> shape, double mass, const btVector3& inertia,
                       const btVector3& position, double friction);

  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<PatchFrictionSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

}  // namespace patchspin::bullet
