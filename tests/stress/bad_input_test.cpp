// Bad input through the public API of the Bullet integration (issue 6):
// invalid options (a model outside the enum, a flatness tolerance beyond
// pi/8, a rho that can never make a patch), zero solver iterations, static
// and negative-mass bodies, degenerate shapes, a body opted in twice,
// disabling a body never enabled, removing (and deleting) an opted-in body
// between steps and inside a step, a sphere (no flat face) opted in. (How
// an opt-in ends with its body: patch_opt_ins_test.cpp.) Each gets a clear patchspin::Error or a
// fallback (stock Bullet), the world keeps running, and the other bodies are unaffected: their
// trajectories are compared with a run without the bad body.
//
// Witnesses: a coin (exact law) and a block (ellipsoidal) sliding and
// spinning, and a rolling sphere (stock), near the origin; the bad body is
// 10 m away, in another simulation island. Bullet solves islands
// independently and in a fixed order (no SOLVER_RANDMIZE_ORDER), and the
// patch solver keeps its state per manifold, so the witnesses must follow
// bit for bit the same trajectory (kSameTrajectoryTol = 0).
#include "stress_scenes.hpp"

#include <patchspin/scenes/inertia.hpp>

#include <patchspin/types.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;
constexpr int kSteps = 240;
constexpr double kSameTrajectoryTol = 1e-20;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const btVector3 kFar = bt(10, 0, 0);  // where bad bodies go

struct Witnesses {
  btRigidBody* coin;
  btRigidBody* block;
  btRigidBody* sphere;
};

Witnesses addWitnesses(Scene& scene) {
  Witnesses w;
  w.coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005), 0.3);
  w.block = scene.addBox(bt(0.05, 0.05, 0.025), 1.0, bt(0, 1, 0.025), 0.4);
  w.sphere = scene.addSphere(0.05, 1.0, bt(0, -1, 0.05), 0.5);
  scene.solver().enablePatchFriction(w.coin, {Model::Exact});
  scene.solver().enablePatchFriction(w.block, {Model::Ellipsoidal});
  w.coin->setLinearVelocity(bt(1.0, 0.2, 0));
  w.coin->setAngularVelocity(bt(0, 0, 20));
  w.block->setLinearVelocity(bt(-0.8, 0.1, 0));
  w.block->setAngularVelocity(bt(0, 0, -10));
  w.sphere->setLinearVelocity(bt(0.5, 0, 0));
  return w;
}

using Trajectory = std::vector<double>;

void record(Trajectory& t, const btRigidBody* b) {
  const btVector3 p = b->getWorldTransform().getOrigin(), v = b->getLinearVelocity(),
                  w = b->getAngularVelocity();
  for (const btVector3& x : {p, v, w})
    for (int i = 0; i < 3; ++i) t.push_back(double(x[i]));
}

// Hooks of a bad-input run: `setup` adds the bad body (it may keep the
// scene and holder), `before(k)` runs before step k (k = 0 .. kSteps-1).
struct Hooks {
  std::function<void(Scene&)> setup;
  std::function<void(Scene&, int)> before;
};

struct RunResult {
  Trajectory witnesses;
  bool coinHadPatch = true;  // the exact coin had a patch report every step
};

RunResult run(const Hooks& hooks) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  const Witnesses w = addWitnesses(scene);
  if (hooks.setup) hooks.setup(scene);
  RunResult r;
  for (int k = 0; k < kSteps; ++k) {
    if (hooks.before) hooks.before(scene, k);
    scene.step(kDt);
    for (const btRigidBody* b : {w.coin, w.block, w.sphere}) record(r.witnesses, b);
    const PatchReport* rep = scene.solver().findPatchReport(w.coin);
    r.coinHadPatch = r.coinHadPatch && rep && rep->model == Model::Exact;
  }
  return r;
}

const RunResult& clean() {
  static const RunResult r = run(Hooks());
  return r;
}

double largestDifference(const Trajectory& a, const Trajectory& b) {
  if (a.size() != b.size()) return kInf;
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) return kInf;
    d = std::max(d, std::abs(a[i] - b[i]));
  }
  return d;
}

void expectWitnessesUnaffected(const RunResult& r, const std::string& what) {
  const RunResult& ref = clean();
  ASSERT_TRUE(ref.coinHadPatch);
  EXPECT_TRUE(r.coinHadPatch) << what << ": the exact coin lost its patch";
  EXPECT_LE(largestDifference(r.witnesses, ref.witnesses), kSameTrajectoryTol) << what;
}

// A body of its own far away, with a box shape (half extents h).
btRigidBody* addFarBox(Scene& scene, const btVector3& h, double mass, const btVector3& inertia) {
  auto shape = std::make_unique<btBoxShape>(h);
  shape->setMargin(btScalar(1e-3));
  btTransform t;
  t.setIdentity();
  t.setOrigin(kFar + bt(0, 0, double(h.z())));
  return scene.addBody(std::move(shape), mass, inertia, t, 0.5);
}

// A 10 x 10 x 4 cm box of 1 kg far away, with the solid box's inertia.
btRigidBody* addFarTile(Scene& scene) {
  return addFarBox(scene, bt(0.05, 0.05, 0.02), 1.0, scenes::boxInertia(1.0, 0.1, 0.1, 0.04));
}

// ---- options --------------------------------------------------------------------

TEST(BadInput, InvalidOptionsThrowAndLeaveTheBodyAsItWas) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005), 0.3);
  PatchFrictionSolver& solver = scene.solver();
  EXPECT_THROW(solver.enablePatchFriction(nullptr, {Model::Exact}), Error);
  const std::vector<PatchOptions> bad = {PatchOptions(Model::Exact, -0.1),
                                         PatchOptions(Model::Exact, kNaN),
                                         PatchOptions(Model::Exact, kInf),
                                         PatchOptions(Model::Exact, 0.3, kNaN),
                                         PatchOptions(Model::Exact, 0.3, 0.0),
                                         PatchOptions(Model::Exact, 0.3, -0.01),
                                         PatchOptions(Model::Exact, 0.3, kInf),
                                         PatchOptions(Model::Exact, 0.3, std::nullopt, 0.0),
                                         PatchOptions(Model::Exact, 0.3, std::nullopt, -0.1),
                                         PatchOptions(Model::Exact, 0.3, std::nullopt, kNaN)};
  for (const PatchOptions& o : bad) {
    try {
      solver.enablePatchFriction(coin, o);
      ADD_FAILURE() << "accepted mu " << o.mu.value_or(-1) << " rho " << o.rho.value_or(-1)
                    << " tol " << o.flatnessTolerance;
    } catch (const Error& e) {
      std::printf("[bad options] %s\n", e.what());
      EXPECT_FALSE(std::string(e.what()).empty());
    }
    EXPECT_FALSE(solver.isPatchFrictionEnabled(coin)) << "a rejected call must not opt the body in";
  }
  // already opted in: a rejected call keeps the old options
  solver.enablePatchFriction(coin, {Model::Ellipsoidal, 0.25});
  EXPECT_THROW(solver.enablePatchFriction(coin, PatchOptions(Model::Exact, -1.0)), Error);
  EXPECT_THROW(solver.enablePatchFriction(coin, PatchOptions(Model::Exact, 0.3, kNaN)), Error);
  scene.step(kDt);
  const PatchReport* rep = solver.findPatchReport(coin);
  ASSERT_NE(rep, nullptr);
  EXPECT_EQ(rep->model, Model::Ellipsoidal);
  EXPECT_EQ(rep->mu, 0.25);
}

// A Model value outside the enum (a cast, a corrupted file) is refused; it
// used to act as the exact law (issue 31).
TEST(BadInput, ModelOutsideTheEnumIsRefused) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005), 0.3);
  for (const int value : {2, -1, 255}) {
    try {
      scene.solver().enablePatchFriction(coin, {static_cast<Model>(value)});
      ADD_FAILURE() << "accepted model " << value;
    } catch (const Error& e) {
      std::printf("[bad model] %s\n", e.what());
      EXPECT_NE(std::string(e.what()).find("PatchOptions::model"), std::string::npos);
    }
    EXPECT_FALSE(scene.solver().isPatchFrictionEnabled(coin));
  }
  EXPECT_NO_THROW(scene.solver().enablePatchFriction(coin, {Model::Exact}));
  EXPECT_NO_THROW(scene.solver().enablePatchFriction(coin, {Model::Ellipsoidal}));
}

// flatnessTolerance at most pi/8 (kMaxFlatnessTolerance): a patch ends at
// twice it, within the 45 degrees of the selection's facing test. At 1 rad
// (accepted before, issue 31) a box landing on an edge was snapped flat; at
// the largest tolerance allowed, a box balanced on an edge (its two faces
// 45 degrees from the ground) gets no patch.
TEST(BadInput, FlatnessToleranceAbovePiOver8IsRefused) {
  EXPECT_DOUBLE_EQ(kMaxFlatnessTolerance, M_PI / 8);
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  const double h = 0.05;
  btRigidBody* box = scene.addBox(bt(h, h, h), 1.0, bt(0, 0, h * std::sqrt(2.0) - 1e-4), 0.5);
  box->getWorldTransform().setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(M_PI / 4)));
  PatchFrictionSolver& solver = scene.solver();
  for (const double tol : {std::nextafter(kMaxFlatnessTolerance, 1.0), 0.5, 1.0, 3.0}) {
    try {
      solver.enablePatchFriction(box, PatchOptions(Model::Exact, 0.5, std::nullopt, tol));
      ADD_FAILURE() << "accepted flatnessTolerance " << tol;
    } catch (const Error& e) {
      std::printf("[bad flatness] %s\n", e.what());
      EXPECT_NE(std::string(e.what()).find("flatnessTolerance"), std::string::npos);
    }
    EXPECT_FALSE(solver.isPatchFrictionEnabled(box));
  }
  solver.enablePatchFriction(box,
                             PatchOptions(Model::Exact, 0.5, std::nullopt, kMaxFlatnessTolerance));
  scene.step(kDt);
  ASSERT_GT(box->getWorldTransform().getOrigin().z(), 0.06) << "still on its edge";
  EXPECT_EQ(solver.findPatchReport(box), nullptr) << "an edge is not a flat patch";
}

// rho outside [kMinRho, kMaxRho] can never make a patch (the lever max|r| /
// rho outside [1e-5, 1e5] for every patch Bullet can have): refused. rho =
// 5e-324 used to be accepted and silently never made one (issue 31). The
// bounds themselves are accepted.
TEST(BadInput, RhoThatCanNeverMakeAPatchIsRefused) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005), 0.3);
  PatchFrictionSolver& solver = scene.solver();
  for (const double rho : {5e-324, 1e-300, kMinRho / 2, 2 * kMaxRho, 1e300}) {
    try {
      solver.enablePatchFriction(coin, PatchOptions(Model::Exact, 0.3, rho));
      ADD_FAILURE() << "accepted rho " << rho;
    } catch (const Error& e) {
      std::printf("[bad rho] %s\n", e.what());
      EXPECT_NE(std::string(e.what()).find("can never make a patch"), std::string::npos);
    }
    EXPECT_FALSE(solver.isPatchFrictionEnabled(coin));
  }
  for (const double rho : {kMinRho, kMaxRho})
    EXPECT_NO_THROW(solver.enablePatchFriction(coin, PatchOptions(Model::Exact, 0.3, rho)));
  // a rho in range for this coin (lever 1 / 0.5 = 2) makes its patch
  solver.enablePatchFriction(coin, PatchOptions(Model::Exact, 0.3, 0.025));
  scene.step(kDt);
  const PatchReport* rep = solver.findPatchReport(coin);
  ASSERT_NE(rep, nullptr);
  EXPECT_EQ(rep->rho, 0.025);
}

// btContactSolverInfo::m_numIterations = 0: Bullet's solver does nothing,
// and neither does the patch (no position correction holding the body at
// the floor while its velocity free-falls, issue 31): a box resting on the
// ground, opted in, moves bit for bit as under stock Bullet, falling.
TEST(BadInput, ZeroSolverIterationsSolveNothingAsInBullet) {
  auto boxRun = [](scenes::SolverKind kind) {
    Scene scene(kG, 0, kind);
    scene.addGroundPlane(1.0);
    btRigidBody* box = scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 0, 0.05 - 1e-4), 0.5);
    box->setLinearVelocity(bt(0.3, 0, 0));
    if (kind == scenes::SolverKind::Patch) scene.solver().enablePatchFriction(box, {Model::Exact});
    Trajectory t;
    for (int k = 0; k < 60; ++k) {
      scene.step(kDt);
      record(t, box);
    }
    return t;
  };
  const Trajectory patch = boxRun(scenes::SolverKind::Patch);
  const Trajectory stock = boxRun(scenes::SolverKind::Stock);
  EXPECT_LE(largestDifference(patch, stock), kSameTrajectoryTol);
  // z and v_z of the last step (record: p, v, w): falling through the floor
  const double z = patch[patch.size() - 9 + 2], vz = patch[patch.size() - 6 + 2];
  EXPECT_LT(z, 0.0);
  EXPECT_LT(vz, -0.9 * kG * 60 * kDt);
}

// A rejected call in the middle of a run changes nothing for anybody.
TEST(BadInput, RejectedOptionsMidRunLeaveTheWorldUnaffected) {
  Hooks h;
  h.before = [](Scene& scene, int k) {
    if (k != 60) return;
    for (btCollisionObject* o :
         {scene.world().getCollisionObjectArray()[1], scene.world().getCollisionObjectArray()[2]})
      EXPECT_THROW(scene.solver().enablePatchFriction(btRigidBody::upcast(o),
                                                      PatchOptions(Model::Exact, -0.5)),
                   Error);
  };
  expectWitnessesUnaffected(run(h), "rejected options mid-run");
}

// ---- static, zero and negative mass ---------------------------------------------------
// Static bodies opted in: the ground (which every witness stands on) and a
// static box. A static body has no dynamics of its own; opting it in must
// not take the patch away from the dynamic bodies standing on it (they are
// opted in themselves) nor change anything else.
TEST(BadInput, StaticBodiesOptedInChangeNothing) {
  Hooks h;
  h.setup = [](Scene& scene) {
    btRigidBody* ground = btRigidBody::upcast(scene.world().getCollisionObjectArray()[0]);
    ASSERT_NE(ground, nullptr);
    ASSERT_EQ(ground->getInvMass(), btScalar(0));
    scene.solver().enablePatchFriction(ground, {Model::Exact});
    btRigidBody* box = addFarBox(scene, bt(0.1, 0.1, 0.1), 0.0, bt(0, 0, 0));
    scene.solver().enablePatchFriction(box, {Model::Ellipsoidal});
  };
  expectWitnessesUnaffected(run(h), "static bodies opted in");
}

// A static box (a table) opted in, with an opted-in box standing on it: box
// against box, Bullet may make either body the manifold's body0; the
// dynamic box must keep its patch whichever it is, and move exactly as
// with the table not opted in.
TEST(BadInput, StaticTableOptedInKeepsThePatchOfTheBoxOnIt) {
  auto boxRun = [](bool tableOptedIn, bool* allPatched) {
    Scene scene(kG, 10);
    btRigidBody* table = scene.addStaticBox(bt(0.5, 0.5, 0.05), bt(0, 0, -0.05), 1.0);
    if (tableOptedIn) scene.solver().enablePatchFriction(table, {Model::Exact});
    btRigidBody* box = scene.addBox(bt(0.05, 0.05, 0.025), 1.0, bt(0, 0, 0.025 - 1e-5), 0.4);
    scene.solver().enablePatchFriction(box, {Model::Exact});
    box->setLinearVelocity(bt(0.5, 0, 0));
    box->setAngularVelocity(bt(0, 0, 10));
    Trajectory t;
    *allPatched = true;
    for (int k = 0; k < 120; ++k) {
      scene.step(kDt);
      record(t, box);
      const PatchReport* rep = scene.solver().findPatchReport(box);
      *allPatched = *allPatched && rep && rep->other == table;
    }
    return t;
  };
  bool patchedRef = false, patched = false;
  const Trajectory ref = boxRun(false, &patchedRef);
  const Trajectory t = boxRun(true, &patched);
  ASSERT_TRUE(patchedRef);
  const double diff = largestDifference(t, ref);
  std::printf("[static table] box keeps its patch: %d, largest trajectory difference %.3e\n",
              int(patched), diff);
  // (found by this test: convertContacts took the manifold's body0 as the
  // patch body whenever it was opted in, static or not; fixed in def45c1)
  EXPECT_TRUE(patched) << "opting the table in took the patch away from the box on it";
  EXPECT_LE(diff, kSameTrajectoryTol);
}

// Negative mass: Bullet itself accepts it (inverse mass -1). Opting it in
// must give a clear Error, or fall back to stock Bullet (no patch for it);
// either way the world keeps running and the witnesses are unaffected.
TEST(BadInput, NegativeMassBodyIsRejectedOrLeftToBullet) {
  bool threw = false, hadPatch = false;
  Hooks h;
  btRigidBody* bad = nullptr;
  h.setup = [&](Scene& scene) {
    bad = addFarBox(scene, bt(0.05, 0.05, 0.05), -1.0, bt(1e-3, 1e-3, 1e-3));
    try {
      scene.solver().enablePatchFriction(bad, {Model::Exact});
    } catch (const Error& e) {
      threw = true;
      std::printf("[negative mass] Error: %s\n", e.what());
    }
  };
  h.before = [&](Scene& scene, int) {
    hadPatch = hadPatch || scene.solver().findPatchReport(bad) != nullptr;
  };
  const RunResult r = run(h);
  std::printf("[negative mass] %s\n", threw      ? "rejected with Error"
                                      : hadPatch ? "given a patch (!)"
                                                 : "accepted, left to stock Bullet");
  EXPECT_TRUE(threw || !hadPatch) << "a negative-mass body must not get a patch";
  expectWitnessesUnaffected(r, "negative mass");
}

// ---- degenerate shapes --------------------------------------------------------------
// A zero-radius cylinder, a box of zero height (a flat square: a valid face)
// and a box of zero width (a degenerate face). No crash, no NaN in anybody
// else; the flat square is a patch of its face.
TEST(BadInput, DegenerateShapesDoNotDisturbTheWorld) {
  struct Case {
    const char* name;
    std::function<btRigidBody*(Scene&)> make;
  };
  const std::vector<Case> cases = {
      {"zero-radius cylinder",
       [](Scene& scene) {
         auto shape = std::make_unique<btCylinderShapeZ>(bt(0, 0, 0.01));
         shape->setMargin(0);
         btTransform t;
         t.setIdentity();
         t.setOrigin(kFar + bt(0, 0, 0.01));
         return scene.addBody(std::move(shape), 1.0, bt(1e-4, 1e-4, 0), t, 0.5);
       }},
      {"zero-height box",
       [](Scene& scene) {
         return addFarBox(scene, bt(0.05, 0.05, 0), 1.0, bt(8e-4, 8e-4, 1.7e-3));
       }},
      {"zero-width box",
       [](Scene& scene) {
         return addFarBox(scene, bt(0, 0.05, 0.05), 1.0, bt(1.7e-3, 8e-4, 8e-4));
       }},
  };
  for (const Case& c : cases) {
    bool badFinite = true;
    const PatchShape* lastShape = nullptr;
    double area = -1.0;
    btRigidBody* bad = nullptr;
    Hooks h;
    h.setup = [&](Scene& scene) {
      bad = c.make(scene);
      bad->setLinearVelocity(bt(0.3, 0, 0));
      scene.solver().enablePatchFriction(bad, {Model::Exact});
    };
    h.before = [&](Scene& scene, int) {
      badFinite = badFinite && isFinite(bad);
      if (const PatchReport* rep = scene.solver().findPatchReport(bad)) {
        lastShape = &*rep->shape;
        area = rep->shape->area();
      }
    };
    const RunResult r = run(h);
    std::printf("[degenerate] %s: finite %d, patch %s (area %.3e)\n", c.name, int(badFinite),
                lastShape ? "yes" : "no", area);
    expectWitnessesUnaffected(r, c.name);
    if (std::string(c.name) == "zero-height box") {
      EXPECT_TRUE(badFinite);
      EXPECT_NEAR(area, 0.01, 1e-6) << "the flat square is a patch of its 10 x 10 cm face";
    }
  }
}

// ---- bodies the friction law cannot take -----------------------------------------
// A body whose spin about the patch normal is locked (angular factor
// (1, 1, 0): a common way to keep a body upright) has no effective mass in
// the friction block's spin DOF on a static floor, so its K is singular. The
// body must still slide and stop under friction (Bullet's point friction,
// the documented fallback for blocks the patch cannot take), and the world
// must keep running with the witnesses unaffected.
TEST(BadInput, BodyWithLockedSpinSlidesAndStops) {
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    btRigidBody* box = nullptr;
    Hooks hooks;
    hooks.setup = [&](Scene& scene) {
      box = addFarTile(scene);
      box->setAngularFactor(bt(1, 1, 0));
      box->setLinearVelocity(bt(0.5, 0, 0));
      scene.solver().enablePatchFriction(box, {model});
    };
    // the box's state before the last step (run() deletes it at the end)
    btVector3 position, velocity;
    hooks.before = [&](Scene&, int) {
      position = box->getWorldTransform().getOrigin();
      velocity = box->getLinearVelocity();
    };
    RunResult r;
    ASSERT_NO_THROW(r = run(hooks)) << int(model);
    expectWitnessesUnaffected(r, "locked spin");
    // mu g = 4.9 m/s^2 stops 0.5 m/s in 0.1 s, well within the run
    EXPECT_LT(double(velocity.length()), 1e-3) << int(model);
    EXPECT_TRUE(std::isfinite(double(position.x()))) << int(model);
  }
}

// A friction coefficient the law cannot take (mu = 1e308: mu Pz overflows
// double) is accepted by enablePatchFriction (finite, >= 0) but refused by
// the friction law, whether the body is opted in with it or switched to it
// mid-run (the patch's law already built): the patch falls back to Bullet's
// contact and the world keeps running. (Switching mid-run threw out of
// stepSimulation before.)
TEST(BadInput, OverflowingFrictionCoefficientFallsBackToBullet) {
  for (Model model : {Model::Ellipsoidal, Model::Exact})
    for (bool midRun : {false, true}) {
      btRigidBody* box = nullptr;
      Hooks hooks;
      hooks.setup = [&](Scene& scene) {
        box = addFarTile(scene);
        box->setLinearVelocity(bt(0.5, 0, 0));
        scene.solver().enablePatchFriction(box, {model, midRun ? 0.5 : 1e308});
      };
      constexpr int kSwitchStep = 20;
      int patchSteps = 0;            // steps with the huge mu after which the box reported a patch
      btVector3 position, velocity;  // before the last step (run() deletes the box at the end)
      hooks.before = [&](Scene& scene, int k) {
        if (midRun && k == kSwitchStep) scene.solver().enablePatchFriction(box, {model, 1e308});
        if (k > (midRun ? kSwitchStep : 0) && scene.solver().findPatchReport(box)) ++patchSteps;
        position = box->getWorldTransform().getOrigin();
        velocity = box->getLinearVelocity();
      };
      RunResult r;
      ASSERT_NO_THROW(r = run(hooks)) << int(model) << " " << midRun;
      expectWitnessesUnaffected(r, "mu = 1e308");
      EXPECT_EQ(patchSteps, 0) << int(model) << " " << midRun;
      EXPECT_TRUE(std::isfinite(double(position.x()))) << int(model);
      EXPECT_TRUE(std::isfinite(double(velocity.x()))) << int(model);
    }
}

// mu = 1e307 passes when the patch is built (mu Pz finite at rest: 1e308)
// but overflows when an impact raises the normal force beyond ~18 N: then
// the law refuses the pressure inside the solver iterations. That visit keeps
// the friction impulse it had, the manifold goes to Bullet's contact
// (stats().blockErrors counts the refusals), and nothing is thrown.
TEST(BadInput, FrictionLawRefusingInsideTheIterationsFallsBackToBullet) {
  for (Model model : {Model::Ellipsoidal, Model::Exact}) {
    btRigidBody* box = nullptr;
    Hooks hooks;
    hooks.setup = [&](Scene& scene) {
      box = addFarTile(scene);
      scene.solver().enablePatchFriction(box, {model, 1e307});
    };
    constexpr int kDropStep = 60;  // resting on a patch by then
    long blockErrors = 0, patchStepsBeforeDrop = 0;
    btVector3 position;  // before the last step (run() deletes the box at the end)
    hooks.before = [&](Scene& scene, int k) {
      if (k > 0 && k <= kDropStep)
        patchStepsBeforeDrop += scene.solver().findPatchReport(box) != nullptr;
      if (k > 0) blockErrors += scene.solver().stats().blockErrors;
      if (k == kDropStep)
        box->setLinearVelocity(bt(0.3, 0, -2.0));  // an impact: ~480 N in one step
      position = box->getWorldTransform().getOrigin();
    };
    RunResult r;
    ASSERT_NO_THROW(r = run(hooks)) << int(model);
    expectWitnessesUnaffected(r, "mu = 1e307, impact");
    std::printf(
        "[mu = 1e307] %s: patch in %ld of %d steps before the impact, %ld refused friction "
        "visits\n",
        int(model) ? "exact" : "ellipsoidal", patchStepsBeforeDrop, kDropStep, blockErrors);
    EXPECT_GE(patchStepsBeforeDrop, kDropStep - 5) << int(model);  // the law took it at rest
    EXPECT_GT(blockErrors, 0) << int(model);
    EXPECT_TRUE(std::isfinite(double(position.z()))) << int(model);
    EXPECT_GT(double(position.z()), 0.0) << int(model);  // still above the floor
  }
}

// ---- opted in twice, disabled without being enabled -------------------------------------
// The second enablePatchFriction replaces the options: the run equals one
// with only the second call (same island: kSameTrajectoryTol).
TEST(BadInput, OptedInTwiceTheSecondOptionsWin) {
  auto coinRun = [](bool twice) {
    Scene scene(kG, 10);
    scene.addGroundPlane(1.0);
    btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005), 0.3);
    coin->setLinearVelocity(bt(1, 0, 0));
    coin->setAngularVelocity(bt(0, 0, 20));
    if (twice) scene.solver().enablePatchFriction(coin, {Model::Ellipsoidal, 0.9});
    scene.solver().enablePatchFriction(coin, {Model::Exact, 0.4});
    Trajectory t;
    const PatchReport* rep = nullptr;
    for (int k = 0; k < 120; ++k) {
      if (twice && k == 60)
        scene.solver().enablePatchFriction(coin, {Model::Exact, 0.4});  // again, same options
      scene.step(kDt);
      record(t, coin);
      rep = scene.solver().findPatchReport(coin);
      EXPECT_TRUE(rep && rep->model == Model::Exact && rep->mu == 0.4) << "step " << k;
    }
    return t;
  };
  EXPECT_LE(largestDifference(coinRun(true), coinRun(false)), kSameTrajectoryTol);
}

TEST(BadInput, DisablingABodyNeverEnabledIsANoOp) {
  Hooks h;
  btRigidBody* stranger = nullptr;
  h.setup = [&](Scene& scene) {
    stranger = addFarBox(scene, bt(0.05, 0.05, 0.05), 1.0, bt(1.7e-3, 1.7e-3, 1.7e-3));
    EXPECT_NO_THROW(scene.solver().disablePatchFriction(stranger));
    EXPECT_NO_THROW(scene.solver().disablePatchFriction(nullptr));
  };
  h.before = [&](Scene& scene, int k) {
    if (k == 100) {
      EXPECT_NO_THROW(scene.solver().disablePatchFriction(stranger));
      // the sphere witness is stock: disabling it changes nothing either
      scene.solver().disablePatchFriction(
          btRigidBody::upcast(scene.world().getCollisionObjectArray()[3]));
    }
  };
  const RunResult r = run(h);
  EXPECT_FALSE(r.witnesses.empty());
  expectWitnessesUnaffected(r, "disable on a body never enabled");
}

// ---- removing an opted-in body ----------------------------------------------------------
// Between steps: removed from the world at step 60 (and disabled), then
// deleted; the world runs on.
TEST(BadInput, RemovingAndDeletingAnOptedInBodyBetweenSteps) {
  Hooks h;
  std::unique_ptr<btBoxShape> shape;
  std::unique_ptr<btRigidBody> body;
  h.setup = [&](Scene& scene) {
    shape = std::make_unique<btBoxShape>(bt(0.05, 0.05, 0.05));
    btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, shape.get(),
                                                  bt(1.7e-3, 1.7e-3, 1.7e-3));
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(kFar + bt(0, 0, 0.05));
    body = std::make_unique<btRigidBody>(info);
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setLinearVelocity(bt(0.5, 0, 0));
    body->setAngularVelocity(bt(0, 0, 10));
    scene.world().addRigidBody(body.get());
    scene.solver().enablePatchFriction(body.get(), {Model::Exact});
  };
  h.before = [&](Scene& scene, int k) {
    if (k == 30) {
      EXPECT_NE(scene.solver().findPatchReport(body.get()), nullptr) << "the box stands on a patch";
    }
    if (k == 60) {
      scene.world().removeRigidBody(body.get());
      scene.solver().disablePatchFriction(body.get());
      body.reset();
    }
    if (k == 61) {
      EXPECT_EQ(scene.solver().patchReports().size(), 2u) << "coin and block only";
    }
  };
  expectWitnessesUnaffected(run(h), "remove + delete between steps");
}

// Inside a step: removed in Bullet's pre-tick callback (before collision
// detection and the solve of that very step) and another one in the
// post-tick callback (after the solve); not disabled.
struct TickRemoval {
  btRigidBody* pre = nullptr;
  btRigidBody* post = nullptr;
  int tick = 0;
};

void preTick(btDynamicsWorld* world, btScalar) {
  auto* t = static_cast<TickRemoval*>(world->getWorldUserInfo());
  if (t->tick == 60 && t->pre) world->removeRigidBody(t->pre);
}
void postTick(btDynamicsWorld* world, btScalar) {
  auto* t = static_cast<TickRemoval*>(world->getWorldUserInfo());
  if (t->tick == 61 && t->post) world->removeRigidBody(t->post);
  ++t->tick;
}

TEST(BadInput, RemovingOptedInBodiesInsideAStep) {
  TickRemoval removal;
  Hooks h;
  h.setup = [&](Scene& scene) {
    removal.pre = addFarBox(scene, bt(0.05, 0.05, 0.05), 1.0, bt(1.7e-3, 1.7e-3, 1.7e-3));
    removal.post = addFarBox(scene, bt(0.05, 0.05, 0.05), 1.0, bt(1.7e-3, 1.7e-3, 1.7e-3));
    removal.post->getWorldTransform().setOrigin(kFar + bt(1, 0, 0.05));
    for (btRigidBody* b : {removal.pre, removal.post}) {
      b->setLinearVelocity(bt(0.4, 0, 0));
      b->setAngularVelocity(bt(0, 0, 8));
      scene.solver().enablePatchFriction(b, {Model::Ellipsoidal});
    }
    scene.world().setInternalTickCallback(preTick, &removal, true);
    scene.world().setInternalTickCallback(postTick, &removal, false);
  };
  // (the two callbacks share the user pointer; setInternalTickCallback sets
  // it). The bodies are read while their scene lives: run() deletes them.
  bool sawBoth = false, sawAfter = false, preInWorld = true, postInWorld = true;
  h.before = [&](Scene& scene, int k) {
    const PatchFrictionSolver& s = scene.solver();
    if (k == 30) sawBoth = s.findPatchReport(removal.pre) && s.findPatchReport(removal.post);
    if (k == 100) {
      sawAfter = s.findPatchReport(removal.pre) || s.findPatchReport(removal.post);
      preInWorld = removal.pre->isInWorld();
      postInWorld = removal.post->isInWorld();
    }
  };
  const RunResult r = run(h);
  EXPECT_TRUE(sawBoth);
  EXPECT_FALSE(sawAfter) << "removed bodies have no patch";
  EXPECT_FALSE(preInWorld);
  EXPECT_FALSE(postInWorld);
  expectWitnessesUnaffected(r, "removed inside a step");
}

// ---- non-finite state, zero mass, absurd sizes, bad steps ---------------------------
// An opted-in body far away whose state turns non-finite mid-run (a NaN or
// infinite velocity, spin or position, as a user's bug would set it), whose
// mass is set to zero, or whose size is absurd: the witnesses run bit for
// bit as without it and the exact coin keeps its patch. (The bad body
// itself is Bullet's: a non-finite one leaves the simulation with Bullet's
// "Overflow in AABB" warning.)
TEST(BadInput, NonFiniteZeroMassOrAbsurdBodiesStayAlone) {
  struct Case {
    const char* name;
    std::function<void(btRigidBody&)> spoil;  // before step 30
    double half = 0.05;                       // the cube's half size [m]
    double mass = 1.0;                        // [kg]
  };
  const std::vector<Case> cases = {
      {"NaN velocity", [](btRigidBody& b) { b.setLinearVelocity(bt(kNaN, 0, 0)); }},
      {"infinite spin", [](btRigidBody& b) { b.setAngularVelocity(bt(0, 0, kInf)); }},
      {"NaN position", [](btRigidBody& b) { b.getWorldTransform().setOrigin(bt(kNaN, 0, 0.05)); }},
      {"infinite position",
       [](btRigidBody& b) { b.getWorldTransform().setOrigin(bt(0, kInf, 0.05)); }},
      {"zero mass", [](btRigidBody& b) { b.setMassProps(0, bt(0, 0, 0)); }},
      {"1 um, 1 ng cube", [](btRigidBody&) {}, 5e-7, 1e-12},
      {"1 km, 1e12 kg cube", [](btRigidBody&) {}, 500.0, 1e12},
  };
  for (const Case& c : cases) {
    btRigidBody* bad = nullptr;
    Hooks h;
    h.setup = [&](Scene& scene) {
      const double a = 2 * c.half;
      // (the kilometre cube stands far enough not to reach the witnesses)
      bad =
          addFarBox(scene, bt(c.half, c.half, c.half), c.mass, scenes::boxInertia(c.mass, a, a, a));
      bad->getWorldTransform().setOrigin(bt(c.half > 1 ? 1e4 : 10, 0, c.half));
      bad->setLinearVelocity(bt(0.3, 0, 0));
      bad->setAngularVelocity(bt(0, 0, 5));
      scene.solver().enablePatchFriction(bad, {Model::Exact});
    };
    h.before = [&](Scene&, int k) {
      if (k == 30) c.spoil(*bad);
    };
    expectWitnessesUnaffected(run(h), c.name);
  }
}

// A step of zero or negative length (Bullet steps a negative one
// backwards): no exception, every body stays finite, and the exact coin has
// its patch again once it is back on the plane. (Measured: ten steps of
// -dt integrate gravity backwards, 0.41 m/s up, and sink the coin 4 mm;
// back on positive steps it leaves the plane, flies 7 mm high and lands
// at step 63.)
TEST(BadInput, ZeroAndNegativeStepsKeepTheWorldFinite) {
  Scene scene(kG, 10);
  scene.addGroundPlane(1.0);
  const Witnesses w = addWitnesses(scene);
  for (int k = 0; k < 120; ++k) {
    const double dt = k >= 30 && k < 40 ? 0.0 : k >= 40 && k < 50 ? -kDt : kDt;
    EXPECT_NO_THROW(scene.step(dt)) << "step " << k;
    for (const btRigidBody* b : {w.coin, w.block, w.sphere})
      ASSERT_TRUE(isFinite(b)) << "step " << k;
    if (k >= 70) {
      EXPECT_NE(scene.solver().findPatchReport(w.coin), nullptr) << "step " << k;
    }
  }
}

// ---- no flat face ---------------------------------------------------------------------
// A sphere opted in has no flat face: stock Bullet handles it exactly as if
// it had never been opted in (kSameTrajectoryTol), and it gets no patch.
TEST(BadInput, SphereOptedInFallsBackToStockBullet) {
  auto sphereRun = [](bool optIn) {
    Scene scene(kG, 10);
    scene.addGroundPlane(1.0);
    btRigidBody* coin = scene.addCylinder(0.05, 0.01, 1.0, bt(0, 1, 0.005), 0.3);
    scene.solver().enablePatchFriction(
        coin, {Model::Exact});  // the solver is not in its no-opt-in shortcut
    btRigidBody* s = scene.addSphere(0.05, 1.0, bt(0, 0, 0.05), 0.5);
    s->setLinearVelocity(bt(0.5, 0, 0));
    s->setAngularVelocity(bt(0, 3, 5));
    if (optIn) scene.solver().enablePatchFriction(s, {Model::Exact});
    Trajectory t;
    for (int k = 0; k < kSteps; ++k) {
      scene.step(kDt);
      record(t, s);
      EXPECT_EQ(scene.solver().findPatchReport(s), nullptr);
    }
    return t;
  };
  EXPECT_LE(largestDifference(sphereRun(true), sphereRun(false)), kSameTrajectoryTol);
}

}  // namespace
}  // namespace patchspin::bullet::stress
