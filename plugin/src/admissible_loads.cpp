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
//  * Arc regions: K is {p >= 0 on every boundary point}, on an arc a
//    constraint between linear (its ends) and conic. Admissible loads come
//    back unchanged (the exact test, minPressure's). Others: the nearest
//    feasible KKT candidate (projectArcRegionExact: a piece end's face, a
//    segment's edge ray, an arc point whose face projection touches there);
//    if none is feasible, the projection onto the cone K_Q of a
//    circumscribed polygon Q, coarse to fine (tangents 2 pi / 64 apart, then
//    2 pi / 1024 and 2 pi / 16384 within two coarser steps of the previous
//    answer's touch angle: within 1.8e-8 R of the arc there), admissible as
//    Q contains the region. Last, a uniform pressure of round-off size lifts
//    a minimum that rounds below 0 (idempotence).
// Tests: tests/core/admissible_loads_test.cpp (brute force, KKT,
// idempotence) and pressure_test.cpp; fuzz/pressure_fuzz.cpp.
#include <patchspin/pressure.hpp>

#include "pressure_numerics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace patchspin {

namespace {

// relative slack of the KKT tests for round-off (the old candidate search
// accepted feasibility to the same 1e-12)
constexpr double kKktSlack = 1e-12;
// The result's own admissibility check: of the mean pressure; normal
// cases: ~1e-12
constexpr double kVerifyTol = 1e-6;

// the scaled loads with Pz = 1 whose centre of pressure (Ty, -Tx) / Pz is k
Vec3 rayThrough(const Vec2& k, double rho) {
  return Vec3(1.0, -k.y() / rho, k.x() / rho);
}

// the loads of scaled loads l
PatchLoads loadsOfScaled(const Vec3& l, double rho) {
  return PatchLoads{l[0], l[1] * rho, l[2] * rho};
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

// ---- polygons -----------------------------------------------------------------

// The former candidate search (every face and adjacent-edge candidate, each
// tested against every constraint): the fallback where the KKT search finds
// nothing to round-off or a vertex pressure is not finite.
Vec3 projectPolygonBySearch(const PatchShape& shape, const std::vector<Vec2>& vertices,
                            const Mat3& M, const Vec3& y, double rho);

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

enum class KktResult { kFound, kInside, kNone };

// kInside: no vertex pressure is negative in the rows' arithmetic (y on
// K's boundary to round-off, where the kern test rounded the other way);
// kNone: no candidate passes to round-off (the fallback search decides).
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

// M maps pressure coefficients to scaled loads: (Pz, Ty, -Tx) = G pi, then
// (Pz, Tx / rho, Ty / rho)
Mat3 scaledLoadMatrix(const PatchShape& shape, double rho) {
  Mat3 P;
  P << 1.0, 0.0, 0.0,        //
      0.0, 0.0, -1.0 / rho,  //
      0.0, 1.0 / rho, 0.0;
  return P * shape.areaMoments().loadMatrix();
}

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

// ---- arc regions ----------------------------------------------------------------

// Tangent steps of the circumscribed polygon, coarse to fine (file
// comment): every arc at kArcTangentSteps[0]; at level l > 0 also
// kArcTangentSteps[l] within kArcWindowSteps steps of level l - 1 of the
// touch angle of level l - 1's projection (where its zero line touches the
// arc: the outward normal -grad p).
constexpr double kTwoPiArc = 2.0 * 3.14159265358979323846;
constexpr double kArcTangentSteps[3] = {kTwoPiArc / 64.0, kTwoPiArc / 1024.0, kTwoPiArc / 16384.0};
constexpr double kArcWindowSteps = 2.0;

struct TangentWindow {
  double centre, halfWidth, step;
};

// The circumscribed polygon Q of an arc region: per piece its start point,
// then per arc the intersections of its tangents at the sorted tangent
// angles (its ends, the coarse grid, the windows' fine grids): the tangents
// at unit directions u, v meet at R (u + v) / (1 + u.v). Each grid's
// directions by a rotation recurrence (one sine and cosine per grid, not
// per vertex; ~1e-14 off the circle after a few hundred steps, what the
// final lift in arcRegionImpl absorbs). Q contains the region (its edges
// are supporting lines). `near` gets the index of the vertex nearest to
// the last window's centre (or npos).
struct TangentPoint {
  double angle;
  Vec2 dir;
};
void addGrid(double lo, double hi, int k, std::vector<TangentPoint>& out) {
  const double step = (hi - lo) / k;
  const Vec2 rot(std::cos(step), std::sin(step));
  Vec2 d(std::cos(lo), std::sin(lo));
  for (int i = 0; i <= k; ++i) {
    out.push_back({lo + step * i, d});
    d = Vec2(d.x() * rot.x() - d.y() * rot.y(), d.x() * rot.y() + d.y() * rot.x());
  }
}
void circumscribedPolygon(const std::vector<BoundaryPiece>& boundary,
                          const std::vector<TangentWindow>& windows, std::vector<Vec2>& q,
                          std::vector<TangentPoint>& points, std::size_t& near) {
  q.clear();
  near = static_cast<std::size_t>(-1);
  double nearGap = std::numeric_limits<double>::infinity();
  for (const BoundaryPiece& p : boundary) {
    q.push_back(p.start());
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    const double t0 = p.angle0, t1 = p.angle1, span = t1 - t0;
    points.clear();
    auto byAngle = [](const TangentPoint& a, const TangentPoint& b) { return a.angle < b.angle; };
    addGrid(t0, t1, std::max(1, static_cast<int>(std::ceil(span / kArcTangentSteps[0]))), points);
    double lastCentre = std::numeric_limits<double>::quiet_NaN();
    for (const TangentWindow& w : windows) {
      // the window's centre in [t0, t0 + 2 pi), and one turn lower
      double c = std::fmod(w.centre - t0, kTwoPiArc);
      if (c < 0.0) c += kTwoPiArc;
      for (const double centre : {t0 + c, t0 + c - kTwoPiArc}) {
        const double lo = std::max(t0, centre - w.halfWidth);
        const double hi = std::min(t1, centre + w.halfWidth);
        if (!(hi > lo)) continue;
        // (each grid is sorted: merged in, not sorted again)
        const std::size_t middle = points.size();
        addGrid(lo, hi, static_cast<int>(std::ceil((hi - lo) / w.step)), points);
        std::inplace_merge(points.begin(), points.begin() + middle, points.end(), byAngle);
        lastCentre = centre;
      }
    }
    // angles closer than a quarter of the finest step merged (the
    // grids overlap; near-equal tangents would make near-equal rows), the
    // arc's ends kept exactly
    constexpr double kMerge = 0.25 * kArcTangentSteps[2];
    std::size_t kept = 1;
    for (std::size_t i = 1; i < points.size(); ++i)
      if (points[i].angle - points[kept - 1].angle > kMerge) points[kept++] = points[i];
    points.resize(kept);
    const TangentPoint end{t1, Vec2(std::cos(t1), std::sin(t1))};
    if (points.size() > 1 && t1 - points.back().angle <= kMerge) {
      points.back() = end;
    } else if (points.back().angle != t1) {
      points.push_back(end);
    }
    points.front().dir = Vec2(std::cos(t0), std::sin(t0));
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Vec2& u = points[i - 1].dir;
      const Vec2& v = points[i].dir;
      q.push_back(p.centre + p.radius / (1.0 + u.dot(v)) * Vec2(u + v));
      const double gap = std::abs(0.5 * (points[i - 1].angle + points[i].angle) - lastCentre);
      if (gap < nearGap) nearGap = gap, near = q.size() - 1;
    }
  }
}

// The exact projection onto K for an arc region, by its KKT conditions. A
// linear pressure >= 0 on a convex region bounded by segments and strictly
// convex arcs vanishes (if anywhere) at one piece end, along one segment, or
// at one arc point where its outward normal is -grad p; so the projection
// is the nearest feasible one of: each piece end's face projection, each
// segment's edge ray (multipliers >= 0), and per arc the face projection of
// the point P(t) whose projection's own touch angle is t (a root of
// r(t) = cross((cos t, sin t), -grad p_z(t)), bracketed on kArcSamples
// points and solved by the Illinois method). Feasible: minPressure >= -kExactFeasible of the mean
// pressure. False where no candidate is feasible (the polygon scheme
// decides then).
constexpr int kArcSamples = 16;
constexpr double kExactFeasible = 1e-10;
bool projectArcRegionExact(const PatchShape& shape, const Mat3& M, const Vec3& y, double rho,
                           Vec3& out) {
  const bool aboutMean = shape.maxDistanceFromOrigin() > shape.diameter();
  Mat3 PinvT;
  PinvT << 1.0, 0.0, 0.0, 0.0, 0.0, -rho, 0.0, rho, 0.0;
  const Mat3 MinvT = aboutMean ? Mat3::Zero() : Mat3(M.inverse().transpose());
  // n(P): the pressure at P of scaled loads z is n(P) . z
  auto row = [&](const Vec2& P) -> Vec3 {
    const Vec3 phi(1.0, P.x(), P.y());
    return aboutMean ? Vec3(PinvT * shape.solveLoadMatrix(phi)) : Vec3(MinvT * phi);
  };
  auto pressureOf = [&](const Vec3& z) {
    return LinearPressure::fromLoads(shape, loadsOfScaled(z, rho));
  };
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& z) {
    const double d = (z - y).norm();
    if (!(d < best) || !(z[0] > 0.0)) return;
    const double mean = z[0] / shape.area();
    if (!(minPressure(shape, pressureOf(z)) >= -kExactFeasible * mean)) return;
    best = d, out = z;
  };
  auto face = [&](const Vec3& n, Vec3& z) {
    const double ny = n.dot(y);
    if (!(ny < 0.0)) return false;
    z = y - ny / n.squaredNorm() * n;
    return true;
  };
  const std::vector<BoundaryPiece>& b = shape.boundary();
  for (const BoundaryPiece& piece : b) {
    const Vec3 nStart = row(piece.start());
    Vec3 z;
    if (face(nStart, z)) consider(z);
    if (piece.kind == BoundaryPiece::Kind::Segment) {
      if (edgeProjection(nStart, row(piece.b), y, z)) consider(z);
      continue;
    }
    // r(t) and the face projection at P(t)
    auto residual = [&](double t, Vec3& zt) {
      const Vec2 u(std::cos(t), std::sin(t));
      if (!face(row(piece.centre + piece.radius * u), zt))
        return std::numeric_limits<double>::quiet_NaN();
      const LinearPressure pz = pressureOf(zt);
      return u.x() * -pz.cy - u.y() * -pz.cx;
    };
    const double t0 = piece.angle0, span = piece.angle1 - piece.angle0;
    double prevT = t0, prevR = residual(t0, z);
    for (int i = 1; i <= kArcSamples; ++i) {
      const double t = t0 + span * i / kArcSamples;
      const double r = residual(t, z);
      if (std::isfinite(prevR) && std::isfinite(r) && (prevR < 0.0) != (r < 0.0)) {
        // the Illinois method on the bracket [prevT, t], to round-off
        double a = prevT, fa = prevR, bb = t, fb = r, c = a, last = a;
        int side = 0;
        bool ok = false;
        for (int it = 0; it < 100; ++it) {
          c = (fa * bb - fb * a) / (fa - fb);
          if (!(c > std::min(a, bb) && c < std::max(a, bb))) c = 0.5 * (a + bb);
          const double fc = residual(c, z);
          if (!std::isfinite(fc)) break;
          ok = true;
          if (fc == 0.0 ||
              std::abs(c - last) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(c))
            break;
          last = c;
          if ((fc < 0.0) == (fb < 0.0)) {
            bb = c, fb = fc;
            if (side == -1) fa *= 0.5;
            side = -1;
          } else {
            a = c, fa = fc;
            if (side == 1) fb *= 0.5;
            side = 1;
          }
        }
        if (ok) consider(z);  // (z: the projection at the last c)
      }
      prevT = t, prevR = r;
    }
  }
  return std::isfinite(best);
}

PatchLoads arcRegionImpl(const PatchShape& shape, const PatchLoads& loads, double rho) {
  if (isAdmissible(shape, loads, 0.0)) return loads;
  const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
  const Mat3 M = scaledLoadMatrix(shape, rho);
  const LinearPressure p = LinearPressure::fromLoads(shape, loads);
  std::vector<TangentWindow> windows;
  std::vector<Vec2> q;
  std::vector<TangentPoint> points;
  q.reserve(256), points.reserve(256);
  Vec3 out = Vec3::Zero();
  const bool exact = projectArcRegionExact(shape, M, y, rho, out);
  for (int level = 0; level < 3 && !exact; ++level) {
    std::size_t near = 0;
    circumscribedPolygon(shape.boundary(), windows, q, points, near);
    // the walk's start: the vertex nearest to the last touch angle where y
    // violates it, else the most negative vertex of Q
    std::size_t worst = 0;
    if (near < q.size() && p.at(q[near]) < 0.0) {
      worst = near;
    } else {
      double lowest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < q.size(); ++k) {
        const double at = p.at(q[k]);
        if (at < lowest) lowest = at, worst = k;
      }
    }
    const KktResult found = projectPolygonByKkt(shape, q, M, y, rho, worst, out);
    if (found == KktResult::kInside) {
      out = y;  // p >= 0 on Q to round-off: y is on K_Q's boundary
    } else if (found != KktResult::kFound) {
      out = projectPolygonBySearch(shape, q, M, y, rho);
    }
    if (level == 2) break;
    // refine about the touch angle of this level's pressure
    const LinearPressure po = LinearPressure::fromLoads(shape, loadsOfScaled(out, rho));
    if (!(out[0] > 0.0) || !(std::abs(po.cx) + std::abs(po.cy) > 0.0)) break;
    windows.push_back(TangentWindow{std::atan2(-po.cy, -po.cx),
                                    kArcWindowSteps * kArcTangentSteps[level],
                                    kArcTangentSteps[level + 1]});
  }
  PatchLoads result = loadsOfScaled(out, rho);
  // where an active vertex of Q is a piece's end (on the region) its
  // pressure may round below 0: add the uniform pressure that lifts the
  // minimum to >= 0 (a change of round-off size), so that the result is
  // admissible with tolerance 0 and comes back unchanged (idempotence;
  // AdmissibleLoadsArcRegion.ProjectionIsAdmissibleIdempotentAndOrthogonal)
  if (result.Pz > 0.0) {
    for (int attempt = 0; attempt < 4 && !isAdmissible(shape, result, 0.0); ++attempt) {
      const double lowest = minPressure(shape, LinearPressure::fromLoads(shape, result));
      // (-lowest alone may round away in Pz: plus a few ulps of the mean)
      const double lift = -lowest + (attempt + 1) * 4.0 * std::numeric_limits<double>::epsilon() *
                                        (result.Pz / shape.area());
      const PatchLoads add = loadsOf(shape, LinearPressure{lift, 0.0, 0.0});
      result = PatchLoads{result.Pz + add.Pz, result.Tx + add.Tx, result.Ty + add.Ty};
    }
  }
  return result;
}

PatchLoads nearestAdmissibleLoadsImpl(const PatchShape& shape, const PatchLoads& loads,
                                      double rho) {
  if (!(loads.Pz > 0.0)) return PatchLoads{};  // documented: no normal force, no load
  if (shape.kind() == PatchShape::Kind::ArcRegion) return arcRegionImpl(shape, loads, rho);
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
  const PatchLoads out = nearestAdmissibleLoadsImpl(shape, loads, rho);
  // found by fuzzing: a denormal rho made the scaled torques overflow (NaN)
  if (!out.asVector().allFinite()) {
    throw Error("nearest admissible loads out of range: torques / rho overflow double (rho = " +
                internal::formatDouble(rho) + " m)");
  }
  // found by fuzzing: torques ~1e300 times Pz rho swamp the projection's
  // round-off test and it returned inadmissible loads; say so instead (also
  // for a result with Pz < 0: torques 1e154 times Pz rho gave Pz = -4.9e138,
  // round-off of the 1e154-sized scaled torque)
  // (for polygons with Pz > 0 isAdmissible's decision, cheaper)
  auto admissible = [&] {
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
