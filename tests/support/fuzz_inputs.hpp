// Fuzz inputs that more than one core test uses, as the fuzz target decoded
// them (fuzz/corpus/).
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/models.hpp>

namespace patchspin::testing {

// The quadrilateral of fuzz/corpus/limits/
// refused-tipping-couple-inf-nan-pressure-ilogb (fuzz round 9, item 63).
inline PatchShape ilogbQuadrilateral() {
  return PatchShape::polygon({Vec2(0.40046074417845756, -0.33925202512364394),
                              Vec2(0.83925202512364394, -0.099539255821542438),
                              Vec2(0.59953925582154244, 0.33925202512364394),
                              Vec2(0.16074797487635606, 0.099539255821542438)});
}

// The dodecagon and pressure of the friction block's ill-conditioned K
// findings (the sixth fuzz round; friction_block_conditioning_test and
// friction_block_ill_conditioned_test), mu 0.5, rho 0.5.
inline FrictionPatch fuzzDodecagonPatch() {
  const PatchShape dodecagon = PatchShape::polygon({{0.93879128094518638, 0.7397127693021015},
                                                    {0.7601480116065954, 0.92699298829973165},
                                                    {0.51179829264545484, 0.99986078090869679},
                                                    {0.2602872306978985, 0.93879128094518638},
                                                    {0.073007011700268465, 0.7601480116065954},
                                                    {0.00013921909130315546, 0.51179829264545473},
                                                    {0.061208719054813621, 0.26028723069789855},
                                                    {0.23985198839340438, 0.073007011700268576},
                                                    {0.48820170735454504, 0.00013921909130315546},
                                                    {0.73971276930210139, 0.061208719054813621},
                                                    {0.92699298829973165, 0.23985198839340471},
                                                    {0.99986078090869679, 0.48820170735454499}});
  return FrictionPatch(
      dodecagon,
      LinearPressure::fromLoads(dodecagon,
                                {0.36071503384922143, -0.1370213875319439, 0.1908799795625202}),
      0.5, 0.5);
}

}  // namespace patchspin::testing
