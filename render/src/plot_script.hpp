// Internal to patchspin::render's plots: writing and running gnuplot
// scripts, the colours shared by the plots (plot_*.cpp).
#pragma once

#include <patchspin/render/plot.hpp>

#include <cstddef>
#include <sstream>
#include <string>

namespace patchspin::render::plotting {

constexpr double kPi = 3.14159265358979323846;

// distinct colours for paths and models (ColorBrewer Dark2), cycled
const char* paletteColour(std::size_t i);
// categorical colours for the (F, T) plane (ColorBrewer Set3-like, light)
extern const char* const kTiles[];
extern const std::size_t kTileColours;
extern const char* const kAttracting;
extern const char* const kRepelling;
extern const char* const kAttractingPale;
extern const char* const kRepellingPale;

// v with 10 significant digits, "NaN" if not finite
std::string num(double v);
// a gnuplot double-quoted string
std::string gpString(const std::string& s);
// script preamble: terminal, output, title handling; RenderError for a
// size below 16 x 16
std::string header(const std::string& pngPath, const PlotOptions& o);
// "set multiplot" for `panels` side by side, with the title
std::string multiplotHeader(std::size_t panels, const PlotOptions& o);
// an inline data block $name
void datablock(std::ostringstream& s, const std::string& name, const std::string& rows);
// Writes <png stem>.gp and runs gnuplot on it; gnuplot's stderr goes into
// the RenderError.
void runGnuplot(const std::string& script, const std::string& pngPath, const PlotOptions& o);

}  // namespace patchspin::render::plotting
