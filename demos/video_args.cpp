// The frame-writing demos' run options (video_args.hpp).
#include "video_args.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace patchspin::demos {

std::string withDefault(const std::string& text, double value, const std::string& note) {
  char number[32];
  std::snprintf(number, sizeof number, "%g", value);
  return withDefault(text, std::string(number), note);
}

std::string withDefault(const std::string& text, const std::string& value,
                        const std::string& note) {
  return text + " (default " + value + note + ")";
}

void addFrameOptions(CLI::App& app, VideoArgs& a, const std::string& outHelp,
                     const std::string& framesHelp) {
  app.add_option("--out", a.out, outHelp);
  app.add_option("--frames", a.frames, withDefault(framesHelp, a.frames));
  app.add_option("--fps", a.fps, withDefault("frames per second of the video", a.fps));
  app.add_option("--size", a.size, withDefault("frame size WxH [px]", a.size));
}

void addRateOption(CLI::App& app, VideoArgs& a, const std::string& note) {
  app.add_option("--rate", a.rate, withDefault("simulation steps per second", a.rate, note));
}

void addSlowmoOption(CLI::App& app, VideoArgs& a) {
  app.add_option("--slowmo", a.slowmo, withDefault("video seconds per simulated second", a.slowmo));
}

void addTimeOptions(CLI::App& app, VideoArgs& a, const std::string& rateNote) {
  addRateOption(app, a, rateNote);
  addSlowmoOption(app, a);
  app.add_option("--t-max", a.tMax,
                 withDefault("simulate at least this long for summary.json [s]", a.tMax));
}

void addOutputFlags(CLI::App& app, VideoArgs& a, const std::string& plotted) {
  if (!plotted.empty())
    app.add_flag_callback(
        "--no-plot", [&a] { a.plot = false; }, "skip " + plotted + " (needs gnuplot)");
  app.add_flag_callback(
      "--quiet", [&a] { a.progress = false; }, "no progress bar");
}

void parseSize(const std::string& size, int& width, int& height) {
  const auto x = size.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument(size);
    std::size_t used = 0;
    width = std::stoi(size.substr(0, x), &used);
    if (used != x) throw std::invalid_argument(size);
    height = std::stoi(size.substr(x + 1), &used);
    if (used != size.size() - x - 1) throw std::invalid_argument(size);
  } catch (const std::exception&) {
    throw CLI::ValidationError("--size", "must be WxH, e.g. 960x540: got '" + size + "'");
  }
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw CLI::ValidationError("--size", "width and height must lie in [16, 8192]");
}

TimeBase timeBase(const VideoArgs& a) {
  TimeBase t;
  t.dt = 1.0 / a.rate;
  t.k = std::max(1, int(std::lround(a.rate / (a.fps * a.slowmo))));
  t.frameSteps = long(a.frames - 1) * t.k;
  t.steps = std::max(t.frameSteps, long(std::ceil(a.tMax / t.dt - 1e-9)));
  return t;
}

nlohmann::json videoSummary(const VideoArgs& a, const TimeBase& t) {
  int width = 0, height = 0;
  parseSize(a.size, width, height);
  return {{"frames", a.frames}, {"fps", a.fps},     {"steps_per_frame", t.k},
          {"width", width},     {"height", height}, {"t_last_frame", double(t.frameSteps) * t.dt}};
}

}  // namespace patchspin::demos
