// grasp (issue 33, item 3): a cube squeezed between two flat pads and
// twisted about the grasp axis, stock Bullet beside the patch law, in the
// multibody world (a two-finger gripper of prismatic links, motors pressing
// with N: PatchMultiBodySolver against btMultiBodyConstraintSolver) and in
// the ordinary world (rigid pads pushed with N: PatchFrictionSolver against
// btSequentialImpulseConstraintSolver); the scene is scenes::Grasp. Two
// twist torques: one below the grasp's limit 2 mu N dbar (the patch law
// holds, stock Bullet's cube turns), one above it (the patch law slips with
// the friction torque mu N dbar per pad), dbar the mean distance of the
// square pad from its centre, (h / 3)(sqrt 2 + asinh 1) for half side h
// (uniform pressure; the pad within the cube face's inscribed circle).
//
// Each run settles for --t-settle with no twist, then is twisted for
// --t-twist. Writes into --out:
//   frame_NNNNN.png       one column per world and law, the lower torque on
//                         top; a dark stick on the cube shows its turn
//   rotation_below.png, rotation_above.png   the cube's turn about the grasp
//                         axis against time per run, with the patch law's
//                         prediction at the limit dashed (gnuplot)
//   grasp_series.csv      world,model,case,t,angle,omega of every step
//   summary.json          parameters; limit (dbar, mu N dbar per pad,
//                         2 mu N dbar); runs.<world>.<model>.<below|above>:
//                         tau [N m], turn [rad] (q q0^-1 at the end, folded
//                         into [0, pi]), max_turn [rad] (its largest value),
//                         angle [rad] (unwrapped turn about +y at the end),
//                         spin_rate [rad/s] (mean over the second half of the
//                         twist), friction_torque_per_pad [N m] ((tau - J
//                         alpha) / 2, alpha from the spin 0.1 s into the twist
//                         and at its end; null once ejected), ejected (the
//                         cube's centre moved more than a half side: thrown
//                         out of the grasp) and t_ejected [s] since the twist
//                         began, reported (patch laws: each pad's normal load
//                         Pz [N], friction torque |T_z| [N m] and sticking,
//                         from the solver's patch report at the end),
//                         prediction (the patch law's angle at the end: 0
//                         below the limit, (|tau| - 2 mu N dbar) t^2 / (2 J)
//                         above it, J = m s^2 / 6).
#include <patchspin/render/plot.hpp>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/grasp.hpp>
#include <patchspin/scenes/mean_distance.hpp>
#include <patchspin/scenes/simulate.hpp>
#include <patchspin/scenes/turn_angle.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "demo_common.hpp"

namespace {

using patchspin::Vec3;
namespace render = patchspin::render;
namespace demos = patchspin::demos;
namespace scenes = patchspin::scenes;
namespace fs = std::filesystem;

// alpha of the friction torque measurement from the spin this long into the
// twist (the pads' slip has started) to its end [s]
constexpr double kAlphaFrom = 0.1;

// The run options (video_args.hpp) with grasp's defaults: frames 0 is the
// whole run; tMax is unused (no --t-max: the run is t-settle + t-twist long).
struct Args : demos::VideoArgs {
  Args() {
    out = "demo-out/grasp";
    frames = 0;
    size = "1280x720";
    slowmo = 1.0;
  }
  std::string models = "exact,stock";
  std::string worlds = "multibody,rigid";
  double cubeSide = 0.06, cubeMass = 1.0, mu = 0.5;
  double padSide = 0.04, padDepth = 0.02, padMass = 0.1, squeeze = 20.0;
  double below = 0.1, above = 0.35;  // twist torques [N m]
  double tSettle = 0.25, tTwist = 2.0;
};

struct Sample {
  double t = 0.0;
  Eigen::Isometry3d cube = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pads[2];
  double angle = 0.0;  // unwrapped turn about +y since the twist began [rad]
  double omega = 0.0;  // spin about y [rad/s]
};

struct Run {
  scenes::GraspWorld world = scenes::GraspWorld::MultiBody;
  std::string worldName, model, caseName;  // "multibody"|"rigid", law, "below"|"above"
  double tau = 0.0;
  std::vector<Sample> samples;
  double turn = 0.0, maxTurn = 0.0, spinRate = 0.0, frictionTorque = 0.0;
  bool ejected = false;
  double tEjected = 0.0;  // since the twist began [s]
  nlohmann::json reported = nullptr;
};

scenes::GraspSpec specOf(const Args& a) {
  scenes::GraspSpec s;
  s.cubeHalf = 0.5 * a.cubeSide;
  s.cubeMass = a.cubeMass;
  s.mu = a.mu;
  s.padHalf = 0.5 * a.padSide;
  s.padHalfDepth = 0.5 * a.padDepth;
  s.padMass = a.padMass;
  s.squeeze = a.squeeze;
  return s;
}

void simulate(const Args& a, Run& run, double dt, long settleSteps, long twistSteps) {
  std::optional<patchspin::Model> model;
  if (run.model != "stock")
    model = run.model == "exact" ? patchspin::Model::Exact : patchspin::Model::Ellipsoidal;
  const scenes::GraspSpec spec = specOf(a);
  scenes::Grasp grasp(run.world, spec, model);
  btRigidBody* cube = grasp.cube();
  const btVector3 start = cube->getWorldTransform().getOrigin();
  btQuaternion q0 = cube->getWorldTransform().getRotation(), prev = q0;
  auto sample = [&](long k, double angle) {
    Sample s;
    s.t = double(k) * dt;
    s.cube = scenes::toIsometry(cube->getWorldTransform());
    for (int i = 0; i < 2; ++i) s.pads[i] = scenes::toIsometry(grasp.padPose(i));
    s.angle = angle;
    s.omega = double(cube->getAngularVelocity().y());
    run.samples.push_back(s);
  };
  run.samples.reserve(std::size_t(settleSteps + twistSteps) + 1);
  sample(0, 0.0);
  const long k0 = settleSteps + std::lround(kAlphaFrom / dt), k1 = settleSteps + twistSteps;
  double angle = 0.0, w0 = 0.0;
  for (long k = 1; k <= k1; ++k) {
    const bool twisting = k > settleSteps;
    grasp.step(dt, twisting ? run.tau : 0.0);
    const btQuaternion q = cube->getWorldTransform().getRotation();
    if (k == settleSteps) q0 = prev = q;
    if (twisting) {
      // the step's turn about +y (the world-frame increment q prev^-1)
      // (w >= 0: the short way, the step's turn in (-pi, pi])
      btQuaternion dq = q * prev.inverse();
      if (dq.w() < 0) dq = -dq;
      angle += 2.0 * std::atan2(double(dq.y()), double(dq.w()));
      prev = q;
      run.maxTurn = std::max(run.maxTurn, scenes::foldedTurnAngle(q, q0));
    }
    if (k == k0) w0 = double(cube->getAngularVelocity().y());
    const btVector3 moved = cube->getWorldTransform().getOrigin() - start;
    if (!run.ejected && double(moved.length()) > spec.cubeHalf) {
      run.ejected = true;
      run.tEjected = double(k - settleSteps) * dt;
    }
    sample(k, angle);
  }
  run.turn = scenes::foldedTurnAngle(cube->getWorldTransform().getRotation(), q0);
  const double jy = a.cubeMass * a.cubeSide * a.cubeSide / 6.0;
  const double w1 = double(cube->getAngularVelocity().y());
  run.frictionTorque = 0.5 * (run.tau - jy * (w1 - w0) / (double(k1 - k0) * dt));
  const Sample& mid = run.samples[std::size_t(settleSteps + twistSteps / 2)];
  run.spinRate = (angle - mid.angle) / (double(k1) * dt - mid.t);
  if (grasp.patch()) {
    nlohmann::json pz = nlohmann::json::array(), tz = nlohmann::json::array(),
                   stick = nlohmann::json::array();
    for (int i = 0; i < 2; ++i) {
      const patchspin::bullet::PatchReport* r = grasp.report(i);
      pz.push_back(r ? demos::jsonOrNull(r->loads.Pz) : nlohmann::json(nullptr));
      tz.push_back(r ? demos::jsonOrNull(std::abs(r->Q.z()) * r->rho) : nlohmann::json(nullptr));
      stick.push_back(r ? nlohmann::json(r->sticking) : nlohmann::json(nullptr));
    }
    run.reported = {{"patches", grasp.reportCount()},
                    {"normal_load", pz},
                    {"friction_torque", tz},
                    {"sticking", stick}};
  }
}

// ---- frames -------------------------------------------------------------------------

constexpr double kStickLength = 0.05;  // the stick on the cube's top [m]

struct Layout {
  std::vector<Vec3> offsets;  // of each run's grasp, where it is drawn
  double columnSpacing = 0.0, rowSpacing = 0.0;
};

// Columns: world, then law; rows: below (top), above.
Layout layOut(const Args& a, const std::vector<Run>& runs, int columns) {
  Layout l;
  l.columnSpacing = 2.6 * (a.cubeSide + 2 * a.padDepth);
  l.rowSpacing = 2.0 * (a.cubeSide + kStickLength) + 0.03;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int column = int(i / 2), row = runs[i].caseName == "below" ? 0 : 1;
    l.offsets.push_back(
        Vec3(l.columnSpacing * (column - 0.5 * (columns - 1)), 0.0, -l.rowSpacing * row));
  }
  return l;
}

std::vector<render::SceneBody> drawGrasp(const Args& a, const Sample& s, const Vec3& offset,
                                         const render::Rgb& colour) {
  const Eigen::Translation3d shift(offset);
  std::vector<render::SceneBody> bodies;
  render::SceneBody cube;
  cube.kind = render::SceneBody::Box;
  cube.dimensions = Vec3::Constant(a.cubeSide);
  cube.pose = shift * s.cube;
  cube.colour = colour;
  bodies.push_back(cube);
  render::SceneBody stick;
  stick.kind = render::SceneBody::Box;
  stick.dimensions = Vec3(0.008, 0.008, kStickLength);
  stick.pose = shift * s.cube * Eigen::Translation3d(0, 0, 0.5 * (a.cubeSide + kStickLength));
  stick.colour = {0.15, 0.15, 0.2};
  stick.spinMarker = false;
  bodies.push_back(stick);
  for (const Eigen::Isometry3d& p : s.pads) {
    render::SceneBody pad;
    pad.kind = render::SceneBody::Box;
    pad.dimensions = Vec3(a.padSide, a.padDepth, a.padSide);
    pad.pose = shift * p;
    pad.colour = {0.35, 0.42, 0.5};
    pad.spinMarker = false;
    bodies.push_back(pad);
  }
  return bodies;
}

std::string valueText(const Args& a, const Run& run, const Sample& s) {
  char text[64];
  if ((s.cube.translation() - run.samples.front().cube.translation()).norm() > 0.5 * a.cubeSide)
    std::snprintf(text, sizeof text, "%s: thrown out", run.model.c_str());
  else
    std::snprintf(text, sizeof text, "%s: %+.4f rad", run.model.c_str(), s.angle);
  return text;
}

std::string worldLabel(const std::string& world) {
  return world == "multibody" ? "multibody world" : "ordinary world";
}

void writeFrames(const Args& a, const std::vector<Run>& runs,
                 const std::vector<std::string>& columns, long settleSteps, long steps, int stride,
                 int frames, double limit) {
  int width = 0, height = 0;
  demos::parseSize(a.size, width, height);
  const Layout layout = layOut(a, runs, int(columns.size()));
  // camera: every grasp at its start, and room for a full turn of the stick
  std::vector<Vec3> corners;
  const double reach = 0.5 * a.cubeSide + kStickLength;
  for (const Vec3& o : layout.offsets)
    for (double dx : {-reach, reach})
      for (double dz : {-reach, reach})
        for (double dy : {-0.5 * a.cubeSide - a.padDepth, 0.5 * a.cubeSide + a.padDepth})
          corners.push_back(o + Vec3(dx, dy, dz));
  const int panelLines = 2 + int(columns.size());  // title, time, the columns
  const double panelFraction = (panelLines * 1.35 + 2.2) / 36.0;
  const double fitTop = std::max(demos::kFitBottom + 0.5, 1.0 - 2.0 * panelFraction);
  const render::Camera camera =
      demos::fitSceneCamera(corners, -75.0, 12.0, double(width) / height, fitTop);

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  double lowest = 0.0;
  for (const Vec3& c : corners) lowest = std::min(lowest, c.z());
  options.groundHeight = lowest - 0.05;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out, a.fps);
  char title[256];
  std::snprintf(title, sizeof title,
                "grasp: %g cm cube squeezed with %g N by two %g cm pads, mu %g, twisted about the "
                "grasp axis",
                100 * a.cubeSide, a.squeeze, 100 * a.padSide, a.mu);
  char caption[256];
  std::snprintf(caption, sizeof caption,
                "top: tau = %g N m, bottom: tau = %g N m; the patch limit 2 mu N dbar = %.4f N m; "
                "twist from t = %g s",
                a.below, a.above, 2 * limit, a.tSettle);
  const double dt = 1.0 / a.rate;
  if (a.progress) demos::printProgress("grasp", 0, frames);
  for (int f = 0; f < frames; ++f) {
    const std::size_t now = std::size_t(std::min(long(f) * stride, steps));
    render::Scene scene;
    scene.camera = camera;
    scene.overlay.time = double(now) * dt;
    scene.overlay.title = title;
    scene.overlay.caption = caption;
    // the columns, left to right, named in the panel
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const Run& run = runs[2 * c];
      render::TrackedBody column;
      column.label =
          "column " + std::to_string(c + 1) + ": " + worldLabel(run.worldName) + ", " +
          (run.model == "stock" ? std::string("stock Bullet") : run.model + " patch law");
      column.colour = demos::rowColour(run.model);
      scene.overlay.tracked.push_back(column);
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const Run& run = runs[i];
      const Sample& s = run.samples[now];
      const render::Rgb colour = demos::rowColour(run.model);
      for (const render::SceneBody& b : drawGrasp(a, s, layout.offsets[i], colour))
        scene.bodies.push_back(b);
      // the stick's tip over the last half second
      render::Trail trail;
      trail.colour = colour;
      const std::size_t from =
          now > std::size_t(0.5 * a.rate) ? now - std::size_t(0.5 * a.rate) : 0;
      for (std::size_t j = std::max<std::size_t>(from, std::size_t(settleSteps)); j <= now; ++j)
        trail.points.push_back(Eigen::Translation3d(layout.offsets[i]) * run.samples[j].cube *
                               Vec3(0, 0, 0.5 * a.cubeSide + kStickLength));
      // (not once the cube is out of the grasp: it spins freely)
      const bool out = run.ejected && double(now) * dt >= a.tSettle + run.tEjected;
      if (trail.points.size() > 1 && !out) scene.trails.push_back(trail);
      // the turn, written below the grasp (a label without an arrow)
      render::Arrow value;
      value.origin = layout.offsets[i] + Vec3(-0.5 * a.cubeSide, 0, -0.5 * a.cubeSide - 0.025);
      value.vector = Vec3::Zero();
      value.colour = {0.0, 0.0, 0.0};
      value.label = valueText(a, run, s);
      scene.arrows.push_back(value);
    }
    writer.write(renderer.render(scene));
    if (a.progress) demos::printProgress("grasp", f + 1, frames);
  }
}

// ---- plots, series, summary -----------------------------------------------------------

// The cube's turn against time since the twist began, per run of one case,
// with the patch law's prediction dashed: holding below the limit, and
// above it turning at (tau - 2 mu N dbar) t^2 / (2 J) from rest.
void plotCase(const Args& a, const std::vector<Run>& runs, const std::string& caseName, double tau,
              double limit, long settleSteps, double dt) {
  render::GroundTrackPlot plot;
  plot.xLabel = "time since the twist began [s]";
  plot.yLabel = "turn of the cube about the grasp axis [rad]";
  for (const Run& run : runs) {
    if (run.caseName != caseName) continue;
    render::GroundTrack track;
    track.label = worldLabel(run.worldName) + ", " + run.model;
    if (run.ejected) {
      char out[64];
      std::snprintf(out, sizeof out, " (thrown out at %.2f s)", run.tEjected);
      track.label += out;
    }
    for (std::size_t k = std::size_t(settleSteps); k < run.samples.size(); ++k)
      track.points.push_back(
          render::Vec2(run.samples[k].t - double(settleSteps) * dt, run.samples[k].angle));
    plot.tracks.push_back(track);
  }
  const double jy = a.cubeMass * a.cubeSide * a.cubeSide / 6.0;
  const double excess = std::max(0.0, std::abs(tau) - 2 * limit);
  render::GroundTrack prediction;
  prediction.label = excess > 0 ? "patch law: slips with 2 mu N dbar" : "patch law: holds";
  prediction.dashed = true;
  prediction.colour = "#000000";
  for (int i = 0; i <= 100; ++i) {
    const double t = a.tTwist * i / 100.0;
    prediction.points.push_back(render::Vec2(t, std::copysign(excess * t * t / (2 * jy), tau)));
  }
  plot.tracks.push_back(prediction);
  render::PlotOptions po;
  char title[160];
  std::snprintf(title, sizeof title,
                "grasp twisted with tau = %g N m (limit 2 mu N dbar = %.4f N m)", tau, 2 * limit);
  po.title = title;
  render::plotGroundTracks(plot, (fs::path(a.out) / ("rotation_" + caseName + ".png")).string(),
                           po);
}

void writeSeries(const Args& a, const std::vector<Run>& runs) {
  const fs::path path = fs::path(a.out) / "grasp_series.csv";
  std::ofstream csv(path);
  csv << "world,model,case,t,angle,omega\n";
  for (const Run& run : runs)
    for (const Sample& s : run.samples) {
      char line[200];
      std::snprintf(line, sizeof line, "%s,%s,%s,%.9g,%.9g,%.9g\n", run.worldName.c_str(),
                    run.model.c_str(), run.caseName.c_str(), s.t, s.angle, s.omega);
      csv << line;
    }
  if (!csv) throw render::RenderError("cannot write " + path.string());
}

nlohmann::json runSummary(const Args& a, const Run& run, double limit) {
  nlohmann::json m = {
      {"tau", run.tau},
      {"turn", run.turn},
      {"max_turn", run.maxTurn},
      {"angle", run.samples.back().angle},
      {"spin_rate", demos::jsonOrNull(run.spinRate)},
      {"friction_torque_per_pad",
       run.ejected ? nlohmann::json(nullptr) : demos::jsonOrNull(run.frictionTorque)},
      {"ejected", run.ejected},
      {"t_ejected", run.ejected ? nlohmann::json(run.tEjected) : nlohmann::json(nullptr)},
      {"reported", run.reported}};
  if (std::abs(run.tau) > 2 * limit) {
    const double jy = a.cubeMass * a.cubeSide * a.cubeSide / 6.0;
    m["prediction"] = {
        {"source", "patch law: slips with friction torque 2 mu N dbar, from rest"},
        {"angle",
         std::copysign((std::abs(run.tau) - 2 * limit) * a.tTwist * a.tTwist / (2 * jy), run.tau)}};
  } else {
    m["prediction"] = {{"source", "patch law: holds (|tau| < 2 mu N dbar)"}, {"angle", 0.0}};
  }
  return m;
}

void validate(const Args& a) {
  int width = 0, height = 0;
  demos::parseSize(a.size, width, height);
  const std::pair<const char*, double> positive[] = {
      {"--cube-side", a.cubeSide}, {"--cube-mass", a.cubeMass}, {"--mu", a.mu},
      {"--pad-side", a.padSide},   {"--pad-depth", a.padDepth}, {"--pad-mass", a.padMass},
      {"--squeeze", a.squeeze},    {"--rate", a.rate},          {"--fps", a.fps},
      {"--slowmo", a.slowmo},      {"--t-twist", a.tTwist}};
  for (const auto& [name, v] : positive)
    if (!(v > 0 && std::isfinite(v))) throw CLI::ValidationError(name, "must be > 0 and finite");
  if (!(a.tSettle >= 0 && std::isfinite(a.tSettle)))
    throw CLI::ValidationError("--t-settle", "must be >= 0 and finite");
  if (!std::isfinite(a.below) || !std::isfinite(a.above))
    throw CLI::ValidationError("--torque-below/--torque-above", "must be finite");
  if (a.frames < 0) throw CLI::ValidationError("--frames", "must be >= 0 (0: the whole run)");
  // the limit mu N dbar holds while the pad's square lies within the cube
  // face at every turn, i.e. within its inscribed circle
  if (a.padSide * std::sqrt(2.0) > a.cubeSide)
    throw CLI::ValidationError("--pad-side",
                               "the pad's diagonal must fit the cube face's inscribed circle "
                               "(pad side <= cube side / sqrt 2)");
  if (a.tTwist <= kAlphaFrom)
    throw CLI::ValidationError("--t-twist", "must exceed the 0.1 s the torque measurement skips");
}

int run(const Args& a) {
  validate(a);
  const std::vector<std::string> worlds =
      demos::splitList(a.worlds, "--worlds", {"multibody", "rigid"});
  const std::vector<std::string> models =
      demos::splitList(a.models, "--models", {"exact", "ellipsoidal", "stock"});
  const double dt = 1.0 / a.rate;
  const long settleSteps = std::lround(a.tSettle / dt), twistSteps = std::lround(a.tTwist / dt);
  const long steps = settleSteps + twistSteps;
  // per pad, mu N dbar
  const double dbar = scenes::meanDistanceOfRectangle(0.5 * a.padSide, 0.5 * a.padSide),
               limit = a.mu * a.squeeze * dbar;

  std::vector<Run> runs;
  std::vector<std::string> columns;
  for (const std::string& w : worlds)
    for (const std::string& m : models) {
      columns.push_back(w + "," + m);
      for (const char* c : {"below", "above"}) {
        Run r;
        r.world = w == "multibody" ? scenes::GraspWorld::MultiBody : scenes::GraspWorld::Rigid;
        r.worldName = w;
        r.model = m;
        r.caseName = c;
        r.tau = r.caseName == "below" ? a.below : a.above;
        runs.push_back(std::move(r));
      }
    }
  for (Run& r : runs) simulate(a, r, dt, settleSteps, twistSteps);

  const int stride = std::max(1, int(std::lround(a.rate / (a.fps * a.slowmo))));
  const int frames = a.frames > 0 ? a.frames : int(steps / stride) + 1;
  fs::create_directories(a.out);
  writeFrames(a, runs, columns, settleSteps, steps, stride, frames, limit);
  writeSeries(a, runs);
  if (a.plot) {
    demos::plotOrWarn("grasp", [&] {
      plotCase(a, runs, "below", a.below, limit, settleSteps, dt);
      plotCase(a, runs, "above", a.above, limit, settleSteps, dt);
    });
  }

  nlohmann::json summary;
  summary["parameters"] = {
      {"cube_side", a.cubeSide}, {"cube_mass", a.cubeMass}, {"mu", a.mu},
      {"pad_side", a.padSide},   {"pad_depth", a.padDepth}, {"pad_mass", a.padMass},
      {"squeeze", a.squeeze},    {"torque_below", a.below}, {"torque_above", a.above},
      {"rate", a.rate},          {"t_settle", a.tSettle},   {"t_twist", a.tTwist}};
  summary["precision"] = scenes::buildPrecision();
  summary["dt"] = dt;
  summary["limit"] = {
      {"source",
       "uniform pressure on the square pad: mu N dbar per pad, dbar = h (sqrt 2 + asinh 1) "
       "/ 3 for half side h"},
      {"mean_distance", dbar},
      {"per_pad", limit},
      {"grasp", 2 * limit}};
  summary["video"] = {{"frames", frames}, {"fps", a.fps}, {"steps_per_frame", stride}};
  nlohmann::json out = nlohmann::json::object();
  for (const Run& r : runs) out[r.worldName][r.model][r.caseName] = runSummary(a, r, limit);
  summary["runs"] = out;
  demos::writeJson(fs::path(a.out) / "summary.json", summary);
  std::printf("grasp: %d frames, %ssummary.json, grasp_series.csv in %s\n", frames,
              a.plot ? "rotation_below.png, rotation_above.png, " : "", a.out.c_str());
  for (const Run& r : runs)
    if (r.ejected)
      std::printf("  %-9s %-11s tau %+.3f N m: thrown out after %.3f s\n", r.worldName.c_str(),
                  r.model.c_str(), r.tau, r.tEjected);
    else
      std::printf("  %-9s %-11s tau %+.3f N m: turned %.4g rad, friction torque per pad %.5f N m\n",
                  r.worldName.c_str(), r.model.c_str(), r.tau, r.samples.back().angle,
                  r.frictionTorque);
  std::printf("  limit per pad mu N dbar = %.5f N m (grasp %.5f N m)\n", limit, 2 * limit);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{
      "grasp: a cube squeezed by two flat pads and twisted about the grasp axis, stock Bullet "
      "beside the patch law, in the multibody world (a two-finger gripper) and in the ordinary "
      "world (rigid pads); below and above the patch limit 2 mu N dbar (headless: PNG frames, "
      "rotation plots, summary.json)"};
  demos::addFrameOptions(app, a, demos::withDefault("output directory", a.out),
                         "number of frames; 0: the whole run");
  demos::addSlowmoOption(app, a);
  app.add_option("--models", a.models,
                 "comma list of exact, ellipsoidal, stock: the columns (default exact,stock)");
  app.add_option("--worlds", a.worlds,
                 "comma list of multibody (btMultiBodyDynamicsWorld, gripper links), rigid "
                 "(btDiscreteDynamicsWorld, rigid pads) (default multibody,rigid)");
  app.add_option("--torque-below", a.below,
                 "twist torque of the top row [N m] (default 0.1, a third of the limit 0.306)");
  app.add_option("--torque-above", a.above,
                 "twist torque of the bottom row [N m] (default 0.35, above the limit 0.306)");
  app.add_option("--cube-side", a.cubeSide, "cube edge [m] (default 0.06)");
  app.add_option("--cube-mass", a.cubeMass, "cube mass [kg] (default 1)");
  app.add_option("--mu", a.mu, "friction coefficient between pads and cube (default 0.5)");
  app.add_option("--pad-side", a.padSide, "side of the square pad face [m] (default 0.04)");
  app.add_option("--pad-depth", a.padDepth,
                 "pad thickness along the grasp axis [m] (default 0.02)");
  app.add_option("--pad-mass", a.padMass, "mass of a pad (finger) [kg] (default 0.1)");
  app.add_option("--squeeze", a.squeeze, "force N with which each pad presses [N] (default 20)");
  demos::addRateOption(app, a);
  app.add_option("--t-settle", a.tSettle,
                 "time the pads close before the twist [s] (default 0.25)");
  app.add_option("--t-twist", a.tTwist, "duration of the twist [s] (default 2)");
  demos::addOutputFlags(app, a, "rotation_*.png");
  return demos::runMain(app, argc, argv, "grasp", [&] { return run(a); });
}
