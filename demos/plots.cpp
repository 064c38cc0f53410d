// plots: command-line driver for the gnuplot plots of patchspin::render
// (plot.hpp) that no other command reaches -- the bifurcation diagrams from
// `patchspin sweep` CSVs (Fig. 11 and Fig. 13 analogues) and the time-against-
// error (Pareto) plot. Used by scripts/make_gallery.sh.
//
//   plots force  --panel TITLE=CSV [--panel ...] --out PNG [--component 0..3] [--torque T]
//   plots plane  --panel TITLE=CSV [--panel ...] --out PNG
//   plots pareto --csv CSV --out PNG [--time-label S] [--error-label S]
//   plots pareto-patch --csv docs/bench/patch_error.csv --out PNG [--level block|law]
//                      [--statistic median|rms|max]
//   plots pareto-sim --csv docs/bench/simulation_error.csv --scene NAME --out PNG
//                    [--metric combined|tstop|terminal]
//
// pareto-patch and pareto-sim read the CSVs of bench_patch_error and
// bench_bullet_simulation (scripts/run_benchmarks.sh) and draw them through
// the same Pareto plot: per patch one series per model, points labelled by
// setting, the shapes pooled (the CSV and the benchmark's table have them
// one by one); per simulation one series per model, points labelled by time
// step. Rows whose error is 0 or missing (a run that did not
// stop, or an error below round-off) cannot sit on a log axis and are left
// out; the plot's title says how many.
//
// Every subcommand takes --size WxH (default 900x600) and --title. Each PNG
// gets its gnuplot script next to it (<png without .png>.gp).
#include <patchspin/render/plot.hpp>

#include <unistd.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
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
  if (panel.csvPath.empty())
    throw std::invalid_argument("--panel needs TITLE=CSV, got '" + text + "'");
  return panel;
}

// "900x600" -> width, height
void parseSize(const std::string& text, render::PlotOptions& options) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 100 ||
      h < 100)
    throw std::invalid_argument("--size needs WxH with W, H >= 100, got '" + text + "'");
  options.width = w;
  options.height = h;
}

// ---- benchmark CSVs (bench_patch_error, bench_bullet_simulation) -------------

// header + rows of a CSV with optional double quotes around fields
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw std::invalid_argument("CSV has no column '" + name + "'");
    return std::size_t(it - header.begin());
  }
  const std::string& at(std::size_t row, const std::string& name) const {
    const std::size_t c = column(name);
    static const std::string empty;
    return c < rows[row].size() ? rows[row][c] : empty;
  }
  // the field as a number; NaN when empty or not a number
  double number(std::size_t row, const std::string& name) const {
    const std::string& f = at(row, name);
    char* end = nullptr;
    const double x = std::strtod(f.c_str(), &end);
    return (f.empty() || end != f.c_str() + f.size()) ? NAN : x;
  }
};

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      out.emplace_back();
    else if (c != '\r')
      out.back() += c;
  }
  return out;
}

Table readTable(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  Table t;
  std::string line;
  if (!std::getline(f, line)) throw std::runtime_error(path + ": empty file");
  t.header = splitCsvLine(line);
  while (std::getline(f, line))
    if (!line.empty()) t.rows.push_back(splitCsvLine(line));
  return t;
}

// model,time,error,label rows for render::plotPareto, written to a temporary
// file that is removed when this object goes
struct ParetoCsv {
  std::filesystem::path path;
  std::ofstream out;
  int kept = 0, dropped = 0;
  explicit ParetoCsv(const std::string& tag)
      : path(std::filesystem::temp_directory_path() /
             ("patchspin_plots_" + tag + "_" + std::to_string(::getpid()) + ".csv")),
        out(path) {
    if (!out) throw std::runtime_error("cannot write " + path.string());
    out << "model,time,error,label\n";
  }
  ~ParetoCsv() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
  void add(const std::string& model, double time, double error, const std::string& label) {
    if (!(time > 0.0) || !(error > 0.0) || !std::isfinite(error)) {
      ++dropped;
      return;
    }
    ++kept;
    char line[512];
    std::snprintf(line, sizeof line, "\"%s\",%.6g,%.6g,\"%s\"\n", model.c_str(), time, error,
                  label.c_str());
    out << line;
  }
  std::string finish() {
    out.close();
    if (kept == 0) throw std::runtime_error("no row with a positive time and error to plot");
    return path.string();
  }
};

// per patch: one series per model (and start, for the block rows), one point
// per setting (its label), over
// all shapes: mean time, and the error statistic pooled over the shapes
// (rms: root of the mean square, the shapes having equal samples; max: the
// largest; median: the median of the shapes' medians)
void plotPatchPareto(const std::string& csv, const std::string& level, const std::string& statistic,
                     const std::string& out, render::PlotOptions options) {
  const Table t = readTable(csv);
  ParetoCsv pareto("patch");
  struct Point {
    std::string model, setting;
    std::vector<double> times, errors;
  };
  std::vector<Point> points;  // in order of first appearance
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    if (t.at(i, "level") != level) continue;
    // "cold, tol 1e-9" -> series "<model>, cold", label "tol 1e-9"
    std::string model = t.at(i, "model"), setting = t.at(i, "setting");
    if (const auto comma = setting.find(", "); comma != std::string::npos) {
      model += ", " + setting.substr(0, comma);
      setting = setting.substr(comma + 2);
    }
    auto it = std::find_if(points.begin(), points.end(), [&](const Point& p) {
      return p.model == model && p.setting == setting;
    });
    if (it == points.end()) it = points.insert(points.end(), Point{model, setting, {}, {}});
    it->times.push_back(1e-9 * t.number(i, "time_ns"));
    it->errors.push_back(t.number(i, "err_" + statistic));
  }
  std::vector<std::string> models;
  for (const Point& p : points)
    if (std::find(models.begin(), models.end(), p.model) == models.end()) models.push_back(p.model);
  // a label only where the point stands apart from every labelled one
  // (settings that change nothing would print on top of each other)
  std::vector<std::pair<double, double>> labelled;
  for (const std::string& model : models) {
    for (Point& p : points) {
      if (p.model != model) continue;
      double time = 0, error = 0;
      for (double x : p.times) time += x / double(p.times.size());
      if (statistic == "rms") {
        for (double e : p.errors) error += e * e / double(p.errors.size());
        error = std::sqrt(error);
      } else if (statistic == "max") {
        error = *std::max_element(p.errors.begin(), p.errors.end());
      } else {
        std::sort(p.errors.begin(), p.errors.end());
        error = p.errors[p.errors.size() / 2];
      }
      bool apart = true;
      for (const auto& [t0, e0] : labelled)
        apart = apart &&
                (std::abs(std::log10(time / t0)) > 0.2 || std::abs(std::log10(error / e0)) > 0.5);
      if (apart) labelled.emplace_back(time, error);
      pareto.add(model, time, error, p.setting == "-" || !apart ? "" : p.setting);
    }
  }
  const std::string data = pareto.finish();
  render::ParetoOptions p;
  p.timeLabel = level == "block" ? "CPU time per friction-block solve [s]"
                                 : "CPU time per law evaluation [s]";
  p.errorLabel = statistic + " relative error of the " + (level == "block" ? "impulse" : "wrench") +
                 " against the exact law";
  if (options.title.empty())
    options.title = std::string("per patch: time against error (") +
                    (level == "block" ? "friction block" : "law") +
                    "; disk, rectangle, hexagon pooled)";
  if (pareto.dropped)
    options.title += " (" + std::to_string(pareto.dropped) + " zero-error rows off the log axes)";
  render::plotPareto(data, out, p, options);
}

// per simulation: one series per model, one point per time step
void plotSimulationPareto(const std::string& csv, const std::string& scene,
                          const std::string& metric, const std::string& out,
                          render::PlotOptions options) {
  const Table t = readTable(csv);
  ParetoCsv pareto("sim");
  std::vector<std::string> series;
  std::map<std::string, std::vector<std::size_t>> rowsOf;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    if (t.at(i, "scene") != scene) continue;
    const std::string& model = t.at(i, "model");
    if (!rowsOf.count(model)) series.push_back(model);
    rowsOf[model].push_back(i);
  }
  if (series.empty()) throw std::invalid_argument("no rows of scene '" + scene + "' in " + csv);
  for (const std::string& model : series)
    for (std::size_t i : rowsOf[model]) {
      const double stop = t.number(i, "err_tstop"), terminal = t.number(i, "err_terminal");
      double e = metric == "tstop"      ? stop
                 : metric == "terminal" ? terminal
                                        : std::max(stop, terminal);
      if (metric == "combined" && (std::isnan(stop) || std::isnan(terminal)))
        e = NAN;  // did not stop
      pareto.add(model, t.number(i, "cpu_per_sim_s"), e, t.at(i, "dt"));
    }
  const std::string data = pareto.finish();
  render::ParetoOptions p;
  p.timeLabel = "CPU time per simulated second [s]";
  const bool ratio =
      !t.rows.empty() && t.at(rowsOf[series.front()].front(), "terminal_kind") == "ratio";
  const std::string terminalName =
      ratio ? "rel. error of terminal v/(R{/Symbol w})" : "|w - w_{ref}| at the end";
  p.errorLabel = metric == "tstop"      ? "relative error of the stopping time"
                 : metric == "terminal" ? terminalName
                                        : "max(rel. error of t_{stop}, " + terminalName + ")";
  if (options.title.empty())
    options.title = scene + ": error against the exact law's reference dynamics";
  if (pareto.dropped)
    options.title +=
        " (" + std::to_string(pareto.dropped) + " runs off the log axes: no stop or zero error)";
  render::plotPareto(data, out, p, options);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "plots: bifurcation diagrams from `patchspin sweep` CSVs and time-against-error plots "
      "(gnuplot PNG)"};
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
    sub->add_option("--panel", panels,
                    "TITLE=CSV of `patchspin sweep --out`, one per panel, left to right")
        ->required();
    sub->add_option("--force-label", forceLabel, "F axis title (default F)");
    sub->add_option("--torque-label", torqueLabel, "T axis title (default T)");
  };

  CLI::App* force =
      app.add_subcommand("force", "limit directions against F (Fig. 11), one panel per sweep");
  addCommon(force);
  addSweep(force);
  force
      ->add_option("--component", component,
                   "0: angle atan2(w3, w1) [deg] (default); 1, 2, 3: w1, w2, w3")
      ->check(CLI::Range(0, 3));
  force->add_option("--torque", torque, "use the rows with this T (default: smallest |T|)");

  CLI::App* plane =
      app.add_subcommand("plane", "number and types of limit directions over (F, T) (Fig. 13)");
  addCommon(plane);
  addSweep(plane);

  std::string csv;
  render::ParetoOptions pareto;
  CLI::App* paretoCmd =
      app.add_subcommand("pareto", "time against error, CSV model,time,error[,label]");
  addCommon(paretoCmd);
  paretoCmd->add_option("--csv", csv, "input CSV")->required();
  paretoCmd->add_option("--time-label", pareto.timeLabel, "x axis title");
  paretoCmd->add_option("--error-label", pareto.errorLabel, "y axis title");

  std::string level = "block", statistic = "rms", scene, metric = "combined";
  CLI::App* patchCmd = app.add_subcommand(
      "pareto-patch", "time against error per patch, from bench_patch_error's CSV");
  addCommon(patchCmd);
  patchCmd->add_option("--csv", csv, "docs/bench/patch_error.csv")->required();
  patchCmd
      ->add_option("--level", level,
                   "block (friction-block solve, default) or law (Q(w) evaluation)")
      ->check(CLI::IsMember({"block", "law"}));
  patchCmd
      ->add_option("--statistic", statistic, "error over the sample: median, rms (default) or max")
      ->check(CLI::IsMember({"median", "rms", "max"}));
  CLI::App* simCmd = app.add_subcommand(
      "pareto-sim", "time against error per simulation, from bench_bullet_simulation's CSV");
  addCommon(simCmd);
  simCmd->add_option("--csv", csv, "docs/bench/simulation_error.csv")->required();
  simCmd->add_option("--scene", scene, "scene name as in the CSV (e.g. \"coin from 1\")")
      ->required();
  simCmd
      ->add_option("--metric", metric,
                   "combined (max of stopping-time and terminal error, default), tstop or terminal")
      ->check(CLI::IsMember({"combined", "tstop", "terminal"}));

  CLI11_PARSE(app, argc, argv);

  try {
    render::PlotOptions options;
    parseSize(size, options);
    options.title = title;
    if (*paretoCmd) {
      render::plotPareto(csv, out, pareto, options);
    } else if (*patchCmd) {
      plotPatchPareto(csv, level, statistic, out, options);
    } else if (*simCmd) {
      plotSimulationPareto(csv, scene, metric, out, options);
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
