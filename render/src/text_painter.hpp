// Text over a rendered frame, through cairo with FreeType-loaded TrueType fonts.
#pragma once

#include <patchspin/render/image.hpp>
#include <patchspin/render/scene.hpp>
#include <string>
#include <vector>

namespace patchspin::render::internal {

// A label at a pixel position (e.g. a projected world point).
struct ScreenLabel {
  double x = 0.0, y = 0.0;  // [px], top-left origin
  std::string text;
  Rgb colour{0.1, 0.1, 0.1};
  bool above = true;  // centred above the point (else left-aligned to its right)
};

class TextPainter {
 public:
  // Throws RenderError if a font file cannot be loaded.
  TextPainter(const std::string& fontFile, const std::string& monoFontFile);
  ~TextPainter();
  TextPainter(const TextPainter&) = delete;
  TextPainter& operator=(const TextPainter&) = delete;

  // Draws the info panel (top left), the labels and the caption onto image.
  void draw(Image& image, const FrameOverlay& overlay, const std::vector<ScreenLabel>& labels,
            double fontPx) const;

 private:
  void* sans_ = nullptr;  // cairo_font_face_t*
  void* mono_ = nullptr;
};

}  // namespace patchspin::render::internal
