// Shared machinery of the scene demos (pushed_disk, thick_disk, disk_torque;
// issue 5): each body runs through patchspin::scenes::simulate itself (with
// its trajectory kept), so the physics and the summary are exactly those of
// `patchspin simulate --engine bullet`. Frames are drawn from the trajectory
// (patch centre and rotation psi about z; the body is drawn upright, tilt is
// not shown); after a stop the body is held at its stopping pose.
//
// Writes <out>/frame_NNNNN.png, <out>/summary.json and, per body,
// <out>/sphere_<key>.png: w(t) on the unit sphere with the limit directions of
// patchspin::findLimitDirections (patch models only) marked by type.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>

#include <patchspin/render/scene.hpp>
#include <patchspin/simulation.hpp>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace patchspin::demos {

// One body of a demo, in its own Bullet world, drawn side by side.
struct DemoBody {
  std::string key;    // summary.json key and plot file suffix, e.g. "case2"
  std::string label;  // overlay text
  render::Rgb colour{0.9, 0.6, 0.15};
  SimulationSpec spec;  // cylinder; force along +x keeps w in the analysis frame
};

// Options shared by every demo.
struct CommonArgs {
  std::string out;
  int frames = 120;
  double fps = 30.0;
  std::string size = "960x540";
  std::string model = "exact";
  double rate = 240.0;  // simulation steps per simulated second
  double slowmo = 2.0;  // video seconds per simulated second
  double tMax = 3.0;    // simulated time limit [s]
  bool plot = true;
  bool progress = true;
};

struct DemoConfig {
  std::string name;     // program name, e.g. "pushed_disk"
  std::string title;    // overlay title
  std::string caption;  // overlay caption
  std::vector<DemoBody> bodies;
  double forceArrowScale = 0.0;  // metres per newton of the force arrows; 0: automatic
};

// Adds --out, --frames, --fps, --size, --model, --rate, --slowmo, --t-max,
// --no-plot and --quiet; call finishCommonArgs after parsing.
void addCommonOptions(CLI::App& app, CommonArgs& args, bool* noPlot, bool* quiet);

// Checks the common arguments; throws CLI::ValidationError.
void validateCommonArgs(const CommonArgs& args);

// Runs, renders and writes everything; returns the exit code.
int runDemo(const DemoConfig& config, const CommonArgs& args);

// "WxH" -> width, height in [16, 8192]; throws CLI::ValidationError.
void parseSize(const std::string& size, int& width, int& height);

// Progress bar "<name>: [###   ] done/total frames" on stderr: redrawn in
// place on a terminal, else a line per 10 %.
void printProgress(const std::string& name, int done, int total);

// A finite number, or JSON null.
nlohmann::json jsonOrNull(double value);

// Parses the command line and calls `run`, turning errors into one line on
// stderr ("<name>: error: ...") and an exit code, as every demo does.
int runMain(CLI::App& app, int argc, char** argv, const char* name,
            const std::function<int()>& run);

}  // namespace patchspin::demos
