// The catalogue of named scenes (see catalogue.hpp).
#include <algorithm>
#include <cmath>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/inertia.hpp>

namespace patchspin::scenes {

// ---- friction laws ----------------------------------------------------------------
const char* toString(Friction f) {
  return f == Friction::Stock ? "stock" : f == Friction::Ellipsoidal ? "ellipsoidal" : "exact";
}

Friction frictionFromString(const std::string& name) {
  for (Friction f : {Friction::Stock, Friction::Ellipsoidal, Friction::Exact})
    if (name == toString(f)) return f;
  throw Error("friction law must be stock, ellipsoidal or exact: got " + name);
}

void optIn(Scene& scene, btRigidBody* body, Friction f) {
  if (f == Friction::Stock) return;
  scene.solver().enablePatchFriction(body,
                                     {f == Friction::Exact ? Model::Exact : Model::Ellipsoidal});
}

// ---- coin trio ----------------------------------------------------------------------
std::unique_ptr<Scene> makeCoin(const CoinSpec& a, Friction f, btRigidBody** coin) {
  // collision margin: 1 mm capped at a tenth of the smaller half size, as
  // simulate() does (the patch uses the real faces anyway)
  constexpr double kMargin = 1e-3;
  auto scene = std::make_unique<Scene>(a.g);
  addGround(*scene, a.ground, 1.0);  // combined friction = the coin's mu
  const double halfHeight = 0.5 * a.height;
  const double margin = std::min(kMargin, 0.1 * std::min(a.radius, halfHeight));
  btRigidBody* body =
      scene->addCylinder(a.radius, a.height, a.mass, bt(0, 0, halfHeight), a.mu, margin);
  body->setLinearVelocity(bt(a.v0, 0, 0));
  body->setAngularVelocity(bt(0, 0, a.omega0));
  if (f != Friction::Stock) {
    bullet::PatchOptions options;
    options.model = f == Friction::Exact ? Model::Exact : Model::Ellipsoidal;
    options.mu = a.mu;
    scene->solver().enablePatchFriction(body, options);
  }
  if (coin) *coin = body;
  return scene;
}

// ---- blocks row ---------------------------------------------------------------------
std::vector<RowBody> blocksRow(const BlocksRowSpec& a) {
  const double pi = std::acos(-1.0);
  std::vector<RowBody> defs;
  RowBody rect;
  rect.key = "rect";
  rect.label = "rectangle";
  rect.size = Vec3(a.rectLX, a.rectLY, a.rectLZ);
  rect.mass = a.rectMass;
  rect.position = Vec3(0, 0, 0.5 * a.rectLZ);
  const double angle = a.rectV0Angle * pi / 180.0;
  rect.v0 = a.rectV0 * Vec2(std::cos(angle), std::sin(angle));
  rect.omega0 = a.rectOmega0;
  defs.push_back(rect);

  // left of the rectangle: the spinning square, then the stack
  const double rectReach = 0.5 * std::hypot(a.rectLX, a.rectLY);
  const double squareReach = a.squareSide / std::sqrt(2.0);
  RowBody square;
  square.key = "square";
  square.label = "square";
  square.size = Vec3(a.squareSide, a.squareSide, a.squareLZ);
  square.mass = a.squareMass;
  square.position = Vec3(-(rectReach + squareReach + 0.06), 0, 0.5 * a.squareLZ);
  square.omega0 = a.squareOmega0;
  defs.push_back(square);

  const double sides[3] = {a.stackBottom, a.stackMiddle, a.stackTop};
  const double stackX = square.position.x() - squareReach - 0.06 - 0.5 * a.stackBottom;
  for (int i = 0; i < 3; ++i) {
    RowBody b;
    b.key = "stack" + std::to_string(i);
    b.label = "stack " + std::to_string(i);
    b.size = Vec3(sides[i], sides[i], a.stackLZ);
    b.mass = a.stackMass;
    b.position = Vec3(stackX, 0, (i + 0.5) * a.stackLZ);
    b.moving = false;
    defs.push_back(b);
  }

  // right of the rectangle (beyond its travel): the coin, then the sphere
  const double rectTravel =
      a.rectV0 * a.rectV0 / (2 * a.mu * a.g) * 2.0;  // twice the pure-sliding travel
  const double coinTravel = a.coinV0 * a.coinV0 / (2 * a.mu * a.g) * 2.0;
  RowBody coin;
  coin.key = "coin";
  coin.label = "coin";
  coin.kind = BodyKind::Cylinder;
  coin.size = Vec3(a.coinRadius, a.coinRadius, a.coinHeight);
  coin.mass = a.coinMass;
  coin.position = Vec3(rectReach + rectTravel + a.coinRadius + 0.06, 0, 0.5 * a.coinHeight);
  coin.v0 = Vec2(a.coinV0, 0);
  coin.omega0 = a.coinOmega0;
  defs.push_back(coin);

  RowBody sphere;
  sphere.key = "sphere";
  sphere.label = "sphere";
  sphere.kind = BodyKind::Sphere;
  sphere.size = Vec3(a.sphereRadius, a.sphereRadius, 2 * a.sphereRadius);
  sphere.mass = a.sphereMass;
  sphere.position = Vec3(coin.position.x() + coinTravel + a.coinRadius + a.sphereRadius + 0.06, 0,
                         a.sphereRadius);
  sphere.v0 = Vec2(a.sphereV0, 0);
  sphere.patch = false;
  defs.push_back(sphere);
  return defs;
}

btRigidBody* addRowBody(Scene& scene, const RowBody& d, double mu, Friction f) {
  // collision margin: 1 mm capped at a tenth of the smallest half size
  constexpr double kMargin = 1e-3;
  const double m = d.mass;
  std::unique_ptr<btCollisionShape> shape;
  btVector3 inertia;
  double minHalf = 0.0;
  switch (d.kind) {
    case BodyKind::Box: {
      const double lx = d.size.x(), ly = d.size.y(), lz = d.size.z();
      shape = std::make_unique<btBoxShape>(bt(lx / 2, ly / 2, lz / 2));
      inertia = boxInertia(m, lx, ly, lz);
      minHalf = std::min({lx / 2, ly / 2, lz / 2});
      break;
    }
    case BodyKind::Cylinder: {
      const double R = d.size.x(), H = d.size.z();
      shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
      inertia = cylinderInertia(m, R, H);
      minHalf = std::min(R, H / 2);
      break;
    }
    case BodyKind::Sphere: {
      const double R = d.size.x();
      shape = std::make_unique<btSphereShape>(btScalar(R));
      inertia = sphereInertia(m, R);
      break;
    }
  }
  if (d.kind != BodyKind::Sphere) shape->setMargin(btScalar(std::min(kMargin, 0.1 * minHalf)));
  btTransform start;
  start.setIdentity();
  start.setOrigin(bt(d.position.x(), d.position.y(), d.position.z()));
  btRigidBody* body = scene.addBody(std::move(shape), m, inertia, start, mu);
  body->setLinearVelocity(bt(d.v0.x(), d.v0.y(), 0));
  body->setAngularVelocity(bt(0, 0, d.omega0));
  if (f != Friction::Stock && d.patch) {
    bullet::PatchOptions options;
    options.model = f == Friction::Exact ? Model::Exact : Model::Ellipsoidal;
    options.mu = mu;
    scene.solver().enablePatchFriction(body, options);
  }
  return body;
}

std::unique_ptr<Scene> makeBlocksRow(const BlocksRowSpec& spec, Friction f,
                                     std::vector<btRigidBody*>* bodies, SolverKind kind) {
  auto scene = std::make_unique<Scene>(spec.g, 10, kind);
  scene->addGroundPlane(1.0);
  for (const RowBody& d : blocksRow(spec)) {
    btRigidBody* b = addRowBody(*scene, d, spec.mu, f);
    if (bodies) bodies->push_back(b);
  }
  return scene;
}

// ---- terrain ------------------------------------------------------------------------
GroundSpec TerrainSpec::defaultGround() {
  GroundSpec g;
  g.kind = Ground::TriangleMesh;
  g.halfSize = 0.3;
  g.spacing = 0.01;
  g.slope = 8.0 * M_PI / 180.0;
  g.crease = true;
  g.creaseX = 0.0;
  return g;
}

std::vector<TerrainBody> terrainBodies(const TerrainSpec& a) {
  const GroundSpec& gr = a.ground;
  if (gr.kind == Ground::Plane || !gr.crease || gr.slopeInTransform)
    throw Error("terrain: the ground must be a mesh or heightfield with a crease");
  if (!(gr.slope > 0.0 && std::tan(gr.slope) < a.mu))
    throw Error("terrain: the slope must rise at less than the friction angle atan(mu)");
  if (!(a.mu > 0.0 && a.g > 0.0)) throw Error("terrain: mu and g must be positive");
  const double c = gr.creaseX, h = gr.halfSize, tanA = std::tan(gr.slope);
  const Vec3 up = Vec3::UnitZ(), slopeNormal(-std::sin(gr.slope), 0.0, std::cos(gr.slope));
  // twice the pure-sliding travel v0^2 / (2 mu g): spin lengthens it (1.9
  // and 2.0 times v0^2 / (2 mu g), 8.3 and 8.4 cm, for the exact law's level
  // coin and block at the defaults, travelling along the path)
  auto travel = [&](double v0) { return 2.0 * v0 * v0 / (2.0 * a.mu * a.g); };
  const double coinReach = a.coinRadius, blockReach = 0.5 * std::hypot(a.blockLX, a.blockLY);
  constexpr double kGap = 0.02;  // between a body's reach and the crease [m]
  std::vector<TerrainBody> bodies;
  auto add = [&](const std::string& key, const std::string& region, BodyKind kind, double x,
                 double y) {
    TerrainBody b;
    b.key = key;
    b.label = key;
    std::replace(b.label.begin(), b.label.end(), '_', ' ');
    b.region = region;
    b.kind = kind;
    const bool coin = kind == BodyKind::Cylinder;
    b.size = coin ? Vec3(a.coinRadius, a.coinRadius, a.coinHeight)
                  : Vec3(a.blockLX, a.blockLY, a.blockLZ);
    b.mass = coin ? a.coinMass : a.blockMass;
    const bool sloped = region == "slope";
    b.normal = sloped ? slopeNormal : up;
    b.tilt = sloped ? gr.slope : 0.0;
    const Vec3 surface(x, y, x <= c ? 0.0 : (x - c) * tanA);
    b.position = surface + 0.5 * b.size.z() * b.normal;
    const double v0 = coin ? a.coinV0 : a.blockV0;
    b.v0 = sloped ? Vec3(0.0, v0, 0.0) : Vec3(v0, 0.0, 0.0);  // across the slope: level
    b.omega0 = coin ? a.coinOmega0 : a.blockOmega0;
    const double reach = coin ? coinReach : blockReach;
    if (std::abs(x) + reach > h || std::abs(y) + reach > h)
      throw Error("terrain: the ground (half size " + std::to_string(h) + " m) is too small for " +
                  key);
    bodies.push_back(b);
  };
  const double coinTravel = travel(a.coinV0), blockTravel = travel(a.blockV0);
  // level: sliding along +x, stopping kGap short of the crease
  add("level_coin", "level", BodyKind::Cylinder, c - kGap - coinReach - coinTravel, 0.05);
  add("level_block", "level", BodyKind::Box, c - kGap - blockReach - blockTravel, -0.15);
  // slope: sliding across it (+y), curving downhill, half the slope's
  // width from the crease
  add("slope_coin", "slope", BodyKind::Cylinder, c + 0.15, 0.03);
  add("slope_block", "slope", BodyKind::Box, c + 0.15, -0.21);
  // over the crease: the rim 3 cm short of it, sliding towards it
  add("crease_coin", "crease", BodyKind::Cylinder, c - coinReach - 0.03, 0.19);
  return bodies;
}

btRigidBody* addTerrainBody(Scene& scene, const TerrainBody& d, double mu, Friction f) {
  // collision margin: 1 mm capped at a tenth of the smallest half size
  constexpr double kMargin = 1e-3;
  std::unique_ptr<btCollisionShape> shape;
  btVector3 inertia;
  double minHalf = 0.0;
  if (d.kind == BodyKind::Cylinder) {
    const double R = d.size.x(), H = d.size.z();
    shape = std::make_unique<btCylinderShapeZ>(bt(R, R, H / 2));
    inertia = cylinderInertia(d.mass, R, H);
    minHalf = std::min(R, H / 2);
  } else if (d.kind == BodyKind::Box) {
    const double lx = d.size.x(), ly = d.size.y(), lz = d.size.z();
    shape = std::make_unique<btBoxShape>(bt(lx / 2, ly / 2, lz / 2));
    inertia = boxInertia(d.mass, lx, ly, lz);
    minHalf = std::min({lx / 2, ly / 2, lz / 2});
  } else {
    throw Error("terrain: bodies are boxes or cylinders");
  }
  shape->setMargin(btScalar(std::min(kMargin, 0.1 * minHalf)));
  btTransform start;
  start.setIdentity();
  start.setOrigin(bt(d.position.x(), d.position.y(), d.position.z()));
  start.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(-d.tilt)));
  btRigidBody* body = scene.addBody(std::move(shape), d.mass, inertia, start, mu);
  body->setLinearVelocity(bt(d.v0.x(), d.v0.y(), d.v0.z()));
  const Vec3 w = d.omega0 * d.normal;
  body->setAngularVelocity(bt(w.x(), w.y(), w.z()));
  if (f != Friction::Stock) {
    bullet::PatchOptions options;
    options.model = f == Friction::Exact ? Model::Exact : Model::Ellipsoidal;
    options.mu = mu;
    scene.solver().enablePatchFriction(body, options);
  }
  return body;
}

std::unique_ptr<Scene> makeTerrain(const TerrainSpec& spec, Friction f,
                                   std::vector<btRigidBody*>* bodies, btRigidBody** ground) {
  const std::vector<TerrainBody> defs = terrainBodies(spec);
  auto scene = std::make_unique<Scene>(spec.g);
  btRigidBody* g = addGround(*scene, spec.ground, 1.0);  // combined friction = the body's mu
  if (ground) *ground = g;
  for (const TerrainBody& d : defs) {
    btRigidBody* b = addTerrainBody(*scene, d, spec.mu, f);
    if (bodies) bodies->push_back(b);
  }
  return scene;
}

// ---- blocks -------------------------------------------------------------------------
std::vector<btVector3> stackPositions(int n, const BlockSpec& s) {
  std::vector<btVector3> pos;
  for (int i = 0; i < n; ++i) pos.push_back(bt(0, 0, s.halfH + i * (2 * s.halfH - s.overlap)));
  return pos;
}

std::vector<btVector3> pyramidPositions(int rows, double gap, const BlockSpec& s) {
  std::vector<btVector3> pos;
  for (int row = 0; row < rows; ++row) {
    const int n = rows - row;
    for (int j = 0; j < n; ++j)
      pos.push_back(
          bt((j - 0.5 * (n - 1)) * (s.a + gap), 0, s.halfH + row * (2 * s.halfH - s.overlap)));
  }
  return pos;
}

std::vector<btRigidBody*> addBlocks(Scene& scene, const std::vector<btVector3>& positions,
                                    Friction f, const BlockSpec& s) {
  scene.addGroundPlane(1.0);
  std::vector<btRigidBody*> blocks;
  for (const btVector3& p : positions) {
    btRigidBody* b = scene.addBox(bt(s.a / 2, s.a / 2, s.halfH), s.mass, p, s.mu);
    optIn(scene, b, f);
    blocks.push_back(b);
  }
  return blocks;
}

HeavyOnLight makeHeavyOnLight(double ratio, Friction f) {
  HeavyOnLight h;
  h.scene = std::make_unique<Scene>(9.81, 10,
                                    f == Friction::Stock ? SolverKind::Stock : SolverKind::Patch);
  h.scene->addGroundPlane(1.0);
  h.light = h.scene->addBox(bt(0.02, 0.05, 0.1), 1.0, bt(0, 0, 0.1), 1.0);
  h.heavy = h.scene->addBox(bt(0.05, 0.05, 0.05), ratio, bt(0, 0, 0.25), 0.5);
  optIn(*h.scene, h.light, f);
  optIn(*h.scene, h.heavy, f);
  return h;
}

std::vector<btRigidBody*> addBasicExample(Scene& scene, Friction f) {
  scene.world().setGravity(bt(0, 0, -10));
  scene.addStaticBox(bt(50, 50, 50), bt(0, 0, -50), 0.5);
  btCollisionShape* shape = scene.addShape(std::make_unique<btBoxShape>(bt(0.1, 0.1, 0.1)));
  btVector3 inertia;
  shape->calculateLocalInertia(1, inertia);
  std::vector<btRigidBody*> boxes;
  for (int k = 0; k < 5; ++k)
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        btTransform start;
        start.setIdentity();
        start.setOrigin(bt(0.2 * i, 0.2 * j, 2 + 0.2 * k));
        boxes.push_back(scene.addBody(shape, 1.0, inertia, start, 0.5));
        optIn(scene, boxes.back(), f);
      }
  return boxes;
}

btRigidBody* addIncline(Scene& scene, double alpha, double g, Friction f, const BlockSpec& s) {
  scene.world().setGravity(bt(g * std::sin(alpha), 0, -g * std::cos(alpha)));
  scene.addGroundPlane(1.0);
  btRigidBody* b = scene.addBox(bt(s.a / 2, s.a / 2, s.halfH), s.mass, bt(0, 0, s.halfH), s.mu);
  optIn(scene, b, f);
  return b;
}

// ---- pour ---------------------------------------------------------------------------
std::unique_ptr<btConvexHullShape> pourCoinShape(double unit) {
  // the hull's points lie one margin inside R and H/2: Bullet clips hull
  // against hull on the points alone, against the floor one margin outside
  auto shape = std::make_unique<btConvexHullShape>();
  shape->setMargin(btScalar(unit * PourSpec::kHullMargin));
  const double r = unit * (PourSpec::kR - PourSpec::kHullMargin),
               h = unit * (PourSpec::kH / 2 - PourSpec::kHullMargin);
  for (int k = 0; k < PourSpec::kHullSides; ++k) {
    const double a = 2 * M_PI * k / PourSpec::kHullSides;
    shape->addPoint(bt(r * std::cos(a), r * std::sin(a), -h), false);
    shape->addPoint(bt(r * std::cos(a), r * std::sin(a), h), k + 1 == PourSpec::kHullSides);
  }
  shape->initializePolyhedralFeatures();
  return shape;
}

Pour::Pour(Scene& scene, const PourSpec& spec) : scene_(scene), spec_(spec), rng_(spec.seed) {
  const double unit = spec_.unit;
  auto at = [unit](double x, double y, double z) { return bt(unit * x, unit * y, unit * z); };
  scene_.addGroundPlane(1.0);
  constexpr double kBoxHalf = PourSpec::kBoxHalf, kWallH = PourSpec::kWallH;
  for (int side = 0; side < 4; ++side) {
    const double sx = side < 2 ? (side == 0 ? -1 : 1) : 0,
                 sy = side >= 2 ? (side == 2 ? -1 : 1) : 0;
    const btVector3 half =
        sx != 0 ? at(0.05, kBoxHalf + 0.1, kWallH / 2) : at(kBoxHalf + 0.1, 0.05, kWallH / 2);
    scene_.addStaticBox(half, at(sx * (kBoxHalf + 0.05), sy * (kBoxHalf + 0.05), kWallH / 2), 1.0);
  }
}

void Pour::pourLayer(double z0, Friction f) {
  const double unit = spec_.unit;
  auto at = [unit](double x, double y, double z) { return bt(unit * x, unit * y, unit * z); };
  const double R = unit * PourSpec::kR, H = unit * PourSpec::kH;
  std::mt19937& rng = rng_;
  std::uniform_real_distribution<double>& u = u_;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const btVector3 p =
          at((i - 4.5) * 0.055 + 0.005 * u(rng), (j - 4.5) * 0.055 + 0.005 * u(rng), z0);
      btRigidBody* c = nullptr;
      btTransform t;
      if (spec_.hull) {
        t.setIdentity();
        t.setOrigin(p);
        // the solid cylinder's inertia, as with the cylinder coins
        c = scene_.addBody(pourCoinShape(unit), PourSpec::kMass,
                           cylinderInertia(PourSpec::kMass, R, H), t, PourSpec::kMu);
      } else {
        c = scene_.addCylinder(R, H, PourSpec::kMass, p, PourSpec::kMu, unit * PourSpec::kMargin);
        t = c->getWorldTransform();
      }
      t.setRotation(
          btQuaternion(bt(u(rng), u(rng), 0).normalized(), btScalar(0.3 * std::abs(u(rng)))));
      c->setWorldTransform(t);
      c->setLinearVelocity(at(0.3 * u(rng), 0.3 * u(rng), -0.5));
      c->setAngularVelocity(bt(0, 0, 10 * u(rng)));
      optIn(scene_, c, f);
      coins_.push_back(c);
    }
}

std::unique_ptr<Scene> makePour(const PourSpec& spec, Friction f, std::vector<btRigidBody*>* coins,
                                double g, SolverKind kind) {
  // the pour tests' first layer: kDropHeight above the empty floor
  constexpr double kDropHeight = 0.03;
  auto scene = std::make_unique<Scene>(g * spec.unit, 10, kind);
  if (spec.hull) scene->world().getDispatchInfo().m_enableSatConvex = true;
  Pour pour(*scene, spec);
  pour.pourLayer(kDropHeight, f);
  if (coins) *coins = pour.coins();
  return scene;
}

// ---- pile ---------------------------------------------------------------------------
double PileSpec::side(int n) {
  return kCell * std::ceil(std::sqrt(n / 2.0));
}

std::vector<BodyState> pileRain(int n, unsigned seed) {
  constexpr double kCell = PileSpec::kCell;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int perSide = int(std::lround(PileSpec::side(n) / kCell));
  std::vector<BodyState> out;
  for (int i = 0; i < n; ++i) {
    const int layer = i / (perSide * perSide), cell = i % (perSide * perSide);
    const double x = -PileSpec::side(n) / 2 + kCell * (cell % perSide + 0.5) + 0.01 * u(rng);
    const double y = -PileSpec::side(n) / 2 + kCell * (cell / perSide + 0.5) + 0.01 * u(rng);
    const double z = 0.05 + 0.1 * layer;
    const btVector3 axis = btVector3(btScalar(u(rng)), btScalar(u(rng)), 0).normalized();
    btQuaternion q(axis, btScalar(0.3 * std::abs(u(rng))));
    q = btQuaternion(btVector3(0, 0, 1), btScalar(3.14159 * u(rng))) * q;
    out.push_back({btTransform(q, btVector3(btScalar(x), btScalar(y), btScalar(z))),
                   btVector3(btScalar(0.5 * u(rng)), btScalar(0.5 * u(rng)), 0),
                   btVector3(0, 0, btScalar(5 * u(rng)))});
  }
  return out;
}

std::vector<btRigidBody*> addPile(Scene& scene, const std::vector<BodyState>& states, Friction f) {
  // collision groups: the floor is a plane for the coins and a box for the boxes
  constexpr int kCoinGroup = 1 << 6, kBoxGroup = 1 << 7, kPlaneGroup = 1 << 8, kFloorGroup = 1 << 9,
                kWallGroup = 1 << 10;
  constexpr double kMu = PileSpec::kMu;
  const int n = int(states.size());
  btCollisionShape* coinShape = scene.addShape(std::make_unique<btCylinderShapeZ>(
      bt(PileSpec::kCoinR, PileSpec::kCoinR, PileSpec::kCoinH / 2)));
  btCollisionShape* boxShape = scene.addShape(std::make_unique<btBoxShape>(
      bt(PileSpec::kBoxHalfX, PileSpec::kBoxHalfY, PileSpec::kBoxHalfZ)));
  coinShape->setMargin(btScalar(PileSpec::kMargin));
  boxShape->setMargin(btScalar(PileSpec::kMargin));
  // floor and walls (0.3 m high, 5 cm thick) around the square [-L/2, L/2]^2
  const double L = PileSpec::side(n), t = 0.05, h = 0.3;
  btCollisionShape* plane =
      scene.addShape(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0));
  btCollisionShape* floor =
      scene.addShape(std::make_unique<btBoxShape>(bt(L / 2 + t, L / 2 + t, t)));
  btCollisionShape* wallX =
      scene.addShape(std::make_unique<btBoxShape>(bt(L / 2 + t, t / 2, h / 2)));
  btCollisionShape* wallY =
      scene.addShape(std::make_unique<btBoxShape>(bt(t / 2, L / 2 + t, h / 2)));
  auto addStatic = [&](btCollisionShape* shape, const btVector3& origin, int group, int mask) {
    btTransform tr;
    tr.setIdentity();
    tr.setOrigin(origin);
    scene.addBody(shape, 0, btVector3(0, 0, 0), tr, kMu, group, mask);
  };
  addStatic(plane, bt(0, 0, 0), kPlaneGroup, kCoinGroup);
  addStatic(floor, bt(0, 0, -t), kFloorGroup, kBoxGroup);
  const int all = kCoinGroup | kBoxGroup;
  addStatic(wallX, bt(0, L / 2 + t / 2, h / 2), kWallGroup, all);
  addStatic(wallX, bt(0, -L / 2 - t / 2, h / 2), kWallGroup, all);
  addStatic(wallY, bt(L / 2 + t / 2, 0, h / 2), kWallGroup, all);
  addStatic(wallY, bt(-L / 2 - t / 2, 0, h / 2), kWallGroup, all);
  const btVector3 coinInertia =
      cylinderInertia(PileSpec::kCoinMass, PileSpec::kCoinR, PileSpec::kCoinH);
  const btVector3 boxInertiaV = boxInertia(PileSpec::kBoxMass, 2 * PileSpec::kBoxHalfX,
                                           2 * PileSpec::kBoxHalfY, 2 * PileSpec::kBoxHalfZ);
  std::vector<btRigidBody*> bodies;
  for (int i = 0; i < n; ++i) {
    const bool coin = i % 2 == 0;
    btRigidBody* body = coin ? scene.addBody(coinShape, PileSpec::kCoinMass, coinInertia,
                                             states[std::size_t(i)].transform, kMu, kCoinGroup,
                                             kCoinGroup | kBoxGroup | kPlaneGroup | kWallGroup)
                             : scene.addBody(boxShape, PileSpec::kBoxMass, boxInertiaV,
                                             states[std::size_t(i)].transform, kMu, kBoxGroup,
                                             kCoinGroup | kBoxGroup | kFloorGroup | kWallGroup);
    body->setLinearVelocity(states[std::size_t(i)].v);
    body->setAngularVelocity(states[std::size_t(i)].w);
    if (scene.kind() != SolverKind::Stock) optIn(scene, body, f);
    bodies.push_back(body);
  }
  return bodies;
}

// ---- the named catalogue ---------------------------------------------------------------
namespace {
constexpr double kG = 9.81;

std::vector<CatalogueEntry> makeCatalogue() {
  std::vector<CatalogueEntry> c;
  c.push_back({"coin", "the coin demo's coin sliding and spinning to rest (one of the coin trio)",
               1.0 / 240.0, 3.0, [](Friction f) { return makeCoin(CoinSpec{}, f, nullptr); }});
  c.push_back({"blocks-row",
               "the blocks demo's row: blocks and a coin sliding and spinning, a stack, a sphere",
               1.0 / 240.0, 3.0,
               [](Friction f) { return makeBlocksRow(BlocksRowSpec{}, f, nullptr); }});
  c.push_back({"terrain",
               "the terrain demo's world: coins and blocks sliding and spinning to rest on a "
               "triangle mesh, level and sloped, one coin over the crease",
               1.0 / 240.0, 2.0,
               [](Friction f) { return makeTerrain(TerrainSpec{}, f, nullptr); }});
  c.push_back({"stack", "a stack of 10 blocks (10 x 10 x 5 cm) standing still", 1.0 / 240.0, 2.0,
               [](Friction f) {
                 auto s = std::make_unique<Scene>(kG);
                 addBlocks(*s, stackPositions(10), f);
                 return s;
               }});
  c.push_back({"pyramid", "a pyramid of 55 blocks, 2 mm gaps, each on two below it", 1.0 / 240.0,
               2.0, [](Friction f) {
                 auto s = std::make_unique<Scene>(kG);
                 addBlocks(*s, pyramidPositions(10, 0.002), f);
                 return s;
               }});
  c.push_back({"incline", "a block on a plane 1 degree steeper than its friction angle (mu 0.5)",
               1.0 / 240.0, 1.0, [](Friction f) {
                 auto s = std::make_unique<Scene>(kG);
                 addIncline(*s, std::atan(BlockSpec{}.mu) + M_PI / 180.0, kG, f);
                 return s;
               }});
  c.push_back({"basic-example",
               "Bullet's BasicExample: 125 boxes (0.2 m) dropped in a 5 x 5 x 5 block, faces "
               "touching",
               1.0 / 60.0, 2.0, [](Friction f) {
                 auto s = std::make_unique<Scene>(10.0);
                 addBasicExample(*s, f);
                 return s;
               }});
  c.push_back({"pour", "100 coins poured into a box (one layer, seed 12345, lengths in metres)",
               1.0 / 240.0, 3.0, [](Friction f) { return makePour(PourSpec{}, f, nullptr, kG); }});
  c.push_back({"pile", "100 coins and boxes rained into a walled square (seed 12445)", 1.0 / 240.0,
               2.0, [](Friction f) {
                 auto s = std::make_unique<Scene>(kG);
                 addPile(*s, pileRain(100, 12345u + 100u), f);
                 return s;
               }});
  return c;
}
}  // namespace

const std::vector<CatalogueEntry>& catalogue() {
  static const std::vector<CatalogueEntry> entries = makeCatalogue();
  return entries;
}

const CatalogueEntry& findScene(const std::string& name) {
  std::string names;
  for (const CatalogueEntry& e : catalogue()) {
    if (e.name == name) return e;
    names += (names.empty() ? "" : ", ") + e.name;
  }
  throw Error("no scene named '" + name + "' in the catalogue (" + names + ")");
}

}  // namespace patchspin::scenes
