// Complete elliptic integrals K(m), E(m) in the PARAMETER m = k^2
// (Abramowitz-Stegun 17.2, the paper's convention below Eq. (53)).
#pragma once

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

}  // namespace patchspin::internal
