// Fuzz inputs that more than one core test uses, as the fuzz target decoded
// them (fuzz/corpus/).
#pragma once

#include <patchspin/geometry.hpp>

namespace patchspin::testing {

// The quadrilateral of fuzz/corpus/limits/
// refused-tipping-couple-inf-nan-pressure-ilogb (fuzz round 9, item 63).
inline PatchShape ilogbQuadrilateral() {
  return PatchShape::polygon({Vec2(0.40046074417845756, -0.33925202512364394),
                              Vec2(0.83925202512364394, -0.099539255821542438),
                              Vec2(0.59953925582154244, 0.33925202512364394),
                              Vec2(0.16074797487635606, 0.099539255821542438)});
}

}  // namespace patchspin::testing
