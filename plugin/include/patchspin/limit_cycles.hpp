// Periodic orbits (limit cycles) of the fast dynamics on the sphere of slip
// directions, Eq. (26)-(27), (103)-(104) at r -> 0, psi = 0:
//
//   w' = V*(w) = (I - w w^T) F_o(w),     r' = r R*(w),   R*(w) = w . F_o(w),
//
// with ' = d/dtau and the fast time tau of Eq. (26), dt = r dtau. F_o is
// FlatBodyModel::limitField [m/s^2], so tau is in s^2/m and V* in m/s^2.
// Poincare-Bendixson on S^2: an orbit that reaches no attracting fixed point
// approaches a cycle (or a polycycle); findLimitCycles finds the cycles that
// seeds reach, forward (attracting) and backward in tau (repelling).
//
// Quantities of a cycle of period T (tau), traversed forward:
//  * Floquet multiplier m = P'(sigma*), the derivative of the return map P
//    of a section through the cycle (m < 1: attracting). For a flow on a
//    surface (Liouville's formula on the cycle) m = exp(oint div V* dtau)
//    with the surface divergence div V* = tr(E^T D E) - 2 R* = tr D -
//    w.D w - 2 R*, D = dF_o/dw, E a tangent basis (the projected Jacobian
//    (31) traced). `multiplier` is that integral (RK4 quadrature along the
//    cycle, relative error < 1e-6 at T/400 per step); `returnMapSlope` is
//    P' from the variational equation and the section, whose absolute
//    error is ~1e-8 at that step for the cycle (and grows with the
//    period: 1e-5 at T = 26 s^2/m, F / (mu m g) = 0.13): the flow component
//    of the variation, O(1), is projected out. They agree where m >> 1e-8; the thick disk's
//    cycle (issue 34) has m = 2.0e-12, where only the first resolves it
//    (the slope converges to it as the step is refined 32-fold).
//  * mean rate <R*> = (1/T) oint R* dtau [m/s^2]: ln r falls by T |<R*>| per
//    period, since (ln r)' = R* (27); over the cycle r-dot = R* on average
//    in tau, the slip's rate of decay as the body comes to rest.
//  * turning rate of the velocity direction per decade of slip: with phi =
//    atan2(w2, w1) the direction of the slip velocity u of O (ground axes at
//    psi = 0; the heading changes by O(r) and is frozen as r -> 0),
//      Gamma = Delta phi / (-Delta log10 r) = -ln(10) Delta phi / (T <R*>)
//    [rad per decade], Delta phi = oint dphi over one period (2 pi times the
//    winding number of (w1, w2) about 0). Over k periods phi turns k Delta
//    phi while log10 r falls k T |<R*>| / ln 10, exactly (w returns to
//    itself), so Gamma is the asymptotic turning per decade as r -> 0.
//    Gamma > 0: counter-clockwise about the patch normal z.
//  * slip ratio v / (R omega) = rho sqrt(1 - w3^2) / (R |w3|), v = |u|,
//    omega = r w3 / rho, R = PatchShape::maxDistanceFromOrigin() (the radius
//    of a disk centred at O); +inf where the cycle crosses w3 = 0.
// Guarded by tests/core/limit_cycles_test.cpp against an independent RK4
// integrator of the fast dynamics with a brute-force quadrature of (16).
#pragma once

#include <patchspin/analysis.hpp>
#include <vector>

namespace patchspin {

struct LimitCycle {
  Vec3 point = Vec3::Zero();        // a point of the cycle (on its Poincare section)
  std::vector<Vec3> orbit;          // kCycleSamples points along one period, forward in tau
  double period = 0.0;              // T in the fast time tau [s^2/m]
  double multiplier = 0.0;          // Floquet multiplier exp(oint div V* dtau), forward [-]
  double returnMapSlope = 0.0;      // P'(sigma*) forward, variational (abs. error >= 1e-8) [-]
  bool attracting = false;          // multiplier < 1 (on the sphere, forward in tau)
  double w3Min = 0.0, w3Max = 0.0;  // extent of w3 on the cycle (parabolic vertex) [-]
  double slipRatioMin = 0.0;        // min and max of v / (R omega) on the cycle [-]
  double slipRatioMax = 0.0;
  double meanRdot = 0.0;       // <R*> = (1/T) oint R* dtau [m/s^2]
  double turn = 0.0;           // Delta phi per period, forward [rad]
  double turnPerDecade = 0.0;  // Gamma = -ln(10) turn / (T <R*>) [rad per decade of r]
  double residual = 0.0;       // |P(sigma*) - sigma*| at the last Newton iterate [rad]
};

// Where the orbit from one seed ends (forward: attractors; backward in tau:
// repellers).
struct SeedEnd {
  enum Kind { FixedPoint, Cycle, Continuum, Unresolved };
  Vec3 seed = Vec3::Zero();
  Kind kind = Unresolved;
  // into LimitAnalysis::directions, CycleAnalysis::cycles or LimitAnalysis::continua
  int index = -1;
  Vec3 last = Vec3::Zero();  // w at the end of the run
};

struct CycleAnalysis {
  std::vector<LimitCycle> cycles;  // attracting and repelling, deduplicated
  std::vector<SeedEnd> forward;    // one per seed, forward in tau
  std::vector<SeedEnd> backward;   // one per seed, backward in tau (empty if not run)
  // seeds whose orbit reached no reported attractor (forward) or repeller
  // (backward) within the budget: a polycycle, a cycle Newton did not
  // resolve, or a budget too short
  std::vector<Vec3> unresolvedForward;
  std::vector<Vec3> unresolvedBackward;
  double fieldScale = 0.0;  // max |F_o| over the seeds [m/s^2]; 1 / fieldScale is the unit of tau
  // false: no search (F_o = 0, or every direction a fixed point); the
  // lists above are then empty. A circle of fixed points (a free
  // axisymmetric body's pure sliding) does not stop the search: a seed that
  // closes on it ends there (SeedEnd::Continuum), and a cycle can still
  // surround a pole (LimitCycles.FreeThickDiskCurlsOnACircleOfLatitude)
  bool searched = false;
  bool complete() const { return unresolvedForward.empty() && unresolvedBackward.empty(); }
};

struct CycleOptions {
  int seeds = 64;          // fibonacciSphere seeds (an even count: no seed on w3 = 0)
  bool backward = true;    // also integrate backward in tau (repelling cycles, sources)
  double budget = 4000.0;  // fast time per seed and direction, in units of 1 / fieldScale
};

// Cycles of the fast dynamics of `model`, given its fixed points `fixed`
// (findLimitDirections). Each seed is integrated (RK4, step 0.02 /
// fieldScale) until it comes within 1e-3 rad of a fixed point that attracts
// on the sphere (both Re lambda of (31) < 0; > 0 backward), or of a cycle
// already found, or until its orbit returns to a section through an earlier
// point of it: then Newton on the return map of that section (RK4 at T/400
// per step, with the variational equation for P') resolves the cycle.
// A cycle whose period exceeds 1000 / fieldScale (the recurrence window; near
// a saddle-node born on it the period diverges, cycle_bifurcation.hpp) is not
// resolved: its seeds end unresolved and complete() is false
// (LimitsToolTest.ASearchThatReachesNoAttractorSaysSoWithItsSeeds).
CycleAnalysis findLimitCycles(const FlatBodyModel& model, const LimitAnalysis& fixed,
                              const CycleOptions& options = CycleOptions());

constexpr int kCycleSamples = 400;  // RK4 steps per period in the refinement

}  // namespace patchspin
