#include "osmesa_context.hpp"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <patchspin/render/scene.hpp>
#include <string>

namespace patchspin::render::internal {

OsmesaContext::OsmesaContext(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    throw RenderError("OSMesa buffer size must be positive: got " + std::to_string(width) + "x" +
                      std::to_string(height));
  }
  // RGBA, 24-bit depth, 8-bit stencil (planar shadows), no accumulation buffer.
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!ctx) throw RenderError("OSMesaCreateContextExt failed (is libosmesa6 installed?)");
  context_ = ctx;
  buffer_.assign(static_cast<std::size_t>(width) * height * 4, 0);
}

OsmesaContext::~OsmesaContext() {
  if (context_) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OsmesaContext::makeCurrent() {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE,
                         width_, height_)) {
    throw RenderError("OSMesaMakeCurrent failed for a " + std::to_string(width_) + "x" +
                      std::to_string(height_) + " buffer");
  }
  // Row 0 of the buffer is the top of the image.
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

const std::vector<std::uint8_t>& OsmesaContext::finish() {
  glFinish();
  return buffer_;
}

}  // namespace patchspin::render::internal
