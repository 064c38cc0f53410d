// scene: renders any scene of the catalogue (scenes/catalogue.hpp) to PNG
// frames, so that a test's or a benchmark's scene can be watched.
//
//   scene --name pyramid --model exact --frames 60 --out demo-out/pyramid
//   scene --list
//
// One world under the chosen law (--model exact | ellipsoidal | stock; every
// body the scene opts in gets it), stepped at the entry's dt for --t-max
// seconds (default: the entry's suggested duration), a frame every k steps
// so that the video runs --slowmo times slower than the simulation at --fps.
// Boxes, cylinders and convex hulls are drawn as they are; spheres as hulls
// of 42 points; static triangle meshes and heightfields as meshes; planes
// and the static walls of the pour and the pile are not drawn (the floor is
// the renderer's ground). Writes <out>/frame_NNNNN.png.
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <patchspin/render/renderer.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <string>
#include <vector>

#include "demo_common.hpp"

namespace {

using patchspin::Vec3;
namespace render = patchspin::render;
namespace scenes = patchspin::scenes;

struct Args {
  std::string name = "coin";
  std::string model = "exact";
  std::string out;  // default demo-out/scene-<name>
  int frames = 90;
  double fps = 30.0;
  double slowmo = 1.0;
  double tMax = -1.0;  // < 0: the entry's duration
  std::string size = "960x540";
  bool list = false;
  bool progress = true;
};

// Unit-sphere points of an icosahedron subdivided once (42 points).
std::vector<Vec3> spherePoints(double r) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if ((v[i] - v[j]).norm() < 2.01) v.push_back(0.5 * (v[i] + v[j]));  // edges have length 2
  for (Vec3& p : v) p = r * p.normalized();
  return v;
}

// The drawable body of a Bullet body, or false for what is not drawn.
bool drawable(const btRigidBody& b, render::SceneBody& out) {
  const btCollisionShape* s = b.getCollisionShape();
  switch (s->getShapeType()) {
    case BOX_SHAPE_PROXYTYPE: {
      if (b.getInvMass() == 0) return false;  // walls and floors
      const btVector3 h = static_cast<const btBoxShape*>(s)->getHalfExtentsWithMargin();
      out.kind = render::SceneBody::Box;
      out.dimensions = Vec3(2 * double(h.x()), 2 * double(h.y()), 2 * double(h.z()));
      break;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto* c = static_cast<const btCylinderShape*>(s);
      if (c->getUpAxis() != 2) return false;
      const btVector3 h = c->getHalfExtentsWithMargin();
      out.kind = render::SceneBody::Cylinder;
      out.dimensions = Vec3(double(h.x()), double(h.x()), 2 * double(h.z()));
      break;
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
      const auto* h = static_cast<const btConvexHullShape*>(s);
      out.kind = render::SceneBody::ConvexHull;
      for (int i = 0; i < h->getNumPoints(); ++i) {
        const btVector3 p = h->getScaledPoint(i);
        out.hullPoints.emplace_back(double(p.x()), double(p.y()), double(p.z()));
      }
      break;
    }
    case SPHERE_SHAPE_PROXYTYPE:
      out.kind = render::SceneBody::ConvexHull;
      out.hullPoints = spherePoints(double(static_cast<const btSphereShape*>(s)->getRadius()));
      out.spinMarker = false;
      break;
    default:
      return false;
  }
  out.pose = scenes::toIsometry(b.getWorldTransform());
  return true;
}

std::vector<render::SceneBody> drawables(const scenes::Scene& scene) {
  std::vector<render::SceneBody> out;
  for (const btRigidBody* b : scene.bodies()) {
    render::SceneBody d;
    d.colour = b->getInvMass() == 0 ? render::Rgb{0.6, 0.6, 0.6} : render::Rgb{0.85, 0.55, 0.2};
    if (drawable(*b, d)) out.push_back(d);
  }
  return out;
}

int run(const Args& a) {
  if (a.list) {
    for (const scenes::CatalogueEntry& e : scenes::catalogue())
      std::cout << e.name << "  " << e.description << "\n";
    return 0;
  }
  const scenes::CatalogueEntry& entry = scenes::findScene(a.name);
  const scenes::Friction law = scenes::frictionFromString(a.model);
  int width = 0, height = 0;
  patchspin::demos::parseSize(a.size, width, height);
  if (a.frames < 1) throw CLI::ValidationError("--frames", "must be >= 1");
  if (!(a.fps > 0) || !(a.slowmo > 0)) throw CLI::ValidationError("--fps/--slowmo", "must be > 0");

  const std::unique_ptr<scenes::Scene> scene = entry.build(law);
  const double dt = entry.dt;
  const double tMax = a.tMax >= 0 ? a.tMax : entry.duration;
  const long steps = long(std::ceil(tMax / dt - 1e-9));
  const long k = std::max(1L, std::lround((1.0 / dt) / (a.fps * a.slowmo)));

  render::RenderOptions options;
  options.width = width;
  options.height = height;
  render::Renderer renderer(options);
  render::FrameWriter writer(a.out.empty() ? "demo-out/scene-" + a.name : a.out, a.fps);
  // camera: fitted to the scene as built
  const render::Camera camera =
      render::fitCamera(drawables(*scene), -60.0, 35.0, double(width) / height, 1.3);
  // static meshes and heightfields: drawn as they are (they never move)
  std::vector<render::SceneMesh> meshes;
  for (const btRigidBody* b : scene->bodies())
    if (b->getInvMass() == 0 && b->getCollisionShape()->isConcave())
      meshes.push_back(patchspin::demos::concaveMesh(*b));
  const std::string title = entry.name + ": " + entry.description;
  if (a.progress) patchspin::demos::printProgress("scene", 0, a.frames);
  long step = 0;
  for (int f = 0; f < a.frames; ++f) {
    render::Scene frame;
    frame.camera = camera;
    frame.bodies = drawables(*scene);
    frame.meshes = meshes;
    frame.overlay.time = double(step) * dt;
    frame.overlay.title = title;
    frame.overlay.model = a.model == "stock" ? "stock Bullet" : a.model + " law";
    writer.write(renderer.render(frame));
    if (a.progress) patchspin::demos::printProgress("scene", f + 1, a.frames);
    for (long j = 0; j < k && step < steps; ++j, ++step) scene->step(dt);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Renders a scene of the catalogue (scenes/catalogue.hpp) to PNG frames."};
  Args a;
  bool quiet = false;
  app.add_option("--name", a.name, "catalogue scene (see --list; default coin)");
  app.add_option("--model", a.model, "exact | ellipsoidal | stock (default exact)");
  app.add_option("--out", a.out, "output directory (default demo-out/scene-<name>)");
  app.add_option("--frames", a.frames, "frames to write (default 90)");
  app.add_option("--fps", a.fps, "frames per video second (default 30)");
  app.add_option("--slowmo", a.slowmo, "video seconds per simulated second (default 1)");
  app.add_option("--t-max", a.tMax, "simulated time limit [s] (default: the scene's)");
  app.add_option("--size", a.size, "frame size WxH (default 960x540)");
  app.add_flag("--list", a.list, "list the catalogue and exit");
  app.add_flag("--quiet", quiet, "no progress bar");
  return patchspin::demos::runMain(app, argc, argv, "scene", [&]() {
    a.progress = !quiet;
    return run(a);
  });
}
