// Normal block part (normal_block.hpp; docs/solver.md (S4)-(S6), (S17)-(S20), (S23)-(S24)).
#include <patchspin/parts/normal_block.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patchspin::parts {

PatchOutlineSummary summarizeOutline(const PatchShape& shape) {
  PatchOutlineSummary s;
  s.disk = shape.isDisk();
  if (s.disk) {
    s.centre = shape.centre();
    s.radius = shape.radius();
  }
  s.diameter = shape.diameter();
  return s;
}

Vec2 nearestPointOn(const PatchShape& shape, const Vec2& p) {
  if (shape.isDisk()) {
    const Vec2 d = p - shape.centre();
    const double n = d.norm();
    return n <= shape.radius() ? p : Vec2(shape.centre() + d * (shape.radius() / n));
  }
  if (shape.contains(p)) return p;
  const auto& v = shape.vertices();
  Vec2 best = v[0];
  double bestDist = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], e = v[(i + 1) % v.size()] - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec2 q = a + t * e;
    if ((q - p).norm() < bestDist) {
      bestDist = (q - p).norm();
      best = q;
    }
  }
  return best;
}

double innerRadiusSquared(const PatchShape& shape) {
  if (shape.isDisk()) return 0.0;
  const auto& v = shape.vertices();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, prev = v.size() - 1; i < v.size(); prev = i++) {
    const Vec2 e = v[i] - v[prev];
    const double len = e.norm();
    if (!(len > 0.0)) continue;
    // signed distance of O from the edge line, > 0 on the inner side (counter-clockwise)
    const double d = (e.x() * -v[prev].y() - e.y() * -v[prev].x()) / len;
    best = std::min(best, d);
  }
  if (!(best > 0.0) || !std::isfinite(best)) return 0.0;
  const double r = best * (1.0 - 1e-9);
  return r * r;
}

namespace {
// (S17): where a is tilted on b, the gap closes only until a's low side is
// kLowSideSinkRelTol of the patch size into b
Vec3 gapTarget(double gap, double clearance, double size, double dt) {
  const double sink = kLowSideSinkRelTol * size;
  return Vec3(-std::clamp(clearance + sink, 0.0, gap) / dt, 0.0, 0.0);
}
}  // namespace

NormalTargets normalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                            double dt, bool splitImpulse, double erp, double erp2, double bounce) {
  NormalTargets t;
  if (gap > 0.0) {
    t.velocity = gapTarget(gap, clearance, size, dt);  // (the tilt: corrected by the push)
  } else if (splitImpulse) {
    t.push = (Vec3(-gap, 0.0, 0.0) + tiltRate) * erp / dt;
  } else {
    t.velocity = (Vec3(-gap, 0.0, 0.0) + tiltRate) * erp2 / dt;
  }
  if (gap > 0.0 && splitImpulse) t.push = tiltRate * erp / dt;
  t.velocity[0] += bounce;
  return t;
}

NormalTargets softNormalTargets(double gap, double clearance, const Vec3& tiltRate, double size,
                                double dt, bool splitImpulse, double erp, double erp2,
                                double softErp, double bounce) {
  NormalTargets t =
      normalTargets(gap, clearance, tiltRate, size, dt, splitImpulse, erp, erp2, bounce);
  if (gap <= 0.0) {
    t.velocity[0] = -gap * softErp / dt + bounce;
    t.push[0] = 0.0;
  }
  return t;
}

void clampNormalImpulse(const Vec3& y, const Vec2& cop, const PatchOutlineSummary& outline,
                        const PatchShape& shape, NormalImpulse& out) {
  const Vec2 clamped = nearestPointOn(shape, cop);
  out.lamN = Vec3(y[0], y[0] * clamped.y(), -y[0] * clamped.x());
  out.tipping = (cop - clamped).norm() > kTipRelTol * outline.diameter;
}

}  // namespace patchspin::parts
