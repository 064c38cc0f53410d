// Shared machinery of the scene demos (pushed_disk, thick_disk, disk_torque,
// curling; issue 5; their disk parameters: disk_args.hpp): each body runs through
// patchspin::scenes::simulate itself (with its trajectory kept), so the physics and the summary are
// exactly those of `patchspin simulate --engine bullet`. Frames are drawn from the trajectory
// (patch centre and rotation psi about z; the body is drawn upright, tilt is
// not shown); after a stop the body is held at its stopping pose.
//
// Writes <out>/frame_NNNNN.png, <out>/summary.json and, per body,
// <out>/sphere_<key>.png: w(t) on the unit sphere with the limit directions of
// patchspin::findLimitDirections (patch models only) marked by type; with
// DemoConfig::trackPlot also <out>/track.png.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>

#include <patchspin/render/scene.hpp>
#include <patchspin/simulation.hpp>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "video_args.hpp"

class btRigidBody;

namespace patchspin::demos {

// One body of a demo, in its own Bullet world, drawn side by side.
struct DemoBody {
  std::string key;    // summary.json key and plot file suffix, e.g. "case2"
  std::string label;  // overlay text
  render::Rgb colour{0.9, 0.6, 0.15};
  SimulationSpec spec;  // cylinder; force along +x keeps w in the analysis frame
};

// Options shared by the scene demos: the run options (video_args.hpp) with
// their defaults, and the friction model.
struct CommonArgs : VideoArgs {
  CommonArgs() {
    frames = 120;
    slowmo = 2.0;
  }
  std::string model = "exact";
};

struct DemoConfig {
  std::string name;     // program name, e.g. "pushed_disk"
  std::string title;    // overlay title
  std::string caption;  // overlay caption
  std::vector<DemoBody> bodies;
  double forceArrowScale = 0.0;  // metres per newton of the force arrows; 0: automatic
  // also write <out>/track.png: every body's ground track from its start, with
  // the reference dynamics (Eq. (93)) of each patch-law body dashed beside it
  bool trackPlot = false;
};

// Adds --out, --frames, --fps, --size, --model, --rate, --slowmo, --t-max,
// --no-plot and --quiet; call finishCommonArgs after parsing.
void addCommonOptions(CLI::App& app, CommonArgs& args, bool* noPlot, bool* quiet);

// Checks the common arguments; throws CLI::ValidationError.
void validateCommonArgs(const CommonArgs& args);

// Runs, renders and writes everything; returns the exit code.
int runDemo(const DemoConfig& config, const CommonArgs& args);

// Camera from the given azimuth and elevation (as render::fitCamera) that
// fits `points` into the frame window x_ndc in [-kFitX, kFitX], y_ndc in
// [kFitBottom, fitTop] (the overlay panel covers the top): the distance by
// bisection, the target shifted along the camera's up vector so that the
// scene is centred in the window (wide, flat scenes: a bounding sphere would
// waste most of the frame). Used by blocks and terrain.
constexpr double kFitX = 0.94, kFitBottom = -0.86;
render::Camera fitSceneCamera(const std::vector<Vec3>& points, double azimuthDeg,
                              double elevationDeg, double aspect, double fitTop,
                              double fovYDeg = 35.0);
// Appends the corners of the drawn body (its bounding box) in the world.
void addCorners(const render::SceneBody& b, std::vector<Vec3>& out);
// Colour of a law's row or body: exact warm, ellipsoidal blue, stock grey.
render::Rgb rowColour(const std::string& model);

// Every triangle of a static triangle mesh or heightfield body (any
// btConcaveShape), in world coordinates, for drawing; throws Error for
// another shape.
render::SceneMesh concaveMesh(const btRigidBody& body);

// Progress bar "<name>: [###   ] done/total frames" on stderr: redrawn in
// place on a terminal, else a line per 10 %.
void printProgress(const std::string& name, int done, int total);

// A finite number, or JSON null.
nlohmann::json jsonOrNull(double value);

// Runs `plot`; if it throws render::RenderError (no gnuplot, a failed plot),
// prints "<name>: warning: no plot: <what>" on stderr and goes on: the plots
// are optional, the frames and summary.json are not.
void plotOrWarn(const std::string& name, const std::function<void()>& plot);

// Writes `json` to `path` (2-space indent, newline at the end); throws
// render::RenderError if it cannot.
void writeJson(const std::filesystem::path& path, const nlohmann::json& json);

// The items of the comma list `text`, in order, each one of `allowed` and
// none twice; else throws CLI::ValidationError(option, ...): "'<item>' is not
// one of <allowed>", "lists <item> twice", "names nothing".
std::vector<std::string> splitList(const std::string& text, const std::string& option,
                                   const std::vector<std::string>& allowed);
// --model of blocks and terrain: a comma list of exact, ellipsoidal, stock
// (as splitList, said in terms of models).
std::vector<std::string> lawList(const std::string& text);

// Parses the command line and calls `run`, turning errors into one line on
// stderr ("<name>: error: ...") and an exit code, as every demo does.
int runMain(CLI::App& app, int argc, char** argv, const char* name,
            const std::function<int()>& run);

}  // namespace patchspin::demos
