// Limit directions of a flat body, Sect. 3.3 and 5.5-5.6: fixed points of
// the fast dynamics w' = V*(w) on the unit sphere, their rate R* and type.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <complex>
#include <patchspin/analysis.hpp>
#include <string>

namespace patchspin {

namespace {

// Relative tolerances (scale: the size of the limit field, ~ mu g).
constexpr double kRealTol = 1e-5;       // |Im| of a (111) eigenvalue still tried as real: split
                                        // double roots have |Im| ~ sqrt(eps); false hits are
                                        // discarded by the Newton polish below
constexpr double kSingularTol = 1e-7;   // singular value of (rdot I - B) taken as zero
constexpr double kResidualTol = 1e-11;  // accepted |(rdot I - B) w - c| (issue: 1e-10)
constexpr double kSameTol = 1e-7;       // two unit directions closer than this are one
constexpr double kHyperTol = 1e-8;      // |Re lambda| or |R*| below this: nonhyperbolic

// Orthonormal basis (columns) of the tangent plane of the sphere at w.
Eigen::Matrix<double, 3, 2> tangentBasis(const Vec3& w) {
  // start from the coordinate axis least aligned with w
  Vec3 best = Vec3::UnitX();
  double lowest = std::abs(w.x());
  if (std::abs(w.y()) < lowest) best = Vec3::UnitY(), lowest = std::abs(w.y());
  if (std::abs(w.z()) < lowest) best = Vec3::UnitZ();
  Eigen::Matrix<double, 3, 2> E;
  E.col(0) = (best - best.dot(w) * w).normalized();
  E.col(1) = w.cross(E.col(0));
  return E;
}

double fieldScale(const FlatBodyModel& model) {
  const BodyLoads loads = model.bodyLoads();
  const Mat3& M = model.massMatrix();
  const Mat3 Minv = M.inverse();
  const double Pz = -loads.force.z();
  return model.body().mu * std::abs(Pz) * Minv.norm() +
         (Minv * model.externalWrench(loads)).norm() + 1e-300;
}

LimitType typeOf(double rdot, const Eigen::Vector2cd& lambda, double scale) {
  // Def. 2, Eq. (32)-(34)
  const double tol = kHyperTol * scale;
  const double a = lambda[0].real(), b = lambda[1].real();
  if (std::abs(rdot) <= tol || std::abs(a) <= tol || std::abs(b) <= tol) {
    return LimitType::Nonhyperbolic;
  }
  const double ra = rdot * a, rb = rdot * b;
  if (std::min(ra, rb) > 0.0) return LimitType::Dominant;
  if (std::max(ra, rb) < 0.0) return LimitType::Isolated;
  return LimitType::Saddle;
}

Eigen::Vector2cd eigenvalues2(const Mat2& J) {
  // of J / c, times c: tr^2 and det square the entries, which overflowed
  // for a field scale ~1e154 (found by fuzzing: inf eigenvalues)
  const double c = J.cwiseAbs().maxCoeff();
  if (!(c > 0.0) || !std::isfinite(c)) return Eigen::Vector2cd(J(0, 0), J(1, 1));
  const Mat2 Js = J / c;
  const double tr = Js.trace(), det = Js.determinant();
  const std::complex<double> disc = std::sqrt(std::complex<double>(tr * tr / 4.0 - det, 0.0));
  Eigen::Vector2cd out;
  out[0] = c * (tr / 2.0 - disc);
  out[1] = c * (tr / 2.0 + disc);
  if (out[0].real() > out[1].real()) std::swap(out[0], out[1]);
  return out;
}

// Adds w unless an equal direction is already listed (keeps the better one).
void addUnique(std::vector<LimitDirection>& list, const LimitDirection& d) {
  for (LimitDirection& e : list) {
    if ((e.w - d.w).norm() < kSameTol) {
      if (d.residual < e.residual) e = d;
      return;
    }
  }
  list.push_back(d);
}

bool onContinuum(const std::vector<LimitContinuum>& continua, const Vec3& w) {
  for (const LimitContinuum& c : continua) {
    if (c.sphere || std::abs(c.normal.dot(w) - c.offset) < 1e-8) return true;
  }
  return false;
}

// Newton on (w, rdot) for (rdot I - B) w = c, |w| = 1.
bool polishLinear(const Mat3& B, const Vec3& c, Vec3& w, double& rdot, double scale) {
  for (int it = 0; it < 30; ++it) {
    const Vec3 f = (rdot * Mat3::Identity() - B) * w - c;
    const double g = 0.5 * (1.0 - w.squaredNorm());
    if (f.norm() <= 1e-15 * scale && std::abs(g) <= 1e-16) break;
    Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
    J.topLeftCorner<3, 3>() = rdot * Mat3::Identity() - B;
    J.topRightCorner<3, 1>() = w;
    J.bottomLeftCorner<1, 3>() = -w.transpose();
    Eigen::Vector4d rhs;
    rhs << -f, -g;
    const Eigen::Vector4d step = J.fullPivLu().solve(rhs);
    if (!step.allFinite()) break;
    w += step.head<3>();
    rdot += step[3];
    if (step.norm() <= 1e-16 * (1.0 + std::abs(rdot))) break;
  }
  w.normalize();
  return ((rdot * Mat3::Identity() - B) * w - c).norm() <= kResidualTol * scale;
}

void solveLinear(const FlatBodyModel& model, LimitAnalysis& out) {
  const Mat3 B = model.linearB();
  const Vec3 c = model.linearC();
  const double scale = B.norm() + c.norm() + 1e-300;
  std::vector<LimitDirection> found;

  if (c.norm() <= 1e-14 * scale) {
    // Prop. 1: c = 0, eigenvectors of B; Prop. 3: a 2-d eigenspace is a circle
    Eigen::EigenSolver<Mat3> es(B);
    std::vector<double> seen;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(es.eigenvalues()[i].imag()) > kRealTol * scale) continue;
      const double lambda = es.eigenvalues()[i].real();
      if (std::any_of(seen.begin(), seen.end(),
                      [&](double s) { return std::abs(s - lambda) < 1e-8 * scale; })) {
        continue;
      }
      seen.push_back(lambda);
      Eigen::JacobiSVD<Mat3> svd(lambda * Mat3::Identity() - B, Eigen::ComputeFullV);
      const Vec3 sv = svd.singularValues();
      int nullity = 0;
      for (int k = 0; k < 3; ++k) nullity += sv[k] <= kSingularTol * scale ? 1 : 0;
      nullity = std::max(nullity, 1);
      if (nullity == 3) {
        LimitContinuum s;
        s.sphere = true;
        s.rdot = lambda;
        s.attracting = lambda < 0.0;
        out.continua.push_back(s);
      } else if (nullity == 2) {
        LimitContinuum circle;
        circle.normal = svd.matrixV().col(0);
        circle.offset = 0.0;
        circle.rdot = lambda;
        circle.attracting = lambda < 0.0;
        out.continua.push_back(circle);
      } else {
        const Vec3 n = svd.matrixV().col(2);
        for (double sign : {1.0, -1.0}) found.push_back(classifyDirection(model, sign * n));
      }
    }
  } else {
    // Eq. (111): real eigenvalues rdot of the 6x6 problem give the candidates
    Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
    C.topRightCorner<3, 3>() = Mat3::Identity();
    C.bottomLeftCorner<3, 3>() = c * c.transpose() - B * B.transpose();
    C.bottomRightCorner<3, 3>() = B + B.transpose();
    Eigen::EigenSolver<Eigen::Matrix<double, 6, 6>> es(C, false);
    for (int i = 0; i < 6; ++i) {
      if (std::abs(es.eigenvalues()[i].imag()) > kRealTol * scale) continue;
      const double rdot0 = es.eigenvalues()[i].real();
      Eigen::JacobiSVD<Mat3> svd(rdot0 * Mat3::Identity() - B,
                                 Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Vec3 sv = svd.singularValues();
      // minimum-norm solution over the nonsingular part, null space apart
      Vec3 wp = Vec3::Zero();
      std::vector<Vec3> nulls;
      for (int k = 0; k < 3; ++k) {
        if (sv[k] > kSingularTol * scale) {
          wp += svd.matrixV().col(k) * (svd.matrixU().col(k).dot(c) / sv[k]);
        } else {
          nulls.push_back(svd.matrixV().col(k));
        }
      }
      std::vector<Vec3> candidates;
      const double a2 = 1.0 - wp.squaredNorm();
      if (nulls.empty()) {
        candidates.push_back(wp);
      } else if (nulls.size() == 1) {
        // rdot is an eigenvalue of B: w = wp + alpha n with |w| = 1
        if (a2 > -1e-6) {
          const double alpha = std::sqrt(std::max(a2, 0.0));
          candidates.push_back(wp + alpha * nulls[0]);
          candidates.push_back(wp - alpha * nulls[0]);
        }
      } else if (nulls.size() == 2 && a2 > 1e-12 &&
                 ((rdot0 * Mat3::Identity() - B) * wp - c).norm() <= kResidualTol * scale) {
        // a 2-d eigenspace with c in range: a circle of limit directions
        LimitContinuum circle;
        circle.normal = svd.matrixV().col(0);
        circle.offset = circle.normal.dot(wp);
        circle.rdot = rdot0;
        circle.attracting = rdot0 < 0.0;
        bool known = false;
        for (const LimitContinuum& e : out.continua) {
          known = known || (std::abs(std::abs(e.normal.dot(circle.normal)) - 1.0) < 1e-9 &&
                            std::abs(e.rdot - circle.rdot) < 1e-8 * scale);
        }
        if (!known) out.continua.push_back(circle);
      }
      for (Vec3 w : candidates) {
        if (!(w.norm() > 0.1)) continue;
        double rdot = rdot0;
        if (!polishLinear(B, c, w, rdot, scale)) continue;
        LimitDirection d = classifyDirection(model, w);
        d.residual = ((rdot * Mat3::Identity() - B) * w - c).norm();
        addUnique(found, d);
      }
    }
  }
  for (const LimitDirection& d : found) {
    if (!onContinuum(out.continua, d.w)) addUnique(out.directions, d);
  }
}

// Newton on the sphere for V*(w) = 0: tangent step from J2 (projected (31)).
bool newtonSphere(const FlatBodyModel& model, Vec3& w, double scale) {
  for (int it = 0; it < 60; ++it) {
    Mat3 D;
    const Vec3 Fo = model.limitField(w, &D);
    const Eigen::Matrix<double, 3, 2> E = tangentBasis(w);
    const Eigen::Vector2d g = E.transpose() * Fo;
    if (g.norm() <= 1e-14 * scale) return true;
    const Mat2 J = E.transpose() * D * E - w.dot(Fo) * Mat2::Identity();
    Eigen::Vector2d step = J.fullPivLu().solve(-g);
    if (!step.allFinite()) return false;
    const double len = step.norm();
    if (len > 0.3) step *= 0.3 / len;  // trust region on the sphere [rad]
    w = (w + E * step).normalized();
    if (len <= 1e-15) break;
  }
  Mat3 D;
  const Vec3 Fo = model.limitField(w, &D);
  return (Fo - w.dot(Fo) * w).norm() <= kResidualTol * scale;
}

void solveNonlinear(const FlatBodyModel& model, const LimitOptions& options, LimitAnalysis& out) {
  const double scale = fieldScale(model);
  std::vector<LimitDirection> found;
  // detectContinua's cache (below)
  std::size_t cachedSize = 0;
  bool cacheValid = false;
  std::pair<std::vector<LimitContinuum>, std::vector<LimitDirection>> cached;
  auto search = [&](const std::vector<Vec3>& seeds) {
    for (Vec3 w : seeds) {
      if (!newtonSphere(model, w, scale)) continue;
      LimitDirection d = classifyDirection(model, w);
      addUnique(found, d);
    }
    cacheValid = false;  // (addUnique may also replace an entry)
  };
  auto ringsAround = [&](const std::vector<LimitDirection>& points) {
    // seeds close to known points find partners born in pitchforks
    // (around at most kMaxRingAnchors points: a body has a handful of limit
    // directions, and hundreds of found points are the nonhyperbolic points
    // of a degenerate field, where 24 seeds each, 3312 for one body, cost
    // 10 s under the fuzzer; found by profiling)
    constexpr std::size_t kMaxRingAnchors = 24;
    std::vector<Vec3> seeds;
    for (std::size_t i = 0; i < std::min(points.size(), kMaxRingAnchors); ++i) {
      const LimitDirection& d = points[i];
      const Eigen::Matrix<double, 3, 2> E = tangentBasis(d.w);
      for (double radius : {1e-3, 1e-2, 5e-2}) {
        for (int k = 0; k < 8; ++k) {
          const double a = 2.0 * M_PI * k / 8.0;
          seeds.push_back(
              (d.w + radius * (std::cos(a) * E.col(0) + std::sin(a) * E.col(1))).normalized());
        }
      }
    }
    return seeds;
  };
  // continua: many nonhyperbolic points with one rate on one plane (cached
  // until `found` changes: the search below asks up to four times, and with
  // many nonhyperbolic points the plane search is cubic in their number)
  auto detectContinuaUncached = [&]() {
    std::vector<LimitContinuum> continua;
    std::vector<bool> used(found.size(), false), grouped(found.size(), false);
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (used[i] || grouped[i] || found[i].type != LimitType::Nonhyperbolic) continue;
      std::vector<std::size_t> group;
      for (std::size_t j = i; j < found.size(); ++j) {
        if (!used[j] && !grouped[j] && found[j].type == LimitType::Nonhyperbolic &&
            std::abs(found[j].rdot - found[i].rdot) < 1e-6 * scale) {
          group.push_back(j);
          grouped[j] = true;
        }
      }
      // split the group into circles: planes through three of its points with
      // the most members (two circles may share one rate by symmetry). A
      // point on no circle is dropped as the anchor and the next one tried,
      // kMaxTries times in all per group: each try costs |group|^2 tests
      // (found by profiling: a degenerate field with 500 nonhyperbolic points
      // on no circle, where every point of a rate group formed the same
      // group again and failed again, 3 s per body under the fuzzer)
      constexpr int kMaxTries = 8;
      int tries = 0;
      while (group.size() >= 4 && tries++ < kMaxTries) {
        std::vector<std::size_t> best;
        const Vec3 p = found[group[0]].w;
        // planes through p, one of the next kAnchors points, and any other:
        // a circle through p with a share of the group has one of its points
        // among them (all pairs cost |group|^3 membership tests: with the
        // hundreds of nonhyperbolic points of a degenerate field, seconds per
        // body under the fuzzer; found by profiling the limits target)
        constexpr std::size_t kAnchors = 8;
        const std::size_t anchorEnd = std::min(group.size(), kAnchors + 1);
        for (std::size_t a = 1; a < anchorEnd; ++a) {
          for (std::size_t b = a + 1; b < group.size(); ++b) {
            Vec3 n = (found[group[a]].w - p).cross(found[group[b]].w - p);
            if (n.norm() < 1e-6) continue;
            n.normalize();
            std::vector<std::size_t> members;
            for (std::size_t j : group) {
              if (std::abs(n.dot(found[j].w - p)) < 1e-6) members.push_back(j);
            }
            if (members.size() > best.size()) best = members;
            if (best.size() == group.size()) break;  // cannot do better
          }
          if (best.size() == group.size()) break;
        }
        if (best.size() < 4) {
          group.erase(group.begin());  // the anchor is on no circle
          continue;
        }
        Vec3 mean = Vec3::Zero();
        for (std::size_t j : best) mean += found[j].w;
        mean /= static_cast<double>(best.size());
        Eigen::MatrixXd P(static_cast<Eigen::Index>(best.size()), 3);
        for (std::size_t k = 0; k < best.size(); ++k) {
          P.row(static_cast<Eigen::Index>(k)) = (found[best[k]].w - mean).transpose();
        }
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(P, Eigen::ComputeThinV);
        LimitContinuum circle;
        circle.normal = svd.matrixV().col(2);
        circle.offset = circle.normal.dot(mean);
        if (circle.offset < -1e-12 || (circle.offset < 1e-12 && circle.normal.z() < 0.0)) {
          circle.normal = -circle.normal;
          circle.offset = -circle.offset;
        }
        circle.rdot = found[i].rdot;
        circle.attracting = circle.rdot < 0.0;
        continua.push_back(circle);
        for (std::size_t j : best) used[j] = true;
        std::vector<std::size_t> rest;
        for (std::size_t j : group) {
          if (!used[j]) rest.push_back(j);
        }
        group = rest;
      }
    }
    std::vector<LimitDirection> isolated;
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (!used[i]) isolated.push_back(found[i]);
    }
    return std::make_pair(continua, isolated);
  };
  auto detectContinua = [&]() {
    if (!cacheValid || cachedSize != found.size()) {
      cached = detectContinuaUncached();
      cachedSize = found.size();
      cacheValid = true;
    }
    return cached;
  };
  auto consistent = [&]() {
    const auto [continua, isolated] = detectContinua();
    if (!continua.empty()) return true;
    int sum = 0;
    for (const LimitDirection& d : isolated) {
      if (d.type == LimitType::Nonhyperbolic) return false;
      sum += d.type == LimitType::Saddle ? -1 : 1;
    }
    return sum == 2;
  };
  search(internal::fibonacciSphere(std::max(options.seeds, 20)));
  if (detectContinua().first.empty()) search(ringsAround(found));
  if (!consistent()) {
    search(internal::fibonacciSphere(4 * std::max(options.seeds, 20)));
    if (detectContinua().first.empty()) search(ringsAround(found));
  }
  auto [continua, isolated] = detectContinua();
  out.continua = continua;
  out.directions = isolated;
}

}  // namespace

const char* toString(LimitType type) {
  switch (type) {
    case LimitType::Dominant:
      return "dominant";
    case LimitType::Isolated:
      return "isolated";
    case LimitType::Saddle:
      return "saddle";
    case LimitType::Nonhyperbolic:
      return "nonhyperbolic";
  }
  return "nonhyperbolic";
}

double LimitContinuum::radius() const {
  return sphere ? 1.0 : std::sqrt(std::max(0.0, 1.0 - offset * offset));
}

LimitDirection classifyDirection(const FlatBodyModel& model, const Vec3& wIn) {
  const Vec3 w = wIn.normalized();
  const double scale = fieldScale(model);
  Mat3 D;
  const Vec3 Fo = model.limitField(w, &D);
  LimitDirection d;
  d.w = w;
  d.rdot = w.dot(Fo);  // Eq. (103)
  d.attracting = d.rdot < 0.0;
  d.residual = (Fo - d.rdot * w).norm();
  // Eq. (31) at a fixed point: V_w = P D P - R* P, P = I - w w^T; on the
  // tangent plane (basis E) this is J2 = E^T D E - R* I.
  const Eigen::Matrix<double, 3, 2> E = tangentBasis(w);
  const Mat2 J = E.transpose() * D * E - d.rdot * Mat2::Identity();
  d.eigenvalues = eigenvalues2(J);
  d.type = typeOf(d.rdot, d.eigenvalues, scale);
  d.minPressure = model.contact(w, 0.0, model.bodyLoads(), false).minPressure;
  return d;
}

namespace {

// Exponent (ilogb) of |x|, or kNoExponent for 0.
constexpr int kNoExponent = -100000;
int exponentOf(double x) {
  return x == 0.0 ? kNoExponent : std::ilogb(std::abs(x));
}

LimitAnalysis solveAtScale(const FlatBodyModel& model, const LimitOptions& options);

// The limit field F_o = M^-1 (Q(w) + Q_e) is linear in the loads (gravity,
// force, couple: the pressure, hence Q, is linear in them) and in M^-1. With
// loads times 2^-eL and m, Jz, Jxz, Jyz times 2^eM (g times 2^(-eL - eM), so
// that m g scales as the loads) it is F_o times 2^(-eL - eM): the same
// directions, with rates, eigenvalues and residuals times 2^(-eL - eM) and
// pressures times 2^-eL (powers of two: exact). Far from unit scale the
// directions are found at unit scale (found by fuzzing: fields of 1e-300
// made every direction a fixed point to round-off, fields of 1e283 and
// tipping couples of 6.8e283 overflowed the residual to inf, a denormal Jz
// ran for 11 s).
LimitAnalysis solveNormalised(const FlatBodyModel& model, const LimitOptions& options) {
  const FlatBody& body = model.body();
  const double rho = model.rho();
  // load exponents, as forces: couples over the shorter of max|r| and rho,
  // the weight and the force with the lever |r_c| / that length
  const int eLength = std::min(exponentOf(body.shape.maxDistanceFromOrigin()), exponentOf(rho));
  const int eWeight = exponentOf(body.mass) + exponentOf(body.g);
  const int eForce = std::max(exponentOf(body.force.x()), exponentOf(body.force.y()));
  const int eTipping = std::max(exponentOf(body.torque.x()), exponentOf(body.torque.y()));
  const int eSpin = exponentOf(body.torque.z());
  const int eCom =
      std::max({exponentOf(body.com.x()), exponentOf(body.com.y()), exponentOf(body.com.z())});
  const int eLever = eCom == kNoExponent ? 0 : std::max(0, eCom - eLength);
  auto plus = [](int e, int d) { return e == kNoExponent ? kNoExponent : e + d; };
  // the pressure's loads (weight, tipping couples, force on its lever) set
  // the friction part mu ∫|p| of the field, through all of M^-1 =
  // W^-1 diag(1/m, 1/m, 1/Jz) W^-T, W^-1 = [[1, 0, yc], [0, 1, -xc],
  // [0, 0, rho]]; the force acts through 1/m and off^2 / Jz, the spin couple
  // T_z through off / Jz. The larger part is brought to unit scale (found by
  // fuzzing: mu = 2.6e-231 with g = 4e289 left a field of 1e-231 at unit
  // loads, directions off by 2e-3 of the field; T_z = 1.9e185 against
  // Jz = 1e300, a field part of 1e-115, set the scale while friction's was
  // 1e8)
  const int ePressure = std::max({eWeight, plus(eForce, eLever), plus(eTipping, -eLength)});
  const int eOffset =
      std::max({exponentOf(body.com.x()), exponentOf(body.com.y()), exponentOf(rho)});
  const int eMass = std::max(-exponentOf(body.mass), 2 * eOffset - exponentOf(body.Jz));
  const int eMu = exponentOf(body.mu);
  const int eFrictionField = eMu == kNoExponent ? kNoExponent : ePressure + eMu + eMass;
  // the external field M^-1 Q_e, Q_e = (P_x, P_y, (T_z + x_c P_y - y_c P_x)
  // / rho), and M^-1 involve x_c and y_c only: z_c is a lever of the
  // pressure (tipping couples, above), not of this field (found by fuzzing:
  // with z_c = 1.7e266 and P_x = 0.5 the lever with z_c put this field at
  // 2^884, the loads were scaled by 2^-883, the friction field, mu = 1.7e-279
  // against g = 4.3e300, came out ~1e-245, B B^T of (111) underflowed and a
  // direction was 1.4e-3 of the field off the fixed point)
  const int eComXY = std::max(exponentOf(body.com.x()), exponentOf(body.com.y()));
  const int eLeverXY = eComXY == kNoExponent ? 0 : std::max(0, eComXY - eLength);
  const int eExternalField =
      std::max(plus(plus(eForce, eLeverXY), eMass), plus(eSpin, eOffset - exponentOf(body.Jz)));
  int eLoad = std::max(eFrictionField, eExternalField);
  eLoad = eLoad == kNoExponent ? ePressure : eLoad - eMass;
  // (not beyond pressures of 2^600 at unit scale: mu of 1e-300 stays tiny)
  constexpr int kMaxPressureExponent = 600;
  eLoad = std::max(eLoad, ePressure - kMaxPressureExponent);
  constexpr int kUnitRange = 100;  // 2^100 ~ 1e30: well inside double's range
  if (std::abs(eLoad) <= kUnitRange && std::abs(eMass) <= kUnitRange) {
    // (its output checked as the scaled path's below: found by fuzzing, com
    // 9e117 m off O with Jz = 1.9e215 stayed at its own scale and returned a
    // rate of inf, where the field itself overflows)
    LimitAnalysis out = solveAtScale(model, options);
    for (const LimitDirection& d : out.directions) {
      if (!std::isfinite(d.rdot) || !d.eigenvalues.allFinite() || !std::isfinite(d.residual) ||
          !std::isfinite(d.minPressure))
        throw Error("limit directions: the limit field overflows double (rate " +
                    internal::formatDouble(d.rdot) + ")");
    }
    for (const LimitContinuum& c : out.continua) {
      if (!std::isfinite(c.rdot)) throw Error("limit directions: the limit field overflows double");
    }
    return out;
  }

  FlatBody unit = body;
  unit.rho = rho;
  unit.mass = std::ldexp(body.mass, eMass);
  unit.Jz = std::ldexp(body.Jz, eMass);
  unit.Jxz = std::ldexp(body.Jxz, eMass);
  unit.Jyz = std::ldexp(body.Jyz, eMass);
  unit.g = std::ldexp(body.g, -eLoad - eMass);
  unit.force = Vec2(std::ldexp(body.force.x(), -eLoad), std::ldexp(body.force.y(), -eLoad));
  unit.torque = Vec3(std::ldexp(body.torque.x(), -eLoad), std::ldexp(body.torque.y(), -eLoad),
                     std::ldexp(body.torque.z(), -eLoad));
  const bool inRange = std::isnormal(unit.mass) && std::isnormal(unit.Jz) && std::isnormal(unit.g);
  if (!inRange) {
    throw Error("limit directions: the body's mass and loads span more than double's range (m " +
                internal::formatDouble(body.mass) + ", Jz " + internal::formatDouble(body.Jz) +
                ", g " + internal::formatDouble(body.g) + ")");
  }
  LimitAnalysis out = solveAtScale(FlatBodyModel(unit, model.model()), options);
  // back to the body's own scale (F_o times 2^(eLoad + eMass))
  const int eField = eLoad + eMass;
  for (LimitDirection& d : out.directions) {
    d.rdot = std::ldexp(d.rdot, eField);
    d.residual = std::ldexp(d.residual, eField);
    d.eigenvalues =
        Eigen::Vector2cd(std::complex<double>(std::ldexp(d.eigenvalues[0].real(), eField),
                                              std::ldexp(d.eigenvalues[0].imag(), eField)),
                         std::complex<double>(std::ldexp(d.eigenvalues[1].real(), eField),
                                              std::ldexp(d.eigenvalues[1].imag(), eField)));
    d.minPressure = std::ldexp(d.minPressure, eLoad);
    if (!std::isfinite(d.rdot) || !d.eigenvalues.allFinite() || !std::isfinite(d.residual) ||
        !std::isfinite(d.minPressure)) {
      throw Error("limit directions: the limit field overflows double (rate " +
                  internal::formatDouble(d.rdot) + " at unit scale times 2^" +
                  std::to_string(eField) + ")");
    }
  }
  for (LimitContinuum& c : out.continua) {
    c.rdot = std::ldexp(c.rdot, eField);
    if (!std::isfinite(c.rdot)) throw Error("limit directions: the limit field overflows double");
  }
  return out;
}

}  // namespace

namespace {
// A body whose centre of mass lies more than kMaxComOffset radii of
// gyration sqrt(Jz / m) from O, horizontally, has a mass matrix (91),
// M = W^T diag(m, m, Jz) W, with a unit-diagonal condition of ~4 (1 + m
// (xc^2 + yc^2) / Jz): from 1e5 (cond 4e10) its inverse has no digits and
// neither has the limit field, which acts through it (found by fuzzing:
// com 1.3e5 to 1.7e10 m from a 0.5 m disk with Jz = 0.5 kg m^2, tiny mu:
// directions 1e-3 to 1 of the field off the fixed point). A physical body
// touches the ground within its own size, a few radii of gyration.
constexpr double kMaxComOffset = 1e5;
void requireResolvableMassMatrix(const FlatBody& body) {
  const double offset = std::hypot(body.com.x(), body.com.y());
  const double gyration = std::sqrt(body.Jz) / std::sqrt(body.mass);
  if (!(offset <= kMaxComOffset * gyration)) {
    throw Error("limit directions: the centre of mass lies " + internal::formatDouble(offset) +
                " m from O, more than 1e5 radii of gyration (" + internal::formatDouble(gyration) +
                " m): the mass matrix is numerically singular");
  }
}
}  // namespace

LimitAnalysis findLimitDirections(const FlatBodyModel& model, const LimitOptions& options) {
  requireResolvableMassMatrix(model.body());
  return solveNormalised(model, options);
}

namespace {

// Friction negligible against the external wrench: F_o = c + f(w) with
// |f| <= kNegligibleFriction |c|, so every fixed point lies within that angle
// of +-c^ (F_o parallel to w), one near each (the tangential Jacobian there,
// -R* P for f = 0, is regular): Newton from +-c^ finds both. With mu = 0 and
// no external wrench the field vanishes: every direction is a limit
// direction, the sphere continuum with rate 0.
constexpr double kNegligibleFriction = 1e-10;
// Below this (at unit loads and M^-1: a friction coefficient near the
// smallest normal double) the field has no digits to resolve directions.
constexpr double kUnresolvableField = 1e-280;

bool solveDegenerate(const FlatBodyModel& model, LimitAnalysis& out) {
  const BodyLoads loads = model.bodyLoads();
  const Mat3 Minv = model.massMatrix().inverse();
  const Vec3 c = Minv * model.externalWrench(loads);
  const double external = c.norm();
  // friction bound mu |M^-1| ∫|p| (1 + max|r| / rho), with the pressure at
  // rest (the friction wrench's share of it is of the friction's order)
  const FlatBody& body = model.body();
  const ContactState rest = model.contactAtRest(Vec3::Zero(), loads);
  const double rmax = body.shape.maxDistanceFromOrigin();
  const double absP =
      body.shape.area() * (std::abs(rest.pressure[0]) +
                           (std::abs(rest.pressure[1]) + std::abs(rest.pressure[2])) * rmax);
  const double friction = body.mu * Minv.norm() * absP * (1.0 + rmax / model.rho());
  if (body.mu == 0.0 && external == 0.0) {
    LimitContinuum sphere;
    sphere.sphere = true;
    sphere.rdot = 0.0;
    sphere.attracting = false;
    out.continua.push_back(sphere);
    return true;
  }
  if (!(external > 0.0 && friction <= kNegligibleFriction * external)) {
    if (!(friction + external >= kUnresolvableField)) {
      throw Error(
          "limit directions: the limit field is below double's resolution (friction scale " +
          internal::formatDouble(friction) +
          " at unit loads; mu = " + internal::formatDouble(body.mu) + ")");
    }
    return false;
  }
  const double scale = fieldScale(model);
  for (double sign : {1.0, -1.0}) {
    Vec3 w = sign * c / external;
    if (!newtonSphere(model, w, scale)) {
      throw Error("limit directions: Newton did not converge near the external wrench's direction");
    }
    addUnique(out.directions, classifyDirection(model, w));
  }
  return true;
}

LimitAnalysis solveAtScale(const FlatBodyModel& model, const LimitOptions& options) {
  LimitAnalysis out;
  if (solveDegenerate(model, out)) {
    out.linear = false;  // closed form, not (111)
  } else {
    out.linear = !model.isNonlinear() && !options.sphereSolver;
    if (out.linear) {
      solveLinear(model, out);
    } else {
      solveNonlinear(model, options, out);
    }
  }
  std::sort(out.directions.begin(), out.directions.end(),
            [](const LimitDirection& a, const LimitDirection& b) {
              if (a.w.x() != b.w.x()) return a.w.x() > b.w.x();
              if (a.w.z() != b.w.z()) return a.w.z() > b.w.z();
              return a.w.y() > b.w.y();
            });
  // tipping: negative pressure somewhere on the patch in a reported direction
  const BodyLoads loads = model.bodyLoads();
  const double meanPressure = -loads.force.z() / model.body().shape.area();
  for (const LimitDirection& d : out.directions) {
    out.tipping = out.tipping || d.minPressure < -1e-12 * meanPressure;
  }
  if (out.linear) {
    const double p = model.contact(Vec3::UnitX(), 0.0, loads, false).minPressure;
    out.tipping = out.tipping || p < -1e-12 * meanPressure;
  }
  int sum = 0;
  bool hyperbolic = true;
  for (const LimitDirection& d : out.directions) {
    hyperbolic = hyperbolic && d.type != LimitType::Nonhyperbolic;
    sum += d.type == LimitType::Saddle ? -1 : 1;
  }
  out.indexConsistent = !out.continua.empty() || !hyperbolic || sum == 2;
  return out;
}

}  // namespace

}  // namespace patchspin
