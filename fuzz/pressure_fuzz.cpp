// Fuzz target: the linear pressure from loads (LinearPressure::fromLoads,
// loadsOf, minPressure, isAdmissible, nearestAdmissibleLoads) on any patch.
//
// Contract: a patchspin::Error (non-finite loads, rho <= 0, bad shape), or
//  * fromLoads: finite coefficients that carry the loads back (loadsOf) to
//    the round-off of solving Eq. (94), i.e. eps times cond(G);
//  * minPressure: finite, at most the mean Pz / A (= p at the centroid) and
//    at most p at every vertex (polygons) or rim sample (disks);
//  * isAdmissible: agrees with minPressure against its own tolerance;
//  * nearestAdmissibleLoads: finite and admissible; zero for Pz <= 0; the
//    loads themselves when admissible; and no farther (in its metric) than
//    two admissible candidates, the zero load and the uniform pressure with
//    the same Pz.
#include "fuzz_common.hpp"

#include <Eigen/Dense>

namespace {

using namespace patchspin;
using namespace patchspin::fuzz;

constexpr double kPi = 3.14159265358979323846;
// Round-off of solving the 3x3 system (94) by the cached explicit inverse of
// G (cofactors, not backward stable): up to a few thousand ulps times cond(G)
// (fuzzing measured 1300 at cond 2e14; at cond 8e7 the error was already 40
// times eps cond 8192, so the check is made for cond(G) < 1e4 only).
constexpr double kSolveSlack = 8192.0 * std::numeric_limits<double>::epsilon();
// Relative slack of the pressure bounds: sums of three products.
constexpr double kPressureSlack = 1e-12;
// Admissibility of the projection: isAdmissible's relative tolerance (of the
// mean pressure). The projection works in load space, so its round-off grows
// with cond(G) (fuzzing measured 2e-7); nearestAdmissibleLoads itself
// verifies its result to 1e-6 and throws otherwise.
constexpr double kProjectionSlack = 1e-6;
// The projection is no farther than the candidates, to its own round-off.
constexpr double kDistanceSlack = 1e-9;

double conditionOf(const Mat3& G) {
  const Eigen::JacobiSVD<Mat3> svd(G);
  const Vec3 s = svd.singularValues();
  return s[2] > 0.0 ? s[0] / s[2] : std::numeric_limits<double>::infinity();
}

void run(ByteReader& in) {
  const PatchShape shape = takeShape(in);
  const double Pz = in.number(), Tx = in.number(), Ty = in.number();
  const PatchLoads loads{Pz, Tx, Ty};
  const bool finiteLoads = std::isfinite(Pz) && std::isfinite(Tx) && std::isfinite(Ty);
  const double A = shape.area();

  // fromLoads and the round trip through loadsOf
  try {
    const LinearPressure p = LinearPressure::fromLoads(shape, loads);
    note("pressure (%.17g, %.17g, %.17g)", p.p0, p.cx, p.cy);
    if (!finiteLoads) fail("fromLoads accepted loads (%.17g %.17g %.17g)", Pz, Tx, Ty);
    checkFinite(p.coefficients(), "pressure from loads");
    const PatchLoads back = loadsOf(shape, p);
    const Vec3 rhs(Pz, Ty, -Tx), rhsBack(back.Pz, back.Ty, -back.Tx);
    const Mat3 G = shape.areaMoments().loadMatrix();
    const double cond = conditionOf(G);
    // |G (G^-1 y) - y| <= eps cond(G) |y| (the product adds |G| |G^-1 y| ~ the same)
    const double tol =
        kSolveSlack * cond * (rhs.norm() + G.norm() * p.coefficients().norm() / cond);
    // (checked where cond(G) < kMaxCondition: beyond, the explicit inverse's
    // error grows like eps cond^2 and no fixed factor bounds it)
    constexpr double kMaxCondition = 1e4;
    if (cond < kMaxCondition && (rhsBack - rhs).norm() > tol) {
      fail("loadsOf(fromLoads(l)) != l: error %.3g, tolerance %.3g (cond %.3g)",
           (rhsBack - rhs).norm(), tol, cond);
    }
    // minPressure: at most the mean and every sampled boundary value
    const double pmin = minPressure(shape, p);
    checkFinite(pmin, "minPressure");
    const double scale = maxAbsPressure(shape, p);
    // (plus an absolute floor: denormal pressures are exact to ~1e-323 only)
    const double slack = kPressureSlack * scale + kSolveSlack * cond * std::abs(Pz) / A + 1e-300;
    // the reference values are long double; the core sums p0 + cx x + cy y in
    // double, ~eps of the terms each (kEvalUlps: a few roundings; a sliver
    // with p0 ~ 8e16 and vertex values ~ -3e9 differed by 8.5 = 0.5 eps p0)
    constexpr long double kEvalUlps = 8.0L * std::numeric_limits<double>::epsilon();
    auto above = [&](const Vec2& point) {
      return pmin > pressureAt(p, point) + slack + kEvalUlps * pressureTerms(p, point);
    };
    if (shape.isDisk()) {
      // the mean pressure, p at the centre (exact). On a polygon the mean is
      // a convex combination of the vertex values, so the vertex checks below
      // imply it; there it is not checked against p at the computed centroid,
      // which on a sliver is off by ~eps diameter^3 / area (found: a 5e-9 m^2
      // sliver 1 m long, centroid off by 2e-8 m, with |grad p| = 2.4e14 Pa/m)
      const long double mean = pressureAt(p, shape.centre());
      if (above(shape.centre()))
        fail("minPressure %.17g above the mean pressure %.17Lg", pmin, mean);
      for (int k = 0; k < 16; ++k) {
        const double a = 2.0 * kPi * k / 16.0;
        const Vec2 rim = shape.centre() + shape.radius() * Vec2(std::cos(a), std::sin(a));
        if (above(rim)) {
          fail("minPressure %.17g above the pressure on the rim %.17Lg (slack %.3g)", pmin,
               pressureAt(p, rim), slack);
        }
      }
    } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
      // (the mean is an average of the region's values: the extremes imply it)
      // A point of an arc is known to ~eps (|C| + R) only (the core takes
      // p(C) - R |grad p|, the harness C + R (cos t, sin t)), so p there to
      // ~eps (|p(C)| terms + R |grad p|) (found: a 1e-8 m high segment of a
      // unit circle with |grad p| = 8e125 Pa/m, p ~ -2e117 Pa, the two
      // differed by 6.5e109 = 0.3 eps R |grad p|).
      long double arcTerms = 0.0L;
      for (const BoundaryPiece& piece : shape.boundary()) {
        if (piece.kind != BoundaryPiece::Kind::Arc) continue;
        arcTerms = std::max(arcTerms, pressureTerms(p, piece.centre) +
                                          piece.radius * std::hypot((long double)p.cx, p.cy));
      }
      for (const Vec2& v : arcRegionExtremePoints(shape, p.cx, p.cy)) {
        if (pmin > pressureAt(p, v) + slack + kEvalUlps * (pressureTerms(p, v) + arcTerms)) {
          fail("minPressure %.17g above the pressure at a boundary point %.17Lg (slack %.3g)", pmin,
               pressureAt(p, v), slack);
        }
      }
    } else {
      for (const Vec2& v : shape.vertices()) {
        if (above(v)) {
          fail("minPressure %.17g above the pressure at a vertex %.17Lg (slack %.3g)", pmin,
               pressureAt(p, v), slack);
        }
      }
    }
    // isAdmissible: consistent with minPressure
    const double relTol = 1e-9;
    const bool admissible = isAdmissible(shape, loads, relTol);
    if (admissible && Pz < 0.0) fail("negative Pz admissible");
    if (admissible && pmin < -relTol * Pz / A - slack) fail("admissible with negative pressure");
    if (!admissible && Pz >= 0.0 && pmin > -relTol * Pz / A + slack) {
      fail("not admissible although minPressure = %.17g >= 0", pmin);
    }
  } catch (const Error& e) {
    checkErrorMessage(e);
    // finite loads may be refused only when the pressure truly overflows:
    // coefficients ~ |loads| |G^-1|, the pressure on the patch ~ that times
    // (1 + the patch's largest distance from O) (found: coefficients 3e299
    // on a patch 4e9 m from O, pressure ~1e309)
    const double size = Vec3(Pz, Tx, Ty).cwiseAbs().maxCoeff() *
                        shape.loadMatrixInverse().cwiseAbs().maxCoeff() *
                        (1.0 + shape.maxDistanceFromOrigin());
    if (finiteLoads && size < 1e300) fail("fromLoads refused finite loads: %s", e.what());
  }

  // the nearest admissible loads
  const double rhoIn = in.byte() & 1 ? in.number() : shape.defaultRho();
  note("loads (%.17g, %.17g, %.17g), rho %.17g", Pz, Tx, Ty, rhoIn);
  const PatchLoads near = nearestAdmissibleLoads(shape, loads, rhoIn);
  note("nearest (%.17g, %.17g, %.17g)", near.Pz, near.Tx, near.Ty);
  if (!finiteLoads) fail("nearestAdmissibleLoads accepted non-finite loads");
  if (!(rhoIn > 0.0) || !std::isfinite(rhoIn))
    fail("nearestAdmissibleLoads accepted rho = %.17g", rhoIn);
  checkFinite(near.asVector(), "nearest admissible loads");
  if (!(Pz > 0.0)) {
    if (!near.asVector().isZero(0.0)) fail("Pz <= 0 not mapped to zero load");
    return;
  }
  if (isAdmissible(shape, loads, 0.0) && !(near.asVector() == loads.asVector())) {
    fail("admissible loads changed by nearestAdmissibleLoads");
  }
  const Mat3 G = shape.areaMoments().loadMatrix();
  const double cond = conditionOf(G);
  // the result must be admissible (zero load is, trivially)
  // (denormal loads excepted: there the relative tolerance itself underflows)
  if (near.Pz > 1e-290 && !isAdmissible(shape, near, kProjectionSlack + kSolveSlack * cond)) {
    const double pmin = minPressure(shape, LinearPressure::fromLoads(shape, near));
    fail(
        "nearest admissible loads (%.17g %.17g %.17g) not admissible: min pressure %.17g, mean "
        "%.17g",
        near.Pz, near.Tx, near.Ty, pmin, near.Pz / shape.area());
  }
  if (near.Pz < 0.0) fail("nearest admissible loads with Pz < 0");
  // no farther than the zero load and the uniform pressure with the same Pz
  auto dist = [&](const PatchLoads& l) {
    return Vec3(l.Pz - Pz, (l.Tx - Tx) / rhoIn, (l.Ty - Ty) / rhoIn).norm();
  };
  const PatchLoads uniform = loadsOf(shape, LinearPressure::uniform(shape, Pz));
  // (the uniform candidate's torques Pz x_c may overflow: then only zero)
  const double best = uniform.asVector().allFinite() ? std::min(dist(PatchLoads{}), dist(uniform))
                                                     : dist(PatchLoads{});
  const double d = dist(near);
  if (d >
      best * (1.0 + kDistanceSlack) + kDistanceSlack * Vec3(Pz, Tx / rhoIn, Ty / rhoIn).norm()) {
    fail("nearest admissible loads at distance %.17g, but an admissible candidate is at %.17g", d,
         best);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput(data, size, run);
}
