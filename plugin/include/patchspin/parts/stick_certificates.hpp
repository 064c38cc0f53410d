// Stick certificates of the exact law (docs/solver.md, Eq. (S14)): quick
// proofs that a friction block sticks, without a block solve. Every
// certificate shows x = lambda0 / L inside the convex hull of points of the
// exact law's unit limit set E (0, law values q(w), and the bicone
// Pi {|(z1, z2)| + |z3| <= 1} that E contains), so a certificate never sticks
// a block that the full solver says slips (stick_certificates_test checks
// this against solveFrictionBlock on seeded random blocks).
#pragma once

#include <patchspin/models.hpp>

namespace patchspin::parts {

// Law values kept for a patch across visits and steps, valid while the law's
// pressure and shape stay (the adapter invalidates them on a refresh).
struct StickCertificates {
  // hull: a law value q(w*) (on E's boundary), its slip w* and the direction
  // of lambda0 / L it was taken for
  Vec3 hullPoint = Vec3::Zero(), hullSlip = Vec3::Zero(), hullDirection = Vec3::Zero();
  bool hullValid = false;
  // where the exact block's last stick test met E's boundary
  // (FrictionBlockResult::gaugeSlip): the next block solve starts there
  Vec3 gaugeSlip = Vec3::Zero();
  // fan: three more law values around fanCentre = q(fanSlip), for
  // fanDirection, and the inverses of [fanCentre, fan[k], fan[k+1]]
  Vec3 fanCentre = Vec3::Zero();
  Vec3 fan[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Mat3 fanInv[3];
  Vec3 fanDirection = Vec3::Zero(), fanSlip = Vec3::Zero();
  bool fanValid = false;

  void invalidate() { hullValid = fanValid = false; }
};

// Whether x = lambda0 / L lies in E, certified by the bicone and one law
// value q* along the ellipsoidal inverse of x's direction, then by the fan.
// piInv: Pi^-1 of `law`; sticking: the block stuck at the end of the last
// step (the fan is built only then); refine: the fan may spend one more law
// value (cleared when that fails, for the rest of the step).
bool exactHullSticks(StickCertificates& certs, const Mat3& piInv, bool sticking,
                     const FrictionPatch& law, const Vec3& lambda0, double L, bool& refine);

// After an exact block solve that stuck: its boundary point along lambda0
// becomes the hull test's q* for the next visits.
void keepGaugePoint(StickCertificates& certs, const Vec3& gaugeSlip, const Vec3& gaugeValue,
                    bool sticking);

}  // namespace patchspin::parts
