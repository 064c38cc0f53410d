// The catalogue of named scenes, built on Scene (scene.hpp) and shared by the
// tests, the demos and the benchmarks; `demos/scene` renders any of them.
//   coin trio   the coin demo's coin, one world per law (exact, ellipsoidal, stock)
//   blocks row  the blocks demo's row (demos/blocks.cpp draws one world per law)
//   terrain     coins and blocks on a triangle-mesh ground, level and sloped
//               (demos/terrain.cpp draws one world per law)
//   stack       blocks standing on each other
//   pyramid     rows of blocks, each on two below it
//   incline     a block on a plane tilted by turning gravity
//   pour        coins poured layer by layer into a walled box, seeded
//   pile        coins and boxes rained into a walled box, seeded
// A scene adds its bodies in a fixed order with fixed parameters: the tests'
// numbers (and tests/bullet/determinism_test.cpp's hashes) depend on it.
#pragma once

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

#include <patchspin/scenes/scene.hpp>
#include <patchspin/scenes/terrain.hpp>
#include <patchspin/types.hpp>

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace patchspin::scenes {

// ---- friction laws ----------------------------------------------------------------
// The law a body gets: stock Bullet (the body not opted in) or a patch law.
enum class Friction { Stock, Ellipsoidal, Exact };
const char* toString(Friction f);
// "stock", "ellipsoidal" or "exact"; throws Error otherwise.
Friction frictionFromString(const std::string& name);
// Opts the body in (PatchOptions with the law alone: mu is Bullet's combined
// friction); nothing for Stock.
void optIn(Scene& scene, btRigidBody* body, Friction f);

// ---- coin trio ----------------------------------------------------------------------
// The coin demo's coin (demos/coin.cpp, `patchspin simulate --engine
// bullet`): a thin coin on the ground plane (friction 1), sliding at v0 along
// x and spinning at omega0, collision margin 1 mm capped at a tenth of the
// smaller of R and H/2; opted in with PatchOptions::mu = mu.
struct CoinSpec {
  double radius = 0.05, height = 0.005, mass = 0.03, mu = 0.3;  // [m], [m], [kg], [-]
  double v0 = 0.5, omega0 = 20.0;                               // [m/s], [rad/s]
  double g = 9.81;                                              // [m/s^2]
  GroundSpec ground;  // the plane z = 0, or a mesh or heightfield of that surface
};
// A world holding the ground and one coin under the law f.
std::unique_ptr<Scene> makeCoin(const CoinSpec& spec, Friction f, btRigidBody** coin);
// The trio's laws in the demo's order (left to right).
constexpr Friction kCoinTrio[3] = {Friction::Exact, Friction::Ellipsoidal, Friction::Stock};

// ---- blocks row ---------------------------------------------------------------------
// The blocks demo's row (demos/blocks.cpp draws one per law): a rectangular
// block sliding and spinning at the origin (as simulate() places it), a
// square block spinning in place, a stack of three blocks at rest, a coin
// sliding and spinning, and a sphere rolling off (never opted in). Every
// body of friction mu on the ground plane (friction 1), exact inertia,
// collision margin 1 mm capped at a tenth of its smallest half size (none
// on the sphere), opted in with PatchOptions::mu = mu.
enum class BodyKind { Box, Cylinder, Sphere };
struct RowBody {
  std::string key, label;
  BodyKind kind = BodyKind::Box;
  Vec3 size = Vec3::Zero();      // box: LX, LY, LZ; cylinder: R, R, H; sphere: R, R, 2R [m]
  double mass = 1.0;             // [kg]
  Vec3 position = Vec3::Zero();  // centre of mass at the start [m]
  Vec2 v0 = Vec2::Zero();        // [m/s]
  double omega0 = 0.0;           // [rad/s]
  bool patch = true;             // opted in under a patch law
  bool moving = true;            // tracked for stopping data (not the stack)
};
struct BlocksRowSpec {
  double mu = 0.3, g = 9.81;
  // rectangular block (the tracked one): face LX x LY, height LZ
  double rectLX = 0.15, rectLY = 0.075, rectLZ = 0.04, rectMass = 1.0;
  double rectV0 = 0.5, rectV0Angle = 0.0, rectOmega0 = 15.0;  // [m/s], [deg], [rad/s]
  // square block spinning in place
  double squareSide = 0.1, squareLZ = 0.04, squareMass = 1.0, squareOmega0 = 20.0;
  // coin
  double coinRadius = 0.05, coinHeight = 0.005, coinMass = 0.03, coinV0 = 0.5, coinOmega0 = 20.0;
  // sphere
  double sphereRadius = 0.03, sphereMass = 0.1, sphereV0 = 0.15;
  // stack: sides bottom to top, each stackLZ high
  double stackBottom = 0.12, stackMiddle = 0.1, stackTop = 0.08, stackLZ = 0.04, stackMass = 0.5;
};
// Every body of the row, the tracked rectangle first.
std::vector<RowBody> blocksRow(const BlocksRowSpec& spec);
// Adds one body of the row (see above); opted in under f where body.patch.
btRigidBody* addRowBody(Scene& scene, const RowBody& body, double mu, Friction f);
// A world holding the ground plane and the row under f; the bodies in row order.
std::unique_ptr<Scene> makeBlocksRow(const BlocksRowSpec& spec, Friction f,
                                     std::vector<btRigidBody*>* bodies,
                                     SolverKind kind = SolverKind::Patch);

// ---- terrain ------------------------------------------------------------------------
// The terrain demo's world (demos/terrain.cpp draws one per law): a mesh (or
// heightfield) ground, level for x <= 0 and rising along x beyond at
// `ground.slope` (terrain.hpp's crease ground, friction 1), with coins and
// rectangular blocks sliding and spinning to rest on it:
//   level_coin, level_block   on the level region, sliding along +x
//   slope_coin, slope_block   on the planar slope, sliding across it (+y)
//   crease_coin               on the level region, sliding over the crease
// Each body's face starts flat on its region; the level and slope bodies
// never reach the crease or the mesh's edge with the default spec (the
// patch law's region: a face on coplanar triangles). Margin 1 mm capped at
// a tenth of the smallest half size, exact inertia, opted in under a patch
// law with PatchOptions::mu = mu.
struct TerrainSpec {
  GroundSpec ground = defaultGround();
  double mu = 0.3, g = 9.81;  // [-], [m/s^2]
  // coins: radius, thickness [m], mass [kg], speed [m/s], spin [rad/s]
  double coinRadius = 0.05, coinHeight = 0.005, coinMass = 0.03, coinV0 = 0.5, coinOmega0 = 20.0;
  // blocks: face LX x LY, height LZ [m], mass [kg], speed [m/s], spin [rad/s]
  double blockLX = 0.15, blockLY = 0.075, blockLZ = 0.04, blockMass = 1.0;
  double blockV0 = 0.5, blockOmega0 = 15.0;
  // a triangle mesh of 1 cm cells over |x|, |y| <= 0.27 m, level for x <= 0,
  // rising at 8 degrees beyond (tan 8 deg = 0.14 < mu: the slope holds)
  static GroundSpec defaultGround();
};
struct TerrainBody {
  std::string key, label;         // e.g. "slope_coin", "slope coin"
  std::string region;             // "level", "slope" or "crease"
  BodyKind kind = BodyKind::Box;  // Box or Cylinder
  Vec3 size = Vec3::Zero();       // box: LX, LY, LZ; cylinder: R, R, H [m]
  double mass = 1.0;              // [kg]
  Vec3 position = Vec3::Zero();   // centre of mass at the start [m]
  Vec3 normal = Vec3::UnitZ();    // of the surface under the face at the start
  double tilt = 0.0;              // the face's tilt about y (the region's slope) [rad]
  Vec3 v0 = Vec3::Zero();         // in the surface's plane [m/s]
  double omega0 = 0.0;            // about `normal` [rad/s]
};
// Every body of the terrain world, in the order makeTerrain adds them,
// placed from the sizes and from twice the pure-sliding travel
// v0^2 / (2 mu g) (spin lengthens it, to
// about twice for the defaults). Throws Error unless the ground is a
// mesh or heightfield crease ground rising at a slope in (0, atan mu), large
// enough that every body starts on it.
std::vector<TerrainBody> terrainBodies(const TerrainSpec& spec);
// Adds one terrain body, its face touching the surface, moving at v0 and
// spinning at omega0, opted in under f.
btRigidBody* addTerrainBody(Scene& scene, const TerrainBody& body, double mu, Friction f);
// A world holding the terrain ground and its bodies under f; the ground
// and then the bodies in order in `ground` and `bodies` (either may be null).
std::unique_ptr<Scene> makeTerrain(const TerrainSpec& spec, Friction f,
                                   std::vector<btRigidBody*>* bodies,
                                   btRigidBody** ground = nullptr);

// ---- blocks: stack, pyramid, incline ----------------------------------------------
// Blocks a x a x 2 halfH [m], mass [kg], friction mu, on the ground plane
// (friction 1). Bullet's box-box test finds no contact between exactly
// touching faces, so a block set on another overlaps it by `overlap`.
struct BlockSpec {
  double a = 0.1, halfH = 0.025, mass = 1.0, mu = 0.5, overlap = 1e-5;
};
// Centres of a stack of n blocks on the ground.
std::vector<btVector3> stackPositions(int n, const BlockSpec& spec = {});
// Centres of a pyramid of `rows` rows (rows + rows-1 + ... + 1 blocks), a
// gap [m] between neighbours in a row, each block standing on two below it.
std::vector<btVector3> pyramidPositions(int rows, double gap, const BlockSpec& spec = {});
// The ground plane, then a block at each position (in order), each under f.
std::vector<btRigidBody*> addBlocks(Scene& scene, const std::vector<btVector3>& positions,
                                    Friction f, const BlockSpec& spec = {});
// A block resting on a plane inclined by alpha [rad]: the plane stays z = 0
// and gravity turns to g (sin alpha, 0, -cos alpha).
btRigidBody* addIncline(Scene& scene, double alpha, double g, Friction f,
                        const BlockSpec& spec = {});

// ---- pour -------------------------------------------------------------------------------
// Coins R 2 cm, H 5 mm, 10 g, friction 0.4, poured in layers of 10 x 10 into
// a 0.6 x 0.6 m box (floor plane and four static walls 0.5 m high), each
// with a seeded random offset, tilt (up to 0.3 rad), slide and spin. Lengths
// in world units of 1/unit m (speeds and g scaled with them, masses and
// times not: the same motion). Coins are Bullet cylinders (margin 0.5 mm) or
// convex hulls of a 16-gon prism (margin 1e-5 m, polyhedral features for
// Bullet's SAT) with the solid cylinder's inertia.
struct PourSpec {
  static constexpr double kR = 0.02, kH = 0.005, kMass = 0.01, kMu = 0.4;  // [m], [m], [kg], [-]
  static constexpr double kMargin = 5e-4;                                  // cylinder coins [m]
  static constexpr int kHullSides = 16;                                    // hull coins' polygon
  static constexpr double kHullMargin = 1e-5;                              // hull coins [m]
  static constexpr double kBoxHalf = 0.3, kWallH = 0.5;                    // [m]
  static constexpr unsigned kSeed = 12345;
  double unit = 1.0;  // world units per metre
  bool hull = false;
  unsigned seed = kSeed;
};
// The hull coin's shape, lengths in world units of 1/unit m.
std::unique_ptr<btConvexHullShape> pourCoinShape(double unit = 1.0);

class Pour {
 public:
  // Adds the floor plane and the four walls to `scene`.
  Pour(Scene& scene, const PourSpec& spec);
  // 10 x 10 coins at height z0 [m], each under f (in the order poured).
  void pourLayer(double z0, Friction f);
  const std::vector<btRigidBody*>& coins() const { return coins_; }
  const PourSpec& spec() const { return spec_; }

 private:
  Scene& scene_;
  PourSpec spec_;
  std::mt19937 rng_;
  std::uniform_real_distribution<double> u_{-1.0, 1.0};
  std::vector<btRigidBody*> coins_;
};

// The 100-coin pour as its tests start it: a world with gravity g unit
// (10 solver iterations, Bullet's SAT for hull coins), the box, and one
// layer 3 cm above the empty floor under f; the coins in the order poured.
std::unique_ptr<Scene> makePour(const PourSpec& spec, Friction f, std::vector<btRigidBody*>* coins,
                                double g = 9.81, SolverKind kind = SolverKind::Patch);

// ---- pile ---------------------------------------------------------------------------------
// The scale benchmark's pile (bench/bench_bullet_scale.cpp): n bodies,
// coins (R 4 cm, H 1 cm, 50 g) and boxes (8 x 6 x 4 cm, 0.2 kg) alternating,
// mu 0.5, margin 1 mm, rained on a 12 cm grid in layers from 5 cm up into a
// walled square of side 0.12 m ceil(sqrt(n / 2)). The floor is a plane for
// the coins and a static box for the boxes (collision groups): stock Bullet
// lets a box fall through a plane and a sliding coin through a static box.
struct PileSpec {
  static constexpr double kCell = 0.12;  // grid spacing [m]
  static constexpr double kCoinR = 0.04, kCoinH = 0.01, kCoinMass = 0.05;
  static constexpr double kBoxHalfX = 0.04, kBoxHalfY = 0.03, kBoxHalfZ = 0.02, kBoxMass = 0.2;
  static constexpr double kMu = 0.5, kMargin = 1e-3;
  static double side(int n);  // of the walled square [m]
};
struct BodyState {
  btTransform transform;
  btVector3 v, w;
};
// The seeded rain: each body's start (transform, slide, spin).
std::vector<BodyState> pileRain(int n, unsigned seed);
// Floor, walls and the n bodies at `states`, all opted in under f; returns
// the bodies (coins at even indices).
std::vector<btRigidBody*> addPile(Scene& scene, const std::vector<BodyState>& states, Friction f);

// ---- heavy on light ---------------------------------------------------------------------
// The hand-back scene (issue 31): a tall light box (0.04 x 0.1 x 0.2 m,
// 1 kg, friction 1 with the ground plane) under a 10 cm cube of `ratio` kg
// (friction 0.5), both under f; a caller pushes the cube along x until the
// light box tips over its edge (its ground patch pivoting on that edge).
struct HeavyOnLight {
  std::unique_ptr<Scene> scene;
  btRigidBody* light = nullptr;
  btRigidBody* heavy = nullptr;
};
HeavyOnLight makeHeavyOnLight(double ratio, Friction f);

// ---- Bullet's BasicExample -------------------------------------------------------------
// Bullet's own example (examples/BasicDemo/BasicExample.cpp), z up: 125
// boxes of 0.2 m (1 kg, Bullet's default margin and friction 0.5) released
// in a 5 x 5 x 5 block with their faces touching, 2 m above a static ground
// box of 100 m, g = 10 m/s^2, stepped at 1/60 s. The boxes' faces meet
// their diagonal neighbours' along an edge: in float, sliver overlaps
// ~1e-7 m wide (in double, none).
std::vector<btRigidBody*> addBasicExample(Scene& scene, Friction f);

// ---- the named catalogue -------------------------------------------------------------------
// One scene of the catalogue as one world: `build` makes it under the law f
// (the coin trio's entry is one coin: the trio is three such worlds).
struct CatalogueEntry {
  std::string name;
  std::string description;
  double dt = 1.0 / 240.0;  // step [s]
  double duration = 2.0;    // suggested run [s]
  std::function<std::unique_ptr<Scene>(Friction)> build;
};
const std::vector<CatalogueEntry>& catalogue();
// The entry of that name; throws Error listing the names otherwise.
const CatalogueEntry& findScene(const std::string& name);

}  // namespace patchspin::scenes
