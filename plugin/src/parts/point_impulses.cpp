// Point impulses part (point_impulses.hpp).
#include <patchspin/parts/point_impulses.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace patchspin::parts {
namespace {

// Relative residual below which an equality counts as met (round-off of a
// few operations on the points' coordinates).
constexpr double kRelTol = 1e-12;
// ... for the tangential sums, which pass through a 3x3 solve whose
// condition grows as the loaded points close up (1e-9: a twist met to nine
// digits is met; a twist out of reach misses by its own size).
constexpr double kTangentRelTol = 1e-9;

// The point of segment [a, b] nearest to c.
Vec2 nearestOnSegment(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e = b - a;
  const double len2 = e.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((c - a).dot(e) / len2, 0.0, 1.0) : 0.0;
  return a + t * e;
}

// The point of the convex hull of `points` nearest to c, for c outside it:
// it lies on a hull edge, and every pair's segment lies in the hull.
Vec2 nearestHullPoint(const std::vector<Vec2>& points, const Vec2& c) {
  Vec2 best = points[0];
  double bestDist = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i; j < points.size(); ++j) {
      const Vec2 q = nearestOnSegment(points[i], points[j], c);
      const double d = (q - c).squaredNorm();
      if (d < bestDist) bestDist = d, best = q;
    }
  return best;
}

// The least-norm p >= 0 with sum p_i = P and sum p_i r_i = P c, or false if
// there is none. Enumerates the supports: the optimum's restriction to its
// support is that support's least-norm solution, which is then >= 0, so the
// least-norm nonnegative candidate over all supports is the optimum.
bool spreadNormal(const std::vector<Vec2>& points, double P, const Vec2& c, double scale,
                  std::vector<double>& p) {
  const std::size_t n = points.size();
  const Eigen::Vector3d b(P, P * c.x(), P * c.y());
  double bestNorm = std::numeric_limits<double>::infinity();
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<std::size_t> support;
    for (std::size_t i = 0; i < n; ++i)
      if (mask & (1u << i)) support.push_back(i);
    Eigen::MatrixXd A(3, Eigen::Index(support.size()));
    for (std::size_t k = 0; k < support.size(); ++k)
      A.col(Eigen::Index(k)) << 1.0, points[support[k]].x(), points[support[k]].y();
    const Eigen::VectorXd x = A.completeOrthogonalDecomposition().solve(b);
    if ((A * x - b).norm() > kRelTol * scale || x.minCoeff() < -kRelTol * P) continue;
    if (x.squaredNorm() < bestNorm) {
      bestNorm = x.squaredNorm();
      p.assign(n, 0.0);
      for (std::size_t k = 0; k < support.size(); ++k)
        p[support[k]] = std::max(0.0, x[Eigen::Index(k)]);
    }
  }
  return std::isfinite(bestNorm);
}

}  // namespace

PointImpulses spreadPatchImpulse(const std::vector<Vec2>& points, const Vec3& lamN,
                                 const Vec3& lamF, double rho) {
  if (points.empty() || points.size() > kMaxPoints)
    throw Error("spreadPatchImpulse: needs 1 to " + std::to_string(kMaxPoints) + " points, got " +
                std::to_string(points.size()));
  const std::size_t n = points.size();
  double extent = 0.0;  // size of the points' coordinates [m]
  for (const Vec2& r : points) extent = std::max(extent, r.norm());
  PointImpulses out;
  out.normal.assign(n, 0.0);
  out.tangent.assign(n, Vec2::Zero());
  // normal: centre of pressure (Ty / Pz, -Tx / Pz) = (-lamN2 / lamN0, lamN1 / lamN0)  (S5)
  const double P = lamN[0];
  if (P > 0.0) {
    const Vec2 c(-lamN[2] / P, lamN[1] / P);
    const double scale = P * (1.0 + extent + c.norm());
    out.momentMatched = spreadNormal(points, P, c, scale, out.normal);
    if (!out.momentMatched) spreadNormal(points, P, nearestHullPoint(points, c), scale, out.normal);
  } else {
    out.momentMatched = lamN[1] == 0.0 && lamN[2] == 0.0;
  }
  // tangential: t_i = w_i (a + b perp(r_i)), w_i = p_i (1 without a load)
  std::vector<double> w(out.normal);
  if (!(P > 0.0)) w.assign(n, 1.0);
  double W = 0.0, Sx = 0.0, Sy = 0.0, Srr = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    W += w[i];
    Sx += w[i] * points[i].x();
    Sy += w[i] * points[i].y();
    Srr += w[i] * points[i].squaredNorm();
  }
  const Vec2 f(lamF[0], lamF[1]);
  const double M = rho * lamF[2];  // twisting couple about n (S1)
  Eigen::Matrix3d K;
  K << W, 0.0, -Sy, 0.0, W, Sx, -Sy, Sx, Srr;
  const Eigen::Vector3d abc =
      K.completeOrthogonalDecomposition().solve(Eigen::Vector3d(f.x(), f.y(), M));
  auto spread = [&](const Vec2& a, double b) {
    for (std::size_t i = 0; i < n; ++i)
      out.tangent[i] = w[i] * (a + b * Vec2(-points[i].y(), points[i].x()));
  };
  spread(Vec2(abc[0], abc[1]), abc[2]);
  Vec2 sumT = Vec2::Zero();
  double twist = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sumT += out.tangent[i];
    twist += points[i].x() * out.tangent[i].y() - points[i].y() * out.tangent[i].x();
  }
  const double forceScale = f.norm() + std::abs(M) / std::max(extent, 1e-300);
  const double twistScale = std::abs(M) + extent * f.norm();
  out.twistMatched = (sumT - f).norm() <= kTangentRelTol * forceScale &&
                     std::abs(twist - M) <= kTangentRelTol * twistScale;
  if (!out.twistMatched) spread(f / W, 0.0);  // the twist is out of reach: the force exactly
  return out;
}

}  // namespace patchspin::parts
