// patchspin::scenes::simulate: the single-body run of simulation.hpp in Bullet.
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/geometry.hpp>
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/scene.hpp>
#include <patchspin/scenes/simulate.hpp>

namespace patchspin::scenes {
namespace {

// Collision margin of the body [m]: far below Bullet's 0.04 m default so that
// stock Bullet sees the real shape of a coin; capped at a tenth of the
// smallest half size.
constexpr double kMargin = 1e-3;
// A run started in motion has stopped once its slip r falls below this
// fraction of r0; the stopping instant is then extrapolated within the step
// from the previous step's decrement (the implicit step stops the body part
// way through a step). 1e-5 r0 is far below any recorded fraction and far
// above the round-off of sticking in float (~1e-7 of g dt).
constexpr double kStopFraction = 1e-5;
// A run started at rest counts as at rest while r stays below this [m/s].
constexpr double kRestSlip = 1e-6;

void validate(const SimulationSpec& s) {
  if (s.model != "ellipsoidal" && s.model != "exact" && s.model != "stock")
    throw Error("model must be ellipsoidal, exact or stock: got " + s.model);
  if (s.precision != "float" && s.precision != "double")
    throw Error("precision must be float or double: got " + s.precision);
  if (s.precision != buildPrecision())
    throw Error("precision " + s.precision +
                " requested, but this patchspin::bullet is built against " + buildPrecision() +
                " Bullet (configure with -DPATCHSPIN_BULLET_DOUBLE=" +
                (s.precision == "double" ? "ON" : "OFF") + ")");
  if (s.shape == SimulationSpec::Shape::Cylinder) {
    internal::requirePositive(s.R, "R");
    internal::requirePositive(s.H, "H");
  } else {
    internal::requirePositive(s.LX, "LX");
    internal::requirePositive(s.LY, "LY");
    internal::requirePositive(s.LZ, "LZ");
  }
  internal::requirePositive(s.mass, "mass");
  internal::requirePositive(s.g, "g");
  internal::requirePositive(s.dt, "dt");
  internal::requirePositive(s.tMax, "t-max");
  internal::requirePositive(s.recordAt, "record-at");
  internal::requireFinite(s.mu, "mu");
  if (s.mu < 0.0) throw Error("mu must be >= 0: got " + internal::formatDouble(s.mu));
  internal::requireFinite(s.force, "force");
  internal::requireFinite(s.torque, "torque");
  internal::requireFinite(s.v0, "v0");
  internal::requireFinite(s.omega0, "omega0");
}

}  // namespace

const char* buildPrecision() {
  return sizeof(btScalar) == sizeof(double) ? "double" : "float";
}

SimulationResult simulate(const SimulationSpec& spec) {
  validate(spec);
  const bool cylinder = spec.shape == SimulationSpec::Shape::Cylinder;
  const double halfHeight = cylinder ? 0.5 * spec.H : 0.5 * spec.LZ;
  const double m = spec.mass;

  // world: static ground plane z = 0 (friction 1: combined friction = the
  // body's mu), gravity -g z
  Scene scene(spec.g);
  scene.addGroundPlane(1.0);

  // body on its flat face, exact inertia of the solid
  std::unique_ptr<btCollisionShape> shape;
  btVector3 inertia;
  double minHalf;
  if (cylinder) {
    shape = std::make_unique<btCylinderShapeZ>(bt(spec.R, spec.R, halfHeight));
    inertia = cylinderInertia(m, spec.R, spec.H);
    minHalf = std::min(spec.R, halfHeight);
  } else {
    shape = std::make_unique<btBoxShape>(bt(spec.LX / 2, spec.LY / 2, halfHeight));
    inertia = boxInertia(m, spec.LX, spec.LY, spec.LZ);
    minHalf = std::min({spec.LX / 2, spec.LY / 2, halfHeight});
  }
  shape->setMargin(btScalar(std::min(kMargin, 0.1 * minHalf)));
  btTransform start;
  start.setIdentity();
  start.setOrigin(bt(0, 0, halfHeight));
  btRigidBody& body = *scene.addBody(std::move(shape), m, inertia, start, spec.mu);
  body.setLinearVelocity(bt(spec.v0.x(), spec.v0.y(), 0));
  body.setAngularVelocity(bt(0, 0, spec.omega0));
  if (spec.model != "stock") {
    bullet::PatchOptions opt;
    opt.model = modelFromString(spec.model);
    opt.mu = spec.mu;
    scene.solver().enablePatchFriction(&body, opt);
  }

  // slip state in the force-aligned frame (x along the force, else along v0)
  const double rho = cylinder ? PatchShape::disk(spec.R).defaultRho()
                              : PatchShape::rectangle(spec.LX, spec.LY).defaultRho();
  Vec2 e1(1, 0);
  if (spec.force.norm() > 0)
    e1 = spec.force.normalized();
  else if (spec.v0.norm() > 0)
    e1 = spec.v0.normalized();
  const Vec2 e2(-e1.y(), e1.x());
  struct State {
    Vec2 position, velocity;
    double omega, tilt;
    Vec3 x;
  };
  auto observe = [&]() {
    const btTransform& tr = body.getWorldTransform();
    const btVector3 c = tr.getOrigin();
    const btVector3 p = tr * btVector3(0, 0, btScalar(-halfHeight));  // patch centre
    const btVector3 w = body.getAngularVelocity();
    const btVector3 v = body.getLinearVelocity() + w.cross(p - c);
    State s;
    s.position = Vec2(double(p.x()), double(p.y()));
    s.velocity = Vec2(double(v.x()), double(v.y()));
    s.omega = double(w.z());
    s.tilt = std::hypot(double(w.x()), double(w.y()));
    s.x = Vec3(s.velocity.dot(e1), s.velocity.dot(e2), rho * s.omega);
    return s;
  };

  SimulationResult result;
  const State s0 = observe();
  const double r0 = s0.x.norm();
  auto record = [&](double t, const State& s) {
    if (!spec.keepTrajectory) return;
    SimulationSample q;
    q.t = t;
    q.position = s.position - s0.position;
    q.psi = result.rotation;
    q.velocity = s.velocity;
    q.omega = s.omega;
    q.r = s.x.norm();
    q.w = q.r > 0 ? Vec3(s.x / q.r) : Vec3::Zero();
    q.tilt = s.tilt;
    result.trajectory.push_back(q);
  };
  record(0.0, s0);

  const btVector3 force = bt(spec.force.x(), spec.force.y(), 0);
  const btVector3 torque = bt(spec.torque.x(), spec.torque.y(), spec.torque.z());
  const long steps = long(std::ceil(spec.tMax / spec.dt - 1e-9));
  bool recorded = false;
  double rPrev = r0, rPrev2 = r0;
  double lastMoving = 0.0;
  State s = s0;
  State sPrev = s0;
  for (long k = 1; k <= steps; ++k) {
    if (k > 1) sPrev = s;
    body.applyCentralForce(force);
    body.applyTorque(torque);
    scene.step(spec.dt);
    const double t = k * spec.dt;
    s = observe();
    result.rotation += s.omega * spec.dt;  // Bullet integrates with the new velocity
    record(t, s);
    const double r = s.x.norm();
    const double dphi = std::remainder(std::atan2(s.velocity.y(), s.velocity.x()) -
                                           std::atan2(sPrev.velocity.y(), sPrev.velocity.x()),
                                       2.0 * std::acos(-1.0));
    if (r0 > 0) {
      if (!recorded && r < spec.recordAt * r0) {
        recorded = true;
        // w is undefined once the patch sticks (r ~ 0, or a creep set by the
        // applied force). If this step is the one that sticks, the slip fell
        // below the threshold within the step, where one step cannot resolve
        // it: record the last slipping step's direction instead.
        const bool stickStep = r <= kStopFraction * r0 && sPrev.x.norm() > 0;
        const State& at = stickStep ? sPrev : s;
        if (!stickStep) result.turn += dphi;
        const double rAt = at.x.norm();
        result.wStop = rAt > 0 ? Vec3(at.x / rAt) : Vec3::Zero();
        if (cylinder && at.omega != 0.0)
          result.epsStop = at.velocity.norm() / (spec.R * std::abs(at.omega));
      } else if (!recorded) {
        result.turn += dphi;
      }
      if (r <= kStopFraction * r0) {
        // stop part way through the step at the previous decrement rate
        const double dec = rPrev2 - rPrev;
        const double frac = dec > 0 ? std::min(1.0, rPrev / dec) : 1.0;
        result.stopped = true;
        result.tStop = t - spec.dt + frac * spec.dt;
        break;
      }
    } else if (r > kRestSlip) {
      lastMoving = t;
    }
    rPrev2 = rPrev;
    rPrev = r;
  }
  if (r0 == 0) {
    result.stopped = s.x.norm() <= kRestSlip;
    result.tStop = lastMoving;
  }
  result.displacement = s.position - s0.position;

  return result;
}

}  // namespace patchspin::scenes
