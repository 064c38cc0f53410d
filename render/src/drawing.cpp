// Fixed-function OpenGL drawing of bodies, meshes and arrows (drawing.hpp).
#include "drawing.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

namespace patchspin::render::drawing {
namespace {

constexpr int kCircleSegments = 72;  // cylinder tessellation
constexpr int kSideBands = 12;       // alternating shade bands on a cylinder side

}  // namespace

Rgb scaled(Rgb c, double s) {
  return {c.r * s, c.g * s, c.b * s};
}
void colour(Rgb c, double alpha) {
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

namespace {

Rgb mixed(Rgb a, Rgb b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

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

}  // namespace

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

}  // namespace patchspin::render::drawing
