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

#include "hull.hpp"
#include "osmesa_context.hpp"
#include "text_painter.hpp"

#ifndef PATCHSPIN_DEFAULT_FONT
#define PATCHSPIN_DEFAULT_FONT ""
#endif
#ifndef PATCHSPIN_DEFAULT_MONO_FONT
#define PATCHSPIN_DEFAULT_MONO_FONT ""
#endif

namespace patchspin::render {

using Mat4 = Eigen::Matrix4d;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCircleSegments = 72;  // cylinder tessellation
constexpr int kSideBands = 12;       // alternating shade bands on a cylinder side

Rgb scaled(Rgb c, double s) {
  return {c.r * s, c.g * s, c.b * s};
}
Rgb mixed(Rgb a, Rgb b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}
void colour(Rgb c, double alpha = 1.0) {
  glColor4d(std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0), alpha);
}
void vertex(const Vec3& p) {
  glVertex3d(p.x(), p.y(), p.z());
}
void normal(const Vec3& n) {
  glNormal3d(n.x(), n.y(), n.z());
}

// view matrix: world -> eye, like gluLookAt
Mat4 lookAt(const Camera& cam) {
  const Vec3 f = (cam.target - cam.eye).normalized();
  Vec3 s = f.cross(cam.up);
  if (s.norm() < 1e-12) s = f.cross(Vec3::UnitX());  // looking along up
  s.normalize();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(cam.eye);
  m(1, 3) = -u.dot(cam.eye);
  m(2, 3) = f.dot(cam.eye);
  return m;
}

// projection matrix, like gluPerspective
Mat4 perspective(double fovYDeg, double aspect, double zNear, double zFar) {
  const double f = 1.0 / std::tan(0.5 * fovYDeg * kPi / 180.0);
  Mat4 m = Mat4::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (zFar + zNear) / (zNear - zFar);
  m(2, 3) = 2.0 * zFar * zNear / (zNear - zFar);
  m(3, 2) = -1.0;
  return m;
}

// Projection onto the plane z = h along the directional light L (w = 0):
//   S = (P.L) I - L P^T,  P = (0, 0, 1, -h),  L = (lx, ly, lz, 0)
Mat4 shadowMatrix(const Vec3& light, double h) {
  const Eigen::Vector4d P(0.0, 0.0, 1.0, -h);
  const Eigen::Vector4d L(light.x(), light.y(), light.z(), 0.0);
  return P.dot(L) * Mat4::Identity() - L * P.transpose();
}

// largest 1-2-5 step not above x
double niceStep(double x) {
  const double e = std::pow(10.0, std::floor(std::log10(x)));
  const double m = x / e;
  return (m >= 5.0 ? 5.0 : m >= 2.0 ? 2.0 : 1.0) * e;
}

// Geometry passes draw either shaded (colours, decals, outlines) or as a flat
// silhouette (shadow pass: position only).
enum class Pass { Shaded, Silhouette };

// Disk-strip intersection on a cap: |y| <= halfWidth, x^2 + y^2 <= R^2, at height z,
// facing nz (+1 or -1).
void drawCapStripe(double R, double halfWidth, double z, double nz) {
  const double a = std::asin(std::min(halfWidth / R, 1.0));
  constexpr int kArc = 8;
  glBegin(GL_POLYGON);
  normal(Vec3(0, 0, nz));
  // right arc from -a to a, then left arc from pi - a to pi + a (CCW from +z)
  std::vector<Vec3> pts;
  for (int i = 0; i <= kArc; ++i) {
    const double t = -a + 2.0 * a * i / kArc;
    pts.emplace_back(R * std::cos(t), R * std::sin(t), z);
  }
  for (int i = 0; i <= kArc; ++i) {
    const double t = kPi - a + 2.0 * a * i / kArc;
    pts.emplace_back(R * std::cos(t), R * std::sin(t), z);
  }
  if (nz < 0) std::reverse(pts.begin(), pts.end());
  for (const Vec3& p : pts) vertex(p);
  glEnd();
}

void drawDisk(const Vec3& centre, double r, double nz) {
  glBegin(GL_TRIANGLE_FAN);
  normal(Vec3(0, 0, nz));
  vertex(centre);
  constexpr int kN = 24;
  for (int i = 0; i <= kN; ++i) {
    const double t = (nz > 0 ? 1.0 : -1.0) * 2.0 * kPi * i / kN;
    vertex(centre + Vec3(r * std::cos(t), r * std::sin(t), 0.0));
  }
  glEnd();
}

void drawCylinder(const SceneBody& body, Pass pass) {
  const double R = body.dimensions.x(), H = body.dimensions.z(), zt = 0.5 * H, zb = -0.5 * H;
  const Rgb base = body.colour, band = scaled(body.colour, 0.78);
  const bool shaded = pass == Pass::Shaded;
  // side: quads with outward normals, alternate bands show the rotation
  glBegin(GL_QUADS);
  for (int i = 0; i < kCircleSegments; ++i) {
    const double t0 = 2.0 * kPi * i / kCircleSegments, t1 = 2.0 * kPi * (i + 1) / kCircleSegments;
    if (shaded) colour((body.spinMarker && (i * kSideBands / kCircleSegments) % 2) ? band : base);
    const Vec3 n0(std::cos(t0), std::sin(t0), 0.0), n1(std::cos(t1), std::sin(t1), 0.0);
    normal(n0);
    vertex(Vec3(R * n0.x(), R * n0.y(), zb));
    normal(n1);
    vertex(Vec3(R * n1.x(), R * n1.y(), zb));
    vertex(Vec3(R * n1.x(), R * n1.y(), zt));
    normal(n0);
    vertex(Vec3(R * n0.x(), R * n0.y(), zt));
  }
  glEnd();
  // caps
  if (shaded) colour(base);
  for (double nz : {1.0, -1.0}) {
    glBegin(GL_TRIANGLE_FAN);
    normal(Vec3(0, 0, nz));
    vertex(Vec3(0, 0, nz * zt));
    for (int i = 0; i <= kCircleSegments; ++i) {
      const double t = nz * 2.0 * kPi * i / kCircleSegments;
      vertex(Vec3(R * std::cos(t), R * std::sin(t), nz * zt));
    }
    glEnd();
  }
  if (!shaded) return;
  // spin marker decals: a stripe across each cap and a dot off-centre (breaks
  // the half-turn symmetry), pulled towards the viewer by polygon offset
  if (body.spinMarker) {
    glPolygonOffset(-1.0f, -1.0f);
    for (double nz : {1.0, -1.0}) {
      colour(mixed(base, Rgb{0.1, 0.1, 0.12}, 0.7));
      drawCapStripe(R, 0.11 * R, nz * zt, nz);
      colour(Rgb{0.97, 0.97, 0.95});
      drawDisk(Vec3(0.0, 0.6 * R, nz * zt), 0.13 * R, nz);
    }
    glPolygonOffset(1.0f, 1.0f);
  }
  // rims
  glDisable(GL_LIGHTING);
  colour(scaled(base, 0.4));
  for (double z : {zt, zb}) {
    glBegin(GL_LINE_LOOP);
    for (int i = 0; i < kCircleSegments; ++i) {
      const double t = 2.0 * kPi * i / kCircleSegments;
      vertex(Vec3(R * std::cos(t), R * std::sin(t), z));
    }
    glEnd();
  }
  glEnable(GL_LIGHTING);
}

void drawPolygonFaces(const std::vector<internal::HullFace>& faces, const SceneBody& body,
                      Pass pass) {
  if (pass == Pass::Shaded) colour(body.colour);
  for (const internal::HullFace& f : faces) {
    glBegin(GL_POLYGON);
    normal(f.normal);
    for (const Vec3& p : f.vertices) vertex(p);
    glEnd();
  }
  if (pass == Pass::Silhouette) return;
  glDisable(GL_LIGHTING);
  colour(scaled(body.colour, 0.4));
  for (const internal::HullFace& f : faces) {
    glBegin(GL_LINE_LOOP);
    for (const Vec3& p : f.vertices) vertex(p);
    glEnd();
  }
  glEnable(GL_LIGHTING);
}

std::vector<internal::HullFace> boxFaces(const Vec3& size) {
  const Vec3 h = 0.5 * size;
  std::vector<internal::HullFace> faces;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sgn : {1.0, -1.0}) {
      internal::HullFace f;
      f.normal = Vec3::Zero();
      f.normal[axis] = sgn;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      // (a, b, axis) is right-handed, so corners CCW in (a, b) face +axis
      const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int i = 0; i < 4; ++i) {
        const int k = sgn > 0 ? i : 3 - i;
        Vec3 p;
        p[axis] = sgn * h[axis];
        p[a] = corners[k][0] * h[a];
        p[b] = corners[k][1] * h[b];
        f.vertices.push_back(p);
      }
      faces.push_back(f);
    }
  }
  return faces;
}

void drawBoxMarker(const SceneBody& body) {
  const Vec3 h = 0.5 * body.dimensions;
  const double halfWidth = 0.09 * std::min(body.dimensions.x(), body.dimensions.y());
  glPolygonOffset(-1.0f, -1.0f);
  for (double nz : {1.0, -1.0}) {
    colour(mixed(body.colour, Rgb{0.1, 0.1, 0.12}, 0.7));
    glBegin(GL_QUADS);
    normal(Vec3(0, 0, nz));
    const double z = nz * h.z();
    const double ys[4] = {-halfWidth, -halfWidth, halfWidth, halfWidth};
    const double xs[4] = {-h.x(), h.x(), h.x(), -h.x()};
    for (int i = 0; i < 4; ++i) {
      const int k = nz > 0 ? i : 3 - i;
      vertex(Vec3(xs[k], ys[k], z));
    }
    glEnd();
    colour(Rgb{0.97, 0.97, 0.95});
    drawDisk(Vec3(0.0, 0.55 * h.y(), z), 0.12 * std::min(h.x(), h.y()), nz);
  }
  glPolygonOffset(1.0f, 1.0f);
}

// A static mesh: flat-shaded triangles, each normal turned towards the eye
// (both sides lit), then the edges in a darker shade. Faces are pushed back
// by polygon offset so their own edges win the depth test.
void drawMesh(const SceneMesh& mesh, const Vec3& eye) {
  const int n = static_cast<int>(mesh.vertices.size());
  for (const std::array<int, 3>& t : mesh.triangles)
    for (int i : t)
      if (i < 0 || i >= n)
        throw RenderError("mesh triangle index " + std::to_string(i) + " outside 0.." +
                          std::to_string(n - 1));
  auto finite = [&](const std::array<int, 3>& t) {
    for (int i : t)
      if (!mesh.vertices[static_cast<std::size_t>(i)].allFinite()) return false;
    return true;
  };
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  colour(mesh.colour);
  glBegin(GL_TRIANGLES);
  for (const std::array<int, 3>& t : mesh.triangles) {
    if (!finite(t)) continue;
    const Vec3 &a = mesh.vertices[static_cast<std::size_t>(t[0])],
               &b = mesh.vertices[static_cast<std::size_t>(t[1])],
               &c = mesh.vertices[static_cast<std::size_t>(t[2])];
    Vec3 nrm = (b - a).cross(c - a);
    if (nrm.dot(eye - a) < 0.0) nrm = -nrm;
    normal(nrm.norm() > 0.0 ? nrm : Vec3::UnitZ());
    vertex(a);
    vertex(b);
    vertex(c);
  }
  glEnd();
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (mesh.edgeAlpha <= 0.0) return;
  glDisable(GL_LIGHTING);
  colour(scaled(mesh.colour, 0.55), std::min(mesh.edgeAlpha, 1.0));
  glBegin(GL_LINES);
  for (const std::array<int, 3>& t : mesh.triangles) {
    if (!finite(t)) continue;
    for (int k = 0; k < 3; ++k) {
      vertex(mesh.vertices[static_cast<std::size_t>(t[k])]);
      vertex(mesh.vertices[static_cast<std::size_t>(t[(k + 1) % 3])]);
    }
  }
  glEnd();
  glEnable(GL_LIGHTING);
}

// Hull faces of recently drawn point sets: a hull is built once, not in
// every pass of every frame.
class HullCache {
 public:
  const std::vector<internal::HullFace>& faces(const std::vector<Vec3>& points) {
    for (const auto& [key, value] : entries_) {
      if (key == points) return value;
    }
    constexpr std::size_t kMaxEntries = 64;
    if (entries_.size() >= kMaxEntries) entries_.clear();
    entries_.emplace_back(points, internal::convexHullFaces(points));
    return entries_.back().second;
  }

 private:
  std::vector<std::pair<std::vector<Vec3>, std::vector<internal::HullFace>>> entries_;
};

void drawBody(const SceneBody& body, Pass pass, HullCache& hulls) {
  glPushMatrix();
  glMultMatrixd(body.pose.matrix().data());
  switch (body.kind) {
    case SceneBody::Cylinder:
      drawCylinder(body, pass);
      break;
    case SceneBody::Box:
      drawPolygonFaces(boxFaces(body.dimensions), body, pass);
      if (pass == Pass::Shaded && body.spinMarker) drawBoxMarker(body);
      break;
    case SceneBody::ConvexHull:
      drawPolygonFaces(hulls.faces(body.hullPoints), body, pass);
      break;
  }
  glPopMatrix();
}

// Shaft and cone along +z of length len, lit.
void drawArrowGeometry(double len, double shaftRadius, double headLength, double headRadius) {
  constexpr int kN = 24;
  const double zs = std::max(0.0, len - headLength);
  glBegin(GL_QUAD_STRIP);
  for (int i = 0; i <= kN; ++i) {
    const double t = 2.0 * kPi * i / kN;
    const Vec3 n(std::cos(t), std::sin(t), 0.0);
    normal(n);
    vertex(Vec3(shaftRadius * n.x(), shaftRadius * n.y(), zs));
    vertex(Vec3(shaftRadius * n.x(), shaftRadius * n.y(), 0.0));
  }
  glEnd();
  // cone: slanted normals
  const double slope = headRadius / std::max(headLength, 1e-12);
  glBegin(GL_TRIANGLES);
  for (int i = 0; i < kN; ++i) {
    const double t0 = 2.0 * kPi * i / kN, t1 = 2.0 * kPi * (i + 1) / kN, tm = 0.5 * (t0 + t1);
    auto n = [&](double t) { return Vec3(std::cos(t), std::sin(t), slope).normalized(); };
    normal(n(t0));
    vertex(Vec3(headRadius * std::cos(t0), headRadius * std::sin(t0), zs));
    normal(n(t1));
    vertex(Vec3(headRadius * std::cos(t1), headRadius * std::sin(t1), zs));
    normal(n(tm));
    vertex(Vec3(0, 0, len));
  }
  glEnd();
  // base of the cone
  glBegin(GL_TRIANGLE_FAN);
  normal(Vec3(0, 0, -1));
  vertex(Vec3(0, 0, zs));
  for (int i = kN; i >= 0; --i) {
    const double t = 2.0 * kPi * i / kN;
    vertex(Vec3(headRadius * std::cos(t), headRadius * std::sin(t), zs));
  }
  glEnd();
}

Vec3 anyPerpendicular(const Vec3& v) {
  const Vec3 a = std::abs(v.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return v.cross(a).normalized();
}

}  // namespace

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
  const Mat4 view = lookAt(cam);
  const Mat4 proj = perspective(cam.fovYDeg, aspect, zNear, zFar);
  const double h = opt.groundHeight;

  glViewport(0, 0, W, H);
  glClearColor(0, 0, 0, 1);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  // sky: gradient in screen space from the horizon line up
  {
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

  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(proj.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(view.data());

  // light fixed in the world (position set under the view matrix)
  const Vec3 light = opt.lightDirection.normalized();
  {
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
  }

  // ground and grid, fogged into the horizon colour
  {
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
  if (opt.shadows && light.z() > 1e-3) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    glPushMatrix();
    const Mat4 S = shadowMatrix(light, h);
    glMultMatrixd(S.data());
    glColor4d(0.05, 0.05, 0.1, 0.45);
    for (const SceneBody& body : scene.bodies) drawBody(body, Pass::Silhouette, impl_->hulls);
    glPopMatrix();
    glDisable(GL_STENCIL_TEST);
  }

  // trails: line strips fading from transparent (oldest) to opaque (newest),
  // lifted a hair above the ground
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

  // bodies: depth-tested among themselves only (ground decals are behind them)
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_LIGHTING);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);  // outlines and decals win against the faces
  glLineWidth(static_cast<GLfloat>(1.2 * ss));
  for (const SceneBody& body : scene.bodies) drawBody(body, Pass::Shaded, impl_->hulls);
  glDisable(GL_POLYGON_OFFSET_FILL);

  // arrows: always on top of the bodies
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

  // read back and box-filter down to the output size
  const std::vector<std::uint8_t>& buf = ctx.finish();
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

  // overlay: labels at projected world points
  const Mat4 pv = proj * view;
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
  const double fontPx = std::max(8.0, opt.height / 36.0 * opt.fontScale);
  impl_->text.draw(image, scene.overlay, labels, fontPx);
  return image;
}

// ---------------------------------------------------------------------------

FrameWriter::FrameWriter(std::string directory, double fps, std::string prefix, int digits)
    : directory_(std::move(directory)), fps_(fps), prefix_(std::move(prefix)), digits_(digits) {
  if (!(fps > 0.0)) throw RenderError("frame rate must be positive: got " + std::to_string(fps));
  if (digits < 1 || digits > 9) throw RenderError("frame digits must be 1..9");
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) throw RenderError("cannot create frame directory " + directory_ + ": " + ec.message());
}

std::string FrameWriter::framePath(int index) const {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*d", digits_, index);
  return (std::filesystem::path(directory_) / (prefix_ + buf + ".png")).string();
}

std::string FrameWriter::ffmpegCommand(const std::string& output) const {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps_);
  const std::string pattern =
      (std::filesystem::path(directory_) / (prefix_ + "%0" + std::to_string(digits_) + "d.png"))
          .string();
  const bool gif = output.size() >= 4 && output.compare(output.size() - 4, 4, ".gif") == 0;
  std::string cmd = "ffmpeg -y -framerate " + std::string(rate) + " -i '" + pattern + "' ";
  if (gif) {
    // two-pass palette in one filter graph: far better colours than the default
    cmd += "-vf 'split[a][b];[a]palettegen[p];[b][p]paletteuse' ";
  } else {
    // H.264 in yuv420p (plays everywhere) needs even sizes
    cmd += "-c:v libx264 -pix_fmt yuv420p -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' ";
  }
  return cmd + "'" + output + "'";
}

std::string FrameWriter::write(const Image& image) {
  const std::string path = framePath(count_);
  writePng(image, path);
  ++count_;
  return path;
}

}  // namespace patchspin::render
