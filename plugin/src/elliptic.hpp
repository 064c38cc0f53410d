// Complete elliptic integrals K(m), E(m) in the PARAMETER m = k^2, and the
// incomplete F(phi | m), E(phi | m) from the complementary parameter,
// (Abramowitz-Stegun 17.2, the paper's convention below Eq. (53)).
#pragma once

#include <algorithm>
#include <cmath>

namespace patchspin::internal {

struct EllipticKE {
  double K = 0.0;
  double E = 0.0;
};

// Arithmetic-geometric mean (Abramowitz-Stegun 17.6):
//   a0 = 1, b0 = sqrt(mc), c0 = sqrt(m), mc = 1 - m
//   a' = (a + b)/2, b' = sqrt(a b), c' = (a - b)/2
//   K = pi / (2 a_N),  E = K (1 - sum_{n>=0} 2^(n-1) c_n^2)
// The complementary parameter mc is passed separately so that callers can
// supply it without cancellation near m = 1 (the rim of the disk). K is
// +infinity for mc = 0; callers multiply it by a factor of mc (see mcK).
// Stops when c_N^2 (about the relative error left in K and in the neglected
// sum terms) is below relTol; relTol ~ 1e-17 gives full double accuracy. The
// iteration is quadratic, so a looser relTol saves at most an iteration or two.
inline EllipticKE completeEllipticKE(double m, double mc, double relTol = 1e-17) {
  EllipticKE r;
  if (mc <= 0.0) {
    r.K = HUGE_VAL;
    r.E = 1.0;
    return r;
  }
  double a = 1.0;
  double b = std::sqrt(mc);
  double sum = 0.5 * m;  // 2^(-1) c0^2
  double pow2 = 0.5;
  for (int it = 0; it < 40; ++it) {
    const double c = 0.5 * (a - b);
    const bool last = c * c <= relTol * a * a;
    const double an = 0.5 * (a + b);
    pow2 *= 2.0;
    sum += pow2 * c * c;
    if (last) {
      // AGM = a_{N+1} (1 - O(c^2/4)); the next sum term is O(2^N c^4)
      a = an;
      break;
    }
    b = std::sqrt(a * b);
    a = an;
  }
  const double pi = 3.14159265358979323846;
  r.K = pi / (2.0 * a);
  r.E = r.K * (1.0 - sum);
  return r;
}

// (1 - m) K(m) with its limit 0 at m = 1 (K has only a log singularity).
inline double mcK(const EllipticKE& ke, double mc) {
  return mc > 0.0 ? mc * ke.K : 0.0;
}

// Carlson's symmetric integral R_F(x, y, z) (x, y, z >= 0, at most one 0) by
// duplication (Carlson 1995, Numer. Algorithms 10): each step divides the
// spread by ~4; stop when it is below kTol of the mean, then the series to
// E3: relative error ~ kTol^6 / 4 < 1e-17.
inline double carlsonRF(double x, double y, double z) {
  constexpr double kTol = 1.5e-3;
  for (int it = 0; it < 60; ++it) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double mean = (x + y + z) / 3.0;
    const double spread = std::max({std::abs(mean - x), std::abs(mean - y), std::abs(mean - z)});
    if (spread <= kTol * mean) break;
    const double lambda = sx * sy + sy * sz + sz * sx;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
  }
  const double A = (x + y + z) / 3.0;
  const double X = 1.0 - x / A, Y = 1.0 - y / A, Z = -(X + Y);
  const double E2 = X * Y - Z * Z, E3 = X * Y * Z;
  return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0) / std::sqrt(A);
}

// Carlson's R_D(x, y, z) (x, y >= 0 not both 0, z > 0) by duplication
// (Carlson 1995; the Numerical Recipes form of the series): spread below
// kTol of the mean gives a relative error ~ kTol^6 / 4.
inline double carlsonRD(double x, double y, double z) {
  constexpr double kTol = 1e-3;
  double sum = 0.0, fac = 1.0, ave = 0.0, dx = 0.0, dy = 0.0, dz = 0.0;
  for (int it = 0; it < 60; ++it) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sy * sz + sz * sx;
    sum += fac / (sz * (z + lambda));
    fac *= 0.25;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
    ave = 0.2 * (x + y + 3.0 * z);
    dx = (ave - x) / ave, dy = (ave - y) / ave, dz = (ave - z) / ave;
    if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) <= kTol) break;
  }
  const double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6.0 * eb, ee = ed + ec + ec;
  const double series = 1.0 + ed * (-3.0 / 14.0 + 9.0 / 88.0 * ed - 9.0 / 52.0 * dz * ee) +
                        dz * (ee / 6.0 + dz * (-9.0 / 22.0 * ec + dz * 3.0 / 26.0 * ea));
  return 3.0 * sum + fac * series / (ave * std::sqrt(ave));
}

struct EllipticFE {
  double F = 0.0;
  double E = 0.0;
};

// Incomplete elliptic integrals F(phi | m), E(phi | m) for any real phi,
// from the complementary parameter mc = 1 - m > 0 (libstdc++'s std::ellint_1
// takes k = sqrt(m), which rounds to 1 for mc < 1e-16 and then loses F's
// log(1/mc) growth that callers multiply by a factor ~sqrt(mc)); one R_F
// shared by both (DLMF 19.25.5, 19.25.7):
//   F = s R_F(c^2, d^2, 1),  E = F - (m/3) s^3 R_D(c^2, d^2, 1)
// on [-pi/2, pi/2] (s = sin, c = cos, d^2 = c^2 + mc s^2), plus 2n times the
// complete K, E (completeEllipticKE) beyond (phi in period n).
// On [-pi/2, pi/2], from s = sin phi, c = cos phi.
inline EllipticFE reducedEllipticFE(double s, double c, double m, double mc) {
  const double c2 = c * c, d2 = c2 + mc * s * s;
  EllipticFE out;
  out.F = s * carlsonRF(c2, d2, 1.0);
  out.E = out.F - (m / 3.0) * s * s * s * carlsonRD(c2, d2, 1.0);
  return out;
}

// F(phi2 | m) - F(phi1 | m) and the same for E, given the sines and cosines
// of the amplitudes (phi - n pi has sin, cos = (-1)^n (sin, cos) phi); the
// complete integrals only when the ends lie in different periods (n2 != n1).
inline EllipticFE ellipticFEDifference(double phi1, double s1, double c1, double phi2, double s2,
                                       double c2, double m, double mc) {
  const double pi = 3.14159265358979323846;
  const double n1 = std::nearbyint(phi1 / pi), n2 = std::nearbyint(phi2 / pi);
  const double f1 = std::fmod(n1, 2.0) == 0.0 ? 1.0 : -1.0;
  const double f2 = std::fmod(n2, 2.0) == 0.0 ? 1.0 : -1.0;
  const EllipticFE a = reducedEllipticFE(f1 * s1, f1 * c1, m, mc);
  const EllipticFE b = reducedEllipticFE(f2 * s2, f2 * c2, m, mc);
  EllipticFE out{b.F - a.F, b.E - a.E};
  if (n2 != n1) {
    const EllipticKE ke = completeEllipticKE(m, mc);
    out.F += 2.0 * (n2 - n1) * ke.K;
    out.E += 2.0 * (n2 - n1) * ke.E;
  }
  return out;
}

}  // namespace patchspin::internal
