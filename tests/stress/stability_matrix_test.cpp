// Stability matrix of the Bullet integration (issue 6): one factor at a time
// around a base scene, plus extreme corners, for the ellipsoidal and exact
// patch models (stock Bullet printed beside them as the reference point).
//
// Base scene: horizontal static plane, a coin (diameter = patch size s,
// height 0.1 s) and a block (s x s x 0.5 s) 2 s apart, both sliding along x at
// v0 = 1 m/s and spinning at omega0 about z; constant density (1 kg each at
// s = 0.1 m). The mass-ratio cells use a stack instead: two s x s x 0.5 s
// blocks, the upper one ratio times as heavy, sliding and spinning together;
// the upper block's friction is kStackGrip (Bullet multiplies the pair's
// frictions: kStackGrip mu between the blocks, mu on the ground), so the pair
// moves as one body (it needs mu g, it gets up to kStackGrip mu g) instead of
// the upper block sliding off the faster-braking lower one.
// Base values: dt = 1/240 s, mu = 0.3, omega0 = 20 rad/s (R omega0 = v0 for
// the coin), s = 0.1 m, 10 solver iterations; the float/double dimension is
// the build (the same test runs against both Debian Bullets).
//
// Checks of every cell (patch models; stock rows are only printed):
//   finite      every position, orientation and velocity finite, every step
//   energy      the kinetic energy of the friction DOFs, sum of
//               m |v_xy|^2 / 2 + J_zz omega_z^2 / 2, never rises from one step
//               to the next by more than kEnergyRelTol E0. Horizontal plane,
//               bodies lying flat: gravity and the normal blocks act only on
//               v_z and the tilt rates (principal axes vertical), so only
//               friction changes this energy. (The total kinetic energy also
//               carries the normal blocks' unconverged vertical velocities in
//               stacks, ~1e-4 m/s, on which gravity does work; it is printed
//               as "max dKE/E0 (total)". The split-impulse position correction
//               uses pseudo velocities, which enter neither.)
//   bounded     every body stays within v0 kRestFactor t_bound + s of its start
//               horizontally (speeds only fall, so it cannot travel farther),
//               and between -penetration bound and z0 + s vertically
//   penetration deepest point below its support <= kPenetrationRel s + margin
//   rest        all bodies at rest (|v| and |omega| s/2 below kRestSpeed)
//               no later than kRestFactor t_bound + dt, and not before
//               (v0 - kRestSpeed) / (mu g) - dt (|friction| <= mu m g)
// Fast subset by default; PATCHSPIN_STRESS_FULL=1 runs the whole matrix.
#include "stress_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kV0 = 1.0;
// Mean distance from the centre of a square of side a: a (sqrt 2 + asinh 1) / 6.
const double kSquareMeanR = (std::sqrt(2.0) + std::asinh(1.0)) / 6.0;

// Step-to-step rise of the kinetic energy allowed, relative to E0: round-off
// of the energy sum and of the velocities (stored in btScalar): 1e-12 in
// double; float velocities carry eps = 6e-8, times the ~100 flops of a step,
// hence 1e-5 (the figure of tests/bullet's energy test).
constexpr double kEnergyRelTol = kDouble ? 1e-12 : 1e-5;
// Penetration allowed: 1 % of the patch size (far below what one sees) on
// top of the collision margin, within which Bullet itself lets shapes sink.
constexpr double kPenetrationRel = 0.01;
// At rest: speed of every point of the body below 1e-3 v0.
constexpr double kRestSpeed = 1e-3 * kV0;
// t_bound = v0 / (mu g) + omega0 J / (mu m g mean|r|): the sum of the
// stopping times of pure sliding and pure spinning. For a uniformly loaded
// disk with the ellipsoidal law, d/dt (u + (9/8) rho omega) = -mu g (w1 + w3)
// <= -mu g, so the combined motion stops within t_bound exactly; 1.5 leaves
// room for the exact law, the block (Pi != I) and the time discretisation.
constexpr double kRestFactor = 1.5;
// Time simulated beyond kRestFactor t_bound to see that the rest lasts.
constexpr double kConfirmTime = 0.25;
// Friction of the stack's upper block (see the head comment).
constexpr double kStackGrip = 3.0;
// Bullet's box-box test finds no contact between exactly touching faces: the
// upper block starts overlapping the lower one by this fraction of s (else
// it falls freely for one step, g dt^2 = 1.1 cm at dt = 1/30 s). Far below
// the penetration bound.
constexpr double kStackOverlap = 1e-4;

struct Cell {
  std::string factor = "base";
  double dt = 1.0 / 240.0;
  double mu = 0.3;
  double massRatio = 0.0;  // > 0: the two-block stack with this m_upper / m_lower
  double omega0 = 20.0;
  double size = 0.1;
  int iterations = 10;
  Friction model = Friction::Ellipsoidal;
};

struct Result {
  bool finite = true, energy = true, bounded = true, penetration = true, rest = false;
  double maxPenetration = 0.0, penetrationBound = 0.0;
  double energyRise = 0.0;  // largest step-to-step rise of the friction DOFs' energy / E0
  double totalRise = 0.0;   // the same for the total kinetic energy
  double restTime = -1.0, restLow = 0.0, restBound = 0.0;
  bool ok() const { return finite && energy && bounded && penetration && rest; }
};

struct Tracked {
  btRigidBody* body;
  btRigidBody* support;  // nullptr: the ground z = 0
  btVector3 start;
  double halfSize;  // s / 2: lever for the rest test
};

// Kinetic energy of the friction DOFs (see the head comment) [J].
double frictionEnergy(const std::vector<btRigidBody*>& bodies) {
  double e = 0.0;
  for (const btRigidBody* b : bodies) {
    const btVector3 v = b->getLinearVelocity(), w = b->getAngularVelocity();
    const double jzz = double(b->getInvInertiaTensorWorld().inverse()[2][2]);
    e += 0.5 * (double(v.x()) * double(v.x()) + double(v.y()) * double(v.y())) /
             double(b->getInvMass()) +
         0.5 * jzz * double(w.z()) * double(w.z());
  }
  return e;
}

Result runCell(const Cell& c) {
  Scene scene(kG, c.iterations);
  scene.addGroundPlane(1.0);
  const double s = c.size;
  const double scale = std::pow(s / 0.1, 3);  // constant density
  const double margin = std::min(1e-3, 0.02 * s);
  const double omega0 = c.omega0;
  std::vector<Tracked> items;
  double tBound = 0.0;
  auto launch = [&](btRigidBody* b) {
    b->setLinearVelocity(bt(kV0, 0, 0));
    b->setAngularVelocity(bt(0, 0, omega0));
  };
  const double tSlide = kV0 / (c.mu * kG);
  // square block: J_z = m s^2 / 6, mean|r| = kSquareMeanR s
  const double tSpinBlock = omega0 * (s * s / 6.0) / (c.mu * kG * kSquareMeanR * s);
  if (c.massRatio > 0.0) {
    const btVector3 half = bt(s / 2, s / 2, s / 4);
    btRigidBody* lower = scene.addBox(half, 1.0 * scale, bt(0, 0, s / 4), c.mu, margin);
    btRigidBody* upper = scene.addBox(half, c.massRatio * scale,
                                      bt(0, 0, 3 * s / 4 - kStackOverlap * s), kStackGrip, margin);
    for (btRigidBody* b : {lower, upper}) {
      optIn(scene, b, c.model);
      launch(b);
    }
    // rigid rotation of the pair about the common axis: the same v0
    items.push_back({lower, nullptr, lower->getWorldTransform().getOrigin(), s / 2});
    items.push_back({upper, lower, upper->getWorldTransform().getOrigin(), s / 2});
    tBound = tSlide + tSpinBlock;
  } else {
    btRigidBody* coin =
        scene.addCylinder(s / 2, 0.1 * s, 1.0 * scale, bt(-s, 0, 0.05 * s), c.mu, margin);
    btRigidBody* block =
        scene.addBox(bt(s / 2, s / 2, s / 4), 1.0 * scale, bt(s, 2 * s, s / 4), c.mu, margin);
    for (btRigidBody* b : {coin, block}) {
      optIn(scene, b, c.model);
      launch(b);
      items.push_back({b, nullptr, b->getWorldTransform().getOrigin(), s / 2});
    }
    // coin: uniform disk, J = m R^2 / 2, mean|r| = 2R/3: 3 R omega0 / (4 mu g)
    const double tSpinCoin = 3.0 * (s / 2) * omega0 / (4.0 * c.mu * kG);
    tBound = tSlide + std::max(tSpinCoin, tSpinBlock);
  }

  Result r;
  r.penetrationBound = kPenetrationRel * s + margin;
  r.restBound = kRestFactor * tBound + c.dt;
  r.restLow = (kV0 - kRestSpeed) / (c.mu * kG) - c.dt;
  const double reach = kV0 * r.restBound + s;
  const double tEnd = r.restBound + kConfirmTime;
  std::vector<btRigidBody*> bodies;
  for (const Tracked& it : items) bodies.push_back(it.body);
  double e = frictionEnergy(bodies), ek = scene.kineticEnergy();
  const double e0 = e;
  double lastMoving = 0.0;
  const int steps = int(std::ceil(tEnd / c.dt));
  for (int k = 1; k <= steps; ++k) {
    scene.step(c.dt);
    const double t = k * c.dt;
    bool moving = false;
    for (const Tracked& it : items) {
      if (!isFinite(it.body)) {
        r.finite = false;
        break;
      }
      const btVector3 p = it.body->getWorldTransform().getOrigin();
      const btVector3 d = p - it.start;
      const double top = it.support ? extremeZ(it.support, false) : 0.0;
      const double pen = std::max(0.0, top - extremeZ(it.body, true));
      r.maxPenetration = std::max(r.maxPenetration, pen);
      if (std::hypot(double(d.x()), double(d.y())) > reach || double(d.z()) > s ||
          double(d.z()) < -(r.penetrationBound + s))
        r.bounded = false;
      const double speed = double(it.body->getLinearVelocity().length()) +
                           double(it.body->getAngularVelocity().length()) * it.halfSize;
      if (speed > kRestSpeed) moving = true;
    }
    if (!r.finite) break;
    if (moving) lastMoving = t;
    const double e1 = frictionEnergy(bodies), ek1 = scene.kineticEnergy();
    r.energyRise = std::max(r.energyRise, (e1 - e) / e0);
    r.totalRise = std::max(r.totalRise, (ek1 - ek) / e0);
    e = e1;
    ek = ek1;
  }
  r.energy = r.finite && r.energyRise <= kEnergyRelTol;
  r.penetration = r.finite && r.maxPenetration <= r.penetrationBound;
  r.bounded = r.bounded && r.finite;
  r.restTime = lastMoving;
  r.rest = r.finite && lastMoving <= r.restBound && lastMoving < tEnd - c.dt / 2 &&
           lastMoving >= r.restLow;
  return r;
}

// One factor at a time around the base (each factor its own test and
// table), then the corners. Every cell runs for both patch models and stock.
template <class Set>
Cell with(const char* factor, Set set) {
  Cell c;
  c.factor = factor;
  set(c);
  return c;
}

std::string describe(const Cell& c) {
  return std::string(toString(c.model)) + " " + c.factor + " dt=1/" + fmt("%.0f", 1.0 / c.dt) +
         " mu=" + fmt("%g", c.mu) + " ratio=" + fmt("%g", c.massRatio) +
         " omega0=" + fmt("%g", c.omega0) + " size=" + fmt("%g", c.size) +
         " iters=" + std::to_string(c.iterations);
}

// Runs the cells (x 3 models), prints the table and checks the patch rows.
// `knownDefect`: energy / penetration / rest / bounded failures are collected
// as the known defect instead of failing (finiteness is always asserted);
// the test is then skipped with the list, and passes once they are fixed.
void runGroup(const std::string& title, const std::vector<Cell>& shapes,
              const char* knownDefect = nullptr) {
  Table table(title, {"model", "factor", "dt [s]", "mu", "m2/m1", "omega0", "size [m]", "iters",
                      "finite", "energy", "bounded", "penetr.", "rest", "max pen. [m] (bound)",
                      "max dE/E0", "max dKE/E0 (total)", "t_rest [s] (window)"});
  std::string defects;
  for (const Cell& base : shapes)
    for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
      Cell c = base;
      c.model = m;
      const Result r = runCell(c);
      table.add({toString(c.model), c.factor, "1/" + fmt("%.0f", 1.0 / c.dt), fmt("%g", c.mu),
                 c.massRatio > 0 ? fmt("%g", c.massRatio) : "-", fmt("%g", c.omega0),
                 fmt("%g", c.size), std::to_string(c.iterations), passFail(r.finite),
                 passFail(r.energy), passFail(r.bounded), passFail(r.penetration), passFail(r.rest),
                 fmt("%.2e", r.maxPenetration) + " (" + fmt("%.1e", r.penetrationBound) + ")",
                 fmt("%.1e", r.energyRise), fmt("%.1e", r.totalRise),
                 fmt("%.3f", r.restTime) + " (" + fmt("%.2f", r.restLow) + ".." +
                     fmt("%.2f", r.restBound) + ")"});
      if (c.model == Friction::Stock) continue;  // the reference point: printed, not asserted
      const std::string where = describe(c);
      EXPECT_TRUE(r.finite) << where;
      const bool soft = r.energy && r.penetration && r.rest && r.bounded;
      if (knownDefect && r.finite && !soft) {
        defects += "\n  " + where + ": energy rise " + fmt("%.1e", r.energyRise) +
                   " E0, penetration " + fmt("%.2e", r.maxPenetration) + " m, rest " +
                   fmt("%.3f", r.restTime) + " s" + (r.bounded ? "" : ", left the scene");
        continue;
      }
      EXPECT_TRUE(r.bounded) << where;
      EXPECT_TRUE(r.energy) << where << ": energy rise " << r.energyRise << " E0";
      EXPECT_TRUE(r.penetration) << where << ": penetration " << r.maxPenetration << " m > "
                                 << r.penetrationBound;
      EXPECT_TRUE(r.rest) << where << ": rest at " << r.restTime << " s, window " << r.restLow
                          << ".." << r.restBound;
    }
  table.emit();
  if (!defects.empty()) GTEST_SKIP() << "known defect: " << knownDefect << defects;
}

std::string title(const char* what) {
  return std::string("Stability matrix: ") + what + (stressFull() ? "" : " (fast subset)");
}

TEST(StabilityMatrix, Base) {
  runGroup(title("base scene"), {Cell()});
}

TEST(StabilityMatrix, TimeStep) {
  std::vector<Cell> cells;
  for (double hz :
       stressFull() ? std::vector<double>{30, 60, 120, 500, 1000} : std::vector<double>{30, 1000})
    cells.push_back(with("dt", [&](Cell& c) { c.dt = 1.0 / hz; }));
  runGroup(title("time step"), cells);
}

TEST(StabilityMatrix, FrictionCoefficient) {
  std::vector<Cell> cells;
  for (double mu : stressFull() ? std::vector<double>{0.05, 0.1, 0.6, 1.0, 1.5}
                                : std::vector<double>{0.05, 1.5})
    cells.push_back(with("mu", [&](Cell& c) { c.mu = mu; }));
  runGroup(title("friction coefficient"), cells);
}

// Light on heavy: the stack holds.
TEST(StabilityMatrix, MassRatioLightOnHeavy) {
  std::vector<Cell> cells;
  for (double q : stressFull() ? std::vector<double>{1e-3, 1e-2, 1e-1} : std::vector<double>{1e-3})
    cells.push_back(with("mass ratio", [&](Cell& c) { c.massRatio = q; }));
  runGroup(title("mass ratio, light on heavy"), cells);
}

// Equal masses: until the solver held the support of a stacked patch
// (PatchSolverSettings::supportedStacks), the upper block rocked at the step
// where the pair comes to rest (tilt rate 7.4e-3 rad/s exact, 4.4e-4
// ellipsoidal, double Bullet) and the friction DOFs' energy rose by 5.6e-9 /
// 9.9e-11 E0 in that step: the Gauss-Seidel residual over the two patches
// (3.9e-8 E0 at 10 iterations, 2.0e-10 at 20, round-off at 50). Now a plain
// test, at the double round-off tolerance.
TEST(StabilityMatrix, MassRatioEqual) {
  runGroup(title("mass ratio, equal masses"),
           {with("mass ratio", [](Cell& c) { c.massRatio = 1.0; })});
}

// Heavy on light, 10:1: plain Gauss-Seidel over the two patches converged
// like the mass ratio (normal impulses short, the friction DOFs' energy
// rising by ~1.6e-5 E0 in a step); with the support held the cell passes in
// both precisions (energy rise at round-off).
TEST(StabilityMatrix, MassRatioHeavyOnLight) {
  runGroup(title("mass ratio, heavy on light"),
           {with("mass ratio", [](Cell& c) { c.massRatio = 10.0; })});
}

// 100:1 and 1000:1. Until the support of a stack on the ground was also
// solved with its load held (see linkStackedPatches), these were known
// defects: at 1000:1 the light block stopped on the floor at each of its
// visits while the heavy one kept sliding, the upper patch reported a stick
// with 0.35 m/s of slip left, the floor patch tipped and the heavy block sank
// 5 cm into the light one; at 100:1 the exact law's friction DOFs gained
// 8.7e-6 E0 in one step. Stock Bullet fails these cells (printed).
// The corner with the largest friction uses mu = 0.6, not 1.5: a stack
// whose weight sits at height h = 0.75 s over a base of half-width b = s / 2
// tips over as a whole once mu > b / h = 2/3 (friction's moment about the
// leading edge beats gravity's), which is a fall, not a slide to rest that
// the checks above could judge (mu = 0.9 tips in every model; mu = 1.5 is
// covered by the single-body cells).
TEST(StabilityMatrix, MassRatioHeavyOnLightExtreme) {
  std::vector<Cell> cells;
  for (double q : stressFull() ? std::vector<double>{1e2, 1e3} : std::vector<double>{1e3})
    cells.push_back(with("mass ratio", [&](Cell& c) { c.massRatio = q; }));
  if (stressFull()) {
    cells.push_back(with("corner", [](Cell& c) {
      c.dt = 1.0 / 30;
      c.massRatio = 1e3;
      c.iterations = 4;
    }));
    cells.push_back(with("corner", [](Cell& c) {
      c.dt = 1.0 / 1000;
      c.massRatio = 1e3;
      c.mu = 0.6;
      c.iterations = 50;
    }));
  }
  runGroup(title("mass ratio 100-1000, heavy on light"), cells);
}

TEST(StabilityMatrix, Spin) {
  std::vector<Cell> cells;
  for (double w :
       stressFull() ? std::vector<double>{0.0, 100.0, 1000.0} : std::vector<double>{0.0, 100.0})
    cells.push_back(with("spin", [&](Cell& c) { c.omega0 = w; }));
  runGroup(title("spin"), cells);
}

// Patch size s: the coin's R omega0 = v0 (capped at omega0 = 1000 rad/s).
TEST(StabilityMatrix, PatchSize) {
  std::vector<Cell> cells;
  for (double s :
       stressFull() ? std::vector<double>{1e-3, 1e-2, 1.0, 10.0} : std::vector<double>{1e-3, 10.0})
    cells.push_back(with("size", [&](Cell& c) {
      c.size = s;
      c.omega0 = std::min(1000.0, kV0 / (s / 2));
    }));
  runGroup(title("patch size"), cells);
}

TEST(StabilityMatrix, SolverIterations) {
  std::vector<Cell> cells;
  for (int n : stressFull() ? std::vector<int>{4, 20, 50} : std::vector<int>{4, 50})
    cells.push_back(with("iterations", [&](Cell& c) { c.iterations = n; }));
  runGroup(title("solver iterations"), cells);
}

TEST(StabilityMatrix, Corners) {
  std::vector<Cell> cells;
  cells.push_back(with("corner", [](Cell& c) {
    c.dt = 1.0 / 30;
    c.mu = 1.5;
    c.omega0 = 1000;
  }));
  cells.push_back(with("corner", [](Cell& c) {
    c.dt = 1.0 / 30;
    c.size = 1e-3;
    c.omega0 = 1000;
  }));
  if (stressFull()) {
    cells.push_back(with("corner", [](Cell& c) {
      c.dt = 1.0 / 1000;
      c.mu = 0.05;
      c.size = 10;
      c.omega0 = 0.2;
    }));
    cells.push_back(with("corner", [](Cell& c) {
      c.dt = 1.0 / 30;
      c.massRatio = 1e-3;
      c.iterations = 4;
    }));
    cells.push_back(with("corner", [](Cell& c) {
      c.size = 10;
      c.mu = 0.05;
      c.omega0 = 0.2;
      c.iterations = 4;
    }));
    cells.push_back(with("corner", [](Cell& c) {
      c.dt = 1.0 / 1000;
      c.size = 1e-3;
      c.mu = 1.5;
      c.omega0 = 1000;
    }));
  }
  runGroup(title("corners"), cells);
}

}  // namespace
}  // namespace patchspin::bullet::stress
