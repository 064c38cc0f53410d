// blocks (issue 5, demo 5): rectangular and square blocks sliding and
// spinning to rest, the patch law against stock Bullet's point friction.
// One Bullet world per model (default: the exact law and stock Bullet), each
// holding the same scene, drawn as rows side by side:
//   rect    a rectangular block sliding and spinning, at the world origin
//           with the settings of `patchspin simulate --engine bullet
//           --shape box:LX,LY,LZ` (the tracked block: same numbers)
//   square  a square block spinning in place (closed-form stopping time)
//   coin    a thin cylinder sliding and spinning (opted in like the blocks)
//   sphere  a ball rolling off, never opted in (stock Bullet in every row)
//   stack   three blocks standing on each other, at rest
// In the patch rows every body but the sphere is opted in
// (PatchFrictionSolver::enablePatchFriction); in the stock row none is.
//
// Writes <out>/frame_NNNNN.png, <out>/summary.json and <out>/blocks_series.csv
// (every moving body's samples). Stopping data follow
// patchspin::scenes::simulate (simulate.hpp): slip x = (u_x, u_y, rho w_z) of
// the patch centre in the frame of v0, rho = Eq. (11) for the face; w_stop
// recorded when r first falls below 1% of r0; stopped once r <= 1e-5 r0, the
// instant extrapolated within the step.
//
// summary.json: rows.<model>.bodies.<key> with
//   rect, square, coin   parameters, stopped, t_stop [s], w_stop, ratio_stop
//                        = |v| / (rho |omega|) at the record (coin also eps_stop
//                        = |v| / (R |omega|)), displacement [m] and distance
//                        (path length) [m] and rotation [rad] up to the stop,
//                        t_spin_stop (|omega| <= 1e-5 |omega0|, extrapolated),
//                        final_yaw [rad], final_slip [m/s] (stock Bullet creeps),
//                        prediction: square: the closed form t = omega0 J_z /
//                        (mu m g arm), arm = mean|r| of the face (patch laws) or
//                        the half diagonal (stock: 4 corner points); rect, coin
//                        in patch rows: the reference dynamics of the same body
//                        (`patchspin simulate --engine reference`)
//   sphere               t_roll, final_speed; prediction 5/7 v0 after 2 v0/(7 mu g)
//   stack0..2            max_shift [m], max_tilt [rad], final_position
// and rows.<model>.stack: stands (every block within 2 mm of its start).
#include <btBulletDynamicsCommon.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <patchspin/analysis.hpp>
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/geometry.hpp>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/scene.hpp>
#include <patchspin/scenes/simulate.hpp>
#include <string>
#include <vector>

#include "demo_common.hpp"

namespace {

using patchspin::Vec2;
using patchspin::Vec3;
namespace render = patchspin::render;
namespace demos = patchspin::demos;
namespace fs = std::filesystem;
using demos::addCorners;
using demos::fitSceneCamera;
using demos::kFitBottom;
using demos::rowColour;

// As patchspin::scenes::simulate: stopped below kStopFraction r0, w recorded
// below kRecordFraction r0.
constexpr double kStopFraction = 1e-5;
constexpr double kRecordFraction = 0.01;
// The stack stands if no block's centre ever moves more than this from where
// it started [m]: settling into the 1 mm margins and float round-off move it
// by well under a millimetre, toppling or sliding off by centimetres.
constexpr double kStackTolerance = 2e-3;
// The sphere rolls once its contact point slips slower than this fraction of
// its initial speed.
constexpr double kRollFraction = 1e-3;
// Stopping ratio of the exact law for a uniformly pressed thin disk
// (DESIGN.md, Farkas et al. 2003), shown for the coin.
constexpr double kCoinReferenceRatio = 0.653;
// Gap between two neighbouring rows [m] on top of the scene's depth.
constexpr double kRowGap = 0.12;

struct Args : demos::VideoArgs {
  Args() { out = "demo-out/blocks"; }
  std::string model = "exact,stock";
  double mu = 0.3, g = 9.81;
  // rectangular block (the tracked one): face LX x LY, height LZ
  double rectLX = 0.15, rectLY = 0.075, rectLZ = 0.04, rectMass = 1.0;
  double rectV0 = 0.5, rectV0Angle = 0.0, rectOmega0 = 15.0;
  // square block spinning in place
  double squareSide = 0.1, squareLZ = 0.04, squareMass = 1.0, squareOmega0 = 20.0;
  // coin
  double coinRadius = 0.05, coinHeight = 0.005, coinMass = 0.03, coinV0 = 0.5, coinOmega0 = 20.0;
  // sphere
  double sphereRadius = 0.03, sphereMass = 0.1, sphereV0 = 0.15;
  // stack: sides bottom to top, each stackLZ high
  double stackBottom = 0.12, stackMiddle = 0.1, stackTop = 0.08, stackLZ = 0.04, stackMass = 0.5;
};

// ---- closed forms -------------------------------------------------------------------

// Mean distance of a uniform LX x LY rectangle from its centre:
//   (4 / (LX LY)) int_0^a int_0^b sqrt(x^2 + y^2) dy dx, a = LX/2, b = LY/2,
//   int_0^a int_0^b r = (2 a b d + a^3 ln((b + d)/a) + b^3 ln((a + d)/b)) / 6,
//   d = sqrt(a^2 + b^2); for a square of side s: (s/6)(sqrt 2 + ln(1 + sqrt 2)).
double meanDistanceRectangle(double lx, double ly) {
  const double a = 0.5 * lx, b = 0.5 * ly, d = std::hypot(a, b);
  const double integral =
      (2 * a * b * d + a * a * a * std::log((b + d) / a) + b * b * b * std::log((a + d) / b)) / 6;
  return 4 * integral / (lx * ly);
}

// ---- bodies -------------------------------------------------------------------------

using Kind = patchspin::scenes::BodyKind;
using BodyDef = patchspin::scenes::RowBody;

struct Sample {
  double t = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // body -> own world
  Vec3 patchCentre = Vec3::Zero();                         // world [m]
  Vec2 velocity = Vec2::Zero();                            // of the patch centre [m/s]
  double omega = 0.0;                                      // spin [rad/s]
  Vec3 x = Vec3::Zero();                                   // (u_x, u_y, rho w_z) [m/s]
  double r = 0.0;
};

struct BodyRun {
  const BodyDef* def = nullptr;
  btRigidBody* body = nullptr;
  double halfHeight = 0.0;  // centre of mass above the patch [m]
  double rho = 0.0;         // Eq. (11) length of the face; 0 for the sphere
  Vec2 e1 = Vec2(1, 0);     // slip frame: x along v0
  std::vector<Sample> samples;
  // stopping data (simulate.hpp semantics)
  bool stopped = false, recorded = false;
  double tStop = 0.0;
  Vec3 wStop = Vec3::Zero();
  std::optional<double> epsStop;    // cylinder: |v| / (R |omega|) at the record
  std::optional<double> ratioStop;  // |v| / (rho |omega|) at the record
  Vec2 displacement = Vec2::Zero();
  double path = 0.0;      // travelled distance of the patch centre until the stop [m]
  double rotation = 0.0;  // until the stop [rad]
  double rPrev = 0.0, rPrev2 = 0.0;
  // spin: stopped once |omega| <= kStopFraction |omega0|, extrapolated as r
  std::optional<double> tSpinStop;
  double omegaPrev = 0.0, omegaPrev2 = 0.0;
  // sphere
  std::optional<double> tRoll;
  // stack
  double maxShift = 0.0, maxTilt = 0.0;

  double r0() const { return samples.front().r; }
  bool atRest(std::size_t i) const {
    const Sample& s = samples[std::min(i, samples.size() - 1)];
    return (stopped && s.t >= tStop) || (r0() > 0 && s.r <= kStopFraction * r0());
  }
};

struct Row {
  std::string model;  // "exact" | "ellipsoidal" | "stock"
  std::string label;
  Vec3 offset = Vec3::Zero();  // where its world is drawn
  std::vector<BodyRun> runs;
};

// Every body of the scene, in world coordinates of its own row: the
// catalogue's blocks row with this run's parameters.
std::vector<BodyDef> sceneBodies(const Args& a) {
  patchspin::scenes::BlocksRowSpec spec;
  spec.mu = a.mu;
  spec.g = a.g;
  spec.rectLX = a.rectLX;
  spec.rectLY = a.rectLY;
  spec.rectLZ = a.rectLZ;
  spec.rectMass = a.rectMass;
  spec.rectV0 = a.rectV0;
  spec.rectV0Angle = a.rectV0Angle;
  spec.rectOmega0 = a.rectOmega0;
  spec.squareSide = a.squareSide;
  spec.squareLZ = a.squareLZ;
  spec.squareMass = a.squareMass;
  spec.squareOmega0 = a.squareOmega0;
  spec.coinRadius = a.coinRadius;
  spec.coinHeight = a.coinHeight;
  spec.coinMass = a.coinMass;
  spec.coinV0 = a.coinV0;
  spec.coinOmega0 = a.coinOmega0;
  spec.sphereRadius = a.sphereRadius;
  spec.sphereMass = a.sphereMass;
  spec.sphereV0 = a.sphereV0;
  spec.stackBottom = a.stackBottom;
  spec.stackMiddle = a.stackMiddle;
  spec.stackTop = a.stackTop;
  spec.stackLZ = a.stackLZ;
  spec.stackMass = a.stackMass;
  return patchspin::scenes::blocksRow(spec);
}

// One row: its own Bullet world (a scenes::Scene), built as scenes::simulate builds
// its single-body world (static plane z = 0 of friction 1, bodies of friction
// mu, no rolling/spinning friction, no restitution, never deactivated, 10
// solver iterations), stepped `steps` times.
class RowWorld {
 public:
  RowWorld(const Args& a, Row& row, const std::vector<BodyDef>& defs)
      : model_(row.model), scene_(a.g) {
    scene_.addGroundPlane(1.0);
    for (const BodyDef& d : defs) {
      BodyRun run;
      run.def = &d;
      run.body = addBody(a, d);
      run.halfHeight = d.kind == Kind::Sphere ? d.size.x() : 0.5 * d.size.z();
      if (d.kind == Kind::Box)
        run.rho = patchspin::PatchShape::rectangle(d.size.x(), d.size.y()).defaultRho();
      if (d.kind == Kind::Cylinder) run.rho = patchspin::PatchShape::disk(d.size.x()).defaultRho();
      if (d.v0.norm() > 0) run.e1 = d.v0.normalized();
      row.runs.push_back(std::move(run));
    }
  }
  RowWorld(const RowWorld&) = delete;
  RowWorld& operator=(const RowWorld&) = delete;

  void step(double dt) { scene_.step(dt); }

 private:
  btRigidBody* addBody(const Args& a, const BodyDef& d) {
    return patchspin::scenes::addRowBody(scene_, d, a.mu,
                                         patchspin::scenes::frictionFromString(model_));
  }

  std::string model_;
  patchspin::scenes::Scene scene_;
};

Sample observe(const BodyRun& run, double t) {
  const btRigidBody& body = *run.body;
  const btTransform& tr = body.getWorldTransform();
  const btVector3 c = tr.getOrigin();
  // patch centre: the face centre below the centre of mass (the sphere's
  // lowest point)
  const btVector3 p = run.def->kind == Kind::Sphere
                          ? c - btVector3(0, 0, btScalar(run.halfHeight))
                          : tr * btVector3(0, 0, btScalar(-run.halfHeight));
  const btVector3 w = body.getAngularVelocity();
  const btVector3 v = body.getLinearVelocity() + w.cross(p - c);
  Sample s;
  s.t = t;
  s.pose = patchspin::scenes::toIsometry(tr);
  s.patchCentre = Vec3(double(p.x()), double(p.y()), double(p.z()));
  s.velocity = Vec2(double(v.x()), double(v.y()));
  s.omega = double(w.z());
  const Vec2 e2(-run.e1.y(), run.e1.x());
  s.x = Vec3(s.velocity.dot(run.e1), s.velocity.dot(e2), run.rho * s.omega);
  s.r = s.x.norm();
  return s;
}

// The stopping bookkeeping of simulate() after one step.
void track(BodyRun& run, const Sample& s, double dt) {
  const Sample& first = run.samples.front();
  const Sample& prev = run.samples.back();
  if (!run.def->moving) {
    run.maxShift = std::max(run.maxShift, (s.pose.translation() - first.pose.translation()).norm());
    const double cosTilt = std::clamp(s.pose.linear()(2, 2), -1.0, 1.0);
    run.maxTilt = std::max(run.maxTilt, std::acos(cosTilt));
    return;
  }
  const double r0 = run.r0();
  if (run.def->kind == Kind::Sphere) {
    if (!run.tRoll && s.r <= kRollFraction * r0) run.tRoll = s.t;
    return;
  }
  const double omega0 = std::abs(first.omega);
  if (!run.tSpinStop && omega0 > 0.0) {
    const double om = std::abs(s.omega);
    if (om <= kStopFraction * omega0) {
      const double dec = run.omegaPrev2 - run.omegaPrev;
      const double frac = dec > 0 ? std::min(1.0, run.omegaPrev / dec) : 1.0;
      run.tSpinStop = s.t - dt + frac * dt;
    }
    run.omegaPrev2 = run.omegaPrev;
    run.omegaPrev = om;
  }
  if (run.stopped || r0 <= 0.0) return;
  run.rotation += s.omega * dt;  // Bullet integrates with the new velocity
  run.path += (s.patchCentre - prev.patchCentre).head<2>().norm();
  run.displacement = (s.patchCentre - first.patchCentre).head<2>();
  if (!run.recorded && s.r < kRecordFraction * r0) {
    run.recorded = true;
    // the step that sticks: record the last slipping step instead (simulate())
    const Sample& at = (s.r <= kStopFraction * r0 && prev.r > 0) ? prev : s;
    run.wStop = at.r > 0 ? Vec3(at.x / at.r) : Vec3::Zero();
    if (at.omega != 0.0) {
      run.ratioStop = at.velocity.norm() / (run.rho * std::abs(at.omega));
      if (run.def->kind == Kind::Cylinder)
        run.epsStop = at.velocity.norm() / (run.def->size.x() * std::abs(at.omega));
    }
  }
  if (s.r <= kStopFraction * r0) {
    const double dec = run.rPrev2 - run.rPrev;
    const double frac = dec > 0 ? std::min(1.0, run.rPrev / dec) : 1.0;
    run.stopped = true;
    run.tStop = s.t - dt + frac * dt;
  }
  run.rPrev2 = run.rPrev;
  run.rPrev = s.r;
}

// Runs one row for `steps` steps of dt, keeping every body's samples.
void simulateRow(const Args& a, Row& row, const std::vector<BodyDef>& defs, double dt, long steps) {
  RowWorld world(a, row, defs);
  for (BodyRun& run : row.runs) {
    run.samples.reserve(std::size_t(steps) + 1);
    run.samples.push_back(observe(run, 0.0));
    run.rPrev = run.rPrev2 = run.r0();
    run.omegaPrev = run.omegaPrev2 = std::abs(run.samples.front().omega);
  }
  for (long k = 1; k <= steps; ++k) {
    world.step(dt);
    for (BodyRun& run : row.runs) {
      const Sample s = observe(run, double(k) * dt);
      track(run, s, dt);
      run.samples.push_back(s);
    }
  }
}

render::SceneBody drawBody(const BodyRun& run, const Sample& s, const Vec3& offset,
                           const render::Rgb& colour) {
  render::SceneBody b;
  b.pose = Eigen::Translation3d(offset) * s.pose;
  b.colour = colour;
  const BodyDef& d = *run.def;
  switch (d.kind) {
    case Kind::Box:
      b.kind = render::SceneBody::Box;
      b.dimensions = d.size;
      break;
    case Kind::Cylinder:
      b.kind = render::SceneBody::Cylinder;
      b.dimensions = d.size;
      break;
    case Kind::Sphere: {
      // a Fibonacci sphere of 48 points
      b.kind = render::SceneBody::ConvexHull;
      constexpr int kPoints = 48;
      const double golden = std::acos(-1.0) * (3.0 - std::sqrt(5.0));
      for (int i = 0; i < kPoints; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / kPoints, rr = std::sqrt(1.0 - z * z);
        b.hullPoints.push_back(d.size.x() *
                               Vec3(rr * std::cos(golden * i), rr * std::sin(golden * i), z));
      }
      break;
    }
  }
  return b;
}

render::Rgb shade(const render::Rgb& c, double f) {
  return {std::clamp(c.r * f, 0.0, 1.0), std::clamp(c.g * f, 0.0, 1.0),
          std::clamp(c.b * f, 0.0, 1.0)};
}

render::Rgb bodyColour(const Row& row, const BodyDef& d) {
  const render::Rgb base = rowColour(row.model);
  if (d.kind == Kind::Sphere) return {0.30, 0.65, 0.55};  // never opted in: the same in every row
  if (d.key == "square") return shade(base, 0.8);
  if (d.key == "coin") return shade(base, 1.1);
  if (d.key == "stack1") return shade(base, 0.75);
  return base;
}

std::string rowLabel(const std::string& model) {
  if (model == "stock") return "stock Bullet (point friction)";
  return model + " patch law";
}

nlohmann::json vec(const Vec2& v) {
  return {v.x(), v.y()};
}
nlohmann::json vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

// The SimulationSpec of a box or cylinder as `patchspin simulate` takes it.
patchspin::SimulationSpec specOf(const Args& a, const BodyDef& d, const std::string& model,
                                 double dt, double tMax) {
  patchspin::SimulationSpec s;
  if (d.kind == Kind::Box) {
    s.shape = patchspin::SimulationSpec::Shape::Box;
    s.LX = d.size.x();
    s.LY = d.size.y();
    s.LZ = d.size.z();
  } else {
    s.shape = patchspin::SimulationSpec::Shape::Cylinder;
    s.R = d.size.x();
    s.H = d.size.z();
  }
  s.model = model;
  s.mass = d.mass;
  s.mu = a.mu;
  s.g = a.g;
  s.v0 = d.v0;
  s.omega0 = d.omega0;
  s.dt = dt;
  s.tMax = tMax;
  return s;
}

// Stopping data and predictions of one body of one row.
nlohmann::json bodySummary(const Args& a, const Row& row, const BodyRun& run, double dt,
                           double tMax) {
  const BodyDef& d = *run.def;
  const Sample& last = run.samples.back();
  nlohmann::json m;
  m["label"] = d.label;
  m["kind"] = d.kind == Kind::Box ? "box" : d.kind == Kind::Cylinder ? "cylinder" : "sphere";
  m["model"] = (row.model != "stock" && d.patch) ? row.model : "stock";
  nlohmann::json p = {{"mass", d.mass},  {"mu", a.mu},         {"g", a.g},
                      {"v0", vec(d.v0)}, {"omega0", d.omega0}, {"position", vec(d.position)}};
  if (d.kind == Kind::Box) {
    p["LX"] = d.size.x();
    p["LY"] = d.size.y();
    p["LZ"] = d.size.z();
  } else {
    p["R"] = d.size.x();
    if (d.kind == Kind::Cylinder) p["H"] = d.size.z();
  }
  m["parameters"] = p;
  const double yawEnd = std::atan2(last.pose.linear()(1, 0), last.pose.linear()(0, 0));
  if (!d.moving) {  // stack block
    m["max_shift"] = run.maxShift;
    m["max_tilt"] = run.maxTilt;
    m["final_position"] = vec(Vec3(last.pose.translation()));
    return m;
  }
  if (d.kind == Kind::Sphere) {
    // slides until v = (5/7) v0 rolling, after t = 2 v0 / (7 mu g)
    const double v0 = d.v0.norm();
    m["t_roll"] = run.tRoll ? nlohmann::json(*run.tRoll) : nlohmann::json(nullptr);
    const Sample& end = run.samples.back();
    const Sample& before = run.samples[run.samples.size() - 2];
    m["final_speed"] = (end.pose.translation() - before.pose.translation()).head<2>().norm() / dt;
    m["final_displacement"] =
        vec(Vec2((end.patchCentre - run.samples.front().patchCentre).head<2>()));
    m["prediction"] = {{"source", "sliding ball: rolls at v = 5/7 v0 after t = 2 v0 / (7 mu g)"},
                       {"t_roll", 2 * v0 / (7 * a.mu * a.g)},
                       {"speed", 5.0 / 7.0 * v0}};
    return m;
  }
  m["rho"] = run.rho;
  m["stopped"] = run.stopped;
  m["t_stop"] = run.stopped ? nlohmann::json(run.tStop) : nlohmann::json(nullptr);
  m["w_stop"] = run.recorded ? vec(run.wStop) : nlohmann::json(nullptr);
  m["ratio_stop"] = run.ratioStop ? demos::jsonOrNull(*run.ratioStop) : nlohmann::json(nullptr);
  if (d.kind == Kind::Cylinder)
    m["eps_stop"] = run.epsStop ? demos::jsonOrNull(*run.epsStop) : nlohmann::json(nullptr);
  m["displacement"] = vec(run.displacement);
  m["distance"] = run.path;
  m["rotation"] = run.rotation;
  m["final_yaw"] = yawEnd;
  m["t_spin_stop"] = run.tSpinStop ? nlohmann::json(*run.tSpinStop) : nlohmann::json(nullptr);
  // stock Bullet creeps on after its stop (coin demo): the slip at the end
  m["final_slip"] = last.r;
  m["final_displacement"] =
      vec(Vec2((last.patchCentre - run.samples.front().patchCentre).head<2>()));

  // predictions
  const bool patchLaw = m["model"] != "stock";
  nlohmann::json pred = nullptr;
  if (d.key == "square" && d.v0.norm() == 0.0) {
    // pure spin of a uniformly pressed face: torque mu m g mean|r| (patch
    // laws; the exact law Eq. (16) directly, the ellipsoidal one through
    // Pi w for w = (0,0,1)), or mu m g d from Bullet's four corner points at
    // the half diagonal d; J_z = m (LX^2 + LY^2) / 12
    const double jz = d.mass * (d.size.x() * d.size.x() + d.size.y() * d.size.y()) / 12;
    const double arm = patchLaw ? meanDistanceRectangle(d.size.x(), d.size.y())
                                : 0.5 * std::hypot(d.size.x(), d.size.y());
    pred = {
        {"source", patchLaw ? "closed form: t = omega0 J_z / (mu m g mean|r|)"
                            : "four corner points: t = omega0 J_z / (mu m g d), d = half diagonal"},
        {patchLaw ? "mean_r" : "half_diagonal", arm},
        {"t_spin_stop", std::abs(d.omega0) * jz / (a.mu * d.mass * a.g * arm)}};
    // the patch laws stop slip and spin together (no drift by symmetry);
    // stock Bullet stops spinning, then creeps (final_slip)
    if (patchLaw) pred["t_stop"] = pred["t_spin_stop"];
  } else if (patchLaw) {
    // the reference dynamics of the same body (`patchspin simulate --engine reference`)
    patchspin::SimulationSpec spec = specOf(a, d, row.model, dt, tMax);
    spec.engine = "reference";
    const patchspin::SimulationResult r = patchspin::simulateReference(spec);
    pred = {{"source", "reference dynamics (patchspin simulate --engine reference)"},
            {"stopped", r.stopped},
            {"t_stop", r.stopped ? nlohmann::json(r.tStop) : nlohmann::json(nullptr)},
            {"w_stop", vec(r.wStop)},
            {"displacement", vec(r.displacement)},
            {"rotation", r.rotation}};
    if (d.kind == Kind::Cylinder && row.model == "exact")
      pred["reference_ratio"] = kCoinReferenceRatio;
  }
  m["prediction"] = pred;
  return m;
}

int run(const Args& a) {
  int width = 0, height = 0;
  demos::parseSize(a.size, width, height);
  const std::vector<double> positive = {
      a.g,          a.rectLX,      a.rectLY,      a.rectLZ,     a.rectMass, a.squareSide,
      a.squareLZ,   a.squareMass,  a.coinRadius,  a.coinHeight, a.coinMass, a.sphereRadius,
      a.sphereMass, a.stackBottom, a.stackMiddle, a.stackTop,   a.stackLZ,  a.stackMass,
      a.fps,        a.rate,        a.slowmo,      a.tMax};
  for (double v : positive)
    if (!(v > 0 && std::isfinite(v)))
      throw CLI::ValidationError("parameters",
                                 "sizes, masses, g, fps, rate, slowmo, "
                                 "t-max must be > 0");
  for (double v : {a.mu, a.rectV0, a.rectV0Angle, a.rectOmega0, a.squareOmega0, a.coinV0,
                   a.coinOmega0, a.sphereV0})
    if (!std::isfinite(v))
      throw CLI::ValidationError("parameters", "speeds and spins must be finite");
  if (a.mu < 0) throw CLI::ValidationError("--mu", "must be >= 0");
  if (a.frames < 1) throw CLI::ValidationError("--frames", "must be >= 1");

  // rows: one world per model
  std::vector<Row> rows;
  for (const std::string& m : demos::lawList(a.model)) {
    Row row;
    row.model = m;
    row.label = rowLabel(m);
    rows.push_back(row);
  }

  const std::vector<BodyDef> defs = sceneBodies(a);
  const demos::TimeBase time = demos::timeBase(a);
  const auto [dt, k, frameSteps, steps] = time;
  const double tMax = double(steps) * dt;
  for (Row& row : rows) simulateRow(a, row, defs, dt, steps);

  // rows side by side along y, the first at the back
  double reach = 0.0;
  for (const BodyDef& d : defs) reach = std::max(reach, 0.5 * std::hypot(d.size.x(), d.size.y()));
  const double pi = std::acos(-1.0);
  const double rectTravelY =
      a.rectV0 * a.rectV0 / (a.mu * a.g) * std::abs(std::sin(a.rectV0Angle * pi / 180.0));
  const double spacing = 2 * reach + rectTravelY + kRowGap;
  for (std::size_t i = 0; i < rows.size(); ++i)
    rows[i].offset = Vec3(0, spacing * (0.5 * double(rows.size() - 1) - double(i)), 0);

  // camera: fits every body at every rendered instant below the panel (two
  // lines and one per tracked body, 1.35 font heights each, font = height/36)
  std::vector<Vec3> corners;
  for (const Row& row : rows)
    for (const BodyRun& r : row.runs)
      for (long s = 0; s <= frameSteps; s += k)
        addCorners(drawBody(r, r.samples[std::size_t(s)], row.offset, bodyColour(row, *r.def)),
                   corners);
  const int panelLines = 2 + 3 * int(rows.size());
  const double panelFraction = (panelLines * 1.35 + 2.2) / 36.0;
  const double fitTop = std::max(kFitBottom + 0.5, 1.0 - 2.0 * panelFraction);
  const render::Camera camera =
      fitSceneCamera(corners, -90.0, 40.0, double(width) / height, fitTop);

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out, a.fps);
  std::string rowsText;
  const char* places[] = {"back", "front", "middle"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const char* place = rows.size() == 1       ? ""
                        : i == 0               ? places[0]
                        : i + 1 == rows.size() ? places[1]
                                               : places[2];
    rowsText += std::string(rowsText.empty() ? "" : ", ") + rows[i].label + (*place ? " (" : "") +
                place + (*place ? ")" : "");
  }
  char title[200];
  std::snprintf(title, sizeof title, "blocks, mu = %g: %s", a.mu, rowsText.c_str());
  // the spin-down times of the square the caption quotes
  const double squareJz = a.squareMass * a.squareSide * a.squareSide / 6;
  const double tFace =
      std::abs(a.squareOmega0) * squareJz /
      (a.mu * a.squareMass * a.g * meanDistanceRectangle(a.squareSide, a.squareSide));
  const double tCorners = std::abs(a.squareOmega0) * squareJz /
                          (a.mu * a.squareMass * a.g * a.squareSide / std::sqrt(2.0));
  char caption[200];
  std::snprintf(caption, sizeof caption,
                "square spinning in place stops after %.3f s with friction on its face, "
                "%.3f s at 4 corner points; the sphere is never opted in",
                tFace, tCorners);
  std::string modelText;
  for (const Row& row : rows) modelText += (modelText.empty() ? "" : " | ") + row.model;
  if (a.progress) demos::printProgress("blocks", 0, a.frames);
  for (int f = 0; f < a.frames; ++f) {
    const std::size_t now = std::size_t(f) * std::size_t(k);
    render::Scene scene;
    scene.camera = camera;
    scene.overlay.time = double(now) * dt;
    scene.overlay.title = title;
    scene.overlay.model = modelText;
    scene.overlay.caption = caption;
    for (const Row& row : rows) {
      for (const BodyRun& r : row.runs) {
        const Sample& s = r.samples[now];
        const render::Rgb colour = bodyColour(row, *r.def);
        scene.bodies.push_back(drawBody(r, s, row.offset, colour));
        if (!r.def->moving) continue;
        render::Trail trail;
        trail.colour = colour;
        const std::size_t stride = std::max<std::size_t>(1, now / 200);
        for (std::size_t j = now % stride; j <= now; j += stride)
          trail.points.push_back(Vec3(r.samples[j].patchCentre.x() + row.offset.x(),
                                      r.samples[j].patchCentre.y() + row.offset.y(),
                                      options.groundHeight));
        scene.trails.push_back(trail);
        if (r.def->kind == Kind::Sphere) continue;
        render::TrackedBody tracked;
        tracked.label =
            (row.model == "stock" ? std::string("stock ") : row.model + " ") + r.def->label;
        tracked.colour = colour;
        // as the coin demo: stock Bullet stops spinning first and creeps on
        const bool spinless = r.rho * std::abs(s.omega) <= kStopFraction * r.r0();
        if (r.atRest(now)) {
          tracked.label += s.r <= kStopFraction * r.r0() ? " (at rest)" : " (stopped, creeping)";
        } else if (spinless && s.r <= kRecordFraction * r.r0()) {
          tracked.label += " (spin stopped, creeping)";
        } else if (spinless) {
          tracked.label += " (sliding, no spin)";
          tracked.w = Vec3(s.x / s.r);
        } else if (s.r > 0) {
          tracked.w = Vec3(s.x / s.r);
          if (r.def->kind == Kind::Cylinder)
            tracked.slipRatio = s.velocity.norm() / (r.def->size.x() * std::abs(s.omega));
        }
        scene.overlay.tracked.push_back(tracked);
      }
    }
    writer.write(renderer.render(scene));
    if (a.progress) demos::printProgress("blocks", f + 1, a.frames);
  }

  // summary.json
  nlohmann::json summary;
  summary["parameters"] = {{"mu", a.mu}, {"g", a.g}, {"rate", a.rate}, {"t_max", tMax}};
  summary["video"] = demos::videoSummary(a, time);
  summary["precision"] = patchspin::scenes::buildPrecision();
  summary["dt"] = dt;
  summary["t_max"] = tMax;
  summary["steps"] = steps;
  nlohmann::json out = nlohmann::json::object();
  for (const Row& row : rows) {
    nlohmann::json bodies = nlohmann::json::object();
    bool stands = true;
    double worstShift = 0.0, worstTilt = 0.0;
    for (const BodyRun& r : row.runs) {
      bodies[r.def->key] = bodySummary(a, row, r, dt, tMax);
      if (!r.def->moving) {
        worstShift = std::max(worstShift, r.maxShift);
        worstTilt = std::max(worstTilt, r.maxTilt);
        stands = stands && r.maxShift <= kStackTolerance;
      }
    }
    nlohmann::json m;
    m["label"] = row.label;
    m["bodies"] = bodies;
    m["stack"] = {{"stands", stands},
                  {"max_shift", worstShift},
                  {"max_tilt", worstTilt},
                  {"tolerance", kStackTolerance}};
    out[row.model] = m;
  }
  summary["rows"] = out;
  const fs::path dir(a.out);
  demos::writeJson(dir / "summary.json", summary);
  // every moving body's samples, for plots of one's own
  {
    std::ofstream csv(dir / "blocks_series.csv");
    csv << "row,body,t,x,y,yaw,vx,vy,omega,r\n";
    for (const Row& row : rows)
      for (const BodyRun& r : row.runs) {
        if (!r.def->moving) continue;
        for (const Sample& q : r.samples) {
          char line[256];
          std::snprintf(line, sizeof line, "%s,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                        row.model.c_str(), r.def->key.c_str(), q.t, q.patchCentre.x(),
                        q.patchCentre.y(), std::atan2(q.pose.linear()(1, 0), q.pose.linear()(0, 0)),
                        q.velocity.x(), q.velocity.y(), q.omega, q.r);
          csv << line;
        }
      }
    if (!csv) throw render::RenderError("cannot write " + (dir / "blocks_series.csv").string());
  }
  std::printf("blocks: %d frames (%s ...), summary.json, blocks_series.csv in %s\n", writer.count(),
              fs::path(writer.framePath(0)).filename().c_str(), a.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{
      "blocks: rectangular and square blocks sliding and spinning to rest with the patch law and "
      "with "
      "stock Bullet, side by side, plus a stack, a coin and a sphere (headless, PNG frames)"};
  demos::addFrameOptions(app, a, "output directory (frames, summary.json)");
  app.add_option(
      "--model", a.model,
      "exact | ellipsoidal | stock, or a comma list drawn as rows (default exact,stock)");
  app.add_option("--mu", a.mu,
                 "friction coefficient of every body on the floor and on each other (default 0.3)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  app.add_option(
         "--rect-size",
         [&a](const CLI::results_t& r) {
           if (r.size() != 3) return false;
           a.rectLX = std::stod(r[0]);
           a.rectLY = std::stod(r[1]);
           a.rectLZ = std::stod(r[2]);
           return true;
         },
         "rectangle LX LY LZ [m] (default 0.15 0.075 0.04)")
      ->expected(3);
  app.add_option("--rect-mass", a.rectMass, "rectangle mass [kg] (default 1)");
  app.add_option("--rect-v0", a.rectV0, "rectangle initial speed [m/s] (default 0.5)");
  app.add_option("--rect-v0-angle", a.rectV0Angle, "direction of v0 from +x [deg] (default 0)");
  app.add_option("--rect-omega0", a.rectOmega0, "rectangle initial spin [rad/s] (default 15)");
  app.add_option("--square-side", a.squareSide, "square block side [m] (default 0.1)");
  app.add_option("--square-height", a.squareLZ, "square block height [m] (default 0.04)");
  app.add_option("--square-mass", a.squareMass, "square block mass [kg] (default 1)");
  app.add_option("--square-omega0", a.squareOmega0,
                 "square block spin, in place [rad/s] (default 20)");
  app.add_option("--coin-radius", a.coinRadius, "coin radius [m] (default 0.05)");
  app.add_option("--coin-height", a.coinHeight, "coin thickness [m] (default 0.005)");
  app.add_option("--coin-mass", a.coinMass, "coin mass [kg] (default 0.03)");
  app.add_option("--coin-v0", a.coinV0, "coin initial speed along x [m/s] (default 0.5)");
  app.add_option("--coin-omega0", a.coinOmega0, "coin initial spin [rad/s] (default 20)");
  app.add_option("--sphere-radius", a.sphereRadius, "sphere radius [m] (default 0.03)");
  app.add_option("--sphere-mass", a.sphereMass, "sphere mass [kg] (default 0.1)");
  app.add_option("--sphere-v0", a.sphereV0,
                 "sphere initial speed along x, not rolling [m/s] (default 0.15)");
  app.add_option(
         "--stack-sides",
         [&a](const CLI::results_t& r) {
           if (r.size() != 3) return false;
           a.stackBottom = std::stod(r[0]);
           a.stackMiddle = std::stod(r[1]);
           a.stackTop = std::stod(r[2]);
           return true;
         },
         "sides of the stacked square blocks, bottom to top [m] (default 0.12 0.1 0.08)")
      ->expected(3);
  app.add_option("--stack-height", a.stackLZ, "height of each stacked block [m] (default 0.04)");
  app.add_option("--stack-mass", a.stackMass, "mass of each stacked block [kg] (default 0.5)");
  demos::addTimeOptions(app, a);
  demos::addOutputFlags(app, a, "");  // no plots
  return demos::runMain(app, argc, argv, "blocks", [&] { return run(a); });
}
