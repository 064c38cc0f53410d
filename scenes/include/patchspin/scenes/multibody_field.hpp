// Fields of many grippers or feet in one btMultiBodyDynamicsWorld, the
// scenes of the multibody world benchmark (issue 33's speed goal;
// bench/bench_bullet_multibody.cpp), built from MultiBodyScene's gripper
// and leg on a square grid far enough apart that none touches another in
// the episode (stock Bullet's cubes, which slip, move at most 7 cm).
//
//   grippers  n two-finger grippers (addGripper: 4 x 4 cm pads, friction 1,
//             squeezing with 20 N) each closing on a 6 cm, 1 kg cube
//             (friction 0.5: mu = 0.5) without gravity, 0.3 m apart; after
//             0.25 s of closing, each cube is twisted about the grasp axis
//             y with half the grasp's limit 2 mu N dbar
//   feet      n legs (addLeg: a 2 kg shin on a 1 kg, 16 x 8 cm foot,
//             friction 0.6 on a ground of friction 1: mu = 0.6) standing
//             0.4 m apart under gravity; after 0.25 s, each foot is twisted
//             about z with 0.8 of its yaw limit mu M g dbar
//
// dbar is the mean distance of the contact rectangle (pad, sole) from its
// centre, for the uniform pressure both scenes press with; both torques are
// below the limit, so under the patch law every cube and foot holds
// (guarded by tests/bullet/multibody_field_test.cpp). A variant (speed_matrix.hpp's) picks
// the solver: stock btMultiBodyConstraintSolver, or PatchMultiBodySolver
// with no collider opted in, or every finger pad / foot opted in,
// ellipsoidal or exact.
#pragma once

#include <patchspin/scenes/multibody_scene.hpp>
#include <patchspin/scenes/speed_matrix.hpp>

#include <memory>
#include <string>
#include <vector>

namespace patchspin::scenes {

enum class MultiBodyFieldKind { Grippers, Feet };

const char* toString(MultiBodyFieldKind k);
// "grippers" or "feet"; Error on anything else.
MultiBodyFieldKind multiBodyFieldKindFromString(const std::string& name);

class MultiBodyField {
 public:
  static constexpr double kDt = 1.0 / 240.0;
  static constexpr int kSettleSteps = 60;  // 0.25 s before the twist
  static constexpr int kTwistSteps = 120;  // 0.5 s of twist

  MultiBodyField(MultiBodyFieldKind kind, int n, SpeedVariant variant);

  MultiBodyFieldKind kind() const { return kind_; }
  int size() const { return n_; }
  MultiBodyScene& scene() { return *scene_; }
  // The twist on each cube (about y) or foot (about z) [N m], and the
  // limit it is a fraction of (the grasp's, both pads; the foot's).
  double twist() const { return twist_; }
  double limit() const { return limit_; }
  // The colliders the patch variants opt in (both pads of each gripper,
  // each foot), whatever the variant.
  const std::vector<btMultiBodyLinkCollider*>& padsAndFeet() const { return opted_; }

  // One step of kDt: the twist is on from step kSettleSteps on, when each
  // twisted body's orientation is recorded.
  void step();
  int steps() const { return steps_; }
  static int episodeSteps() { return kSettleSteps + kTwistSteps; }
  // Largest turn of a cube or foot since the twist came on, about any axis,
  // folded into [0, pi] [rad] (0 before it came on).
  double largestTurn() const;
  // Largest move of a cube in the pads' plane (x-z) since the twist came
  // on [m] (0 for feet). (Along the grasp axis y the fingers and the cube
  // float together: the two motors balance only to the solver's
  // convergence, and the grasp drifts ~1 mm in 0.5 s without slipping.)
  double largestSlip() const;

 private:
  btQuaternion orientation(int i) const;
  MultiBodyFieldKind kind_;
  int n_;
  std::unique_ptr<MultiBodyScene> scene_;
  std::vector<btRigidBody*> cubes_;
  std::vector<btMultiBody*> legs_;
  std::vector<btMultiBodyLinkCollider*> opted_;
  std::vector<btQuaternion> atTwist_;
  std::vector<btVector3> cubeAtTwist_;
  double twist_ = 0.0, limit_ = 0.0;
  int steps_ = 0;
};

}  // namespace patchspin::scenes
