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
using patchspin::internal::stableMatrixNorm;

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
  // (friction with the pressure's own size, mu ∫|p| (1 + max|r| / rho), not
  // mu Pz: found, couples about x of 6.8e283 on a 0.5 m disk make a
  // pressure, hence a field, of ~1e283 where mu Pz |M^-1| = 1.9)
  const LinearPressure rest = [&] {
    const Vec3 c = flat.contactAtRest(Vec3::Zero(), loads).pressure;
    return LinearPressure{c[0], c[1], c[2]};
  }();
  const double rmax = shape.maxDistanceFromOrigin();
  const double absP =
      shape.area() * (std::abs(rest.p0) + (std::abs(rest.cx) + std::abs(rest.cy)) * rmax);
  const double scale = body.mu * std::max(std::abs(loads.force.z()), absP) *
                           (1.0 + rmax / flat.rho()) * stableMatrixNorm(Minv) +
                       Vec3(Minv * flat.externalWrench(loads)).stableNorm();
  note("field scale %.17g", scale);
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
      fail("direction (%.17g %.17g %.17g) is no fixed point: |V*| = %.3g, scale %.3g", d.w.x(),
           d.w.y(), d.w.z(), off, scale);
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

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput(data, size, run);
}
