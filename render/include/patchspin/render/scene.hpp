// Plain scene description drawn by patchspin::render. No Bullet types: the
// demos copy their world into these structs once per frame.
//
// World frame: x, y horizontal, z up (as in simulation.hpp); SI units (metres).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace patchspin::render {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Every rendering or plotting failure (bad input, missing font, missing
// gnuplot, unwritable file) throws this with a message saying what to do.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Linear RGB colour, each channel in [0, 1].
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

// One rigid body.
struct SceneBody {
  enum Kind { Cylinder, Box, ConvexHull };
  Kind kind = Cylinder;
  // Cylinder: (radius, radius, height), axis along body z, centred at the body origin.
  // Box: full edge lengths (LX, LY, LZ), centred at the body origin.
  // ConvexHull: unused.                                                      [m]
  Vec3 dimensions = Vec3(0.05, 0.05, 0.01);
  // ConvexHull only: points in the body frame (the hull of at most ~64 points
  // is rebuilt every frame, O(n^4)).                                         [m]
  std::vector<Vec3> hullPoints;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // body frame -> world
  Rgb colour{0.85, 0.55, 0.2};
  // Spin cue: a stripe and a dot on cylinder caps, bands on the cylinder side,
  // a stripe on the top and bottom faces of boxes.
  bool spinMarker = true;
};

// A static triangle mesh in world coordinates (terrain, level geometry),
// drawn lit above the ground plane: every mesh covers the ground and its grid
// (meant to lie on or above z = RenderOptions::groundHeight); shadows and
// trails are drawn over it, bodies in front of it. Flat shaded, both sides
// lit (each triangle's normal is turned towards the eye).
// (Renderer.MeshAppearsWhereThePinholeProjectionPutsIt)
struct SceneMesh {
  std::vector<Vec3> vertices;                 // world [m]
  std::vector<std::array<int, 3>> triangles;  // indices into vertices; a triangle
                                              // with a non-finite vertex is skipped
  Rgb colour{0.66, 0.70, 0.60};
  // opacity of the triangle edges, drawn in a darker shade of the colour so
  // the tessellation shows; 0: no edges                                   [0, 1]
  double edgeAlpha = 0.2;
};

// Fading trail of a patch's reference point: points oldest first; the oldest
// is drawn transparent, the newest opaque.
struct Trail {
  std::vector<Vec3> points;  // world [m]
  Rgb colour{0.1, 0.3, 0.8};
  double widthPx = 2.5;  // line width in output pixels
};

// Arrow for an applied force (or any vector), drawn on top of the bodies.
struct Arrow {
  Vec3 origin = Vec3::Zero();   // world [m]
  Vec3 vector = Vec3::UnitX();  // world [m]; the caller chooses the N -> m scale
  Rgb colour{0.85, 0.1, 0.1};
  std::string label;  // drawn next to the tip if not empty, e.g. "F = 1.2 N"
};

// Per-body data shown in the overlay.
struct TrackedBody {
  std::string label;                // e.g. "exact"
  Rgb colour{0.0, 0.0, 0.0};        // swatch colour, usually the body colour
  std::optional<double> slipRatio;  // v/(R omega) [-]
  std::optional<Vec3> w;            // slip direction (unit vector), Sect. 3
  // Where the label is drawn: above the world point anchor if set, else just
  // above the image of Scene::bodies[body] if body >= 0, else nowhere.
  std::optional<Vec3> anchor;
  int body = -1;
};

// A small live chart in the bottom-right corner of the frame, e.g. v/(R omega)
// of each tracked body up to the current time (drawn with cairo).
struct ChartSeries {
  Rgb colour{0.0, 0.0, 0.0};
  std::vector<double> t;  // [s], increasing
  std::vector<double> y;  // same length; NaN leaves a gap
};
struct OverlayChart {
  std::string title;                // UTF-8, e.g. "v/(R\xcf\x89)"
  double tMin = 0.0, tMax = 1.0;    // horizontal range [s]
  double yMin = 0.0, yMax = 2.0;    // vertical range; the series are clipped to it
  std::optional<double> reference;  // dashed horizontal line, e.g. 0.653
  std::string referenceLabel;       // written at its right end
  std::vector<ChartSeries> series;
};

// Text drawn over the frame.
struct FrameOverlay {
  double time = 0.0;  // [s]
  std::string model;  // shown as "model: <model>"; omitted if empty
  std::string title;  // first line of the panel; omitted if empty
  std::vector<TrackedBody> tracked;
  std::string caption;                // bottom line; omitted if empty
  std::optional<OverlayChart> chart;  // bottom right; omitted if empty
};

// Pinhole camera.
struct Camera {
  Vec3 eye = Vec3(0.35, -0.45, 0.3);  // [m]
  Vec3 target = Vec3::Zero();         // [m]
  Vec3 up = Vec3::UnitZ();
  double fovYDeg = 35.0;  // vertical field of view [deg]
};

struct Scene {
  std::vector<SceneBody> bodies;
  std::vector<SceneMesh> meshes;
  std::vector<Trail> trails;
  std::vector<Arrow> arrows;
  FrameOverlay overlay;
  Camera camera;
};

// A camera looking at the bounding sphere of the bodies (and margin * its
// radius around it) from the given azimuth (from +x towards +y) and elevation
// above the ground, so that everything fits a frame of the given aspect ratio.
Camera fitCamera(const std::vector<SceneBody>& bodies, double azimuthDeg, double elevationDeg,
                 double aspect, double margin = 1.3, double fovYDeg = 35.0);

// Centre and radius of a sphere around all bodies [m].
void boundingSphere(const std::vector<SceneBody>& bodies, Vec3& centre, double& radius);

}  // namespace patchspin::render
