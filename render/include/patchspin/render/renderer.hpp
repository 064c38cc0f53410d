// Off-screen renderer: draws a Scene with legacy OpenGL through OSMesa (software,
// no display, no GPU), puts the text overlay on with cairo + FreeType, and
// returns an Image; FrameWriter writes numbered PNG frames.
//
// Same inputs give byte-identical frames (OSMesa's software rasteriser is
// deterministic and the PNG writer stores no time stamps).
#pragma once

#include <memory>
#include <patchspin/render/image.hpp>
#include <patchspin/render/scene.hpp>
#include <string>

namespace patchspin::render {

struct RenderOptions {
  int width = 960;  // output size [px]
  int height = 540;
  // The scene is drawn at supersample x the size and box-filtered down
  // (anti-aliasing; OSMesa has no multisampling).
  int supersample = 2;
  double groundHeight = 0.0;  // ground plane z [m]
  double gridSpacing = 0.0;   // [m]; 0 picks a 1-2-5 step from the camera distance
  bool shadows = true;        // planar shadows of the bodies on the ground
  Vec3 lightDirection = Vec3(-0.35, -0.5, 1.0);  // towards the light (need not be unit)
  Rgb skyTop{0.56, 0.68, 0.82};
  Rgb skyHorizon{0.90, 0.92, 0.95};
  Rgb ground{0.80, 0.80, 0.78};
  // TrueType fonts (FreeType); the defaults are the DejaVu fonts found at
  // configure time (Debian fonts-dejavu-core).
  std::string fontFile;      // proportional, for labels
  std::string monoFontFile;  // monospaced, for numbers
  double fontScale = 1.0;    // text size relative to the default (height / 36)
};

class Renderer {
 public:
  // Creates the OSMesa context and loads the fonts; throws RenderError.
  explicit Renderer(const RenderOptions& options = RenderOptions());
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  Image render(const Scene& scene);
  const RenderOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes <directory>/<prefix>00000.png, <prefix>00001.png, ... (digits wide),
// creating the directory if needed. Frame i shows time i / fps.
class FrameWriter {
 public:
  explicit FrameWriter(std::string directory, double fps = 30.0, std::string prefix = "frame_",
                       int digits = 5);
  // Writes the next frame and returns its path.
  std::string write(const Image& image);
  // Path of frame number index (whether or not it exists yet).
  std::string framePath(int index) const;
  int count() const { return count_; }
  double fps() const { return fps_; }
  // Time shown by frame number index [s].
  double frameTime(int index) const { return index / fps_; }
  // Shell command that turns the frames into a video (.mp4) or an animated
  // .gif with ffmpeg, e.g. for the README.
  std::string ffmpegCommand(const std::string& output) const;

 private:
  std::string directory_;
  double fps_;
  std::string prefix_;
  int digits_;
  int count_ = 0;
};

}  // namespace patchspin::render
