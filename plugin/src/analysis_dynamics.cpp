// Reference slip dynamics of a flat body, Eq. (93), with an adaptive
// Dormand-Prince 5(4) step; `patchspin simulate --engine reference`.
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <patchspin/analysis.hpp>

namespace patchspin {

namespace {

using State = Eigen::Matrix<double, 6, 1>;  // (X, Y, psi, x_g)

Mat2 rotation(double psi) {
  Mat2 R;
  R << std::cos(psi), -std::sin(psi), std::sin(psi), std::cos(psi);
  return R;
}

// Loads at heading psi: force and couple constant in the ground frame.
BodyLoads loadsAt(const BodyLoads& ground, double psi) {
  const Mat2 Rt = rotation(psi).transpose();
  BodyLoads out;
  out.force << Rt * ground.force.head<2>(), ground.force.z();
  out.couple << Rt * ground.couple.head<2>(), ground.couple.z();
  return out;
}

State pack(const BodyState& s) {
  State y;
  y << s.position, s.psi, s.x;
  return y;
}

BodyState unpack(const State& y) {
  BodyState s;
  s.position = y.head<2>();
  s.psi = y[2];
  s.x = y.tail<3>();
  return s;
}

class SlipOde {
 public:
  explicit SlipOde(const FlatBodyModel& model)
      : model_(model), ground_(model.bodyLoads()), Minv_(model.massMatrix().inverse()) {}

  // d/dt (X, Y, psi, x_g). In body axes Eq. (93): M x_b' = Q + Q_e - G x_b;
  // x_g = R(psi) x_b gives x_g' = R (x_b' + omega S x_b), S = [[0,-1],[1,0]].
  State operator()(const State& y) const {
    const double psi = y[2];
    const Mat2 R = rotation(psi);
    Vec3 xb;
    xb << R.transpose() * y.segment<2>(3), y[5];
    const double omega = xb.z() / model_.rho();
    const BodyLoads loads = loadsAt(ground_, psi);
    const double r = xb.norm();
    Vec3 Q = Vec3::Zero();
    if (r > 0.0) Q = model_.contact(xb / r, omega, loads, false).Q;
    const Vec3 xbDot =
        Minv_ * (Q + model_.externalWrench(loads) - model_.gyroscopicMatrix(omega) * xb);
    State d;
    d.head<2>() = y.segment<2>(3);
    d[2] = omega;
    d.segment<2>(3) = R * (xbDot.head<2>() + omega * Vec2(-xb.y(), xb.x()));
    d[5] = xbDot.z();
    return d;
  }

 private:
  const FlatBodyModel& model_;
  BodyLoads ground_;
  Mat3 Minv_;
};

// Dormand-Prince 5(4) tableau.
constexpr double kA[7][6] = {
    {0, 0, 0, 0, 0, 0},
    {1.0 / 5, 0, 0, 0, 0, 0},
    {3.0 / 40, 9.0 / 40, 0, 0, 0, 0},
    {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
constexpr double kB4[7] = {5179.0 / 57600, 0,       7571.0 / 16695, 393.0 / 640, -92097.0 / 339200,
                           187.0 / 2100,   1.0 / 40};

// One step; returns the 5th-order state and the error estimate.
State dpStep(const SlipOde& f, const State& y, const State& k1, double h, State& err, State& k7) {
  State k[7];
  k[0] = k1;
  for (int s = 1; s < 7; ++s) {
    State ys = y;
    for (int j = 0; j < s; ++j) ys += h * kA[s][j] * k[j];
    k[s] = f(ys);
  }
  State y5 = y;
  err.setZero();
  for (int j = 0; j < 7; ++j) {
    if (j < 6) y5 += h * kA[6][j] * k[j];
    err += h * ((j < 6 ? kA[6][j] : 0.0) - kB4[j]) * k[j];
  }
  k7 = k[6];  // first-same-as-last
  return y5;
}

}  // namespace

ReferenceRun integrateReference(const FlatBodyModel& model, const BodyState& initial,
                                const ReferenceOptions& options) {
  internal::requirePositive(options.tMax, "time limit tMax");
  internal::requirePositive(options.recordAt, "record fraction");
  internal::requireFinite(initial.x, "initial slip state");
  const SlipOde f(model);
  const BodyLoads ground = model.bodyLoads();
  ReferenceRun run;
  State y = pack(initial);
  double r0 = initial.x.norm();
  if (r0 == 0.0) {
    if (model.canStick(loadsAt(ground, initial.psi))) {
      run.stopped = true;
      run.final = initial;
      return run;
    }
    // at rest but the loads exceed friction: start along the free acceleration
    const Vec3 a = f(y).tail<3>();
    y.tail<3>() = 1e-12 * a.normalized();
  }
  const double rStart = y.tail<3>().norm();
  const double length = model.rho();
  double t = 0.0;
  State k1 = f(y);
  double h = 1e-3 * rStart / std::max(k1.tail<3>().norm(), 1e-300);
  h = std::min(h, options.tMax);
  double nextSample = 0.0;
  auto sample = [&](double time, const State& s) {
    if (options.sampleDt > 0.0 && time >= nextSample) {
      run.samples.emplace_back(time, unpack(s));
      nextSample = time + options.sampleDt;
    }
  };
  sample(t, y);
  // pressure watch: the smallest pressure on the patch at every step
  const double meanPressure = -ground.force.z() / model.body().shape.area();
  auto track = [&](const State& s) {
    const Mat2 R = rotation(s[2]);
    Vec3 xb;
    xb << R.transpose() * s.segment<2>(3), s[5];
    if (!(xb.norm() > 0.0)) return;
    const ContactState c = model.contact(xb, xb.z() / model.rho(), loadsAt(ground, s[2]), false);
    run.minPressureRatio = std::min(run.minPressureRatio, c.minPressure / meanPressure);
    run.tipping = run.tipping || run.minPressureRatio < -1e-12;
  };
  track(y);
  bool recorded = r0 == 0.0;
  while (t < options.tMax) {
    h = std::min(h, options.tMax - t);
    State err, k7;
    State yNew = dpStep(f, y, k1, h, err, k7);
    // error relative to the current slip speed, so that w stays resolved as r -> 0
    const double r = y.tail<3>().norm();
    const double rScale = std::max(std::min(r, yNew.tail<3>().norm()), 1e-300);
    double e = 0.0;
    for (int i = 0; i < 2; ++i)
      e = std::max(e, std::abs(err[i]) / (options.relTol * (length + std::abs(y[i]))));
    e = std::max(e, std::abs(err[2]) / (options.relTol * (1.0 + std::abs(y[2]))));
    for (int i = 3; i < 6; ++i) e = std::max(e, std::abs(err[i]) / (options.relTol * rScale));
    if (!(e <= 1.0)) {
      h *= std::max(0.1, 0.9 * std::pow(std::isfinite(e) ? e : 1e10, -0.2));
      if (h < 1e-300) break;
      continue;
    }
    double rNew = yNew.tail<3>().norm();
    const bool recordedBefore = recorded;
    if (!recorded && rNew < options.recordAt * r0) {
      // land the step on r = recordAt r0 (secant on the step length)
      const double target = options.recordAt * r0;
      if (rNew < 0.999 * target && r > target) {
        double hTry = h * (r - target) / (r - rNew);
        for (int it = 0; it < 4; ++it) {
          State errTry, k7Try;
          const State yTry = dpStep(f, y, k1, hTry, errTry, k7Try);
          const double rTry = yTry.tail<3>().norm();
          if (std::abs(rTry - target) <= 1e-6 * target || it == 3 || rTry >= r) {
            if (rTry < r) {
              yNew = yTry;
              k7 = k7Try;
              h = hTry;
              rNew = rTry;
            }
            break;
          }
          hTry *= (r - target) / (r - rTry);
        }
      }
      if (rNew < options.recordAt * r0 * (1.0 + 1e-6)) {
        recorded = true;
        run.tRecord = t + h;
        run.recordState = unpack(yNew);
        run.wRecord = yNew.tail<3>() / rNew;
      }
    }
    // turn of the slip velocity up to the record (this step's included: it
    // lands on r = recordAt r0)
    if (!recordedBefore) {
      run.turnRecord += std::remainder(std::atan2(yNew[4], yNew[3]) - std::atan2(y[4], y[3]),
                                       2.0 * std::acos(-1.0));
    }
    t += h;
    y = yNew;
    k1 = k7;
    ++run.steps;
    track(y);
    sample(t, y);
    if (rNew < options.stopFraction * std::max(r0, rStart)) {
      // slip ends at t + r / |r'| (r' -> R* < 0 along the limit direction)
      const Vec3 x = y.tail<3>();
      const double rdot = x.dot(k1.tail<3>()) / rNew;
      if (rdot < 0.0 && model.canStick(loadsAt(ground, y[2]))) {
        run.stopped = true;
        run.tStop = t + rNew / -rdot;
        if (!recorded) {
          recorded = true;
          run.tRecord = t;
          run.recordState = unpack(y);
          run.wRecord = x / rNew;
        }
        y.tail<3>().setZero();
        run.final = unpack(y);
        return run;
      }
    }
    h *= std::min(5.0, std::max(0.2, 0.9 * std::pow(std::max(e, 1e-10), -0.2)));
  }
  run.tStop = t;
  run.final = unpack(y);
  return run;
}

FlatBody flatBodyFromSpec(const SimulationSpec& spec) {
  FlatBody body;
  internal::requirePositive(spec.mass, "mass");
  if (spec.shape == SimulationSpec::Shape::Cylinder) {
    internal::requirePositive(spec.R, "cylinder radius R");
    internal::requirePositive(spec.H, "cylinder height H");
    body.shape = PatchShape::disk(spec.R);
    body.com = Vec3(0.0, 0.0, spec.H / 2.0);
    body.Jz = spec.mass * spec.R * spec.R / 2.0;
  } else {
    internal::requirePositive(spec.LX, "box size LX");
    internal::requirePositive(spec.LY, "box size LY");
    internal::requirePositive(spec.LZ, "box size LZ");
    body.shape = PatchShape::rectangle(spec.LX, spec.LY);
    body.com = Vec3(0.0, 0.0, spec.LZ / 2.0);
    body.Jz = spec.mass * (spec.LX * spec.LX + spec.LY * spec.LY) / 12.0;
  }
  body.mass = spec.mass;
  body.mu = spec.mu;
  body.g = spec.g;
  body.force = spec.force;
  body.torque = spec.torque;
  return body;
}

SimulationResult simulateReference(const SimulationSpec& spec) {
  if (spec.model == "stock") {
    throw Error(
        "model 'stock' is Bullet's own friction: use it with --engine bullet, not reference");
  }
  const Model law = modelFromString(spec.model);
  internal::requireFinite(spec.v0, "initial velocity v0");
  internal::requireFinite(spec.omega0, "initial spin omega0");
  internal::requirePositive(spec.tMax, "time limit t-max");
  internal::requirePositive(spec.dt, "time step dt");
  if (!(spec.recordAt > 0.0 && spec.recordAt < 1.0)) {
    throw Error("record-at must lie in (0, 1): got " + internal::formatDouble(spec.recordAt));
  }
  const FlatBodyModel model(flatBodyFromSpec(spec), law);
  BodyState start;
  start.x = Vec3(spec.v0.x(), spec.v0.y(), model.rho() * spec.omega0);
  ReferenceOptions options;
  options.tMax = spec.tMax;
  options.recordAt = spec.recordAt;
  options.sampleDt = spec.keepTrajectory ? spec.dt : 0.0;
  const ReferenceRun run = integrateReference(model, start, options);

  // output frame: x along the applied force (along v0 without one), z up
  double alpha = 0.0;
  if (spec.force.norm() > 0.0) {
    alpha = std::atan2(spec.force.y(), spec.force.x());
  } else if (spec.v0.norm() > 0.0) {
    alpha = std::atan2(spec.v0.y(), spec.v0.x());
  }
  const Mat2 Rt = rotation(alpha).transpose();
  SimulationResult result;
  result.stopped = run.stopped;
  result.tStop = run.tStop;
  if (run.wRecord.norm() > 0.0) {
    result.wStop << Rt * run.wRecord.head<2>(), run.wRecord.z();
    if (spec.shape == SimulationSpec::Shape::Cylinder) {
      const Vec3& x = run.recordState.x;
      const double omega = x.z() / model.rho();
      result.epsStop = omega != 0.0 ? x.head<2>().norm() / (spec.R * std::abs(omega))
                                    : std::numeric_limits<double>::infinity();
    }
  }
  result.displacement = run.final.position - start.position;
  result.rotation = run.final.psi - start.psi;
  result.turn = run.turnRecord;
  for (const auto& [time, s] : run.samples) {
    SimulationSample sample;
    sample.t = time;
    sample.position = s.position;
    sample.psi = s.psi;
    sample.velocity = s.x.head<2>();
    sample.omega = s.x.z() / model.rho();
    sample.r = s.x.norm();
    if (sample.r > 0.0) sample.w << Rt * (s.x.head<2>() / sample.r), s.x.z() / sample.r;
    result.trajectory.push_back(sample);
  }
  return result;
}

}  // namespace patchspin
