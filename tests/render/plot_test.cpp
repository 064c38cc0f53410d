// Plots through gnuplot: each kind gives a PNG of the requested size with
// content, from small synthetic data; bad input and a missing gnuplot give
// clear errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <patchspin/render/image.hpp>
#include <patchspin/render/plot.hpp>
#include <string>

namespace patchspin::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 240;
// a blank (uniform) PNG has variance 0; axes, curves and text give far more
constexpr double kMinVariance = 100.0;

std::string tempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("patchspin_plot_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

PlotOptions smallOptions() {
  PlotOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.fontSize = 7;
  o.title = "test";
  return o;
}

void expectValidPng(const std::string& path) {
  const Image image = readPng(path);
  EXPECT_EQ(image.width, kWidth);
  EXPECT_EQ(image.height, kHeight);
  EXPECT_GT(pixelVariance(image), kMinVariance);
}

// `patchspin sweep` CSVs shaped like the thin disk of Sect. 6.1: a pitchfork
// at F = Fc and a change of stability at F = 1 (synthetic values, not physics)
std::vector<SweepPanel> writeSweeps(const std::string& dir) {
  std::vector<SweepPanel> panels;
  for (const char* model : {"ellipsoidal", "exact"}) {
    const std::string path = dir + "/sweep_" + model + ".csv";
    std::ofstream out(path);
    out << "F,T,n_directions,tipping,directions\n";
    for (int i = 0; i <= 12; ++i) {
      for (int j = 0; j <= 4; ++j) {
        const double F = 0.1 * i, T = 0.05 * j, Fc = 1.0 / 9.0 + T;
        std::string dirs = "-1 0 0 -3 attracting isolated";
        int n = 2;
        if (F > 1.0) {
          dirs += "|1 0 0 0.5 repelling isolated";
        } else if (F > Fc) {
          dirs += "|1 0 0 -1 attracting dominant";
        } else {
          const double w1 = F / Fc, w3 = std::sqrt(1.0 - w1 * w1);
          dirs += "|1 0 0 -1 attracting saddle|" + std::to_string(w1) + " 0 " + std::to_string(w3) +
                  " -1 attracting dominant|" + std::to_string(w1) + " 0 " + std::to_string(-w3) +
                  " -1 attracting dominant";
          n = 4;
        }
        out << F << "," << T << "," << n << "," << (j == 4 && i == 12) << ",\"" << dirs << "\"\n";
      }
    }
    panels.push_back({model, path});
  }
  return panels;
}

TEST(Plot, SlipSphere) {
  SpherePlot plot;
  for (int k = 0; k < 2; ++k) {
    SpherePath path;
    path.label = k ? "ellipsoidal" : "exact";
    // a path crossing from the hidden to the visible hemisphere
    for (int i = 0; i <= 50; ++i) {
      const double s = i / 50.0, a = 4.0 * s + k;
      path.w.push_back(Vec3((1 - s) * std::cos(a) + 0.8 * s, (1 - s) * std::sin(a), 0.3 + 0.5 * s));
    }
    plot.paths.push_back(path);
  }
  plot.limits = {{Vec3(0.8, 0, 0.6), Stability::Attracting, LimitKind::Dominant, "w_3"},
                 {Vec3(1, 0, 0), Stability::Attracting, LimitKind::Saddle, "w_1"},
                 {Vec3(-1, 0, 0), Stability::Repelling, LimitKind::Isolated, ""}};
  const std::string dir = tempDir("sphere");
  plotSlipSphere(plot, dir + "/sphere.png", smallOptions());
  expectValidPng(dir + "/sphere.png");
  // the script stays next to the PNG so it can be rerun
  EXPECT_TRUE(std::filesystem::exists(dir + "/sphere.gp"));
}

TEST(Plot, SlipRatioAgainstTime) {
  TimeSeriesPlot plot;
  for (int k = 0; k < 3; ++k) {
    TimeSeries ts;
    ts.label = k == 0 ? "exact" : k == 1 ? "ellipsoidal" : "stock";
    for (int i = 0; i <= 100; ++i) {
      const double t = 0.02 * i;
      ts.t.push_back(t);
      ts.slipRatio.push_back(i == 100 ? NAN : 0.653 + (1.0 + k) * std::exp(-2.0 * t));
      ts.r.push_back(std::max(0.0, 2.0 - t));
    }
    plot.series.push_back(ts);
  }
  const std::string dir = tempDir("ratio");
  plotSlipRatio(plot, dir + "/ratio.png", smallOptions());
  expectValidPng(dir + "/ratio.png");
  plot.logR = true;  // r = 0 at the end must be dropped, not break the log axis
  plotSlipRatio(plot, dir + "/ratio_log.png", smallOptions());
  expectValidPng(dir + "/ratio_log.png");
}

TEST(Plot, GroundTracks) {
  GroundTrackPlot plot;
  for (int k = 0; k < 2; ++k) {
    GroundTrack t;
    t.label = k == 0 ? "bullet" : "reference";
    t.dashed = k == 1;
    if (k == 1) t.colour = "#000000";
    for (int i = 0; i <= 50; ++i) t.points.emplace_back(0.02 * i, -0.001 * (1 + k) * i * i / 50.0);
    plot.tracks.push_back(t);
  }
  const std::string dir = tempDir("tracks");
  plotGroundTracks(plot, dir + "/tracks.png", smallOptions());
  expectValidPng(dir + "/tracks.png");
  plot.equalAxes = true;
  plotGroundTracks(plot, dir + "/tracks_equal.png", smallOptions());
  expectValidPng(dir + "/tracks_equal.png");
  plot.tracks[1].points.clear();
  EXPECT_THROW(plotGroundTracks(plot, dir + "/empty.png", smallOptions()), RenderError);
}

TEST(Plot, BifurcationAgainstForceAndOverPlane) {
  const std::string dir = tempDir("bifurcation");
  const std::vector<SweepPanel> sweeps = writeSweeps(dir);
  plotBifurcationForce(sweeps, dir + "/force.png", BifurcationOptions(), smallOptions());
  expectValidPng(dir + "/force.png");
  BifurcationOptions component;
  component.component = 3;
  component.torque = 0.1;
  plotBifurcationForce(sweeps, dir + "/force_w3.png", component, smallOptions());
  expectValidPng(dir + "/force_w3.png");
  plotBifurcationPlane(sweeps, dir + "/plane.png", BifurcationOptions(), smallOptions());
  expectValidPng(dir + "/plane.png");
  // a malformed direction entry names file and line
  {
    std::ofstream out(dir + "/bad.csv");
    out << "F,T,directions\n0,0,\"1 0 0 attracting dominant\"\n";
  }
  try {
    plotBifurcationPlane({{"bad", dir + "/bad.csv"}}, dir + "/bad.png");
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2: a direction must be"), std::string::npos)
        << e.what();
  }
}

// A sweep with limit cycles (the optional `cycles` column of `patchspin
// sweep`): below F = 0.5 two attracting cycles around the poles (synthetic
// ranges), none above. The F diagram draws them as bars (its image differs
// from the same sweep without the column); the plane counts them; a
// malformed cycle entry names file and line.
TEST(Plot, BifurcationMarksLimitCycles) {
  const std::string dir = tempDir("cycles");
  for (bool cycles : {true, false}) {
    std::ofstream out(dir + (cycles ? "/with.csv" : "/without.csv"));
    out << "F,T,directions" << (cycles ? ",cycles" : "") << "\n";
    for (int i = 0; i <= 10; ++i) {
      for (int j = 0; j <= 2; ++j) {
        const double F = 0.1 * i, T = 0.1 * j;
        out << F << "," << T << ",\"-1 0 0 -3 attracting isolated\"";
        if (cycles) {
          out << ",\"";
          if (F < 0.5) {
            out << "attracting 8.9 2e-12 -22 -0.6 0.75 -0.7 0.7 0.65 0.8 40 128|"
                   "attracting 8.9 2e-12 22 -0.6 0.75 -0.7 0.7 -0.8 -0.65 -128 -40";
          }
          out << "\"";
        }
        out << "\n";
      }
    }
  }
  BifurcationOptions w3;
  w3.component = 3;
  plotBifurcationForce({{"with", dir + "/with.csv"}}, dir + "/with.png", w3, smallOptions());
  plotBifurcationForce({{"with", dir + "/without.csv"}}, dir + "/without.png", w3, smallOptions());
  expectValidPng(dir + "/with.png");
  EXPECT_NE(readPng(dir + "/with.png").rgb, readPng(dir + "/without.png").rgb);
  plotBifurcationForce({{"with", dir + "/with.csv"}}, dir + "/angle.png", BifurcationOptions(),
                       smallOptions());
  expectValidPng(dir + "/angle.png");
  plotBifurcationPlane({{"with", dir + "/with.csv"}}, dir + "/plane.png", BifurcationOptions(),
                       smallOptions());
  expectValidPng(dir + "/plane.png");
  {
    std::ofstream out(dir + "/bad.csv");
    out << "F,T,directions,cycles\n0,0,\"1 0 0 -1 attracting dominant\",\"attracting 1 2\"\n";
  }
  try {
    plotBifurcationForce({{"bad", dir + "/bad.csv"}}, dir + "/bad.png");
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2: a cycle must be"), std::string::npos)
        << e.what();
  }
}

TEST(Plot, Pareto) {
  const std::string dir = tempDir("pareto");
  {
    std::ofstream out(dir + "/bench.csv");
    out << "model,time,error,label\n"
        << "exact,2e-6,1e-3,4 nodes\nexact,4e-6,1e-6,8 nodes\nexact,8e-6,1e-10,16 nodes\n"
        << "ellipsoidal,2e-7,0.05,\nstock,1e-7,0.4,\n";
  }
  plotPareto(dir + "/bench.csv", dir + "/pareto.png", ParetoOptions(), smallOptions());
  expectValidPng(dir + "/pareto.png");
}

TEST(Plot, CsvReadersReturnTheRowsWritten) {
  const std::string dir = tempDir("readers");
  {
    std::ofstream out(dir + "/series.csv");
    out << "# coin\nt,label,slipRatio,r\n0,exact,1.5,2\n0,stock,2.5,2\n0.1, exact ,nan,1.25\n";
  }
  const std::vector<TimeSeries> series = readTimeSeriesCsv(dir + "/series.csv");
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].label, "exact");
  EXPECT_EQ(series[1].label, "stock");
  ASSERT_EQ(series[0].t.size(), 2u);
  EXPECT_EQ(series[0].t[1], 0.1);
  EXPECT_TRUE(std::isnan(series[0].slipRatio[1]));
  EXPECT_EQ(series[0].r[1], 1.25);
  EXPECT_EQ(series[1].slipRatio[0], 2.5);
  {
    std::ofstream out(dir + "/paths.csv");
    out << "label,w1,w2,w3\na,1,0,0\na,0,1,0\nb,0,0,-1\n";
  }
  const std::vector<SpherePath> paths = readSpherePathsCsv(dir + "/paths.csv");
  ASSERT_EQ(paths.size(), 2u);
  ASSERT_EQ(paths[0].w.size(), 2u);
  EXPECT_EQ(paths[0].w[1], Vec3(0, 1, 0));
  EXPECT_EQ(paths[1].w[0], Vec3(0, 0, -1));
  {
    // quoted fields, with a comma and a doubled quote inside
    std::ofstream out(dir + "/limits.csv");
    out << "label,w1,w2,w3,stability,kind\n\"w_1, \"\"a\"\"\",-1,0,0,attracting,isolated\n"
        << "  \"b\" ,0,0,1,repelling,nonhyperbolic\n";
  }
  const std::vector<LimitDirection> limits = readLimitDirectionsCsv(dir + "/limits.csv");
  ASSERT_EQ(limits.size(), 2u);
  EXPECT_EQ(limits[0].label, "w_1, \"a\"");
  EXPECT_EQ(limits[0].w, Vec3(-1, 0, 0));
  EXPECT_EQ(limits[0].stability, Stability::Attracting);
  EXPECT_EQ(limits[0].kind, LimitKind::Isolated);
  EXPECT_EQ(limits[1].label, "b");
  EXPECT_EQ(limits[1].stability, Stability::Repelling);
  EXPECT_EQ(limits[1].kind, LimitKind::Nonhyperbolic);
  {
    std::ofstream out(dir + "/bad.csv");
    out << "w1,w2,w3,stability,kind\n1,0,0,attracting,stable\n";
  }
  EXPECT_THROW(readLimitDirectionsCsv(dir + "/bad.csv"), RenderError);
}

TEST(Plot, ClearErrors) {
  const std::string dir = tempDir("errors");
  // missing gnuplot: the message says what to install
  PlotOptions o = smallOptions();
  o.gnuplot = "/nonexistent/gnuplot";
  try {
    plotPareto(writeSweeps(dir)[0].csvPath, dir + "/x.png", ParetoOptions(), o);
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    // the CSV check comes first: a sweep file has no 'model' column
    EXPECT_NE(std::string(e.what()).find("missing column 'model'"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(dir + "/bench.csv");
    out << "model,time,error\nexact,1e-6,1e-3\n";
  }
  try {
    plotPareto(dir + "/bench.csv", dir + "/x.png", ParetoOptions(), o);
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  // a bad value names file, line and column
  {
    std::ofstream out(dir + "/bad.csv");
    out << "model,time,error\nexact,fast,1e-3\n";
  }
  try {
    plotPareto(dir + "/bad.csv", dir + "/x.png", ParetoOptions(), smallOptions());
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2: 'time' is not a number"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(plotPareto(dir + "/missing.csv", dir + "/x.png"), RenderError);
}

}  // namespace
}  // namespace patchspin::render
