// Linear pressure from loads, Eq. (94); admissible loads (DESIGN item 2);
// Pi of Eq. (36), (40) from the moment table (DESIGN item 1).
#include <patchspin/internal/exact.hpp>
#include <patchspin/pressure.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patchspin {

namespace {

constexpr double kPi = 3.14159265358979323846;

// |(x, y)|: sqrt(x^2 + y^2) where that sum of squares is a normal double
// (then it is within ~2 ulps of the exact value, as hypot is within 1), the
// scaled std::hypot only where it under- or overflows. glibc's hypot costs
// ~50 instructions and a long-latency call on every pressure check.
double planarNorm(double x, double y) {
  const double s = x * x + y * y;
  if (s >= std::numeric_limits<double>::min() && s <= std::numeric_limits<double>::max())
    return std::sqrt(s);
  if (x == 0.0 && y == 0.0) return 0.0;
  return std::hypot(x, y);
}

// (each visit of a patch refreshes its pressure: the common, finite case
// tests inline and calls out only to name the offending value)
bool finite3(double a, double b, double c) {
  return std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
}

void requireFiniteLoads(const PatchLoads& loads) {
  if (finite3(loads.Pz, loads.Tx, loads.Ty)) return;
  internal::requireFinite(loads.Pz, "normal force Pz");
  internal::requireFinite(loads.Tx, "tipping torque Tx");
  internal::requireFinite(loads.Ty, "tipping torque Ty");
}

// (Pz, Tx, Ty) <-> the right-hand side (Pz, Ty, -Tx) of Eq. (94).
Vec3 loadsToRhs(const PatchLoads& l) {
  return Vec3(l.Pz, l.Ty, -l.Tx);
}
PatchLoads rhsToLoads(const Vec3& r) {
  return PatchLoads{r[0], -r[2], r[1]};
}

}  // namespace

LinearPressure LinearPressure::fromLoads(const PatchShape& shape, const PatchLoads& loads) {
  requireFiniteLoads(loads);
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
    lowest = p.at(shape.centre()) - shape.radius() * planarNorm(p.cx, p.cy);
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
  requireFiniteLoads(loads);
  if (loads.Pz < 0.0) return false;
  const LinearPressure p = LinearPressure::fromLoads(shape, loads);
  return minPressure(shape, p) >= -relTol * loads.Pz / shape.area();
}

// Projection onto the admissible set in scaled load coordinates
//   l~ = (Pz, Tx / rho, Ty / rho) = M (p0, cx, cy).
// Polygons: the set is the polyhedral cone {a_i . l~ >= 0}, a_i = M^-T (1, x_i, y_i);
// the projection is the nearest feasible candidate over the active sets of
// size 0, 1 and 2 (faces, edges) and the apex 0. An edge of the cone is a
// pressure vanishing at two vertices and >= 0 at the others, so its zero
// line is a side of the (convex) polygon: only adjacent vertices pair up,
// n + n candidates instead of n + n(n-1)/2 (a cut disk has 64 vertices).
// Disks: the cone {z0 >= R |(z1, z2)|}, z = (p(C), cx, cy); the boundary is
// the rays t (1, cos th / R, sin th / R) (in z), and the projection maximises
// (N u . y)^2 / |N u|^2 over th (sampled, then golden-section refined).
namespace {
PatchLoads nearestAdmissibleLoadsImpl(const PatchShape& shape, const PatchLoads& loads, double rho);
}  // namespace

PatchLoads nearestAdmissibleLoads(const PatchShape& shape, const PatchLoads& loads, double rho) {
  requireFiniteLoads(loads);
  internal::requirePositive(rho, "length scale rho");
  // as for FrictionPatch: within 1e12 of Eq. (11) either way; beyond, the
  // metric's torque terms under- or overflow (found by fuzzing: rho = 1e308)
  const double natural = shape.defaultRho();
  if (rho < natural * 1e-12 || rho > natural * 1e12) {
    throw Error("length scale rho = " + internal::formatDouble(rho) +
                " m is out of range for this patch: Eq. (11) gives " +
                internal::formatDouble(natural) + " m; allowed 1e-12 to 1e12 times that");
  }
  const PatchLoads out = nearestAdmissibleLoadsImpl(shape, loads, rho);
  // found by fuzzing: a denormal rho made the scaled torques overflow (NaN)
  if (!out.asVector().allFinite()) {
    throw Error("nearest admissible loads out of range: torques / rho overflow double (rho = " +
                internal::formatDouble(rho) + " m)");
  }
  // found by fuzzing: torques ~1e300 times Pz rho swamp the projection's
  // round-off test and it returned inadmissible loads; say so instead (also
  // for a result with Pz < 0: torques 1e154 times Pz rho gave Pz = -4.9e138,
  // round-off of the 1e154-sized scaled torque)
  constexpr double kVerifyTol = 1e-6;  // of the mean pressure; normal cases: ~1e-12
  if (!out.asVector().isZero(0.0) && !(out.asVector() == loads.asVector()) &&
      !isAdmissible(shape, out, kVerifyTol)) {
    throw Error(
        "nearest admissible loads out of range: no admissible projection to double "
        "precision for (Pz, Tx, Ty) = (" +
        internal::formatDouble(loads.Pz) + ", " + internal::formatDouble(loads.Tx) + ", " +
        internal::formatDouble(loads.Ty) + ")");
  }
  return out;
}

namespace {
PatchLoads nearestAdmissibleLoadsImpl(const PatchShape& shape, const PatchLoads& loads,
                                      double rho) {
  if (!(loads.Pz > 0.0)) return PatchLoads{};  // documented: no normal force, no load
  if (isAdmissible(shape, loads, 0.0)) return loads;
  // M maps pressure coefficients to scaled loads
  const Mat3 G = shape.areaMoments().loadMatrix();
  Mat3 P;                    // (Pz, Ty, -Tx) -> (Pz, Tx/rho, Ty/rho)
  P << 1.0, 0.0, 0.0,        //
      0.0, 0.0, -1.0 / rho,  //
      0.0, 1.0 / rho, 0.0;
  const Mat3 M = P * G;
  const Vec3 y(loads.Pz, loads.Tx / rho, loads.Ty / rho);
  auto toLoads = [&](const Vec3& l) { return PatchLoads{l[0], l[1] * rho, l[2] * rho}; };

  if (!shape.isDisk()) {
    // (with O outside the polygon, G^-1 (1, x_i, y_i) by PatchShape's
    // solve about the vertex mean: M^-1 = G^-1 P^-1, whose cofactor inverse
    // about a far O loses ~(max|r| / size)^4 eps; P^-1 is exact up to rho's
    // rounding. A patch about a point inside it keeps M^-1.)
    const bool aboutMean = shape.maxDistanceFromOrigin() > shape.diameter();
    Mat3 PinvT;              // P^-T
    PinvT << 1.0, 0.0, 0.0,  //
        0.0, 0.0, -rho,      //
        0.0, rho, 0.0;
    const Mat3 Minv = aboutMean ? Mat3::Zero() : Mat3(M.inverse());
    // the cone's inward normals a_i and their norms (computed once: the
    // Bullet layer calls this at every pressure refresh of a patch whose
    // centre of pressure is outside its kern)
    struct Row {
      Vec3 a;
      double norm;
    };
    std::vector<Row> rows;
    rows.reserve(shape.vertices().size());
    for (const Vec2& v : shape.vertices()) {
      const Vec3 phi(1.0, v.x(), v.y());
      const Vec3 a =
          aboutMean ? Vec3(PinvT * shape.solveLoadMatrix(phi)) : Vec3(Minv.transpose() * phi);
      rows.push_back({a, a.norm()});
    }
    // feasibility with a small relative slack for round-off
    auto feasible = [&](const Vec3& l) {
      const double scale = l.norm();
      for (const Row& r : rows)
        if (r.a.dot(l) < -1e-12 * r.norm * scale) return false;
      return true;
    };
    Vec3 best = Vec3::Zero();
    double bestDist = y.norm();
    auto consider = [&](const Vec3& l) {
      const double dist = (l - y).norm();
      if (dist < bestDist && feasible(l)) {
        bestDist = dist;
        best = l;
      }
    };
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Vec3& ai = rows[i].a;
      // the face candidate y - (a_i.y / |a_i|^2) a_i has the multiplier
      // -a_i.y / |a_i|^2 of the KKT conditions, which must be >= 0: only
      // faces that y violates can hold the projection
      const double aiy = ai.dot(y);
      if (aiy < 0.0) consider(y - aiy / ai.squaredNorm() * ai);
      // the edge ray u of faces i and i+1 (only rays with u.y > 0 are nearer
      // than the apex)
      const Row& next = rows[(i + 1) % rows.size()];
      const Vec3 d = ai.cross(next.a);
      const double dn = d.norm();
      if (dn <= 1e-14 * rows[i].norm * next.norm) continue;
      const Vec3 u = d / dn;
      const double uy = u.dot(y);
      if (uy > 0.0) consider(uy * u);
    }
    // the uniform pressure's ray is admissible by construction: the answer is
    // at least as near as its nearest point (found by fuzzing: on a sliver
    // triangle 1e8 m long, round-off in the test above rejected every face
    // and edge candidate and the answer fell back to the zero load, farther
    // than the uniform pressure)
    const Vec3 uniform = M.col(0);
    const Vec3 onRay = std::max(0.0, uniform.dot(y) / uniform.squaredNorm()) * uniform;
    if ((onRay - y).norm() < bestDist) best = onRay;
    return toLoads(best);
  }

  // disk: z = T pi with z = (p(C), cx, cy)
  const Vec2 C = shape.centre();
  const double R = shape.radius();
  // disk centred at O (every disk patch of the Bullet layer): M = diag(A, .)
  // with the in-plane block a rotation times I / rho, so the admissible set
  // is the circular cone |(y1, y2)| <= kappa y0, kappa = I / (A R rho), and
  // the Euclidean projection has a closed form: with s = |(y1, y2)|,
  //   s <= kappa y0        -> y (admissible, handled above)
  //   kappa s <= -y0       -> 0 (y in the polar cone)
  //   otherwise            -> (y0 + kappa s) / (1 + kappa^2) (1, kappa e),  e = (y1, y2) / s
  const double cTol = 1e-12 * G.norm();
  if (C.norm() <= 1e-12 * R && std::abs(G(0, 1)) <= cTol && std::abs(G(0, 2)) <= cTol &&
      std::abs(G(1, 2)) <= cTol && std::abs(G(1, 1) - G(2, 2)) <= cTol) {
    const double kappa = G(1, 1) / (G(0, 0) * R * rho);
    const double sPerp = std::hypot(y[1], y[2]);
    if (kappa * sPerp <= -y[0]) return PatchLoads{};
    const double t = (y[0] + kappa * sPerp) / (1.0 + kappa * kappa);
    return toLoads(Vec3(t, t * kappa * y[1] / sPerp, t * kappa * y[2] / sPerp));
  }
  Mat3 T;
  T << 1.0, C.x(), C.y(),  //
      0.0, 1.0, 0.0,       //
      0.0, 0.0, 1.0;
  const Mat3 N = M * T.inverse();
  // (the gain is |y|^2 minus the squared distance to the ray: maximised as
  // minus that distance itself, taken from y - t N u. As |y|^2 - d^2 it
  // lost d below sqrt(eps) |y|, where every ray's gain was |y|^2 to the
  // last bit and the first sample won: found by fuzzing, loads 3e-9 of
  // their size outside the set projected 33% farther than the nearest ray)
  auto gain = [&](double th) {
    const Vec3 u(1.0, std::cos(th) / R, std::sin(th) / R);
    const Vec3 Nu = N * u;
    const double t = std::max(0.0, Nu.dot(y) / Nu.squaredNorm());
    return -(y - t * Nu).squaredNorm();
  };
  constexpr int kSamples = 256;
  int bestIndex = 0;
  double bestGain = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < kSamples; ++i) {
    const double g = gain(2.0 * kPi * i / kSamples);
    if (g > bestGain) {
      bestGain = g;
      bestIndex = i;
    }
  }
  // golden-section refinement on the bracketing samples
  double lo = 2.0 * kPi * (bestIndex - 1) / kSamples, hi = 2.0 * kPi * (bestIndex + 1) / kSamples;
  const double invPhi = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - invPhi * (hi - lo), x2 = lo + invPhi * (hi - lo);
  double g1 = gain(x1), g2 = gain(x2);
  for (int it = 0; it < 80; ++it) {
    if (g1 > g2) {
      hi = x2, x2 = x1, g2 = g1, x1 = hi - invPhi * (hi - lo), g1 = gain(x1);
    } else {
      lo = x1, x1 = x2, g1 = g2, x2 = lo + invPhi * (hi - lo), g2 = gain(x2);
    }
  }
  const double th = 0.5 * (lo + hi);
  const Vec3 u(1.0, std::cos(th) / R, std::sin(th) / R);
  const Vec3 Nu = N * u;
  const double t = std::max(0.0, Nu.dot(y) / Nu.squaredNorm());
  // the uniform pressure's ray (admissible by construction) and the zero
  // load, as for polygons (a backstop: the boundary search returns them
  // only where it misses the nearest ray)
  Vec3 best = t * Nu;
  const Vec3 uniform = M.col(0);
  const Vec3 onRay = std::max(0.0, uniform.dot(y) / uniform.squaredNorm()) * uniform;
  if ((onRay - y).norm() < (best - y).norm()) best = onRay;
  if (y.norm() < (best - y).norm()) best = Vec3::Zero();
  return toLoads(best);
}
}  // namespace

PiMoments piMoments(const PatchShape& shape, const LinearPressure& pressure) {
  if (!finite3(pressure.p0, pressure.cx, pressure.cy))
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
