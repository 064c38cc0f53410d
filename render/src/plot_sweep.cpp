// The bifurcation plots of `patchspin sweep`, plots (c) of plot.hpp.
#include "plot_csv.hpp"
#include "plot_limit_styles.hpp"
#include "plot_script.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace patchspin::render {
using namespace plotting;

namespace {

// One parameter point of a `patchspin sweep` CSV.
struct SweepCycle {
  bool attracting = false;
  std::array<double, 4> lo{}, hi{};  // ranges of the angle atan2(w3, w1) [deg], w1, w2, w3
};
struct SweepPoint {
  double F = 0.0, T = 0.0;
  bool tipping = false;
  std::vector<LimitDirection> directions;
  std::vector<SweepCycle> cycles;
};

std::vector<SweepPoint> readSweep(const std::string& csvPath) {
  const Csv csv = readCsv(csvPath);
  std::vector<SweepPoint> points;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    SweepPoint p;
    p.F = csv.number(i, "F");
    p.T = csv.number(i, "T");
    if (csv.has("tipping")) p.tipping = csv.number(i, "tipping") != 0.0;
    // "w1 w2 w3 rdot attracting|repelling type" entries separated by '|'
    std::stringstream entries(csv.text(i, "directions"));
    std::string entry;
    while (std::getline(entries, entry, '|')) {
      if (trim(entry).empty()) continue;
      std::istringstream in(entry);
      double w1, w2, w3, rdot;
      std::string stability, type;
      if (!(in >> w1 >> w2 >> w3 >> rdot >> stability >> type)) {
        throw RenderError(csvPath + ":" + std::to_string(csv.lineOf[i]) +
                          ": a direction must be 'w1 w2 w3 rdot attracting|repelling type', got '" +
                          entry + "'");
      }
      // reuse the cell parsers on a one-row table
      Csv one;
      one.path = csvPath;
      one.column = {{"stability", 0}, {"kind", 1}};
      one.rows = {{stability, type}};
      one.lineOf = {csv.lineOf[i]};
      LimitDirection d;
      d.w = Vec3(w1, w2, w3);
      d.stability = parseStability(one, 0);
      d.kind = parseKind(one, 0);
      p.directions.push_back(d);
    }
    // optional: "attracting|repelling period multiplier turn w1min w1max w2min
    // w2max w3min w3max angle_min angle_max" entries separated by '|'
    if (csv.has("cycles")) {
      std::stringstream cycles(csv.text(i, "cycles"));
      while (std::getline(cycles, entry, '|')) {
        if (trim(entry).empty()) continue;
        std::istringstream in(entry);
        std::string stability;
        double period, multiplier, turn;
        SweepCycle c;
        if (!(in >> stability >> period >> multiplier >> turn >> c.lo[1] >> c.hi[1] >> c.lo[2] >>
              c.hi[2] >> c.lo[3] >> c.hi[3] >> c.lo[0] >> c.hi[0]) ||
            (stability != "attracting" && stability != "repelling")) {
          throw RenderError(csvPath + ":" + std::to_string(csv.lineOf[i]) +
                            ": a cycle must be 'attracting|repelling period multiplier turn w1min "
                            "w1max w2min w2max w3min w3max angle_min angle_max', got '" +
                            entry + "'");
        }
        c.attracting = stability == "attracting";
        p.cycles.push_back(c);
      }
    }
    points.push_back(std::move(p));
  }
  return points;
}

// smallest positive gap between sorted distinct values (grid spacing), or a
// fallback for a single value
double gridStep(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  double step = 0.0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    const double d = values[i] - values[i - 1];
    if (d > 0.0 && (step == 0.0 || d < step)) step = d;
  }
  if (step == 0.0) step = values.empty() || values[0] == 0.0 ? 1.0 : 0.1 * std::abs(values[0]);
  return step;
}

}  // namespace

void plotBifurcationForce(const std::vector<SweepPanel>& panelList, const std::string& pngPath,
                          const BifurcationOptions& b, const PlotOptions& o) {
  if (b.component < 0 || b.component > 3) {
    throw RenderError("plotBifurcationForce: component must be 0 (angle), 1, 2 or 3, got " +
                      std::to_string(b.component));
  }
  if (panelList.empty()) throw RenderError("plotBifurcationForce: no sweeps");
  std::vector<std::vector<SweepPoint>> sweeps;
  for (const SweepPanel& panel : panelList) sweeps.push_back(readSweep(panel.csvPath));
  // the torque slice: given, or the smallest |T| present
  double T0 = sweeps[0][0].T;
  for (const auto& sweep : sweeps) {
    for (const SweepPoint& p : sweep) {
      if (std::abs(p.T) < std::abs(T0)) T0 = p.T;
    }
  }
  if (b.torque) T0 = *b.torque;
  // values equal up to printing round-off count as the same slice
  const double tTol = 1e-9 * std::max(1.0, std::abs(T0));

  std::ostringstream s;
  s << header(pngPath, o);
  std::set<int> allStyles;
  bool anyCycle[2] = {false, false};  // attracting, repelling
  std::string panels;
  for (std::size_t m = 0; m < sweeps.size(); ++m) {
    std::map<int, std::string> byStyle;
    bool any = false;
    for (const SweepPoint& p : sweeps[m]) {
      if (std::abs(p.T - T0) > tTol) continue;
      any = true;
      for (const LimitDirection& d : p.directions) {
        const int st = styleIndex(d.stability, d.kind);
        const double y =
            b.component == 0 ? std::atan2(d.w.z(), d.w.x()) * 180.0 / kPi : d.w[b.component - 1];
        byStyle[st] += num(p.F) + " " + num(y) + "\n";
        allStyles.insert(st);
      }
    }
    if (!any) {
      throw RenderError(panelList[m].csvPath + ": no parameter points at T = " + num(T0));
    }
    // cycles: a vertical bar over the range of the plotted quantity on the
    // orbit, one datablock per stability
    std::string cycleData[2];
    for (const SweepPoint& p : sweeps[m]) {
      if (std::abs(p.T - T0) > tTol) continue;
      for (const SweepCycle& c : p.cycles) {
        const std::size_t k = static_cast<std::size_t>(b.component);
        cycleData[c.attracting ? 0 : 1] +=
            num(p.F) + " " + num(c.lo[k]) + " 0 " + num(c.hi[k] - c.lo[k]) + "\n";
        anyCycle[c.attracting ? 0 : 1] = true;
      }
    }
    std::string plots;
    for (int k = 0; k < 2; ++k) {
      if (cycleData[k].empty()) continue;
      const std::string name = "m" + std::to_string(m) + "_cycles" + std::to_string(k);
      datablock(s, name, cycleData[k]);
      plots +=
          std::string(plots.empty() ? "" : ", ") + "$" + name +
          " with vectors nohead lw 3 lc rgb " +
          gpString(stabilityColour(k == 0 ? Stability::Attracting : Stability::Repelling, true)) +
          " notitle";
    }
    for (const auto& [st, data] : byStyle) {
      const std::string name = "m" + std::to_string(m) + "_s" + std::to_string(st);
      datablock(s, name, data);
      plots += std::string(plots.empty() ? "" : ", ") + "$" + name + " with points pt " +
               std::to_string(pointType(styleKind(st))) + " ps 1.1 lw 1.5 lc rgb " +
               gpString(stabilityColour(styleStability(st))) + " notitle";
    }
    // an empty panel still needs something to plot
    if (plots.empty()) plots = "NaN notitle";
    panels +=
        "set title " + gpString(panelList[m].title) + " noenhanced\nplot " + plots + "__KEY__\n";
  }
  // key (all styles present in any panel) on every panel
  std::string key = limitKeyEntries(allStyles);
  for (int k = 0; k < 2; ++k) {
    if (!anyCycle[k]) continue;
    key += ", keyentry with vectors nohead lw 3 lc rgb " +
           gpString(stabilityColour(k == 0 ? Stability::Attracting : Stability::Repelling, true)) +
           " title " + gpString(k == 0 ? "attracting cycle (range)" : "repelling cycle (range)");
  }
  std::string p = panels;
  for (std::size_t at; (at = p.find("__KEY__")) != std::string::npos;) p.replace(at, 7, key);
  s << multiplotHeader(sweeps.size(), o) << "set grid lc rgb '#dddddd'\n"
    << "set xlabel "
    << gpString(b.forceLabel + (T0 != 0.0 ? "   (" + b.torqueLabel + " = " + num(T0) + ")" : ""))
    << "\n"
    << (b.component == 0
            ? "set ylabel 'atan2(w_3, w_1) [deg]'\nset yrange [-190:190]\nset ytics 45\n"
            : "set ylabel 'w_" + std::to_string(b.component) + "'\nset yrange [-1.08:1.08]\n")
    << "set key bottom right box opaque spacing 1.1 samplen 1\n"
    << p << "unset multiplot\n";
  runGnuplot(s.str(), pngPath, o);
}

void plotBifurcationPlane(const std::vector<SweepPanel>& panelList, const std::string& pngPath,
                          const BifurcationOptions& b, const PlotOptions& o) {
  if (panelList.empty()) throw RenderError("plotBifurcationPlane: no sweeps");
  // per (panel, F, T): counts of each style, and the tipping flag
  std::map<std::tuple<std::size_t, double, double>, std::pair<std::array<int, kStyles>, bool>>
      points;
  std::map<std::tuple<std::size_t, double, double>, std::array<int, 2>> cycleCounts;
  std::vector<double> Fs, Ts;
  for (std::size_t m = 0; m < panelList.size(); ++m) {
    for (const SweepPoint& p : readSweep(panelList[m].csvPath)) {
      auto& entry = points[{m, p.F, p.T}];
      for (const LimitDirection& d : p.directions) {
        ++entry.first[static_cast<std::size_t>(styleIndex(d.stability, d.kind))];
      }
      entry.second = entry.second || p.tipping;
      auto& cycles = cycleCounts[{m, p.F, p.T}];
      for (const SweepCycle& c : p.cycles) ++cycles[c.attracting ? 0 : 1];
      Fs.push_back(p.F);
      Ts.push_back(p.T);
    }
  }
  const double dF = gridStep(Fs), dT = gridStep(Ts);
  // category text, e.g. "4: 2 A-dom, 1 A-iso, 1 A-sad"
  std::map<std::tuple<std::size_t, double, double>, std::string> categoryOf;
  std::map<std::string, int> frequency;
  for (const auto& [key, value] : points) {
    const auto& [counts, tipping] = value;
    int total = 0;
    std::string parts;
    for (int st = 0; st < kStyles; ++st) {
      if (!counts[st]) continue;
      total += counts[st];
      parts += std::string(parts.empty() ? "" : ", ") + std::to_string(counts[st]) + " " +
               (styleStability(st) == Stability::Attracting ? "A-" : "R-") +
               kindShort(styleKind(st));
    }
    // and the limit cycles, e.g. " + 2 A-cyc"
    std::string cyclePart;
    const std::array<int, 2> cycles = cycleCounts[key];
    for (int k = 0; k < 2; ++k) {
      if (cycles[k])
        cyclePart += " + " + std::to_string(cycles[k]) + (k == 0 ? " A-cyc" : " R-cyc");
    }
    const std::string cat = std::to_string(total) + ": " + (total ? parts : "none") + cyclePart +
                            (tipping ? " (tips)" : "");
    categoryOf[key] = cat;
    ++frequency[cat];
  }
  // the most frequent categories first, each its own colour, the same in every
  // panel; beyond the palette the rarest share one "other" entry
  std::vector<std::string> categories;
  for (const auto& [cat, n] : frequency) categories.push_back(cat);
  std::stable_sort(
      categories.begin(), categories.end(),
      [&](const std::string& x, const std::string& y) { return frequency[x] > frequency[y]; });
  if (categories.size() > kTileColours) {
    categories.resize(kTileColours - 1);
    categories.push_back("other");
  }
  std::map<std::size_t, std::map<std::size_t, std::string>> tiles;  // panel -> category -> rows
  for (const auto& [key, cat] : categoryOf) {
    auto it = std::find(categories.begin(), categories.end(), cat);
    if (it == categories.end()) it = categories.end() - 1;  // "other"
    const std::size_t c = static_cast<std::size_t>(it - categories.begin());
    tiles[std::get<0>(key)][c] += num(std::get<1>(key)) + " " + num(std::get<2>(key)) + " " +
                                  num(0.5 * dF) + " " + num(0.5 * dT) + "\n";
  }
  std::ostringstream s;
  s << header(pngPath, o);
  std::string panels;
  for (std::size_t m = 0; m < panelList.size(); ++m) {
    std::string plots;
    for (const auto& [c, data] : tiles[m]) {
      const std::string name = "m" + std::to_string(m) + "_c" + std::to_string(c);
      datablock(s, name, data);
      plots += std::string(plots.empty() ? "" : ", ") + "$" + name +
               " with boxxyerror fs solid 1.0 noborder lc rgb " + gpString(kTiles[c]) + " notitle";
    }
    // every category in every key, so panels read alike
    for (std::size_t c = 0; c < categories.size(); ++c) {
      plots += ", keyentry with boxes fs solid 1.0 lc rgb " + gpString(kTiles[c]) + " title " +
               gpString(categories[c]);
    }
    panels += "set title " + gpString(panelList[m].title) + " noenhanced\nplot " + plots + "\n";
  }
  s << multiplotHeader(panelList.size(), o) << "set xlabel " << gpString(b.forceLabel) << "\n"
    << "set ylabel " << gpString(b.torqueLabel) << "\nset key below Left reverse samplen 1.5\n"
    << "set style fill solid 1.0\nset tics out\nset grid front lc rgb '#ffffff' lw 0.5\n"
    << "set offsets 0,0,0,0\nset autoscale fix\n"
    << panels << "unset multiplot\n";
  runGnuplot(s.str(), pngPath, o);
}

}  // namespace patchspin::render
