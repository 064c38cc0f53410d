// Friction block part (friction_block_part.hpp; docs/solver.md (S7)-(S14)).
#include <patchspin/parts/friction_block_part.hpp>

#include <patchspin/friction_block.hpp>
#include <patchspin/pressure.hpp>

#include <Eigen/Dense>

#include <cmath>

namespace patchspin::parts {
namespace {

// A refresh due while the patch sticks deep inside its limit set is deferred
// when the centre of pressure moved by at most kDeferMove of the diameter
// since the last refresh: Pi then changes by at most ~8 kDeferMove relative,
// far inside the margin 1 - kDeferStick, so the stick test decides as the
// refreshed law would (friction_block_part_test).
constexpr double kDeferMove = 1e-2;
constexpr double kDeferStick = 0.5;

// The quick stick test's measure of x against the law's Pi: |Pi^-1 x| for
// the ellipsoidal law (its exact stick test), the bicone's gauge
// |(z1, z2)| + |z3| for the exact law (a set its limit set contains).  (S13)-(S14)
double quickStickSize(Model model, const Vec3& unitLoad) {
  return model == Model::Ellipsoidal
             ? unitLoad.norm()
             : std::hypot(unitLoad.x(), unitLoad.y()) + std::abs(unitLoad.z());
}

const Mat3& piInverse(PressureRecord& law, const FrictionPatch& friction) {
  if (!law.piInvValid) {
    law.piInv = friction.Pi().inverse();
    law.piInvValid = true;
  }
  return law.piInv;
}

}  // namespace

Vec3 solveFrictionVelocity(FrictionBlockState& fb, FrictionPatch& friction,
                           StickCertificates& certs, const PatchOutlineSummary& shape,
                           const PatchBlocks& k, bool interior, const Vec3& s, const Vec3& lamFIn,
                           const Vec3& lamN, int held, const FrictionPartSettings& settings,
                           FrictionPartCounters& counters, bool& refreshed) {
  const double L = fb.mu * lamN[0];
  refreshed = false;
  if (!(L > 0.0)) return Vec3::Zero();
  try {
    const Mat3& K = interior ? k.Ks : k.Kff;
    FrictionBlockInput in;
    in.b = s - K * lamFIn;
    in.K = K;
    in.L = L;
    if (fb.model == Model::Exact) in.warmGauge = certs.gaugeSlip;
    in.tolerance = settings.blockTolerance;
    // the law's pressure: the linear pressure of Eq. (94) carrying the
    // loads, or the nearest admissible one where that would be negative
    // (DESIGN item 2), refreshed only when the centre of pressure (Ty, -Tx) /
    // Pz has moved by more than the refresh tolerance of the diameter (S7)
    const PatchLoads raw = toLoads(lamN);
    const Vec2 cop(raw.Ty / raw.Pz, -raw.Tx / raw.Pz);
    const double moved = (cop - fb.law.pressureCop).norm() / shape.diameter;
    // lambda0 = -K^-1 b, the impulse that stops the slip, and its quick-test size
    auto stickSize = [&](Vec3& lambda0) {
      const Mat3& piInv = piInverse(fb.law, friction);
      lambda0 = -(interior ? Vec3(k.KsInv * in.b) : Vec3(k.Kff.inverse() * in.b));
      const Vec3 unitLoad = piInv * lambda0;
      const double size = quickStickSize(fb.model, unitLoad);
      return lambda0.allFinite() && unitLoad.allFinite() ? size : INFINITY;
    };
    // (computed once per visit unless a refresh changes Pi in between)
    Vec3 lambda0;
    double size = NAN;
    const bool stuckBefore = fb.stateSticking || (fb.haveLast && fb.lastSticking);
    bool refreshDue = moved > (fb.refreshes == 0 ? settings.pressureRefreshTolerance
                                                 : settings.pressureLagTolerance);
    if (refreshDue && settings.deferStickingRefresh && moved <= kDeferMove && stuckBefore) {
      size = stickSize(lambda0);
      if (size <= kDeferStick * L) {
        refreshDue = false;
        ++counters.deferredRefreshes;
      }
    }
    if (refreshDue) {
      ++counters.pressureRefreshes;
      ++fb.refreshes;
      PatchLoads loads = raw;
      // a disk's linear pressure is >= 0 iff the centre of pressure lies in
      // its kern, |cop - C| <= I / (A R) = R / 4; for a polygon the test is
      // nearestAdmissibleLoads' own first step
      if (!shape.disk || (cop - shape.centre).squaredNorm() > 0.0625 * shape.radius * shape.radius)
        loads = nearestAdmissibleLoads(friction.shape(), loads, fb.rho);
      friction.setLoads(PatchLoads{loads.Pz / fb.dt, loads.Tx / fb.dt, loads.Ty / fb.dt});
      fb.law.pressureCop = cop;
      fb.law.piInvValid = false;
      certs.invalidate();
      refreshed = true;
      size = NAN;
    }
    // a slipping block whose input has not changed since its last solve
    // keeps that solution without the quick test (which would fail again)
    const bool reuseSlip = fb.haveLast && !refreshed && !fb.lastSticking && held == fb.lastHeld &&
                           (in.b - fb.lastB).norm() <= settings.reuseTolerance * in.b.norm() &&
                           std::abs(L - fb.lastL) <= settings.reuseTolerance * L;
    bool quick = false;
    if (settings.quickStick && !(reuseSlip && !fb.stateSticking)) {
      if (std::isnan(size)) size = stickSize(lambda0);
      if (std::isfinite(size) &&
          (size <= L || (fb.model == Model::Exact && stuckBefore &&
                         exactHullSticks(certs, fb.law.piInv, fb.stateSticking, friction, lambda0,
                                         L, fb.fanRefine)))) {
        quick = true;
        ++counters.quickSticks;
        fb.lastImpulse = lambda0;
        fb.lastSlip.setZero();
        fb.lastSticking = true;
        fb.haveLast = true;
        fb.lastHeld = held;
        fb.lastB = in.b;
        fb.lastL = L;
      }
    }
    if (!quick && !reuseSlip) {
      ++counters.blockSolves;
      // the exact block's warm start (its direction only): where the block
      // slipped at its last solution and the impulse so far moves the slip by
      // at most kWarmFromS of it, the slip s = b + K lamF itself, one
      // fixed-point step s -> b + K L q(s^) on from that solution and closer to
      // the answer than its slip by |K| L |dq/ds| (a slipping coin: 1.7 law
      // evaluations with the Jacobian per solve instead of 2); elsewhere (in a
      // pile, an impulse that reverses or cancels the slip) that solution's
      // slip (docs/notes/2026-11-29-exact-solve-evaluations.md)
      constexpr double kWarmFromS = 0.5;
      const bool warmFromS = fb.model == Model::Exact && fb.warmSlip.norm() > 0.0 &&
                             (s - in.b).norm() <= kWarmFromS * s.norm();
      in.warmSlip = warmFromS ? s : fb.warmSlip;
      if (fb.model == Model::Exact) in.piInverse = &piInverse(fb.law, friction);
      const FrictionBlockResult solved = solveFrictionBlock(friction, fb.model, in);
      fb.lastImpulse = solved.impulse;
      fb.lastSlip = solved.slip;
      fb.lastSticking = solved.sticking;
      if (fb.model == Model::Exact)
        keepGaugePoint(certs, solved.gaugeSlip, solved.gaugeValue, solved.sticking);
      fb.haveLast = true;
      fb.lastHeld = held;
      fb.lastB = in.b;
      fb.lastL = L;
    }
    fb.sticking = fb.lastSticking;
    fb.warmSlip = fb.lastSlip;
    return fb.lastImpulse;
  } catch (const Error&) {
    // the law or the block refused its input (e.g. the pressure of a patch
    // at the edge of double range): the impulse stays as it was
    ++counters.blockErrors;
    fb.failed = true;
    return lamFIn;
  }
}

bool frictionCanTake(FrictionBlockState& fb, const FrictionPatch& law, const Vec3& lamN,
                     const Vec3& lamF, const Vec6& ds) {
  const Vec3 lamS = lamF + ds.tail<3>();
  const double Ls = fb.mu * (lamN[0] + ds[0]);
  const Vec3 z = piInverse(fb.law, law) * lamS;
  return quickStickSize(fb.model, z) <= Ls;
}

}  // namespace patchspin::parts
