// One PatchFrictionSolver stepping two worlds (issue 31, finding 8f): each
// world keeps its own patch states (PatchSelection::enterWorld), so each
// moves bit for bit as it does with a solver of its own, whatever the other
// world does in between; reports and stats are those of the last world step.
//
// Independent check: the same two worlds, each stepped with its own solver.
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace patchspin::bullet {
namespace {

using scenes::bt;
using scenes::Scene;

constexpr double kDt = 1.0 / 240.0;
constexpr int kSteps = 240;

struct Bodies {
  btRigidBody* coin;
  btRigidBody* box;
  btRigidBody* top;  // a box on the box
};

// A coin sliding and spinning, a box sliding with another on it; `fast`
// changes the launch so the two worlds differ.
Bodies populate(Scene& scene, double fast) {
  scene.addGroundPlane(1.0);
  Bodies b;
  b.coin = scene.addCylinder(0.05, 0.01, 0.02, bt(0, 0, 0.005), 0.3);
  b.box = scene.addBox(bt(0.05, 0.05, 0.05), 1.0, bt(0, 1, 0.05), 0.5);
  b.top = scene.addBox(bt(0.04, 0.04, 0.02), 0.3, bt(0, 1, 0.12), 0.5);
  scene.solver().enablePatchFriction(b.coin, {Model::Exact});
  scene.solver().enablePatchFriction(b.box, {Model::Ellipsoidal});
  scene.solver().enablePatchFriction(b.top, {Model::Exact});
  b.coin->setLinearVelocity(bt(0.5 * fast, 0, 0));
  b.coin->setAngularVelocity(bt(0, 0, 20 * fast));
  b.box->setLinearVelocity(bt(0.6 * fast, 0, 0));
  b.box->setAngularVelocity(bt(0, 0, 4 * fast));
  return b;
}

void record(std::vector<btScalar>& out, const Bodies& b) {
  for (const btRigidBody* r : {b.coin, b.box, b.top}) {
    const btTransform& tr = r->getWorldTransform();
    for (int i = 0; i < 3; ++i) {
      out.push_back(tr.getOrigin()[i]);
      out.push_back(r->getLinearVelocity()[i]);
      out.push_back(r->getAngularVelocity()[i]);
      for (int k = 0; k < 3; ++k) out.push_back(tr.getBasis()[i][k]);
    }
  }
}

TEST(SharedSolver, TwoWorldsMoveAsWithSolversOfTheirOwn) {
  std::vector<btScalar> ownA, ownB;
  {
    Scene a(9.81, 10), b(9.81, 10);
    const Bodies ba = populate(a, 1.0), bb = populate(b, 1.5);
    for (int k = 0; k < kSteps; ++k) {
      a.step(kDt);
      record(ownA, ba);
      b.step(kDt);
      record(ownB, bb);
    }
  }
  PatchFrictionSolver solver;
  std::vector<btScalar> sharedA, sharedB;
  long patchesA = 0, patchesB = 0;
  {
    Scene a(9.81, 10, solver), b(9.81, 10, solver);
    const Bodies ba = populate(a, 1.0), bb = populate(b, 1.5);
    for (int k = 0; k < kSteps; ++k) {
      a.step(kDt);
      record(sharedA, ba);
      // the reports are world a's
      patchesA += solver.stats().patches;
      EXPECT_EQ(solver.findPatchReport(bb.coin), nullptr);
      if (k < 60) {
        EXPECT_NE(solver.findPatchReport(ba.coin), nullptr) << "step " << k;
      }
      b.step(kDt);
      record(sharedB, bb);
      patchesB += solver.stats().patches;
      EXPECT_EQ(solver.findPatchReport(ba.coin), nullptr);
      if (k < 60) {
        EXPECT_NE(solver.findPatchReport(bb.coin), nullptr) << "step " << k;
      }
    }
  }
  EXPECT_GT(patchesA, 2 * kSteps);
  EXPECT_GT(patchesB, 2 * kSteps);
  ASSERT_EQ(sharedA.size(), ownA.size());
  ASSERT_EQ(sharedB.size(), ownB.size());
  EXPECT_TRUE(sharedA == ownA) << "world a moved otherwise with a shared solver";
  EXPECT_TRUE(sharedB == ownB) << "world b moved otherwise with a shared solver";
}

}  // namespace
}  // namespace patchspin::bullet
