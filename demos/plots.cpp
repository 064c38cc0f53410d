// plots: command-line driver for the gnuplot plots of patchspin::render
// (plot.hpp) that no other command reaches -- the bifurcation diagrams from
// `patchspin sweep` CSVs (Fig. 11 and Fig. 13 analogues) and the time-against-
// error (Pareto) plot. Used by scripts/make_gallery.sh.
//
//   plots force  --panel TITLE=CSV [--panel ...] --out PNG [--component 0..3] [--torque T]
//   plots plane  --panel TITLE=CSV [--panel ...] --out PNG
//   plots pareto --csv CSV --out PNG [--time-label S] [--error-label S]
//
// Every subcommand takes --size WxH (default 900x600) and --title. Each PNG
// gets its gnuplot script next to it (<png without .png>.gp).
#include <patchspin/render/plot.hpp>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace render = patchspin::render;

// "TITLE=CSV" -> panel; a bare path gets its file name as title
render::SweepPanel parsePanel(const std::string& text) {
  render::SweepPanel panel;
  const auto eq = text.find('=');
  if (eq == std::string::npos) {
    panel.csvPath = text;
    const auto slash = text.find_last_of('/');
    panel.title = slash == std::string::npos ? text : text.substr(slash + 1);
  } else {
    panel.title = text.substr(0, eq);
    panel.csvPath = text.substr(eq + 1);
  }
  if (panel.csvPath.empty()) throw std::invalid_argument("--panel needs TITLE=CSV, got '" + text + "'");
  return panel;
}

// "900x600" -> width, height
void parseSize(const std::string& text, render::PlotOptions& options) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 100 || h < 100)
    throw std::invalid_argument("--size needs WxH with W, H >= 100, got '" + text + "'");
  options.width = w;
  options.height = h;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"plots: bifurcation diagrams from `patchspin sweep` CSVs and time-against-error plots (gnuplot PNG)"};
  app.require_subcommand(1);

  std::string size = "900x600", title, out;
  std::vector<std::string> panels;
  int component = 0;
  std::optional<double> torque;
  std::string forceLabel = "F", torqueLabel = "T";

  auto addCommon = [&](CLI::App* sub) {
    sub->add_option("--out", out, "PNG file to write")->required();
    sub->add_option("--size", size, "image size WxH [px] (default 900x600)");
    sub->add_option("--title", title, "plot title (gnuplot enhanced text)");
  };
  auto addSweep = [&](CLI::App* sub) {
    sub->add_option("--panel", panels, "TITLE=CSV of `patchspin sweep --out`, one per panel, left to right")
        ->required();
    sub->add_option("--force-label", forceLabel, "F axis title (default F)");
    sub->add_option("--torque-label", torqueLabel, "T axis title (default T)");
  };

  CLI::App* force = app.add_subcommand("force", "limit directions against F (Fig. 11), one panel per sweep");
  addCommon(force);
  addSweep(force);
  force->add_option("--component", component, "0: angle atan2(w3, w1) [deg] (default); 1, 2, 3: w1, w2, w3")
      ->check(CLI::Range(0, 3));
  force->add_option("--torque", torque, "use the rows with this T (default: smallest |T|)");

  CLI::App* plane = app.add_subcommand("plane", "number and types of limit directions over (F, T) (Fig. 13)");
  addCommon(plane);
  addSweep(plane);

  std::string csv;
  render::ParetoOptions pareto;
  CLI::App* paretoCmd = app.add_subcommand("pareto", "time against error, CSV model,time,error[,label]");
  addCommon(paretoCmd);
  paretoCmd->add_option("--csv", csv, "input CSV")->required();
  paretoCmd->add_option("--time-label", pareto.timeLabel, "x axis title");
  paretoCmd->add_option("--error-label", pareto.errorLabel, "y axis title");

  CLI11_PARSE(app, argc, argv);

  try {
    render::PlotOptions options;
    parseSize(size, options);
    options.title = title;
    if (*paretoCmd) {
      render::plotPareto(csv, out, pareto, options);
    } else {
      std::vector<render::SweepPanel> sweepPanels;
      for (const auto& p : panels) sweepPanels.push_back(parsePanel(p));
      render::BifurcationOptions bifurcation;
      bifurcation.component = component;
      bifurcation.torque = torque;
      bifurcation.forceLabel = forceLabel;
      bifurcation.torqueLabel = torqueLabel;
      if (*force)
        render::plotBifurcationForce(sweepPanels, out, bifurcation, options);
      else
        render::plotBifurcationPlane(sweepPanels, out, bifurcation, options);
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "plots: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plots: error: %s\n", e.what());
    return 1;
  }
  std::printf("plots: wrote %s\n", out.c_str());
  return 0;
}
