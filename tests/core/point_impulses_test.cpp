// Point impulses part: a patch impulse spread over contact points.
// Independent checks: the sums and moments recomputed from the points, the
// square's closed forms, the least-norm property against random feasible
// perturbations (null space of the constraints), and the nearest hull point
// against random convex combinations of the points.
#include <patchspin/parts/point_impulses.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace patchspin::parts {
namespace {

// Sums and moments: round-off of a few products on coordinates ~0.1 m and
// impulses ~1 N s.
constexpr double kSumTol = 1e-12;

struct Sums {
  double P = 0.0;
  Vec2 moment = Vec2::Zero();  // (sum p y, -sum p x) = (Lambda_Tx, Lambda_Ty)
  Vec2 force = Vec2::Zero();
  double twist = 0.0;
};
Sums sums(const std::vector<Vec2>& r, const PointImpulses& s) {
  Sums out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    out.P += s.normal[std::size_t(i)];
    out.moment += s.normal[std::size_t(i)] * Vec2(r[i].y(), -r[i].x());
    out.force += s.tangent[std::size_t(i)];
    out.twist +=
        r[i].x() * s.tangent[std::size_t(i)].y() - r[i].y() * s.tangent[std::size_t(i)].x();
  }
  return out;
}

std::vector<Vec2> square(double h) {
  return {Vec2(h, h), Vec2(-h, h), Vec2(-h, -h), Vec2(h, -h)};
}

TEST(PointImpulses, SquareUnderCentralLoadAndPureTwistMatchesClosedForm) {
  const double h = 0.05, P = 2.0, M = 0.03, rho = 0.04;
  const auto r = square(h);
  const PointImpulses s =
      spreadPatchImpulse(r.data(), int(r.size()), Vec3(P, 0, 0), Vec3(0, 0, M / rho), rho);
  EXPECT_TRUE(s.momentMatched);
  EXPECT_TRUE(s.twistMatched);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(s.normal[std::size_t(i)], P / 4, kSumTol);
    // each corner carries a quarter of the twist at lever h sqrt(2), across its radius
    const Vec2 expected = M / (4 * 2 * h * h) * Vec2(-r[i].y(), r[i].x());
    EXPECT_NEAR((s.tangent[std::size_t(i)] - expected).norm(), 0.0, kSumTol);
  }
}

// Random points and impulses whose centre of pressure lies in the points'
// hull: every sum exact, p >= 0, and no feasible perturbation spreads the
// load more evenly (smaller sum of squares) or the tangential impulses at a
// smaller sum |t|^2 / p.
TEST(PointImpulses, ReachableWrenchIsMetExactlyWithTheLeastNorm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t n = 3 + std::size_t(trial % 2);
    std::vector<Vec2> r(n);
    for (auto& p : r) p = 0.05 * Vec2(u(rng), u(rng));
    // a centre of pressure as a random convex combination: inside the hull
    Eigen::VectorXd wts(n);
    for (std::size_t i = 0; i < n; ++i) wts[Eigen::Index(i)] = 0.05 + std::abs(u(rng));
    wts /= wts.sum();
    Vec2 c = Vec2::Zero();
    for (std::size_t i = 0; i < n; ++i) c += wts[Eigen::Index(i)] * r[i];
    const double P = 1.0 + std::abs(u(rng)), rho = 0.03;
    const Vec3 lamN(P, P * c.y(), -P * c.x());
    const Vec3 lamF(0.3 * u(rng), 0.3 * u(rng), 0.2 * u(rng));
    const PointImpulses s = spreadPatchImpulse(r.data(), int(r.size()), lamN, lamF, rho);
    ASSERT_TRUE(s.momentMatched);
    const Sums got = sums(r, s);
    EXPECT_NEAR(got.P, P, kSumTol);
    EXPECT_NEAR((got.moment - lamN.tail<2>()).norm(), 0.0, kSumTol);
    for (double p : s.normal) EXPECT_GE(p, 0.0);
    ASSERT_TRUE(s.twistMatched);
    EXPECT_NEAR((got.force - lamF.head<2>()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(got.twist, rho * lamF[2], 1e-9 * 0.05);
    // perturbations in the null space of [1; x; y] keep the sums
    Eigen::MatrixXd A(3, Eigen::Index(n));
    for (std::size_t i = 0; i < n; ++i) A.col(Eigen::Index(i)) << 1.0, r[i].x(), r[i].y();
    const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(A).kernel();
    double norm0 = 0.0;
    for (double p : s.normal) norm0 += p * p;
    for (int k = 0; k < 200 && N.cols() > 0 && N.norm() > 0; ++k) {
      Eigen::VectorXd z(N.cols());
      for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = 0.1 * u(rng);
      const Eigen::VectorXd d = N * z;
      double norm = 0.0;
      bool feasible = true;
      for (std::size_t i = 0; i < n; ++i) {
        const double p = s.normal[std::size_t(i)] + d[Eigen::Index(i)];
        feasible = feasible && p >= 0.0;
        norm += p * p;
      }
      if (feasible) {
        EXPECT_GE(norm, norm0 - 1e-12);
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

// A centre of pressure outside the points' hull: the load still sums
// exactly, and its centre is the hull point nearest the asked one (no random
// convex combination of the points is nearer).
TEST(PointImpulses, UnreachableMomentGoesToTheNearestHullPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const std::size_t n = 1 + std::size_t(trial % 4);
    std::vector<Vec2> r(n);
    for (auto& p : r) p = 0.05 * Vec2(u(rng), u(rng));
    const Vec2 c = 0.2 * Vec2(u(rng), u(rng)).normalized();  // beyond every point
    const double P = 1.5;
    const PointImpulses s = spreadPatchImpulse(r.data(), int(r.size()),
                                               Vec3(P, P * c.y(), -P * c.x()), Vec3::Zero(), 0.03);
    EXPECT_FALSE(s.momentMatched);
    const Sums got = sums(r, s);
    EXPECT_NEAR(got.P, P, kSumTol);
    const Vec2 cop(-got.moment.y() / P, got.moment.x() / P);
    const double dist = (cop - c).norm();
    for (int k = 0; k < 2000; ++k) {
      Eigen::VectorXd wts(n);
      for (std::size_t i = 0; i < n; ++i) wts[Eigen::Index(i)] = std::abs(u(rng));
      wts /= wts.sum();
      Vec2 q = Vec2::Zero();
      for (std::size_t i = 0; i < n; ++i) q += wts[Eigen::Index(i)] * r[i];
      EXPECT_GE((q - c).norm(), dist - 1e-12);
    }
  }
}

// All the load on one point: the force is carried exactly, a twist cannot
// be (said so), and the points without load carry no friction.
TEST(PointImpulses, TwistOnOneLoadedPointKeepsTheForceExact) {
  const auto r = square(0.05);
  const Vec2 corner = r[0];
  const double P = 1.0, rho = 0.03;
  const PointImpulses s = spreadPatchImpulse(
      r.data(), int(r.size()), Vec3(P, P * corner.y(), -P * corner.x()), Vec3(0.2, -0.1, 0.5), rho);
  EXPECT_TRUE(s.momentMatched);
  EXPECT_FALSE(s.twistMatched);
  const Sums got = sums(r, s);
  EXPECT_NEAR((got.force - Vec2(0.2, -0.1)).norm(), 0.0, kSumTol);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_NEAR(s.normal[std::size_t(i)], 0.0, kSumTol);
    EXPECT_NEAR(s.tangent[std::size_t(i)].norm(), 0.0, kSumTol);
  }
}

// One point (a coin on a plane: Bullet keeps one): it carries the whole
// load and the force; the couple and the twist only where they are those
// of the load and force at that point.
TEST(PointImpulses, OnePointCarriesTheLoadAndTheForce) {
  const std::vector<Vec2> r = {Vec2(0.039, -0.002)};
  const double P = 0.49, rho = 0.03;
  const Vec2 f(0.2, -0.1);
  for (const bool atPoint : {true, false}) {
    const Vec2 c = atPoint ? r[0] : Vec2(-0.002, 0.0024);
    const double M = atPoint ? r[0].x() * f.y() - r[0].y() * f.x() : 0.004;
    const PointImpulses s = spreadPatchImpulse(r.data(), 1, Vec3(P, P * c.y(), -P * c.x()),
                                               Vec3(f.x(), f.y(), M / rho), rho);
    EXPECT_EQ(s.momentMatched, atPoint);
    EXPECT_EQ(s.twistMatched, atPoint);
    const Sums got = sums(r, s);
    EXPECT_NEAR(got.P, P, kSumTol);
    EXPECT_NEAR((got.force - f).norm(), 0.0, kSumTol);
    if (atPoint) {
      EXPECT_NEAR((got.moment - P * Vec2(c.y(), -c.x())).norm(), 0.0, kSumTol);
      EXPECT_NEAR(got.twist, M, kSumTol);
    }
  }
}

TEST(PointImpulses, RefusesNoPointsAndTooMany) {
  const std::vector<Vec2> many(kMaxPoints + 1, Vec2::Zero());
  EXPECT_THROW(spreadPatchImpulse(many.data(), 0, Vec3(1, 0, 0), Vec3::Zero(), 0.1), Error);
  EXPECT_THROW(spreadPatchImpulse(many.data(), kMaxPoints + 1, Vec3(1, 0, 0), Vec3::Zero(), 0.1),
               Error);
}

}  // namespace
}  // namespace patchspin::parts
