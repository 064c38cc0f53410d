// Scene: an owning Bullet world (see scene.hpp).
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/scene.hpp>

namespace patchspin::scenes {
namespace {
std::unique_ptr<btSequentialImpulseConstraintSolver> makeSolver(SolverKind kind) {
  if (kind == SolverKind::PatchPoolMt) return nullptr;
  if (kind == SolverKind::Stock) return std::make_unique<btSequentialImpulseConstraintSolver>();
  return std::make_unique<bullet::PatchFrictionSolver>();
}
std::unique_ptr<bullet::PatchSolverPoolMt> makePool(SolverKind kind) {
  if (kind != SolverKind::PatchPoolMt) return nullptr;
  return std::make_unique<bullet::PatchSolverPoolMt>(kPoolSolvers);
}
}  // namespace

Scene::Scene(double g, int iterations, SolverKind kind)
    : kind_(kind),
      config_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(makeSolver(kind)),
      pool_(makePool(kind)) {
  if (pool_)
    world_ = std::make_unique<btDiscreteDynamicsWorldMt>(dispatcher_.get(), broadphase_.get(),
                                                         pool_.get(), nullptr, config_.get());
  else
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), config_.get());
  world_->setGravity(bt(0, 0, -g));
  world_->getSolverInfo().m_numIterations = iterations;
}

Scene::Scene(double g, int iterations, bullet::PatchFrictionSolver& shared)
    : kind_(SolverKind::Patch),
      config_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      shared_(&shared),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       &shared, config_.get())) {
  world_->setGravity(bt(0, 0, -g));
  world_->getSolverInfo().m_numIterations = iterations;
}

Scene::~Scene() {
  for (auto& b : bodies_)
    if (b->isInWorld()) world_->removeRigidBody(b.get());
}

bullet::PatchFrictionSolver& Scene::solver() {
  if (kind_ == SolverKind::Stock)
    throw Error("Scene::solver: this scene steps with stock Bullet's solver");
  if (pool_) return pool_->solver(0);
  if (shared_) return *shared_;
  return static_cast<bullet::PatchFrictionSolver&>(*solver_);
}
bullet::PatchSolverPoolMt& Scene::pool() {
  if (!pool_) throw Error("Scene::pool: this scene steps a btDiscreteDynamicsWorld");
  return *pool_;
}
const bullet::PatchFrictionSolver& Scene::solver() const {
  return const_cast<Scene*>(this)->solver();
}

btCollisionShape* Scene::addShape(std::unique_ptr<btCollisionShape> shape) {
  shapes_.push_back(std::move(shape));
  return shapes_.back().get();
}

btRigidBody* Scene::addBody(std::unique_ptr<btCollisionShape> shape, double mass,
                            const btVector3& inertia, const btTransform& start, double friction,
                            int group, int mask) {
  return addBody(addShape(std::move(shape)), mass, inertia, start, friction, group, mask);
}

btRigidBody* Scene::addBody(btCollisionShape* sharedShape, double mass, const btVector3& inertia,
                            const btTransform& start, double friction, int group, int mask) {
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, sharedShape, inertia);
  info.m_startWorldTransform = start;
  auto body = std::make_unique<btRigidBody>(info);
  body->setFriction(btScalar(friction));
  body->setRollingFriction(0);
  body->setSpinningFriction(0);
  body->setRestitution(0);
  // the runs decide themselves when something has stopped
  if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
  if (group >= 0)
    world_->addRigidBody(body.get(), group, mask);
  else
    world_->addRigidBody(body.get());
  bodies_.push_back(std::move(body));
  bodyList_.push_back(bodies_.back().get());
  return bodies_.back().get();
}

namespace {
btTransform at(const btVector3& position) {
  btTransform tr;
  tr.setIdentity();
  tr.setOrigin(position);
  return tr;
}
}  // namespace

btRigidBody* Scene::addGroundPlane(double friction) {
  return addBody(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, btVector3(0, 0, 0),
                 at(btVector3(0, 0, 0)), friction);
}

btRigidBody* Scene::addCylinder(double R, double H, double mass, const btVector3& position,
                                double friction, double margin) {
  auto shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
  shape->setMargin(btScalar(margin));
  return addBody(std::move(shape), mass, cylinderInertia(mass, R, H), at(position), friction);
}

btRigidBody* Scene::addBox(const btVector3& half, double mass, const btVector3& position,
                           double friction, double margin) {
  auto shape = std::make_unique<btBoxShape>(half);
  shape->setMargin(btScalar(margin));
  return addBody(std::move(shape), mass,
                 boxInertia(mass, 2 * double(half.x()), 2 * double(half.y()), 2 * double(half.z())),
                 at(position), friction);
}

btRigidBody* Scene::addSphere(double radius, double mass, const btVector3& position,
                              double friction) {
  return addBody(std::make_unique<btSphereShape>(btScalar(radius)), mass,
                 sphereInertia(mass, radius), at(position), friction);
}

btRigidBody* Scene::addStaticBox(const btVector3& half, const btVector3& position,
                                 double friction) {
  return addBody(std::make_unique<btBoxShape>(half), 0, btVector3(0, 0, 0), at(position), friction);
}

btRigidBody* Scene::addCompound(std::vector<CompoundPart> parts, const btTransform& start,
                                double friction) {
  // centre of mass (double)
  double mass = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  auto toE = [](const btVector3& v) {
    return Eigen::Vector3d(double(v.x()), double(v.y()), double(v.z()));
  };
  for (const CompoundPart& p : parts) {
    if (!(p.mass >= 0.0)) throw Error("Scene::addCompound: a part's mass must be >= 0");
    mass += p.mass;
    c += p.mass * toE(p.pose.getOrigin());
  }
  if (mass > 0.0) c /= mass;
  // inertia about c in the compound's axes (parallel-axis theorem)
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (const CompoundPart& p : parts) {
    const Eigen::Matrix3d R = toIsometry(p.pose).linear();
    const Eigen::Vector3d d = toE(p.pose.getOrigin()) - c;
    J += R * toE(p.inertia).asDiagonal() * R.transpose() +
         p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  const Eigen::Matrix3d off = J - Eigen::Matrix3d(J.diagonal().asDiagonal());
  if (off.cwiseAbs().maxCoeff() > 1e-9 * J.trace())
    throw Error("Scene::addCompound: the compound's axes are not principal");
  // the children, shifted so that the body's origin is c
  auto compound = std::make_unique<btCompoundShape>();
  const btVector3 shift = bt(c.x(), c.y(), c.z());
  for (CompoundPart& p : parts) {
    btTransform pose = p.pose;
    pose.setOrigin(pose.getOrigin() - shift);
    compound->addChildShape(pose, addShape(std::move(p.shape)));
  }
  btTransform at = start;
  at.setOrigin(start * shift);
  return addBody(std::move(compound), mass, bt(J(0, 0), J(1, 1), J(2, 2)), at, friction);
}

void Scene::step(double dt) {
  world_->stepSimulation(btScalar(dt), 0);
}

double Scene::kineticEnergy() const {
  double e = 0;
  for (const auto& b : bodies_) {
    if (b->getInvMass() == 0) continue;
    const btVector3 v = b->getLinearVelocity();
    const btVector3 w = b->getAngularVelocity();
    const btVector3 Iw = b->getInvInertiaTensorWorld().inverse() * w;
    e += 0.5 * double(v.length2()) / double(b->getInvMass()) + 0.5 * double(w.dot(Iw));
  }
  return e;
}

}  // namespace patchspin::scenes
