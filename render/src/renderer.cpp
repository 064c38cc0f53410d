// Scene drawing with legacy fixed-function OpenGL (OSMesa's compatibility
// profile). Pass order, each a plain loop:
//   sky gradient -> ground + grid -> meshes -> shadows, trails (decals) ->
//   bodies -> arrows -> read back, downsample -> text overlay.
#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <patchspin/render/renderer.hpp>

#include "drawing.hpp"
#include "osmesa_context.hpp"
#include "text_painter.hpp"

#ifndef PATCHSPIN_DEFAULT_FONT
#define PATCHSPIN_DEFAULT_FONT ""
#endif
#ifndef PATCHSPIN_DEFAULT_MONO_FONT
#define PATCHSPIN_DEFAULT_MONO_FONT ""
#endif

namespace patchspin::render {

using namespace drawing;

// ---------------------------------------------------------------------------

namespace {
// World points whose images bound the body's image: hull points, box
// corners, or points on the cylinder rims.
std::vector<Vec3> outlinePoints(const SceneBody& b) {
  std::vector<Vec3> pts;
  switch (b.kind) {
    case SceneBody::ConvexHull:
      for (const Vec3& p : b.hullPoints) pts.push_back(b.pose * p);
      break;
    case SceneBody::Box:
      for (int i = 0; i < 8; ++i) {
        pts.push_back(b.pose * Vec3((i & 1 ? 0.5 : -0.5) * b.dimensions.x(),
                                    (i & 2 ? 0.5 : -0.5) * b.dimensions.y(),
                                    (i & 4 ? 0.5 : -0.5) * b.dimensions.z()));
      }
      break;
    case SceneBody::Cylinder:
      for (int i = 0; i < 32; ++i) {
        const double t = 2.0 * kPi * i / 32;
        for (double z : {-0.5, 0.5}) {
          pts.push_back(b.pose * Vec3(b.dimensions.x() * std::cos(t),
                                      b.dimensions.x() * std::sin(t), z * b.dimensions.z()));
        }
      }
      break;
  }
  return pts;
}
}  // namespace

void boundingSphere(const std::vector<SceneBody>& bodies, Vec3& centre, double& radius) {
  std::vector<Vec3> pts;
  for (const SceneBody& b : bodies) {
    const std::vector<Vec3> outline = outlinePoints(b);
    pts.insert(pts.end(), outline.begin(), outline.end());
  }
  if (pts.empty()) {
    centre = Vec3::Zero();
    radius = 0.1;
    return;
  }
  Vec3 lo = pts[0], hi = pts[0];
  for (const Vec3& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  centre = 0.5 * (lo + hi);
  radius = 0.0;
  for (const Vec3& p : pts) radius = std::max(radius, (p - centre).norm());
  radius = std::max(radius, 1e-6);
}

Camera fitCamera(const std::vector<SceneBody>& bodies, double azimuthDeg, double elevationDeg,
                 double aspect, double margin, double fovYDeg) {
  Vec3 centre;
  double radius;
  boundingSphere(bodies, centre, radius);
  const double az = azimuthDeg * kPi / 180.0, el = elevationDeg * kPi / 180.0;
  const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const double halfY = 0.5 * fovYDeg * kPi / 180.0;
  const double halfX = std::atan(aspect * std::tan(halfY));
  const double distance = margin * radius / std::sin(std::min(halfX, halfY));
  Camera cam;
  cam.target = centre;
  cam.eye = centre + distance * dir;
  cam.up = Vec3::UnitZ();
  cam.fovYDeg = fovYDeg;
  return cam;
}

// ---------------------------------------------------------------------------
// The passes of Renderer::render, in drawing order.

namespace {
// What the passes share: the camera, its matrices and the scene's scale.
struct FrameView {
  const Camera& cam;
  double distance;  // eye to target [m]
  double radius;    // the bodies' bounding sphere
  double fogEnd;    // fog is full at this distance from the eye
  Mat4 view, proj;
  double groundHeight;
};

// sky: gradient in screen space from the horizon line up
void drawSky(const RenderOptions& opt, const FrameView& v) {
  const Camera& cam = v.cam;
  const Mat4& view = v.view;
  const Mat4& proj = v.proj;
  // horizon: vanishing line of the ground, the image of the horizontal view direction
  Vec3 fwd = cam.target - cam.eye;
  fwd.z() = 0.0;
  double horizonY = -1.0;  // NDC
  if (fwd.norm() > 1e-12) {
    const Eigen::Vector4d clip = proj * view * Eigen::Vector4d(fwd.x(), fwd.y(), 0.0, 0.0);
    if (clip.w() > 1e-12) horizonY = std::clamp(clip.y() / clip.w(), -1.0, 1.0);
  } else {
    horizonY = 1.0;  // looking straight down
  }
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glBegin(GL_QUADS);
  colour(opt.skyHorizon);
  glVertex2d(-1, -1);
  glVertex2d(1, -1);
  glVertex2d(1, horizonY);
  glVertex2d(-1, horizonY);
  glVertex2d(-1, horizonY);
  glVertex2d(1, horizonY);
  colour(opt.skyTop);
  glVertex2d(1, 1);
  glVertex2d(-1, 1);
  glEnd();
}

// light fixed in the world (position set under the view matrix); returns
// its unit direction
Vec3 setUpLight(const RenderOptions& opt) {
  const Vec3 light = opt.lightDirection.normalized();
  const GLfloat pos[4] = {static_cast<GLfloat>(light.x()), static_cast<GLfloat>(light.y()),
                          static_cast<GLfloat>(light.z()), 0.0f};
  const GLfloat ambient[4] = {0.38f, 0.38f, 0.40f, 1.0f};
  const GLfloat diffuse[4] = {0.68f, 0.68f, 0.66f, 1.0f};
  const GLfloat specular[4] = {0.25f, 0.25f, 0.25f, 1.0f};
  const GLfloat none[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, none);
  glLightfv(GL_LIGHT0, GL_POSITION, pos);
  glLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, specular);
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);
  const GLfloat shininess = 24.0f;
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, shininess);
  return light;
}

// ground and grid, then the meshes, fogged into the horizon colour
void drawGround(const Scene& scene, const RenderOptions& opt, const FrameView& v, int ss) {
  const Camera& cam = v.cam;
  const double distance = v.distance, fogEnd = v.fogEnd, h = v.groundHeight;
  const GLfloat fogColour[4] = {static_cast<GLfloat>(opt.skyHorizon.r),
                                static_cast<GLfloat>(opt.skyHorizon.g),
                                static_cast<GLfloat>(opt.skyHorizon.b), 1.0f};
  glEnable(GL_FOG);
  glFogi(GL_FOG_MODE, GL_LINEAR);
  glFogfv(GL_FOG_COLOR, fogColour);
  glFogf(GL_FOG_START, static_cast<GLfloat>(1.0 * distance));
  glFogf(GL_FOG_END, static_cast<GLfloat>(fogEnd));

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_LIGHTING);
  const double extent = fogEnd * 1.2;
  const Vec3 c(cam.target.x(), cam.target.y(), h);
  // ground in tiles so per-vertex fog varies across it
  constexpr int kTiles = 32;
  colour(opt.ground);
  glBegin(GL_QUADS);
  normal(Vec3::UnitZ());
  for (int i = 0; i < kTiles; ++i) {
    for (int j = 0; j < kTiles; ++j) {
      const double x0 = c.x() - extent + 2.0 * extent * i / kTiles;
      const double x1 = c.x() - extent + 2.0 * extent * (i + 1) / kTiles;
      const double y0 = c.y() - extent + 2.0 * extent * j / kTiles;
      const double y1 = c.y() - extent + 2.0 * extent * (j + 1) / kTiles;
      vertex(Vec3(x0, y0, h));
      vertex(Vec3(x1, y0, h));
      vertex(Vec3(x1, y1, h));
      vertex(Vec3(x0, y1, h));
    }
  }
  glEnd();

  // grid lines (decals on the ground: no depth test needed, the camera is above it)
  glDisable(GL_LIGHTING);
  glDisable(GL_DEPTH_TEST);
  const double step = opt.gridSpacing > 0.0 ? opt.gridSpacing : niceStep(distance / 12.0);
  // lines fade out with distance from the eye (minor ones sooner), so the
  // grid never gets denser than a few pixels per cell towards the horizon
  const double reach = std::min(3.0 * distance, 400.0 * step);
  const long n = static_cast<long>(std::ceil(reach / step));
  const long i0 = static_cast<long>(std::floor(c.x() / step));
  const long j0 = static_cast<long>(std::floor(c.y() / step));
  const Vec3 eyeOnGround(cam.eye.x(), cam.eye.y(), h);
  constexpr int kPieces = 48;
  for (int major = 0; major < 2; ++major) {
    const double fade = (major ? 3.0 : 1.8) * distance;
    const Rgb lineColour = scaled(opt.ground, major ? 0.6 : 0.78);
    glLineWidth(static_cast<GLfloat>((major ? 1.6 : 1.0) * ss));
    auto line = [&](const Vec3& a, const Vec3& b) {
      glBegin(GL_LINE_STRIP);
      for (int k = 0; k <= kPieces; ++k) {
        const Vec3 p = a + (b - a) * (static_cast<double>(k) / kPieces);
        const double x = (p - eyeOnGround).norm() / fade;
        colour(lineColour, std::clamp(1.0 - x * x, 0.0, 1.0));
        vertex(p);
      }
      glEnd();
    };
    for (long k = -n; k <= n; ++k) {
      const long ix = i0 + k, iy = j0 + k;
      if ((ix % 5 == 0) == static_cast<bool>(major)) {
        line(Vec3(ix * step, c.y() - reach, h), Vec3(ix * step, c.y() + reach, h));
      }
      if ((iy % 5 == 0) == static_cast<bool>(major)) {
        line(Vec3(c.x() - reach, iy * step, h), Vec3(c.x() + reach, iy * step, h));
      }
    }
  }
  // meshes: over the ground (its depth cleared), depth-tested among
  // themselves, fogged like it
  if (!scene.meshes.empty()) {
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_LIGHTING);
    glLineWidth(static_cast<GLfloat>(ss));
    for (const SceneMesh& mesh : scene.meshes) drawMesh(mesh, cam.eye);
    glDisable(GL_LIGHTING);
    glDisable(GL_DEPTH_TEST);
  }
  glDisable(GL_FOG);
}

// shadows: bodies flattened onto the ground along the light; the stencil
// lets each pixel darken once however many bodies overlap
void drawShadows(const Scene& scene, const RenderOptions& opt, const Vec3& light, double h,
                 HullCache& hulls) {
  if (!(opt.shadows && light.z() > 1e-3)) return;
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  glPushMatrix();
  const Mat4 S = shadowMatrix(light, h);
  glMultMatrixd(S.data());
  glColor4d(0.05, 0.05, 0.1, 0.45);
  for (const SceneBody& body : scene.bodies) drawBody(body, Pass::Silhouette, hulls);
  glPopMatrix();
  glDisable(GL_STENCIL_TEST);
}

// trails: line strips fading from transparent (oldest) to opaque (newest),
// lifted a hair above the ground
void drawTrails(const Scene& scene, int ss) {
  for (const Trail& trail : scene.trails) {
    const std::size_t n = trail.points.size();
    if (n < 2) continue;
    glLineWidth(static_cast<GLfloat>(std::max(1.0, trail.widthPx * ss)));
    glBegin(GL_LINE_STRIP);
    for (std::size_t i = 0; i < n; ++i) {
      const double age = static_cast<double>(i) / static_cast<double>(n - 1);
      colour(trail.colour, 0.9 * age);
      vertex(trail.points[i]);
    }
    glEnd();
  }
}

// bodies: depth-tested among themselves only (ground decals are behind them)
void drawBodies(const Scene& scene, int ss, HullCache& hulls) {
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_LIGHTING);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);  // outlines and decals win against the faces
  glLineWidth(static_cast<GLfloat>(1.2 * ss));
  for (const SceneBody& body : scene.bodies) drawBody(body, Pass::Shaded, hulls);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

// arrows: always on top of the bodies
void drawArrows(const Scene& scene, double radius) {
  glClear(GL_DEPTH_BUFFER_BIT);
  for (const Arrow& arrow : scene.arrows) {
    const double len = arrow.vector.norm();
    if (len < 1e-12) continue;
    const Vec3 z = arrow.vector / len, x = anyPerpendicular(z), y = z.cross(x);
    Mat4 m = Mat4::Identity();
    m.block<3, 1>(0, 0) = x;
    m.block<3, 1>(0, 1) = y;
    m.block<3, 1>(0, 2) = z;
    m.block<3, 1>(0, 3) = arrow.origin;
    glPushMatrix();
    glMultMatrixd(m.data());
    colour(arrow.colour);
    // head length grows with the arrow but stays within 30 % of it; head and
    // shaft widths are fixed fractions of the head length
    const double head = std::min(0.3 * len, 0.12 * radius + 0.15 * len);
    const double headRadius = 0.35 * head, shaftRadius = 0.35 * headRadius;
    drawArrowGeometry(len, shaftRadius, head, headRadius);
    glPopMatrix();
  }
  glDisable(GL_LIGHTING);
}

// read back and box-filter down to the output size
Image downsample(const std::vector<std::uint8_t>& buf, const RenderOptions& opt, int W) {
  const int ss = opt.supersample;
  Image image;
  image.width = opt.width;
  image.height = opt.height;
  image.rgb.resize(static_cast<std::size_t>(opt.width) * opt.height * 3);
  const int n2 = ss * ss;
  for (int y = 0; y < opt.height; ++y) {
    for (int x = 0; x < opt.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < ss; ++dy) {
        const std::uint8_t* row = buf.data() + 4 * (static_cast<std::size_t>(y * ss + dy) * W);
        for (int dx = 0; dx < ss; ++dx) {
          const std::uint8_t* p = row + 4 * (x * ss + dx);
          sum[0] += p[0];
          sum[1] += p[1];
          sum[2] += p[2];
        }
      }
      std::uint8_t* out = image.pixel(x, y);
      for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>((sum[c] + n2 / 2) / n2);
    }
  }
  return image;
}

// overlay: labels at projected world points
std::vector<internal::ScreenLabel> screenLabels(const Scene& scene, const RenderOptions& opt,
                                                const Mat4& pv) {
  auto toPixel = [&](const Vec3& p) -> std::optional<Eigen::Vector2d> {
    const Eigen::Vector4d clip = pv * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (clip.w() <= 1e-12) return std::nullopt;
    return Eigen::Vector2d((0.5 + 0.5 * clip.x() / clip.w()) * opt.width,
                           (0.5 - 0.5 * clip.y() / clip.w()) * opt.height);
  };
  std::vector<internal::ScreenLabel> labels;
  for (const TrackedBody& b : scene.overlay.tracked) {
    if (b.label.empty()) continue;
    if (b.anchor) {
      if (auto px = toPixel(*b.anchor))
        labels.push_back({px->x(), px->y(), b.label, {0.1, 0.1, 0.1}, true});
    } else if (b.body >= 0 && b.body < static_cast<int>(scene.bodies.size())) {
      // centred over the body's image, just above its top
      double top = 1e300, left = 1e300, right = -1e300;
      for (const Vec3& p : outlinePoints(scene.bodies[static_cast<std::size_t>(b.body)])) {
        if (auto px = toPixel(p)) {
          top = std::min(top, px->y());
          left = std::min(left, px->x());
          right = std::max(right, px->x());
        }
      }
      if (right >= left)
        labels.push_back({0.5 * (left + right), top, b.label, {0.1, 0.1, 0.1}, true});
    }
  }
  for (const Arrow& a : scene.arrows) {
    if (a.label.empty()) continue;
    if (auto px = toPixel(a.origin + a.vector)) {
      labels.push_back({px->x(), px->y(), a.label, scaled(a.colour, 0.7), false});
    }
  }
  return labels;
}
}  // namespace

// ---------------------------------------------------------------------------

struct Renderer::Impl {
  RenderOptions options;
  internal::OsmesaContext context;
  internal::TextPainter text;
  HullCache hulls;

  explicit Impl(const RenderOptions& o)
      : options(o),
        context(o.width * o.supersample, o.height * o.supersample),
        text(o.fontFile, o.monoFontFile) {}
};

namespace {
RenderOptions withDefaults(RenderOptions o) {
  if (o.width <= 0 || o.height <= 0) {
    throw RenderError("render size must be positive: got " + std::to_string(o.width) + "x" +
                      std::to_string(o.height));
  }
  if (o.supersample < 1 || o.supersample > 4) {
    throw RenderError("supersample must be 1..4: got " + std::to_string(o.supersample));
  }
  if (o.fontFile.empty()) o.fontFile = PATCHSPIN_DEFAULT_FONT;
  if (o.monoFontFile.empty()) o.monoFontFile = PATCHSPIN_DEFAULT_MONO_FONT;
  return o;
}
}  // namespace

Renderer::Renderer(const RenderOptions& options)
    : impl_(std::make_unique<Impl>(withDefaults(options))) {}

Renderer::~Renderer() = default;

const RenderOptions& Renderer::options() const {
  return impl_->options;
}

Image Renderer::render(const Scene& scene) {
  const RenderOptions& opt = impl_->options;
  internal::OsmesaContext& ctx = impl_->context;
  ctx.makeCurrent();
  const int W = ctx.width(), H = ctx.height(), ss = opt.supersample;
  const double aspect = static_cast<double>(opt.width) / opt.height;

  // camera and depth range from the scene scale
  const Camera& cam = scene.camera;
  const double distance = std::max((cam.eye - cam.target).norm(), 1e-6);
  Vec3 centre;
  double radius;
  boundingSphere(scene.bodies, centre, radius);
  const double zNear = std::max(1e-4, 0.02 * distance);
  const double fogEnd = 6.0 * distance, zFar = 1.5 * fogEnd;
  const FrameView v{cam,
                    distance,
                    radius,
                    fogEnd,
                    lookAt(cam),
                    perspective(cam.fovYDeg, aspect, zNear, zFar),
                    opt.groundHeight};

  glViewport(0, 0, W, H);
  glClearColor(0, 0, 0, 1);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  drawSky(opt, v);

  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(v.proj.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(v.view.data());
  const Vec3 light = setUpLight(opt);
  drawGround(scene, opt, v, ss);
  drawShadows(scene, opt, light, v.groundHeight, impl_->hulls);
  drawTrails(scene, ss);
  drawBodies(scene, ss, impl_->hulls);
  drawArrows(scene, v.radius);

  Image image = downsample(ctx.finish(), opt, W);
  const std::vector<internal::ScreenLabel> labels = screenLabels(scene, opt, v.proj * v.view);
  const double fontPx = std::max(8.0, opt.height / 36.0 * opt.fontScale);
  impl_->text.draw(image, scene.overlay, labels, fontPx);
  return image;
}

}  // namespace patchspin::render
