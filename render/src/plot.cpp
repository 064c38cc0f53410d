// Plots (b), (d), (e) of plot.hpp and its CSV readers; the slip sphere
// (a) is in plot_slip_sphere.cpp, the sweeps (c) in plot_sweep.cpp, the
// gnuplot scripts in plot_script.cpp.
#include "plot_csv.hpp"
#include "plot_limit_styles.hpp"
#include "plot_script.hpp"

#include <cmath>
#include <sstream>

namespace patchspin::render {
using namespace plotting;

// ---- (b) ------------------------------------------------------------------------

void plotSlipRatio(const TimeSeriesPlot& plot, const std::string& pngPath, const PlotOptions& o) {
  if (plot.series.empty()) throw RenderError("plotSlipRatio: no series");
  std::ostringstream s;
  s << header(pngPath, o);
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const TimeSeries& ts = plot.series[i];
    if (ts.slipRatio.size() != ts.t.size() || ts.r.size() != ts.t.size()) {
      throw RenderError("plotSlipRatio: series '" + ts.label +
                        "' has t, slipRatio and r of different lengths");
    }
    std::string rows;
    for (std::size_t k = 0; k < ts.t.size(); ++k) {
      const double r = (plot.logR && !(ts.r[k] > 0.0)) ? NAN : ts.r[k];
      rows += num(ts.t[k]) + " " + num(ts.slipRatio[k]) + " " + num(r) + "\n";
    }
    datablock(s, "s" + std::to_string(i), rows);
  }
  auto series = [&](int column) {
    std::string p;
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      p += std::string(i ? ", \\\n     " : "") + "$s" + std::to_string(i) +
           " using 1:" + std::to_string(column) + " with lines lw 2.2 lc rgb " +
           gpString(paletteColour(i)) + " title " + gpString(plot.series[i].label) + " noenhanced";
    }
    return p;
  };
  s << "set multiplot layout 2,1";
  if (!o.title.empty()) s << " title " << gpString(o.title) << " noenhanced";
  s << "\nset lmargin 11\nset rmargin 3\nset grid lc rgb '#dddddd'\n"
    << "set key top right box opaque\n"
    << "set ylabel 'v/(R{/Symbol w})'\nset format x ''\n";
  if (plot.ratioMax)
    s << "set yrange [0:" << num(*plot.ratioMax) << "]\n";
  else
    s << "set yrange [0:*]\n";
  if (plot.referenceRatio) {
    const double ref = *plot.referenceRatio;
    s << "set arrow 1 from graph 0, first " << num(ref) << " to graph 1, first " << num(ref)
      << " nohead dt 2 lw 1.5 lc rgb '#000000' front\n"
      << "set label 1 " << gpString(plot.referenceLabel) << " at graph 0.01, first " << num(ref)
      << " offset 0,0.7 tc rgb '#000000' front noenhanced\n";
  }
  s << "plot " << series(2) << "\n";
  s << "unset arrow 1\nunset label 1\nunset title\nset format x '%g'\nset xlabel 't [s]'\n"
    << "set ylabel 'r = |x_o| [m/s]'\nset yrange [*:*]\nset key top right box opaque\n";
  if (plot.logR) s << "set logscale y\nset format y '10^{%L}'\n";
  s << "plot " << series(3) << "\nunset multiplot\n";
  runGnuplot(s.str(), pngPath, o);
}

// ---- (d) ------------------------------------------------------------------------

void plotPareto(const std::string& csvPath, const std::string& pngPath, const ParetoOptions& p,
                const PlotOptions& o) {
  const Csv csv = readCsv(csvPath);
  const bool labelled = csv.has("label");
  std::vector<std::string> models;
  std::map<std::string, std::string> data;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const std::string& model = csv.text(i, "model");
    const double t = csv.number(i, "time"), e = csv.number(i, "error");
    if (!(t > 0.0) || !(e > 0.0)) {
      throw RenderError(csvPath + ":" + std::to_string(csv.lineOf[i]) +
                        ": time and error must be > 0 (log axes)");
    }
    if (std::find(models.begin(), models.end(), model) == models.end()) models.push_back(model);
    std::string label =
        labelled && csv.index("label") < csv.rows[i].size() ? csv.text(i, "label") : "";
    data[model] += num(t) + " " + num(e) + " " + gpString(label) + "\n";
  }
  std::ostringstream s;
  s << header(pngPath, o);
  std::string plots;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const std::string name = "m" + std::to_string(m);
    datablock(s, name, data[models[m]]);
    const std::string c = gpString(paletteColour(m));
    plots += std::string(m ? ", \\\n     " : "") + "$" + name +
             " using 1:2 with linespoints pt 7 ps 1.4 lw 1.8 lc rgb " + c + " title " +
             gpString(models[m]) + " noenhanced";
    if (labelled) {
      plots += ", $" + name + " using 1:2:3 with labels left offset char 0.8,0.5 font '," +
               num(o.fontSize - 2) + "' tc rgb " + c + " notitle noenhanced";
    }
  }
  if (!o.title.empty()) s << "set title " << gpString(o.title) << " noenhanced\n";
  s << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set grid xtics ytics mxtics mytics lc rgb '#e0e0e0'\n"
    << "set xlabel " << gpString(p.timeLabel) << "\nset ylabel " << gpString(p.errorLabel) << "\n"
    << "set key top right box opaque\nset offsets graph 0.05, graph 0.15, graph 0.05, graph 0.05\n"
    << "plot " << plots << "\n";
  runGnuplot(s.str(), pngPath, o);
}

// ---- (e) ------------------------------------------------------------------------

void plotGroundTracks(const GroundTrackPlot& plot, const std::string& pngPath,
                      const PlotOptions& o) {
  if (plot.tracks.empty()) throw RenderError("plotGroundTracks: no tracks");
  std::ostringstream s;
  s << header(pngPath, o);
  std::string plots, dashed, ends;
  for (std::size_t i = 0; i < plot.tracks.size(); ++i) {
    const GroundTrack& t = plot.tracks[i];
    if (t.points.empty()) throw RenderError("plotGroundTracks: track '" + t.label + "' is empty");
    std::string rows;
    for (const Vec2& p : t.points) rows += num(p.x()) + " " + num(p.y()) + "\n";
    datablock(s, "t" + std::to_string(i), rows);
    const std::string colour = gpString(t.colour.empty() ? paletteColour(i) : t.colour);
    const std::string line = "$t" + std::to_string(i) + " using 1:2 with lines " +
                             (t.dashed ? "lw 1.4 dt 2" : "lw 2.6") + " lc rgb " + colour +
                             " title " + gpString(t.label) + " noenhanced";
    (t.dashed ? dashed : plots) += ", \\\n     " + line;
    const Vec2 a = t.points.front(), b = t.points.back();
    ends += ", \\\n     '+' using (" + num(a.x()) + "):(" + num(a.y()) +
            ") every ::0::0 with points pt 6 ps 1.2 lc rgb " + colour + " notitle" +
            ", \\\n     '+' using (" + num(b.x()) + "):(" + num(b.y()) +
            ") every ::0::0 with points pt 2 ps 1.4 lc rgb " + colour + " notitle";
  }
  if (!o.title.empty()) s << "set title " << gpString(o.title) << " noenhanced\n";
  s << "set grid lc rgb '#dddddd'\nset key bottom left box opaque\n"
    << "set xlabel " << gpString(plot.xLabel) << "\nset ylabel " << gpString(plot.yLabel)
    << "\nset offsets graph 0.03, graph 0.03, graph 0.08, graph 0.08\n";
  if (plot.equalAxes) s << "set size ratio -1\n";
  // solid tracks first, dashed ones over them
  std::string all = plots + dashed + ends;
  s << "plot " << all.erase(0, all.find('$')) << "\n";
  runGnuplot(s.str(), pngPath, o);
}

// ---- CSV readers -------------------------------------------------------------

std::vector<TimeSeries> readTimeSeriesCsv(const std::string& csvPath) {
  const Csv csv = readCsv(csvPath);
  std::vector<TimeSeries> out;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const std::string& label = csv.text(i, "label");
    auto it =
        std::find_if(out.begin(), out.end(), [&](const TimeSeries& t) { return t.label == label; });
    if (it == out.end()) {
      out.push_back(TimeSeries{label, {}, {}, {}});
      it = out.end() - 1;
    }
    it->t.push_back(csv.number(i, "t"));
    it->slipRatio.push_back(csv.number(i, "slipRatio"));
    it->r.push_back(csv.number(i, "r"));
  }
  return out;
}

std::vector<SpherePath> readSpherePathsCsv(const std::string& csvPath) {
  const Csv csv = readCsv(csvPath);
  std::vector<SpherePath> out;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const std::string& label = csv.text(i, "label");
    auto it =
        std::find_if(out.begin(), out.end(), [&](const SpherePath& p) { return p.label == label; });
    if (it == out.end()) {
      out.push_back(SpherePath{label, {}});
      it = out.end() - 1;
    }
    it->w.emplace_back(csv.number(i, "w1"), csv.number(i, "w2"), csv.number(i, "w3"));
  }
  return out;
}

std::vector<LimitDirection> readLimitDirectionsCsv(const std::string& csvPath) {
  const Csv csv = readCsv(csvPath);
  const bool labelled = csv.has("label");
  std::vector<LimitDirection> out;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    LimitDirection l;
    l.w = Vec3(csv.number(i, "w1"), csv.number(i, "w2"), csv.number(i, "w3"));
    l.stability = parseStability(csv, i);
    l.kind = parseKind(csv, i);
    if (labelled && csv.index("label") < csv.rows[i].size()) l.label = csv.text(i, "label");
    out.push_back(l);
  }
  return out;
}
}  // namespace patchspin::render
