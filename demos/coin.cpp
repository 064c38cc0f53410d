// coin: the flagship demo of issue 5. A thin coin slides and spins freely on
// the floor; three copies side by side -- the exact law (Eq. (16)), the
// ellipsoidal law (Eq. (41)) and stock Bullet -- each in its own Bullet world
// (identical to `patchspin simulate --engine bullet`), drawn into one frame.
//
// Writes <out>/frame_NNNNN.png, <out>/summary.json, <out>/coin_ratio.png
// (v/(R omega) and r against time, gnuplot) and <out>/coin_series.csv.
//
// Stopping data follow patchspin::scenes::simulate (simulate.hpp): the slip
// r = |(u_x, u_y, rho w_z)| of the patch centre, rho = 2R/3 (Eq. (11));
// eps_stop = |v| / (R |omega|) when r first falls below 1% of r0; stopped
// once r <= 1e-5 r0, the instant extrapolated within the step.
//
// summary.json, per model: stopped, t_stop [s], eps_stop, w_stop,
// displacement [m] and rotation [rad] up to the stop (all as `patchspin
// simulate --json`), max_tilt_rate |(omega_x, omega_y)| over the run [rad/s],
// max_slip_after_stop [m/s] (stock Bullet creeps on), final_displacement [m]
// at the end of the run.
#include "demo_common.hpp"

#include <patchspin/geometry.hpp>
#include <patchspin/render/plot.hpp>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/simulate.hpp>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace {

using patchspin::Vec2;
using patchspin::Vec3;
namespace render = patchspin::render;
namespace fs = std::filesystem;

// Fractions of r0 as in patchspin::scenes::simulate: stopped below
// kStopFraction r0, eps_stop recorded below kRecordFraction r0.
constexpr double kStopFraction = 1e-5;
constexpr double kRecordFraction = 0.01;
// Reference stopping ratio of the exact law for a uniformly pressed thin disk
// (DESIGN.md, Farkas et al. 2003).
constexpr double kReferenceRatio = 0.653;
// Upper end of the ratio axes: the coin starts at v0/(R omega0) = 0.5 and the
// interesting values lie below 1; stock Bullet's wild values are clipped.
constexpr double kRatioAxisMax = 2.0;
// Lower end of the log r axis of coin_ratio.png, relative to r0.
constexpr double kPlotFloor = 1e-7;
// Lateral spacing of the coins in the frame, in radii.
constexpr double kSpacingRadii = 3.0;

struct Args : patchspin::demos::VideoArgs {
  Args() { out = "demo-out/coin"; }
  std::string model = "all";
  double radius = 0.05, height = 0.005, mass = 0.03, mu = 0.3, v0 = 0.5, omega0 = 20.0;
  double g = 9.81;
};

// One sample of one coin per simulation step.
struct Sample {
  double t = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // body -> own world
  Vec3 patchCentre = Vec3::Zero();                         // world [m]
  Vec2 velocity = Vec2::Zero();                            // of the patch centre [m/s]
  double omega = 0.0;                                      // spin [rad/s]
  double tilt = 0.0;                                       // |(omega_x, omega_y)| [rad/s]
  Vec3 x = Vec3::Zero();                                   // (u_x, u_y, rho w_z) [m/s]
  double r = 0.0;
};

struct Coin {
  std::string model;  // "exact" | "ellipsoidal" | "stock"
  std::string label;
  render::Rgb colour;
  Vec3 offset = Vec3::Zero();  // where its world is drawn
  std::vector<Sample> samples;
  // stopping data (simulate.hpp semantics)
  bool stopped = false, recorded = false;
  double tStop = 0.0;
  std::optional<double> epsStop;
  Vec3 wStop = Vec3::Zero();
  Vec2 displacement = Vec2::Zero();  // at the stop (or at the end if never)
  double rotation = 0.0;             // until the stop [rad]
  double maxTilt = 0.0;              // over the whole run [rad/s]
  double maxCreep = 0.0;             // largest slip r after the stop [m/s]

  double r0() const { return samples.front().r; }
  // at rest: from the stopping instant on, or whenever r is at the stop threshold
  bool atRest(const Sample& s) const {
    return (stopped && s.t >= tStop) || s.r <= kStopFraction * r0();
  }
  // spin at round-off (stock Bullet stops spinning first and slides on)
  bool spinless(const Sample& s, double R) const {
    return R * std::abs(s.omega) <= kStopFraction * r0();
  }
  // v/(R omega), NaN at rest (0/0 up to round-off) or without spin (infinite)
  double slipRatio(const Sample& s, double R) const {
    if (atRest(s) || spinless(s, R)) return std::numeric_limits<double>::quiet_NaN();
    return s.velocity.norm() / (R * std::abs(s.omega));
  }
};

// Runs one coin for `steps` steps of dt in its own world (the catalogue's
// coin, scenes::makeCoin).
void simulateCoin(Coin& coin, const Args& a, double dt, long steps) {
  patchspin::scenes::CoinSpec spec;
  spec.radius = a.radius;
  spec.height = a.height;
  spec.mass = a.mass;
  spec.mu = a.mu;
  spec.v0 = a.v0;
  spec.omega0 = a.omega0;
  spec.g = a.g;
  btRigidBody* body = nullptr;
  const std::unique_ptr<patchspin::scenes::Scene> scene =
      patchspin::scenes::makeCoin(spec, patchspin::scenes::frictionFromString(coin.model), &body);
  const double halfHeight = 0.5 * a.height;

  // slip state in the frame of v0 (x along v0), as simulate does
  const double rho = patchspin::PatchShape::disk(a.radius).defaultRho();
  const Vec2 e1 = a.v0 != 0.0 ? Vec2(a.v0 > 0 ? 1.0 : -1.0, 0.0) : Vec2(1.0, 0.0);
  const Vec2 e2(-e1.y(), e1.x());
  auto observe = [&](double t) {
    const btTransform& tr = body->getWorldTransform();
    const btVector3 c = tr.getOrigin();
    const btVector3 p = tr * btVector3(0, 0, btScalar(-halfHeight));
    const btVector3 w = body->getAngularVelocity();
    const btVector3 v = body->getLinearVelocity() + w.cross(p - c);
    Sample s;
    s.t = t;
    s.pose = patchspin::scenes::toIsometry(tr);
    s.patchCentre = Vec3(double(p.x()), double(p.y()), double(p.z()));
    s.velocity = Vec2(double(v.x()), double(v.y()));
    s.omega = double(w.z());
    s.tilt = std::hypot(double(w.x()), double(w.y()));
    s.x = Vec3(s.velocity.dot(e1), s.velocity.dot(e2), rho * s.omega);
    s.r = s.x.norm();
    return s;
  };

  coin.samples.clear();
  coin.samples.reserve(std::size_t(steps) + 1);
  coin.samples.push_back(observe(0.0));
  const double r0 = coin.r0();
  double rPrev = r0, rPrev2 = r0;
  for (long k = 1; k <= steps; ++k) {
    scene->step(dt);
    const Sample s = observe(double(k) * dt);
    coin.samples.push_back(s);
    coin.maxTilt = std::max(coin.maxTilt, s.tilt);
    if (coin.stopped) coin.maxCreep = std::max(coin.maxCreep, s.r);
    if (coin.stopped || r0 <= 0.0) continue;
    coin.rotation += s.omega * dt;  // Bullet integrates with the new velocity
    coin.displacement = (s.patchCentre - coin.samples.front().patchCentre).head<2>();
    if (!coin.recorded && s.r < kRecordFraction * r0) {
      coin.recorded = true;
      coin.wStop = s.r > 0 ? Vec3(s.x / s.r) : Vec3::Zero();
      if (s.omega != 0.0) coin.epsStop = s.velocity.norm() / (a.radius * std::abs(s.omega));
    }
    if (s.r <= kStopFraction * r0) {
      // stop part way through the step at the previous decrement rate
      const double dec = rPrev2 - rPrev;
      const double frac = dec > 0 ? std::min(1.0, rPrev / dec) : 1.0;
      coin.stopped = true;
      coin.tStop = s.t - dt + frac * dt;
    }
    rPrev2 = rPrev;
    rPrev = s.r;
  }
}

render::SceneBody coinBody(const Coin& coin, const Sample& s, const Args& a) {
  render::SceneBody b;
  b.kind = render::SceneBody::Cylinder;
  b.dimensions = Vec3(a.radius, a.radius, a.height);
  b.pose = Eigen::Translation3d(coin.offset) * s.pose;
  b.colour = coin.colour;
  return b;
}

int run(const Args& a) {
  int width = 0, height = 0;
  patchspin::demos::parseSize(a.size, width, height);
  if (!(a.radius > 0 && a.height > 0 && a.mass > 0 && a.g > 0 && a.mu >= 0 && a.fps > 0 &&
        a.rate > 0 && a.slowmo > 0 && a.tMax > 0 && std::isfinite(a.v0) && std::isfinite(a.omega0)))
    throw CLI::ValidationError(
        "parameters", "need radius, height, mass, g, fps, rate, slowmo, t-max > 0, mu >= 0");
  if (a.frames < 1) throw CLI::ValidationError("--frames", "must be >= 1");

  // coins: exact, ellipsoidal, stock, side by side along y
  std::vector<Coin> coins;
  auto addCoin = [&](const std::string& model, const std::string& label, render::Rgb colour) {
    if (a.model != "all" && a.model != model) return;
    Coin c;
    c.model = model;
    c.label = label;
    c.colour = colour;
    coins.push_back(c);
  };
  addCoin("exact", "exact", {0.90, 0.60, 0.15});
  addCoin("ellipsoidal", "ellipsoidal", {0.25, 0.50, 0.90});
  addCoin("stock", "stock Bullet", {0.60, 0.60, 0.62});
  if (coins.empty())
    throw CLI::ValidationError("--model", "must be ellipsoidal, exact, stock or all");
  const double spacing = kSpacingRadii * a.radius;
  for (std::size_t i = 0; i < coins.size(); ++i)
    coins[i].offset = Vec3(0, spacing * (0.5 * double(coins.size() - 1) - double(i)), 0);

  // time: rate steps per simulated second, a frame every k steps so that the
  // video runs `slowmo` times slower than the simulation at `fps`
  const patchspin::demos::TimeBase time = patchspin::demos::timeBase(a);
  const auto [dt, k, frameSteps, steps] = time;
  for (Coin& c : coins) simulateCoin(c, a, dt, steps);

  // camera: fits every coin at every rendered instant
  std::vector<render::SceneBody> extent;
  for (const Coin& c : coins)
    for (long s = 0; s <= frameSteps; s += k)
      extent.push_back(coinBody(c, c.samples[std::size_t(s)], a));
  const render::Camera camera =
      render::fitCamera(extent, -90.0, 42.0, double(width) / height, 1.25);

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out, a.fps);
  const double tEnd = double(frameSteps) * dt;

  char title[160];
  std::snprintf(title, sizeof title,
                "coin R = %g cm, H = %g mm, mu = %g, v0 = %g m/s, omega0 = %g rad/s",
                100 * a.radius, 1000 * a.height, a.mu, a.v0, a.omega0);
  if (a.progress) patchspin::demos::printProgress("coin", 0, a.frames);
  for (int f = 0; f < a.frames; ++f) {
    const std::size_t now = std::size_t(f) * std::size_t(k);
    render::Scene scene;
    scene.camera = camera;
    scene.overlay.time = coins.front().samples[now].t;
    scene.overlay.title = title;
    scene.overlay.model =
        a.model == "all" ? "exact | ellipsoidal | stock Bullet" : coins.front().label;
    scene.overlay.caption =
        "exact stops near v/(R\xcf\x89) = 0.653; ellipsoidal ends in pure spin; "
        "stock Bullet rocks and drifts";
    render::OverlayChart chart;
    chart.title = "v/(R\xcf\x89)";
    chart.tMin = 0.0;
    chart.tMax = std::max(tEnd, dt);
    chart.yMin = 0.0;
    chart.yMax = kRatioAxisMax;
    chart.reference = kReferenceRatio;
    chart.referenceLabel = "0.653";
    for (std::size_t i = 0; i < coins.size(); ++i) {
      const Coin& c = coins[i];
      const Sample& s = c.samples[now];
      scene.bodies.push_back(coinBody(c, s, a));
      // trail of the patch centre, at most ~200 points
      render::Trail trail;
      trail.colour = c.colour;
      const std::size_t stride = std::max<std::size_t>(1, now / 200);
      for (std::size_t j = now % stride; j <= now; j += stride)
        trail.points.push_back(Vec3(c.samples[j].patchCentre.x() + c.offset.x(),
                                    c.samples[j].patchCentre.y() + c.offset.y(),
                                    options.groundHeight));
      scene.trails.push_back(trail);
      render::TrackedBody tracked;
      tracked.label = c.label;
      tracked.colour = c.colour;
      tracked.body = int(i);
      const double ratio = c.slipRatio(s, a.radius);
      if (std::isfinite(ratio)) {
        tracked.slipRatio = ratio;
        tracked.w = Vec3(s.x / s.r);
      } else if (c.atRest(s)) {
        // stock Bullet keeps creeping after its first stop (r ~ 1e-4 m/s)
        tracked.label += s.r <= kStopFraction * c.r0() ? " (at rest)" : " (stopped, creeping)";
      } else if (c.spinless(s, a.radius)) {
        tracked.label += " (sliding, no spin)";
        tracked.w = Vec3(s.x / s.r);
      }
      scene.overlay.tracked.push_back(tracked);
      render::ChartSeries series;
      series.colour = c.colour;
      for (std::size_t j = 0; j <= now; ++j) {
        series.t.push_back(c.samples[j].t);
        series.y.push_back(c.slipRatio(c.samples[j], a.radius));
      }
      chart.series.push_back(series);
    }
    scene.overlay.chart = chart;
    writer.write(renderer.render(scene));
    if (a.progress) patchspin::demos::printProgress("coin", f + 1, a.frames);
  }

  // summary.json
  nlohmann::json summary;
  summary["parameters"] = {
      {"radius", a.radius}, {"height", a.height},         {"mass", a.mass}, {"mu", a.mu},
      {"v0", a.v0},         {"omega0", a.omega0},         {"g", a.g},       {"dt", dt},
      {"steps", steps},     {"t_end", double(steps) * dt}};
  summary["video"] = patchspin::demos::videoSummary(a, time);
  summary["precision"] = patchspin::scenes::buildPrecision();
  summary["reference_ratio"] = kReferenceRatio;
  nlohmann::json models = nlohmann::json::object();
  for (const Coin& c : coins) {
    nlohmann::json m;
    m["stopped"] = c.stopped;
    m["t_stop"] = c.stopped ? nlohmann::json(c.tStop) : nlohmann::json(nullptr);
    m["eps_stop"] = c.epsStop ? patchspin::demos::jsonOrNull(*c.epsStop) : nlohmann::json(nullptr);
    m["w_stop"] = c.recorded ? nlohmann::json{c.wStop.x(), c.wStop.y(), c.wStop.z()}
                             : nlohmann::json(nullptr);
    m["max_tilt_rate"] = c.maxTilt;
    m["max_slip_after_stop"] = c.maxCreep;
    m["displacement"] = {c.displacement.x(), c.displacement.y()};
    m["rotation"] = c.rotation;
    const Vec3 end = c.samples.back().patchCentre - c.samples.front().patchCentre;
    m["final_displacement"] = {end.x(), end.y()};
    models[c.model] = m;
  }
  summary["models"] = models;
  const fs::path out(a.out);
  patchspin::demos::writeJson(out / "summary.json", summary);

  // v/(R omega) and r against time: the whole run in the CSV; the plot up to
  // the last frame or half as long again as the last stop, whichever is later
  double tPlot = tEnd;
  for (const Coin& c : coins)
    if (c.stopped) tPlot = std::max(tPlot, 1.5 * c.tStop);
  render::TimeSeriesPlot plot;
  plot.ratioMax = kRatioAxisMax;
  plot.logR = true;
  std::ofstream csv(out / "coin_series.csv");
  csv << "label,t,slipRatio,r\n";
  for (const Coin& c : coins) {
    render::TimeSeries series;
    series.label = c.label;
    for (const Sample& s : c.samples) {
      if (s.t <= tPlot) {
        series.t.push_back(s.t);
        series.slipRatio.push_back(c.slipRatio(s, a.radius));
        // log axis: the sticking round-off (down to 1e-40 m/s) is dropped
        // below kPlotFloor r0, which keeps stock Bullet's creep visible
        series.r.push_back(s.r >= kPlotFloor * c.r0() ? s.r : 0.0);
      }
      char line[160];
      std::snprintf(line, sizeof line, "%s,%.9g,%.9g,%.9g\n", c.label.c_str(), s.t,
                    c.slipRatio(s, a.radius), s.r);
      csv << line;
    }
    plot.series.push_back(series);
  }
  csv.close();
  if (a.plot) {
    render::PlotOptions po;
    po.title = "coin: v/(R\xcf\x89) and slip r against time";
    patchspin::demos::plotOrWarn(
        "coin", [&] { render::plotSlipRatio(plot, (out / "coin_ratio.png").string(), po); });
  }
  std::printf("coin: %d frames (%s ...), summary.json%s in %s\n", writer.count(),
              fs::path(writer.framePath(0)).filename().c_str(), a.plot ? ", coin_ratio.png" : "",
              a.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{
      "coin: a thin coin sliding and spinning to rest with the exact, the ellipsoidal and stock "
      "Bullet friction, side by side (headless, PNG frames)"};
  patchspin::demos::addFrameOptions(app, a,
                                    "output directory (frames, summary.json, coin_ratio.png)");
  app.add_option("--model", a.model,
                 "ellipsoidal | exact | stock | all (default all, side by side)");
  app.add_option("--radius", a.radius, "coin radius R [m] (default 0.05)");
  app.add_option("--height", a.height, "coin thickness H [m] (default 0.005)");
  app.add_option("--mass", a.mass, "coin mass [kg] (default 0.03)");
  app.add_option("--mu", a.mu, "friction coefficient (default 0.3)");
  app.add_option("--v0", a.v0, "initial speed along x [m/s] (default 0.5)");
  app.add_option("--omega0", a.omega0, "initial spin [rad/s] (default 20)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  patchspin::demos::addTimeOptions(app, a, "; 480 also sensible");
  patchspin::demos::addOutputFlags(app, a, "coin_ratio.png");
  return patchspin::demos::runMain(app, argc, argv, "coin", [&] { return run(a); });
}
