// Point impulses part (point_impulses.hpp).
#include <patchspin/parts/point_impulses.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace patchspin::parts {
namespace {

// Relative residual below which an equality counts as met (round-off of a
// few operations on the points' coordinates).
constexpr double kRelTol = 1e-12;
// ... for the tangential sums, whose closed form divides by the loaded
// points' spread and loses digits as they close up (1e-9: a twist met to
// nine digits is met; a twist out of reach misses by its own size).
constexpr double kTangentRelTol = 1e-9;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The point of segment [a, b] nearest to c, as a + t (b - a).
double segmentParameter(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e = b - a;
  const double len2 = e.squaredNorm();
  return len2 > 0.0 ? std::clamp((c - a).dot(e) / len2, 0.0, 1.0) : 0.0;
}

// The point of the convex hull of the points nearest to c, for c outside it:
// it lies on a hull edge, and every pair's segment lies in the hull.
Vec2 nearestHullPoint(const Vec2* r, int n, const Vec2& c) {
  Vec2 best = r[0];
  double bestDist = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      const Vec2 q = r[i] + segmentParameter(r[i], r[j], c) * (r[j] - r[i]);
      const double d = (q - c).squaredNorm();
      if (d < bestDist) bestDist = d, best = q;
    }
  return best;
}

// The least-norm p >= 0 with sum p_i = P and sum p_i r_i = P c, or false if
// c is not in the points' hull (to within tol [m]). The optimum restricted
// to its support is that support's least-norm solution, so it is the
// least-norm nonnegative candidate among: all points, every triangle (c's
// barycentric coordinates), every segment through c, every point at c.
// With at most four points these are all the supports. Over all points, in
// coordinates about their centroid m, A A^T = diag(n, S) with S the 2x2
// second moment: p_i = P / n + (r_i - m) . S^-1 P (c - m), exact when S is
// regular (not all points on one line).
bool spreadNormal(const Vec2* r, int n, double P, const Vec2& c, double tol, double* p) {
  double best[kMaxPoints];
  double bestNorm = std::numeric_limits<double>::infinity();
  auto offer = [&](const double* q) {
    double norm = 0.0;
    for (int i = 0; i < n; ++i) norm += q[i] * q[i];
    if (norm < bestNorm) {
      bestNorm = norm;
      std::copy(q, q + n, best);
    }
  };
  if (n >= 3) {
    Vec2 m = Vec2::Zero();
    for (int i = 0; i < n; ++i) m += r[i];
    m /= double(n);
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (int i = 0; i < n; ++i) {
      const Vec2 d = r[i] - m;
      sxx += d.x() * d.x(), sxy += d.x() * d.y(), syy += d.y() * d.y();
    }
    const double det = sxx * syy - sxy * sxy;
    if (det > 1e-8 * (sxx + syy) * (sxx + syy)) {
      const Vec2 e = P * (c - m);
      const Vec2 nu((syy * e.x() - sxy * e.y()) / det, (sxx * e.y() - sxy * e.x()) / det);
      double q[kMaxPoints];
      bool nonnegative = true;
      for (int i = 0; i < n; ++i) {
        q[i] = P / double(n) + (r[i] - m).dot(nu);
        nonnegative = nonnegative && q[i] >= 0.0;
      }
      if (nonnegative) {
        std::copy(q, q + n, p);
        return true;  // the unconstrained optimum is feasible
      }
    }
  }
  double q[kMaxPoints];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const double area = cross(r[j] - r[i], r[k] - r[i]);
        if (!(std::abs(area) > 0.0)) continue;
        const double bi = cross(r[j] - c, r[k] - c) / area, bj = cross(r[k] - c, r[i] - c) / area;
        const double bk = 1.0 - bi - bj;
        if (std::min({bi, bj, bk}) < -kRelTol) continue;
        std::fill(q, q + n, 0.0);
        q[i] = P * std::max(0.0, bi), q[j] = P * std::max(0.0, bj), q[k] = P * std::max(0.0, bk);
        offer(q);
      }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double t = segmentParameter(r[i], r[j], c);
      if ((r[i] + t * (r[j] - r[i]) - c).norm() > tol) continue;
      std::fill(q, q + n, 0.0);
      q[i] = P * (1.0 - t), q[j] = P * t;
      offer(q);
    }
  for (int i = 0; i < n; ++i) {
    if ((r[i] - c).norm() > tol) continue;
    std::fill(q, q + n, 0.0);
    q[i] = P;
    offer(q);
  }
  if (!std::isfinite(bestNorm)) return false;
  std::copy(best, best + n, p);
  return true;
}

}  // namespace

PointImpulses spreadPatchImpulse(const Vec2* points, int n, const Vec3& lamN, const Vec3& lamF,
                                 double rho) {
  if (n < 1 || n > kMaxPoints)
    throw Error("spreadPatchImpulse: needs 1 to " + std::to_string(kMaxPoints) + " points, got " +
                std::to_string(n));
  double extent2 = 0.0;
  for (int i = 0; i < n; ++i) extent2 = std::max(extent2, points[i].squaredNorm());
  const double extent = std::sqrt(extent2);  // size of the points' coordinates [m]
  PointImpulses out;
  out.count = n;
  // normal: centre of pressure (Ty / Pz, -Tx / Pz) = (-lamN2 / lamN0, lamN1 / lamN0)  (S5)
  const double P = lamN[0];
  if (P > 0.0) {
    const Vec2 c(-lamN[2] / P, lamN[1] / P);
    const double tol = kRelTol * (extent + c.norm() + 1e-300);  // [m]
    if (n == 1) {
      // one point carries it all (a coin on a plane: Bullet's manifold
      // keeps one point), the couple only if c is on it; what the search
      // below finds for one point, without it
      out.normal[0] = P;
      out.momentMatched = !((points[0] - c).norm() > tol);
    } else {
      out.momentMatched = spreadNormal(points, n, P, c, tol, out.normal.data());
      if (!out.momentMatched)
        spreadNormal(points, n, P, nearestHullPoint(points, n, c), tol, out.normal.data());
    }
  } else {
    out.momentMatched = lamN[1] == 0.0 && lamN[2] == 0.0;
  }
  // tangential: t_i = w_i (a + b perp(r_i)), w_i = p_i (1 without a load)
  double w[kMaxPoints];
  for (int i = 0; i < n; ++i) w[i] = P > 0.0 ? out.normal[std::size_t(i)] : 1.0;
  double W = 0.0, Sx = 0.0, Sy = 0.0, Srr = 0.0;
  for (int i = 0; i < n; ++i) {
    W += w[i];
    Sx += w[i] * points[i].x();
    Sy += w[i] * points[i].y();
    Srr += w[i] * points[i].squaredNorm();
  }
  const Vec2 f(lamF[0], lamF[1]);
  const double M = rho * lamF[2];  // twisting couple about n (S1)
  auto spread = [&](const Vec2& a, double b) {
    for (int i = 0; i < n; ++i)
      out.tangent[std::size_t(i)] = w[i] * (a + b * Vec2(-points[i].y(), points[i].x()));
  };
  // [W 0 -Sy; 0 W Sx; -Sy Sx Srr] (a, b) = (f, M): with the weighted centre
  // s = (Sx, Sy) / W, b = (M - s x f) / (Srr - W |s|^2), a = f / W - b perp(s)
  const Vec2 s = Vec2(Sx, Sy) / W;
  const double spreadMoment = Srr - W * s.squaredNorm();  // sum w |r - s|^2
  if (spreadMoment > 1e-12 * Srr) {
    const double b = (M - cross(s, f)) / spreadMoment;
    spread(f / W - b * Vec2(-s.y(), s.x()), b);
    Vec2 sumT = Vec2::Zero();
    double twist = 0.0;
    for (int i = 0; i < n; ++i) {
      const Vec2& t = out.tangent[std::size_t(i)];
      sumT += t;
      twist += cross(points[i], t);
    }
    const double forceScale = f.norm() + std::abs(M) / std::max(extent, 1e-300);
    const double twistScale = std::abs(M) + extent * f.norm();
    out.twistMatched = (sumT - f).norm() <= kTangentRelTol * forceScale &&
                       std::abs(twist - M) <= kTangentRelTol * twistScale;
    if (!out.twistMatched) spread(f / W, 0.0);  // out of reach: the force exactly
  } else {
    // the load on one point (or all at its centre): the twist is s x f
    spread(f / W, 0.0);
    out.twistMatched =
        std::abs(M - cross(s, f)) <= kTangentRelTol * (std::abs(M) + extent * f.norm());
  }
  return out;
}

}  // namespace patchspin::parts
