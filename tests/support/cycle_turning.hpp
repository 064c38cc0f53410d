// Turning of the slip velocity's direction phi = atan2(u_y, u_x) against the
// decades of slip, log10 r, for a trajectory and for a limit cycle of the
// fast dynamics (patchspin/limit_cycles.hpp), written here for the tests of
// issue 34, item 3 (tests/core/ and tests/bullet/limit_cycle_turning_test).
//
// On a cycle traversed once, phi turns by LimitCycle::turn while log10 r
// falls by -T <R*> / ln 10, so the turn per decade over whole periods is
// Gamma = LimitCycle::turnPerDecade. Over part of a period the turn depends
// on where on the cycle the window starts: CycleTable tabulates, along the
// cycle's orbit, the unwrapped phi and the decades fallen,
//   D(tau) = -(1 / ln 10) int_0^tau R*(w) dtau,   R* = w . F_o(w)   (27),
// (midpoint rule on the orbit's segments, each one's fast time its length
// over |V*|), and predicts
// the turn over D decades from a point w on (or near) the cycle.
#pragma once

#include <algorithm>
#include <cmath>
#include <patchspin/limit_cycles.hpp>
#include <vector>

namespace patchspin::testing {

struct TurnSample {
  double decades;  // -log10 r [-]
  double phi;      // unwrapped direction of the slip velocity [rad]
  Vec3 w;          // slip direction (u_x, u_y, rho omega) / r
};

// phi unwrapped along slip states x (ground axes at psi = 0, x along the
// force); states with r = 0 are skipped.
inline std::vector<TurnSample> turnSamples(const std::vector<Vec3>& states) {
  std::vector<TurnSample> out;
  for (const Vec3& x : states) {
    const double r = x.norm();
    if (!(r > 0.0)) continue;
    const double phi = std::atan2(x.y(), x.x());
    TurnSample s{-std::log10(r), phi, x / r};
    if (!out.empty()) s.phi = out.back().phi + std::remainder(phi - out.back().phi, 2.0 * M_PI);
    out.push_back(s);
  }
  return out;
}

// phi where the trajectory has fallen to `decades` (linear in decades between
// the two samples around it); NaN outside the samples.
inline double phiAt(const std::vector<TurnSample>& s, double decades) {
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i - 1].decades <= decades && decades <= s[i].decades && s[i].decades > s[i - 1].decades) {
      const double t = (decades - s[i - 1].decades) / (s[i].decades - s[i - 1].decades);
      return s[i - 1].phi + t * (s[i].phi - s[i - 1].phi);
    }
  }
  return NAN;
}

class CycleTable {
 public:
  CycleTable(const FlatBodyModel& model, const LimitCycle& cycle) : cycle_(cycle) {
    const std::size_t n = cycle.orbit.size();
    phi_.assign(n + 1, 0.0);
    dec_.assign(n + 1, 0.0);
    tau_.assign(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = cycle.orbit[i];
      const Vec3& b = cycle.orbit[(i + 1) % n];
      phi_[i + 1] =
          phi_[i] + std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()), 2.0 * M_PI);
      // the segment's fast time |b - a| / |V*| and its R*, both at the
      // midpoint (the nodes need not be equally spaced in tau)
      const Vec3 m = (a + b).normalized();
      const Vec3 F = model.limitField(m);
      const double rstar = m.dot(F);
      const double dtau = (b - a).norm() / (F - rstar * m).norm();
      tau_[i + 1] = tau_[i] + dtau;
      dec_[i + 1] = dec_[i] - dtau * rstar / std::log(10.0);
    }
  }
  // fast time of one period of the table [s^2/m]
  double period() const { return tau_.back(); }
  // decades fallen and phi turned over one period of the table
  double decadesPerPeriod() const { return dec_.back(); }
  double turnPerPeriod() const { return phi_.back(); }

  // Phase (fractional node index in [0, n)) of the orbit point nearest to w,
  // projected onto the chord to the nearer neighbour.
  double phaseOf(const Vec3& w) const {
    const std::size_t n = cycle_.orbit.size();
    std::size_t best = 0;
    for (std::size_t i = 1; i < n; ++i)
      if ((cycle_.orbit[i] - w).norm() < (cycle_.orbit[best] - w).norm()) best = i;
    double phase = double(best);
    for (int side : {-1, 1}) {
      const std::size_t j = (best + n + std::size_t(side + 1) - 1) % n;  // best -1 or +1
      const Vec3 a = cycle_.orbit[best], d = cycle_.orbit[j] - a;
      const double t = (w - a).dot(d) / d.squaredNorm();
      if (t > 0.0) phase = double(best) + side * std::min(t, 1.0);
    }
    return phase < 0.0 ? phase + double(n) : phase;
  }

  // The cycle's point `decades` on from phase `start` (linear between nodes,
  // normalised).
  Vec3 pointAfter(double start, double decades) const {
    const double p = phaseAfter(start, decades), n = double(cycle_.orbit.size());
    const double q = p - n * std::floor(p / n);
    const std::size_t i = std::min(std::size_t(q), cycle_.orbit.size() - 1);
    const double f = q - double(i);
    return ((1.0 - f) * cycle_.orbit[i] + f * cycle_.orbit[(i + 1) % cycle_.orbit.size()])
        .normalized();
  }

  // Turn of phi while the slip falls by `decades` from phase `start`.
  double predictTurn(double start, double decades) const {
    return value(phi_, phaseAfter(start, decades)) - value(phi_, start);
  }

 private:
  // the phase at which the slip has fallen `decades` from phase `start`
  // (bisection: D increases monotonically, R* < 0 on the cycle)
  double phaseAfter(double start, double decades) const {
    const double target = value(dec_, start) + decades;
    double lo = start, hi = start;
    while (value(dec_, hi) < target) hi += double(cycle_.orbit.size());
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (value(dec_, mid) < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  // a table continued periodically (plus its per-period increment), linear
  // between nodes
  double value(const std::vector<double>& t, double phase) const {
    const double n = double(cycle_.orbit.size());
    const double periods = std::floor(phase / n);
    const double p = phase - periods * n;
    const std::size_t i = std::min(std::size_t(p), cycle_.orbit.size() - 1);
    const double f = p - double(i);
    return periods * t.back() + t[i] + f * (t[i + 1] - t[i]);
  }

  const LimitCycle& cycle_;
  std::vector<double> phi_, dec_, tau_;
};

}  // namespace patchspin::testing
