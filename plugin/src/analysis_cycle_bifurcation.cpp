// The bifurcation where an attracting cycle of the fast dynamics dies,
// located and classified; definitions in patchspin/cycle_bifurcation.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <patchspin/cycle_bifurcation.hpp>

namespace patchspin {

namespace {

// a node of V* born on the track of the cycle lies within this of its orbit
// (the pair is born ON the cycle; by the sweep's next force it has moved off
// by O(sqrt(dF)) only) [rad]
constexpr double kNearTrack = 0.3;

double distanceToOrbit(const std::vector<Vec3>& orbit, const Vec3& w) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < orbit.size(); ++i) {
    const Vec3& p = orbit[i];
    const Vec3 e = orbit[(i + 1) % orbit.size()] - p;
    const double t =
        std::clamp(e.squaredNorm() > 0.0 ? (w - p).dot(e) / e.squaredNorm() : 0.0, 0.0, 1.0);
    best = std::min(best, (p + t * e - w).norm());
  }
  return best;
}

bool isNode(const LimitDirection& d) {  // attracting on the sphere, real eigenvalues
  return d.eigenvalues[0].real() < 0.0 && d.eigenvalues[1].real() < 0.0 &&
         d.eigenvalues[0].imag() == 0.0;
}
bool isSaddle(const LimitDirection& d) {
  return d.eigenvalues[0].real() * d.eigenvalues[1].real() < 0.0;
}

FlatBodyModel modelAt(const FlatBody& base, Model law, double F) {
  FlatBody body = base;
  body.force.x() = F;
  return FlatBodyModel(body, law);
}

// The node of `a` nearest the track, if within kNearTrack, and the saddle
// nearest that node.
struct Pair {
  const LimitDirection* node = nullptr;
  const LimitDirection* saddle = nullptr;
};
Pair pairOnTrack(const LimitAnalysis& a, const std::vector<Vec3>& track) {
  Pair p;
  double best = kNearTrack;
  for (const LimitDirection& d : a.directions) {
    const double dist = isNode(d) ? distanceToOrbit(track, d.w) : best;
    if (dist < best) best = dist, p.node = &d;
  }
  if (!p.node) return p;
  double nearest = std::numeric_limits<double>::infinity();
  for (const LimitDirection& d : a.directions) {
    if (isSaddle(d) && (d.w - p.node->w).norm() < nearest)
      nearest = (d.w - p.node->w).norm(), p.saddle = &d;
  }
  return p;
}

}  // namespace

const char* toString(CycleBifurcation::Kind kind) {
  return kind == CycleBifurcation::SaddleNodeOnCycle ? "saddle-node on the cycle (SNIC)"
                                                     : "unclassified";
}

CycleBifurcation locateCycleBifurcation(const FlatBody& base, Model law, double fWith,
                                        double fWithout, const LimitCycle& cycle, double tol,
                                        const std::vector<double>& approachOffsets) {
  if (!(tol > 0.0) || !std::isfinite(tol) || !std::isfinite(fWith) || !std::isfinite(fWithout))
    throw Error("locateCycleBifurcation: the forces and tol must be finite, tol > 0");
  CycleBifurcation out;
  out.withCycle = fWith;
  out.withoutCycle = fWithout;
  out.force = 0.5 * (fWith + fWithout);
  out.forceError = 0.5 * std::abs(fWithout - fWith);
  // the node must be on the track at fWithout; then bisect on its existence
  const LimitAnalysis far = findLimitDirections(modelAt(base, law, fWithout));
  // (its saddle may already have gone into another fixed point here: the
  // node alone decides existence; its saddle is the one nearest it at F*)
  const Pair first = pairOnTrack(far, cycle.orbit);
  if (!first.node) return out;
  LimitDirection node = *first.node, saddle;
  bool haveSaddle = false;
  double lo = fWith, hi = fWithout;  // no pair at lo, the pair at hi
  for (int it = 0; it < 200 && std::abs(hi - lo) > tol; ++it) {
    const double mid = 0.5 * (lo + hi);
    const LimitAnalysis a = findLimitDirections(modelAt(base, law, mid));
    // the pair near the one last seen (it moves by O(sqrt(dF)) between forces)
    const Pair p = pairOnTrack(a, {node.w});
    if (p.node) {
      hi = mid;
      node = *p.node;
      haveSaddle = p.saddle != nullptr;
      if (haveSaddle) saddle = *p.saddle;
    } else {
      lo = mid;
    }
  }
  out.force = 0.5 * (lo + hi);
  out.forceError = 0.5 * std::abs(hi - lo);
  if (!haveSaddle) return out;  // a node alone vanishing is no saddle-node
  out.point = (node.w + saddle.w).normalized();
  out.pairSeparation = (node.w - saddle.w).norm();
  out.nodeEigenvalue = std::abs(node.eigenvalues[0].real()) < std::abs(node.eigenvalues[1].real())
                           ? node.eigenvalues[0].real()
                           : node.eigenvalues[1].real();
  out.saddleEigenvalue = std::max(saddle.eigenvalues[0].real(), saddle.eigenvalues[1].real());
  out.kind = CycleBifurcation::SaddleNodeOnCycle;
  // the cycle on its side, farthest offset first
  std::vector<double> offsets = approachOffsets;
  std::sort(offsets.begin(), offsets.end(), std::greater<double>());
  const double side = fWith < fWithout ? -1.0 : 1.0;
  out.distanceToCycle = distanceToOrbit(cycle.orbit, out.point);
  for (double delta : offsets) {
    const double F = out.force + side * delta;
    const FlatBodyModel model = modelAt(base, law, F);
    const LimitAnalysis a = findLimitDirections(model);
    CycleOptions options;
    options.seeds = 8;
    options.backward = false;
    const CycleAnalysis c = findLimitCycles(model, a, options);
    // the attracting cycle nearest the given one
    const LimitCycle* best = nullptr;
    double bestDistance = kNearTrack;
    for (const LimitCycle& y : c.cycles) {
      const double d = y.attracting ? distanceToOrbit(cycle.orbit, y.point) : bestDistance;
      if (d < bestDistance) bestDistance = d, best = &y;
    }
    if (!best) continue;
    out.approach.push_back({F, best->period, best->w3Min, best->w3Max, best->multiplier});
    out.distanceToCycle = distanceToOrbit(best->orbit, out.point);
  }
  return out;
}

}  // namespace patchspin
