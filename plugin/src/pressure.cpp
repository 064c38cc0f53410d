// Linear pressure from loads, Eq. (94); the admissibility test (DESIGN item 2;
// the projection onto admissible loads: admissible_loads.cpp);
// Pi of Eq. (36), (40) from the moment table (DESIGN item 1).
#include <patchspin/internal/exact.hpp>
#include <patchspin/pressure.hpp>

#include "arc_region_numerics.hpp"
#include "pressure_numerics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patchspin {

namespace {

// (Pz, Tx, Ty) <-> the right-hand side (Pz, Ty, -Tx) of Eq. (94).
Vec3 loadsToRhs(const PatchLoads& l) {
  return Vec3(l.Pz, l.Ty, -l.Tx);
}
PatchLoads rhsToLoads(const Vec3& r) {
  return PatchLoads{r[0], -r[2], r[1]};
}

}  // namespace

LinearPressure LinearPressure::fromLoads(const PatchShape& shape, const PatchLoads& loads) {
  internal::requireFiniteLoads(loads);
  // Eq. (94): [Pz, Ty, -Tx] = G (p0, cx, cy)
  const Vec3 c = shape.solveLoadMatrix(loadsToRhs(loads));
  if (!c.allFinite()) {  // found by fuzzing: loads ~1e308 gave p = -inf
    throw Error("loads out of range: the pressure carrying (Pz, Tx, Ty) = (" +
                internal::formatDouble(loads.Pz) + ", " + internal::formatDouble(loads.Tx) + ", " +
                internal::formatDouble(loads.Ty) + ") overflows double");
  }
  return LinearPressure{c[0], c[1], c[2]};
}

LinearPressure LinearPressure::uniform(const PatchShape& shape, double Pz) {
  internal::requireFinite(Pz, "normal force Pz");
  return LinearPressure{Pz / shape.area(), 0.0, 0.0};
}

PatchLoads loadsOf(const PatchShape& shape, const LinearPressure& p) {
  return rhsToLoads(shape.areaMoments().loadMatrix() * p.coefficients());
}

double minPressure(const PatchShape& shape, const LinearPressure& p) {
  double lowest = std::numeric_limits<double>::infinity();
  if (shape.isDisk()) {
    // min over the disk of an affine function: p(C) - R |grad p|
    lowest = p.at(shape.centre()) - shape.radius() * internal::planarNorm(p.cx, p.cy);
  } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
    // at a piece's start or at an arc's point of outward normal
    // -grad p / |grad p| (arc_region_numerics.hpp), with the coefficients
    // scaled by a power of two (as the polygon's overflow path below)
    if (!p.coefficients().allFinite()) {
      lowest = std::numeric_limits<double>::quiet_NaN();
    } else {
      const double largest = p.coefficients().cwiseAbs().maxCoeff();
      const int e = largest > 0.0 ? std::ilogb(largest) : 0;
      lowest = std::ldexp(internal::arcRegionMinLinear(shape.boundary(), std::ldexp(p.p0, -e),
                                                       std::ldexp(p.cx, -e), std::ldexp(p.cy, -e)),
                          e);
    }
  } else {
    for (const Vec2& v : shape.vertices()) {
      double at = p.at(v);
      // (a product that overflows where the sum does not, cx x = -inf and
      // cy y = +inf, gave NaN, which std::min passes over: minPressure
      // returned another vertex's -5e297 where this one's is -2.3e303;
      // found by fuzzing. Then the sum is taken with the coefficients
      // scaled by a power of two.)
      if (!std::isfinite(at)) {
        // a NaN or infinite coefficient has no binary exponent to scale by
        // (ilogb(NaN) is FP_ILOGBNAN, INT_MIN with glibc on x86, and -e
        // overflowed int: undefined behaviour, found by fuzzing, `limits`:
        // FlatBodyModel::contactAtRest with a tipping couple of inf gave a
        // pressure of NaN): the pressure is not finite on the patch
        if (!p.coefficients().allFinite()) {
          lowest = std::numeric_limits<double>::quiet_NaN();
          break;
        }
        const int e = std::ilogb(p.coefficients().cwiseAbs().maxCoeff());
        const LinearPressure scaled{std::ldexp(p.p0, -e), std::ldexp(p.cx, -e),
                                    std::ldexp(p.cy, -e)};
        at = std::ldexp(scaled.at(v), e);
        if (!std::isfinite(at)) {
          lowest = at;
          break;
        }
      }
      lowest = std::min(lowest, at);
    }
  }
  // found by fuzzing: finite coefficients whose pressure overflows gave inf
  if (!std::isfinite(lowest)) {
    throw Error("pressure out of range: (p0, cx, cy) = (" + internal::formatDouble(p.p0) + ", " +
                internal::formatDouble(p.cx) + ", " + internal::formatDouble(p.cy) +
                ") is not finite on the patch");
  }
  return lowest;
}

bool isAdmissible(const PatchShape& shape, const PatchLoads& loads, double relTol) {
  internal::requireFiniteLoads(loads);
  if (loads.Pz < 0.0) return false;
  const LinearPressure p = LinearPressure::fromLoads(shape, loads);
  return minPressure(shape, p) >= -relTol * loads.Pz / shape.area();
}

// nearestAdmissibleLoads: admissible_loads.cpp

PiMoments piMoments(const PatchShape& shape, const LinearPressure& pressure) {
  if (!(std::isfinite(pressure.p0) && std::isfinite(pressure.cx) && std::isfinite(pressure.cy)))
    internal::requireFinite(pressure.coefficients(), "pressure (p0, cx, cy)");
  // every integral of Eq. (36) is m.row(f) (p0, cx, cy) (DESIGN item 1)
  const Eigen::Matrix<double, 6, 1> v = shape.momentTable().m * pressure.coefficients();
  PiMoments out;
  out.Pz = v[MomentTable::kOne];
  if (!(out.Pz > 0.0)) {
    throw Error(
        "pressure carries no positive normal force: Pz = " + internal::formatDouble(out.Pz) + " N");
  }
  if (!v.allFinite()) {
    throw Error("pressure out of range: its moments (36) overflow double (Pz = " +
                internal::formatDouble(out.Pz) + " N)");
  }
  const double inv = 1.0 / out.Pz;
  out.pi_x = v[MomentTable::kX] * inv;
  out.pi_y = v[MomentTable::kY] * inv;
  out.pi_xy = v[MomentTable::kR] * inv;
  out.pi_x0 = v[MomentTable::kXOverR] * inv;
  out.pi_y0 = v[MomentTable::kYOverR] * inv;
  // found by fuzzing: a tiny Pz from cancelling large coefficients made the
  // averages overflow
  if (!std::isfinite(inv) || !Vec3(out.pi_x, out.pi_y, out.pi_xy).allFinite() ||
      !std::isfinite(out.pi_x0) || !std::isfinite(out.pi_y0)) {
    throw Error("pressure out of range: its averages (36) overflow double (Pz = " +
                internal::formatDouble(out.Pz) + " N)");
  }
  return out;
}

Mat3 ellipsoidalPi(const PiMoments& m, double rho) {
  if (!(rho > 0.0 && rho <= std::numeric_limits<double>::max()))
    internal::requirePositive(rho, "length scale rho");
  // Eq. (40) without the factor -mu Pz
  Mat3 Pi;
  Pi << 1.0, 0.0, -m.pi_y0,  //
      0.0, 1.0, m.pi_x0,     //
      -m.pi_y / rho, m.pi_x / rho, m.pi_xy / rho;
  if (!Pi.allFinite()) {
    throw Error("Pi (40) is not finite: moments (pi_x, pi_y, pi_xy, pi_x0, pi_y0) = (" +
                internal::formatDouble(m.pi_x) + ", " + internal::formatDouble(m.pi_y) + ", " +
                internal::formatDouble(m.pi_xy) + ", " + internal::formatDouble(m.pi_x0) + ", " +
                internal::formatDouble(m.pi_y0) + "), rho = " + internal::formatDouble(rho));
  }
  return Pi;
}

PiMoments piMomentsHertz(const PatchShape& disk, const HertzPressure& pressure) {
  if (!disk.isDisk()) throw Error("Hertz pressure (57) is defined on disks only");
  internal::requirePositive(pressure.Pz, "Hertz normal force Pz");
  // axisymmetric about the centre C: pi_x, pi_y = C. The pure-spin friction of
  // the unit-load Hertz pressure about O gives the rest, Eq. (39):
  //   ∫ p1 (-y/r, x/r, r/rho) dA = (-pi_y0, pi_x0, pi_xy / rho)
  const double rho = 1.0;
  const Vec3 spin =
      internal::exactDiskHertz(disk.centre(), disk.radius(), rho, Vec3(0.0, 0.0, 1.0), nullptr);
  PiMoments out;
  out.Pz = pressure.Pz;
  out.pi_x = disk.centre().x();
  out.pi_y = disk.centre().y();
  out.pi_y0 = -spin[0];
  out.pi_x0 = spin[1];
  out.pi_xy = spin[2] * rho;
  return out;
}

}  // namespace patchspin
