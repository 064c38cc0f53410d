// The friction block's solvers after validation and scaling (friction_block.cpp
// dispatches to them). Private to patchspin::core (not installed).
#pragma once

#include <patchspin/friction_block.hpp>

namespace patchspin::internal {

// Newton iterations stop when the residual is below this fraction of the
// problem's own slip scale |b| + L |K|: ~100 ulps, well below any physical
// effect yet reachable in double precision.
constexpr double kRelativeTolerance = 1e-14;
// Cap on every iteration loop; the blocks converge in a few steps.
constexpr int kMaxIterations = 100;
// A slip is resolved (its direction, hence the law at it, known) where |s|
// exceeds this fraction of the block's slip scale: the Newton tolerance
// leaves 1e-14 of it, magnified by the law's sensitivity, up to 1e5 at the
// lever domain's ends (as the step fuzz target checks it).
constexpr double kResolvedSlip = 1e-2;

// Ellipsoidal law q(w) = -Pi w: stick iff |A^-1 b| <= 1 (A = L K Pi), else the
// root r > 0 of |(r I + A)^-1 b| = 1 (ellipsoidal_block.cpp).
FrictionBlockResult solveEllipsoidal(const Mat3& Pi, const FrictionBlockInput& in);

// Exact law: the gauge stick test along -K^-1 b, then the minimum of the slip
// potential D(s) by safeguarded Newton (exact_block.cpp). plainCondition
// receives |K|_F |K^-1|_F of K's symmetric part before any slip is returned.
FrictionBlockResult solveExact(const FrictionPatch& patch, const FrictionBlockInput& in,
                               double* plainCondition);

// The exact block of a patch smaller than kRecentreBelow rho, solved about the
// patch's centre and moved back to O (exact_block_recentred.cpp). False where
// the patch is not that small or the recentred block is refused.
bool solveExactRecentred(const FrictionPatch& patch, const FrictionBlockInput& in,
                         FrictionBlockResult& out);

// An exact slip with K's plain condition (times max(1, lever, 1 / lever)) of
// kVerifyCondition or more is returned only if it is the law at its own slip
// and does not gain kinetic energy; throws Error otherwise (exact_block.cpp).
FrictionBlockResult requireVerifiedExactSlip(const FrictionPatch& patch,
                                             const FrictionBlockInput& in,
                                             const FrictionBlockResult& r, double cond);

}  // namespace patchspin::internal
