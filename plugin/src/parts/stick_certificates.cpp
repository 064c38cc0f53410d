// Stick certificates of the exact law (stick_certificates.hpp; docs/solver.md (S14)).
//
// E (unit mu Pz) is convex and odd, and every law value q(w) lies on its
// boundary, so E contains conv(B u {+-q*}) for the bicone B = Pi {|(z1, z2)|
// + |z3| <= 1} and any q* = q(w). With q* along the ellipsoidal inverse of
// x's direction (w = -Pi^-1 x: the ellipsoidal q(w) is parallel to x),
// x = a q* + (1 - a) b with b in B certifies x in E (a tried on a grid).
// Near E's boundary a fan of three more law values q_k = q(w_k), w_k = w*
// turned by kFanSpread towards three directions 120 degrees apart, gives
// tetrahedra conv{0, q*, q_k, q_k+1} inside E; x in one of them is certified.
// Between its corners E bulges beyond a flat face by ~kFanSpread^2 / 8 of its
// size, so for x beyond a face by less than kFanBulge one more law value, at
// x's barycentric mix of the corners' slips, splits the cone into three.
// The constants below decide only when evaluations are worth it, never the
// soundness of a certificate (measurements: docs/notes/solver-work-saving.md).
#include <patchspin/parts/stick_certificates.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace patchspin::parts {
namespace {

// q* is kept while x turns by less than this (cosine; ~2.6 degrees)
constexpr double kHullTurnCos = 0.999;
// the fan's law values: w* turned by this (radians on the unit sphere, ~)
constexpr double kFanSpread = 0.4;
// slack for the law's own accuracy (1e-12 relative) and the 3x3 solves
constexpr double kFanSlack = 1e-9;
// x beyond kFanGate times the ellipsoid Pi B is not tried (the exact set and
// the ellipsoid agree on pure translation and pure spin)
constexpr double kFanGate = 1.2;
// a face's barycentric sum beyond this: not refined (E bulges ~2 % at most)
constexpr double kFanBulge = 1.03;

// The slip of the fan's k-th law value: w* turned by kFanSpread.
Vec3 fanSlip(const Vec3& ws, int k) {
  const Vec3 u = ws.unitOrthogonal(), v = ws.cross(u);
  const double angle = 2.0943951023931957 * k;  // 2 pi / 3
  return (ws + kFanSpread * (std::cos(angle) * u + std::sin(angle) * v)).normalized();
}

bool exactFanSticks(StickCertificates& st, const Mat3& piInv, bool sticking,
                    const FrictionPatch& friction, const Vec3& x, const Vec3& direction,
                    bool& refine) {
  if ((piInv * x).norm() > kFanGate) return false;
  if (!st.fanValid || direction.dot(st.fanDirection) < kHullTurnCos) {
    st.fanValid = false;
    // three evaluations: only for a patch that ended the last step stuck
    if (!sticking || st.hullDirection.dot(direction) < kHullTurnCos) return false;
    // hullPoint = q(w*) with w* = hullSlip
    st.fanCentre = st.hullPoint;
    const Vec3& ws = st.hullSlip;
    for (int k = 0; k < 3; ++k) {
      st.fan[k] = friction.unitQ(Model::Exact, fanSlip(ws, k));
      if (!st.fan[k].allFinite()) return false;
    }
    for (int k = 0; k < 3; ++k) {
      Mat3 M;
      M << st.fanCentre, st.fan[k], st.fan[(k + 1) % 3];
      st.fanInv[k] = M.inverse();
      if (!st.fanInv[k].allFinite()) return false;
    }
    st.fanDirection = st.hullDirection;
    st.fanSlip = ws;
    st.fanValid = true;
  }
  const double sign = st.fanCentre.dot(x) >= 0.0 ? 1.0 : -1.0;  // E is odd
  // x in conv{0, p0, p1, p2}: barycentric a = [p0 p1 p2]^-1 x >= 0, sum <= 1
  // (a singular or ill-conditioned corner gives a non-finite or useless a)
  auto coordinates = [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec3& a) {
    Mat3 M;
    M << p0, p1, p2;
    a = M.inverse() * x;
    return a.allFinite() && a.minCoeff() >= 0.0;
  };
  const Vec3& ws = st.fanSlip;
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = sign * (st.fanInv[k] * x);  // the fan's corners are cached
    if (!a.allFinite() || a.minCoeff() < 0.0) continue;
    if (a.sum() <= 1.0 - kFanSlack) return true;
    // beyond what E bulges out there, or a patch that slipped at the end of
    // the last step: most likely a slip, not worth one more evaluation
    if (a.sum() > kFanBulge || !sticking || !refine) return false;
    const Vec3 p[3] = {sign * st.fanCentre, sign * st.fan[k], sign * st.fan[(k + 1) % 3]};
    // one more law value inside the face's corner directions, at the slips'
    // mix with x's barycentric weights, splits the cone into three
    const Vec3 wsK = fanSlip(ws, k), wsK1 = fanSlip(ws, (k + 1) % 3);
    const Vec3 wr = (a[0] * ws + a[1] * wsK + a[2] * wsK1).normalized();
    const Vec3 r = sign * friction.unitQ(Model::Exact, wr);
    if (!r.allFinite()) return false;
    for (int j = 0; j < 3; ++j) {
      Vec3 b;
      if (coordinates(r, p[j], p[(j + 1) % 3], b) && b.sum() <= 1.0 - kFanSlack) return true;
    }
    refine = false;  // failed once: not again in this step (the patch most likely slips)
    return false;
  }
  return false;
}

}  // namespace

bool exactHullSticks(StickCertificates& st, const Mat3& piInv, bool sticking,
                     const FrictionPatch& friction, const Vec3& lambda0, double L, bool& refine) {
  const Vec3 x = lambda0 / L;
  const double xNorm = x.norm();
  if (!(xNorm > 0.0) || !std::isfinite(xNorm)) return false;
  const Vec3 direction = x / xNorm;
  if (!st.hullValid || direction.dot(st.hullDirection) < kHullTurnCos) {
    const Vec3 w = -(piInv * direction);
    const double wNorm = w.norm();
    if (!(wNorm > 0.0) || !std::isfinite(wNorm)) return false;
    st.hullSlip = w / wNorm;
    st.hullPoint = friction.unitQ(Model::Exact, st.hullSlip);
    st.hullDirection = direction;
    st.hullValid = st.hullPoint.allFinite();
    if (!st.hullValid) return false;
  }
  const Vec3 q = st.hullPoint.dot(x) >= 0.0 ? st.hullPoint : Vec3(-st.hullPoint);
  auto inHull = [&](double a) {
    const Vec3 z = piInv * (x - a * q);
    return std::hypot(z.x(), z.y()) + std::abs(z.z()) <= 1.0 - a;
  };
  // the projection of x on q, and a grid in [0, 1]
  const double along = std::clamp(x.dot(q) / q.squaredNorm(), 0.0, 1.0);
  if (inHull(along) || inHull(0.9375 * along)) return true;
  for (int k = 1; k < 8; ++k)
    if (inHull(k / 8.0)) return true;
  return exactFanSticks(st, piInv, sticking, friction, x, direction, refine);
}

void keepGaugePoint(StickCertificates& st, const Vec3& gaugeSlip, const Vec3& gaugeValue,
                    bool sticking) {
  if (gaugeSlip.isZero(0.0)) return;
  st.gaugeSlip = gaugeSlip;
  if (sticking && gaugeValue.allFinite()) {
    st.hullSlip = gaugeSlip;
    st.hullPoint = gaugeValue;
    st.hullDirection = gaugeValue.normalized();
    st.hullValid = true;
    st.fanValid = false;
  }
}

}  // namespace patchspin::parts
