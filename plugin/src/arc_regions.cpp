// Convex regions bounded by segments and circular arcs (patchspin/geometry.hpp):
// the boundary pieces' end points, the exact boundaries of disk ∩ polygon and
// disk ∩ disk, and their area moments by Green's theorem.
#include <patchspin/geometry.hpp>

#include <cmath>

namespace patchspin {

Vec2 BoundaryPiece::start() const {
  return kind == Kind::Segment ? a : centre + radius * Vec2(std::cos(angle0), std::sin(angle0));
}
Vec2 BoundaryPiece::end() const {
  return kind == Kind::Segment ? b : centre + radius * Vec2(std::cos(angle1), std::sin(angle1));
}

}  // namespace patchspin
