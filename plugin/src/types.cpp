#include <patchspin/types.hpp>

#include <cmath>
#include <cstdio>

namespace patchspin {

const char* toString(Model model) {
  return model == Model::Ellipsoidal ? "ellipsoidal" : "exact";
}

Model modelFromString(std::string_view name) {
  if (name == "ellipsoidal") return Model::Ellipsoidal;
  if (name == "exact") return Model::Exact;
  throw Error("model must be 'ellipsoidal' or 'exact': got '" + std::string(name) + "'");
}

namespace internal {

std::string formatDouble(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

void requireFinite(double value, const char* what) {
  if (!std::isfinite(value))
    throw Error(std::string(what) + " must be finite: got " + formatDouble(value));
}

void requireFinite(const Vec2& value, const char* what) {
  if (!value.allFinite()) {
    throw Error(std::string(what) + " must be finite: got (" + formatDouble(value.x()) + ", " +
                formatDouble(value.y()) + ")");
  }
}

void requireFinite(const Vec3& value, const char* what) {
  if (!value.allFinite()) {
    throw Error(std::string(what) + " must be finite: got (" + formatDouble(value.x()) + ", " +
                formatDouble(value.y()) + ", " + formatDouble(value.z()) + ")");
  }
}

void requirePositive(double value, const char* what) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw Error(std::string(what) + " must be positive and finite: got " + formatDouble(value));
  }
}

}  // namespace internal
}  // namespace patchspin
