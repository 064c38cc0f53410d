// The slip sphere, plot (a) of plot.hpp.
#include "plot_csv.hpp"
#include "plot_limit_styles.hpp"
#include "plot_script.hpp"

#include <cmath>
#include <set>
#include <sstream>

namespace patchspin::render {
using namespace plotting;
namespace {

struct SphereView {
  Vec3 d, right, up;  // towards the viewer; screen axes
  explicit SphereView(double azDeg, double elDeg) {
    const double a = azDeg * kPi / 180.0, e = elDeg * kPi / 180.0;
    d = Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    right = Vec3::UnitZ().cross(d);
    if (right.norm() < 1e-9) right = Vec3::UnitY();  // looking along z
    right.normalize();
    up = d.cross(right);
  }
  std::string xy(const Vec3& p) const { return num(p.dot(right)) + " " + num(p.dot(up)); }
  bool front(const Vec3& p) const { return p.dot(d) >= 0.0; }
};

// A curve on the sphere split into its visible and hidden parts, with the
// horizon crossing added to both so the parts meet.
void splitCurve(const std::vector<Vec3>& pts, const SphereView& v, std::string& front,
                std::string& back) {
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3 p = pts[i].normalized();
    if (i > 0) {
      const Vec3 q = pts[i - 1].normalized();
      const double dq = q.dot(v.d), dp = p.dot(v.d);
      if ((dq >= 0.0) != (dp >= 0.0)) {
        const double s = dq / (dq - dp);
        const Vec3 c = (q + s * (p - q)).normalized();
        (dq >= 0.0 ? front : back) += v.xy(c) + "\n\n";  // end the old part
        (dp >= 0.0 ? front : back) += v.xy(c) + "\n";    // start the new one
      }
    }
    (v.front(p) ? front : back) += v.xy(p) + "\n";
  }
  front += "\n";
  back += "\n";
}

std::vector<Vec3> greatCircle(const Vec3& a, const Vec3& b) {
  std::vector<Vec3> pts;
  constexpr int kN = 180;
  for (int i = 0; i <= kN; ++i) {
    const double t = 2.0 * kPi * i / kN;
    pts.push_back(std::cos(t) * a + std::sin(t) * b);
  }
  return pts;
}

}  // namespace

void plotSlipSphere(const SpherePlot& plot, const std::string& pngPath, const PlotOptions& o) {
  const SphereView v(plot.azimuthDeg, plot.elevationDeg);
  std::ostringstream s;
  s << header(pngPath, o);
  // coordinate circles w_i = 0 and the three positive half-axes
  std::string gridFront, gridBack;
  splitCurve(greatCircle(Vec3::UnitX(), Vec3::UnitY()), v, gridFront, gridBack);
  splitCurve(greatCircle(Vec3::UnitY(), Vec3::UnitZ()), v, gridFront, gridBack);
  splitCurve(greatCircle(Vec3::UnitZ(), Vec3::UnitX()), v, gridFront, gridBack);
  datablock(s, "grid_front", gridFront);
  datablock(s, "grid_back", gridBack);
  std::string axesFront, axesBack;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = Vec3::Unit(i);
    (v.front(e) ? axesFront : axesBack) += v.xy(Vec3::Zero()) + "\n" + v.xy(e) + "\n\n";
    const Vec3 tip = 1.13 * e;
    s << "set label " << (i + 1) << " " << gpString(plot.axisNames[i]) << " at "
      << num(tip.dot(v.right)) << "," << num(tip.dot(v.up)) << " center tc rgb "
      << gpString(v.front(e) ? "#303030" : "#909090") << " font \"," << num(o.fontSize + 1)
      << "\"\n";
  }
  datablock(s, "axes_front", axesFront + "\n");
  datablock(s, "axes_back", axesBack + "\n");

  // paths, start and end markers
  std::string plots;
  auto add = [&plots](const std::string& item) {
    plots += (plots.empty() ? "" : ", \\\n     ") + item;
  };
  add("$grid_back with lines lc rgb '#c3cbd5' dt 3 notitle");
  add("$axes_back with lines lc rgb '#b0b0b0' dt 2 notitle");
  for (std::size_t i = 0; i < plot.paths.size(); ++i) {
    const SpherePath& p = plot.paths[i];
    if (p.w.empty()) continue;
    std::string front, back;
    splitCurve(p.w, v, front, back);
    const std::string id = std::to_string(i);
    datablock(s, "path" + id + "_front", front);
    datablock(s, "path" + id + "_back", back);
    datablock(s, "path" + id + "_ends",
              v.xy(p.w.front().normalized()) + "\n\n\n" + v.xy(p.w.back().normalized()) + "\n");
    const std::string c = gpString(paletteColour(i));
    add("$path" + id + "_back with lines lw 1.5 dt 2 lc rgb " + c + " notitle");
  }
  add("$grid_front with lines lc rgb '#7f8c9b' lw 1.2 notitle");
  add("$axes_front with lines lc rgb '#404040' lw 1.2 notitle");
  for (std::size_t i = 0; i < plot.paths.size(); ++i) {
    if (plot.paths[i].w.empty()) continue;
    const std::string id = std::to_string(i), c = gpString(paletteColour(i));
    add("$path" + id + "_front with lines lw 2.5 lc rgb " + c + " title " +
        gpString(plot.paths[i].label) + " noenhanced");
    add("$path" + id + "_ends index 0 with points pt 6 ps 1.2 lw 2 lc rgb " + c + " notitle");
    add("$path" + id + "_ends index 1 with points pt 2 ps 1.4 lw 2.5 lc rgb " + c + " notitle");
  }
  // limit directions by style, hidden ones paler
  std::set<int> styles;
  std::map<std::pair<int, bool>, std::string> limitRows;
  std::string limitLabels;
  for (const LimitDirection& l : plot.limits) {
    const Vec3 w = l.w.normalized();
    const int st = styleIndex(l.stability, l.kind);
    styles.insert(st);
    limitRows[{st, v.front(w)}] += v.xy(w) + "\n";
    if (!l.label.empty()) limitLabels += v.xy(w) + " " + gpString(l.label) + "\n";
  }
  for (const auto& [key, rows] : limitRows) {
    const std::string name =
        "limit" + std::to_string(key.first) + (key.second ? "_front" : "_back");
    datablock(s, name, rows);
    add("$" + name + " with points pt " + std::to_string(pointType(styleKind(key.first))) +
        " ps 2.0 lw 2 lc rgb " + gpString(stabilityColour(styleStability(key.first), !key.second)) +
        " notitle");
  }
  if (!limitLabels.empty()) {
    datablock(s, "limit_labels", limitLabels);
    add("$limit_labels using 1:2:3 with labels offset char 1.2,0.9 tc rgb '#202020' notitle");
  }
  plots += limitKeyEntries(styles);
  plots += ", keyentry with points pt 6 ps 1.2 lw 2 lc rgb '#505050' title 'start'";
  plots += ", keyentry with points pt 2 ps 1.4 lw 2.5 lc rgb '#505050' title 'end'";

  s << "set size ratio -1\nunset border\nunset tics\n"
    << "set xrange [-1.3:1.3]\nset yrange [-1.22:1.22]\n"
    << "set object 1 circle at 0,0 size 1 fc rgb '#f0f3f7' fs solid 1.0 border lc rgb '#4a5560' "
       "lw 1.5 behind\n"
    << "set key outside right top Left reverse samplen 2 spacing 1.2\n";
  if (!o.title.empty()) s << "set title " << gpString(o.title) << " noenhanced\n";
  s << "plot " << plots << "\n";
  runGnuplot(s.str(), pngPath, o);
}

}  // namespace patchspin::render
