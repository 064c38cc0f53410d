// Scene: an owning Bullet world with a PatchFrictionSolver (see scene.hpp).
#include <patchspin/bullet/scene.hpp>

namespace patchspin::bullet {
namespace {
btVector3 bt(double x, double y, double z) { return btVector3(btScalar(x), btScalar(y), btScalar(z)); }
}  // namespace

Scene::Scene(double g, int iterations)
    : config_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<PatchFrictionSolver>()),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                        config_.get())) {
  world_->setGravity(bt(0, 0, -g));
  world_->getSolverInfo().m_numIterations = iterations;
}

Scene::~Scene() {
  for (auto& b : bodies_) world_->removeRigidBody(b.get());
}

btRigidBody* Scene::addBody(std::unique_ptr<btCollisionShape> shape, double mass, const btVector3& inertia,
                            const btVector3& position, double friction) {
  btTransform tr;
  tr.setIdentity();
  tr.setOrigin(position);
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shape.get(), inertia);
  info.m_startWorldTransform = tr;
  auto body = std::make_unique<btRigidBody>(info);
  body->setFriction(btScalar(friction));
  body->setRollingFriction(0);
  body->setSpinningFriction(0);
  body->setRestitution(0);
  // the runs decide themselves when something has stopped
  if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
  world_->addRigidBody(body.get());
  shapes_.push_back(std::move(shape));
  bodies_.push_back(std::move(body));
  return bodies_.back().get();
}

btRigidBody* Scene::addGroundPlane(double friction) {
  return addBody(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, btVector3(0, 0, 0),
                 btVector3(0, 0, 0), friction);
}

btRigidBody* Scene::addCylinder(double R, double H, double mass, const btVector3& position, double friction,
                                double margin) {
  auto shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
  shape->setMargin(btScalar(margin));
  const double jx = mass * (3 * R * R + H * H) / 12;
  return addBody(std::move(shape), mass, bt(jx, jx, mass * R * R / 2), position, friction);
}

btRigidBody* Scene::addBox(const btVector3& half, double mass, const btVector3& position, double friction,
                           double margin) {
  auto shape = std::make_unique<btBoxShape>(half);
  shape->setMargin(btScalar(margin));
  const double x = 2 * double(half.x()), y = 2 * double(half.y()), z = 2 * double(half.z());
  return addBody(std::move(shape), mass, bt(mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12,
                                            mass * (x * x + y * y) / 12),
                 position, friction);
}

btRigidBody* Scene::addSphere(double radius, double mass, const btVector3& position, double friction) {
  const double j = 0.4 * mass * radius * radius;
  return addBody(std::make_unique<btSphereShape>(btScalar(radius)), mass, bt(j, j, j), position, friction);
}

btRigidBody* Scene::addStaticBox(const btVector3& half, const btVector3& position, double friction) {
  return addBody(std::make_unique<btBoxShape>(half), 0, btVector3(0, 0, 0), position, friction);
}

void Scene::step(double dt) { world_->stepSimulation(btScalar(dt), 0); }

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

}  // namespace patchspin::bullet
