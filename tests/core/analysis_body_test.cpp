// The flat-body model of Sect. 5 checked against independent computations:
// the 3-D Newton-Euler equations with brute-force pressure integrals, the
// brute-force friction integral (16), finite differences of the Jacobian.
#include <gtest/gtest.h>

#include <cmath>
#include <oracle.hpp>
#include <patchspin/analysis.hpp>
#include <random>

namespace patchspin {
namespace {

// Brute-force quadrature runs at relTol 1e-11; the model's own solves are
// exact to round-off, so agreement is limited by the quadrature.
constexpr double kQuadTol = 1e-9;

FlatBody skewBody() {
  FlatBody body;
  body.shape = PatchShape::polygon(
      {Vec2(-0.06, -0.04), Vec2(0.07, -0.05), Vec2(0.08, 0.03), Vec2(-0.02, 0.06)});
  body.mass = 1.7;
  body.Jz = 0.006;
  body.Jxz = -0.0007;
  body.Jyz = 0.0004;
  body.com = Vec3(0.008, -0.005, 0.03);
  body.mu = 0.35;
  body.g = 9.81;
  body.force = Vec2(1.2, -0.7);
  body.torque = Vec3(0.03, -0.02, 0.015);
  return body;
}

// 3-D Newton-Euler about C with physical moments, independent of (85)-(97):
//   sum of moments about C = J omega' + omega x (J omega),
//   J = [[., ., Jxz], [., ., Jyz], [Jxz, Jyz, Jz]], omega = (0, 0, w_z),
// with omega' from the z row. The pressure's moment about C is
// ∫ (r - r_c) x (0, 0, p) dA, by brute-force quadrature of p, x p, y p.
TEST(FlatBodyModel, PressureSatisfiesNewtonEuler) {
  for (Model law : {Model::Ellipsoidal, Model::Exact}) {
    const FlatBody body = skewBody();
    const FlatBodyModel model(body, law);
    const BodyLoads loads = model.bodyLoads();
    const Vec3 w = Vec3(0.4, -0.3, 0.6).normalized();
    const double omega = 7.0;
    const ContactState c = model.contact(w, omega, loads);
    LinearPressure p;
    p.p0 = c.pressure[0];
    p.cx = c.pressure[1];
    p.cy = c.pressure[2];
    const auto field = testing::linearField(p);
    const double Pz = testing::bruteForceIntegral(body.shape, field, 1e-12);
    const double Sx = testing::bruteForceIntegral(
        body.shape, [&](const Vec2& q) { return q.x() * field(q); }, 1e-12);
    const double Sy = testing::bruteForceIntegral(
        body.shape, [&](const Vec2& q) { return q.y() * field(q); }, 1e-12);
    const double scale = body.mass * body.g;
    EXPECT_NEAR(Pz, -loads.force.z(), kQuadTol * scale);
    // friction force at O and torque about O
    const Vec3 P(c.Q.x(), c.Q.y(), 0.0);
    const Vec3 Tf(0.0, 0.0, c.Q.z() * model.rho());
    const Vec3& rc = body.com;
    // moments about C: pressure, friction, couple (the external force acts at C)
    const Vec3 Mp(Sy - rc.y() * Pz, -(Sx - rc.x() * Pz), 0.0);
    const Vec3 M = Mp + Tf - rc.cross(P) + loads.couple;
    const double omegaDot = M.z() / body.Jz;
    const Vec3 Jw(body.Jxz * omega, body.Jyz * omega, body.Jz * omega);
    const Vec3 Jwdot(body.Jxz * omegaDot, body.Jyz * omegaDot, body.Jz * omegaDot);
    const Vec3 Ldot = Jwdot + Vec3(0.0, 0.0, omega).cross(Jw);
    EXPECT_NEAR(M.x(), Ldot.x(), kQuadTol * scale * 0.1) << toString(law);
    EXPECT_NEAR(M.y(), Ldot.y(), kQuadTol * scale * 0.1) << toString(law);
    // the friction is the law (16) / (41) for this pressure
    if (law == Model::Exact) {
      const Vec3 Qbf = testing::bruteForceQ(body.shape, field, body.mu, model.rho(), w, 1e-11);
      EXPECT_LT((Qbf - c.Q).norm(), kQuadTol * scale);
    }
  }
}

// dQ/dw (with the pressure's dependence on w) against central differences on
// the sphere's tangent plane (step 1e-6: truncation 1e-12, round-off 1e-10).
TEST(FlatBodyModel, JacobianMatchesFiniteDifferences) {
  for (Model law : {Model::Ellipsoidal, Model::Exact}) {
    const FlatBodyModel model(skewBody(), law);
    const Vec3 w = Vec3(-0.2, 0.5, 0.4).normalized();
    Mat3 D;
    model.limitField(w, &D);
    const Vec3 t1 = w.cross(Vec3::UnitZ()).normalized(), t2 = w.cross(t1);
    for (const Vec3& t : {t1, t2}) {
      const double h = 1e-6;
      const Vec3 fd = (model.limitField((w + h * t).normalized()) -
                       model.limitField((w - h * t).normalized())) /
                      (2 * h);
      EXPECT_LT((fd - D * t).norm(), 1e-7 * D.norm()) << toString(law);
    }
  }
}

// Limit directions of thick, skewed bodies under both laws (sphere solver):
// each is a zero of V* to 1e-10 (checked with an independently computed
// exact wrench for the exact law), and the index sum is 2.
TEST(FlatBodyModel, RandomNonlinearBodies) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    FlatBody body = skewBody();
    body.com = Vec3(0.01 * u(rng), 0.01 * u(rng), 0.02 + 0.01 * u(rng));
    body.Jxz = 0.0005 * u(rng);
    body.Jyz = 0.0005 * u(rng);
    body.force = Vec2(2.0 * u(rng), 2.0 * u(rng));
    body.torque = Vec3(0.02 * u(rng), 0.02 * u(rng), 0.03 * u(rng));
    const Model law = trial % 2 ? Model::Exact : Model::Ellipsoidal;
    const FlatBodyModel model(body, law);
    LimitOptions options;
    options.seeds = 200;
    const LimitAnalysis a = findLimitDirections(model, options);
    EXPECT_FALSE(a.linear);
    EXPECT_TRUE(a.indexConsistent) << trial;
    EXPECT_GE(a.directions.size(), 2u);
    const double scale = body.mu * body.g;
    for (const LimitDirection& d : a.directions) {
      EXPECT_LT(d.residual, 1e-10 * scale) << trial;
      if (law == Model::Exact && trial < 2 * 2) {
        const ContactState c = model.contact(d.w, 0.0, model.bodyLoads());
        LinearPressure p;
        p.p0 = c.pressure[0];
        p.cx = c.pressure[1];
        p.cy = c.pressure[2];
        const Vec3 Q = testing::bruteForceQ(body.shape, testing::linearField(p), body.mu,
                                            model.rho(), d.w, 1e-11);
        const Vec3 Fo =
            model.massMatrix().inverse() * (Q + model.externalWrench(model.bodyLoads()));
        EXPECT_LT((Fo - Fo.dot(d.w) * d.w).norm(), kQuadTol * scale) << trial;
      }
    }
  }
}

// Sticking test at the edge of the friction set. The exact law's set is the
// convex hull of its limit surface {Q(w)}: an external wrench -Q(w0) s can
// be held iff s <= 1 (checked at s = 1 -+ 1e-6, i.e. far below the grid's
// resolution, so the Newton refinement is what decides). Ellipsoidal: the
// image of the unit ball, same test with its Q(w0) = -mu Pz Pi w0.
TEST(FlatBodyModel, CanStickIsSharpAtTheFrictionLimit) {
  for (Model law : {Model::Exact, Model::Ellipsoidal}) {
    FlatBody body = skewBody();
    body.com.z() = 0.0;  // thin: the pressure does not depend on the friction
    body.Jxz = body.Jyz = 0.0;
    body.torque = Vec3(0.03, -0.02, 0.0);
    body.force = Vec2::Zero();
    const FlatBodyModel probe(body, law);
    for (const Vec3& w0 : {Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8).normalized(), Vec3(0, 0, -1)}) {
      const Vec3 Q0 = probe.contact(w0, 0.0, probe.bodyLoads()).Q;
      for (double s : {1.0 - 1e-6, 1.0 + 1e-6}) {
        // Q_e = (Fx, Fy, T_ez / rho), T_ez = couple_z + x_c Fy - y_c Fx (79)
        FlatBody b = body;
        b.force = -s * Q0.head<2>();
        b.torque.z() =
            -s * Q0.z() * probe.rho() - (body.com.x() * b.force.y() - body.com.y() * b.force.x());
        EXPECT_EQ(FlatBodyModel(b, law).canStick(FlatBodyModel(b, law).bodyLoads()), s < 1.0)
            << toString(law) << " w0 = " << w0.transpose() << " s = " << s;
      }
    }
  }
}

// Bad input: a clear Error, never NaN.
TEST(FlatBodyModel, RejectsBadInput) {
  FlatBody body = skewBody();
  body.mass = -1.0;
  EXPECT_THROW(FlatBodyModel(body, Model::Exact), Error);
  body = skewBody();
  body.mu = std::nan("");
  EXPECT_THROW(FlatBodyModel(body, Model::Exact), Error);
  body = skewBody();
  body.g = 0.0;
  EXPECT_THROW(FlatBodyModel(body, Model::Exact), Error);
  SimulationSpec spec;
  spec.model = "stock";
  EXPECT_THROW(simulateReference(spec), Error);
}

}  // namespace
}  // namespace patchspin
