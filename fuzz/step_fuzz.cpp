// Fuzz target: the implicit friction block solveFrictionBlock (step.hpp) of
// both laws, with any patch, free slip b, matrix K, bound L and warm start.
//
// Contract: a patchspin::Error (non-finite input, L < 0, K not positive
// definite; the exact block with K's plain condition number (times the
// lever's distance from 1) 1e5 or more,
// where it may refuse a slip it cannot verify; a block outside its domain, step.hpp: pressure
// negative beyond 1e-6 of the mean, lever max|r| / rho outside [1e-5, 1e5], K's diagonal spanning
// more than 1e30, an exact law whose round-off model exceeds 1e-6, which must be refused), or
// finite impulse and slip with
//  * slip = b + K impulse, and slip = 0 when sticking;
//  * the impulse inside the limit set L E:
//      ellipsoidal |impulse| <= L ||Pi||_F,
//      exact       |impulse_xy| <= L ∫|p|/Pz, |impulse_z| <= L ∫|p| r_max / (Pz rho);
//  * when slipping, the law itself: impulse = L q(slip / |slip|);
//  * exact law (maximum dissipation, K SPD): the kinetic energy of the slip
//    does not grow, s^T K^-1 s <= b^T K^-1 b.
#include "fuzz_common.hpp"

#include <patchspin/friction_block.hpp>

#include <Eigen/Dense>

namespace {

using namespace patchspin;
using namespace patchspin::fuzz;
using patchspin::internal::stableMatrixNorm;

// Relative slack of the set bounds and of slip = b + K impulse: round-off of
// a few 3x3 products.
constexpr double kBoundSlack = 1e-9;
// impulse = L q(s^): the solver stops at 1e-14 of the slip scale, so the
// direction of s is known to ~1e-14 scale / |s|; checked where that is below
// kLawSlack / 100 and to kLawSlack (relative to L |q|-scale).
constexpr double kLawSlack = 1e-6;
// Energy: the solver's round-off (1e-14 of the scale) squared into energy.
constexpr double kEnergySlack = 1e-9;

Mat3 takeK(ByteReader& in) {
  const uint8_t mode = in.byte();
  Mat3 K;
  switch (mode % 3) {
    case 0:  // raw
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K(i, j) = in.number();
      return K;
    case 1: {  // A A^T + d I: symmetric positive (semi)definite
      Mat3 A;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(i, j) = in.number();
      return A * A.transpose() + std::abs(in.number()) * Mat3::Identity();
    }
    default:  // diagonal
      K.setZero();
      K.diagonal() = in.vec3();
      return K;
  }
}

bool isSpd(const Mat3& K) {
  if (!K.allFinite() || !K.isApprox(K.transpose(), 0.0)) return false;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(K);
  return es.eigenvalues().minCoeff() > 0.0;
}

// cond of K scaled to a unit diagonal (2-norm): the block refuses K
// above 1e10 in the Frobenius norm (at most 3 times this) as numerically
// singular (its K^-1 would carry more than ~2e-6 relative error)
double scaledCondition(const Mat3& K) {
  const Vec3 d = K.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
  const Mat3 S = d.asDiagonal() * K * d.asDiagonal();
  if (!S.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::SelfAdjointEigenSolver<Mat3> es(S);
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  return lo > 0.0 ? hi / lo : std::numeric_limits<double>::infinity();
}
constexpr double kSingularCondition = 1e10 / 3.0;

// K's plain condition number (2-norm, symmetric part): the exact block may
// refuse a K at or above 1e5 in |K|_F |K^-1|_F (at most 3 times this) times
// max(1, lever, 1 / lever) when it cannot verify its slip against the law
// (step.cpp, requireVerifiedExactSlip); below that it must solve
double plainCondition(const Mat3& K) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(0.5 * (K + K.transpose()));
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  return lo > 0.0 ? hi / lo : std::numeric_limits<double>::infinity();
}
constexpr double kUnverifiedCondition = 1e5 / 3.0;

// The exact unit law's round-off factor over eps times its terms about O
// (step.cpp, requireExactLawDigits): max(1, diameter^2 / A) for the kernel
// integrals' cancellation on a sliver. (Until the eighth round a polygon
// also counted max|r|^2 / A, the round-off of its Pz from area moments
// about O: found, a 23-gon 900 diameters from O whose pure translation gave
// a unit force of 1 + 1.1e-7. Its moments are now summed about the vertex
// mean where O is outside it: item 58.)
double lawRoundOffFactor(const PatchShape& shape) {
  return std::max(1.0, shape.diameter() / shape.area() * shape.diameter());
}

void run(ByteReader& in) {
  const PatchShape shape = takeShape(in);
  const uint8_t mode = in.byte();
  const double mu = in.number(), rho = in.number();
  const double Pz = in.number(), Tx = in.number(), Ty = in.number();
  PatchLoads loads{Pz, Tx, Ty};
  if (mode & 2) loads = nearestAdmissibleLoads(shape, loads, shape.defaultRho());
  const FrictionPatch patch(shape, LinearPressure::fromLoads(shape, loads), mu, rho);
  const Model model = mode & 1 ? Model::Exact : Model::Ellipsoidal;

  FrictionBlockInput input;
  input.b = in.vec3();
  input.L = in.number();
  input.K = takeK(in);
  if (mode & 4) input.warmSlip = in.vec3();
  // (read last: the corpus's earlier inputs keep their meaning)
  if (mode & 8) input.warmGauge = in.vec3();
  // the iterations' stopping tolerance, tighter than the default 1e-14 only
  // (|t| capped at 1e-14; a non-finite t as it is, to be refused): the
  // checks below are set for the default, and a tolerance below what double
  // resolves must still return the law at the slip (found by hand, eleventh
  // round: 1e-18 on a far polygon, 0.027 of L off). Read after the warm
  // gauge; corpus files from before this bit that have it set now read one
  // more number (0, the default, once the bytes run out).
  if (mode & 16) {
    const double t = in.number();
    input.tolerance = std::isfinite(t) ? std::min(std::abs(t), 1e-14) : t;
  }
  const bool finite = input.b.allFinite() && std::isfinite(input.L) && input.K.allFinite() &&
                      input.warmSlip.allFinite() && input.warmGauge.allFinite() &&
                      std::isfinite(input.tolerance);

  note("mu %.17g, rho %.17g, loads (%.17g %.17g %.17g)", mu, rho, loads.Pz, loads.Tx, loads.Ty);
  note("%s, b (%.17g %.17g %.17g), L %.17g, warm (%.17g %.17g %.17g)", toString(model), input.b.x(),
       input.b.y(), input.b.z(), input.L, input.warmSlip.x(), input.warmSlip.y(),
       input.warmSlip.z());
  for (int i = 0; i < 3; ++i)
    note("K (%.17g %.17g %.17g)", input.K(i, 0), input.K(i, 1), input.K(i, 2));
  note("warm gauge (%.17g %.17g %.17g), tolerance %.17g", input.warmGauge.x(), input.warmGauge.y(),
       input.warmGauge.z(), input.tolerance);
  // the block's features, for triage: min p over the mean pressure, the
  // lever max|r| / rho, the spread of K's diagonal, K's unit-diagonal cond
  {
    const double meanP = patch.Pz() / shape.area();
    const Vec3 kd = input.K.diagonal().cwiseAbs();
    double minP = std::numeric_limits<double>::quiet_NaN();
    try {
      minP = minPressure(shape, patch.pressure());
    } catch (const Error&) {
    }
    note("features: minp/mean %.3g, lever %.3g, K spread %.3g, K cond %.3g", minP / meanP,
         shape.maxDistanceFromOrigin() / patch.rho(), kd.maxCoeff() / kd.minCoeff(),
         isSpd(input.K) ? scaledCondition(input.K) : -1.0);
  }
  // the block's domain in the patch (step.hpp): pressure >= 0 to 1e-6 of
  // the mean, lever max|r| / rho in [1e-5, 1e5]. Outside it (beyond
  // kDomainMargin, room for the round-off of min p and of the lever) the
  // block must refuse; inside it (by the margin) it must not refuse for it.
  // min p is recomputed here in long double at the vertices, as
  // p(C) - R |grad p| on a disk, or at an arc region's extreme points, not
  // taken from the core.
  constexpr double kDomainMargin = 1.01;
  constexpr double kNegativePressureTol = 1e-6, kMinLever = 1e-5, kMaxLever = 1e5;
  const double lever = shape.maxDistanceFromOrigin() / patch.rho();
  const double meanPressure = patch.Pz() / shape.area();
  const double lowest = [&] {
    const LinearPressure& p = patch.pressure();
    auto at = [&](const Vec2& v) {
      return double((long double)p.p0 + (long double)p.cx * v.x() + (long double)p.cy * v.y());
    };
    if (shape.isDisk()) return at(shape.centre()) - shape.radius() * std::hypot(p.cx, p.cy);
    double m = std::numeric_limits<double>::infinity();
    if (shape.kind() == PatchShape::Kind::ArcRegion) {
      for (const Vec2& v : arcRegionExtremePoints(shape, p.cx, p.cy)) m = std::min(m, at(v));
      return m;
    }
    for (const Vec2& v : shape.vertices()) m = std::min(m, at(v));
    return m;
  }();
  // and, exact law, its round-off model (below: forceRoundOff) at most
  // 1e-6 of the unit force
  constexpr double kLawNoDigits = 1e-6;
  const double lawNoise = [&] {
    if (model != Model::Exact) return 0.0;
    const LinearPressure& pq = patch.pressure();
    const double rm = shape.maxDistanceFromOrigin();
    const double terms =
        shape.area() * (std::abs(pq.p0) + (std::abs(pq.cx) + std::abs(pq.cy)) * rm);
    return 64.0 * std::numeric_limits<double>::epsilon() * lawRoundOffFactor(shape) * terms /
           std::abs(patch.Pz());
  }();
  // and K's diagonal spanning at most 1e30, where it is positive (a K with
  // a diagonal entry <= 0 is not positive definite: refused for that)
  constexpr double kMaxDiagonalSpan = 1e30;
  const Vec3 kDiagonal = input.K.diagonal();
  const double span =
      kDiagonal.minCoeff() > 0.0 ? kDiagonal.maxCoeff() / kDiagonal.minCoeff() : 1.0;
  // (the Hertz pressure is not fuzzed here: every patch has a linear one)
  const bool outsideDomain =
      lever > kMaxLever * kDomainMargin || lever < kMinLever / kDomainMargin ||
      lowest < -kNegativePressureTol * kDomainMargin * meanPressure ||
      span > kMaxDiagonalSpan * kDomainMargin || lawNoise > kLawNoDigits * kDomainMargin;
  const bool nearDomainEdge =
      !outsideDomain &&
      (lever > kMaxLever / kDomainMargin || lever < kMinLever * kDomainMargin ||
       lowest < -kNegativePressureTol / kDomainMargin * meanPressure ||
       span > kMaxDiagonalSpan / kDomainMargin || lawNoise > kLawNoDigits / kDomainMargin);
  FrictionBlockResult out;
  try {
    out = solveFrictionBlock(patch, model, input);
  } catch (const Error& e) {
    checkErrorMessage(e);
    // refusing is right for bad input, and for K not positive definite
    // (and for magnitudes whose products overflow: kRange; and, exact law,
    // for a numerically singular K: scaledCondition)
    constexpr double kRange = 1e100;
    const double size =
        input.b.stableNorm() + input.L * stableMatrixNorm(input.K) + input.warmSlip.stableNorm();
    const bool moderate = size < kRange && stableMatrixNorm(input.K) < kRange &&
                          stableMatrixNorm(Mat3(input.K.inverse())) < kRange && input.L < kRange;
    // (or a pressure whose unscaled terms c_k dF_k, before 1/Pz, are within
    // 1e8 of overflow: the law's Jacobian refuses those, as in friction_q;
    // found, loads ~1e300 on a 0.5 m disk)
    const LinearPressure& pc = patch.pressure();
    const double pressureTerms =
        shape.area() *
        (std::abs(pc.p0) + (std::abs(pc.cx) + std::abs(pc.cy)) * shape.maxDistanceFromOrigin()) *
        (1.0 + shape.maxDistanceFromOrigin() / patch.rho());
    const bool hugePressure = !(pressureTerms < std::numeric_limits<double>::max() / 1e8);
    const bool singular = isSpd(input.K) && scaledCondition(input.K) >= kSingularCondition;
    const bool unverified =
        model == Model::Exact && isSpd(input.K) &&
        plainCondition(input.K) * std::max({1.0, lever, 1.0 / lever}) >= kUnverifiedCondition;
    if (finite && moderate && !hugePressure && !singular && !unverified && !outsideDomain &&
        !nearDomainEdge && input.L >= 0.0 && isSpd(input.K)) {
      fail("valid block refused (%s): %s", toString(model), e.what());
    }
    return;
  }
  if (!finite) fail("non-finite block input accepted");
  // K positive definite (step.hpp), on every path: its symmetric part at a
  // unit largest entry, with room for the round-off of a nearly singular K
  // (the core decides by leading minors, this by eigenvalues)
  {
    const double kMax = input.K.cwiseAbs().maxCoeff();
    if (kMax > 0.0 && std::isfinite(kMax)) {
      const Mat3 sym = 0.5 * (input.K + input.K.transpose()) / kMax;
      const Eigen::SelfAdjointEigenSolver<Mat3> es(sym);
      constexpr double kIndefinite = 1e-12;
      if (es.eigenvalues().minCoeff() < -kIndefinite * es.eigenvalues().cwiseAbs().maxCoeff() &&
          input.L > 0.0 && !input.b.isZero(0.0)) {
        fail("K not positive definite accepted (eigenvalues %.3g %.3g %.3g of the unit-scaled K)",
             es.eigenvalues()(0), es.eigenvalues()(1), es.eigenvalues()(2));
      }
    }
  }
  if (outsideDomain && finite) {
    fail(
        "block outside the domain accepted: lever %.17g, min p %.17g of the mean, K's diagonal "
        "spans %.17g, "
        "law round-off %.3g",
        lever, lowest / meanPressure, span, lawNoise);
  }
  if (input.L < 0.0) fail("L = %.17g accepted", input.L);
  checkFinite(out.impulse, "block impulse");
  checkFinite(out.slip, "block slip");
  note("impulse (%.17g %.17g %.17g), slip (%.17g %.17g %.17g), sticking %d", out.impulse.x(),
       out.impulse.y(), out.impulse.z(), out.slip.x(), out.slip.y(), out.slip.z(),
       int(out.sticking));
  if (out.sticking && !out.slip.isZero(0.0)) fail("sticking with nonzero slip");
  // the stick test's boundary point, where located: a unit slip and a finite law value
  if (!out.gaugeSlip.isZero(0.0)) {
    checkFinite(out.gaugeValue, "gauge value");
    if (!(std::abs(out.gaugeSlip.norm() - 1.0) < 1e-12)) fail("gauge slip not a unit vector");
  }

  // slip = b + K impulse
  // (plus the rounding of slip and impulse to the denormal grid, half a step
  // per entry, the impulse's through K; found: b of denormals against
  // K_xx = 3.8e146, where K^-1 b = 0 in x)
  const double slipScale =
      input.b.stableNorm() + stableMatrixNorm(input.K) * out.impulse.stableNorm();
  const double slipDenormals =
      4.0 * std::numeric_limits<double>::denorm_min() * (1.0 + stableMatrixNorm(input.K));
  if (Vec3(out.slip - input.b - input.K * out.impulse).stableNorm() >
      kBoundSlack * slipScale + slipDenormals) {
    fail("slip != b + K impulse");
  }
  if (input.L == 0.0) {
    if (!out.impulse.isZero(0.0)) fail("impulse without normal impulse");
    return;
  }

  // the limit set
  const double L = input.L;
  const double absRatio = absPressureIntegral(shape, patch.pressure(), patch.Pz()) / patch.Pz();
  const double rmax = shape.maxDistanceFromOrigin();
  const double unitScale = model == Model::Ellipsoidal ? stableMatrixNorm(patch.Pi())
                                                       : absRatio * (1.0 + rmax / patch.rho());
  // The exact unit law's own round-off: it sums the pressure's terms about
  // O, each up to A |c_k| max|r|^k / Pz (times the lever for the torque),
  // and a sliver's kernel integrals cancel by diameter^2 / A, as in
  // friction_q (kTermsUlps there). Negligible unless the pressure cancels.
  // Found: a 1e-8 m x 0.5 m sliver with p0 = 2.6e16 and cx = -5.1e16 for
  // Pz = 0.92 (terms / Pz = 3e8): q(w) changed by 40% between w and
  // w (1 + 1e-12) and its torque left the bound, so no slip could be
  // consistent with it (the core accepts such pressures: the open friction_q
  // finding)
  constexpr double kTermsUlps = 64.0;
  const LinearPressure& pq = patch.pressure();
  const double termsA =
      shape.area() * (std::abs(pq.p0) + (std::abs(pq.cx) + std::abs(pq.cy)) * rmax);
  const double forceRoundOff = kTermsUlps * std::numeric_limits<double>::epsilon() *
                               lawRoundOffFactor(shape) * termsA / std::abs(patch.Pz());
  const double lawRoundOff = forceRoundOff * (1.0 + rmax / patch.rho());
  note("law round-off model: %.3g of the set", lawRoundOff / unitScale);
  // (plus the rounding of the impulse to the denormal grid: each of its
  // three entries, and of L q, is off by up to half a denormal step; found,
  // L = 5e-324 gave a law error of 1 denormal against 3, and a torque of 1
  // denormal against a bound that rounded to 0)
  const double denormalRounding = 4.0 * std::numeric_limits<double>::denorm_min();
  if (model == Model::Ellipsoidal) {
    if (out.impulse.stableNorm() > L * unitScale * (1.0 + kBoundSlack) + denormalRounding) {
      fail("ellipsoidal impulse %.17g outside L |Pi| = %.17g", out.impulse.stableNorm(),
           L * unitScale);
    }
  } else {
    if (std::hypot(out.impulse.x(), out.impulse.y()) > L * absRatio * (1.0 + kBoundSlack) +
                                                           kBoundSlack * L * unitScale +
                                                           L * forceRoundOff + denormalRounding) {
      fail("exact impulse force %.17g outside L ∫|p|/Pz = %.17g",
           std::hypot(out.impulse.x(), out.impulse.y()), L * absRatio);
    }
    // (the unit bounds first, then times L: with a denormal L, L ∫|p|/Pz
    // times max|r| lost every digit or underflowed to 0 before the lever
    // was applied; found, L = 1.9e-317 on a 1e-8 m patch with rho = 1e-8,
    // where the core's torque L q_z = 0.18 L was inside the set)
    if (std::abs(out.impulse.z()) > L * (absRatio * lever) * (1.0 + kBoundSlack) +
                                        kBoundSlack * L * unitScale + L * (forceRoundOff * lever) +
                                        denormalRounding) {
      fail("exact impulse torque %.17g outside its bound", std::abs(out.impulse.z()));
    }
  }

  // slipping: the impulse is the law at the slip direction
  const double s = out.slip.stableNorm();
  const double scale = input.b.stableNorm() + L * stableMatrixNorm(input.K) * unitScale;
  // where the law itself has digits (lawRoundOff above)
  const bool lawHasDigits =
      model == Model::Ellipsoidal || lawRoundOff < kLawSlack / 100.0 * unitScale;
  // (and where the slip's direction survives its rounding to the denormal
  // grid, half a step per entry: found, b and K of denorm_min against L =
  // 0.5 solve at unit scale to a slip (1, 1, 0.4), which rounds to (1, 1, 0)
  // denormal steps; its direction, and the law at it, are lost)
  const bool slipResolved = std::numeric_limits<double>::denorm_min() < kLawSlack / 100.0 * s;
  if (!out.sticking && s > 1e4 * kLawSlack * scale && slipResolved && isSpd(input.K) &&
      lawHasDigits) {
    const Vec3 q = patch.unitQ(model, out.slip);
    if ((out.impulse - L * q).stableNorm() > kLawSlack * L * unitScale + denormalRounding) {
      fail("%s slip: impulse != L q(s^), error %.3g of %.3g", toString(model),
           (out.impulse - L * q).stableNorm(), L * unitScale);
    }
  }

  // maximum dissipation: the slip's kinetic energy does not grow (for a
  // pressure >= 0 on the patch: with negative parts the exact law is not a
  // maximum-dissipation law and friction may feed energy in; found, a 1e-8 m
  // disk with min p = -1.3e16 and Pz = 1e-8)
  // (and only where the law has digits: a law that is round-off noise is no
  // maximum-dissipation law either; found, the sliver above with
  // terms / Pz = 3e10 gained energy 4e-16 -> 2.7)
  if (model == Model::Exact && isSpd(input.K) && lawHasDigits &&
      minPressure(shape, patch.pressure()) >= 0.0) {
    const Eigen::LLT<Mat3> llt(input.K);
    const double e0 = input.b.dot(llt.solve(input.b)), e1 = out.slip.dot(llt.solve(out.slip));
    if (std::isfinite(e0) &&
        e1 > e0 * (1.0 + kEnergySlack) + kEnergySlack * scale * scale / stableMatrixNorm(input.K)) {
      fail("exact block gains energy: %.17g -> %.17g", e0, e1);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput(data, size, run);
}
