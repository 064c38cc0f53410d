#include <png.h>

#include <cstdio>
#include <memory>
#include <patchspin/render/image.hpp>
#include <patchspin/render/scene.hpp>

namespace patchspin::render {

namespace {
struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;
}  // namespace

void writePng(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw RenderError("writePng: image buffer does not match its size " +
                      std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file) throw RenderError("writePng: cannot open " + path + " for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    throw RenderError("writePng: libpng initialisation failed");
  }
  // libpng reports errors by longjmp; only plain data live in this frame.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw RenderError("writePng: libpng failed writing " + path);
  }
  png_init_io(png, file.get());
  // one filter and a fast zlib level: frames are written often, size matters less
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_compression_level(png, 3);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, image.pixel(0, y));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(file.get()) != 0) throw RenderError("writePng: cannot write " + path);
}

Image readPng(const std::string& path) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) {
    throw RenderError("readPng: cannot read " + path + ": " + img.message);
  }
  img.format = PNG_FORMAT_RGB;
  Image out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.rgb.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr)) {
    std::string message = img.message;
    png_image_free(&img);
    throw RenderError("readPng: cannot decode " + path + ": " + message);
  }
  return out;
}

double pixelVariance(const Image& image) {
  if (image.rgb.empty()) return 0.0;
  double sum = 0.0, sum2 = 0.0;
  for (std::uint8_t v : image.rgb) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  const double n = static_cast<double>(image.rgb.size());
  const double mean = sum / n;
  return sum2 / n - mean * mean;
}

}  // namespace patchspin::render
