// MultiBodyScene (multibody_scene.hpp).
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/multibody_scene.hpp>

namespace patchspin::scenes {
namespace {

btTransform at(const btVector3& position) {
  btTransform tr;
  tr.setIdentity();
  tr.setOrigin(position);
  return tr;
}

}  // namespace

MultiBodyScene::MultiBodyScene(double g, int iterations, bool patch)
    : config_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()) {
  if (patch) {
    auto solver = std::make_unique<bullet::PatchMultiBodySolver>();
    patch_ = solver.get();
    solver_ = std::move(solver);
  } else {
    solver_ = std::make_unique<btMultiBodyConstraintSolver>();
  }
  world_ = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                      solver_.get(), config_.get());
  world_->setGravity(bt(0, 0, -g));
  world_->getSolverInfo().m_numIterations = iterations;
}

MultiBodyScene::~MultiBodyScene() {
  for (Motor& m : motors_) world_->removeMultiBodyConstraint(m.motor.get());
  for (auto& c : colliders_) world_->removeCollisionObject(c.get());
  for (auto& b : multiBodies_) world_->removeMultiBody(b.get());
  for (auto& b : bodies_) world_->removeRigidBody(b.get());
}

bullet::PatchMultiBodySolver& MultiBodyScene::solver() {
  if (!patch_) throw Error("MultiBodyScene::solver: a stock scene has no patch solver");
  return *patch_;
}

btRigidBody* MultiBodyScene::addGroundPlane(double friction) {
  shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0));
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  btRigidBody* body = bodies_.back().get();
  body->setFriction(btScalar(friction));
  body->setRestitution(0);
  world_->addRigidBody(body);
  return body;
}

btRigidBody* MultiBodyScene::addRigid(std::unique_ptr<btCollisionShape> shape, double mass,
                                      const btVector3& inertia, const btVector3& position,
                                      double friction) {
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shape.get(), inertia);
  shapes_.push_back(std::move(shape));
  info.m_startWorldTransform = at(position);
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  btRigidBody* body = bodies_.back().get();
  body->setFriction(btScalar(friction));
  body->setRollingFriction(0);
  body->setSpinningFriction(0);
  body->setRestitution(0);
  body->setActivationState(DISABLE_DEACTIVATION);
  world_->addRigidBody(body);
  return body;
}

btRigidBody* MultiBodyScene::addBox(const btVector3& half, double mass, const btVector3& position,
                                    double friction, double margin) {
  auto shape = std::make_unique<btBoxShape>(half);
  shape->setMargin(btScalar(margin));
  return addRigid(
      std::move(shape), mass,
      boxInertia(mass, 2 * double(half.x()), 2 * double(half.y()), 2 * double(half.z())), position,
      friction);
}

btRigidBody* MultiBodyScene::addCylinder(double R, double H, double mass, const btVector3& position,
                                         double friction, double margin) {
  auto shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
  shape->setMargin(btScalar(margin));
  return addRigid(std::move(shape), mass, cylinderInertia(mass, R, H), position, friction);
}

btMultiBody* MultiBodyScene::addMultiBody(std::unique_ptr<btMultiBody> body) {
  body->setCanSleep(false);
  body->setLinearDamping(0);
  body->setAngularDamping(0);
  multiBodies_.push_back(std::move(body));
  return multiBodies_.back().get();
}

btMultiBodyLinkCollider* MultiBodyScene::addCollider(btMultiBody* body, int link,
                                                     std::unique_ptr<btCollisionShape> shape,
                                                     const btTransform& pose, double friction,
                                                     bool isStatic) {
  colliders_.push_back(std::make_unique<btMultiBodyLinkCollider>(body, link));
  btMultiBodyLinkCollider* c = colliders_.back().get();
  c->setCollisionShape(shape.get());
  shapes_.push_back(std::move(shape));
  c->setWorldTransform(pose);
  c->setFriction(btScalar(friction));
  c->setRollingFriction(0);
  c->setSpinningFriction(0);
  c->setRestitution(0);
  c->setActivationState(DISABLE_DEACTIVATION);
  const int group =
      isStatic ? int(btBroadphaseProxy::StaticFilter) : int(btBroadphaseProxy::DefaultFilter);
  const int mask = isStatic ? int(btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter)
                            : int(btBroadphaseProxy::AllFilter);
  world_->addCollisionObject(c, group, mask);
  if (link < 0)
    body->setBaseCollider(c);
  else
    body->getLink(link).m_collider = c;
  return c;
}

btMultiBody* MultiBodyScene::addCylinderBase(double R, double H, double mass,
                                             const btVector3& position, double friction,
                                             double margin) {
  btMultiBody* body = addMultiBody(
      std::make_unique<btMultiBody>(0, btScalar(mass), cylinderInertia(mass, R, H), false, false));
  body->setBasePos(position);
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  body->finalizeMultiDof();
  world_->addMultiBody(body);
  auto shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
  shape->setMargin(btScalar(margin));
  addCollider(body, -1, std::move(shape), at(position), friction, false);
  return body;
}

btMultiBody* MultiBodyScene::addBoxBase(const btVector3& half, double mass,
                                        const btVector3& position, double friction, double margin) {
  const btVector3 inertia =
      boxInertia(mass, 2 * double(half.x()), 2 * double(half.y()), 2 * double(half.z()));
  btMultiBody* body =
      addMultiBody(std::make_unique<btMultiBody>(0, btScalar(mass), inertia, false, false));
  body->setBasePos(position);
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  body->finalizeMultiDof();
  world_->addMultiBody(body);
  auto shape = std::make_unique<btBoxShape>(half);
  shape->setMargin(btScalar(margin));
  addCollider(body, -1, std::move(shape), at(position), friction, false);
  return body;
}

MultiBodyScene::Prismatic MultiBodyScene::addPrismaticBox(const btVector3& half, double mass,
                                                          const btVector3& position,
                                                          double friction, double speed,
                                                          double maxForce, double margin) {
  // the base: fixed, at the link's origin, without a collider
  btMultiBody* body =
      addMultiBody(std::make_unique<btMultiBody>(1, btScalar(1), bt(1, 1, 1), true, false));
  body->setBasePos(position);
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  const btVector3 inertia =
      boxInertia(mass, 2 * double(half.x()), 2 * double(half.y()), 2 * double(half.z()));
  body->setupPrismatic(0, btScalar(mass), inertia, -1, btQuaternion::getIdentity(), bt(1, 0, 0),
                       bt(0, 0, 0), bt(0, 0, 0), true);
  body->finalizeMultiDof();
  body->setJointVel(0, btScalar(speed));
  world_->addMultiBody(body);
  auto shape = std::make_unique<btBoxShape>(half);
  shape->setMargin(btScalar(margin));
  addCollider(body, 0, std::move(shape), at(position), friction, false);
  auto motor = std::make_unique<btMultiBodyJointMotor>(body, 0, 0, btScalar(speed), btScalar(0));
  world_->addMultiBodyConstraint(motor.get());
  motors_.push_back({std::move(motor), maxForce});
  return {body, motors_.back().motor.get()};
}

MultiBodyScene::Gripper MultiBodyScene::addGripper(const btVector3& pad, double fingerMass,
                                                   double gap, double squeeze, double friction,
                                                   double margin, const btVector3& origin) {
  constexpr double kClosing = 0.05;  // [m/s]
  btMultiBody* body =
      addMultiBody(std::make_unique<btMultiBody>(2, btScalar(1), bt(1, 1, 1), true, false));
  body->setBasePos(origin);
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  const btVector3 inertia =
      boxInertia(fingerMass, 2 * double(pad.x()), 2 * double(pad.y()), 2 * double(pad.z()));
  const double offset = gap + double(pad.y());
  for (int i = 0; i < 2; ++i)
    body->setupPrismatic(i, btScalar(fingerMass), inertia, -1, btQuaternion::getIdentity(),
                         bt(0, 1, 0), bt(0, i == 0 ? -offset : offset, 0), bt(0, 0, 0), true);
  body->finalizeMultiDof();
  world_->addMultiBody(body);
  Gripper gripper;
  gripper.body = body;
  for (int i = 0; i < 2; ++i) {
    auto shape = std::make_unique<btBoxShape>(pad);
    shape->setMargin(btScalar(margin));
    addCollider(body, i, std::move(shape), at(origin + bt(0, i == 0 ? -offset : offset, 0)),
                friction, false);
    const double closing = i == 0 ? kClosing : -kClosing;
    auto motor =
        std::make_unique<btMultiBodyJointMotor>(body, i, 0, btScalar(closing), btScalar(0));
    world_->addMultiBodyConstraint(motor.get());
    motors_.push_back({std::move(motor), squeeze});
    gripper.motors[i] = motors_.back().motor.get();
  }
  return gripper;
}

btMultiBody* MultiBodyScene::addLeg(const btVector3& foot, double footMass, const btVector3& shin,
                                    double shinMass, const btVector3& footCentre, double friction,
                                    double margin) {
  const double rise = double(foot.z() + shin.z());
  const btVector3 shinInertia =
      boxInertia(shinMass, 2 * double(shin.x()), 2 * double(shin.y()), 2 * double(shin.z()));
  btMultiBody* body =
      addMultiBody(std::make_unique<btMultiBody>(1, btScalar(shinMass), shinInertia, false, false));
  body->setBasePos(footCentre + bt(0, 0, rise));
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  const btVector3 footInertia =
      boxInertia(footMass, 2 * double(foot.x()), 2 * double(foot.y()), 2 * double(foot.z()));
  body->setupFixed(0, btScalar(footMass), footInertia, -1, btQuaternion::getIdentity(),
                   bt(0, 0, -rise), bt(0, 0, 0));
  body->finalizeMultiDof();
  world_->addMultiBody(body);
  auto shape = std::make_unique<btBoxShape>(foot);
  shape->setMargin(btScalar(margin));
  addCollider(body, 0, std::move(shape), at(footCentre), friction, false);
  return body;
}

btMultiBody* MultiBodyScene::addBlockOverTable(const btVector3& table, double tableMass,
                                               const btVector3& block, double blockMass,
                                               double sliderMass, double speed, double maxForce,
                                               double friction, double margin) {
  btMultiBody* body =
      addMultiBody(std::make_unique<btMultiBody>(4, btScalar(1), bt(1, 1, 1), true, false));
  body->setBasePos(bt(0, 0, 0));
  body->setWorldToBaseRot(btQuaternion::getIdentity());
  const btQuaternion none = btQuaternion::getIdentity();
  const btVector3 tableCentre = bt(0, 0, -double(table.z()));
  const btVector3 blockCentre = bt(0, 0, double(block.z()));
  const btVector3 small(btScalar(1e-3), btScalar(1e-3), btScalar(1e-3));
  // 0: a carriage along y (no collider), 1: the table on it along x
  body->setupPrismatic(0, btScalar(sliderMass), small, -1, none, bt(0, 1, 0), tableCentre,
                       bt(0, 0, 0), true);
  body->setupPrismatic(
      1, btScalar(tableMass),
      boxInertia(tableMass, 2 * double(table.x()), 2 * double(table.y()), 2 * double(table.z())), 0,
      none, bt(1, 0, 0), bt(0, 0, 0), bt(0, 0, 0), true);
  // 2: a slider along z (no collider), 3: the block on it, spherical
  body->setupPrismatic(2, btScalar(sliderMass), small, -1, none, bt(0, 0, 1), blockCentre,
                       bt(0, 0, 0), true);
  body->setupSpherical(
      3, btScalar(blockMass),
      boxInertia(blockMass, 2 * double(block.x()), 2 * double(block.y()), 2 * double(block.z())), 2,
      none, bt(0, 0, 0), bt(0, 0, 0), true);
  body->setHasSelfCollision(true);
  body->finalizeMultiDof();
  body->setJointVel(1, btScalar(speed));
  world_->addMultiBody(body);
  for (int link : {1, 3}) {
    auto shape = std::make_unique<btBoxShape>(link == 1 ? table : block);
    shape->setMargin(btScalar(margin));
    addCollider(body, link, std::move(shape), at(link == 1 ? tableCentre : blockCentre), friction,
                false);
  }
  auto motor = std::make_unique<btMultiBodyJointMotor>(body, 1, 0, btScalar(speed), btScalar(0));
  world_->addMultiBodyConstraint(motor.get());
  motors_.push_back({std::move(motor), maxForce});
  return body;
}

btMultiBodyLinkCollider* MultiBodyScene::collider(btMultiBody* body, int link) {
  return link < 0 ? body->getBaseCollider() : body->getLink(link).m_collider;
}

void MultiBodyScene::step(double dt) {
  for (Motor& m : motors_) m.motor->setMaxAppliedImpulse(btScalar(m.maxForce * dt));
  world_->stepSimulation(btScalar(dt), 0);
}

}  // namespace patchspin::scenes
