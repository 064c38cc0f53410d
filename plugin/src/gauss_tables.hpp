// Gauss-Legendre rules on [0, 1], orders 1 .. kGaussMaxOrder, by Newton on
// P_n: the exact laws' far branches (exact_polygon.cpp, exact_arc_region.cpp).
#pragma once

#include <array>

namespace patchspin::internal {

constexpr int kGaussMaxOrder = 24;

struct GaussTables {
  // x[n][i], w[n][i]: node and weight i of the n-point rule on [0, 1]
  std::array<std::array<double, kGaussMaxOrder>, kGaussMaxOrder + 1> x{}, w{};
  GaussTables();
};
// The tables, built at the first call.
const GaussTables& gaussTables();

}  // namespace patchspin::internal
