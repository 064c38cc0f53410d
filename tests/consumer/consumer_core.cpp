// Uses the installed patchspin::core: ellipsoidal friction on a centred disk
// under uniform pressure, where Pi = I (Sect. 4.5.2), so Q = -mu Pz w.
#include <cmath>
#include <cstdio>
#include <patchspin/patchspin.hpp>

int main() {
  using namespace patchspin;
  const PatchShape disk = PatchShape::disk(0.05);
  const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, {10.0, 0.0, 0.0}), 0.5);
  const Vec3 w = Vec3(0.6, 0.0, 0.8);
  const Vec3 q = patch.ellipsoidalQ(w);
  std::printf("Q = (%.6f, %.6f, %.6f)\n", q.x(), q.y(), q.z());
  const Vec3 expected = -0.5 * 10.0 * w;
  return (q - expected).norm() < 1e-12 ? 0 : 1;
}
