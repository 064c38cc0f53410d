// Scene: a small owning Bullet world, with the PatchFrictionSolver or stock
// Bullet's btSequentialImpulseConstraintSolver, in the precision of this
// build's btScalar. The one world and body builder of the tests, demos,
// tools and benchmarks (Box2D-style scene builders in one place; the named
// scenes are in catalogue.hpp). Ground frame: z up. Not installed: part of
// the top-level build only.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>
#include <memory>
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/bullet/patch_solver_pool_mt.hpp>
#include <vector>

namespace patchspin::scenes {

// Which constraint solver the world steps with. Patch: PatchFrictionSolver
// (bodies opted in get patch friction, the others Bullet's own); Stock:
// Bullet's btSequentialImpulseConstraintSolver; PatchPoolMt: a
// btDiscreteDynamicsWorldMt with a PatchSolverPoolMt of kPoolSolvers
// solvers (islands solved as the task scheduler in place dispatches them).
enum class SolverKind { Patch, Stock, PatchPoolMt };
constexpr int kPoolSolvers = 2;

constexpr bool kDoublePrecision = sizeof(btScalar) == sizeof(double);
// "float" or "double": the precision of this build's btScalar.
inline const char* precisionName() {
  return kDoublePrecision ? "double" : "float";
}

inline btVector3 bt(double x, double y, double z) {
  return btVector3(btScalar(x), btScalar(y), btScalar(z));
}

// One part of a compound body (Scene::addCompound): its shape, its pose in
// the compound's frame, its mass [kg] and its principal moments of inertia
// about its own centre, in its own axes [kg m^2] (inertia.hpp).
struct CompoundPart {
  std::unique_ptr<btCollisionShape> shape;
  btTransform pose = btTransform::getIdentity();
  double mass = 0.0;
  btVector3 inertia{0, 0, 0};
};

// A Bullet transform as an Eigen isometry (rotation from its normalised
// quaternion), for drawing and for the core's plain structs.
inline Eigen::Isometry3d toIsometry(const btTransform& tr) {
  const btQuaternion q = tr.getRotation();
  const btVector3 o = tr.getOrigin();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(double(q.w()), double(q.x()), double(q.y()), double(q.z()))
                      .normalized()
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(double(o.x()), double(o.y()), double(o.z()));
  return pose;
}

class Scene {
 public:
  // Gravity -g z [m/s^2]; `iterations` solver iterations per step.
  explicit Scene(double g = 9.81, int iterations = 10, SolverKind kind = SolverKind::Patch);
  // A Patch scene whose world steps with `shared`, a solver owned by the
  // caller that may step other worlds too (it must outlive the scene).
  Scene(double g, int iterations, bullet::PatchFrictionSolver& shared);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  btDiscreteDynamicsWorld& world() { return *world_; }
  const btDiscreteDynamicsWorld& world() const { return *world_; }
  SolverKind kind() const { return kind_; }
  // The patch solver (PatchPoolMt: the pool's first, whose per-body API,
  // stats and reports are the pool's); throws Error in a Stock scene.
  bullet::PatchFrictionSolver& solver();
  const bullet::PatchFrictionSolver& solver() const;
  // The solver pool; throws Error unless PatchPoolMt.
  bullet::PatchSolverPoolMt& pool();

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
  // A btCompoundShape body of `parts` (each a child), whose compound frame
  // (the frame of the parts' poses) is placed at `start`. All masses 0: a
  // static body, the poses as given. Otherwise a dynamic body whose origin
  // is the parts' centre of mass c = sum m_i t_i / m (Bullet turns a body
  // about its origin): every pose is shifted by -c and the body placed at
  // start * (I, c); its inertia is the parts' by the parallel-axis theorem,
  //   J = sum R_i diag(J_i) R_i^T + m_i (|d_i|^2 I - d_i d_i^T),  d_i = t_i - c,
  // which must be diagonal in the compound's axes (products of inertia
  // within 1e-9 of the trace; otherwise Error: turn the parts so that the
  // compound's axes are principal). Margins are the parts' own.
  btRigidBody* addCompound(std::vector<CompoundPart> parts, const btTransform& start,
                           double friction);

  // A shape owned by the scene, to be shared by several bodies.
  btCollisionShape* addShape(std::unique_ptr<btCollisionShape> shape);
  // Data the scene keeps until its shapes are gone (a triangle mesh's
  // vertices, a heightfield's heights).
  template <class T>
  T* keep(std::unique_ptr<T> data) {
    T* raw = data.get();
    kept_.emplace_back(std::move(data));
    return raw;
  }
  // Any body: the given shape, mass [kg] (0: static), inertia [kg m^2],
  // start transform and friction; no restitution, no rolling or spinning
  // friction, dynamic bodies never deactivated (the runs decide themselves
  // when something has stopped). `group` >= 0: added with that collision
  // group and mask.
  btRigidBody* addBody(std::unique_ptr<btCollisionShape> shape, double mass,
                       const btVector3& inertia, const btTransform& start, double friction,
                       int group = -1, int mask = -1);
  btRigidBody* addBody(btCollisionShape* sharedShape, double mass, const btVector3& inertia,
                       const btTransform& start, double friction, int group = -1, int mask = -1);
  // Every body added, in the order added (static ones included).
  const std::vector<btRigidBody*>& bodies() const { return bodyList_; }

  // One world step of exactly dt [s] (stepSimulation(dt, 0)).
  void step(double dt);

  // Total kinetic energy of the dynamic bodies [J].
  double kineticEnergy() const;

 private:
  SolverKind kind_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;  // Patch, Stock
  std::unique_ptr<bullet::PatchSolverPoolMt> pool_;              // PatchPoolMt
  bullet::PatchFrictionSolver* shared_ = nullptr;                // a caller's solver
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::shared_ptr<void>> kept_;  // (destroyed after the shapes)
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<btRigidBody*> bodyList_;
};

}  // namespace patchspin::scenes
