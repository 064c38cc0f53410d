// Principal moments of inertia of uniform solids about their centre of mass
// [kg m^2], in the shape's own axes: the one place for these formulas (every
// world and body builder of the tests, demos, tools and benchmarks uses them).
// Each is evaluated in double, in the order written, and rounded to btScalar
// once: the scenes' results depend on these bits (tests/bullet/determinism).
#pragma once

#include <btBulletDynamicsCommon.h>

namespace patchspin::scenes {

// Solid cylinder, radius R, height H [m], axis z:
//   J_x = J_y = m (3 R^2 + H^2) / 12,   J_z = m R^2 / 2
inline btVector3 cylinderInertia(double m, double R, double H) {
  const double jx = m * (3 * R * R + H * H) / 12;
  return btVector3(btScalar(jx), btScalar(jx), btScalar(m * R * R / 2));
}

// Solid box, full side lengths lx, ly, lz [m]:
//   J_x = m (ly^2 + lz^2) / 12, and cyclically
inline btVector3 boxInertia(double m, double lx, double ly, double lz) {
  return btVector3(btScalar(m * (ly * ly + lz * lz) / 12), btScalar(m * (lx * lx + lz * lz) / 12),
                   btScalar(m * (lx * lx + ly * ly) / 12));
}

// Solid sphere, radius r [m]: J = 2 m r^2 / 5
inline btVector3 sphereInertia(double m, double r) {
  const double j = 0.4 * m * r * r;
  return btVector3(btScalar(j), btScalar(j), btScalar(j));
}

// Solid regular hexagonal prism, circumradius a, height h [m], axis z:
//   J_z = 5 m a^2 / 12,   J_x = J_y = J_z / 2 + m h^2 / 12
inline btVector3 hexagonalPrismInertia(double m, double a, double h) {
  const double jz = 5.0 / 12.0 * m * a * a, jx = 0.5 * jz + m * h * h / 12;
  return btVector3(btScalar(jx), btScalar(jx), btScalar(jz));
}

}  // namespace patchspin::scenes
