// Plots as PNG through gnuplot (Debian gnuplot-nox, pngcairo terminal).
//
// Each function writes a self-contained gnuplot script <png without .png>.gp
// (data inline as datablocks, so `gnuplot file.gp` redraws it) and runs
// gnuplot on it as a subprocess. Throws RenderError with gnuplot's message if
// it fails, and a clear "install gnuplot-nox" message if it is missing.
//
// CSV inputs: a header row naming the columns (any order, extra columns
// ignored, names case-sensitive), comma separated, fields may be in double
// quotes ("" inside is a quote); blank lines and lines starting with '#' are
// skipped.
#pragma once

#include <optional>
#include <patchspin/render/scene.hpp>
#include <string>
#include <vector>

namespace patchspin::render {

struct PlotOptions {
  int width = 1000;  // [px]
  int height = 700;  // [px]
  std::string title;
  std::string gnuplot;   // program to run; empty = the one found at configure time
  double fontSize = 11;  // [pt]
};

// ---- (a) slip direction w(t) on the unit sphere (Fig. 9, 10, 12, 13) -------

// Limit direction types, Sect. 3 (Eq. (31)-(34)): the time direction in which
// trajectories reach the discontinuity (attracting/repelling) and whether
// almost all, one, or a one-parameter set of them do (dominant / isolated /
// saddle-type); nonhyperbolic when the linearisation does not decide
// (patchspin::LimitType).
enum class Stability { Attracting, Repelling };
enum class LimitKind { Dominant, Isolated, Saddle, Nonhyperbolic };

struct LimitDirection {
  Vec3 w = Vec3::UnitZ();  // unit vector (normalised if not)
  Stability stability = Stability::Attracting;
  LimitKind kind = LimitKind::Dominant;
  std::string label;  // drawn next to the marker, e.g. "w1"; optional
};

struct SpherePath {
  std::string label;    // key entry
  std::vector<Vec3> w;  // points of w(t) in time order (normalised if not)
};

struct SpherePlot {
  std::vector<SpherePath> paths;
  std::vector<LimitDirection> limits;
  // orthographic view from the direction (cos e cos a, cos e sin a, sin e)
  double azimuthDeg = 30.0;
  double elevationDeg = 20.0;
  std::string axisNames[3] = {"w_1", "w_2", "w_3"};  // gnuplot enhanced text
};

// Paths: solid on the visible hemisphere, dashed behind; a small circle marks
// the start, a cross the end. Limit directions: blue attracting, red
// repelling; filled circle dominant, open circle isolated, triangle saddle,
// open diamond nonhyperbolic; paler when behind the sphere.
void plotSlipSphere(const SpherePlot& plot, const std::string& pngPath,
                    const PlotOptions& options = PlotOptions());

// ---- (b) v/(R omega) and r against time, several models together ---------

struct TimeSeries {
  std::string label;              // e.g. "exact"
  std::vector<double> t;          // [s]
  std::vector<double> slipRatio;  // v/(R omega) [-]; NaN where undefined
  std::vector<double> r;          // slip magnitude |x_o| [m/s]
};

struct TimeSeriesPlot {
  std::vector<TimeSeries> series;
  // horizontal reference line on the ratio panel; 0.653 is the stopping ratio
  // of a force-free, uniformly pressed thin disk under the exact law quoted in
  // DESIGN.md (Farkas et al. 2003); set another value or none
  std::optional<double> referenceRatio = 0.653;
  std::string referenceLabel = "0.653";
  std::optional<double> ratioMax;  // upper end of the ratio axis; auto if empty
  bool logR = false;               // logarithmic r axis (points with r <= 0 dropped)
};

// Two panels stacked: v/(R omega)(t) on top, r(t) below.
void plotSlipRatio(const TimeSeriesPlot& plot, const std::string& pngPath,
                   const PlotOptions& options = PlotOptions());

// ---- (c) bifurcation diagrams of limit directions (Fig. 11, 13) ------------

// Input: the CSV of `patchspin sweep --out FILE`, one file per model, one row
// per parameter point. Columns used:
//   F, T        the load parameters (in the sweep's units)
//   directions  "w1 w2 w3 rdot attracting|repelling type|..." , one entry per
//               limit direction, type dominant|isolated|saddle|nonhyperbolic
//   tipping     optional, 1 if the pressure turns negative (marked in the
//               (F, T) categories)
//   cycles      optional, the limit cycles: "attracting|repelling period
//               multiplier turn w1min w1max w2min w2max w3min w3max angle_min
//               angle_max|..." (ranges over the orbit, angle = atan2(w3, w1)
//               [deg]); the F diagram draws each as a bar over its range,
//               the (F, T) categories count them ("+ 2 A-cyc")
// Example row:  0.5,0,2,...,0,1,"1 0 0 -2.1 attracting dominant|-1 0 0 -4.9 attracting isolated"
struct SweepPanel {
  std::string title;    // panel title, e.g. "ellipsoidal"
  std::string csvPath;  // the sweep's CSV
};

struct BifurcationOptions {
  // what the F diagram plots for each direction: 0 = the angle atan2(w3, w1)
  // [deg] (separates the directions near the invariant circle w2 = 0 of
  // Sect. 6.1-6.3), or the component w1, w2 or w3 (1, 2, 3)
  int component = 0;
  std::optional<double> torque;  // F diagram: rows with this T (default: smallest |T|)
  std::string forceLabel = "F";  // axis titles (gnuplot enhanced text)
  std::string torqueLabel = "T";
};

// Limit directions against F (angle or component, see above), styled by type
// as in plotSlipSphere, and limit cycles as bars over their range (pale,
// coloured by stability). One panel per sweep, side by side.
void plotBifurcationForce(const std::vector<SweepPanel>& panels, const std::string& pngPath,
                          const BifurcationOptions& bifurcation = BifurcationOptions(),
                          const PlotOptions& options = PlotOptions());

// Over the (F, T) plane: each grid point coloured by the number and types of
// its limit directions (e.g. "4: 2 A-dom, 1 A-iso, 1 A-sad"), tiles sized from the
// grid spacing; colours agree across panels. One panel per sweep, side by side.
void plotBifurcationPlane(const std::vector<SweepPanel>& panels, const std::string& pngPath,
                          const BifurcationOptions& bifurcation = BifurcationOptions(),
                          const PlotOptions& options = PlotOptions());

// ---- (d) time against error (Pareto) ---------------------------------------

// CSV, one row per measured configuration:
//   model,time,error[,label]
//   model  free text; one colour per model, its rows joined in file order
//   time   cost, e.g. seconds per evaluation or per step (> 0, log axis)
//   error  error against the reference (> 0, log axis)
//   label  optional annotation next to the point
// Example:  exact-gl8,2.1e-7,3.0e-9,8 nodes
struct ParetoOptions {
  std::string timeLabel = "time per evaluation [s]";
  std::string errorLabel = "relative error";
};

void plotPareto(const std::string& csvPath, const std::string& pngPath,
                const ParetoOptions& pareto = ParetoOptions(),
                const PlotOptions& options = PlotOptions());

// ---- (e) ground tracks: where bodies slid, seen from above ---------------------

struct GroundTrack {
  std::string label;         // key entry
  std::vector<Vec2> points;  // positions in time order [m]
  bool dashed = false;       // thinner and dashed, drawn over the solid ones
  std::string colour;        // "#rrggbb"; empty: the palette's colour of its index
};

struct GroundTrackPlot {
  std::vector<GroundTrack> tracks;
  std::string xLabel = "x [m]", yLabel = "y [m]";  // gnuplot enhanced text
  // true: both axes to the same scale; false: each axis fitted to the data
  // (shows a sideways drift much smaller than the travel)
  bool equalAxes = false;
};

// The tracks as lines in the plane; a small circle marks each start, a cross
// each end.
void plotGroundTracks(const GroundTrackPlot& plot, const std::string& pngPath,
                      const PlotOptions& options = PlotOptions());

// ---- CSV readers for scripts (same CSV rules as above) ----------------------

// label,t,slipRatio,r  -> one TimeSeries per label (first-appearance order);
// slipRatio may be "nan" where undefined.
std::vector<TimeSeries> readTimeSeriesCsv(const std::string& csvPath);

// label,w1,w2,w3  -> one SpherePath per label, points in file order.
std::vector<SpherePath> readSpherePathsCsv(const std::string& csvPath);

// w1,w2,w3,stability,kind[,label] -> limit directions (stability attracting |
// repelling, kind dominant | isolated | saddle | nonhyperbolic).
std::vector<LimitDirection> readLimitDirectionsCsv(const std::string& csvPath);

}  // namespace patchspin::render
