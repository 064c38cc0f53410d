// Off-screen renderer: output size, content, determinism, and geometry placed
// where an independent pinhole projection says it should be.
#include <gtest/gtest.h>
#include <unistd.h>

#include <patchspin/render/renderer.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "demo_test_util.hpp"

namespace patchspin::render {
namespace {

using demo_test::countDifferentPixels;
using demo_test::fileBytes;

constexpr int kWidth = 160;
constexpr int kHeight = 120;

std::string tempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("patchspin_render_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

SceneBody disk(const Vec3& centre, double angle) {
  SceneBody b;
  b.kind = SceneBody::Cylinder;
  b.dimensions = Vec3(0.05, 0.05, 0.01);
  b.pose.translation() = centre;
  b.pose.linear() = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
  return b;
}

// a coin on the ground seen from above at an angle, with the overlay
Scene coinScene(double angle = 0.3, const Vec3& centre = Vec3(0.0, 0.0, 0.005)) {
  Scene s;
  s.bodies.push_back(disk(centre, angle));
  s.camera.eye = Vec3(0.12, -0.16, 0.2);
  s.camera.target = Vec3::Zero();
  s.camera.fovYDeg = 40.0;
  s.overlay.time = 0.5;
  s.overlay.model = "exact";
  return s;
}

RenderOptions smallOptions() {
  RenderOptions o;
  o.width = kWidth;
  o.height = kHeight;
  return o;
}

// Image box of a disk body (rim points) under an independent pinhole model:
// camera basis (s, u, -f), focal length from the vertical field of view.
struct PixelBox {
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
};
PixelBox projectDisk(const Camera& cam, const SceneBody& body) {
  const Vec3 f = (cam.target - cam.eye).normalized();
  const Vec3 s = f.cross(cam.up).normalized();
  const Vec3 u = s.cross(f);
  const double focal = 0.5 * kHeight / std::tan(0.5 * cam.fovYDeg * M_PI / 180.0);
  const double R = body.dimensions.x(), H = body.dimensions.z();
  PixelBox box;
  for (int i = 0; i < 64; ++i) {
    const double t = 2.0 * M_PI * i / 64;
    for (double z : {-0.5 * H, 0.5 * H}) {
      const Vec3 p = body.pose * Vec3(R * std::cos(t), R * std::sin(t), z) - cam.eye;
      const double depth = p.dot(f);
      const double x = 0.5 * kWidth + focal * p.dot(s) / depth;
      const double y = 0.5 * kHeight - focal * p.dot(u) / depth;
      box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x);
      box.y0 = std::min(box.y0, y), box.y1 = std::max(box.y1, y);
    }
  }
  return box;
}

TEST(Renderer, SmallSceneGivesPngOfRequestedSizeNotBlank) {
  Renderer renderer(smallOptions());
  const std::string dir = tempDir("size");
  FrameWriter writer(dir, 25.0);
  const std::string path = writer.write(renderer.render(coinScene()));
  EXPECT_EQ(path, (std::filesystem::path(dir) / "frame_00000.png").string());
  EXPECT_EQ(writer.write(renderer.render(coinScene(0.4))),
            (std::filesystem::path(dir) / "frame_00001.png").string());
  EXPECT_EQ(writer.count(), 2);
  EXPECT_DOUBLE_EQ(writer.frameTime(50), 2.0);
  const Image back = readPng(path);
  EXPECT_EQ(back.width, kWidth);
  EXPECT_EQ(back.height, kHeight);
  // a blank (uniform) frame has variance 0; sky, ground, coin and text give
  // far more than a standard deviation of 10 grey levels
  constexpr double kMinVariance = 100.0;
  EXPECT_GT(pixelVariance(back), kMinVariance);
}

TEST(Renderer, PngRoundTripKeepsPixels) {
  Renderer renderer(smallOptions());
  const Image image = renderer.render(coinScene());
  const std::string path = tempDir("roundtrip") + "/a.png";
  writePng(image, path);
  const Image back = readPng(path);
  EXPECT_EQ(back.width, image.width);
  EXPECT_EQ(back.height, image.height);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST(Renderer, SameSceneTwiceGivesIdenticalBytes) {
  const std::string dir = tempDir("determinism");
  Scene scene = coinScene();
  Trail trail;
  for (int i = 0; i < 20; ++i) trail.points.push_back(Vec3(-0.1 + 0.005 * i, 0.002 * i, 0.0));
  scene.trails.push_back(trail);
  Arrow arrow;
  arrow.origin = Vec3(0.0, 0.0, 0.01);
  arrow.vector = Vec3(0.06, 0.0, 0.0);
  arrow.label = "F";
  scene.arrows.push_back(arrow);
  scene.overlay.tracked.push_back(
      {"exact", {0.9, 0.5, 0.2}, 0.653, Vec3(0.6, 0.0, 0.8), Vec3(0, 0, 0.02)});

  Renderer first(smallOptions());
  writePng(first.render(scene), dir + "/a.png");
  writePng(first.render(scene), dir + "/b.png");
  // a second renderer (a second OSMesa context) gives the same bytes too
  Renderer second(smallOptions());
  writePng(second.render(scene), dir + "/c.png");
  const std::string a = fileBytes(dir + "/a.png");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, fileBytes(dir + "/b.png"));
  EXPECT_EQ(a, fileBytes(dir + "/c.png"));
}

TEST(Renderer, FrameChangesWhenBodyMovesOrSpins) {
  Renderer renderer(smallOptions());
  const Image base = renderer.render(coinScene(0.3));
  const Image moved = renderer.render(coinScene(0.3, Vec3(0.01, 0.0, 0.005)));
  // a pure spin about the disk axis changes only the spin markers
  const Image spun = renderer.render(coinScene(0.3 + 0.5 * M_PI));
  // differences well above filtering noise (there is none: same input, same
  // bytes) in at least a handful of pixels
  constexpr int kLevel = 20;
  constexpr int kMinPixels = 20;
  EXPECT_GT(countDifferentPixels(base, moved, kLevel), kMinPixels);
  EXPECT_GT(countDifferentPixels(base, spun, kLevel), kMinPixels);
}

// The coin is drawn where an independent pinhole model puts it: adding it
// changes pixels only inside the projected box of its corners, and fills a
// good part of that box.
TEST(Renderer, BodyAppearsWhereThePinholeProjectionPutsIt) {
  RenderOptions o = smallOptions();
  o.shadows = false;  // shadows fall outside the body's own projection
  Renderer renderer(o);
  // off the image centre, so a mirrored or shifted projection would show
  Scene with = coinScene(0.3, Vec3(0.05, 0.03, 0.005));
  with.camera.eye = Vec3(0.1, -0.15, 0.25);
  with.overlay = FrameOverlay();  // time panel only, identical in both images
  with.overlay.time = 0.0;
  Scene without = with;
  without.bodies.clear();
  const Image a = renderer.render(with), b = renderer.render(without);

  const PixelBox box = projectDisk(with.camera, with.bodies[0]);
  const double x0 = box.x0, x1 = box.x1, y0 = box.y0, y1 = box.y1;
  // the box filter of supersampling spreads an edge by at most one pixel
  constexpr double kEdgePx = 1.5;
  int inside = 0, outside = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
      const double cx = x + 0.5, cy = y + 0.5;
      if (cx >= x0 - kEdgePx && cx <= x1 + kEdgePx && cy >= y0 - kEdgePx && cy <= y1 + kEdgePx) {
        ++inside;
      } else {
        ++outside;
      }
    }
  }
  EXPECT_EQ(outside, 0);
  // an ellipse fills pi/4 ~ 0.785 of its bounding box; perspective and the
  // polygonal rim cost a little, grid lines hidden under it nothing
  constexpr double kMinFill = 0.6;
  EXPECT_GT(inside, kMinFill * (x1 - x0) * (y1 - y0));
}

// A mesh (a square of two triangles lying on the ground, off the image
// centre) is drawn where an independent pinhole model puts its corners:
// adding it changes pixels only inside their projected box, and fills most
// of it.
TEST(Renderer, MeshAppearsWhereThePinholeProjectionPutsIt) {
  RenderOptions o = smallOptions();
  o.shadows = false;
  Renderer renderer(o);
  Scene without;
  without.camera.eye = Vec3(0.1, -0.15, 0.25);
  without.camera.target = Vec3::Zero();
  without.camera.fovYDeg = 40.0;
  Scene with = without;
  SceneMesh square;
  square.vertices = {Vec3(0.02, -0.01, 0.0), Vec3(0.09, -0.01, 0.0), Vec3(0.09, 0.06, 0.0),
                     Vec3(0.02, 0.06, 0.0)};
  // one triangle wound each way: both sides are drawn
  square.triangles = {{0, 1, 2}, {0, 3, 2}};
  square.colour = Rgb{0.2, 0.6, 0.3};
  with.meshes.push_back(square);
  const Image a = renderer.render(with), b = renderer.render(without);

  const Camera& cam = with.camera;
  const Vec3 f = (cam.target - cam.eye).normalized();
  const Vec3 s = f.cross(cam.up).normalized();
  const Vec3 u = s.cross(f);
  const double focal = 0.5 * kHeight / std::tan(0.5 * cam.fovYDeg * M_PI / 180.0);
  PixelBox box;
  std::vector<Eigen::Vector2d> image;  // the corners' pixels, in order round the square
  for (const Vec3& corner : square.vertices) {
    const Vec3 p = corner - cam.eye;
    const double depth = p.dot(f);
    const double x = 0.5 * kWidth + focal * p.dot(s) / depth;
    const double y = 0.5 * kHeight - focal * p.dot(u) / depth;
    image.emplace_back(x, y);
    box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x);
    box.y0 = std::min(box.y0, y), box.y1 = std::max(box.y1, y);
  }
  // area (shoelace) and perimeter of the projected quadrilateral [px]
  double area = 0.0, perimeter = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const Eigen::Vector2d &p = image[i], &q = image[(i + 1) % image.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
    perimeter += (q - p).norm();
  }
  area = std::abs(area);
  ASSERT_GT(box.x0, 0.0);
  ASSERT_LT(box.x1, kWidth);
  // the box filter of supersampling spreads an edge by at most one pixel
  constexpr double kEdgePx = 1.5;
  int inside = 0, outside = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
      const double cx = x + 0.5, cy = y + 0.5;
      if (cx >= box.x0 - kEdgePx && cx <= box.x1 + kEdgePx && cy >= box.y0 - kEdgePx &&
          cy <= box.y1 + kEdgePx) {
        ++inside;
      } else {
        ++outside;
      }
    }
  }
  EXPECT_EQ(outside, 0);
  // the changed pixels cover the projected quadrilateral: its area, give or
  // take the pixels its edges cross (partly covered: changed or not)
  EXPECT_NEAR(inside, area, kEdgePx * perimeter);
  // green: the mesh's own colour at the square's centre, not the grey ground
  const Vec3 c = Vec3(0.055, 0.025, 0.0) - cam.eye;
  const int px = int(0.5 * kWidth + focal * c.dot(s) / c.dot(f));
  const int py = int(0.5 * kHeight - focal * c.dot(u) / c.dot(f));
  const std::uint8_t* centre = a.pixel(px, py);
  EXPECT_GT(int(centre[1]), int(centre[0]) + 20);
}

// A mesh triangle indexing outside the vertices is an error, not a crash.
TEST(Renderer, MeshIndexOutsideTheVerticesThrows) {
  Renderer renderer(smallOptions());
  Scene scene = coinScene();
  SceneMesh bad;
  bad.vertices = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  bad.triangles = {{0, 1, 3}};
  scene.meshes.push_back(bad);
  EXPECT_THROW(renderer.render(scene), RenderError);
}

// A convex hull of a box's corners (plus interior points that must be
// ignored) draws like the box itself.
TEST(Renderer, ConvexHullOfBoxCornersDrawsLikeTheBox) {
  Renderer renderer(smallOptions());
  Scene boxScene;
  SceneBody box;
  box.kind = SceneBody::Box;
  box.dimensions = Vec3(0.08, 0.05, 0.04);
  box.spinMarker = false;
  box.pose.translation() = Vec3(0, 0, 0.02);
  box.pose.linear() = Eigen::AngleAxisd(0.4, Vec3::UnitZ()).toRotationMatrix();
  boxScene.bodies.push_back(box);
  boxScene.camera = fitCamera(boxScene.bodies, -60.0, 35.0, double(kWidth) / kHeight);
  Scene hullScene = boxScene;
  SceneBody& hull = hullScene.bodies[0];
  hull.kind = SceneBody::ConvexHull;
  for (int i = 0; i < 8; ++i) {
    hull.hullPoints.push_back(
        0.5 * Vec3((i & 1 ? 1 : -1) * 0.08, (i & 2 ? 1 : -1) * 0.05, (i & 4 ? 1 : -1) * 0.04));
  }
  hull.hullPoints.push_back(Vec3(0.01, -0.005, 0.003));                 // interior
  hull.hullPoints.push_back(Vec3(0.04, 0.0, 0.0));                      // on a face
  hull.hullPoints.insert(hull.hullPoints.begin(), hull.hullPoints[0]);  // a duplicate first
  Scene empty = boxScene;
  empty.bodies.clear();
  const Image a = renderer.render(boxScene), b = renderer.render(hullScene),
              e = renderer.render(empty);
  // the same faces may be split into different triangles, which moves a few
  // edge pixels by a few levels; nothing else may differ
  constexpr int kLevel = 12;
  const int bodyPixels = countDifferentPixels(a, e, kLevel);
  ASSERT_GT(bodyPixels, 300);  // the box covers a good part of the frame
  EXPECT_LE(countDifferentPixels(a, b, kLevel), bodyPixels / 50);
}

TEST(Renderer, OverlayTextIsDrawn) {
  Renderer renderer(smallOptions());
  Scene plain = coinScene();
  Scene text = plain;
  text.overlay.title = "coin";
  text.overlay.tracked.push_back(
      {"exact", {0.9, 0.5, 0.2}, 0.653, Vec3(0.6, 0.0, 0.8), std::nullopt});
  // two more panel lines of text: well over a hundred changed pixels
  constexpr int kMinPixels = 100;
  EXPECT_GT(countDifferentPixels(renderer.render(plain), renderer.render(text), 40), kMinPixels);
}

// A tracked body's label without an anchor sits just above the body's image.
TEST(Renderer, BodyLabelIsDrawnAboveTheBody) {
  Renderer renderer(smallOptions());
  Scene plain = coinScene(0.3, Vec3(0.03, 0.02, 0.005));
  plain.overlay = FrameOverlay();
  Scene labelled = plain;
  TrackedBody tracked;
  tracked.label = "exact";
  tracked.body = 0;
  labelled.overlay.tracked.push_back(tracked);
  const Image a = renderer.render(plain), b = renderer.render(labelled);
  const PixelBox box = projectDisk(plain.camera, plain.bodies[0]);
  // the info panel gains a line too (top left, below its first line); look
  // only right of the panel's swatch column and below its two lines
  int above = 0, elsewhere = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
      const bool inPanel = x < 80 && y < 40;
      if (inPanel) continue;
      // label box: centred on the body, bottom edge above the body's top
      // (one pixel of filter spread)
      const bool overBody =
          y + 0.5 < box.y0 + 1.0 && std::abs(x + 0.5 - 0.5 * (box.x0 + box.x1)) < 40;
      (overBody ? above : elsewhere) += 1;
    }
  }
  constexpr int kMinLabelPixels = 50;  // five letters and their box
  EXPECT_GT(above, kMinLabelPixels);
  EXPECT_EQ(elsewhere, 0);
}

// Trails fade: the newest end is drawn stronger than the oldest.
TEST(Renderer, TrailFadesFromOldToNew) {
  RenderOptions o = smallOptions();
  Renderer renderer(o);
  Scene plain;
  plain.camera.eye = Vec3(0.0, -0.001, 0.4);  // looking straight down
  plain.camera.target = Vec3::Zero();
  Scene trailed = plain;
  Trail trail;
  trail.colour = {0.0, 0.0, 0.0};
  trail.widthPx = 3.0;
  for (int i = 0; i <= 100; ++i) trail.points.push_back(Vec3(-0.15 + 0.003 * i, 0.0, 0.0));
  trailed.trails.push_back(trail);
  const Image a = renderer.render(plain), b = renderer.render(trailed);
  // summed darkening in the left (old) and right (new) thirds of the image
  double oldEnd = 0.0, newEnd = 0.0;
  for (int y = kHeight / 2 - 6; y < kHeight / 2 + 6; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const double d = int(a.pixel(x, y)[1]) - int(b.pixel(x, y)[1]);
      if (x < kWidth / 3) oldEnd += d;
      if (x >= 2 * kWidth / 3) newEnd += d;
    }
  }
  // alpha grows linearly along the trail: mean alpha in the thirds is about
  // 1/6 and 5/6 of the maximum, a ratio of 5; ask for a clear factor of 2
  constexpr double kMinRatio = 2.0;
  EXPECT_GT(newEnd, 0.0);
  EXPECT_GT(newEnd, kMinRatio * oldEnd);
}

// A force arrow starting inside a body is still drawn (on top of it).
TEST(Renderer, ArrowIsDrawnOverTheBody) {
  Renderer renderer(smallOptions());
  Scene plain = coinScene();
  plain.overlay = FrameOverlay();
  Scene arrowed = plain;
  Arrow arrow;
  arrow.origin = Vec3(0.0, 0.0, 0.005);  // inside the coin
  arrow.vector = Vec3(0.03, 0.0, 0.0);   // ends inside the coin too (R = 0.05)
  arrowed.arrows.push_back(arrow);
  const PixelBox box = projectDisk(plain.camera, plain.bodies[0]);
  const Image a = renderer.render(plain), b = renderer.render(arrowed);
  int inside = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) {
        EXPECT_TRUE(x + 0.5 > box.x0 && x + 0.5 < box.x1 && y + 0.5 > box.y0 && y + 0.5 < box.y1)
            << x << "," << y;
        ++inside;
      }
    }
  }
  constexpr int kMinArrowPixels = 10;  // a 3 cm arrow seen from 30 cm covers far more
  EXPECT_GT(inside, kMinArrowPixels);
}

// The live chart sits in the bottom-right corner and draws its series.
TEST(Renderer, OverlayChartIsDrawnBottomRight) {
  Renderer renderer(smallOptions());
  Scene plain = coinScene();
  Scene charted = plain;
  OverlayChart chart;
  chart.title = "ratio";
  chart.tMax = 1.0;
  chart.yMax = 2.0;
  chart.reference = 0.653;
  ChartSeries series;
  series.colour = {1.0, 0.0, 0.0};
  for (int i = 0; i <= 50; ++i) {
    series.t.push_back(0.02 * i);
    series.y.push_back(1.5 - 0.02 * i);
  }
  chart.series.push_back(series);
  charted.overlay.chart = chart;
  const Image a = renderer.render(plain), b = renderer.render(charted);
  int changed = 0, outside = 0, red = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
      ++changed;
      // the box is 34 % x 30 % of the frame plus a margin: well inside the
      // bottom-right 45 % x 45 %
      if (x < 0.55 * kWidth || y < 0.55 * kHeight) ++outside;
      if (q[0] > 200 && q[1] < 80 && q[2] < 80) ++red;
    }
  }
  EXPECT_EQ(outside, 0);
  constexpr int kMinChartPixels = 200;  // frame, box and text of a 54 x 36 px panel
  constexpr int kMinSeriesPixels = 10;  // a 1.5 px line across the plot area
  EXPECT_GT(changed, kMinChartPixels);
  EXPECT_GT(red, kMinSeriesPixels);
}

TEST(Renderer, BadInputIsRejected) {
  RenderOptions o = smallOptions();
  o.width = 0;
  EXPECT_THROW(Renderer{o}, RenderError);
  o = smallOptions();
  o.fontFile = "/nonexistent/font.ttf";
  EXPECT_THROW(Renderer{o}, RenderError);
  EXPECT_THROW(readPng("/nonexistent/frame.png"), RenderError);
  Renderer renderer(smallOptions());
  Scene s = coinScene();
  s.bodies[0].kind = SceneBody::ConvexHull;  // no points
  EXPECT_THROW(renderer.render(s), RenderError);
}

}  // namespace
}  // namespace patchspin::render
