// 8-bit RGB images and their PNG files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace patchspin::render {

// Row-major, top row first, 3 bytes (R, G, B) per pixel.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  std::uint8_t* pixel(int x, int y) {
    return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
  }
  const std::uint8_t* pixel(int x, int y) const {
    return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
  }
};

// Writes an 8-bit RGB PNG with libpng. No time or text chunks and fixed
// compression settings, so equal images give byte-identical files.
// Throws RenderError if the file cannot be written.
void writePng(const Image& image, const std::string& path);

// Reads any PNG (palette, grey, alpha and 16-bit are converted; alpha is
// dropped). Throws RenderError if the file is missing or not a PNG.
Image readPng(const std::string& path);

// Population variance of all channel values, a "not blank" measure [0, 65025/4].
double pixelVariance(const Image& image);

}  // namespace patchspin::render
