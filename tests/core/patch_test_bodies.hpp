// Random bodies and frames for the tests of the patch parts (seeded).
#pragma once

#include <patchspin/parts/patch_body.hpp>

#include <Eigen/Geometry>

#include <random>

namespace patchspin::parts::testing {

inline Mat3 randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

// A body of 0.5-4 kg with a lever of up to 0.17 m and a random inertia of a
// 10-cm-sized body; lockedY: its linear factor (1, 0, 1).
inline PatchBody randomBody(std::mt19937& rng, bool lockedY = false) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.5, 4.0);
  PatchBody b;
  b.dynamic = true;
  b.r = Vec3(u(rng), u(rng), u(rng)) * 0.1;
  const double m = pos(rng);
  b.invM = lockedY ? Vec3(1.0 / m, 0.0, 1.0 / m) : Vec3::Constant(1.0 / m);
  const Mat3 R = randomRotation(rng);
  b.invI = R * Vec3(pos(rng), pos(rng), pos(rng)).asDiagonal() * R.transpose() * 50.0;
  return b;
}

inline Eigen::Matrix<double, 6, 6> inverseMass(const PatchBody& b) {
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  M.topLeftCorner<3, 3>() = b.invM.asDiagonal();
  M.bottomRightCorner<3, 3>() = b.invI;
  return M;
}

}  // namespace patchspin::parts::testing
