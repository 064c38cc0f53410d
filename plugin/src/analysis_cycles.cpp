// Limit cycles of the fast dynamics w' = V*(w) on the sphere, Eq. (27),
// (104): seeds integrated to their attractor, recurrence on a section, Newton
// on the return map. Definitions in patchspin/limit_cycles.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <patchspin/limit_cycles.hpp>

namespace patchspin {

namespace {

// Tolerances, angles on the unit sphere [rad], times in 1 / fieldScale.
constexpr double kSeedStep = 0.02;     // RK4 step of the seed runs: <= 0.02 rad per step
constexpr double kCapture = 1e-3;      // a seed this close to an attracting fixed point ends there
constexpr double kOnCycle = 1e-4;      // ... or this close to an attracting cycle found before
constexpr double kReturnWindow = 0.1;  // a return within this of the section's anchor: try Newton
// no return to the section within this: new anchor (a cycle's period in
// these units: 47 for issue 34's thick disk at F / (mu m g) = 0.0911, 190 at
// 0.132, diverging at the saddle-node near 0.135: cycle_bifurcation.hpp)
constexpr double kReanchorTime = 1000.0;
constexpr double kNewtonTol = 1e-11;     // |P(sigma) - sigma| of a resolved cycle (RK4 at T/400
                                         // is ~1e-8 accurate; this is the map's own fixed point)
constexpr double kMaxNewtonStep = 0.05;  // trust region of the Newton step on sigma
constexpr double kSameCycle = 1e-4;      // a cycle point this close to a known orbit: same cycle

// Field of the fast dynamics in direction d = +-1 (backward in tau: d = -1):
// V = d (I - w w^T) F_o, Eq. (104); with a tangent delta also its derivative
// dV delta = d (D delta - (delta.F_o + w.D delta) w - R* delta), and the
// surface divergence d (tr D - w.D w - 2 R*).
struct FieldValue {
  Vec3 V = Vec3::Zero();
  Vec3 dV = Vec3::Zero();
  double rdot = 0.0;  // R* = w . F_o (not times d)
  double div = 0.0;
};

FieldValue evalField(const FlatBodyModel& model, const Vec3& w, const Vec3* delta, double d) {
  FieldValue out;
  Mat3 D;
  const Vec3 F = model.limitField(w, delta ? &D : nullptr);
  out.rdot = w.dot(F);
  out.V = d * (F - out.rdot * w);
  if (delta) {
    const Vec3 Dd = D * (*delta);
    out.dV = d * (Dd - (delta->dot(F) + w.dot(Dd)) * w - out.rdot * (*delta));
    out.div = d * (D.trace() - w.dot(D * w) - 2.0 * out.rdot);
  }
  return out;
}

// RK4 state: w, the tangent variation delta, and oint R* dtau, oint div dtau.
struct Flow {
  Vec3 w = Vec3::Zero();
  Vec3 delta = Vec3::Zero();
  double intR = 0.0;
  double intDiv = 0.0;
};

Flow rk4(const FlatBodyModel& model, const Flow& y, double h, double d, bool variational) {
  auto deriv = [&](const Flow& s) {
    const FieldValue f = evalField(model, s.w, variational ? &s.delta : nullptr, d);
    Flow k;
    k.w = f.V;
    k.delta = f.dV;
    k.intR = f.rdot;
    k.intDiv = f.div;
    return k;
  };
  auto axpy = [](const Flow& s, double a, const Flow& k) {
    Flow o;
    o.w = s.w + a * k.w;
    o.delta = s.delta + a * k.delta;
    o.intR = s.intR + a * k.intR;
    o.intDiv = s.intDiv + a * k.intDiv;
    return o;
  };
  const Flow k1 = deriv(y);
  const Flow k2 = deriv(axpy(y, h / 2, k1));
  const Flow k3 = deriv(axpy(y, h / 2, k2));
  const Flow k4 = deriv(axpy(y, h, k3));
  Flow o = y;
  o.w += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
  o.delta += h / 6 * (k1.delta + 2 * k2.delta + 2 * k3.delta + k4.delta);
  o.intR += h / 6 * (k1.intR + 2 * k2.intR + 2 * k3.intR + k4.intR);
  o.intDiv += h / 6 * (k1.intDiv + 2 * k2.intDiv + 2 * k3.intDiv + k4.intDiv);
  // back onto the sphere and its tangent plane (the exact flow keeps both)
  o.w.normalize();
  o.delta -= o.w.dot(o.delta) * o.w;
  return o;
}

// A Poincare section: the half great circle {w . n = 0, w . a > 0} through
// the anchor a, n = V(a) / |V(a)| (so the flow crosses it upward, n . V > 0),
// with the coordinate sigma = atan2(w . b, w . a), b = a x n.
struct Section {
  Vec3 a, n, b;
  Vec3 point(double sigma) const { return std::cos(sigma) * a + std::sin(sigma) * b; }
  double coordinate(const Vec3& w) const { return std::atan2(w.dot(b), w.dot(a)); }
};

Section sectionAt(const FlatBodyModel& model, const Vec3& anchor, double d) {
  Section s;
  s.a = anchor.normalized();
  s.n = evalField(model, s.a, nullptr, d).V.normalized();
  s.b = s.a.cross(s.n);
  return s;
}

double unwrap(double dphi) {
  while (dphi > M_PI) dphi -= 2.0 * M_PI;
  while (dphi < -M_PI) dphi += 2.0 * M_PI;
  return dphi;
}

// The return map P(sigma) of `sec`, its derivative, the return time T and
// the integrals along the way (RK4 step h, at most maxTime).
struct Return {
  bool ok = false;
  double sigma = 0.0, dsigma = 0.0, T = 0.0, intR = 0.0, intDiv = 0.0, turn = 0.0;
  std::vector<Vec3> orbit;
};

Return returnMap(const FlatBodyModel& model, const Section& sec, double sigma, double h,
                 double maxTime, double d, bool record) {
  Return out;
  Flow y;
  y.w = sec.point(sigma);
  y.delta = -std::sin(sigma) * sec.a + std::cos(sigma) * sec.b;  // dw / dsigma
  double s = 0.0, g = 0.0;
  while (s < maxTime) {
    if (record) out.orbit.push_back(y.w);
    const Flow next = rk4(model, y, h, d, true);
    const double gNext = next.w.dot(sec.n);
    if (g < 0.0 && gNext >= 0.0 && next.w.dot(sec.a) > 0.0) {
      // crossing inside this step: secant on theta for g(rk4(y, theta h)) = 0
      double t0 = 0.0, g0 = g, t1 = 1.0, g1 = gNext;
      Flow hit = next;
      for (int it = 0; it < 8 && std::abs(g1) > 1e-15; ++it) {
        const double t2 = t1 - g1 * (t1 - t0) / (g1 - g0);
        if (!std::isfinite(t2)) break;
        hit = rk4(model, y, t2 * h, d, true);
        t0 = t1, g0 = g1;
        t1 = t2, g1 = hit.w.dot(sec.n);
      }
      hit = rk4(model, y, t1 * h, d, true);
      out.turn += unwrap(std::atan2(hit.w.y(), hit.w.x()) - std::atan2(y.w.y(), y.w.x()));
      out.T = s + t1 * h;
      out.intR = hit.intR;
      out.intDiv = hit.intDiv;
      out.sigma = sec.coordinate(hit.w);
      // the hit point moves with delta and along the flow to stay on the
      // section: dw_hit = delta - V (n . delta) / (n . V)
      const Vec3 V = evalField(model, hit.w, nullptr, d).V;
      const Vec3 dw = hit.delta - V * (sec.n.dot(hit.delta) / sec.n.dot(V));
      const double x = hit.w.dot(sec.a), z = hit.w.dot(sec.b);
      out.dsigma = (x * sec.b.dot(dw) - z * sec.a.dot(dw)) / (x * x + z * z);
      out.ok = std::isfinite(out.sigma) && std::isfinite(out.dsigma);
      return out;
    }
    out.turn += unwrap(std::atan2(next.w.y(), next.w.x()) - std::atan2(y.w.y(), y.w.x()));
    y = next;
    g = gNext;
    s += h;
  }
  return out;
}

// Distance from w to the closed polyline `orbit`.
double distanceToOrbit(const std::vector<Vec3>& orbit, const Vec3& w) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < orbit.size(); ++i) {
    const Vec3& p = orbit[i];
    const Vec3& q = orbit[(i + 1) % orbit.size()];
    const Vec3 e = q - p;
    const double t =
        std::clamp(e.squaredNorm() > 0.0 ? (w - p).dot(e) / e.squaredNorm() : 0.0, 0.0, 1.0);
    best = std::min(best, (p + t * e - w).norm());
  }
  return best;
}

// Newton on P(sigma) - sigma from sigma0 on `sec` with first-return time T0.
bool resolveCycle(const FlatBodyModel& model, const Section& sec, double sigma0, double T0,
                  double d, double rho, double R, LimitCycle& cycle) {
  double sigma = sigma0;
  double h = T0 / kCycleSamples;
  for (int it = 0; it < 16; ++it) {
    const Return r = returnMap(model, sec, sigma, h, 1.5 * T0 + 10.0 * h, d, false);
    if (!r.ok) return false;
    const double F = r.sigma - sigma;
    // the period's own step, then fixed: P must be one map for Newton
    if (it == 0) h = r.T / kCycleSamples;
    if (std::abs(F) <= kNewtonTol) {
      const Return c = returnMap(model, sec, sigma, h, 1.5 * r.T, d, true);
      if (!c.ok) return false;
      cycle.point = sec.point(sigma);
      cycle.period = c.T;
      cycle.residual = std::abs(c.sigma - sigma);
      cycle.orbit = c.orbit;
      if (d < 0.0) std::reverse(cycle.orbit.begin(), cycle.orbit.end());
      // forward flow: multipliers invert, the turn changes sign; oint R* is
      // over the same points and times
      cycle.multiplier = std::exp(d * c.intDiv);
      cycle.returnMapSlope = d > 0.0 ? c.dsigma : 1.0 / c.dsigma;
      cycle.attracting = cycle.multiplier < 1.0;
      cycle.meanRdot = c.intR / c.T;
      cycle.turn = d * c.turn;
      cycle.turnPerDecade = -std::log(10.0) * cycle.turn / c.intR;
      // extremes of w3: vertex of the parabola through three successive
      // samples (T/400 apart; a node alone misses the extreme by up to 2e-5)
      cycle.w3Min = std::numeric_limits<double>::infinity();
      cycle.w3Max = -cycle.w3Min;
      const std::size_t n = cycle.orbit.size();
      for (std::size_t i = 0; i < n; ++i) {
        const double a = cycle.orbit[(i + n - 1) % n].z(), b = cycle.orbit[i].z(),
                     e = cycle.orbit[(i + 1) % n].z();
        const double curv = a - 2.0 * b + e;
        double z = b;
        if (((b >= a && b >= e) || (b <= a && b <= e)) && curv != 0.0)
          z = b - (e - a) * (e - a) / (8.0 * curv);
        cycle.w3Min = std::min(cycle.w3Min, z);
        cycle.w3Max = std::max(cycle.w3Max, z);
      }
      // v / (R omega) = rho sqrt(1 - w3^2) / (R |w3|) falls as |w3| grows
      auto ratio = [&](double w3) {
        return w3 != 0.0 ? rho * std::sqrt(std::max(0.0, 1.0 - w3 * w3)) / (R * std::abs(w3))
                         : std::numeric_limits<double>::infinity();
      };
      const double far = std::max(std::abs(cycle.w3Min), std::abs(cycle.w3Max));
      double near = 0.0;  // the cycle crosses w3 = 0
      if (cycle.w3Min > 0.0) near = cycle.w3Min;
      if (cycle.w3Max < 0.0) near = -cycle.w3Max;
      cycle.slipRatioMin = ratio(far);
      cycle.slipRatioMax = ratio(near);
      return true;
    }
    double step = -F / (r.dsigma - 1.0);
    if (!std::isfinite(step)) return false;
    step = std::clamp(step, -kMaxNewtonStep, kMaxNewtonStep);
    sigma += step;
    if (std::abs(sigma) > 0.5) return false;
  }
  return false;
}

// Integrates one seed in direction d until it ends (see the header).
SeedEnd runSeed(const FlatBodyModel& model, const LimitAnalysis& fixed, const Vec3& seed, double d,
                double scale, double budget, double rho, double R,
                std::vector<LimitCycle>& cycles) {
  SeedEnd end;
  end.seed = seed;
  // fixed points attracting on the sphere in direction d: d Re(lambda) < 0
  std::vector<int> sinks;
  for (std::size_t i = 0; i < fixed.directions.size(); ++i) {
    const LimitDirection& p = fixed.directions[i];
    if (d * p.eigenvalues[0].real() < 0.0 && d * p.eigenvalues[1].real() < 0.0)
      sinks.push_back(static_cast<int>(i));
  }
  const double h = kSeedStep / scale;
  Flow y;
  y.w = seed.normalized();
  Section sec = sectionAt(model, y.w, d);
  double anchorTime = 0.0, g = 0.0;
  int steps = 0;
  for (double s = 0.0; s < budget / scale; s += h, ++steps) {
    for (int i : sinks) {
      if ((y.w - fixed.directions[static_cast<std::size_t>(i)].w).norm() < kCapture) {
        end.kind = SeedEnd::FixedPoint, end.index = i, end.last = y.w;
        return end;
      }
    }
    // a circle of fixed points n.w = offset, closed on in direction d
    for (std::size_t c = 0; c < fixed.continua.size(); ++c) {
      const LimitContinuum& k = fixed.continua[c];
      const double off = k.normal.dot(y.w) - k.offset;
      if (std::abs(off) < kCapture &&
          off * k.normal.dot(evalField(model, y.w, nullptr, d).V) < 0.0) {
        end.kind = SeedEnd::Continuum, end.index = static_cast<int>(c), end.last = y.w;
        return end;
      }
    }
    if (steps % 16 == 0) {
      for (std::size_t c = 0; c < cycles.size(); ++c) {
        const bool attractsHere = d > 0.0 ? cycles[c].attracting : !cycles[c].attracting;
        if (attractsHere && distanceToOrbit(cycles[c].orbit, y.w) < kOnCycle) {
          end.kind = SeedEnd::Cycle, end.index = static_cast<int>(c), end.last = y.w;
          return end;
        }
      }
    }
    const Flow next = rk4(model, y, h, d, false);
    const double gNext = next.w.dot(sec.n);
    if (g < 0.0 && gNext >= 0.0 && next.w.dot(sec.a) > 0.0) {
      // recurrence: the orbit is back at the section through its anchor
      const double sigma = sec.coordinate(next.w);
      LimitCycle cycle;
      if (std::abs(sigma) < kReturnWindow &&
          resolveCycle(model, sec, sigma, s + h - anchorTime, d, rho, R, cycle)) {
        int index = -1;
        for (std::size_t c = 0; c < cycles.size() && index < 0; ++c) {
          if (distanceToOrbit(cycles[c].orbit, cycle.point) < kSameCycle)
            index = static_cast<int>(c);
        }
        if (index < 0) {
          cycles.push_back(cycle);
          index = static_cast<int>(cycles.size()) - 1;
        }
        const bool attractsHere = d > 0.0 ? cycle.attracting : !cycle.attracting;
        if (attractsHere) {
          end.kind = SeedEnd::Cycle, end.index = index, end.last = next.w;
          return end;
        }
      }
      sec = sectionAt(model, next.w, d), anchorTime = s + h, g = 0.0;
    } else if (s + h - anchorTime > kReanchorTime / scale) {
      sec = sectionAt(model, next.w, d), anchorTime = s + h, g = 0.0;
    } else {
      g = gNext;
    }
    y = next;
    if (!y.w.allFinite()) break;  // the field overflowed: unresolved, not a silent loop
  }
  end.last = y.w;
  // a seed on a stable manifold (measure zero) ends at a saddle: listed as
  // unresolved, with the nearest fixed point named
  for (std::size_t i = 0; i < fixed.directions.size(); ++i) {
    if ((y.w - fixed.directions[i].w).norm() < kCapture) end.index = static_cast<int>(i);
  }
  return end;
}

}  // namespace

CycleAnalysis findLimitCycles(const FlatBodyModel& model, const LimitAnalysis& fixed,
                              const CycleOptions& options) {
  CycleAnalysis out;
  const std::vector<Vec3> seeds = internal::fibonacciSphere(std::max(options.seeds, 2));
  for (const Vec3& w : seeds) out.fieldScale = std::max(out.fieldScale, model.limitField(w).norm());
  const bool everyDirectionFixed = std::any_of(fixed.continua.begin(), fixed.continua.end(),
                                               [](const LimitContinuum& c) { return c.sphere; });
  if (!(out.fieldScale > 0.0) || !std::isfinite(out.fieldScale) || everyDirectionFixed) {
    // F_o = 0 or every direction fixed: no isolated cycle to find
    return out;
  }
  out.searched = true;
  const double rho = model.rho();
  const double R = model.body().shape.maxDistanceFromOrigin();
  for (const Vec3& seed : seeds) {
    out.forward.push_back(
        runSeed(model, fixed, seed, 1.0, out.fieldScale, options.budget, rho, R, out.cycles));
    if (out.forward.back().kind == SeedEnd::Unresolved) out.unresolvedForward.push_back(seed);
  }
  if (options.backward) {
    for (const Vec3& seed : seeds) {
      out.backward.push_back(
          runSeed(model, fixed, seed, -1.0, out.fieldScale, options.budget, rho, R, out.cycles));
      if (out.backward.back().kind == SeedEnd::Unresolved) out.unresolvedBackward.push_back(seed);
    }
  }
  return out;
}

}  // namespace patchspin
