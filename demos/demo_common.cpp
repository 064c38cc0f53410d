// Shared machinery of the scene demos (see demo_common.hpp).
#include "demo_common.hpp"

#include <btBulletDynamicsCommon.h>

#include <patchspin/analysis.hpp>
#include <patchspin/geometry.hpp>
#include <patchspin/render/plot.hpp>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/simulate.hpp>
#include <patchspin/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include <unistd.h>

namespace patchspin::demos {
namespace {

namespace fs = std::filesystem;

// Lateral spacing of the bodies in the frame, in radii.
constexpr double kSpacingRadii = 3.0;
// Automatic force arrow: the largest force is drawn this many radii long.
constexpr double kArrowRadii = 2.0;

// The body's sample at step index i (held at the last one after the stop).
const SimulationSample& sampleAt(const SimulationResult& r, std::size_t i) {
  return r.trajectory[std::min(i, r.trajectory.size() - 1)];
}

render::SceneBody drawBody(const DemoBody& b, const SimulationSample& s, const Vec3& offset) {
  render::SceneBody d;
  d.kind = render::SceneBody::Cylinder;
  d.dimensions = Vec3(b.spec.R, b.spec.R, b.spec.H);
  d.pose = Eigen::Translation3d(offset + Vec3(s.position.x(), s.position.y(), 0.5 * b.spec.H)) *
           Eigen::AngleAxisd(s.psi, Vec3::UnitZ());
  d.colour = b.colour;
  return d;
}

// The flat body of the analysis for a cylinder standing on its face: the
// patch a disk, C at height H/2 above its centre, Jz = m R^2 / 2.
FlatBody flatBodyOf(const SimulationSpec& s) {
  FlatBody fb;
  fb.shape = PatchShape::disk(s.R);
  fb.mass = s.mass;
  fb.Jz = 0.5 * s.mass * s.R * s.R;
  fb.com = Vec3(0, 0, 0.5 * s.H);
  fb.mu = s.mu;
  fb.g = s.g;
  fb.force = s.force;
  fb.torque = s.torque;
  return fb;
}

render::LimitKind kindOf(LimitType t) {
  switch (t) {
    case LimitType::Dominant:
      return render::LimitKind::Dominant;
    case LimitType::Isolated:
      return render::LimitKind::Isolated;
    case LimitType::Saddle:
      return render::LimitKind::Saddle;
    default:
      return render::LimitKind::Nonhyperbolic;
  }
}

std::string hexColour(const render::Rgb& c) {
  char s[8];
  auto byte = [](double v) { return int(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); };
  std::snprintf(s, sizeof s, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return s;
}

// <out>/track.png (DemoConfig::trackPlot): the tracks from each start in the
// body's colour, each patch-law body's reference dynamics dashed black.
void writeTrackPlot(const DemoConfig& config, const std::vector<SimulationResult>& results,
                    double dt, double tMax, const fs::path& out) {
  render::GroundTrackPlot plot;
  for (std::size_t i = 0; i < config.bodies.size(); ++i) {
    const DemoBody& b = config.bodies[i];
    render::GroundTrack bullet;
    bullet.label = b.label + " (Bullet)";
    bullet.colour = hexColour(b.colour);
    for (const SimulationSample& s : results[i].trajectory) bullet.points.push_back(s.position);
    plot.tracks.push_back(bullet);
    if (b.spec.model == "stock") continue;
    SimulationSpec spec = b.spec;
    spec.engine = "reference";
    spec.dt = dt;
    spec.tMax = tMax;
    spec.keepTrajectory = true;
    render::GroundTrack reference;
    reference.label = b.label + " (reference, Eq. (93))";
    reference.colour = "#000000";
    reference.dashed = true;
    for (const SimulationSample& s : simulateReference(spec).trajectory)
      reference.points.push_back(s.position);
    plot.tracks.push_back(reference);
  }
  render::PlotOptions po;
  po.title = config.name + ": ground tracks of the patch centre (axes not to the same scale)";
  plotOrWarn(config.name,
             [&] { render::plotGroundTracks(plot, (out / "track.png").string(), po); });
}

}  // namespace

void addCommonOptions(CLI::App& app, CommonArgs& a, bool* noPlot, bool* quiet) {
  // (the defaults shown are the demo's own: CommonArgs as the demo set it)
  app.add_option("--out", a.out, "output directory (frames, summary.json, sphere_*.png)")
      ->capture_default_str();
  app.add_option("--frames", a.frames, "number of frames")->capture_default_str();
  app.add_option("--fps", a.fps, "frames per second of the video")->capture_default_str();
  app.add_option("--size", a.size, "frame size WxH [px]")->capture_default_str();
  app.add_option("--model", a.model,
                 "friction model: exact | ellipsoidal | stock (| all where side by side)")
      ->capture_default_str();
  app.add_option("--rate", a.rate, "simulation steps per second")->capture_default_str();
  app.add_option("--slowmo", a.slowmo, "video seconds per simulated second")->capture_default_str();
  app.add_option("--t-max", a.tMax, "simulated time limit [s]")->capture_default_str();
  app.add_flag("--no-plot", *noPlot, "skip the slip-sphere plots (need gnuplot)");
  app.add_flag("--quiet", *quiet, "no progress bar");
}

void validateCommonArgs(const CommonArgs& a) {
  int w = 0, h = 0;
  parseSize(a.size, w, h);
  if (!(a.fps > 0 && a.rate > 0 && a.slowmo > 0 && a.tMax > 0))
    throw CLI::ValidationError("parameters", "need fps, rate, slowmo, t-max > 0");
  if (a.frames < 1) throw CLI::ValidationError("--frames", "must be >= 1");
  if (a.model != "exact" && a.model != "ellipsoidal" && a.model != "stock" && a.model != "all")
    throw CLI::ValidationError("--model", "must be exact, ellipsoidal, stock or all");
}

int runDemo(const DemoConfig& config, const CommonArgs& a) {
  int width = 0, height = 0;
  parseSize(a.size, width, height);
  const TimeBase time = timeBase(a);
  const double dt = time.dt;
  const int k = time.k;
  const long frameSteps = time.frameSteps;
  const double tMax = std::max(a.tMax, double(frameSteps) * dt);

  // every body through patchspin::scenes::simulate (same world, same summary)
  const std::size_t n = config.bodies.size();
  std::vector<SimulationResult> results(n);
  std::vector<Vec3> offsets(n);
  double maxForce = 0.0, maxR = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    SimulationSpec spec = config.bodies[i].spec;
    spec.dt = dt;
    spec.tMax = tMax;
    spec.keepTrajectory = true;
    spec.precision = patchspin::scenes::buildPrecision();
    results[i] = patchspin::scenes::simulate(spec);
    maxForce = std::max(maxForce, spec.force.norm());
    maxR = std::max(maxR, spec.R);
  }
  const double spacing = kSpacingRadii * maxR;
  for (std::size_t i = 0; i < n; ++i)
    offsets[i] = Vec3(0, spacing * (0.5 * double(n - 1) - double(i)), 0);
  const double arrowScale = config.forceArrowScale > 0
                                ? config.forceArrowScale
                                : (maxForce > 0 ? kArrowRadii * maxR / maxForce : 0.0);

  // camera: fits every body at every rendered instant
  std::vector<render::SceneBody> extent;
  for (std::size_t i = 0; i < n; ++i)
    for (long s = 0; s <= frameSteps; s += k)
      extent.push_back(
          drawBody(config.bodies[i], sampleAt(results[i], std::size_t(s)), offsets[i]));
  const render::Camera camera =
      render::fitCamera(extent, -90.0, 42.0, double(width) / height, 1.25);

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out, a.fps);
  if (a.progress) printProgress(config.name, 0, a.frames);
  for (int f = 0; f < a.frames; ++f) {
    const std::size_t now = std::size_t(f) * std::size_t(k);
    render::Scene scene;
    scene.camera = camera;
    scene.overlay.time = double(now) * dt;
    scene.overlay.title = config.title;
    scene.overlay.model = a.model;
    scene.overlay.caption = config.caption;
    for (std::size_t i = 0; i < n; ++i) {
      const DemoBody& b = config.bodies[i];
      const SimulationResult& r = results[i];
      const SimulationSample& s = sampleAt(r, now);
      scene.bodies.push_back(drawBody(b, s, offsets[i]));
      // trail of the patch centre, at most ~200 points
      render::Trail trail;
      trail.colour = b.colour;
      const std::size_t last = std::min(now, r.trajectory.size() - 1);
      const std::size_t stride = std::max<std::size_t>(1, last / 200);
      for (std::size_t j = last % stride; j <= last; j += stride)
        trail.points.push_back(offsets[i] + Vec3(r.trajectory[j].position.x(),
                                                 r.trajectory[j].position.y(),
                                                 options.groundHeight));
      scene.trails.push_back(trail);
      if (b.spec.force.norm() > 0) {
        render::Arrow arrow;
        arrow.origin = offsets[i] + Vec3(s.position.x(), s.position.y(), b.spec.H);
        arrow.vector = arrowScale * Vec3(b.spec.force.x(), b.spec.force.y(), 0);
        char text[64];
        std::snprintf(text, sizeof text, "F = %.3g N", b.spec.force.norm());
        arrow.label = text;
        scene.arrows.push_back(arrow);
      }
      render::TrackedBody tracked;
      tracked.label = b.label;
      tracked.colour = b.colour;
      tracked.body = int(i);
      const bool atRest = r.stopped && double(now) * dt >= r.tStop;
      if (atRest) {
        tracked.label += " (at rest)";
      } else if (s.r > 0) {
        tracked.w = s.w;
        if (s.omega != 0.0) tracked.slipRatio = s.velocity.norm() / (b.spec.R * std::abs(s.omega));
      }
      scene.overlay.tracked.push_back(tracked);
    }
    writer.write(renderer.render(scene));
    if (a.progress) printProgress(config.name, f + 1, a.frames);
  }

  // summary.json: per body as `patchspin simulate --engine bullet --json`
  nlohmann::json summary;
  summary["video"] = videoSummary(a, time);
  summary["precision"] = patchspin::scenes::buildPrecision();
  summary["dt"] = dt;
  summary["t_max"] = tMax;
  nlohmann::json bodies = nlohmann::json::object();
  for (std::size_t i = 0; i < n; ++i) {
    const DemoBody& b = config.bodies[i];
    const SimulationResult& r = results[i];
    const SimulationSpec& s = b.spec;
    nlohmann::json m;
    m["label"] = b.label;
    m["model"] = s.model;
    m["parameters"] = {{"R", s.R},
                       {"H", s.H},
                       {"mass", s.mass},
                       {"mu", s.mu},
                       {"g", s.g},
                       {"force", {s.force.x(), s.force.y()}},
                       {"torque", {s.torque.x(), s.torque.y(), s.torque.z()}},
                       {"v0", {s.v0.x(), s.v0.y()}},
                       {"omega0", s.omega0}};
    m["stopped"] = r.stopped;
    m["t_stop"] = r.stopped ? nlohmann::json(r.tStop) : nlohmann::json(nullptr);
    m["eps_stop"] = r.epsStop ? jsonOrNull(*r.epsStop) : nlohmann::json(nullptr);
    m["w_stop"] = {r.wStop.x(), r.wStop.y(), r.wStop.z()};
    m["displacement"] = {r.displacement.x(), r.displacement.y()};
    m["rotation"] = r.rotation;
    bodies[b.key] = m;
  }
  summary["bodies"] = bodies;
  const fs::path out(a.out);
  writeJson(out / "summary.json", summary);

  // w(t) on the unit sphere with the limit directions of the body's own model
  if (a.plot) {
    for (std::size_t i = 0; i < n; ++i) {
      const DemoBody& b = config.bodies[i];
      render::SpherePlot plot;
      render::SpherePath path;
      path.label = b.label;
      for (const SimulationSample& s : results[i].trajectory)
        if (s.r > 0) path.w.push_back(s.w);
      plot.paths.push_back(path);
      std::string incomplete;
      if (b.spec.model != "stock") {
        const FlatBodyModel model(flatBodyOf(b.spec), modelFromString(b.spec.model));
        const LimitAnalysis analysis = findLimitDirections(model);
        // Poincare-Hopf: a missed direction is flagged in the title
        if (!analysis.indexConsistent) incomplete = " (limit search incomplete: index sum != 2)";
        for (const LimitDirection& d : analysis.directions) {
          render::LimitDirection l;
          l.w = d.w;
          l.stability = d.attracting ? render::Stability::Attracting : render::Stability::Repelling;
          l.kind = kindOf(d.type);
          plot.limits.push_back(l);
        }
      }
      render::PlotOptions po;
      po.title = config.name + ": " + b.label + ", w(t) and limit directions" + incomplete;
      const std::string file = (out / ("sphere_" + b.key + ".png")).string();
      plotOrWarn(config.name, [&] { render::plotSlipSphere(plot, file, po); });
    }
  }
  if (a.plot && config.trackPlot) writeTrackPlot(config, results, dt, tMax, out);
  std::printf("%s: %d frames, summary.json%s%s in %s\n", config.name.c_str(), writer.count(),
              a.plot ? ", sphere_*.png" : "", a.plot && config.trackPlot ? ", track.png" : "",
              a.out.c_str());
  return 0;
}

namespace {
// Collects every triangle a concave shape reports, moved by `tr`.
class TriangleCollector : public btTriangleCallback {
 public:
  TriangleCollector(const btTransform& tr, render::SceneMesh& mesh) : tr_(tr), mesh_(mesh) {}
  void processTriangle(btVector3* v, int, int) override {
    const int base = int(mesh_.vertices.size());
    for (int i = 0; i < 3; ++i) {
      const btVector3 p = tr_ * v[i];
      mesh_.vertices.emplace_back(double(p.x()), double(p.y()), double(p.z()));
    }
    mesh_.triangles.push_back({base, base + 1, base + 2});
  }

 private:
  btTransform tr_;
  render::SceneMesh& mesh_;
};
}  // namespace

render::SceneMesh concaveMesh(const btRigidBody& ground) {
  render::SceneMesh mesh;
  const auto* shape = dynamic_cast<const btConcaveShape*>(ground.getCollisionShape());
  if (!shape) throw Error("concaveMesh: the body is not a triangle mesh or heightfield");
  TriangleCollector collect(ground.getWorldTransform(), mesh);
  const btScalar big = btScalar(1e6);
  shape->processAllTriangles(&collect, btVector3(-big, -big, -big), btVector3(big, big, big));
  return mesh;
}

// fitSceneCamera, addCorners, rowColour: see demo_common.hpp.
render::Camera fitSceneCamera(const std::vector<Vec3>& points, double azimuthDeg,
                              double elevationDeg, double aspect, double fitTop, double fovYDeg) {
  const double pi = std::acos(-1.0);
  const double az = azimuthDeg * pi / 180.0, el = elevationDeg * pi / 180.0;
  const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                 std::sin(el));  // target -> eye
  const Vec3 fwd = -dir;
  const Vec3 right = fwd.cross(Vec3::UnitZ()).normalized();
  const Vec3 up = right.cross(fwd);
  const double tanY = std::tan(0.5 * fovYDeg * pi / 180.0), tanX = aspect * tanY;
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double size = (hi - lo).norm();
  // projected range of the points for a camera at distance D, target shifted by s
  auto range = [&](double D, double s, double& xMax, double& yMin, double& yMax) {
    const Vec3 target = centre + s * up, eye = target + D * dir;
    xMax = 0.0;
    yMin = 1e300;
    yMax = -1e300;
    for (const Vec3& p : points) {
      const Vec3 q = p - eye;
      const double depth = q.dot(fwd);
      xMax = std::max(xMax, std::abs(q.dot(right) / (depth * tanX)));
      yMin = std::min(yMin, q.dot(up) / (depth * tanY));
      yMax = std::max(yMax, q.dot(up) / (depth * tanY));
    }
  };
  // for a distance, the shift that centres the points in the window
  auto centredShift = [&](double D) {
    double a = -size, b = size;
    for (int i = 0; i < 60; ++i) {
      const double m = 0.5 * (a + b);
      double xMax, yMin, yMax;
      range(D, m, xMax, yMin, yMax);
      // raising the target moves the points down the frame
      if (0.5 * (yMin + yMax) > 0.5 * (fitTop + kFitBottom))
        a = m;
      else
        b = m;
    }
    return 0.5 * (a + b);
  };
  double dLo = 0.5 * size, dHi = 50.0 * size;
  for (int i = 0; i < 60; ++i) {
    const double D = 0.5 * (dLo + dHi);
    double xMax, yMin, yMax;
    range(D, centredShift(D), xMax, yMin, yMax);
    if (xMax <= kFitX && yMax - yMin <= fitTop - kFitBottom)
      dHi = D;
    else
      dLo = D;
  }
  render::Camera cam;
  cam.target = centre + centredShift(dHi) * up;
  cam.eye = cam.target + dHi * dir;
  cam.up = Vec3::UnitZ();
  cam.fovYDeg = fovYDeg;
  return cam;
}

void addCorners(const render::SceneBody& b, std::vector<Vec3>& out) {
  const Vec3 h = b.kind == render::SceneBody::Cylinder
                     ? Vec3(b.dimensions.x(), b.dimensions.y(), 0.5 * b.dimensions.z())
                 : b.kind == render::SceneBody::Box ? Vec3(0.5 * b.dimensions)
                                                    : Vec3::Zero();
  if (b.kind == render::SceneBody::ConvexHull) {
    for (const Vec3& p : b.hullPoints) out.push_back(b.pose * p);
    return;
  }
  for (int i = 0; i < 8; ++i)
    out.push_back(b.pose * Vec3((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(),
                                (i & 4 ? 1 : -1) * h.z()));
}

render::Rgb rowColour(const std::string& model) {
  if (model == "exact") return {0.90, 0.60, 0.15};
  if (model == "ellipsoidal") return {0.25, 0.50, 0.90};
  return {0.60, 0.60, 0.62};
}

void printProgress(const std::string& name, int done, int total) {
  constexpr int kBar = 40;
  static const bool kTerminal = ::isatty(STDERR_FILENO) != 0;
  if (!kTerminal && done != total && (done * 10 / total == (done - 1) * 10 / total || done == 0))
    return;
  const int filled = total > 0 ? done * kBar / total : kBar;
  std::fprintf(stderr, "%s%s: [%s%s] %d/%d frames%s", kTerminal ? "\r" : "", name.c_str(),
               std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(kBar - filled), ' ').c_str(), done, total,
               kTerminal && done != total ? "" : "\n");
  std::fflush(stderr);
}

nlohmann::json jsonOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

void plotOrWarn(const std::string& name, const std::function<void()>& plot) {
  try {
    plot();
  } catch (const render::RenderError& e) {
    std::fprintf(stderr, "%s: warning: no plot: %s\n", name.c_str(), e.what());
  }
}

void writeJson(const fs::path& path, const nlohmann::json& json) {
  std::ofstream file(path);
  file << json.dump(2) << "\n";
  if (!file) throw render::RenderError("cannot write " + path.string());
}

namespace {
// splitList with its own words for an item not allowed and for no item.
std::vector<std::string> splitListSaying(
    const std::string& text, const std::string& option, const std::vector<std::string>& allowed,
    const std::function<std::string(const std::string&)>& notAllowed, const std::string& empty) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (std::find(allowed.begin(), allowed.end(), item) == allowed.end())
      throw CLI::ValidationError(option, notAllowed(item));
    if (std::find(out.begin(), out.end(), item) != out.end())
      throw CLI::ValidationError(option, "lists " + item + " twice");
    out.push_back(item);
  }
  if (out.empty()) throw CLI::ValidationError(option, empty);
  return out;
}
}  // namespace

std::vector<std::string> splitList(const std::string& text, const std::string& option,
                                   const std::vector<std::string>& allowed) {
  std::string names;
  for (const std::string& a : allowed) names += (names.empty() ? "" : ", ") + a;
  return splitListSaying(
      text, option, allowed,
      [&](const std::string& item) { return "'" + item + "' is not one of " + names; },
      "names nothing");
}

std::vector<std::string> lawList(const std::string& text) {
  return splitListSaying(
      text, "--model", {"exact", "ellipsoidal", "stock"},
      [](const std::string& item) {
        return "must be exact, ellipsoidal or stock, or a comma list: got '" + item + "'";
      },
      "names no model");
}

int runMain(CLI::App& app, int argc, char** argv, const char* name,
            const std::function<int()>& run) {
  try {
    app.parse(argc, argv);
    return run();
  } catch (const CLI::Error& e) {  // parse errors and --size validation
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace patchspin::demos
