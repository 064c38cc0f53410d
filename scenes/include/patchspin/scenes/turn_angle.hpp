// The angle of a body's turn, as the scenes' tests and benchmarks measure
// holding: the turn q in [0, pi] from its vector part, 2 asin |v|, in
// double, rather than btQuaternion::getAngle's 2 acos w, which in float
// reads exactly 0 for any turn below about 7e-4 rad (w rounds to 1) and so
// cannot show a hold bound of 1e-4 rad.
#pragma once

#include <LinearMath/btQuaternion.h>

#include <algorithm>
#include <cmath>

namespace patchspin::scenes {

inline double foldedTurnAngle(const btQuaternion& q) {
  const double v = std::sqrt(double(q.x()) * double(q.x()) + double(q.y()) * double(q.y()) +
                             double(q.z()) * double(q.z()));
  return 2.0 * std::asin(std::min(1.0, v));
}

// The turn from orientation `from` to `to`.
inline double foldedTurnAngle(const btQuaternion& to, const btQuaternion& from) {
  return foldedTurnAngle(to * from.inverse());
}

}  // namespace patchspin::scenes
