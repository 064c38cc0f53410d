// What the nearest admissible loads of polygons (admissible_loads.cpp) and
// of arc regions (admissible_loads_arc_region.cpp) share: the scaled loads
// y = (Pz, Tx / rho, Ty / rho), and the projection onto the cone of a
// polygon's admissible loads, which an arc region's circumscribed polygon
// falls back to.
#pragma once

#include <patchspin/pressure.hpp>

#include <cstddef>
#include <vector>

namespace patchspin::internal {

// relative slack of the KKT tests for round-off (the old candidate search
// accepted feasibility to the same 1e-12)
constexpr double kKktSlack = 1e-12;

// the loads of scaled loads l
inline PatchLoads loadsOfScaled(const Vec3& l, double rho) {
  return PatchLoads{l[0], l[1] * rho, l[2] * rho};
}

// M maps pressure coefficients to scaled loads: (Pz, Ty, -Tx) = G pi, then
// (Pz, Tx / rho, Ty / rho)
Mat3 scaledLoadMatrix(const PatchShape& shape, double rho);

// Projection of y onto the edge ray of faces ni, nj (rows of vertex
// pressures) if its KKT conditions hold; false otherwise.
bool edgeProjection(const Vec3& ni, const Vec3& nj, const Vec3& y, Vec3& out);

// kInside: no vertex pressure is negative in the rows' arithmetic (y on
// K's boundary to round-off, where the kern test rounded the other way);
// kNone: no candidate passes to round-off (the fallback search decides).
enum class KktResult { kFound, kInside, kNone };

// The projection of y onto the cone of loads of pressures >= 0 at the
// polygon `vertices`, by its KKT conditions, starting the walk at vertex
// `worst` (the most negative one).
KktResult projectPolygonByKkt(const PatchShape& shape, const std::vector<Vec2>& vertices,
                              const Mat3& M, const Vec3& y, double rho, std::size_t worst,
                              Vec3& out);

// The former candidate search (every face and adjacent-edge candidate, each
// tested against every constraint): the fallback where the KKT search finds
// nothing to round-off or a vertex pressure is not finite.
Vec3 projectPolygonBySearch(const PatchShape& shape, const std::vector<Vec2>& vertices,
                            const Mat3& M, const Vec3& y, double rho);

// nearestAdmissibleLoads for an arc region and Pz > 0; `admissible`: the
// result is known admissible with tolerance 0 (isAdmissible's decision,
// taken on the way), so the caller's own check would only repeat it.
PatchLoads nearestAdmissibleArcRegion(const PatchShape& shape, const PatchLoads& loads, double rho,
                                      bool& admissible);

}  // namespace patchspin::internal
