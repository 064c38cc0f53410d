// terrain (issue 32, item 5): coins and blocks sliding and spinning to rest
// on a triangle-mesh (or heightfield) ground, the patch laws beside stock
// Bullet. One Bullet world per law (default: exact, ellipsoidal, stock), each
// holding the catalogue's terrain scene (scenes::makeTerrain), drawn side by
// side along x. The ground is level for x <= 0 and a planar slope beyond:
//   level_coin, level_block   on coplanar level triangles: one patch each
//   slope_coin, slope_block   on coplanar sloped triangles: one patch each,
//                             sliding across the slope and holding on it
//   crease_coin               slides onto the crease: while its face spans
//                             both planes it is left to Bullet's points,
//                             counted in NotPatchedCounts::crease
// Beside each law's terrain world, its level bodies alone on a ground plane
// (the plane reference the mesh must reproduce, issue 32 item 2).
//
// Writes <out>/frame_NNNNN.png, <out>/summary.json and, unless --no-plot,
// <out>/terrain_ratio.png (the level coins' v/(R omega) and slip r, gnuplot).
// Stopping data as patchspin::scenes::simulate, in the plane of the body's
// starting surface (normal n): slip x = (u.e1, u.e2, rho w.n) of the face
// centre, e1 along v0, rho = Eq. (11) of the face; recorded when r first
// falls below 1% of r0, stopped once r <= 1e-5 r0 (extrapolated in the step).
//
// summary.json: laws.<law>.bodies.<key> with region, stopped, t_stop [s],
// eps_stop = |u| / (R |w.n|) (coins) and ratio_stop = |u| / (rho |w.n|) at the
// record, travel (path of the face centre until the stop) [m], displacement
// [m], rotation until the stop and final_yaw (about n, at the end) [rad],
// max_slip_after_stop and final_slip [m/s] (stock Bullet creeps),
// fell_through (ended below its starting surface by more than its height), steps:
// patched / not_patched (with the solver's reasons) / no_contact, and for the
// level bodies plane_reference (the same numbers on a ground plane);
// laws.<law>.not_patched: the world's NotPatchedCounts summed over the steps.
#include <btBulletDynamicsCommon.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/geometry.hpp>
#include <patchspin/render/plot.hpp>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/simulate.hpp>
#include <string>
#include <vector>

#include "demo_common.hpp"

namespace {

using patchspin::Vec3;
namespace render = patchspin::render;
namespace scenes = patchspin::scenes;
namespace demos = patchspin::demos;
namespace fs = std::filesystem;
using patchspin::bullet::NotPatchedCounts;

// As patchspin::scenes::simulate: stopped below kStopFraction r0, ratios
// recorded below kRecordFraction r0.
constexpr double kStopFraction = 1e-5;
constexpr double kRecordFraction = 0.01;
// Stopping ratio of the exact law for a uniformly pressed thin disk
// (DESIGN.md, Farkas et al. 2003), drawn on the plot.
constexpr double kReferenceRatio = 0.653;
// Upper end of the ratio axis of terrain_ratio.png (stock Bullet's wild
// values are clipped) and its r floor relative to r0 (round-off dropped).
constexpr double kRatioAxisMax = 2.0;
constexpr double kPlotFloor = 1e-7;
// Gap between two neighbouring worlds in the frame [m].
constexpr double kWorldGap = 0.06;

struct Args : demos::VideoArgs {
  Args() { out = "demo-out/terrain"; }
  std::string model = "exact,ellipsoidal,stock";
  std::string ground = "mesh";
  double slopeDeg = 8.0;  // [deg]
  double spacing = 0.01;  // grid cell [m]
  double mu = 0.3, g = 9.81;
  double coinV0 = 0.5, coinOmega0 = 20.0, blockV0 = 0.5, blockOmega0 = 15.0;
};

// ---- tracking ------------------------------------------------------------------------

struct Sample {
  double t = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // body -> own world
  Vec3 faceCentre = Vec3::Zero();                          // world [m]
  double speed = 0.0;                                      // |u| in the plane [m/s]
  double spin = 0.0;                                       // w.n [rad/s]
  double r = 0.0;                                          // |(u.e1, u.e2, rho w.n)| [m/s]
};

struct StepCounts {
  long patched = 0, notPatched = 0, noContact = 0;
  NotPatchedCounts reasons;  // summed over the steps
};

nlohmann::json countsJson(const NotPatchedCounts& c) {
  return {{"unsupported_shape", c.unsupportedShape},
          {"side_contact", c.sideContact},
          {"not_flat", c.notFlat},
          {"off_faces", c.offFaces},
          {"tip_cooldown", c.tipCooldown},
          {"no_overlap", c.noOverlap},
          {"law_refused", c.lawRefused},
          {"sliver", c.sliver},
          {"singular_blocks", c.singularBlocks},
          {"crease", c.crease},
          {"bad_mesh", c.badMesh},
          {"total", c.total()}};
}

struct Track {
  const scenes::TerrainBody* def = nullptr;
  btRigidBody* body = nullptr;
  double rho = 0.0;  // Eq. (11) of the face [m]
  Vec3 e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
  std::vector<Sample> samples;
  bool stopped = false, recorded = false;
  double tStop = 0.0, rPrev = 0.0, rPrev2 = 0.0;
  std::optional<double> epsStop, ratioStop;
  double travel = 0.0, rotation = 0.0, maxCreep = 0.0;
  Vec3 displacement = Vec3::Zero();
  StepCounts steps;

  double r0() const { return samples.front().r; }
  bool atRest(const Sample& s) const {
    return (stopped && s.t >= tStop) || s.r <= kStopFraction * r0();
  }
  // v/(R omega) of a coin, NaN at rest or without spin
  double slipRatio(const Sample& s) const {
    if (atRest(s) || s.spin == 0.0) return std::numeric_limits<double>::quiet_NaN();
    return s.speed / (def->size.x() * std::abs(s.spin));
  }
};

Track makeTrack(const scenes::TerrainBody& d, btRigidBody* body) {
  Track t;
  t.def = &d;
  t.body = body;
  t.rho = d.kind == scenes::BodyKind::Cylinder
              ? patchspin::PatchShape::disk(d.size.x()).defaultRho()
              : patchspin::PatchShape::rectangle(d.size.x(), d.size.y()).defaultRho();
  t.e1 = d.v0.norm() > 0 ? Vec3(d.v0.normalized()) : Vec3(d.normal.unitOrthogonal());
  t.e2 = d.normal.cross(t.e1);
  return t;
}

Sample observe(const Track& k, double t) {
  const btTransform& tr = k.body->getWorldTransform();
  const btVector3 c = tr.getOrigin();
  const btVector3 p = tr * btVector3(0, 0, btScalar(-0.5 * k.def->size.z()));
  const btVector3 w = k.body->getAngularVelocity();
  const btVector3 v = k.body->getLinearVelocity() + w.cross(p - c);
  const Vec3 n = k.def->normal, vp(double(v.x()), double(v.y()), double(v.z())),
             wv(double(w.x()), double(w.y()), double(w.z()));
  const Vec3 u = vp - vp.dot(n) * n;
  Sample s;
  s.t = t;
  s.pose = scenes::toIsometry(tr);
  s.faceCentre = Vec3(double(p.x()), double(p.y()), double(p.z()));
  s.speed = u.norm();
  s.spin = wv.dot(n);
  s.r = Vec3(u.dot(k.e1), u.dot(k.e2), k.rho * s.spin).norm();
  return s;
}

// The stopping bookkeeping of simulate() after one step.
void track(Track& k, const Sample& s, double dt) {
  const Sample& prev = k.samples.back();
  if (k.stopped) k.maxCreep = std::max(k.maxCreep, s.r);
  const double r0 = k.r0();
  if (k.stopped || r0 <= 0.0) return;
  k.rotation += s.spin * dt;  // Bullet integrates with the new velocity
  k.travel += (s.faceCentre - prev.faceCentre).norm();
  k.displacement = s.faceCentre - k.samples.front().faceCentre;
  if (!k.recorded && s.r < kRecordFraction * r0) {
    k.recorded = true;
    // the step that sticks: record the last slipping step instead (simulate())
    const Sample& at = (s.r <= kStopFraction * r0 && prev.r > 0) ? prev : s;
    if (at.spin != 0.0) {
      k.ratioStop = at.speed / (k.rho * std::abs(at.spin));
      if (k.def->kind == scenes::BodyKind::Cylinder)
        k.epsStop = at.speed / (k.def->size.x() * std::abs(at.spin));
    }
  }
  if (s.r <= kStopFraction * r0) {
    const double dec = k.rPrev2 - k.rPrev;
    const double frac = dec > 0 ? std::min(1.0, k.rPrev / dec) : 1.0;
    k.stopped = true;
    k.tStop = s.t - dt + frac * dt;
  }
  k.rPrev2 = k.rPrev;
  k.rPrev = s.r;
}

// What the solver did with the body's contacts in the last step.
void countStep(Track& k, const scenes::Scene& scene) {
  const patchspin::bullet::PatchFrictionSolver& solver = scene.solver();
  const NotPatchedCounts* np = solver.notPatchedOf(k.body);
  if (solver.findPatchReport(k.body)) {
    ++k.steps.patched;
  } else if (np) {
    ++k.steps.notPatched;
  } else {
    ++k.steps.noContact;
  }
  if (np) k.steps.reasons += *np;
}

// Steps `scene` `steps` times, sampling every track; the world's
// NotPatchedCounts summed into `world` (if not null).
void stepAndTrack(scenes::Scene& scene, std::vector<Track>& tracks, double dt, long steps,
                  NotPatchedCounts* world) {
  for (Track& k : tracks) {
    k.samples.reserve(std::size_t(steps) + 1);
    k.samples.push_back(observe(k, 0.0));
    k.rPrev = k.rPrev2 = k.r0();
  }
  for (long i = 1; i <= steps; ++i) {
    scene.step(dt);
    if (world) *world += scene.solver().stats().notPatched;
    for (Track& k : tracks) {
      const Sample s = observe(k, double(i) * dt);
      track(k, s, dt);
      k.samples.push_back(s);
      countStep(k, scene);
    }
  }
}

// Rotation about n from the first pose to the last [rad].
double finalYaw(const Track& k) {
  const Eigen::Matrix3d rel =
      k.samples.back().pose.linear() * k.samples.front().pose.linear().transpose();
  const Vec3 n = k.def->normal, a = k.e1, b = rel * a;
  return std::atan2(n.dot(a.cross(b)), a.dot(b - b.dot(n) * n));
}

// ---- worlds -----------------------------------------------------------------------------

struct World {
  std::string law;  // "exact" | "ellipsoidal" | "stock"
  std::string label;
  Vec3 offset = Vec3::Zero();  // where it is drawn
  std::vector<Track> tracks;   // terrain bodies, in terrainBodies order
  std::vector<Track> plane;    // the level bodies alone on a ground plane
  NotPatchedCounts notPatched;
  // the ground's level and sloped triangles (drawn in two colours), in its
  // own world's coordinates, then moved to `offset`
  render::SceneMesh level, slope;
};

// The triangles of `all` whose normal is within half the slope of vertical
// (level) or not (sloped).
render::SceneMesh splitMesh(const render::SceneMesh& all, double slope, bool level) {
  const double cosHalf = std::cos(0.5 * slope);
  render::SceneMesh part;
  part.colour = level ? render::Rgb{0.66, 0.70, 0.60} : render::Rgb{0.76, 0.68, 0.52};
  for (const std::array<int, 3>& t : all.triangles) {
    const Vec3 &a = all.vertices[std::size_t(t[0])], &b = all.vertices[std::size_t(t[1])],
               &c = all.vertices[std::size_t(t[2])];
    const Vec3 n = (b - a).cross(c - a).normalized();
    if ((std::abs(n.z()) >= cosHalf) != level) continue;
    const int base = int(part.vertices.size());
    part.vertices.insert(part.vertices.end(), {a, b, c});
    part.triangles.push_back({base, base + 1, base + 2});
  }
  return part;
}

render::SceneBody drawBody(const Track& k, const Sample& s, const Vec3& offset,
                           const render::Rgb& colour) {
  render::SceneBody b;
  b.kind = k.def->kind == scenes::BodyKind::Cylinder ? render::SceneBody::Cylinder
                                                     : render::SceneBody::Box;
  b.dimensions = k.def->size;
  b.pose = Eigen::Translation3d(offset) * s.pose;
  b.colour = colour;
  return b;
}

render::Rgb bodyColour(const World& w, const Track& k) {
  const render::Rgb base = demos::rowColour(w.law);
  const double f = k.def->kind == scenes::BodyKind::Box ? 0.8 : 1.0;
  return {std::min(1.0, base.r * f), std::min(1.0, base.g * f), std::min(1.0, base.b * f)};
}

nlohmann::json vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json stopJson(const Track& k) {
  nlohmann::json m;
  m["stopped"] = k.stopped;
  m["t_stop"] = k.stopped ? nlohmann::json(k.tStop) : nlohmann::json(nullptr);
  if (k.def->kind == scenes::BodyKind::Cylinder)
    m["eps_stop"] = k.epsStop ? demos::jsonOrNull(*k.epsStop) : nlohmann::json(nullptr);
  m["ratio_stop"] = k.ratioStop ? demos::jsonOrNull(*k.ratioStop) : nlohmann::json(nullptr);
  m["travel"] = k.travel;
  m["displacement"] = vec(k.displacement);
  m["rotation"] = k.rotation;
  m["final_yaw"] = finalYaw(k);
  m["max_slip_after_stop"] = k.maxCreep;
  m["final_slip"] = k.samples.back().r;
  // below the plane of its starting surface by more than its own height at
  // the end: through the ground (Bullet's thin-shape tunnelling on meshes)
  const Vec3 end = k.samples.back().faceCentre - k.samples.front().faceCentre;
  m["fell_through"] = end.dot(k.def->normal) < -k.def->size.z();
  return m;
}

std::string lawLabel(const std::string& law) {
  return law == "stock" ? "stock Bullet" : law + " law";
}

int run(const Args& a) {
  int width = 0, height = 0;
  demos::parseSize(a.size, width, height);
  for (double v : {a.g, a.spacing, a.fps, a.rate, a.slowmo, a.tMax})
    if (!(v > 0 && std::isfinite(v)))
      throw CLI::ValidationError("parameters", "g, spacing, fps, rate, slowmo, t-max must be > 0");
  for (double v : {a.mu, a.slopeDeg, a.coinV0, a.coinOmega0, a.blockV0, a.blockOmega0})
    if (!std::isfinite(v)) throw CLI::ValidationError("parameters", "must be finite");
  if (a.frames < 1) throw CLI::ValidationError("--frames", "must be >= 1");

  scenes::TerrainSpec spec;
  spec.ground.kind = scenes::groundFromString(a.ground);
  if (spec.ground.kind == scenes::Ground::Plane)
    throw CLI::ValidationError("--ground", "must be mesh or heightfield");
  spec.ground.slope = a.slopeDeg * M_PI / 180.0;
  spec.ground.spacing = a.spacing;
  spec.mu = a.mu;
  spec.g = a.g;
  spec.coinV0 = a.coinV0;
  spec.coinOmega0 = a.coinOmega0;
  spec.blockV0 = a.blockV0;
  spec.blockOmega0 = a.blockOmega0;
  const std::vector<scenes::TerrainBody> defs = scenes::terrainBodies(spec);  // throws Error

  std::vector<World> worlds;
  for (const std::string& m : demos::lawList(a.model)) {
    World w;
    w.law = m;
    w.label = lawLabel(m);
    worlds.push_back(w);
  }

  const demos::TimeBase time = demos::timeBase(a);
  const auto [dt, k, frameSteps, steps] = time;
  const double tMax = double(steps) * dt;

  // simulate: the terrain world, then the level bodies alone on a plane
  long triangles = 0;
  for (World& w : worlds) {
    const scenes::Friction f = scenes::frictionFromString(w.law);
    std::vector<btRigidBody*> bodies;
    btRigidBody* ground = nullptr;
    const std::unique_ptr<scenes::Scene> scene = scenes::makeTerrain(spec, f, &bodies, &ground);
    const render::SceneMesh mesh = demos::concaveMesh(*ground);
    w.level = splitMesh(mesh, spec.ground.slope, true);
    w.slope = splitMesh(mesh, spec.ground.slope, false);
    triangles = long(mesh.triangles.size());
    for (std::size_t i = 0; i < defs.size(); ++i) w.tracks.push_back(makeTrack(defs[i], bodies[i]));
    stepAndTrack(*scene, w.tracks, dt, steps, &w.notPatched);

    scenes::Scene plane(a.g);
    plane.addGroundPlane(1.0);
    for (const scenes::TerrainBody& d : defs)
      if (d.region == "level")
        w.plane.push_back(makeTrack(d, scenes::addTerrainBody(plane, d, a.mu, f)));
    stepAndTrack(plane, w.plane, dt, steps, nullptr);
    if (a.progress) std::fprintf(stderr, "terrain: simulated %s\n", w.law.c_str());
  }

  // worlds side by side along x, the first on the left
  const double spacing = 2.0 * spec.ground.halfSize + kWorldGap;
  for (std::size_t i = 0; i < worlds.size(); ++i)
    worlds[i].offset = Vec3(spacing * (double(i) - 0.5 * double(worlds.size() - 1)), 0, 0);
  for (World& w : worlds)
    for (render::SceneMesh* m : {&w.level, &w.slope})
      for (Vec3& p : m->vertices) p += w.offset;

  // camera: fits the grounds and every body at every rendered instant below
  // the panel (two lines and one per world, 1.35 font heights each, font =
  // height / 36)
  std::vector<Vec3> corners;
  for (const World& w : worlds) {
    Vec3 lo = w.level.vertices.front(), hi = lo;
    for (const render::SceneMesh* m : {&w.level, &w.slope})
      for (const Vec3& p : m->vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    corners.push_back(lo);
    corners.push_back(hi);
    corners.emplace_back(lo.x(), hi.y(), lo.z());
    corners.emplace_back(hi.x(), lo.y(), hi.z());
    for (const Track& t : w.tracks)
      for (long s = 0; s <= frameSteps; s += k)
        demos::addCorners(drawBody(t, t.samples[std::size_t(s)], w.offset, {}), corners);
  }
  const int panelLines = 2 + int(worlds.size());
  const double panelFraction = (panelLines * 1.35 + 2.2) / 36.0;
  const double fitTop = std::max(demos::kFitBottom + 0.5, 1.0 - 2.0 * panelFraction);
  const render::Camera camera =
      demos::fitSceneCamera(corners, -90.0, 42.0, double(width) / height, fitTop);

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out, a.fps);
  char title[200];
  std::snprintf(title, sizeof title,
                "terrain: %s of %ld triangles, level | %g\xc2\xb0 slope, mu = %g",
                scenes::toString(spec.ground.kind), triangles, a.slopeDeg, a.mu);
  std::string modelText;
  for (const World& w : worlds) modelText += (modelText.empty() ? "" : " | ") + w.label;
  auto place = [&](std::size_t i) {
    return worlds.size() == 1       ? "alone"
           : i == 0                 ? "left"
           : i + 1 == worlds.size() ? "right"
                                    : "middle";
  };
  if (a.progress) demos::printProgress("terrain", 0, a.frames);
  for (int f = 0; f < a.frames; ++f) {
    const std::size_t now = std::size_t(f) * std::size_t(k);
    render::Scene scene;
    scene.camera = camera;
    scene.overlay.time = double(now) * dt;
    scene.overlay.title = title;
    scene.overlay.model = modelText;
    scene.overlay.caption =
        "one patch per face on coplanar triangles; the coin on the crease is left to Bullet's "
        "points (counted)";
    for (std::size_t i = 0; i < worlds.size(); ++i) {
      const World& w = worlds[i];
      scene.meshes.push_back(w.level);
      scene.meshes.push_back(w.slope);
      int atRest = 0;
      for (const Track& t : w.tracks) {
        const Sample& s = t.samples[now];
        const render::Rgb colour = bodyColour(w, t);
        scene.bodies.push_back(drawBody(t, s, w.offset, colour));
        if (t.atRest(s)) ++atRest;
        render::Trail trail;
        trail.colour = colour;
        const std::size_t stride = std::max<std::size_t>(1, now / 200);
        for (std::size_t j = now % stride; j <= now; j += stride)
          trail.points.push_back(t.samples[j].faceCentre + w.offset);
        scene.trails.push_back(trail);
      }
      render::TrackedBody tracked;
      char label[160];
      std::snprintf(label, sizeof label, "%s (%s): %d/%zu at rest; level coin", w.label.c_str(),
                    place(i), atRest, w.tracks.size());
      tracked.label = label;
      tracked.colour = demos::rowColour(w.law);
      // the level coin's v/(R omega) while it slides and spins
      const Track& coin = w.tracks.front();
      const double ratio = coin.slipRatio(coin.samples[now]);
      if (std::isfinite(ratio)) tracked.slipRatio = ratio;
      scene.overlay.tracked.push_back(tracked);
    }
    writer.write(renderer.render(scene));
    if (a.progress) demos::printProgress("terrain", f + 1, a.frames);
  }

  // summary.json
  nlohmann::json summary;
  summary["parameters"] = {{"mu", a.mu},
                           {"g", a.g},
                           {"rate", a.rate},
                           {"coin_v0", a.coinV0},
                           {"coin_omega0", a.coinOmega0},
                           {"block_v0", a.blockV0},
                           {"block_omega0", a.blockOmega0}};
  summary["ground"] = {{"kind", scenes::toString(spec.ground.kind)},
                       {"triangles", triangles},
                       {"half_size", spec.ground.halfSize},
                       {"spacing", spec.ground.spacing},
                       {"slope_deg", a.slopeDeg},
                       {"crease_x", spec.ground.creaseX}};
  summary["video"] = demos::videoSummary(a, time);
  summary["precision"] = scenes::buildPrecision();
  summary["dt"] = dt;
  summary["steps"] = steps;
  summary["t_max"] = tMax;
  summary["reference_ratio"] = kReferenceRatio;
  nlohmann::json laws = nlohmann::json::object();
  for (const World& w : worlds) {
    nlohmann::json bodies = nlohmann::json::object();
    for (const Track& t : w.tracks) {
      nlohmann::json m = stopJson(t);
      m["region"] = t.def->region;
      m["kind"] = t.def->kind == scenes::BodyKind::Cylinder ? "coin" : "block";
      m["steps"] = {{"patched", t.steps.patched},
                    {"not_patched", t.steps.notPatched},
                    {"no_contact", t.steps.noContact},
                    {"reasons", countsJson(t.steps.reasons)}};
      for (const Track& p : w.plane)
        if (p.def == t.def) m["plane_reference"] = stopJson(p);
      bodies[t.def->key] = m;
    }
    laws[w.law] = {{"label", w.label},
                   {"opted_in", w.law != "stock"},
                   {"not_patched", countsJson(w.notPatched)},
                   {"bodies", bodies}};
  }
  summary["laws"] = laws;
  const fs::path out(a.out);
  demos::writeJson(out / "summary.json", summary);

  // the level coins' v/(R omega) and r against time, up to half as long
  // again as the last stop (at least to the last frame)
  if (a.plot) {
    double tPlot = double(frameSteps) * dt;
    for (const World& w : worlds)
      if (w.tracks.front().stopped) tPlot = std::max(tPlot, 1.5 * w.tracks.front().tStop);
    render::TimeSeriesPlot plot;
    plot.ratioMax = kRatioAxisMax;
    plot.logR = true;
    for (const World& w : worlds) {
      const Track& c = w.tracks.front();
      render::TimeSeries series;
      series.label = w.label + ", level coin on the " + scenes::toString(spec.ground.kind);
      for (const Sample& s : c.samples) {
        if (s.t > tPlot) break;
        series.t.push_back(s.t);
        series.slipRatio.push_back(c.slipRatio(s));
        series.r.push_back(s.r >= kPlotFloor * c.r0() ? s.r : 0.0);
      }
      plot.series.push_back(series);
    }
    render::PlotOptions po;
    po.title = "terrain: level coin, v/(R\xcf\x89) and slip r against time";
    demos::plotOrWarn(
        "terrain", [&] { render::plotSlipRatio(plot, (out / "terrain_ratio.png").string(), po); });
  }
  std::printf("terrain: %d frames (%s ...), summary.json%s in %s\n", writer.count(),
              fs::path(writer.framePath(0)).filename().c_str(), a.plot ? ", terrain_ratio.png" : "",
              a.out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app{
      "terrain: coins and blocks sliding and spinning to rest on a triangle-mesh ground, level and "
      "sloped, with the patch laws and with stock Bullet side by side (headless, PNG frames)"};
  demos::addFrameOptions(app, a, "output directory (frames, summary.json, terrain_ratio.png)");
  app.add_option("--model", a.model,
                 "exact | ellipsoidal | stock, or a comma list drawn side by side (default "
                 "exact,ellipsoidal,stock)");
  app.add_option("--ground", a.ground, "mesh | heightfield (default mesh)");
  app.add_option("--slope", a.slopeDeg,
                 "slope of the rising half [deg], below the friction angle (default 8)");
  app.add_option("--spacing", a.spacing, "grid cell of the ground [m] (default 0.01)");
  app.add_option("--mu", a.mu, "friction coefficient of every body on the ground (default 0.3)");
  app.add_option("--g", a.g, "gravity [m/s^2] (default 9.81)");
  app.add_option("--coin-v0", a.coinV0, "coins' initial speed [m/s] (default 0.5)");
  app.add_option("--coin-omega0", a.coinOmega0, "coins' initial spin [rad/s] (default 20)");
  app.add_option("--block-v0", a.blockV0, "blocks' initial speed [m/s] (default 0.5)");
  app.add_option("--block-omega0", a.blockOmega0, "blocks' initial spin [rad/s] (default 15)");
  demos::addTimeOptions(app, a);
  demos::addOutputFlags(app, a, "terrain_ratio.png");
  return demos::runMain(app, argc, argv, "terrain", [&] { return run(a); });
}
