// Numerics shared by the core's pressure code (pressure.cpp, models.cpp,
// admissible_loads.cpp).
#pragma once

#include <patchspin/pressure.hpp>

#include <cmath>
#include <limits>

namespace patchspin::internal {

// |(x, y)|: sqrt(x^2 + y^2) where that sum of squares is a normal double
// (then it is within ~2 ulps of the exact value, as hypot is within 1), the
// scaled std::hypot only where it under- or overflows. glibc's hypot costs
// ~50 instructions and a long-latency call on every pressure check.
inline double planarNorm(double x, double y) {
  const double s = x * x + y * y;
  if (s >= std::numeric_limits<double>::min() && s <= std::numeric_limits<double>::max())
    return std::sqrt(s);
  if (x == 0.0 && y == 0.0) return 0.0;
  return std::hypot(x, y);
}

// Error naming the first of Pz, Tx, Ty that is not finite. (Each visit of a
// patch refreshes its pressure: the common, finite case tests inline and
// calls out only to name the offending value.)
inline void requireFiniteLoads(const PatchLoads& loads) {
  if (std::isfinite(loads.Pz) && std::isfinite(loads.Tx) && std::isfinite(loads.Ty)) return;
  requireFinite(loads.Pz, "normal force Pz");
  requireFinite(loads.Tx, "tipping torque Tx");
  requireFinite(loads.Ty, "tipping torque Ty");
}

}  // namespace patchspin::internal
