// Stress scenes of the Bullet integration (issue 6): a stack of 10 blocks,
// a 55-block pyramid, coins poured into a box, a block on an incline just
// below and just above the friction angle, a disk spinning at 1000 rad/s and
// a patch shrinking to a point. Each scene also runs with stock Bullet (no
// body opted in) and prints its figure beside ours; only the patch runs are
// asserted. Full-size pour behind PATCHSPIN_STRESS_FULL=1.
#include "stress_scenes.hpp"

#include <closed_forms.hpp>

#include <patchspin/models.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

// ---- stacks --------------------------------------------------------------------
// Blocks a x a x h (10 x 10 x 5 cm, 1 kg, mu 0.5), each opted in. Bullet's
// box-box test finds no contact between exactly touching faces, so each
// block starts overlapping the one below by kOverlap (else it falls freely
// for a step). After kStandTime every block is within kStandTol of where it
// started (1 % of the block: the stack visibly stands) and no longer drifts:
// its displacement over the last kDriftWindow, divided by that time, is below
// kStandSpeed (at rest: 1 mm/s, far above float round-off). The speed itself
// is no criterion: with 10 solver iterations the blocks of the pyramid
// jitter at up to 1-3 mm/s from one step to the next with every model, stock
// included (the largest speed over the window is reported), and the speed
// at the last step was a sample of that jitter (it passed or failed with
// unrelated changes: 1.3e-4 or 1.3e-3 m/s twenty steps apart).
constexpr double kA = 0.1, kHalfH = 0.025;
constexpr double kOverlap = 1e-5;
constexpr double kStandTime = 2.0;
constexpr double kDriftWindow = 0.25;
constexpr double kStandTol = 0.01 * kA;
constexpr double kStandSpeed = 1e-3;

struct StandResult {
  bool finite = true;
  double maxMove = 0.0;
  double drift = 0.0;     // largest displacement over the last kDriftWindow / kDriftWindow [m/s]
  double maxSpeed = 0.0;  // largest |v| + |omega| a/2 over the last kDriftWindow [m/s]
};

// `positions`: block centres; runs kStandTime and measures.
StandResult standStill(const std::vector<btVector3>& positions, Friction model, int iterations = 10) {
  Scene scene(kG, iterations);
  scene.addGroundPlane(1.0);
  std::vector<btRigidBody*> blocks;
  for (const btVector3& p : positions) {
    btRigidBody* b = scene.addBox(bt(kA / 2, kA / 2, kHalfH), 1.0, p, 0.5);
    optIn(scene, b, model);
    blocks.push_back(b);
  }
  StandResult r;
  const int steps = int(std::lround(kStandTime / kDt)),
            windowStart = steps - int(std::lround(kDriftWindow / kDt));
  std::vector<btVector3> atWindowStart;
  for (int k = 0; k < steps; ++k) {
    if (k == windowStart)
      for (btRigidBody* b : blocks) atWindowStart.push_back(b->getWorldTransform().getOrigin());
    scene.step(kDt);
    for (btRigidBody* b : blocks) r.finite = r.finite && isFinite(b);
    if (!r.finite) return r;
    if (k >= windowStart)
      for (btRigidBody* b : blocks)
        r.maxSpeed = std::max(r.maxSpeed, double(b->getLinearVelocity().length()) +
                                              double(b->getAngularVelocity().length()) * kA / 2);
  }
  for (size_t i = 0; i < blocks.size(); ++i) {
    const btVector3 p = blocks[i]->getWorldTransform().getOrigin();
    r.maxMove = std::max(r.maxMove, double((p - positions[i]).length()));
    r.drift = std::max(r.drift, double((p - atWindowStart[i]).length()) / kDriftWindow);
  }
  return r;
}

// (Found by this test with the solver of commit ebe872d, which warm
// started the patch blocks with Bullet's m_warmstartingFactor 0.85: the
// contacts under a column of blocks started 15 % short each step and the
// blocks kept a steady sinking velocity, 2.7 cm/s at the top of the stack of
// 10, 6 mm sunk. Fixed by the full warm start, kPatchWarmStartFactor = 1.)
void reportStand(const char* scene, const std::vector<btVector3>& positions) {
  Table table(scene, {"model", "finite", "max displacement [m]", "drift, last 0.25 s [m/s]",
                      "max speed, last 0.25 s [m/s]", "stands"});
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const StandResult r = standStill(positions, m);
    const bool ok = r.finite && r.maxMove < kStandTol && r.drift < kStandSpeed;
    table.add({toString(m), passFail(r.finite), fmt("%.3e", r.maxMove), fmt("%.3e", r.drift),
               fmt("%.3e", r.maxSpeed), passFail(ok)});
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(r.finite) << toString(m);
    EXPECT_LT(r.maxMove, kStandTol) << toString(m);
    EXPECT_LT(r.drift, kStandSpeed) << toString(m);
  }
  table.emit();
}

TEST(StressScenes, StackOfTenBlocksStandsStill) {
  std::vector<btVector3> pos;
  for (int i = 0; i < 10; ++i) pos.push_back(bt(0, 0, kHalfH + i * (2 * kHalfH - kOverlap)));
  reportStand("Stack of 10 blocks, 2 s", pos);
}

// 10 rows, 10 + 9 + ... + 1 = 55 blocks; a 2 mm gap between neighbours in a
// row, each block standing on two below it (two patches, each a rectangle
// (a - gap)/2 x a).
TEST(StressScenes, PyramidOf55BlocksStands) {
  constexpr double kGap = 0.002;
  std::vector<btVector3> pos;
  for (int row = 0; row < 10; ++row) {
    const int n = 10 - row;
    for (int j = 0; j < n; ++j)
      pos.push_back(bt((j - 0.5 * (n - 1)) * (kA + kGap), 0, kHalfH + row * (2 * kHalfH - kOverlap)));
  }
  ASSERT_EQ(pos.size(), 55u);
  reportStand("Pyramid of 55 blocks, 2 s", pos);
}

// ---- coins poured into a box -----------------------------------------------------
// Coins R = 2 cm, H = 5 mm, 10 g, mu 0.4 (Bullet cylinders; with
// PATCHSPIN_POUR_COIN=hull, convex hulls of a 16-gon prism, see below),
// poured in layers of 10 x 10 (one every kPourInterval, 3 cm above the
// pile) into a 0.6 x 0.6 m box (static floor plane and four static walls
// 0.5 m high), each with a seeded random tilt (up to 0.3 rad), offset and
// velocity. kPourTime after the last layer: none has left the box (inside
// the walls, above the floor by more than kPourSinkTol: a coin resting on
// its rim sinks by its margin at most) and all have come to rest (speeds
// below kPourRestSpeed at every step of the last kPourCreepWindow; coins
// leaning on others are Bullet point contacts, which settle more slowly
// than patches, hence 1 cm/s). The largest speed over the window, not the
// last step's: a coin rocking in place (float, seed 12345, ellipsoidal, at
// up to 2.4 cm/s) passed or failed by the phase its rocking was in at the
// last step (7.6e-3 m/s at 10 s, 1.4e-2 at 8 s).
// kPourTime is set by the slowest physics in the pour, not by the solver: a
// coin that lands tilted with spin rolls on its rim like Euler's disk, and
// rolling without slip dissipates nothing, so it only comes to rest once it
// lies flat. The slowest one of the 100-coin pour (coin 2: tilted 0.20 rad
// at landing, 0.11 at 1.6 s, 0.055 at 3.9 s, precessing at 10-16 rad/s,
// the same in all three models: it is on Bullet's point contacts) lies flat
// at ~5 s; 4 s, the first choice, caught it mid-roll. 8 s, the second,
// caught the slowest of the five seeds' pours (double, seed 3, one coin
// rolling on its rim at 0.23-0.29 m/s in every model) lying down inside
// the window: it was last above 1 cm/s 7.73 s after the last layer (patch
// laws; stock 8.03 s), hence 10 s. With one seed and 8 s, both patch
// models were at rest, every coin on a patch (largest speed 2.3e-5 m/s in
// float, 1e-27 in double), while stock Bullet's float pour is not: its flat
// coins keep wobbling on their point contacts (1-5 cm/s at 6, 8 and 10 s).
// In double, stock is at rest too. (Figures in metres; in decimetres, the
// float default below: ellipsoidal 1.5e-12 m/s, exact 0, stock 5.6e-2.)
// Length unit (pourUnit): decimetres in float Bullet, metres in double.
// Bullet's GJK stops on absolute tolerances (|v|^2 < 1e-6 world units^2 in
// float, 1e-12 in double), and its manual asks for moving objects of at
// least ~0.2 units; a coin is 0.04 x 0.005 m. In metres float Bullet
// reports no contact for 37 % of overlapping coin pairs (census test
// below), coins landing on coins pass into each other, and Baumgarte
// velocity, erp |depth| / dt, pushes the interleaved coins apart for as
// long as the pile holds them together: the 1000-coin pile boiled (at 8 s
// 953 of 1000 coins above 1 cm/s with stock Bullet, 837 ellipsoidal,
// ~1 m/s at most, 70-120 coin-coin contacts deeper than 4 mm at every
// second; one coin 2.2 mm under the floor). In decimetres the census
// misses none and no coin-coin contact is deeper than ~1 mm; dropped as
// one column (before kPourInterval), at 8 s 162 (ellipsoidal) and 256
// (stock) of 1000 coins were above 1 cm/s, at most 0.073 and 0.079 m/s.
// Not at rest either: run on to 20 s, 86-129 (ellipsoidal) and 149-273
// (stock) coins keep moving, the fastest tilted coins inside the pile
// rocking at 1-2 rad/s on 5-10 contact manifolds. Poured layer by layer,
// 12 s: 202 (ellipsoidal), 171 (exact), 231 (stock) above 1 cm/s, no
// coin deeper than 0.72 mm under the floor; ellipsoidal with 30 solver
// iterations 62 at 12 s, with 50 56-75 from 12 to 16 s, with 30 and
// convex-convex multipoint iterations (3, 3) 36-71 (largest speeds
// 0.03-0.1 m/s): fewer, never none. Tried in metres: CCD
// (2 mm swept sphere, Bullet's allowed CCD penetration lowered from 4 cm
// to 0.1 mm), no change; convex-convex multipoint iterations (3, 3),
// worse (997 coins moving at 2 s, one 5.3 mm under the floor); steps of
// 1/960 s, worse (largest speed 4 m/s: Baumgarte grows as 1/dt); the
// layers poured one every 0.4 s from 3 cm above the pile, 942 moving at
// 12 s. In decimetres: 30 solver iterations, 114 moving at 8 s
// (ellipsoidal); split impulse at every depth, worse (178 ellipsoidal,
// 794 stock); centimetres, worse than decimetres (194, ellipsoidal:
// Bullet's other absolute lengths, the 4 cm split-impulse threshold and
// the contact thresholds, shrink with the unit). In double Bullet in
// decimetres, six of the 100 coins still roll on their rims at 8 s, tilt
// shrinking and spin growing like Euler's disk, with Bullet's own solver
// too; in metres the double pour is at rest, hence its default.
// The 1000-coin pile creeps; it does not jitter in place (scratch driver,
// float, decimetres, layer by layer, run on to 20-34 s): the coins' mean
// height keeps falling, 0.03-0.05 mm/s at 12-30 s with stock Bullet and
// with the ellipsoidal law, 160-380 coins move by more than 1 mm in every
// second (the table's creep columns) and the kinetic energy holds at
// ~1e-4 J: the pile compacts under its own weight, which feeds the motion.
// Bullet's point-contact friction does not hold it. Bullet's default
// solver has one friction direction per contact point (along the slip at
// set-up), none across it; with two (SOLVER_USE_2_FRICTION_DIRECTIONS)
// 51-161 coins are above 1 cm/s at 16-20 s (stock; ellipsoidal 100-186),
// with two and 50 iterations 9-41 (stock; ellipsoidal 28-41), the height
// still falling by 0.01 mm/s; 50 iterations with one direction leave
// 39-114 (stock); warm starting off, no better (and deeper contacts).
// The patches' own part (ellipsoidal, one direction, 10 iterations, 17-20
// s): a flatness tolerance of 0.005 rad instead of the default 0.02 leaves
// 72-90 coins above 1 cm/s, 0.002 37-87, against 168-220 with the default
// (coins tilted within the tolerance and its hysteresis are held flat by
// their patch against their other contacts), still creeping at 0.02-0.03
// mm/s; no tilt correction on patches whose centre is lifted, 116-205.
// 0.005 as the default was tried and not kept: every test passes in both
// precisions, and 8 s after the 1000-coin pour's last layer (float) the
// largest speeds fall from 0.131 / 0.117 m/s (ellipsoidal / exact) to
// 0.055 / 0.033 and the coins moved by more than 1 mm in the last second
// from 337 / 362 to 317 / 193, still creeping; but the 100-coin pour is
// no longer at rest on its patches: 1.4e-3 m/s (ellipsoidal, every coin
// on a patch) and 7.2e-3 (exact, 99 on patches) against 1.5e-12 and 0.
// The same driver, before the stack-hold fix (see the pour test's fixed
// defects). Not for want of friction: with mu = 1 on every contact (instead
// of 0.4 on the floor and 0.16 coin on coin, Bullet's product of the two)
// the pile creeps as much or more (10-14 s: 466-684 coins moved by more than
// 1 mm in each second with stock Bullet, 313-390 ellipsoidal, the mean
// height falling by 0.05-0.13 mm/s, against 351-562, 300-368 and 0.03-0.11
// with the pour's friction). Not for want of iterations: with two friction
// directions and 150 iterations, 9-41 (stock) and 17-48 (ellipsoidal) coins
// are above 1 cm/s at 15-20 s, the height falling by 0.01-0.02 mm/s, as with
// 50. Split impulses at every depth in this pour: stock 669-760 above 1 cm/s
// at 9-14 s. Bullet's sleeping at its default thresholds (0.8 units/s, here
// 8 cm/s, and 1 rad/s, for 2 s) puts no coin to sleep in 20 s, stock or
// ellipsoidal: the pile is one island, and some coin in it is always faster.
// Traced (mu = 1, ellipsoidal, 13.0-13.3 s): a flat coin resting on its
// patch (omega = 0) is lifted 0.24 mm when its side neighbour's rim contact
// appears 0.18 mm deep, its normal 0.06-0.13 out of the horizontal; tilted
// past the flatness hysteresis it loses its patch and falls back at 3.5 cm/s
// 0.14 s later. The full pour adds rows with two friction directions and 50
// iterations: Bullet's own contacts at the strongest settings tried do not
// hold the pile either, stock or under the ellipsoidal law.
// Hull coins (PATCHSPIN_POUR_COIN=hull), an experiment, not the default
// (the figures in this paragraph are from metres and a hull margin of
// 0.5 mm, with which the hulls were 1 mm thinner against each other than
// against the floor, see kPourHullMargin; with 1e-5 m, 1000 hull coins in
// metres, float, ellipsoidal: 316 above 1 cm/s at 8 s, at most 0.070 m/s,
// the deepest 0.26 mm under the floor):
// with btCylinderShapeZ coins Bullet builds a coin-on-coin manifold one GJK
// point per step (cylinders are not polyhedral), and the 1000-coin pile
// never comes to rest in any model, stock included: at 8 s in float, 953
// (stock) and 837 (ellipsoidal) of 1000 coins above 1 cm/s, largest speeds
// 0.89-1.07 m/s, and one coin 2.20 mm under the floor (ellipsoidal),
// beyond kPourSinkTol. A hull with polyhedral features and Bullet's SAT
// (m_enableSatConvex) gets a full clipped manifold in one step. The
// cylinders stay the default: a coin is a disk, the patch models' main
// case, and the hull's facets change the physics (below). Measured with
// the hulls (float, same seeds; coins above 1 cm/s at 8 s, largest speed,
// deepest coin at 8 s): 200 coins: ellipsoidal 1 (1.7e-2 m/s),
// exact 0 (6.6e-3), stock 16 (6.2e-2), cylinders 22 / - / 46; 400 coins:
// 9 (5.1e-2), 22 (2.9e-2), stock 79 (7.3e-2), cylinders 161 / - / 259;
// 1000 coins: 347 (8.6e-2, 0.98 mm), 359 (7.2e-2, 0.86 mm), stock 491
// (0.20 m/s, 1.29 mm), against the cylinders' 837 / - / 953 (~1 m/s,
// 2.20 / 1.87 / 1.60 mm). Calmer, not at rest. Without SAT (Bullet's GJK
// normal, then clipping) 200 coins leave 10 / 5 / 11 moving. 32 sides
// instead of 16 leave 58 of 400 moving (ellipsoidal) at 2.7x the time: the
// 16-gon's facets also resist rolling on the rim (it tips over a facet at
// pi/16), and a coin standing on its edge in the pile stands on a facet (a
// patch with the floor, 3.0e-5 m^2). The 100-coin pour: 99 of 100 coins on
// floor patches (16-gons, area 1.164e-3 m^2 against the disk's 1.257e-3),
// largest speed 1.8e-3 m/s (ellipsoidal) and 2.0e-3 (exact), 4.9e-13 and
// 3.1e-14 on the patches; stock 4.1e-2 (one coin moving). In double Bullet
// the hulls help little: 1000 coins end with largest speeds 9.9e-2 m/s
// (ellipsoidal), 0.10 (exact) and 0.15 (stock), against the cylinders'
// 0.15, 0.096 and 0.093, none escaped; the 100-coin pour is at rest in all
// three models (5.7e-11, 3.4e-11, 7.5e-5 m/s, every coin on a patch).
// The full hull pour takes 1030 s (float) and 1079 s (double) for its
// three runs, against ~700 s (float) with cylinders. Side facets also make
// patches (19-22 of ~480 in the 1000-coin pours, coins side by side or
// against a wall, mostly without load).
constexpr double kPourR = 0.02, kPourH = 0.005, kPourMass = 0.01;
// The cylinder coins' collision margin (Bullet's cylinder keeps its outline
// R x H and puts the margin inside it).
constexpr double kPourMargin = 5e-4;
// Sides of the hull coins' polygon and their margin. The hull's points lie
// one margin inside R and H/2 and the margin is tiny: Bullet clips hull
// against hull (SAT, m_enableSatConvex) on the points alone, margins
// ignored, while against the floor and the walls the contact is one margin
// outside the points. With the cylinder's 0.5 mm the coins were 1 mm
// thinner against each other than against the floor (two coaxial coins
// overlapping by 1.04 mm: Bullet reported 0.035 mm; with 1e-5 m, 1.016 mm).
constexpr int kPourCoinSides = 16;
constexpr double kPourHullMargin = 1e-5;
constexpr double kBoxHalf = 0.3, kWallH = 0.5;
constexpr double kPourTime = 10.0;  // after the last layer
// Layers are poured one by one onto the pile, not dropped as one column:
// dropped together, each column of ten coins landed within ~0.1 s at up
// to 2.5 m/s, and in decimetres too one coin was driven through the four
// below it and the floor (exact model: 5 mm under the floor from 0.15 s
// on, held there by the coin above it, traced).
constexpr double kPourInterval = 0.4, kPourDropHeight = 0.03;
constexpr double kPourSinkTol = 2e-3;
constexpr double kPourRestSpeed = 1e-2;
// A pile at rest does not creep: over the last second of the pour no coin
// moves by more than 1 mm (a coin at kPourRestSpeed would move 10 mm).
constexpr double kPourCreepWindow = 1.0, kPourCreepTol = 1e-3;
// The 1000-coin pile's creep is compared with stock Bullet's over the last
// kPourCreepWindows windows, not the last alone: in a creeping pile the
// count of coins moved changes by tens from one window to the next (the
// pour test's figures), so one window's comparison sits at that noise.
constexpr int kPourCreepWindows = 5;

struct PourResult {
  bool finite = true;
  int escaped = 0;
  // largest speed |v| + R |omega| over the last kPourCreepWindow: a coin
  // rocking in place is caught at any phase of its rocking, not only when
  // the last step finds it fast
  double maxSpeed = 0.0;
  double maxSpeedOnPatch = 0.0;  // the same, over the steps a coin stood on a patch
  // the last time, after the last layer, that a coin was faster than
  // kPourRestSpeed (0 if none was)
  double settledAt = 0.0;  // s
  int patches = 0;
  // over the last kPourCreepWindow: coins moved by more than kPourCreepTol
  // (|dp| + R x rotation angle) and the change of the coins' mean height
  int crept = 0;
  double meanHeightRate = 0.0;  // m/s
  // coins moved by more than kPourCreepTol in each of the last
  // kPourCreepWindows windows, the last window last, and their mean
  std::vector<int> creptPerWindow;
  double creptMean = 0.0;
};

// A coin as a convex hull of a kPourCoinSides-gon prism with polyhedral
// features (Bullet clips hull against hull with them); lengths in world
// units of 1/unit m.
std::unique_ptr<btConvexHullShape> pourCoinShape(double unit = 1.0) {
  auto shape = std::make_unique<btConvexHullShape>();
  shape->setMargin(btScalar(unit * kPourHullMargin));
  const double r = unit * (kPourR - kPourHullMargin), h = unit * (kPourH / 2 - kPourHullMargin);
  for (int k = 0; k < kPourCoinSides; ++k) {
    const double a = 2 * M_PI * k / kPourCoinSides;
    shape->addPoint(bt(r * std::cos(a), r * std::sin(a), -h), false);
    shape->addPoint(bt(r * std::cos(a), r * std::sin(a), h), k + 1 == kPourCoinSides);
  }
  shape->initializePolyhedralFeatures();
  return shape;
}

static_assert(kPourRestSpeed == 1e-2 && kPourCreepWindow == 1.0 && kPourCreepWindows == 5,
              "the pour table's columns name 1 cm/s, 1 s and 5 s");
const std::vector<std::string> kPourColumns = {"model",
                                               "finite",
                                               "escaped",
                                               "max speed in the last 1 s [m/s]",
                                               "max speed on a patch [m/s]",
                                               "patches at the end",
                                               "moved > 1 mm in the last 1 s",
                                               "the same, each of the last 5 s (mean)",
                                               "mean height change [mm/s]",
                                               "last above 1 cm/s [s]",
                                               "at rest"};

// The pour's "at rest": no coin faster than kPourRestSpeed and none moved by
// more than kPourCreepTol in the last kPourCreepWindow.
bool pourAtRest(const PourResult& r) {
  return r.maxSpeed < kPourRestSpeed && r.crept == 0;
}

// "a / b / c / d / e (mean)", the counts of the creep windows, oldest first
std::string windowCounts(const PourResult& r) {
  std::string s;
  for (int n : r.creptPerWindow) s += (s.empty() ? "" : " / ") + std::to_string(n);
  return s + fmt(" (%.1f)", r.creptMean);
}

void addPourRow(Table& table, const std::string& label, bool stock, const PourResult& r) {
  table.add({label, passFail(r.finite), std::to_string(r.escaped), fmt("%.3e", r.maxSpeed),
             stock ? "-" : fmt("%.3e", r.maxSpeedOnPatch), std::to_string(r.patches),
             std::to_string(r.crept), windowCounts(r), fmt("%.2e", 1e3 * r.meanHeightRate),
             fmt("%.2f", r.settledAt), passFail(pourAtRest(r))});
}

// World units per metre of the pour (PATCHSPIN_POUR_UNIT: dm or m; the
// default is dm in float Bullet, m in double). See the census test below:
// in metres float Bullet misses a third of the overlaps between cylinder
// coins and the pile boils; double Bullet misses none in metres, and in
// decimetres tilted coins on the floor spin up (below).
constexpr double kDecimetres = 10.0;  // world units per metre
double pourUnit() {
  const char* unit = std::getenv("PATCHSPIN_POUR_UNIT");
  if (!unit || std::string(unit).empty()) return kDouble ? 1.0 : kDecimetres;
  if (std::string(unit) == "dm") return kDecimetres;
  if (std::string(unit) == "m") return 1.0;
  throw std::invalid_argument(std::string("PATCHSPIN_POUR_UNIT: expected dm or m, got '") + unit + "'");
}

bool pourHullCoins() {
  const char* coin = std::getenv("PATCHSPIN_POUR_COIN");
  if (!coin || std::string(coin).empty() || std::string(coin) == "cylinder") return false;
  if (std::string(coin) == "hull") return true;
  throw std::invalid_argument(std::string("PATCHSPIN_POUR_COIN: expected cylinder or hull, got '") + coin + "'");
}

// Bullet's solver settings for the pour: its defaults (one friction
// direction per contact point, along the slip when the step starts) with
// the scenes' 10 iterations, or the strongest point contacts tried on the
// 1000-coin pile (two directions, SOLVER_USE_2_FRICTION_DIRECTIONS, and 50
// iterations).
struct PourSolver {
  bool twoFrictionDirections = false;
  int iterations = 10;
};
constexpr PourSolver kStrongPointContacts{true, 50};

// The pour in world units of 1/unit m: lengths, speeds and g scaled, masses
// and times not (the same motion); the result in metres.
// The pour's random layout and throws (the full pour's, and the first of
// the 100-coin pours' seeds below).
constexpr unsigned kPourSeed = 12345;

PourResult pour(int layers, Friction model, bool hull, double unit, PourSolver solver = {},
                unsigned seed = kPourSeed) {
  Scene scene(kG * unit, solver.iterations);
  if (solver.twoFrictionDirections)
    scene.world().getSolverInfo().m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  if (hull) scene.world().getDispatchInfo().m_enableSatConvex = true;  // hull-hull axes by SAT (see above)
  OwnedBodies owned(scene.world());
  scene.addGroundPlane(1.0);
  auto at = [unit](double x, double y, double z) { return bt(unit * x, unit * y, unit * z); };
  for (int side = 0; side < 4; ++side) {
    const double sx = side < 2 ? (side == 0 ? -1 : 1) : 0, sy = side >= 2 ? (side == 2 ? -1 : 1) : 0;
    const btVector3 half = sx != 0 ? at(0.05, kBoxHalf + 0.1, kWallH / 2) : at(kBoxHalf + 0.1, 0.05, kWallH / 2);
    scene.addStaticBox(half, at(sx * (kBoxHalf + 0.05), sy * (kBoxHalf + 0.05), kWallH / 2), 1.0);
  }
  const double R = unit * kPourR, H = unit * kPourH;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<btRigidBody*> coins;
  auto pourLayer = [&](double z0) {  // 10 x 10 coins at height z0 [m]
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) {
        const btVector3 p = at((i - 4.5) * 0.055 + 0.005 * u(rng), (j - 4.5) * 0.055 + 0.005 * u(rng), z0);
        btRigidBody* c = nullptr;
        btTransform t;
        if (hull) {
          t.setIdentity();
          t.setOrigin(p);
          // the solid cylinder's inertia, as with the cylinder coins
          const double jx = kPourMass * (3 * R * R + H * H) / 12;
          c = owned.add(pourCoinShape(unit), kPourMass, bt(jx, jx, kPourMass * R * R / 2), t, 0.4);
        } else {
          c = scene.addCylinder(R, H, kPourMass, p, 0.4, unit * kPourMargin);
          t = c->getWorldTransform();
        }
        t.setRotation(btQuaternion(bt(u(rng), u(rng), 0).normalized(), btScalar(0.3 * std::abs(u(rng)))));
        c->setWorldTransform(t);
        c->setLinearVelocity(at(0.3 * u(rng), 0.3 * u(rng), -0.5));
        c->setAngularVelocity(bt(0, 0, 10 * u(rng)));
        optIn(scene, c, model);
        coins.push_back(c);
      }
  };
  // a layer every kPourInterval, kPourDropHeight above the highest coin
  const int steps = int(std::lround((kPourInterval * (layers - 1) + kPourTime) / kDt));
  const int windowSteps = int(std::lround(kPourCreepWindow / kDt));
  const int creepFrom = steps - windowSteps;
  const double lastLayer = kPourInterval * (layers - 1);
  PourResult r;
  // a coin's motion since a pose: |dp| + R x rotation angle [m]
  auto movedSince = [R, unit](const btRigidBody* c, const btTransform& was) {
    const btTransform& now = c->getWorldTransform();
    const btQuaternion turn = now.getRotation() * was.getRotation().inverse();
    const double angle = 2 * std::acos(std::min(1.0, std::abs(double(turn.getW()))));
    return (double((now.getOrigin() - was.getOrigin()).length()) + R * angle) / unit;
  };
  // the coins' poses at the start of the current creep window
  std::vector<btTransform> windowStart;
  auto countCrept = [&]() {
    int n = 0;
    for (size_t i = 0; i < windowStart.size(); ++i)
      n += movedSince(coins[i], windowStart[i]) > kPourCreepTol;
    return n;
  };
  std::vector<double> windowSpeed;  // each coin's largest speed since creepFrom
  for (int k = 0, poured = 0; k < steps; ++k) {
    if (k >= steps - kPourCreepWindows * windowSteps && (steps - k) % windowSteps == 0) {
      if (!windowStart.empty()) r.creptPerWindow.push_back(countCrept());
      windowStart.clear();
      for (const btRigidBody* c : coins) windowStart.push_back(c->getWorldTransform());
    }
    if (k == creepFrom) windowSpeed.assign(coins.size(), 0.0);
    if (poured < layers && k * kDt >= poured * kPourInterval - 1e-9) {
      double top = 0.0;
      for (const btRigidBody* c : coins) top = std::max(top, extremeZ(c, false) / unit);
      pourLayer(top + kPourDropHeight);
      ++poured;
    }
    scene.step(kDt);
    const double t = (k + 1) * kDt;
    for (size_t i = 0; i < coins.size(); ++i) {
      const btRigidBody* c = coins[i];
      const double speed =
          (double(c->getLinearVelocity().length()) + double(c->getAngularVelocity().length()) * R) /
          unit;
      if (!windowSpeed.empty()) {
        windowSpeed[i] = std::max(windowSpeed[i], speed);
        if (scene.solver().findPatchReport(c))
          r.maxSpeedOnPatch = std::max(r.maxSpeedOnPatch, speed);
      }
      if (t > lastLayer && speed >= kPourRestSpeed) r.settledAt = t - lastLayer;
    }
  }
  double heightChange = 0.0;
  for (size_t i = 0; i < coins.size(); ++i) {
    const btRigidBody* c = coins[i];
    if (!isFinite(c)) {
      r.finite = false;
      continue;
    }
    const btTransform& now = c->getWorldTransform();
    const btTransform& was = windowStart.at(i);  // the poses at creepFrom
    heightChange += double(now.getOrigin().z() - was.getOrigin().z()) / unit;
    const btVector3 p = now.getOrigin() / btScalar(unit);
    if (std::abs(double(p.x())) > kBoxHalf || std::abs(double(p.y())) > kBoxHalf ||
        extremeZ(c, true) / unit < -kPourSinkTol)
      ++r.escaped;
    const double speed = windowSpeed.at(i);
    r.maxSpeed = std::max(r.maxSpeed, speed);
  }
  r.creptPerWindow.push_back(countCrept());
  r.crept = r.creptPerWindow.back();  // the last window's
  for (int n : r.creptPerWindow) r.creptMean += n;
  r.creptMean /= double(r.creptPerWindow.size());
  r.patches = int(scene.solver().patchReports().size());
  r.meanHeightRate = heightChange / double(coins.size()) / kPourCreepWindow;
  return r;
}

TEST(StressScenes, CoinsPouredIntoABoxComeToRestAndStayInside) {
  const int layers = stressFull() ? 10 : 1;
  std::string defects;
  Table table("Pour of " + std::to_string(100 * layers) + (pourHullCoins() ? " hull" : "") + " coins into a box, " +
                  fmt("%.0f", kPourTime) + " s, lengths in " + (pourUnit() == 1.0 ? "m" : "dm"),
              kPourColumns);
  // The 100-coin pour (CI) is run with several seeds: which coins end
  // leaning on a neighbour on Bullet's point contacts, where a coin rocks
  // without losing energy (below), is chance, so one seed says little.
  const std::vector<unsigned> seeds = stressFull() ? std::vector<unsigned>{kPourSeed}
                                                   : std::vector<unsigned>{kPourSeed, 1, 2, 3, 4};
  auto reportMotion = [&defects](const std::string& label, const PourResult& r) {
    if (r.finite && !pourAtRest(r))
      defects += "\n  " + label + ": max speed " + fmt("%.2e", r.maxSpeed) +
                 " m/s in the last second of " + fmt("%.0f", kPourTime) + " s, " +
                 fmt("%.2f", r.settledAt) + " s the last time above " +
                 fmt("%.0f", 1e2 * kPourRestSpeed) + " cm/s; in its last second " +
                 std::to_string(r.crept) + " coins moved by more than 1 mm, mean height " +
                 fmt("%+.2e", 1e3 * r.meanHeightRate) + " mm/s";
  };
  std::map<Friction, int> restingPours;
  for (unsigned seed : seeds) {
    const std::string ofSeed = seeds.size() > 1 ? ", seed " + std::to_string(seed) : std::string();
    std::vector<std::pair<Friction, PourResult>> runs;
    for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
      runs.emplace_back(m, pour(layers, m, pourHullCoins(), pourUnit(), {}, seed));
      restingPours[m] += pourAtRest(runs.back().second);
    }
    const PourResult& stock = runs.back().second;
    for (const auto& [m, r] : runs) {
      addPourRow(table, toString(m) + ofSeed, m == Friction::Stock, r);
      if (m == Friction::Stock) continue;
      EXPECT_TRUE(r.finite) << toString(m) << ofSeed;
      EXPECT_EQ(r.escaped, 0) << toString(m) << ofSeed;
      // no more coins creep than with Bullet's own point contacts (figures
      // in the two branches below): in the 1000-coin pour, which creeps in
      // every model, the mean over the last kPourCreepWindows seconds; in
      // the 100-coin pours, whose earlier windows still hold coins settling
      // (float, seed 1, ellipsoidal: 0.2 against stock's 0.0), the last
      // second
      if (stressFull())
        EXPECT_LE(r.creptMean, stock.creptMean)
            << toString(m) << ": more coins crept than with stock Bullet";
      else
        EXPECT_LE(r.crept, stock.crept)
            << toString(m) << ofSeed << ": more coins crept than with stock Bullet";
      // what the patches carry is at rest (the coins still moving are on
      // Bullet's point contacts, below). Not in the 1000-coin pour: 10 s
      // after its last layer it is still moving in every model (largest
      // speed over the last second, |v| + R |omega|, float, decimetres:
      // ellipsoidal 0.34 m/s, exact 0.34, stock 0.39; double, metres: 0.53,
      // 0.30, 0.47; coins on patches up to 0.27 / 0.16 m/s and 0.33 / 0.15;
      // no coin escapes or sinks in either; in its last second, float, 283,
      // 323 and 512 coins moved by more than 1 mm and the mean height fell
      // by 0.042, 0.042 and 0.078 mm/s, double 128, 145 and 404 and 0.048,
      // 0.035 and 0.076 mm/s: the pile creeps; 24 Nov), so it is reported
      // with the rest. Run on to 60 s after the last layer (this test built
      // with kPourTime 60 and 60 windows, float, decimetres, 24 Nov) it
      // creeps still: coins moved per second, mean over 0-10 s and over
      // 50-60 s, ellipsoidal 388 -> 58, exact 425 -> 58, stock 676 -> 88;
      // two friction directions and 50 iterations, level from ~20 s,
      // ellipsoidal 60 -> 8.1, stock 74 -> 7.4; largest speed in the 60th
      // second 0.10-0.19 m/s in every row.
      // (8 s after the last layer, with the last step's speeds, after the
      // clearance fix: float 0.035, 0.049 and 0.089 m/s, 222, 177 and 540
      // coins moved; double 0.082, 0.135, 0.145 m/s, 184, 174, 464.) The figures
      // below up to "In double" are from metres, before the length unit and
      // the layer-by-layer pour (see above the scene).
      // Measured every second (scratch driver, float): the 1000-coin pile does
      // not settle, it boils at a steady state, vertical speeds of +-0.2-0.4
      // m/s at 1-16 s. Stock: 992 of 1000 coins above 1 cm/s at 0.5 s, 953 at
      // 8 s; 916 at 8 s with 50 solver iterations instead of 10, and 887
      // with the split-impulse threshold at 0 (no Baumgarte velocity) instead
      // of Bullet's -4 cm. Ellipsoidal: 897 at 1 s, 837 at 8 s, 810 at 15 s,
      // with 175 -> 405 coins on patches. Two layers (200 coins) leave 46
      // (stock) and 22 (ellipsoidal) coins moving at 8 s, four layers 259 and
      // 161. The patches shrink the number of moving coins, but a pile that
      // Bullet's own contacts keep boiling (stock, whatever the iterations)
      // does not come to rest with any friction model. In double Bullet it
      // boils too, at a lower level: from 15 to 24 s, 141-252 coins above
      // 1 cm/s (stock) and 110-186 (ellipsoidal, 507-540 on patches)
      if (!stressFull()) {
        // what Bullet's point contacts do (a coin rolling on its rim, or one
        // bridging the floor and a neighbour, rocking) is compared with stock
        // Bullet and reported below, not asserted: those coins move without
        // losing energy in every model (measured, double, seed 3: one coin
        // rolled at 0.23-0.29 m/s on its rim for 7 s in every model and lay
        // flat at 7.73 s; float, seed 12345, ellipsoidal: a coin bridging the
        // floor and a neighbour, tilted 0.13 rad, its rim on each, rocks in
        // place about the line through its two supports, +-0.008 rad with a
        // period of 0.12 s, at up to 2.4 cm/s; it slid off flat at 4.2 s
        // before the patch's gap was limited by the face's clearance,
        // 62aa52e. It has no patch, only Bullet's point contacts; run on from
        // the pour's end, it stops within 1.25 s and lies flat with Bullet's
        // warm starting off, slows to ~2e-3 m/s with 50 iterations, and
        // handed to stock Bullet (patch friction disabled on every coin)
        // rocks on at 1.1-1.8 cm/s for 6 s, among stock's flat coins
        // wobbling at up to 6 cm/s. Scratch runs, 24 Nov)
        EXPECT_LT(r.maxSpeedOnPatch, kPourRestSpeed) << toString(m) << ofSeed;
      } else {
        // The 1000-coin pile creeps in every model (below), but the patches
        // do not make it creep more than Bullet's own point contacts do.
        // Coins moved by more than 1 mm in each of the last five seconds,
        // oldest first (mean), 10 s after the last layer, 24 Nov: float,
        // ellipsoidal 327 / 254 / 254 / 267 / 283 (277.0), exact 369 / 318
        // / 333 / 316 / 323 (331.8), stock 696 / 584 / 540 / 575 / 512
        // (581.4); double 205 / 217 / 150 / 137 / 128 (167.4), 193 / 164 /
        // 139 / 113 / 145 (150.8), 558 / 490 / 464 / 413 / 404 (465.8).
        // With two friction directions and 50 iterations, float,
        // ellipsoidal 29 / 14 / 12 / 12 / 17 (16.8) against stock's 26 / 34
        // / 7 / 5 / 26 (19.6); double 9 / 7 / 5 / 1 / 4 (5.2) against 13 /
        // 5 / 9 / 3 / 4 (6.8). One window's count moves by tens from one
        // second to the next (stock, strong, float: 34 then 7), so the last
        // second alone compared at that noise (double, strong: 4 against 4;
        // an intermediate build of 24 Nov read 6 against 4 and failed); the
        // five seconds' mean is compared. Last second, earlier builds:
        // before patches were made without Bullet's points (24 Nov), float
        // 207 / 202 and double 191 / 182, strong 17 / 3; at 8 s: 222 / 177
        // against 540 and 184 / 174 against 464, strong 2 / 3 and 7 / 9;
        // before the clearance fix, float 271 / 296, double 294 / 200,
        // strong 52 / 23; before the stack-hold fix, float 337 / 362,
        // double 189 / 219.
        if (r.finite && r.maxSpeedOnPatch >= kPourRestSpeed)
          defects += std::string("\n  ") + toString(m) + ": max speed on a patch " +
                     fmt("%.2e", r.maxSpeedOnPatch) + " m/s in the last second of " +
                     fmt("%.0f", kPourTime) + " s";
      }
    }
    for (const auto& [m, r] : runs)
      if (m != Friction::Stock) reportMotion(toString(m) + ofSeed, r);
  }
  // the patch laws bring at least as many of the pours to rest as stock
  // Bullet does
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact})
    EXPECT_GE(restingPours[m], restingPours[Friction::Stock]) << toString(m);
  if (seeds.size() > 1)
    std::printf("[pour] pours at rest of %zu: ellipsoidal %d, exact %d, stock %d\n", seeds.size(),
                restingPours[Friction::Ellipsoidal], restingPours[Friction::Exact],
                restingPours[Friction::Stock]);
  if (stressFull()) {
    // Bullet's own limit, shown in the table: with the strongest point
    // contacts tried (see the comment below) stock Bullet does not hold the
    // pile either, nor does the ellipsoidal law, but it leaves no more coins
    // creeping than stock (mean of the last 5 s, float 16.8 against 19.6,
    // double 5.2 against 6.8; above).
    const std::string strong = ", 2 friction directions, 50 iterations";
    const PourResult ell =
        pour(layers, Friction::Ellipsoidal, pourHullCoins(), pourUnit(), kStrongPointContacts);
    const PourResult stockStrong =
        pour(layers, Friction::Stock, pourHullCoins(), pourUnit(), kStrongPointContacts);
    addPourRow(table, "ellipsoidal" + strong, false, ell);
    addPourRow(table, "stock" + strong, true, stockStrong);
    EXPECT_TRUE(ell.finite) << strong;
    EXPECT_EQ(ell.escaped, 0) << strong;
    EXPECT_LE(ell.creptMean, stockStrong.creptMean)
        << "ellipsoidal" << strong << ": more coins crept than with stock";
    reportMotion("ellipsoidal" + strong, ell);
    reportMotion("stock" + strong, stockStrong);
  }
  table.emit();
  // Fixed defect (62aa52e): with two friction directions and 50 iterations
  // the ellipsoidal pile crept more than stock's (52 / 23 coins against
  // 7 / 9). Traced (scratch driver): coin 916, tilted 0.015 rad on coin 616,
  // cycled every ~11 steps: its patch formed, closed the gap at its centre
  // (0.2 mm) in one step, which drove its low rim into 616; the patch
  // tipped back to Bullet, whose contacts pushed the coin up over ten steps,
  // and the patch formed again. A patch now closes its gap only until the
  // low side of a tilted face touches (PatchFrictionSolver.
  // TiltedPatchDoesNotDriveItsLowEdgeIn).
  // Fixed defect: the first run of the rows with two friction directions
  // and 50 iterations, in double Bullet, threw coins out of the box under
  // the ellipsoidal law (174 escaped, largest speed 70 m/s; float: none).
  // Traced: coin 246 lay between two patches (356 on it, it on 146), the
  // lower body of a stack solved with its support held, while a
  // neighbour's point contact (346) pressed on it; within one step it left
  // at 62 m/s and 2085 rad/s, Bullet's rows on it carrying 1.7 N s. The
  // hold's fold assumes the held body moves only as its patch lets it, and
  // the support's share is not projected onto its limits, so with other
  // rows on that body the held iterations need not converge. Holds are now
  // taken only where the held body is in none of Bullet's rows
  // (PatchFrictionSolver.StackHoldsOnlyWhereTheHeldBodyCarriesNothingElse).
  // Fixed defect: in the double build's exact pour one coin (53), flat on a
  // floor patch, hovered, falling at g dt in every step with Pz = 0 while
  // something pushed it back up. The push came from a second "patch" with
  // its neighbour: the two coins touched rim to rim, their faces were
  // parallel, and the pair was taken for a face contact between one coin's
  // bottom and the other's top, gap -5.4 mm, whose position correction
  // lifted the coin 0.25 mm every few steps. Faces now have to face the
  // contact and hold its points (kFacingCos, kOnFaceMargins in the solver;
  // PatchFrictionSolver.CoinsSideBySideTouchRimToRimAndAreNoPatch).
  // Before: with 4 s, the pour was not at rest in any model (coins still
  // rolling on their rims, above). The 1000-coin pile
  // (PATCHSPIN_STRESS_FULL=1, float, ellipsoidal) also ends with one coin
  // 2.1 mm under the floor, beyond kPourSinkTol (hull coins: deepest after
  // 2 s 1.37 mm ellipsoidal, 1.40 exact, 2.0 stock; at 8 s 0.98, 0.86,
  // 1.29):
  // analysed, it is a bottom coin under ten layers, tilted 0.042 rad (beyond
  // the patch's flatness hysteresis, so on Bullet's point contacts), and
  // stock Bullet's own pour ends with its deepest coin 1.6 mm under (both
  // also sink below 2 mm for a moment: 783 coins vs 807 stock). The depth
  // is Bullet's point-contact penetration under the pile's weight with 10
  // iterations, not the patch: the deepest coins at the end are all point
  // contacts, and the three coins that crossed 2 mm while they still
  // reported a floor patch were being knocked over by falling coins (tilted
  // 0.12-0.17 rad within that step; the next step hands them to Bullet).
  // The coins standing on a patch are at rest (asserted above: at most
  // 1.1e-3 m/s over the last second of the five 100-coin pours); the
  // moving ones are on Bullet's point contacts, which do not dissipate a
  // wobble on the rim (rolling without slip loses no energy). Tried:
  // Bullet's rolling and spinning friction (1e-3 m) on the coins brings
  // stock's 100-coin pour to rest but not the patch pours: a coin tilted
  // 0.035 rad with its rim on a flat neighbour's, still a patch within the
  // flatness hysteresis, is turned flat by the patch's tilt correction into
  // the neighbour's point contact and hops off the floor every 0.4 s
  // (1.5 cm/s).
  if (!defects.empty())
    GTEST_SKIP() << "known defect: poured coins not at rest after " << kPourTime
                 << " s (see the test's comment)" << defects;
}

// The hull coins' 100-coin pour in every run (the option above is otherwise
// only taken by hand): no coin escapes or sinks past kPourSinkTol, every
// patch model ends at rest (measured, the largest speed over the last
// second: 0 in both models in float, in decimetres, stock 6.2e-2 m/s;
// 5.4e-31 m/s in double, in metres, stock 3.2e-2; every coin on a patch;
// with 8 s and the last step's speeds stock read 3.8e-3 and 1.9e-4), and
// the coins on patches are at rest.
TEST(StressScenes, HullCoinsPouredIntoABoxComeToRestAndStayInside) {
  Table table("Pour of 100 hull coins into a box, " + fmt("%.0f", kPourTime) + " s, lengths in " +
                  (pourUnit() == 1.0 ? "m" : "dm"),
              kPourColumns);
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const PourResult r = pour(1, m, true, pourUnit());
    addPourRow(table, toString(m), m == Friction::Stock, r);
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(r.finite) << toString(m);
    EXPECT_EQ(r.escaped, 0) << toString(m);
    EXPECT_LT(r.maxSpeed, kPourRestSpeed) << toString(m);
    EXPECT_LT(r.maxSpeedOnPatch, kPourRestSpeed) << toString(m);
    EXPECT_EQ(r.crept, 0) << toString(m) << ": the pile creeps";
  }
  table.emit();
}

// A coin rolling on its rim, pushed into the floor past Bullet's
// split-impulse threshold, stays there: Bullet's limit cycle, in every
// model (the rim is a point contact, Bullet's). Found on 24 Nov: scratch
// runs of the 100-coin pours with Bullet's warm-starting factor at 0.5,
// 0.7, 0.95 or 1.0, or a linear slop of 0.2 or 0.5 mm, counted coins as
// escaped (sunk past kPourSinkTol); every one was such a coin, inside the
// box, rolling at |v| + R |omega| = 0.31 m/s, tilted 0.087 rad, its lowest
// point 4.9-5.4 mm under the floor (the centre 0.6-1.1 mm under), the same
// state in every model. Bullet's split-impulse threshold is 0.04 world
// units (m_splitImpulsePenetrationThreshold), 4 mm in the float pour's
// decimetres; deeper contacts are corrected by a split impulse whose turn
// is scaled by m_splitImpulseTurnErp (0.1). Started in the state of one
// such coin (seed 12345, factor 1.0, coin 37, at 10 s), a lone coin keeps
// it: in a plain-Bullet scratch driver (no patchspin, float) the state
// repeats to four digits for 20 s (|omega| 12.28 rad/s, v_z -0.050 m/s in
// every step, 4 manifold points, the deepest 4.9 mm); with the turn erp at
// 1, with split impulses at every depth (threshold 0) or none (Baumgarte
// at every depth), or with half the spin, the coin comes out and lies
// flat. Measured here in decimetres and, where the threshold is 4 cm
// (Baumgarte at this depth), in metres. Measured (float / double):
// trapped in decimetres in every model at 4.90 / 4.96 mm, 0.31 m/s;
// released with the turn erp at 1 and in metres, flat, stock's coin in
// metres in float falling at g dt and pushed back in every step.
TEST(StressScenes, ARollingCoinSunkPastBulletsSplitThresholdStaysInTheFloor) {
  constexpr double kTrapTime = 10.0;  // [s]
  // depth of the coin's lowest point under the floor [m] (the state below is
  // 4.9 mm in; a coin out of the floor has its outline on it)
  constexpr double kTrappedDepth = 4e-3, kReleasedDepth = 1e-4;
  constexpr double kFlatTilt = 1e-3;  // [rad] lying flat (trapped: 0.089)
  struct Run {
    std::string label;
    Friction model;
    double unit;
    double turnErp;  // Bullet's m_splitImpulseTurnErp
  };
  const double defaultTurnErp = double(btContactSolverInfo().m_splitImpulseTurnErp);
  const std::vector<Run> runs = {
      {"stock, dm", Friction::Stock, kDecimetres, defaultTurnErp},
      {"ellipsoidal, dm", Friction::Ellipsoidal, kDecimetres, defaultTurnErp},
      {"exact, dm", Friction::Exact, kDecimetres, defaultTurnErp},
      {"stock, dm, turn erp 1", Friction::Stock, kDecimetres, 1.0},
      {"ellipsoidal, dm, turn erp 1", Friction::Ellipsoidal, kDecimetres, 1.0},
      {"stock, m", Friction::Stock, 1.0, defaultTurnErp},
      {"ellipsoidal, m", Friction::Ellipsoidal, 1.0, defaultTurnErp},
  };
  Table table("A coin rolling on its rim, started 4.9 mm into the floor, after " +
                  fmt("%.0f", kTrapTime) + " s",
              {"run", "lowest point [mm]", "tilt [rad]", "max speed in the last 1 s [m/s]"});
  for (const Run& run : runs) {
    const double unit = run.unit;
    Scene scene(kG * unit, PourSolver{}.iterations);  // the pours' solver settings
    scene.world().getSolverInfo().m_splitImpulseTurnErp = btScalar(run.turnErp);
    scene.addGroundPlane(1.0);
    btRigidBody* coin = scene.addCylinder(unit * kPourR, unit * kPourH, kPourMass, bt(0, 0, 0), 0.4,
                                          unit * kPourMargin);
    const btVector3 up = bt(0.011, -0.087, 0.996).normalized();
    const btVector3 axis = bt(0, 0, 1).cross(up);
    btTransform t;
    t.setIdentity();
    t.setRotation(btQuaternion(axis.normalized(), btAsin(axis.length())));
    t.setOrigin(bt(0, 0, -0.0006 * unit));
    coin->setWorldTransform(t);
    coin->setLinearVelocity(bt(0.0094 * unit, -0.0062 * unit, -0.0532 * unit));
    coin->setAngularVelocity(bt(3.359, 11.912, 2.433));
    optIn(scene, coin, run.model);
    const int steps = int(std::lround(kTrapTime / kDt));
    double maxSpeed = 0.0;
    for (int k = 0; k < steps; ++k) {
      scene.step(kDt);
      if (k >= steps - int(std::lround(1.0 / kDt)))
        maxSpeed =
            std::max(maxSpeed, (double(coin->getLinearVelocity().length()) +
                                double(coin->getAngularVelocity().length()) * unit * kPourR) /
                                   unit);
    }
    ASSERT_TRUE(isFinite(coin)) << run.label;
    const double lowest = extremeZ(coin, true) / unit;
    const double tilt = std::acos(
        std::min(1.0, std::abs(double(coin->getWorldTransform().getBasis().getColumn(2).z()))));
    table.add({run.label, fmt("%+.3f", 1e3 * lowest), fmt("%.3f", tilt), fmt("%.3e", maxSpeed)});
    if (unit == kDecimetres && run.turnErp == defaultTurnErp) {
      // Bullet's limit cycle (above), whatever the coin's friction model
      EXPECT_LT(lowest, -kTrappedDepth) << run.label << ": the coin came out of the floor";
      EXPECT_GT(maxSpeed, kPourRestSpeed) << run.label;
    } else {
      // released: the coin lies flat on the floor, and at rest on its patch
      // (stock Bullet's flat coin, in metres, falls at g dt in every step
      // and is pushed back: 4.1e-2 m/s in float, 9e-9 in double)
      EXPECT_GT(lowest, -kReleasedDepth) << run.label;
      EXPECT_LT(tilt, kFlatTilt) << run.label;
      if (run.model != Friction::Stock) {
        EXPECT_LT(maxSpeed, kPourRestSpeed) << run.label;
      }
    }
  }
  table.emit();
}

// Why the cylinder pour boils: Bullet's float build often reports no contact
// between two overlapping cylinder coins (btCylinderShapeZ, GJK/EPA), so
// coins pass into each other where they land. Interleaved coins are then
// pushed apart by Baumgarte velocity, erp |depth| / dt, for as long as the
// pile holds them together (traced in the 1000-coin pour: a coin landing
// at 1.3 m/s on a tilted one, 945 of 11,340 sampled points inside it, up
// to 2.48 mm deep, and Bullet found no contact; the next step it was
// through). The census: a seeded sample of coin pairs, each pose checked
// for overlap independently of Bullet (points of coin B's solid cylinder
// on a grid, 0.1 R x 0.1 H x 4 degrees, tested against coin A's cylinder),
// kept if some point lies at least kCensusDepth inside A; then each pair
// is given to Bullet as cylinders and as the pour's hull coins (SAT).
// Asserted: the hull coins see every overlap (each 16-gon lies within
// R (1 - cos(pi/16)) = 0.38 mm of its circle, so the hulls of two coins
// overlapping by 1 mm overlap by at least 0.24 mm), and so do the
// cylinders with lengths in decimetres. Reported: the cylinders' misses in
// metres, Bullet's defect (measured: float 1,302 of 3,514 pairs, 37 %;
// double none).
TEST(StressScenes, CoinOverlapsSeenByBulletCensus) {
  constexpr int kCensusPoses = 4000;
  constexpr double kCensusDepth = 1e-3;
  auto sampledDepth = [](const btTransform& a, const btTransform& b) {
    double deepest = -1.0;
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j < (i == 0 ? 1 : 90); ++j)
        for (int l = 0; l <= 10; ++l) {
          const double r = kPourR * i / 10, t = 2 * M_PI * j / 90, z = kPourH * (l / 10.0 - 0.5);
          const btVector3 q = a.invXform(b * bt(r * std::cos(t), r * std::sin(t), z));
          deepest = std::max(deepest, std::min(kPourH / 2 - std::abs(double(q.z())),
                                               kPourR - std::hypot(double(q.x()), double(q.y()))));
        }
    return deepest;
  };
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  world.getDispatchInfo().m_enableSatConvex = true;
  btCylinderShapeZ cylinder(bt(kPourR, kPourR, kPourH / 2));
  cylinder.setMargin(btScalar(kPourMargin));
  // the same coins with lengths in decimetres (Bullet's manual: moving
  // objects should be at least ~0.2 units; its GJK stops on absolute
  // tolerances, |v|^2 < 1e-6 in float)
  constexpr double kDm = kDecimetres;
  btCylinderShapeZ cylinderDm(bt(kDm * kPourR, kDm * kPourR, kDm * kPourH / 2));
  cylinderDm.setMargin(btScalar(kDm * kPourMargin));
  const std::unique_ptr<btConvexHullShape> hull = pourCoinShape();
  struct Counter : btCollisionWorld::ContactResultCallback {
    int touching = 0;
    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      touching += p.getDistance() < 0;
      return 0;
    }
  };
  auto seen = [&](btCollisionShape* shape, const btTransform& ta, const btTransform& tb) {
    btCollisionObject a, b;
    a.setCollisionShape(shape);
    b.setCollisionShape(shape);
    a.setWorldTransform(ta);
    b.setWorldTransform(tb);
    world.addCollisionObject(&a);
    world.addCollisionObject(&b);
    Counter c;
    world.contactPairTest(&a, &b, c);
    world.removeCollisionObject(&a);
    world.removeCollisionObject(&b);
    return c.touching > 0;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int pairs = 0, cylinderMissed = 0, cylinderDmMissed = 0, hullMissed = 0;
  for (int k = 0; k < kCensusPoses; ++k) {
    // A tilted up to 0.3 rad as in the pour; B within 2R and H of it, tilted up to 0.5 rad
    const btTransform ta(btQuaternion(bt(u(rng), u(rng), 0).normalized(), btScalar(0.3 * std::abs(u(rng)))),
                         bt(0.1 * u(rng), 0.1 * u(rng), 0.002));
    const double rho = 2 * kPourR * std::abs(u(rng)), phi = M_PI * u(rng), dz = kPourH * u(rng);
    const btTransform tb(btQuaternion(bt(u(rng), u(rng), 0).normalized(), btScalar(0.5 * std::abs(u(rng)))),
                         ta * bt(rho * std::cos(phi), rho * std::sin(phi), dz));
    if (sampledDepth(ta, tb) < kCensusDepth) continue;
    ++pairs;
    cylinderMissed += !seen(&cylinder, ta, tb);
    cylinderDmMissed += !seen(&cylinderDm, btTransform(ta.getBasis(), ta.getOrigin() * btScalar(kDm)),
                              btTransform(tb.getBasis(), tb.getOrigin() * btScalar(kDm)));
    hullMissed += !seen(hull.get(), ta, tb);
  }
  Table table("Coin pairs overlapping by at least 1 mm that Bullet reports as not touching",
              {"coins", "overlapping pairs", "no contact"});
  table.add({"cylinders (btCylinderShapeZ, GJK/EPA)", std::to_string(pairs), std::to_string(cylinderMissed)});
  table.add({"the same cylinders, lengths in dm", std::to_string(pairs), std::to_string(cylinderDmMissed)});
  table.add({"16-gon hulls (SAT and clipping)", std::to_string(pairs), std::to_string(hullMissed)});
  table.emit();
  ASSERT_GT(pairs, kCensusPoses / 2);  // the sample is mostly overlaps (3,514 of 4,000)
  EXPECT_EQ(hullMissed, 0);
  EXPECT_EQ(cylinderDmMissed, 0);
}

// ---- incline -----------------------------------------------------------------------
// The block (10 x 10 x 5 cm, 1 kg, mu 0.5) on a plane inclined by alpha: the
// plane stays z = 0 and gravity turns, g (sin alpha, 0, -cos alpha).
// Friction angle atan(mu) = 26.57 deg.
//   alpha = atan(mu) - 1 deg: stays; displacement over 2 s below
//     kInclineStayTol (the no-creep bound of tests/bullet: 1e-6 m double,
//     1e-5 m float, see patch_friction_solver_test.cpp);
//   alpha = atan(mu) + 1 deg: slides from rest with a = g (sin alpha - mu cos
//     alpha) = 0.151 m/s^2. Bullet's symplectic Euler gives v_n = n dt a
//     exactly, so v(t)/t must match a to round-off: kInclineAccelTol = 1e-3
//     relative (float: ~500 velocity updates of relative error 6e-8 each).
constexpr double kInclineMu = 0.5;
constexpr double kInclineStayTol = kDouble ? 1e-6 : 1e-5;
constexpr double kInclineAccelTol = 1e-3;
constexpr double kOneDegree = M_PI / 180.0;

struct InclineResult {
  bool finite = true;
  double displacement = 0.0, velocity = 0.0, time = 0.0, tilt = 0.0;
};

InclineResult incline(double alpha, Friction model, double duration) {
  Scene scene(kG, 10);
  scene.world().setGravity(bt(kG * std::sin(alpha), 0, -kG * std::cos(alpha)));
  scene.addGroundPlane(1.0);
  btRigidBody* b = scene.addBox(bt(kA / 2, kA / 2, kHalfH), 1.0, bt(0, 0, kHalfH), kInclineMu);
  optIn(scene, b, model);
  const btVector3 start = b->getWorldTransform().getOrigin();
  InclineResult r;
  const int n = int(std::lround(duration / kDt));
  for (int k = 0; k < n; ++k) {
    scene.step(kDt);
    r.finite = r.finite && isFinite(b);
    const btVector3 w = b->getAngularVelocity();
    r.tilt = std::max(r.tilt, std::hypot(double(w.x()), double(w.y())));
  }
  r.time = n * kDt;
  const btVector3 d = b->getWorldTransform().getOrigin() - start;
  r.displacement = std::hypot(double(d.x()), double(d.y()));
  r.velocity = double(b->getLinearVelocity().x());
  return r;
}

TEST(StressScenes, BlockOnInclineStaysBelowAndSlidesAboveTheFrictionAngle) {
  const double phi = std::atan(kInclineMu);
  Table table("Block on an incline, mu = 0.5 (friction angle 26.57 deg)",
              {"model", "alpha [deg]", "displacement [m]", "a measured [m/s^2]", "a = g(sin - mu cos)", "tilt rate max"});
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const double below = phi - kOneDegree, above = phi + kOneDegree;
    const InclineResult stay = incline(below, m, 2.0);
    const InclineResult slide = incline(above, m, 1.0);
    const double aExpected = kG * (std::sin(above) - kInclineMu * std::cos(above));
    const double aMeasured = slide.velocity / slide.time;
    table.add({toString(m), fmt("%.2f", below * 180 / M_PI), fmt("%.3e", stay.displacement), "-", "0",
               fmt("%.2e", stay.tilt)});
    table.add({toString(m), fmt("%.2f", above * 180 / M_PI), fmt("%.3e", slide.displacement), fmt("%.6f", aMeasured),
               fmt("%.6f", aExpected), fmt("%.2e", slide.tilt)});
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(stay.finite && slide.finite) << toString(m);
    EXPECT_LT(stay.displacement, kInclineStayTol) << toString(m);
    EXPECT_NEAR(aMeasured, aExpected, kInclineAccelTol * aExpected) << toString(m);
  }
  table.emit();
}

// ---- disk spinning at 1000 rad/s ---------------------------------------------------
// Coin R = 5 cm, H = 1 cm, 1 kg, mu 0.3, spinning in place at 1000 rad/s
// (rim speed 50 m/s). Uniform pressure on a centred disk: spin torque
// mu m g 2R/3 (exact law, and the ellipsoidal one with pi_xy = rho), J =
// m R^2 / 2, so it stops at t = 3 R omega0 / (4 mu g) = 12.74 s. Each step
// removes the same d omega exactly; float round-off of omega (6e-5 rad/s per
// step at 1000 rad/s) over 3000 steps stays below 2e-4 omega0:
// kSpinStopTol = 1e-3 relative, plus one step. Tilt rates below 1e-3 rad/s
// (the rocking bound); the centre stays within 1 % of R
// (kSpinDriftTol: a pure spin carries no net friction force).
constexpr double kSpinR = 0.05, kSpinH = 0.01, kSpinMu = 0.3, kOmega0 = 1000.0;
constexpr double kSpinStopTol = 1e-3;
constexpr double kTiltBound = 1e-3;
constexpr double kSpinDriftTol = 0.01 * kSpinR;

struct SpinResult {
  bool finite = true;
  double tStop = -1.0, tilt = 0.0, drift = 0.0;
};

SpinResult spinDown(Friction model, double tMax) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  btRigidBody* c = scene.addCylinder(kSpinR, kSpinH, 1.0, bt(0, 0, kSpinH / 2), kSpinMu);
  optIn(scene, c, model);
  c->setAngularVelocity(bt(0, 0, kOmega0));
  SpinResult r;
  for (int k = 1; k * kDt <= tMax; ++k) {
    scene.step(kDt);
    if (!isFinite(c)) {
      r.finite = false;
      break;
    }
    const btVector3 w = c->getAngularVelocity();
    r.tilt = std::max(r.tilt, std::hypot(double(w.x()), double(w.y())));
    const btVector3 p = c->getWorldTransform().getOrigin();
    r.drift = std::max(r.drift, std::hypot(double(p.x()), double(p.y())));
    const PatchReport* rep = scene.solver().findPatchReport(c);
    const bool stopped = model == Friction::Stock ? std::abs(double(w.z())) < 1e-3 * kOmega0 : rep && rep->sticking;
    if (stopped) {
      r.tStop = k * kDt;
      break;
    }
  }
  return r;
}

TEST(StressScenes, DiskSpinningAt1000RadPerSecondSpinsDownOnTime) {
  const double tPredicted = 3.0 * kSpinR * kOmega0 / (4.0 * kSpinMu * kG);
  Table table("Disk spinning at 1000 rad/s (predicted stop " + fmt("%.4f", tPredicted) + " s)",
              {"model", "finite", "t_stop [s]", "rel. error", "max tilt rate [rad/s]", "centre drift [m]"});
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const SpinResult r = spinDown(m, 1.5 * tPredicted);
    table.add({toString(m), passFail(r.finite), fmt("%.4f", r.tStop), fmt("%.2e", (r.tStop - tPredicted) / tPredicted),
               fmt("%.2e", r.tilt), fmt("%.2e", r.drift)});
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(r.finite) << toString(m);
    EXPECT_NEAR(r.tStop, tPredicted, kSpinStopTol * tPredicted + kDt) << toString(m);
    EXPECT_LT(r.tilt, kTiltBound) << toString(m);
    EXPECT_LT(r.drift, kSpinDriftTol) << toString(m);
  }
  table.emit();
}

// ---- a patch shrinking to a point ---------------------------------------------------
// Disk of radius R, uniform pressure, sliding at u along x while spinning at
// omega: eps = R omega / u -> 0 as R -> 0. Eq. (44) (point Coulomb
// friction): P = -mu Pz (1, 0), T_z = 0. Expanding the local slip direction
// of Eq. (16) in eps (v = (u - omega y, omega x)):
//   exact:        |P| = mu Pz (1 - eps^2 / 8 + O(eps^4)),  T_z = -mu Pz omega R^2 / (4 u) (1 + O(eps^2))
//   ellipsoidal:  |P| = mu Pz / sqrt(1 + (2 eps / 3)^2)    (Eq. (43), rho = pi_xy = 2R/3, closed),
//                 T_z = -mu Pz (2R/3) (2 eps / 3) / sqrt(1 + (2 eps / 3)^2)
// so |Q - Q44| -> 0 like eps^2 (force) and R eps (torque). Tolerances as a
// function of R: the exact law within kShrinkRelTol eps^2 of its leading
// terms (the O(eps^4) rest, relative eps^2, with coefficient below 1 for
// eps <= 0.3: measured 0.13), the ellipsoidal law to round-off (1e-12). The
// exact law is also compared with the Weidman-Malhotra closed form
// (tests/support) to 1e-9 for eps >= 0.03; below, the closed form itself
// loses digits (its elliptic-integral terms cancel for slip ratio
// u / (R omega) > ~100: 2.6e-9 at eps = 3e-3, 1.5e-6 at 3e-4) and the
// expansion, whose rest is eps^4, is the sharper oracle.
constexpr double kShrinkRelTol = 1.0;
constexpr double kClosedFormTol = 1e-9;

TEST(StressScenes, ShrinkingPatchApproachesPointCoulombFrictionEq44) {
  const double mu = 0.4, Pz = 2.0, u = 1.0, omega = 3.0;
  Table table("Patch shrinking to a point: friction wrench vs Eq. (44), u = 1 m/s, omega = 3 rad/s",
              {"R [m]", "eps", "exact 1-|P|/muPz", "eps^2/8", "exact Tz/(muPz)", "-omega R^2/(4u)",
               "ell. 1-|P|/muPz", "ell. Tz/(muPz)"});
  double lastDeficit = 1e300;
  for (double R : {0.1, 0.03, 0.01, 3e-3, 1e-3, 1e-4}) {
    const PatchShape disk = PatchShape::disk(R);
    const FrictionPatch patch(disk, LinearPressure::uniform(disk, Pz), mu);
    const double rho = patch.rho(), eps = R * omega / u;
    const Vec3 xo = slipState(u, 0, omega, rho);
    const Vec3 qe = *patch.QofSlip(Model::Exact, xo);
    const Vec3 qa = *patch.QofSlip(Model::Ellipsoidal, xo);
    const double deficitE = 1.0 - std::hypot(qe.x(), qe.y()) / (mu * Pz);
    const double tzE = qe.z() * rho / (mu * Pz);
    const double deficitA = 1.0 - std::hypot(qa.x(), qa.y()) / (mu * Pz);
    const double tzA = qa.z() * rho / (mu * Pz);
    table.add({fmt("%g", R), fmt("%.0e", eps), fmt("%.4e", deficitE), fmt("%.4e", eps * eps / 8), fmt("%.4e", tzE),
               fmt("%.4e", -omega * R * R / (4 * u)), fmt("%.4e", deficitA), fmt("%.4e", tzA)});
    // independent closed form of the exact law (Weidman-Malhotra, Eq. (52)-(53))
    if (eps >= 0.03) {
      const Vec3 qc = testing::uniformDiskQ(R, mu, Pz, rho, xo.normalized());
      EXPECT_NEAR((qe - qc).norm(), 0.0, kClosedFormTol * mu * Pz) << "R = " << R;
    }
    // exact law: leading terms in eps, Eq. (44) in the limit
    EXPECT_NEAR(deficitE, eps * eps / 8, kShrinkRelTol * eps * eps * eps * eps / 8 + 1e-12) << "R = " << R;
    EXPECT_NEAR(tzE, -omega * R * R / (4 * u), kShrinkRelTol * eps * eps * omega * R * R / (4 * u) + 1e-15)
        << "R = " << R;
    EXPECT_NEAR(qe.y(), 0.0, 1e-12 * mu * Pz);
    EXPECT_LT(deficitE, lastDeficit) << "the approach to Eq. (44) is monotone";
    lastDeficit = deficitE;
    // ellipsoidal law, closed form of Eq. (43)
    const double k = 2.0 * eps / 3.0;
    EXPECT_NEAR(deficitA, 1.0 - 1.0 / std::sqrt(1 + k * k), 1e-12) << "R = " << R;
    EXPECT_NEAR(tzA, -(2 * R / 3) * k / std::sqrt(1 + k * k), 1e-12 * R) << "R = " << R;
  }
  table.emit();
}

// The same in a Bullet world: a coin (H = R / 5, 20 g, mu 0.3) sliding at
// 1 m/s and spinning at 20 rad/s. Over the first 0.1 s the mean
// deceleration must approach mu g (point friction) like eps^2 and the spin
// torque (reported T_z) must vanish like R^2. Stock Bullet's deceleration is
// printed beside it (point friction at its rim contact points).
//   |a / (mu g) - 1| <= c eps^2 (1 + eps^2) + kDecelFloor with eps the
//   largest R |omega| / |u| of the window (eps grows as the coin slows:
//   d ln eps / dt = mu g / (2u) > 0), c = 1/8 (exact; the expansion above
//   with its measured O(eps^4) coefficient 0.13 < 1) or 2/9 (ellipsoidal:
//   1 - 1/sqrt(1 + (2 eps/3)^2) <= (2/9) eps^2); kDecelFloor = 1e-3 for the
//   first step's contact and float velocities.
//   |T_z| <= mu Pz omega R^2 / (4 u) (1 + eps^2) (exact) or mu Pz (4/9)
//   omega R^2 / u (ellipsoidal, Eq. (43) bounded by its leading term), with
//   Pz, u, omega of the first step's report (the implicit step evaluates
//   the law at the slip after the step).
constexpr double kDecelFloor = 1e-3;

TEST(StressScenes, ShrinkingCoinInBulletApproachesPointFriction) {
  const double mu = 0.3, m = 0.02, v0 = 1.0, w0 = 20.0, window = 0.1;
  Table table("Shrinking coin in Bullet: deceleration over the first 0.1 s and spin torque (v0 = 1 m/s, omega0 = 20)",
              {"R [m]", "eps max", "model", "a/(mu g)", "bound |a/(mu g) - 1|", "Tz [N m] (first step)", "bound |Tz|"});
  for (double R : {0.05, 0.015, 0.005, 0.0015, 0.0005}) {
    for (Friction f : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
      Scene scene(kG, 10);
      scene.addGroundPlane(1.0);
      btRigidBody* c = scene.addCylinder(R, R / 5, m, bt(0, 0, R / 10), mu, std::min(1e-3, R / 50));
      optIn(scene, c, f);
      c->setLinearVelocity(bt(v0, 0, 0));
      c->setAngularVelocity(bt(0, 0, w0));
      double tz = 0.0, tzBound = 0.0, epsMax = R * w0 / v0;
      const double coef = f == Friction::Exact ? 1.0 / 8.0 : 2.0 / 9.0;
      const int n = int(std::lround(window / kDt));
      for (int k = 0; k < n; ++k) {
        scene.step(kDt);
        const double u = std::hypot(double(c->getLinearVelocity().x()), double(c->getLinearVelocity().y()));
        epsMax = std::max(epsMax, R * std::abs(double(c->getAngularVelocity().z())) / u);
        const PatchReport* rep = scene.solver().findPatchReport(c);
        if (k == 0 && rep) {
          tz = rep->Q.z() * rep->rho;
          const double ur = std::hypot(rep->slip.x(), rep->slip.y()), wr = rep->slip.z() / rep->rho;
          const double e = R * std::abs(wr) / ur;
          tzBound = f == Friction::Exact ? mu * rep->loads.Pz * std::abs(wr) * R * R / (4 * ur) * (1 + e * e)
                                         : mu * rep->loads.Pz * (4.0 / 9.0) * std::abs(wr) * R * R / ur;
        }
      }
      const double a = (v0 - double(c->getLinearVelocity().length())) / (n * kDt);
      const double aBound = coef * epsMax * epsMax * (1 + epsMax * epsMax) + kDecelFloor;
      table.add({fmt("%g", R), fmt("%.2g", epsMax), toString(f), fmt("%.5f", a / (mu * kG)),
                 f == Friction::Stock ? "-" : fmt("%.2e", aBound), fmt("%.3e", tz),
                 f == Friction::Stock ? "-" : fmt("%.2e", tzBound)});
      if (f == Friction::Stock) continue;
      EXPECT_TRUE(isFinite(c));
      EXPECT_NEAR(a / (mu * kG), 1.0, aBound) << toString(f) << " R = " << R;
      EXPECT_LE(std::abs(tz), tzBound) << toString(f) << " R = " << R;
      EXPECT_GT(std::abs(tz), 0.0) << toString(f) << " R = " << R << ": a spinning patch has a spin torque";
    }
  }
  table.emit();
}

}  // namespace
}  // namespace patchspin::bullet::stress
