// Gauss-Legendre nodes and weights on [-1, 1] in long double, for test
// references more precise than double (Newton on P_n from the Chebyshev
// guesses, to 1e-21).
#pragma once

#include <cmath>
#include <vector>

namespace patchspin::testing {

inline void gaussLegendreLong(int n, std::vector<long double>& x, std::vector<long double>& w) {
  x.assign(n, 0.0L), w.assign(n, 0.0L);
  const long double pi = 3.141592653589793238462643383279502884L;
  for (int i = 0; i < n; ++i) {
    long double z = std::cos(pi * (i + 0.75L) / (n + 0.5L)), dp = 0.0L;
    for (int it = 0; it < 100; ++it) {
      long double p0 = 1.0L, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const long double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0L);
      const long double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-21L) break;
    }
    x[i] = z;
    w[i] = 2.0L / ((1.0L - z * z) * dp * dp);
  }
}

}  // namespace patchspin::testing
