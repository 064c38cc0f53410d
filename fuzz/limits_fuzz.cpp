// Fuzz target: the limit-direction solver findLimitDirections (analysis.hpp)
// for a flat body with any patch, mass, inertia, centre of mass, mu, gravity,
// force, couple and rho, both laws. The sphere solver's seed count is kept at
// its minimum (20) so that one input runs well under a second.
//
// Contract: a patchspin::Error, or finite output: every direction a unit
// vector with finite rate, eigenvalues, residual and pressure, and a fixed
// point of the limit field F_o (98): |F_o(w) - (w . F_o) w| small against
// the field's scale mu Pz |M^-1| + |M^-1 Q_e|; every continuum a unit
// normal with |offset| <= 1.
#include "fuzz_common.hpp"

#include <patchspin/analysis.hpp>

namespace {

using namespace patchspin;
using namespace patchspin::fuzz;

// Fixed points are polished to 1e-11 of the field scale (kResidualTol in
// analysis_limits.cpp); the eigenvector branch (c = 0) takes singular values
// below 1e-7 of the scale as zero: 1e-6 leaves room for both.
constexpr double kFixedPointSlack = 1e-6;
// |w| = 1 to round-off.
constexpr double kUnitSlack = 1e-12;

void run(ByteReader& in) {
  const PatchShape shape = takeShape(in);
  FlatBody body;
  body.shape = shape;
  const uint8_t mode = in.byte();
  body.mass = in.number();
  body.Jz = in.number();
  if (mode & 2) {
    body.Jxz = in.number();
    body.Jyz = in.number();
  }
  body.com = in.vec3();
  body.mu = in.number();
  body.g = in.number();
  body.force = in.vec2();
  body.torque = in.vec3();
  if (mode & 4) body.rho = in.number();
  const Model model = mode & 1 ? Model::Exact : Model::Ellipsoidal;
  note("%s, m %.17g, Jz %.17g, Jxz %.17g, Jyz %.17g, com (%.17g %.17g %.17g), mu %.17g, g %.17g",
       toString(model), body.mass, body.Jz, body.Jxz, body.Jyz, body.com.x(), body.com.y(),
       body.com.z(), body.mu, body.g);
  note("force (%.17g %.17g), torque (%.17g %.17g %.17g), rho %.17g", body.force.x(), body.force.y(),
       body.torque.x(), body.torque.y(), body.torque.z(), body.rho);
  const FlatBodyModel flat(body, model);

  // scale of the limit field (as the solver's own fieldScale)
  const BodyLoads loads = flat.bodyLoads();
  const Mat3 Minv = flat.massMatrix().inverse();
  const double scale = body.mu * std::abs(loads.force.z()) * Minv.stableNorm() +
                       Vec3(Minv * flat.externalWrench(loads)).stableNorm();
  note("field scale %.17g", scale);
  // EXCLUDED (fuzz/README.md): fields below 1e-290, near the smallest normal
  // double (e.g. mu = g = 5e-324). There every direction is a fixed point to
  // round-off and the solver collects thousands of them, deduplicated in
  // quadratic time: 5 s to 150 s per input under the fuzzer, an open finding
  // (the limit directions of a vanishing field carry no information)
  constexpr double kDenormalField = 1e-290;
  if (!(scale >= kDenormalField) && std::isfinite(scale)) return;
  // EXCLUDED as well: friction below the round-off of the field (mu |Pz|
  // |M^-1| < 1e-14 of the scale, e.g. mu = 5e-324 against a force 1e300):
  // the field is the external load alone, the same in every direction, and
  // the solver degenerates the same way (15 s per input, open)
  // And fields above 1e200 (e.g. g = 1e300 with a force of 1e223): the
  // solver's products overflow and it runs to its iteration limits, 14 s per
  // input (open); only finiteness was checked there anyway (kModerate)
  constexpr double kHugeField = 1e200;
  if (!(scale <= kHugeField)) return;
  constexpr double kNegligibleFriction = 1e-14;
  if (body.mu * std::abs(loads.force.z()) * Minv.stableNorm() < kNegligibleFriction * scale) return;

  LimitOptions options;
  options.seeds = 20;
  options.sphereSolver = (mode & 8) != 0;
  const LimitAnalysis result = findLimitDirections(flat, options);
  // the fixed-point identity is checked for field scales inside kModerate,
  // away from the ends of double's range (found: at scale 1e-301 the polish
  // works on denormals); outside it, finiteness only
  constexpr double kModerate = 1e100;
  const bool moderate = scale < kModerate && scale > 1.0 / kModerate;
  for (const LimitDirection& d : result.directions) {
    checkFinite(d.w, "limit direction");
    if (std::abs(d.w.norm() - 1.0) > kUnitSlack) fail("limit direction not a unit vector");
    checkFinite(d.rdot, "rdot");
    checkFinite(d.residual, "residual");
    checkFinite(d.minPressure, "minPressure");
    if (!d.eigenvalues.allFinite()) fail("eigenvalues not finite");
    if (!moderate) continue;
    const Vec3 F = flat.limitField(d.w);
    checkFinite(F, "limit field");
    const double off = (F - d.w.dot(F) * d.w).stableNorm();
    if (off > kFixedPointSlack * scale + std::numeric_limits<double>::min()) {
      fail("direction (%.17g %.17g %.17g) is no fixed point: |V*| = %.3g, scale %.3g", d.w.x(), d.w.y(),
           d.w.z(), off, scale);
    }
  }
  for (const LimitContinuum& c : result.continua) {
    checkFinite(c.normal, "continuum normal");
    checkFinite(c.offset, "continuum offset");
    checkFinite(c.rdot, "continuum rdot");
    if (std::abs(c.normal.norm() - 1.0) > kUnitSlack || std::abs(c.offset) > 1.0 + kUnitSlack) {
      fail("continuum with |n| = %.17g, offset %.17g", c.normal.norm(), c.offset);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return runInput(data, size, run); }
