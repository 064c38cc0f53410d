// The frame-writing demos' run options (blocks, coin, terrain, grasp; and,
// through CommonArgs, the scene demos): where the frames go, how many and how
// large, the simulation's time base, and the --no-plot and --quiet flags.
// The help of every option here that takes a value, --out aside, ends in
// "(default <value>)" with the value as the demo set it before adding the
// option, so the help shows the default actually used. The demos' tests
// (tests/render/*demo_test.cpp) run the demos through these options.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

namespace patchspin::demos {

struct VideoArgs {
  std::string out;               // output directory
  int frames = 150;              // number of frames
  double fps = 30.0;             // frames per second of the video
  std::string size = "960x540";  // frame size WxH [px]
  double rate = 240.0;           // simulation steps per simulated second
  double slowmo = 4.0;           // video seconds per simulated second
  double tMax = 3.0;             // simulated at least this long [s]
  bool plot = true;              // false: --no-plot
  bool progress = true;          // false: --quiet
};

// "<text> (default <value><note>)", the value as %g (a number) or as is
// (text).
std::string withDefault(const std::string& text, double value, const std::string& note = "");
std::string withDefault(const std::string& text, const std::string& value,
                        const std::string& note = "");

// --out (help `outHelp` as given), --frames (help `framesHelp` and the
// default), --fps, --size.
void addFrameOptions(CLI::App& app, VideoArgs& a, const std::string& outHelp,
                     const std::string& framesHelp = "number of frames");
// --rate, its default followed by `note` (e.g. "; 480 also sensible").
void addRateOption(CLI::App& app, VideoArgs& a, const std::string& note = "");
// --slowmo.
void addSlowmoOption(CLI::App& app, VideoArgs& a);
// --rate (as addRateOption), --slowmo, --t-max.
void addTimeOptions(CLI::App& app, VideoArgs& a, const std::string& rateNote = "");
// --no-plot ("skip <plotted> (needs gnuplot)"; none if `plotted` is empty)
// and --quiet; they clear a.plot and a.progress.
void addOutputFlags(CLI::App& app, VideoArgs& a, const std::string& plotted);

// --size: "WxH" -> width, height in [16, 8192]; throws CLI::ValidationError.
void parseSize(const std::string& size, int& width, int& height);

// The time base of a run: steps of dt = 1/rate, a frame every k steps so that
// the video at fps runs slowmo times slower than the simulation; the last
// frame at step frameSteps; the run `steps` long, to the last frame and for
// at least tMax.
struct TimeBase {
  double dt = 0.0;
  int k = 1;
  long frameSteps = 0;
  long steps = 0;
};
TimeBase timeBase(const VideoArgs& a);

// summary.json's "video": frames, fps, steps_per_frame (k), width, height
// and t_last_frame, the simulated time of the last frame [s].
nlohmann::json videoSummary(const VideoArgs& a, const TimeBase& t);

}  // namespace patchspin::demos
