// Internal numerical quadrature: Gauss-Legendre nodes and an adaptive,
// vector-valued Gauss-Legendre rule. Used once per shape (moment tables),
// never in a solver loop.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <vector>

namespace patchspin::internal {

struct GaussRule {
  std::vector<double> nodes;  // on [-1, 1]
  std::vector<double> weights;
};

// n-point Gauss-Legendre rule by Newton iteration on P_n (exact for degree 2n-1).
GaussRule gaussLegendre(int n);

// Integrates a vector-valued f: [a, b] -> R^N to a relative accuracy `relTol`
// per component (relative to the integral of |f|), by recursive bisection
// comparing a 15-point rule on the interval with the sum over its halves.
template <int N, class F>
Eigen::Matrix<double, N, 1> adaptiveGauss(F&& f, double a, double b, double relTol);

// ---- implementation ----

const GaussRule& gauss15();

template <int N, class F>
void gaussOnInterval(F& f, double a, double b, Eigen::Matrix<double, N, 1>& value,
                     Eigen::Matrix<double, N, 1>& absValue) {
  const GaussRule& rule = gauss15();
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  value.setZero();
  absValue.setZero();
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    const Eigen::Matrix<double, N, 1> fx = f(mid + half * rule.nodes[i]);
    value += rule.weights[i] * fx;
    absValue += rule.weights[i] * fx.cwiseAbs();
  }
  value *= half;
  absValue *= std::abs(half);
}

template <int N, class F>
Eigen::Matrix<double, N, 1> adaptiveGaussRecurse(F& f, double a, double b,
                                                 const Eigen::Matrix<double, N, 1>& whole,
                                                 const Eigen::Matrix<double, N, 1>& tol, int depth,
                                                 long& budget) {
  using V = Eigen::Matrix<double, N, 1>;
  const double m = 0.5 * (a + b);
  V left, right, absLeft, absRight;
  gaussOnInterval<N>(f, a, m, left, absLeft);
  gaussOnInterval<N>(f, m, b, right, absRight);
  const V sum = left + right;
  // accept at the tolerance, or once the difference is down to round-off of
  // the local |f| (a tighter tolerance could never be met: no endless split)
  const V roundOff = (64.0 * std::numeric_limits<double>::epsilon()) * (absLeft + absRight);
  const V accept = tol.cwiseMax(roundOff);
  // a non-finite integrand (overflowing input) would never converge: 2^50
  // evaluations; stop and let the caller reject the result
  if (!sum.allFinite()) return sum;
  // the budget bounds the work when noise in f keeps the rule from converging
  // (each split may otherwise double the work down to depth 50: 2^50 calls)
  if (depth >= 50 || --budget <= 0 || ((sum - whole).cwiseAbs().array() <= accept.array()).all()) {
    return sum;
  }
  // halve the tolerance per half so the errors add up to at most tol
  return adaptiveGaussRecurse<N>(f, a, m, left, 0.5 * tol, depth + 1, budget) +
         adaptiveGaussRecurse<N>(f, m, b, right, 0.5 * tol, depth + 1, budget);
}

template <int N, class F>
Eigen::Matrix<double, N, 1> adaptiveGauss(F&& f, double a, double b, double relTol) {
  using V = Eigen::Matrix<double, N, 1>;
  V whole, absWhole;
  gaussOnInterval<N>(f, a, b, whole, absWhole);
  if (!whole.allFinite() || !absWhole.allFinite()) return whole;  // caller rejects it
  // absolute floor: relTol of the integral of |f| (a component that is zero
  // by symmetry must not demand relative accuracy of zero)
  const V tol = (relTol * absWhole.array().max(absWhole.maxCoeff() * 1e-300)).matrix();
  // at most kMaxSplits subdivisions (30 evaluations each): ~1e6 evaluations
  constexpr long kMaxSplits = 1L << 15;
  long budget = kMaxSplits;
  return adaptiveGaussRecurse<N>(f, a, b, whole, tol, 0, budget);
}

}  // namespace patchspin::internal
