// Gauss-Legendre rules on [0, 1] (gauss_tables.hpp).
#include "gauss_tables.hpp"

#include <cmath>

namespace patchspin::internal {

GaussTables::GaussTables() {
  const double pi = std::acos(-1.0);
  for (int n = 1; n <= kGaussMaxOrder; ++n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(pi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = 0.0;
        for (int j = 1; j <= n; ++j) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
        }
        dp = n * (z * p0 - p1) / (z * z - 1.0);
        const double dz = p0 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-17) break;
      }
      x[n][i] = 0.5 * (1.0 - z);
      w[n][i] = 1.0 / ((1.0 - z * z) * dp * dp);  // = 2/((1-z^2)P'^2) / 2
    }
  }
}

const GaussTables& gaussTables() {
  static const GaussTables tables;
  return tables;
}

}  // namespace patchspin::internal
