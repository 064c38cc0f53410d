#include "quadrature.hpp"

namespace patchspin::internal {

GaussRule gaussLegendre(int n) {
  GaussRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    // initial guess (Tricomi), then Newton on P_n
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      // P_n = p1, P_{n-1} = p0;  P_n' = n (x P_n - P_{n-1}) / (x^2 - 1)
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.nodes[i] = x;
    rule.weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

const GaussRule& gauss15() {
  static const GaussRule rule = gaussLegendre(15);
  return rule;
}

}  // namespace patchspin::internal
