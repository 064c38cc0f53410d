// Friction block part: one patch's 3-DOF friction block inside the solver
// iterations (DESIGN item 4; docs/solver.md, Eqs. (S7)-(S14)). It computes
// the block's accumulated impulse; the caller applies the change, so that a
// coupled clamp (a stacked patch's support) can refuse it first.
//
// Per visit: the pressure refresh policy (the law follows the normal block's
// centre of pressure), the quick stick test, reuse of the last solution while
// the input stays put, else solveFrictionBlock (friction_block.hpp).
#pragma once

#include <patchspin/models.hpp>
#include <patchspin/parts/normal_block.hpp>
#include <patchspin/parts/patch_blocks.hpp>
#include <patchspin/parts/stick_certificates.hpp>

namespace patchspin::parts {

// The policy's settings (the Bullet adapter's PatchSolverSettings document
// the first four).
struct FrictionPartSettings {
  double pressureRefreshTolerance = 1e-6;  // of the diameter
  double pressureLagTolerance = 1e-3;      // of the diameter, second and later refreshes in a step
  bool quickStick = true;
  bool deferStickingRefresh = true;
  // relative residual at which a block solve stops (FrictionBlockInput::tolerance)
  double blockTolerance = 0.0;
  // a slipping block whose (b, L) changed by less than this, relative, since
  // its last solve keeps that solution
  double reuseTolerance = 1e-12;
};

// Work done, summed over visits (PatchSolverStats has the same names).
struct FrictionPartCounters {
  long blockSolves = 0;
  long pressureRefreshes = 0;
  long deferredRefreshes = 0;
  long quickSticks = 0;
  long blockErrors = 0;
};

// The law's pressure as the visits know it: refreshed with the centre of
// pressure pressureCop (patch frame [m]); piInv = Pi^-1 while piInvValid.
struct PressureRecord {
  Vec2 pressureCop = Vec2::Zero();
  bool piInvValid = false;
  Mat3 piInv = Mat3::Identity();
};

// One patch's friction block within a step.
struct FrictionBlockState {
  Model model = Model::Ellipsoidal;
  double mu = 0.0, rho = 0.0, dt = 0.0;  // [-], [m], [s]
  bool stateSticking = false;            // the block stuck at the end of the last step
  bool sticking = false;                 // ... at its last visit
  bool failed = false;                   // the law or block refused its input in this step
  bool fanRefine = true;                 // the stick certificates may refine (until that fails)
  int refreshes = 0;                     // pressure refreshes in this step
  Vec3 warmSlip = Vec3::Zero();          // slip of the last solution (or the last step's)
  // the last solve of this step, reused while its input stays put
  bool haveLast = false;
  int lastHeld = 0;  // the support hold it was solved with (0 none, 1 normal, 2 all)
  double lastL = 0.0;
  Vec3 lastB = Vec3::Zero();
  Vec3 lastImpulse = Vec3::Zero(), lastSlip = Vec3::Zero();
  bool lastSticking = false;
  PressureRecord law;
};

// The block's new accumulated impulse for the slip s (friction DOFs, with
// the normal block's change already in), the accumulated impulses lamF and
// lamN, and K = Ks (interior) or Kff. `law` is the patch's friction law,
// refreshed here when its pressure is due; `refreshed` says so. L = mu lamN_z
// <= 0 gives zero. On Error from the law or the block: lamF unchanged,
// state.failed set, counted.                                         (S7)-(S14)
Vec3 solveFrictionVelocity(FrictionBlockState& state, FrictionPatch& law, StickCertificates& certs,
                           const PatchOutlineSummary& outline, const PatchBlocks& k, bool interior,
                           const Vec3& s, const Vec3& lamF, const Vec3& lamN, int held,
                           const FrictionPartSettings& settings, FrictionPartCounters& counters,
                           bool& refreshed);

// Whether the block keeps its impulse inside the quick test's set (L Pi B,
// or the exact law's bicone) after taking the share ds of a stacked patch.
bool frictionCanTake(FrictionBlockState& state, const FrictionPatch& law, const Vec3& lamN,
                     const Vec3& lamF, const Vec6& ds);

}  // namespace patchspin::parts
