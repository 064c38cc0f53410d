// Where an attracting limit cycle of the fast dynamics (limit_cycles.hpp)
// dies as the force F along x grows or falls: the bifurcation between a force
// with the cycle and one without, located and classified.
//
// The one kind recognised is the saddle-node on the invariant circle (SNIC):
// a node (attracting on the sphere) and a saddle of V* are born together ON
// the cycle, which becomes their connection. Its signatures, all reported:
//  * on the side without the cycle, the node and the saddle are continued
//    towards the cycle's side; they merge at F*: their separation shrinks
//    as |F - F*|^(1/2) and the node's weak eigenvalue of (31), and the
//    saddle's positive one, tend to 0 (det of the projected Jacobian -> 0);
//  * the merged point lies on the cycle's track (distance -> 0);
//  * on the cycle's side, the period diverges as T ~ c |F - F*|^(-1/2)
//    (the orbit lingers at the ghost of the saddle-node), while the cycle's
//    extent stays finite (not a Hopf: amplitude -> 0) and no saddle is
//    approached (not a homoclinic loop of a hyperbolic saddle: T ~ -ln|F - F*|);
//    its Floquet multiplier falls towards 0 as the orbit lingers where the
//    flow contracts (at a fold of cycles it would rise to 1).
// F* is bisected on the existence of the node: at each force the fixed
// points (findLimitDirections) are searched for a node within 0.3 rad of the
// one last seen (on the cycle's track at fWithout); the reported F* is the
// final bracket's midpoint. The saddle is the one nearest the node at the
// last force with the node (at fWithout it may already have merged with
// another fixed point, as the thick disk's does by 0.14 mu m g). Any other
// change of the cycle count (no node born on the track: a Hopf bifurcation,
// a fold of cycles, ...) is returned as `Unclassified` with the bracket
// only: it is not located.
// Guarded by tests/core/cycle_bifurcation_test.cpp (the thick disk of issue
// 34, against an independent quadrature of the law and a plain root finder).
#pragma once

#include <patchspin/limit_cycles.hpp>
#include <vector>

namespace patchspin {

struct CycleBifurcation {
  enum Kind { Unclassified, SaddleNodeOnCycle };
  Kind kind = Unclassified;
  double withCycle = 0.0, withoutCycle = 0.0;  // the bracket given [N]
  double force = 0.0;                          // F* [N] (Unclassified: the bracket's midpoint)
  double forceError = 0.0;                     // half-width of the final bracket [N]
  Vec3 point = Vec3::Zero();      // the saddle-node at F* (mid of the last node-saddle pair)
  double pairSeparation = 0.0;    // |node - saddle| at the last force with the pair
  double nodeEigenvalue = 0.0;    // the node's eigenvalue nearest 0 there [m/s^2]
  double saddleEigenvalue = 0.0;  // the saddle's positive eigenvalue there [m/s^2]
  double distanceToCycle = 0.0;   // from `point` to the given cycle's orbit [rad]
  // the cycle on its side of F*, at distances |F - F*| from it
  struct Sample {
    double force = 0.0;   // [N]
    double period = 0.0;  // [s^2/m]
    double w3Min = 0.0, w3Max = 0.0;
    double multiplier = 0.0;
  };
  std::vector<Sample> approach;  // nearest last; a sample whose cycle was not found is left out
};

const char* toString(CycleBifurcation::Kind kind);

// The bifurcation between forces fWith (the body `base` with force.x() =
// fWith has the attracting cycle `cycle` under `law`) and fWithout (it has
// not), located to |F - F*| <= tol [N]. `approachOffsets`: the distances
// |F - F*| [N] at which the cycle is sampled (period, extent) as evidence.
CycleBifurcation locateCycleBifurcation(const FlatBody& base, Model law, double fWith,
                                        double fWithout, const LimitCycle& cycle, double tol,
                                        const std::vector<double>& approachOffsets = {});

}  // namespace patchspin
