// The mean distance dbar of a flat contact area from its centre [m]: under
// uniform pressure a patch holds a twist about its normal up to mu N dbar
// and slips with that friction torque (the grippers' pads, the feet's soles
// of the multibody scenes and the grasp demo).
#pragma once

#include <cmath>

namespace patchspin::scenes {

// The rectangle [-a, a] x [-b, b]:
//   dbar = (d + a^2/(2b) ln((b + d)/a) + b^2/(2a) ln((a + d)/b)) / 3,
//   d = sqrt(a^2 + b^2)
// (a square of half side h: h (sqrt 2 + asinh 1) / 3). Checked against
// quadrature in MultiBodyField.MeanDistanceOfRectangleMatchesQuadrature.
inline double meanDistanceOfRectangle(double a, double b) {
  const double d = std::hypot(a, b);
  return (d + a * a / (2 * b) * std::log((b + d) / a) + b * b / (2 * a) * std::log((a + d) / b)) /
         3.0;
}

}  // namespace patchspin::scenes
