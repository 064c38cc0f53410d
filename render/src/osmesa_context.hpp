// The one owner of an OSMesa context: nothing else in patchspin touches OSMesa.
#pragma once

#include <cstdint>
#include <vector>

namespace patchspin::render::internal {

// An off-screen RGBA colour buffer with 24-bit depth and 8-bit stencil,
// rendered by Mesa's software rasteriser.
class OsmesaContext {
 public:
  // Throws RenderError if OSMesa cannot create the context.
  OsmesaContext(int width, int height);
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  // Binds the context and its buffer to this thread (call before any GL).
  void makeCurrent();
  // Finishes all GL work; the buffer is RGBA, top row first.
  const std::vector<std::uint8_t>& finish();

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void* context_ = nullptr;  // OSMesaContext, kept opaque to keep osmesa.h out of the header
  int width_;
  int height_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace patchspin::render::internal
