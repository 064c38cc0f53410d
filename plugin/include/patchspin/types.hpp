// Basic types of patchspin's core: Eigen fixed-size, double precision.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <string_view>

namespace patchspin {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// Every invalid input to the public API throws this, with a message that
// names the offending parameter and its value.
class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Friction law of a patch.
//   Ellipsoidal: Q = -mu Pz Pi w, Eq. (41)
//   Exact:       local Coulomb friction integrated over the patch, Eq. (16)
enum class Model { Ellipsoidal, Exact };

const char* toString(Model model);
// Parses "ellipsoidal" or "exact"; throws Error otherwise.
Model modelFromString(std::string_view name);

namespace internal {
// Throws Error("<what>: got <value>") unless value is finite.
void requireFinite(double value, const char* what);
void requireFinite(const Vec2& value, const char* what);
void requireFinite(const Vec3& value, const char* what);
// Throws Error unless value is finite and > 0.
void requirePositive(double value, const char* what);
std::string formatDouble(double value);
// The Frobenius norm of m without over- or underflow, as its nine entries'
// vector norm: Eigen 3.4.0's stableNorm() of a fixed-size matrix aborts on
// an assertion in builds without NDEBUG (Block.h:120, stable_norm_impl).
inline double stableMatrixNorm(const Mat3& m) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(m.data()).stableNorm();
}
}  // namespace internal

}  // namespace patchspin
