// The nearest admissible loads (DESIGN item 2): the Euclidean projection of
// the scaled loads y = (Pz, Tx / rho, Ty / rho) onto the loads of linear
// pressures p >= 0 on the patch, a closed convex cone K.
//  * Polygons: K = {n_i . y >= 0}, n_i . y the pressure at vertex i. A face
//    (one vertex at zero pressure) or an edge ray (a side at zero pressure)
//    holds the projection; it is the one whose KKT conditions hold (unique),
//    and only faces with n_i . y < 0 and edges with a negative end qualify
//    (|y - p|^2 = -sum lambda_i n_i . y). O(n) flops, no allocation.
//  * Disks: K = {|w - a c| <= kappa a}, w = (Ty, -Tx) / rho, a = Pz,
//    c = C / rho, kappa = R / (4 rho) (the kern |cop - C| <= R / 4): an
//    oblique circular cone, the projection p = (I + mu H)^-1 y on the
//    quadric y^T H y = 0, mu the root of a monotone secular equation.
//  * Arc regions: admissible_loads_arc_region.cpp.
// Tests: tests/core/admissible_loads_test.cpp (brute force, KKT,
// idempotence) and pressure_test.cpp; fuzz/pressure_fuzz.cpp.
#include <patchspin/pressure.hpp>

#include "admissible_loads_internal.hpp"
#include "pressure_numerics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace patchspin {

namespace {

// The result's own admissibility check: of the mean pressure; normal
// cases: ~1e-12
constexpr double kVerifyTol = 1e-6;

// the scaled loads with Pz = 1 whose centre of pressure (Ty, -Tx) / Pz is k
Vec3 rayThrough(const Vec2& k, double rho) {
  return Vec3(1.0, -k.y() / rho, k.x() / rho);
}

// ---- disks ------------------------------------------------------------------

// Projection of z onto the cone {sum beta_i z_i^2 <= 0, z_0 >= 0} in its
// principal axes (beta_0 < 0 < beta_1, beta_2), for z outside it with
// z_0 >= 0: p_i = z_i / (1 + mu beta_i), mu in (0, 1 / |beta_0|] the root of
// sum beta_i p_i^2 = 0. With sigma = mu |beta_0| in (0, 1], d_i = 1 +
// sigma g_i (g_i = beta_i / |beta_0|) and r = sqrt(beta_1 p_1^2 + beta_2
// p_2^2), the root of Phi(sigma) = sqrt|beta_0| z_0 / r(sigma) - (1 - sigma),
// which increases from Phi(0) < 0 (z outside) to Phi(1) >= 0: unique. Phi is
// linear where g_1 = g_2 (a cone about its axis: 1 / r = d / |(z_1, z_2)|),
// so Newton's method from sigma = 0 takes a step or two; it runs inside a
// shrinking bracket (bisection where a step leaves it). In sigma, not
// 1 - sigma: the d_i keep every digit where g_i is large (a narrow cone,
// rho >> R). p_0 from the quadric itself, so the result lies on the cone to
// round-off also where sigma -> 1 (z_0 -> 0).
Vec3 projectOntoQuadricCone(const Vec3& beta, const Vec3& z) {
  const double s0 = std::sqrt(-beta[0]);
  const double g1 = beta[1] / -beta[0], g2 = beta[2] / -beta[0];
  const double target = s0 * z[0];
  double r = 0.0, p1 = 0.0, p2 = 0.0, slope = 0.0;
  auto evaluate = [&](double sigma) {  // Phi(sigma) and its slope
    const double d1 = 1.0 + sigma * g1, d2 = 1.0 + sigma * g2;
    p1 = z[1] / d1;
    p2 = z[2] / d2;
    r = std::sqrt(beta[1] * p1 * p1 + beta[2] * p2 * p2);
    const double rate = beta[1] * p1 * p1 * g1 / d1 + beta[2] * p2 * p2 * g2 / d2;  // -r dr/dsigma
    slope = 1.0 + (target / r) * (rate / (r * r));
    return target / r - (1.0 - sigma);
  };
  double lo = 0.0, hi = 1.0, sigma = 0.0;
  for (int it = 0; it < 100; ++it) {
    const double phi = evaluate(sigma);
    if (phi == 0.0) break;
    (phi < 0.0 ? lo : hi) = sigma;
    double next = sigma - phi / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - sigma) <= 4.0 * std::numeric_limits<double>::epsilon() * next) {
      sigma = next;
      break;
    }
    sigma = next;
  }
  evaluate(sigma);
  return Vec3(r / s0, p1, p2);
}

// Disk of centre C, radius R: see the file comment. y0 > 0.
Vec3 projectDisk(const Vec2& C, double R, double rho, const Vec3& y) {
  const Vec2 c = C / rho;
  const double kappa = R / (4.0 * rho);
  const double s = c.norm();
  const Vec2 e = s > 0.0 ? Vec2(c / s) : Vec2(1.0, 0.0);
  const Vec2 w(y[2], -y[1]);
  const double a = y[0], wc = e.dot(w), wp = e.x() * w.y() - e.y() * w.x();
  // the polar cone {a + c.w + kappa |w| <= 0} projects to the apex
  if (a + s * wc + kappa * internal::planarNorm(wc, wp) <= 0.0) return Vec3::Zero();
  // H = [[s^2 - kappa^2, -s, 0], [-s, 1, 0], [0, 0, 1]] in (a, wc, wp):
  // eigenvalues al0 = -kappa^2 / al1 < 0 < al1 and 1; the axis v0 of the cone
  // (each root from the sum without cancellation, the other from the
  // product -kappa^2: half < 0 where kappa > 1, rho below R / 4)
  const double half = 0.5 * (s * s - kappa * kappa + 1.0);
  const double root = internal::planarNorm(half, kappa);
  const double al1 = half >= 0.0 ? half + root : -(kappa / (half - root)) * kappa;
  const double al0 = half >= 0.0 ? -(kappa / al1) * kappa : half - root;
  const double vn = internal::planarNorm(1.0 - al0, s);
  const Vec2 v0((1.0 - al0) / vn, s / vn), v1(-v0.y(), v0.x());
  const Vec3 yh(v0.x() * a + v0.y() * wc, v1.x() * a + v1.y() * wc, wp);
  Vec3 ph;
  if (yh[0] > 0.0) {
    ph = projectOntoQuadricCone(Vec3(al0, al1, 1.0), yh);
  } else {
    // Moreau: y minus its projection onto the polar cone, which is
    // {y^T H^-1 y <= 0, v0 . y <= 0}
    const Vec3 q =
        projectOntoQuadricCone(Vec3(1.0 / al0, 1.0 / al1, 1.0), Vec3(-yh[0], yh[1], yh[2]));
    ph = yh - Vec3(-q[0], q[1], q[2]);
  }
  const double pa = v0.x() * ph[0] + v1.x() * ph[1];
  const double pc = v0.y() * ph[0] + v1.y() * ph[1];
  const Vec2 pw = pc * e + ph[2] * Vec2(-e.y(), e.x());
  return Vec3(pa, -pw.y(), pw.x());
}

}  // namespace

// ---- polygons -----------------------------------------------------------------

namespace internal {
namespace {

// n_k: the vertex pressure p(v_k) = n_k . y as a row in scaled coordinates,
// n_k = M^-T (1, x_k, y_k), M the map of pressure coefficients to scaled
// loads. Computed as the former search did (bit for bit, so that the
// projections agree to the last bit): with O outside the polygon,
// P^-T G^-1 (1, x_k, y_k) by PatchShape's solve about the vertex mean (M^-1
// = G^-1 P^-1, whose cofactor inverse about a far O loses ~(max|r| /
// size)^4 eps; P^-1 is exact up to rho's rounding), else M^-T itself.
class VertexRows {
 public:
  VertexRows(const PatchShape& shape, const std::vector<Vec2>& vertices, const Mat3& M, double rho)
      : shape_(shape),
        vertices_(vertices),
        aboutMean_(shape.maxDistanceFromOrigin() > shape.diameter()) {
    PinvT_ << 1.0, 0.0, 0.0,  //
        0.0, 0.0, -rho,       //
        0.0, rho, 0.0;
    if (!aboutMean_) Minv_ = M.inverse();
  }
  Vec3 operator()(std::size_t k) const {
    const Vec2& v = vertices_[k % vertices_.size()];
    const Vec3 phi(1.0, v.x(), v.y());
    return aboutMean_ ? Vec3(PinvT_ * shape_.solveLoadMatrix(phi)) : Vec3(Minv_.transpose() * phi);
  }

 private:
  const PatchShape& shape_;
  const std::vector<Vec2>& vertices_;
  bool aboutMean_;
  Mat3 PinvT_;
  Mat3 Minv_ = Mat3::Zero();
};

// Projection onto the face n . p = 0 if its KKT conditions hold: n . y < 0
// and the pressure of p >= 0 at both neighbouring vertices (a pressure zero
// at a vertex and >= 0 at its neighbours is >= 0 on the convex polygon).
bool faceProjection(const Vec3& n, const Vec3& prev, const Vec3& next, const Vec3& y, Vec3& out) {
  const double ny = n.dot(y);
  if (!(ny < 0.0)) return false;
  const Vec3 p = y - ny / n.squaredNorm() * n;
  const double tol = kKktSlack * p.norm();
  if (prev.dot(p) < -tol * prev.norm() || next.dot(p) < -tol * next.norm()) return false;
  out = p;
  return true;
}

}  // namespace

// Projection onto the edge ray of faces i, j (the side v_i v_j at zero
// pressure) if its KKT conditions hold: y - p = -(li ni + lj nj), li, lj >= 0
// and p = t u, t >= 0. d = ni x nj points into K: d = rho^2 det(G^-1) M
// (phi_i x phi_j), the loads of the pressure cross(v_j - v_i, x - v_i) >= 0.
bool edgeProjection(const Vec3& ni, const Vec3& nj, const Vec3& y, Vec3& out) {
  const Vec3 d = ni.cross(nj);
  const double dn = d.norm();
  const double gii = ni.squaredNorm(), gjj = nj.squaredNorm(), gij = ni.dot(nj);
  if (dn <= 1e-14 * std::sqrt(gii) * std::sqrt(gjj)) return false;
  const Vec3 u = d / dn;
  const double uy = u.dot(y);
  if (!(uy > 0.0)) return false;
  // the multipliers from the Gram system, det = |ni x nj|^2
  const double si = ni.dot(y), sj = nj.dot(y), det = dn * dn;
  const double li = (gij * sj - gjj * si) / det, lj = (gij * si - gii * sj) / det;
  const double tol = kKktSlack * y.norm();
  if (li * std::sqrt(gii) < -tol || lj * std::sqrt(gjj) < -tol) return false;
  out = uy * u;
  return true;
}

KktResult projectPolygonByKkt(const PatchShape& shape, const std::vector<Vec2>& vertices,
                              const Mat3& M, const Vec3& y, double rho, std::size_t worst,
                              Vec3& out) {
  const std::size_t n = vertices.size();
  const VertexRows row(shape, vertices, M, rho);
  // a walk from the most negative vertex: where face i's projection leaves
  // a neighbour's pressure negative, the answer lies on that side's edge ray
  // or beyond it. O(1) per step, a few steps (the faces with negative
  // pressure are contiguous: a linear function is negative on a half-plane)
  {
    std::size_t i = worst + 2 * n;  // (i - 1 stays unsigned for n steps)
    Vec3 prev = row(i - 1), cur = row(i), next = row(i + 1);
    int from = 0;  // +1: came from the next face, -1: from the previous one
    for (std::size_t step = 0; step < n; ++step) {
      const double ny = cur.dot(y);
      if (!(ny < 0.0)) break;
      const Vec3 p = y - ny / cur.squaredNorm() * cur;
      const double tol = kKktSlack * p.norm();
      const double vPrev = prev.dot(p) / prev.norm(), vNext = next.dot(p) / next.norm();
      if (vPrev >= -tol && vNext >= -tol) {
        out = p;
        return KktResult::kFound;
      }
      const int dir = vNext < vPrev ? 1 : -1;
      if (dir == from) break;  // back where it came from: the scan decides
      if (dir > 0 ? edgeProjection(cur, next, y, out) : edgeProjection(prev, cur, y, out))
        return KktResult::kFound;
      if (dir > 0) {
        ++i, prev = cur, cur = next, next = row(i + 1);
      } else {
        --i, next = cur, cur = prev, prev = row(i - 1);
      }
      from = -dir;
    }
  }
  // then every face with a negative vertex and every side with a negative end
  Vec3 prev = row(n - 1), cur = row(0);
  double sCur = cur.dot(y);
  bool negative = false;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 next = row(k + 1);
    const double sNext = next.dot(y);
    negative = negative || sCur < 0.0;
    if (sCur < 0.0 && faceProjection(cur, prev, next, y, out)) return KktResult::kFound;
    if ((sCur < 0.0 || sNext < 0.0) && edgeProjection(cur, next, y, out)) return KktResult::kFound;
    prev = cur, cur = next, sCur = sNext;
  }
  return negative ? KktResult::kNone : KktResult::kInside;
}

Vec3 projectPolygonBySearch(const PatchShape& shape, const std::vector<Vec2>& vertices,
                            const Mat3& M, const Vec3& y, double rho) {
  const VertexRows vertexRow(shape, vertices, M, rho);
  struct Row {
    Vec3 a;
    double norm;
  };
  std::vector<Row> rows;
  rows.reserve(vertices.size());
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Vec3 a = vertexRow(k);
    rows.push_back({a, a.norm()});
  }
  // feasibility with a small relative slack for round-off
  auto feasible = [&](const Vec3& l) {
    const double scale = l.norm();
    for (const Row& r : rows)
      if (r.a.dot(l) < -1e-12 * r.norm * scale) return false;
    return true;
  };
  Vec3 best = Vec3::Zero();
  double bestDist = y.norm();
  auto consider = [&](const Vec3& l) {
    const double dist = (l - y).norm();
    if (dist < bestDist && feasible(l)) {
      bestDist = dist;
      best = l;
    }
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Vec3& ai = rows[i].a;
    // only faces that y violates can hold the projection (KKT multiplier
    // -a_i.y / |a_i|^2 >= 0)
    const double aiy = ai.dot(y);
    if (aiy < 0.0) consider(y - aiy / ai.squaredNorm() * ai);
    // the edge ray u of faces i and i+1 (only rays with u.y > 0 are nearer
    // than the apex)
    const Row& next = rows[(i + 1) % rows.size()];
    const Vec3 d = ai.cross(next.a);
    const double dn = d.norm();
    if (dn <= 1e-14 * rows[i].norm * next.norm) continue;
    const Vec3 u = d / dn;
    const double uy = u.dot(y);
    if (uy > 0.0) consider(uy * u);
  }
  // the uniform pressure's ray is admissible by construction: the answer is
  // at least as near as its nearest point (found by fuzzing: on a sliver
  // triangle 1e8 m long, round-off in the test above rejected every face
  // and edge candidate and the answer fell back to the zero load, farther
  // than the uniform pressure)
  const Vec3 uniform = M.col(0);
  const Vec3 onRay = std::max(0.0, uniform.dot(y) / uniform.squaredNorm()) * uniform;
  if ((onRay - y).norm() < bestDist) best = onRay;
  return best;
}

Mat3 scaledLoadMatrix(const PatchShape& shape, double rho) {
  Mat3 P;
  P << 1.0, 0.0, 0.0,        //
      0.0, 0.0, -1.0 / rho,  //
      0.0, 1.0 / rho, 0.0;
  return P * shape.areaMoments().loadMatrix();
}

}  // namespace internal

namespace {

using internal::KktResult;
using internal::loadsOfScaled;
using internal::projectPolygonByKkt;
using internal::projectPolygonBySearch;
using internal::scaledLoadMatrix;

// The smallest vertex pressure of the pressure carrying `loads` on a polygon
// and its vertex, in isAdmissible's own arithmetic (fromLoads, then
// minPressure's values); NaN where a value may not be finite (then
// isAdmissible itself, with its scaled evaluation and its errors, decides).
// A linear function along a convex polygon's vertex cycle has one minimum
// (a line meets the boundary twice), so beyond 16 vertices every (n / 8)-th
// vertex is evaluated and the lowest one's neighbours are followed
// downhill: ~n / 8 + n / 8 values instead of n (a cut disk has 64). Only
// where two vertices agree to round-off may that stop one ulp above
// minPressure's value (AdmissibleLoads.KernTestAgreesWithIsAdmissible).
double lowestVertexPressure(const PatchShape& shape, const PatchLoads& loads, std::size_t& worst) {
  const Vec3 c = shape.solveLoadMatrix(Vec3(loads.Pz, loads.Ty, -loads.Tx));
  // every vertex value is finite if this bound is
  const double bound =
      std::abs(c[0]) + (std::abs(c[1]) + std::abs(c[2])) * shape.maxDistanceFromOrigin();
  worst = 0;
  if (!(bound <= std::numeric_limits<double>::max()))
    return std::numeric_limits<double>::quiet_NaN();
  const LinearPressure p{c[0], c[1], c[2]};
  const std::vector<Vec2>& v = shape.vertices();
  const std::size_t n = v.size(), stride = n > 16 ? n / 8 : 1;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; k += stride) {
    const double at = p.at(v[k]);
    if (at < lowest) lowest = at, worst = k;
  }
  if (stride == 1) return lowest;
  for (const std::size_t step : {std::size_t(1), n - 1}) {  // forward, then back
    for (;;) {
      const std::size_t k = (worst + step) % n;
      const double at = p.at(v[k]);
      if (!(at < lowest)) break;
      lowest = at, worst = k;
    }
  }
  return lowest;
}

// isAdmissible(shape, loads, relTol) for a polygon and Pz > 0, the same
// decision, cheaper
bool polygonAdmissible(const PatchShape& shape, const PatchLoads& loads, double relTol) {
  std::size_t worst = 0;
  const double lowest = lowestVertexPressure(shape, loads, worst);
  if (std::isnan(lowest)) return isAdmissible(shape, loads, relTol);
  return lowest >= -relTol * loads.Pz / shape.area();
}

PatchLoads polygonImpl(const PatchShape& shape, const PatchLoads& loads, double rho) {
  // the kern test: admissible loads come back unchanged, exactly where
  // isAdmissible(shape, loads, 0) says so
  std::size_t worst = 0;
  const double lowest = lowestVertexPressure(shape, loads, worst);
  if (std::isnan(lowest)) {
    // out of range somewhere: isAdmissible's scaled evaluation (and its
    // errors), then the former search
    if (isAdmissible(shape, loads, 0.0)) return loads;
    const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
    return loadsOfScaled(
        projectPolygonBySearch(shape, shape.vertices(), scaledLoadMatrix(shape, rho), y, rho), rho);
  }
  if (lowest >= -0.0) return loads;  // isAdmissible(shape, loads, 0)
  const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
  const Mat3 M = scaledLoadMatrix(shape, rho);
  Vec3 out;
  const KktResult found = projectPolygonByKkt(shape, shape.vertices(), M, y, rho, worst, out);
  // (the former search returned an edge ray or the uniform pressure's ray
  // here, however far: AdmissibleLoads.MatchesSearchAndKkt, idempotence)
  // (only within the result's own check: on a sliver 1e10 m long the rows
  // said inside where the vertex pressure was -2e14 times the mean; found
  // by fuzzing)
  if (found == KktResult::kInside && lowest >= -kVerifyTol * loads.Pz / shape.area()) return loads;
  if (found != KktResult::kFound) out = projectPolygonBySearch(shape, shape.vertices(), M, y, rho);
  return loadsOfScaled(out, rho);
}

// `known`: the result is known admissible with tolerance 0 (arc regions)
PatchLoads nearestAdmissibleLoadsImpl(const PatchShape& shape, const PatchLoads& loads, double rho,
                                      bool& known) {
  known = false;
  if (!(loads.Pz > 0.0)) return PatchLoads{};  // documented: no normal force, no load
  if (shape.kind() == PatchShape::Kind::ArcRegion)
    return internal::nearestAdmissibleArcRegion(shape, loads, rho, known);
  if (!shape.isDisk()) return polygonImpl(shape, loads, rho);
  if (isAdmissible(shape, loads, 0.0)) return loads;
  const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
  const Vec2 C = shape.centre();
  const double R = shape.radius();
  const Mat3 G = shape.areaMoments().loadMatrix();
  // disk centred at O (every disk patch of the Bullet layer): M = diag(A, .)
  // with the in-plane block a rotation times I / rho, so the admissible set
  // is the circular cone |(y1, y2)| <= kappa y0, kappa = I / (A R rho), and
  // the Euclidean projection has a closed form: with s = |(y1, y2)|,
  //   s <= kappa y0        -> y (admissible, handled above)
  //   kappa s <= -y0       -> 0 (y in the polar cone)
  //   otherwise            -> (y0 + kappa s) / (1 + kappa^2) (1, kappa e),  e = (y1, y2) / s
  const double cTol = 1e-12 * G.norm();
  if (C.norm() <= 1e-12 * R && std::abs(G(0, 1)) <= cTol && std::abs(G(0, 2)) <= cTol &&
      std::abs(G(1, 2)) <= cTol && std::abs(G(1, 1) - G(2, 2)) <= cTol) {
    const double kappa = G(1, 1) / (G(0, 0) * R * rho);
    const double sPerp = std::hypot(y[1], y[2]);
    if (kappa * sPerp <= -y[0]) return PatchLoads{};
    const double t = (y[0] + kappa * sPerp) / (1.0 + kappa * kappa);
    return loadsOfScaled(Vec3(t, t * kappa * y[1] / sPerp, t * kappa * y[2] / sPerp), rho);
  }
  // the uniform pressure's ray (admissible by construction) and the zero
  // load as backstops, as for polygons
  Vec3 best = projectDisk(C, R, rho, y);
  const Vec3 uniform = rayThrough(C, rho);  // the uniform pressure's centre of pressure is C
  const Vec3 onRay = std::max(0.0, uniform.dot(y) / uniform.squaredNorm()) * uniform;
  if ((onRay - y).norm() < (best - y).norm()) best = onRay;
  if (y.norm() < (best - y).norm()) best = Vec3::Zero();
  return loadsOfScaled(best, rho);
}

}  // namespace

PatchLoads nearestAdmissibleLoads(const PatchShape& shape, const PatchLoads& loads, double rho) {
  internal::requireFiniteLoads(loads);
  internal::requirePositive(rho, "length scale rho");
  // as for FrictionPatch: within 1e12 of Eq. (11) either way; beyond, the
  // metric's torque terms under- or overflow (found by fuzzing: rho = 1e308)
  const double natural = shape.defaultRho();
  if (rho < natural * 1e-12 || rho > natural * 1e12) {
    throw Error("length scale rho = " + internal::formatDouble(rho) +
                " m is out of range for this patch: Eq. (11) gives " +
                internal::formatDouble(natural) + " m; allowed 1e-12 to 1e12 times that");
  }
  bool known = false;
  const PatchLoads out = nearestAdmissibleLoadsImpl(shape, loads, rho, known);
  // found by fuzzing: a denormal rho made the scaled torques overflow (NaN)
  if (!out.asVector().allFinite()) {
    throw Error("nearest admissible loads out of range: torques / rho overflow double (rho = " +
                internal::formatDouble(rho) + " m)");
  }
  // found by fuzzing: torques ~1e300 times Pz rho swamp the projection's
  // round-off test and it returned inadmissible loads; say so instead (also
  // for a result with Pz < 0: torques 1e154 times Pz rho gave Pz = -4.9e138,
  // round-off of the 1e154-sized scaled torque)
  // (for polygons with Pz > 0 isAdmissible's decision, cheaper; none where
  // the projection took isAdmissible's decision with tolerance 0 itself)
  auto admissible = [&] {
    if (known) return true;
    return shape.kind() != PatchShape::Kind::Polygon || !(out.Pz > 0.0)
               ? isAdmissible(shape, out, kVerifyTol)
               : polygonAdmissible(shape, out, kVerifyTol);
  };
  if (!out.asVector().isZero(0.0) && !(out.asVector() == loads.asVector()) && !admissible()) {
    throw Error(
        "nearest admissible loads out of range: no admissible projection to double "
        "precision for (Pz, Tx, Ty) = (" +
        internal::formatDouble(loads.Pz) + ", " + internal::formatDouble(loads.Tx) + ", " +
        internal::formatDouble(loads.Ty) + ")");
  }
  return out;
}

}  // namespace patchspin
