// Per patch: time per friction-block solve against the error of the friction
// impulse it returns, for the ellipsoidal law, the exact law and stock
// Bullet's point friction, over a fixed seeded sample (issue 6).
//
// Sample (per shape: disk R = 5 cm, rectangle 10 x 6 cm, irregular hexagon
// with O off its centroid; kSamples problems each, seed kSeed):
//   slip direction w   uniform on the sphere
//   pressure           linear, Pz = m g, tilted along a random direction by a
//                      random fraction (0 .. 0.95) of the most the patch admits
//   K                  slip mobility diag(1/m, 1/m, gamma/m), gamma = rho^2 m / Jz
//                      in [0.5, 1.5], times I + C with a random symmetric C,
//                      zero diagonal, |C_ij| <= 0.1 (a centre of mass off O):
//                      SPD by diagonal dominance
//   L                  mu Pz dt (mu 0.5, dt 1/60 s)
//   slip magnitude     |s| = kappa |K lambda*|, kappa log-uniform in [1e-2, 1e2]
//                      (from nearly sticking to fast sliding)
// Each problem is built backwards from its answer: the exact block's solution
// is the slip s = |s| w with the impulse lambda* = L q(w), q the exact law, so
// the free slip is b = s - K lambda*. The block is the minimum of a strictly
// convex potential (step.hpp), so lambda* is its unique solution; the
// solvers never see w or lambda*.
//
// Reference: q(w) is the core's exact law (16) at full accuracy
// (FrictionPatch::unitQ, ExactAccuracy tolerance 0), which the tests hold to
// 1e-10 of the brute-force quadrature oracle (largest deviation seen 2e-14,
// tests/core/*exact*_test.cpp). The error of a solve is
//   |lambda - lambda*| / |lambda*|   in Q coordinates (Px, Py, Tz/rho) dt.
// For the exact model it is the block solver's convergence error; for the
// ellipsoidal law and point friction it is the error of the law itself.
//
// Stock Bullet's point friction (no Bullet linked): what
// btSequentialImpulseConstraintSolver does with a flat contact. The manifold
// holds at most 4 points (btPersistentManifold keeps the 4 of largest area):
// the 4 corners of a rectangle, the 4 of the hexagon's vertices spanning the
// largest area, 4 rim points at 0/90/180/270 deg of a disk. The normal load is
// split over the points in proportion to the linear pressure there (clamped
// at 0), so sum n_i = Pz. Bullet's default solver mode has one friction row
// per point (no SOLVER_USE_2_FRICTION_DIRECTIONS), along the point's
// tangential velocity at the start of the solve (here: under the free slip
// b), clamped to |impulse| <= mu n_i dt, solved by projected Gauss-Seidel
// (sequential impulses) with the effective mass 1 / (J K J^T) of each row;
// 10 iterations is Bullet's default (m_numIterations), 4 and 50 bracket it.
// Bullet has no spin friction row by default (m_spinningFriction = 0): spin
// is resisted only through the points' lever arms, as here.
//
// Settings of the block rows: cold start (warmSlip = 0, the first solver
// iteration) or warm (warmSlip = the answer's slip turned by kWarmOffset,
// standing in for the previous iteration's slip), and the block's stopping
// tolerance FrictionBlockInput::tolerance (default 1e-14; the Bullet layer
// uses 1e-9 with float and 1e-12 with double Bullet). That tolerance is the
// block's only accuracy knob: solveFrictionBlock evaluates the exact law at
// full accuracy (unitQ, ExactAccuracy tolerance 0). The law's own knob
// (ExactAccuracy::tolerance, on FrictionPatch::exactQ only) is measured at
// the law level ("law" rows:
// time per Q(w) evaluation and |q - q*| / |q*|), next to the ellipsoidal law
// and the closed-form point-friction law (Q of the points' Coulomb forces,
// with exact directions, i.e. what converged point friction gives while
// slipping).
//
// Time: CPU time per call (the machine is shared; CPU time is what an idle
// core would take).
//
// Output: the Google Benchmark table, then a summary table (median, RMS and
// max error per setting) and, with --csv=PATH, that summary as CSV
// (docs/bench/patch_error.csv): level,shape,model,setting,time_ns,err_median,
// err_rms,err_max,samples.
#include <patchspin/friction_block.hpp>
#include <patchspin/models.hpp>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>

#include "capturing_reporter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace patchspin;

constexpr int kSamples = 256;
constexpr unsigned kSeed = 20261122;
constexpr double kMass = 1.0, kG = 9.81, kMu = 0.5, kDt = 1.0 / 60.0;
constexpr double kPi = 3.14159265358979323846;
// below this point speed [m/s] a contact point has no tangential direction
// (Bullet: lat_rel_vel <= SIMD_EPSILON); it then takes the plane's x axis
constexpr double kPointSpeedFloor = 1e-12;
// warm start of the "warm" block rows: the answer's slip direction turned by
// this angle [rad] about a random axis (a previous solver iteration's slip)
constexpr double kWarmOffset = 0.05;

// ---- stock Bullet point friction ---------------------------------------------

struct PointContact {
  std::vector<Vec2> points;   // manifold points (patch frame) [m]
  std::vector<double> share;  // n_i / Pz, sums to 1
};

// the 4 of the polygon's vertices spanning the largest area (all if <= 4)
std::vector<Vec2> largestQuad(const std::vector<Vec2>& v) {
  if (v.size() <= 4) return v;
  std::vector<Vec2> best;
  double bestArea = -1.0;
  const int n = int(v.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d) {
          const Vec2 q[4] = {v[a], v[b], v[c], v[d]};
          double area = 0.0;
          for (int k = 0; k < 4; ++k)
            area += q[k].x() * q[(k + 1) % 4].y() - q[(k + 1) % 4].x() * q[k].y();
          if (area > bestArea) bestArea = area, best.assign(q, q + 4);
        }
  return best;
}

PointContact pointContact(const PatchShape& shape, const LinearPressure& p) {
  PointContact pc;
  if (shape.isDisk()) {
    for (int k = 0; k < 4; ++k)
      pc.points.push_back(shape.centre() +
                          shape.radius() * Vec2(std::cos(k * kPi / 2), std::sin(k * kPi / 2)));
  } else {
    pc.points = largestQuad(shape.vertices());
  }
  double sum = 0.0;
  for (const Vec2& x : pc.points)
    pc.share.push_back(std::max(p.at(x), 0.0)), sum += pc.share.back();
  for (double& s : pc.share) s /= sum;
  return pc;
}

// row of the point's velocity along d in slip coordinates x_o = (ux, uy, rho wz):
// v = (x0 - x2 y / rho, x1 + x2 x / rho), d.v = J.x_o; the impulse along d
// acts on Q = (Px, Py, Tz / rho) as J^T
Vec3 pointRow(const Vec2& x, const Vec2& d, double rho) {
  return Vec3(d.x(), d.y(), (x.x() * d.y() - x.y() * d.x()) / rho);
}

Vec2 pointDirection(const Vec3& slip, const Vec2& x, double rho) {
  const Vec2 v(slip.x() - slip.z() * x.y() / rho, slip.y() + slip.z() * x.x() / rho);
  const double speed = v.norm();
  return speed > kPointSpeedFloor ? Vec2(v / speed) : Vec2(1.0, 0.0);
}

// Bullet's sequential impulses on the point rows: one block solve
Vec3 solvePointFriction(const PointContact& pc, double rho, const FrictionBlockInput& in,
                        int iterations) {
  constexpr int kMaxPoints = 4;
  const int n = int(pc.points.size());
  std::array<Vec3, kMaxPoints> J, KJ;
  std::array<double, kMaxPoints> mass{}, limit{}, applied{};
  for (int i = 0; i < n; ++i) {
    J[i] = pointRow(pc.points[i], pointDirection(in.b, pc.points[i], rho), rho);
    KJ[i] = in.K * J[i];
    mass[i] = 1.0 / J[i].dot(KJ[i]);
    limit[i] = in.L * pc.share[i];
  }
  Vec3 s = in.b, lambda = Vec3::Zero();
  for (int it = 0; it < iterations; ++it) {
    for (int i = 0; i < n; ++i) {
      const double next = std::clamp(applied[i] - mass[i] * J[i].dot(s), -limit[i], limit[i]);
      const double delta = next - applied[i];
      applied[i] = next;
      lambda += delta * J[i];
      s += delta * KJ[i];
    }
  }
  return lambda;
}

// closed-form point-friction law per unit mu Pz: Coulomb forces at the points
Vec3 pointFrictionQ(const PointContact& pc, double rho, const Vec3& w) {
  Vec3 q = Vec3::Zero();
  for (std::size_t i = 0; i < pc.points.size(); ++i)
    q -= pc.share[i] * pointRow(pc.points[i], pointDirection(w, pc.points[i], rho), rho);
  return q;
}

// ---- the sample ---------------------------------------------------------------

struct Problem {
  FrictionPatch patch;
  PointContact points;
  FrictionBlockInput input;
  Vec3 w;       // slip direction of the exact solution
  Vec3 lambda;  // exact impulse lambda* = L q(w)
  Vec3 q;       // exact unit law q(w)
  Vec3 warm;    // a warm start: the exact slip turned by kWarmOffset rad
};

struct ShapeSample {
  std::string name;
  std::vector<Problem> problems;
};

PatchShape makeShape(int k) {
  if (k == 0) return PatchShape::disk(0.05);
  if (k == 1) return PatchShape::rectangle(0.10, 0.06);
  // irregular convex hexagon, O inside but off the centroid
  return PatchShape::polygon({Vec2(0.06, 0.0), Vec2(0.05, 0.04), Vec2(0.0, 0.055),
                              Vec2(-0.05, 0.03), Vec2(-0.045, -0.035), Vec2(0.01, -0.05)});
}

// linear pressure with total Pz, tilted by `tilt` (0..1) of the admissible maximum along angle
// theta
LinearPressure tiltedPressure(const PatchShape& shape, double Pz, double tilt, double theta) {
  const Vec2 c = shape.centroid(), dir(std::cos(theta), std::sin(theta));
  const double p0 = Pz / shape.area();
  double reach = 0.0;  // largest drop -dir.(x - c) over the patch
  if (shape.isDisk()) {
    reach = shape.radius() - dir.dot(shape.centre() - c);
  } else {
    for (const Vec2& v : shape.vertices()) reach = std::max(reach, -dir.dot(v - c));
  }
  const Vec2 grad = tilt * p0 / reach * dir;
  return LinearPressure{p0 - grad.dot(c), grad.x(), grad.y()};
}

const std::vector<ShapeSample>& sample() {
  static const std::vector<ShapeSample> shapes = [] {
    std::vector<ShapeSample> out;
    const char* names[3] = {"disk", "rectangle", "hexagon"};
    for (int k = 0; k < 3; ++k) {
      std::mt19937 rng(kSeed + k);
      std::normal_distribution<double> normal;
      std::uniform_real_distribution<double> u(0.0, 1.0);
      const PatchShape shape = makeShape(k);
      ShapeSample s{names[k], {}};
      for (int i = 0; i < kSamples; ++i) {
        const Vec3 w = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
        const LinearPressure p = tiltedPressure(shape, kMass * kG, 0.95 * u(rng), 2 * kPi * u(rng));
        FrictionPatch patch(shape, p, kMu);
        const double gamma = 0.5 + u(rng);
        Mat3 coupling = Mat3::Zero();
        for (int a = 0; a < 3; ++a)
          for (int b = a + 1; b < 3; ++b)
            coupling(a, b) = coupling(b, a) = 0.2 * (2 * u(rng) - 1) / 2;
        const Vec3 d(1.0 / kMass, 1.0 / kMass, gamma / kMass);
        const Mat3 K =
            d.cwiseSqrt().asDiagonal() * (Mat3::Identity() + coupling) * d.cwiseSqrt().asDiagonal();
        FrictionBlockInput in;
        in.K = K;
        in.L = kMu * patch.Pz() * kDt;
        const Vec3 q = patch.unitQ(Model::Exact, w);
        const Vec3 lambda = in.L * q;
        const double kappa = std::pow(10.0, -2.0 + 4.0 * u(rng));
        const Vec3 slip = kappa * (K * lambda).norm() * w;
        in.b = slip - K * lambda;
        const Vec3 axis = w.cross(Vec3(normal(rng), normal(rng), normal(rng))).normalized();
        const Vec3 warm =
            slip.norm() * (std::cos(kWarmOffset) * w + std::sin(kWarmOffset) * axis.cross(w));
        s.problems.push_back(Problem{patch, pointContact(shape, p), in, w, lambda, q, warm});
      }
      out.push_back(std::move(s));
    }
    return out;
  }();
  return shapes;
}

// ---- settings -----------------------------------------------------------------

struct Setting {
  std::string level;    // "block" or "law"
  std::string model;    // "ellipsoidal" | "exact" | "stock"
  std::string setting;  // human-readable accuracy setting
  // one evaluation on problem p; returns the impulse (block) or unit law (law)
  std::function<Vec3(const Problem&)> run;
  std::function<Vec3(const Problem&)> reference;
};

std::vector<Setting> settings() {
  std::vector<Setting> s;
  auto blockRef = [](const Problem& p) { return p.lambda; };
  auto lawRef = [](const Problem& p) { return p.q; };
  // block rows: cold (warmSlip = 0) or warm start, at the block's tolerance
  // (FrictionBlockInput::tolerance; 0 = its default 1e-14)
  auto block = [](Model model, bool warm, double tol) {
    return [model, warm, tol](const Problem& p) {
      FrictionBlockInput in = p.input;
      if (warm) in.warmSlip = p.warm;
      in.tolerance = tol;
      return solveFrictionBlock(p.patch, model, in).impulse;
    };
  };
  struct BlockSetting {
    bool warm;
    double tol;
    const char* name;
  };
  const BlockSetting blockSettings[] = {
      {false, 0.0, "cold, tol 1e-14 (default)"}, {false, 1e-12, "cold, tol 1e-12"},
      {false, 1e-9, "cold, tol 1e-9"},           {false, 1e-6, "cold, tol 1e-6"},
      {true, 0.0, "warm, tol 1e-14 (default)"},  {true, 1e-9, "warm, tol 1e-9"}};
  for (Model model : {Model::Ellipsoidal, Model::Exact})
    for (const BlockSetting& b : blockSettings)
      s.push_back({"block", model == Model::Exact ? "exact" : "ellipsoidal", b.name,
                   block(model, b.warm, b.tol), blockRef});
  for (int it : {4, 10, 50}) {
    s.push_back({"block", "stock",
                 "PGS " + std::to_string(it) + " it" + (it == 10 ? " (default)" : ""),
                 [it](const Problem& p) {
                   return solvePointFriction(p.points, p.patch.rho(), p.input, it);
                 },
                 blockRef});
  }
  s.push_back({"law", "ellipsoidal", "-",
               [](const Problem& p) { return p.patch.unitQ(Model::Ellipsoidal, p.w); }, lawRef});
  for (int e : {4, 7, 10}) {
    const double tol = std::pow(10.0, -e);
    s.push_back({"law", "exact", "tol 1e-" + std::to_string(e),
                 [tol](const Problem& p) {
                   return Vec3(p.patch.exactQ(p.w, nullptr, ExactAccuracy{tol}) /
                               (p.patch.mu() * p.patch.Pz()));
                 },
                 lawRef});
  }
  s.push_back({"law", "stock", "point Coulomb (closed form)",
               [](const Problem& p) { return pointFrictionQ(p.points, p.patch.rho(), p.w); },
               lawRef});
  return s;
}

struct ErrorStats {
  double median = 0, rms = 0, max = 0;
};

ErrorStats measureErrors(const Setting& set, const ShapeSample& shape) {
  std::vector<double> e;
  for (const Problem& p : shape.problems) {
    const Vec3 ref = set.reference(p);
    e.push_back((set.run(p) - ref).norm() / ref.norm());
  }
  ErrorStats st;
  double sq = 0;
  for (double x : e) sq += x * x, st.max = std::max(st.max, x);
  st.rms = std::sqrt(sq / double(e.size()));
  std::nth_element(e.begin(), e.begin() + long(e.size() / 2), e.end());
  st.median = e[e.size() / 2];
  return st;
}

// ---- reporting ------------------------------------------------------------------

struct Row {
  std::string level, shape, model, setting;
  ErrorStats err;
  double timeNs = 0;
};
std::map<std::string, Row> gRows;  // by benchmark name

void captureRun(const benchmark::BenchmarkReporter::Run& r) {
  auto it = gRows.find(r.benchmark_name());
  if (it != gRows.end())
    it->second.timeNs =
        r.GetAdjustedCPUTime() * 1e9 / benchmark::GetTimeUnitMultiplier(r.time_unit);
}

}  // namespace

int main(int argc, char** argv) {
  // our own flag: --csv=PATH
  std::string csvPath;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--csv=", 6) == 0)
      csvPath = argv[i] + 6;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;

  const auto& shapes = sample();
  const std::vector<Setting> all = settings();
  for (const ShapeSample& shape : shapes) {
    for (const Setting& set : all) {
      std::string name = set.level + "/" + shape.name + "/" + set.model + "/" + set.setting;
      for (char& c : name)
        if (c == ' ') c = '_';
      Row row{set.level, shape.name, set.model, set.setting, measureErrors(set, shape), 0.0};
      gRows[name] = row;
      benchmark::RegisterBenchmark(name.c_str(), [&set, &shape, row](benchmark::State& state) {
        std::size_t i = 0;
        for (auto _ : state) {
          benchmark::DoNotOptimize(set.run(shape.problems[i]));
          if (++i == shape.problems.size()) i = 0;
        }
        state.counters["err_median"] = row.err.median;
        state.counters["err_max"] = row.err.max;
      });
    }
  }
  patchspin::bench::CapturingReporter reporter(captureRun);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  // summary in sample order (the map is sorted by name)
  std::vector<const Row*> rows;
  for (const ShapeSample& shape : shapes)
    for (const Setting& set : all)
      for (const auto& kv : gRows)
        if (kv.second.shape == shape.name && kv.second.level == set.level &&
            kv.second.model == set.model && kv.second.setting == set.setting &&
            kv.second.timeNs > 0)
          rows.push_back(&kv.second);
  std::printf(
      "\nPer patch, %d seeded problems per shape (seed %u). Error: |lambda - lambda*| / |lambda*| "
      "of the\n"
      "block's impulse (level block) or |q - q*| / |q*| of the law (level law); * = exact law "
      "(16),\n"
      "full accuracy. CPU time per block solve / per law evaluation, cycling through the "
      "sample.\n\n",
      kSamples, kSeed);
  std::printf("%-6s %-10s %-12s %-28s %10s %11s %11s %11s\n", "level", "shape", "model", "setting",
              "time [ns]", "err median", "err rms", "err max");
  for (const Row* r : rows)
    std::printf("%-6s %-10s %-12s %-28s %10.1f %11.3g %11.3g %11.3g\n", r->level.c_str(),
                r->shape.c_str(), r->model.c_str(), r->setting.c_str(), r->timeNs, r->err.median,
                r->err.rms, r->err.max);
  if (!csvPath.empty()) {
    std::ofstream f(csvPath);
    if (!f) {
      std::fprintf(stderr, "bench_patch_error: cannot write %s\n", csvPath.c_str());
      return 1;
    }
    f << "level,shape,model,setting,time_ns,err_median,err_rms,err_max,samples\n";
    char line[512];
    for (const Row* r : rows) {
      std::snprintf(line, sizeof line, "%s,%s,%s,\"%s\",%.6g,%.6g,%.6g,%.6g,%d\n", r->level.c_str(),
                    r->shape.c_str(), r->model.c_str(), r->setting.c_str(), r->timeNs,
                    r->err.median, r->err.rms, r->err.max, kSamples);
      f << line;
    }
    std::printf("\nwrote %s\n", csvPath.c_str());
  }
  return 0;
}
