// A block on an incline stays below and slides above its friction angle
// (issue 6). Moved from scenes_test.cpp; the scene is scenes::addIncline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stress_scenes.hpp"

namespace patchspin::bullet::stress {
namespace {

constexpr double kG = 9.81;
constexpr double kDt = 1.0 / 240.0;

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
constexpr scenes::BlockSpec kBlock{};  // 10 x 10 x 5 cm, 1 kg, mu 0.5
constexpr double kInclineMu = kBlock.mu;
static_assert(kInclineMu == 0.5, "the friction angle of the comments");
constexpr double kInclineStayTol = kDouble ? 1e-6 : 1e-5;
constexpr double kInclineAccelTol = 1e-3;
constexpr double kOneDegree = M_PI / 180.0;

struct InclineResult {
  bool finite = true;
  double displacement = 0.0, velocity = 0.0, time = 0.0, tilt = 0.0;
};

InclineResult incline(double alpha, Friction model, double duration) {
  Scene scene(kG, 10);
  btRigidBody* b = scenes::addIncline(scene, alpha, kG, model, kBlock);
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
              {"model", "alpha [deg]", "displacement [m]", "a measured [m/s^2]",
               "a = g(sin - mu cos)", "tilt rate max"});
  for (Friction m : {Friction::Ellipsoidal, Friction::Exact, Friction::Stock}) {
    const double below = phi - kOneDegree, above = phi + kOneDegree;
    const InclineResult stay = incline(below, m, 2.0);
    const InclineResult slide = incline(above, m, 1.0);
    const double aExpected = kG * (std::sin(above) - kInclineMu * std::cos(above));
    const double aMeasured = slide.velocity / slide.time;
    table.add({toString(m), fmt("%.2f", below * 180 / M_PI), fmt("%.3e", stay.displacement), "-",
               "0", fmt("%.2e", stay.tilt)});
    table.add({toString(m), fmt("%.2f", above * 180 / M_PI), fmt("%.3e", slide.displacement),
               fmt("%.6f", aMeasured), fmt("%.6f", aExpected), fmt("%.2e", slide.tilt)});
    if (m == Friction::Stock) continue;
    EXPECT_TRUE(stay.finite && slide.finite) << toString(m);
    EXPECT_LT(stay.displacement, kInclineStayTol) << toString(m);
    EXPECT_NEAR(aMeasured, aExpected, kInclineAccelTol * aExpected) << toString(m);
  }
  table.emit();
}

}  // namespace
}  // namespace patchspin::bullet::stress
