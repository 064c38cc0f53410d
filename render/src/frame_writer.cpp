// Numbered PNG frames and the ffmpeg command that joins them (renderer.hpp).
#include <patchspin/render/renderer.hpp>

#include <cstdio>
#include <filesystem>

namespace patchspin::render {

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
