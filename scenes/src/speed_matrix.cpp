// The speed matrix's scenes (speed_matrix.hpp).
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/speed_matrix.hpp>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>

#include <cmath>
#include <random>

namespace patchspin::scenes {

const char* toString(SpeedScene s) {
  return s == SpeedScene::Slipping ? "slipping" : s == SpeedScene::ToRest ? "to-rest" : "pile";
}
const char* toString(SpeedVariant v) {
  switch (v) {
    case SpeedVariant::Stock:
      return "stock";
    case SpeedVariant::StockControl:
      return "stock-control";
    case SpeedVariant::NoneOptedIn:
      return "none-opted-in";
    case SpeedVariant::Ellipsoidal:
      return "ellipsoidal";
    case SpeedVariant::Exact:
      return "exact";
  }
  return "?";
}
const char* toString(SpeedBroadphase b) {
  return b == SpeedBroadphase::Default ? "default" : "tight";
}

SpeedVariant speedVariantFromString(const std::string& name) {
  for (SpeedVariant v : {SpeedVariant::Stock, SpeedVariant::StockControl, SpeedVariant::NoneOptedIn,
                         SpeedVariant::Ellipsoidal, SpeedVariant::Exact})
    if (name == toString(v)) return v;
  throw Error(
      "speed variant must be stock, stock-control, none-opted-in, ellipsoidal or exact: got " +
      name);
}

SpeedCell speedCellFromString(const std::string& text) {
  const std::size_t a = text.find(':'), b = a == std::string::npos ? a : text.find(':', a + 1);
  if (b == std::string::npos)
    throw Error("speed cell must be scene:N:broadphase (e.g. pile:100:tight): got " + text);
  SpeedCell c;
  const std::string scene = text.substr(0, a), n = text.substr(a + 1, b - a - 1),
                    bp = text.substr(b + 1);
  if (scene == "slipping")
    c.scene = SpeedScene::Slipping;
  else if (scene == "to-rest")
    c.scene = SpeedScene::ToRest;
  else if (scene == "pile")
    c.scene = SpeedScene::Pile;
  else
    throw Error("speed scene must be slipping, to-rest or pile: got " + scene);
  std::size_t used = 0;
  try {
    c.n = std::stoi(n, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != n.size() || c.n < 1 || c.n > 100000)
    throw Error("speed cell's N must be an integer in [1, 100000]: got " + n);
  if (bp == "default")
    c.broadphase = SpeedBroadphase::Default;
  else if (bp == "tight")
    c.broadphase = SpeedBroadphase::Tight;
  else
    throw Error("speed broadphase must be default or tight: got " + bp);
  return c;
}

int episodeSteps(SpeedScene s) {
  return s == SpeedScene::Slipping ? 48 : s == SpeedScene::ToRest ? 120 : 240;
}

SpeedBroadphaseScope::SpeedBroadphaseScope(SpeedBroadphase b) : saved_(double(gDbvtMargin)) {
  gDbvtMargin = btScalar(b == SpeedBroadphase::Tight ? 0.005 : 0.05);
}
SpeedBroadphaseScope::~SpeedBroadphaseScope() {
  gDbvtMargin = btScalar(saved_);
}

namespace {

// N coins on a square grid 0.8 m apart, each launched in a seeded direction.
std::vector<btRigidBody*> addCoinField(Scene& scene, int n, double vMin, double vMax, double wMin,
                                       double wMax, Friction f) {
  constexpr double kSpacing = 0.8;
  scene.addGroundPlane(1.0);
  btCollisionShape* shape = scene.addShape(std::make_unique<btCylinderShapeZ>(
      bt(PileSpec::kCoinR, PileSpec::kCoinR, PileSpec::kCoinH / 2)));
  shape->setMargin(btScalar(PileSpec::kMargin));
  const btVector3 inertia =
      cylinderInertia(PileSpec::kCoinMass, PileSpec::kCoinR, PileSpec::kCoinH);
  std::mt19937 rng(35u + unsigned(n));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int side = int(std::ceil(std::sqrt(double(n))));
  std::vector<btRigidBody*> coins;
  for (int i = 0; i < n; ++i) {
    btTransform start;
    start.setIdentity();
    start.setOrigin(bt(kSpacing * (i % side), kSpacing * (i / side), PileSpec::kCoinH / 2));
    btRigidBody* coin = scene.addBody(shape, PileSpec::kCoinMass, inertia, start, PileSpec::kMu);
    const double angle = 2 * M_PI * u(rng), v = vMin + (vMax - vMin) * u(rng);
    const double w = (u(rng) < 0.5 ? -1 : 1) * (wMin + (wMax - wMin) * u(rng));
    coin->setLinearVelocity(bt(v * std::cos(angle), v * std::sin(angle), 0));
    coin->setAngularVelocity(bt(0, 0, w));
    if (scene.kind() != SolverKind::Stock) optIn(scene, coin, f);
    coins.push_back(coin);
  }
  return coins;
}

}  // namespace

SpeedWorld makeSpeedWorld(const SpeedCell& cell, SpeedVariant v) {
  const bool stock = v == SpeedVariant::Stock || v == SpeedVariant::StockControl;
  const Friction f = v == SpeedVariant::Ellipsoidal ? Friction::Ellipsoidal
                     : v == SpeedVariant::Exact     ? Friction::Exact
                                                    : Friction::Stock;  // (opts nothing in)
  SpeedWorld w;
  w.scene = std::make_unique<Scene>(9.81, 10, stock ? SolverKind::Stock : SolverKind::Patch);
  switch (cell.scene) {
    case SpeedScene::Slipping:
      w.bodies = addCoinField(*w.scene, cell.n, 1.2, 1.5, 10.0, 20.0, f);
      break;
    case SpeedScene::ToRest:
      w.bodies = addCoinField(*w.scene, cell.n, 0.2, 0.5, 2.0, 10.0, f);
      break;
    case SpeedScene::Pile:
      w.bodies = addPile(*w.scene, pileRain(cell.n, 35u), f);
      break;
  }
  return w;
}

SpeedOutcome speedOutcome(const SpeedWorld& w) {
  SpeedOutcome out;
  if (w.bodies.empty()) return out;
  int slipping = 0;
  double energy = 0.0;
  for (const btRigidBody* b : w.bodies) {
    const btVector3 v = b->getLinearVelocity(), om = b->getAngularVelocity();
    if (v.length() > 1e-3 || om.length() > 1e-2) ++slipping;
    const btVector3 Iw = b->getInvInertiaTensorWorld().inverse() * om;
    energy += 0.5 * (double(v.length2()) / double(b->getInvMass()) + double(om.dot(Iw)));
  }
  out.slippingFraction = double(slipping) / double(w.bodies.size());
  out.kineticEnergyPerBody = energy / double(w.bodies.size());
  return out;
}

}  // namespace patchspin::scenes
