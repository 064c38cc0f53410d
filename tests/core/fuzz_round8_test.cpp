// Eighth fuzz round (issue 6): regression tests for the classes decided in
// it (fuzz/README.md, "Eighth round", items 57-62). Each fails on 95c6a5c
// (checked: the blocks were refused, the pressures lost); each is checked
// against an independent computation (50-digit arithmetic, long double
// sums about the vertex mean, brute-force quadrature of Eq. (16)).
#include <patchspin/friction_block.hpp>
#include <patchspin/pressure.hpp>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gtest/gtest.h>

#include "oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace patchspin;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;

// ---- 50 significant digits, for the ellipsoidal block (item 57) ----------
using Big = boost::multiprecision::cpp_bin_float_50;
using BigVec = std::array<Big, 3>;
using BigMat = std::array<BigVec, 3>;

BigMat toBig(const Mat3& m) {
  BigMat out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = Big(m(i, j));
  return out;
}
BigVec toBig(const Vec3& v) { return {Big(v[0]), Big(v[1]), Big(v[2])}; }
BigMat times(const BigMat& a, const BigMat& b) {
  BigMat out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return out;
}
BigVec times(const BigMat& a, const BigVec& v) {
  BigVec out;
  for (int i = 0; i < 3; ++i) out[i] = a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2];
  return out;
}
Big det(const BigMat& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}
// a^-1 v by Cramer's rule: with 50 digits, a condition number of 1e36
// (rI + L K Pi below) leaves 14
BigVec solve(const BigMat& a, const BigVec& v) {
  const Big d = det(a);
  BigVec out;
  for (int k = 0; k < 3; ++k) {
    BigMat ak = a;
    for (int i = 0; i < 3; ++i) ak[i][k] = v[i];
    out[k] = det(ak) / d;
  }
  return out;
}
Big norm(const BigVec& v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The ellipsoidal block of step.hpp in its first form, (rI + A) w = b with
// A = L K Pi and |w| = 1, solved by bisection in r (no Newton, no
// reformulation, no scaling) in 50 digits; the impulse -L Pi w. Stick iff
// |A^-1 b| <= 1 (then the impulse is -K^-1 b).
struct BigBlock {
  bool sticking = false;
  Vec3 impulse = Vec3::Zero();
};
BigBlock solveEllipsoidalBig(const Mat3& Pi, const Mat3& K, const Vec3& b, double L) {
  const BigMat P = toBig(Pi), Kb = toBig(K);
  const BigVec bb = toBig(b);
  BigMat A = times(Kb, P);
  for (auto& row : A)
    for (Big& x : row) x *= Big(L);
  BigBlock out;
  auto wOf = [&](const Big& r) {
    BigMat M = A;
    for (int i = 0; i < 3; ++i) M[i][i] += r;
    return solve(M, bb);
  };
  if (norm(wOf(Big(0))) <= 1) {
    out.sticking = true;
    const BigVec lambda = solve(Kb, bb);
    out.impulse = -Vec3(double(lambda[0]), double(lambda[1]), double(lambda[2]));
    return out;
  }
  // |w(r)| decreases from |A^-1 b| > 1 to below 1 at r = |b| + |A|_F:
  // bisection, geometric over the decades, then plain
  Big aNorm = 0;
  for (const auto& row : A)
    for (const Big& x : row) aNorm += x * x;
  Big hi = norm(bb) + sqrt(aNorm), lo = hi * Big(1e-200);
  EXPECT_GT(norm(wOf(lo)), 1) << "the bracket's lower end is past the root";
  for (int it = 0; it < 2000 && hi - lo > hi * Big(1e-40); ++it) {
    const Big mid = hi > 4 * lo ? sqrt(lo * hi) : (lo + hi) / 2;
    (norm(wOf(mid)) > 1 ? lo : hi) = mid;
  }
  BigVec w = wOf(lo);
  const Big n = norm(w);
  for (Big& x : w) x /= n;
  const BigVec piW = times(P, w);
  out.impulse = -L * Vec3(double(piW[0]), double(piW[1]), double(piW[2]));
  return out;
}

// ---- long double sums about the vertex mean (items 58, 59) ----------------
// The polygon's area moments about its vertex mean g, in long double by the
// triangle formulas (no product of coordinates beyond the patch's size),
// and the loads (Pz, Tx, Ty) about O of a linear pressure p about O: the
// moments of p about g, moved to O. Independent of the core's sums.
struct LongLoads {
  long double Pz, Tx, Ty;
};
LongLoads loadsAboutVertexMean(const std::vector<Vec2>& v, const LinearPressure& p) {
  long double gx = 0.0L, gy = 0.0L;
  for (const Vec2& a : v) gx += a.x(), gy += a.y();
  gx /= static_cast<long double>(v.size());
  gy /= static_cast<long double>(v.size());
  long double A = 0.0L, sx = 0.0L, sy = 0.0L, ixx = 0.0L, ixy = 0.0L, iyy = 0.0L;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % v.size()];
    const long double ax = a.x() - gx, ay = a.y() - gy, bx = b.x() - gx, by = b.y() - gy;
    const long double c = ax * by - ay * bx;
    A += c / 2.0L, sx += c / 6.0L * (ax + bx), sy += c / 6.0L * (ay + by);
    ixx += c / 12.0L * (ax * ax + ax * bx + bx * bx);
    iyy += c / 12.0L * (ay * ay + ay * by + by * by);
    ixy += c / 24.0L * (2.0L * ax * ay + ax * by + bx * ay + 2.0L * bx * by);
  }
  const long double p0 = static_cast<long double>(p.p0) + static_cast<long double>(p.cx) * gx +
                         static_cast<long double>(p.cy) * gy;
  const long double Pz = p0 * A + p.cx * sx + p.cy * sy;
  const long double mx = p0 * sx + p.cx * ixx + p.cy * ixy;  // ∫ x' p about g
  const long double my = p0 * sy + p.cx * ixy + p.cy * iyy;
  // Eq. (94): Ty = ∫ x p, Tx = -∫ y p (about O)
  return {Pz, -(my + gy * Pz), mx + gx * Pz};
}

// The exact law's round-off model of step.cpp (requireExactLawDigits)
// without its constant: eps max(1, diameter^2 / A) times the pressure's
// terms about O over Pz.
double lawModel(const PatchShape& shape, const LinearPressure& p, double Pz) {
  const double terms =
      shape.area() * (std::abs(p.p0) + (std::abs(p.cx) + std::abs(p.cy)) * shape.maxDistanceFromOrigin()) / Pz;
  return kEps * std::max(1.0, shape.diameter() / shape.area() * shape.diameter()) * terms;
}

std::vector<Vec2> far23gon() {
  return {{0.99330679445895709, -0.51251019147067856}, {0.99328221757588198, -0.51258869994415635},
          {0.99327973340295261, -0.51267092787417023}, {0.99329952617991091, -0.51275077679131864},
          {0.99334012796703552, -0.51282232466670141}, {0.99339852751551672, -0.51288026512171103},
          {0.99347039359800327, -0.51292030097785934}, {0.99355039623592289, -0.51293946295884774},
          {0.9936326019996089, -0.51293632990820637},  {0.99371091406363488, -0.51291113418996881},
          {0.99377952438046591, -0.51286574445529398}, {0.99383334443677396, -0.51280352705315835},
          {0.99386838264519284, -0.51272909636365238}, {0.99388204038209371, -0.51264797257051975},
          {0.99387330471561031, -0.51256617225437973}, {0.9938428235301624, -0.51248976217046915},
          {0.99379285747583324, -0.51242440930515909}, {0.99372711230629251, -0.51237496058149945},
          {0.99365046404000079, -0.51234508338511164}, {0.99356859732822678, -0.51233699357097273},
          {0.9934875838504672, -0.51235129112358868},  {0.9934134320057556, -0.51238691565888916},
          {0.993351641297192, -0.51244122506806211}};
}

// The 37-gon of diameter 4e-4 m about (0.5, 1), 2,800 diameters from O
// (fuzz corpus: refused-exact-far-37gon-pz-no-digits-denormal-L).
std::vector<Vec2> far37gon() {
  return {{0.5001983642578125, 1.0000000000019837},   {0.50019551096820902, 1.0000335237242479},
          {0.50018703318401625, 1.0000660830300021},  {0.5001731747956496, 1.0000967412473003},
          {0.50015433448371083, 1.0001246163950499},  {0.50013105424967164, 1.0001489065560023},
          {0.50010400382347941, 1.0001689129464522},  {0.50007396139664484, 1.0001840600189718},
          {0.50004179123509007, 1.0001939120198624},  {0.50000841881579083, 1.0001981855249966},
          {0.49997480420248935, 1.0001967575934121},  {0.49994191442640845, 1.0001896693041008},
          {0.49991069566652357, 1.0001771245742404},  {0.49988204602971686, 1.0001594842928692},
          {0.49985678971387693, 1.0001372559387642},  {0.49983565329722646, 1.0001110789812024},
          {0.4998192448359895, 1.0000817064835925},   {0.499808036371721, 1.000049983439212},
          {0.49980235035153081, 1.0000168224622903},  {0.49980235035186726, 0.99998317753375676},
          {0.49980803637272064, 0.99995001655694871}, {0.49981924483762363, 0.99991829351279249},
          {0.49983565329944801, 0.99988892101551063}, {0.49985678971662206, 0.9998627440583715},
          {0.49988204603290654, 0.99984051570477184}, {0.49991069567006607, 0.99982287542397352},
          {0.49994191443020181, 0.99981033069473757}, {0.49997480420642454, 0.99980324240608398},
          {0.50000841881975455, 0.9998018144751718},  {0.5000417912389683, 0.99980608798097337},
          {0.50007396140032612, 0.99981593998250762}, {0.5001040038268576, 0.99983108705562784},
          {0.50013105425264981, 0.99985109344661871}, {0.50015433448620317, 0.99987538360803685},
          {0.5001731747975845, 0.99990325875616326},  {0.50018703318533786, 0.99993391697373857},
          {0.5001955109688796, 0.99996647627966229}};
}

}  // namespace

// 57. The ellipsoidal block with K near singular along a wide diagonal: a
// 1e-8 m disk with rho = 1e-8 and K whose unit-diagonal condition is 1.9e9
// (below the 1e10 refusal) with a diagonal spanning 1.2e27 and 2.1e27 (below
// 1e30): fuzz/known_failures of the seventh round and its twin. The pivoted
// re-solve of (rI + L K Pi) w = b left the slip 4.3e-7 of the slip scale
// off its law (eps times the condition of rI + A, which carries the span),
// and the block refused K as numerically singular. Now the re-solve that
// misses is repeated on the impulse's side, (K + (r / L) Pi^-1) lambda =
// -b scaled by K's diagonal (step.cpp). Checked against the same block
// solved in its first form in 50 digits (bisection in r, Cramer's rule):
// the stick decision, and the impulse to kImpulse of L |Pi| (measured
// 6e-17 and 8e-16 of it; the slip's direction is not resolved, its size
// is ~1e-4 against a slip scale of 2.8e12, so only the impulse is
// compared); and the answer's own backward error in 50 digits: the slip b
// + K impulse is along w = -Pi^-1 impulse / L, |w| = 1, to the block's
// documented 1e-10 of |b| + |L K Pi| (step.hpp; measured 2.5e-17 and
// 2.1e-17 of it).
TEST(FuzzRound8, EllipsoidalBlockWithANearSingularWideDiagonalKIsSolved) {
  struct Case {
    PatchLoads loads;
    Mat3 K;
    Vec3 warm;
  };
  std::vector<Case> cases(2);
  cases[0].loads = {1.4899643344710497e+236, -1.4991057232768605e+228, 1.8623432307385959e+228};
  cases[0].K << 1.8994705936215963e-07, 6459695.0000000065, 4.3582916259794539e-12,  //
      6459695.0000000065, 2.196804715965055e+20, 2579234964.2162175,                  //
      4.3582916259794539e-12, 2579234964.2162175, 2.6609808944266215e+19;
  cases[0].warm = Vec3(7113015296.0, 0.0, 1.5627709092286829e-312);
  cases[1].loads = {8.3943422731309656e+234, -8.4458441411370788e+226, 1.0492295786676125e+227};
  cases[1].K << 1.0575695363890247e-07, 4820035.0, 3.2520294189453125e-12,  //
      4820035.0, 2.196804715965055e+20, -63903.268157400002,                //
      3.2520294189453125e-12, -63903.268157400002, 1410963865600.0;
  cases[1].warm = Vec3(0.5, 1e-8, 1e-8);
  const PatchShape disk = PatchShape::disk(1e-8, Vec2(1e-8, 1e-8));
  // kImpulse: far above the measured 8e-16, far below the fuzz target's
  // law slack of 1e-6 of L |Pi|
  constexpr double kImpulse = 1e-10, kBackward = 1e-10;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const FrictionPatch patch(disk, LinearPressure::fromLoads(disk, cases[c].loads), 1e-8, 1e-8);
    FrictionBlockInput in;
    in.b = Vec3(0.0, 4.9406564584124654e-324, 0.5);
    in.L = 1e-8;
    in.K = cases[c].K;
    in.warmSlip = cases[c].warm;
    FrictionBlockResult r;
    ASSERT_NO_THROW(r = solveFrictionBlock(patch, Model::Ellipsoidal, in)) << "case " << c;
    const Mat3& Pi = patch.Pi();
    const BigBlock ref = solveEllipsoidalBig(Pi, in.K, in.b, in.L);
    ASSERT_FALSE(ref.sticking) << "case " << c;
    EXPECT_FALSE(r.sticking) << "case " << c;
    const double setSize = in.L * Pi.norm();
    EXPECT_LT((r.impulse - ref.impulse).norm(), kImpulse * setSize)
        << "case " << c << ": impulse " << r.impulse.transpose() << ", 50 digits " << ref.impulse.transpose();
    // the backward error of the returned impulse, in 50 digits
    const BigVec lambda = toBig(r.impulse);
    const BigVec w0 = solve(toBig(Pi), lambda);
    BigVec w = {-w0[0] / in.L, -w0[1] / in.L, -w0[2] / in.L};
    const double wNorm = double(norm(w));
    // (|w| = 1 to the rounding of -L Pi w and of its inverse: Pi is well
    // conditioned)
    EXPECT_NEAR(wNorm, 1.0, 1e-12) << "case " << c;
    for (Big& x : w) x /= Big(wNorm);
    const BigVec kl = times(toBig(in.K), lambda);
    const BigVec b = toBig(in.b);
    const BigVec s = {b[0] + kl[0], b[1] + kl[1], b[2] + kl[2]};
    const Big along = s[0] * w[0] + s[1] * w[1] + s[2] * w[2];
    const BigVec e = {s[0] - along * w[0], s[1] - along * w[1], s[2] - along * w[2]};
    const double scale = in.b.norm() + (in.L * (in.K * Pi)).norm();
    EXPECT_LT(double(norm(e)), kBackward * scale) << "case " << c;
    EXPECT_GT(double(along), -kBackward * scale) << "case " << c;
  }
}

// 58. The exact polygon law far from O: Pz (the unit law's normalisation)
// came from area moments summed about O, whose products round to ~eps
// max|r|^2 / A, so the unit force in pure translation was 1 + 1.1e-7 on a
// 23-gon 900 diameters from O, 1 + 2.5e-7 on a 37-gon 2,800 diameters
// from O, 1 + 5.5e-7 on a 1.2e-8 m quadrilateral 8,800 diameters from O;
// the seventh round refused those blocks (item 55). Now a polygon's
// moments are summed about its vertex mean where O is outside it
// (geometry.cpp). Checked: Pz against the long double sum about the vertex
// mean, and the unit force in pure translation, to kPz times the law's
// round-off model (step.cpp: 64 of it is refused; measured 7e-4 to 0.055
// for Pz, 0.008 to 0.19 for the force; on 95c6a5c 7e4 and refused); the
// block, slipping about an ICR at the patch's vertex mean (the hard case:
// the law turns fastest there), is solved, and its impulse is L q(s^) with
// q = Q / Pz by brute-force quadrature of Eq. (16) and of ∫p dA
// (tests/support/oracle.hpp), to kLaw of L (the fuzz target's law slack;
// measured 5.5e-13, 1.6e-11 and 2.8e-8 of L, the last the rounding of s =
// b + K impulse about O for a patch 1e-8 m across, as in item 56).
TEST(FuzzRound8, ExactPolygonLawFarFromOIsSolvedWithPzAboutTheVertexMean) {
  struct Case {
    const char* name;
    std::vector<Vec2> vertices;
    PatchLoads loads;
    double rho;
  };
  const std::vector<Case> cases = {
      {"23-gon 900 diameters from O", far23gon(),
       {0.044933735669085033, 0.023031487191871106, 0.04464514278227618}, 0.0},
      {"37-gon 2,800 diameters from O", far37gon(),
       {104871.91672465707, -104874.82550656002, 52431.654679402403}, 0.5},
      {"1.2e-8 m quadrilateral 8,800 diameters from O",
       {{5.7509619923003298e-06, -0.00010628063654460903},
        {5.7627784805965424e-06, -0.00010628032686178125},
        {5.7627784807117414e-06, -0.00010626880698244775},
        {5.7558854282998356e-06, -0.00010626880698237882}},
       {382.34459070385174, 0.040633901886729266, 0.0022021178888884077}, 0.5}};
  constexpr double kPz = 8.0, kLaw = 1e-6;
  for (const Case& c : cases) {
    const PatchShape shape = PatchShape::polygon(c.vertices);
    const LinearPressure p = LinearPressure::fromLoads(shape, c.loads);
    ASSERT_GE(minPressure(shape, p), -1e-6 * c.loads.Pz / shape.area()) << c.name;
    const double rho = c.rho > 0.0 ? c.rho : shape.defaultRho();
    const FrictionPatch patch(shape, p, 0.5, rho);
    const double model = lawModel(shape, p, patch.Pz());
    const LongLoads ref = loadsAboutVertexMean(shape.vertices(), p);
    EXPECT_LT(std::abs(static_cast<double>((patch.Pz() - ref.Pz) / ref.Pz)), kPz * model) << c.name;
    const Vec3 q = patch.unitQ(Model::Exact, Vec3::UnitX());
    EXPECT_LT(std::abs(std::hypot(q.x(), q.y()) - 1.0), kPz * model) << c.name;

    // the block: K = I, b with its ICR rho (-b_y, b_x) / b_z at the vertex
    // mean g, L small enough to slip
    Vec2 g = Vec2::Zero();
    for (const Vec2& v : shape.vertices()) g += v;
    g /= static_cast<double>(shape.vertices().size());
    FrictionBlockInput in;
    in.b = Vec3(g.y() / rho, -g.x() / rho, 1.0);
    in.L = 0.1;
    FrictionBlockResult r;
    ASSERT_NO_THROW(r = solveFrictionBlock(patch, Model::Exact, in)) << c.name;
    ASSERT_FALSE(r.sticking) << c.name;
    const Vec3 Q = patchspin::testing::bruteForceQ(shape, patchspin::testing::linearField(p), 1.0, rho, r.slip, 1e-12);
    const double pz = patchspin::testing::bruteForceIntegral(shape, patchspin::testing::linearField(p), 1e-13);
    EXPECT_LT((r.impulse - in.L * (Q / pz)).norm(), kLaw * in.L)
        << c.name << ": impulse " << r.impulse.transpose() << ", L q " << (in.L * Q / pz).transpose();
  }
}

// 59. LinearPressure::fromLoads (Eq. (94)) and nearestAdmissibleLoads about
// a far O: both solved with the cofactor inverse of G about O, whose
// condition is ~(max|r| / size)^4 (1e16 at 1e4 diameters), so fromLoads'
// pressure on the patch was off by up to 5.8e3 times its mean (measured,
// this sweep on 95c6a5c) and nearestAdmissibleLoads refused 25-40% of the
// loads it was given beyond 10 diameters ("no admissible projection to
// double precision"). G^-1 is now applied in factored form about the
// vertex mean (PatchShape::solveLoadMatrix). Sweep: 500 convex polygons
// (3 to 22 vertices, aspect 1 to 1e-4, 1e-6 to 1e6 m), O outside them at
// 1 to 1e4 diameters, tilted pressures >= 0 given by their loads in long
// double (sums about the vertex mean, above). fromLoads returns the
// pressure at every vertex to kPressure of the mean (measured worst
// 3.3e-8: the loads about O carry the tilt to ~eps max|r| / size; on
// 95c6a5c 247 times the mean); loads
// pushed outside the admissible set (torques 3 times past the patch) are
// projected, admissible to 1e-6 (nearestAdmissibleLoads' own check), and
// refused at most kRefused times (measured 1 of 500; on 95c6a5c 152).
TEST(FuzzRound8, FromLoadsAndNearestAdmissibleLoadsKeepTheirDigitsFarFromO) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  constexpr double kPressure = 1e-6;
  constexpr int kRefused = 5;
  int refused = 0, checked = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const double offset = std::pow(10.0, 3.9 * U(rng)) + 1.0;  // (below the 1e4 limit)
    const int n = 3 + static_cast<int>(U(rng) * 20);
    const double aspect = std::pow(10.0, -4.0 * U(rng)), size = std::pow(10.0, -6.0 + 12.0 * U(rng));
    const double angle = 2.0 * kPi * U(rng), direction = 2.0 * kPi * U(rng);
    std::vector<Vec2> v;
    const Vec2 centre = offset * 2.0 * size * Vec2(std::cos(direction), std::sin(direction));
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * kPi * i / n;
      const Vec2 u(std::cos(t), aspect * std::sin(t));
      v.push_back(centre + size * Vec2(std::cos(angle) * u.x() - std::sin(angle) * u.y(),
                                       std::sin(angle) * u.x() + std::cos(angle) * u.y()));
    }
    const PatchShape shape = PatchShape::polygon(v);
    ASSERT_GT(shape.maxDistanceFromOrigin(), shape.diameter());
    // p = 1 + t n.(x - g) / halfwidth >= 0 (t <= 1), given about O
    Vec2 g = Vec2::Zero();
    for (const Vec2& a : shape.vertices()) g += a;
    g /= static_cast<double>(shape.vertices().size());
    const double th = 2.0 * kPi * U(rng), tilt = U(rng);
    const Vec2 nrm(std::cos(th), std::sin(th));
    double halfWidth = 0.0;
    for (const Vec2& a : shape.vertices()) halfWidth = std::max(halfWidth, std::abs(nrm.dot(a - g)));
    const LinearPressure p{1.0 - tilt * nrm.dot(g) / halfWidth, tilt * nrm.x() / halfWidth,
                           tilt * nrm.y() / halfWidth};
    const LongLoads l = loadsAboutVertexMean(shape.vertices(), p);
    const PatchLoads loads{double(l.Pz), double(l.Tx), double(l.Ty)};
    const LinearPressure back = LinearPressure::fromLoads(shape, loads);
    const double mean = loads.Pz / shape.area();
    for (const Vec2& a : shape.vertices()) {
      auto at = [&](const LinearPressure& q) {
        return static_cast<long double>(q.p0) + static_cast<long double>(q.cx) * a.x() +
               static_cast<long double>(q.cy) * a.y();
      };
      worst = std::max(worst, static_cast<double>(std::abs(at(back) - at(p))) / mean);
    }
    // loads outside: the torques about g pushed 3 times past the patch
    const double reach = 3.0 * shape.diameter() * loads.Pz;
    const PatchLoads outside{loads.Pz, loads.Tx + reach * std::cos(th), loads.Ty + reach * std::sin(th)};
    try {
      const PatchLoads near = nearestAdmissibleLoads(shape, outside, shape.defaultRho());
      EXPECT_TRUE(isAdmissible(shape, near, 1e-6)) << "trial " << trial;
      ++checked;
    } catch (const Error& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find("no admissible projection"), std::string::npos) << e.what();
    }
  }
  EXPECT_LT(worst, kPressure);
  EXPECT_LE(refused, kRefused) << checked << " projected";
}

// 61. minPressure on a polygon whose vertex products overflow where their
// sum does not: p = (-5.2e297, -5.2e303, 3.7e303) on a triangle with a
// vertex at (4.3e5, 6.0e5) gives cx x = -inf and cy y = +inf, NaN, which
// std::min passed over, so minPressure returned the vertex at O's
// -5.2e297 where the pressure at that vertex is -2.3e303 (found by the
// pressure target). Checked against the pressure at every vertex in long
// double (range to 1e4932), to kUlps eps of the terms |p0| + |cx x| + |cy
// y| (the sum cancels them 1e6-fold; measured 0.9 eps of them).
TEST(FuzzRound8, MinPressureWithOverflowingVertexProductsIsTheLowestVertex) {
  const PatchShape triangle = PatchShape::polygon(
      {{0.0, 0.0}, {428990.26137603901, 604750.50188696722}, {428989.27616420639, 604750.330503618}});
  const LinearPressure p{-5.1874508961404106e+297, -5.22801961128216e+303, 3.708582688189708e+303};
  long double lowest = std::numeric_limits<long double>::infinity(), terms = 0.0L;
  for (const Vec2& v : triangle.vertices()) {
    const long double x = static_cast<long double>(p.cx) * v.x(), y = static_cast<long double>(p.cy) * v.y();
    if (p.p0 + x + y < lowest) lowest = p.p0 + x + y, terms = std::abs(p.p0) + std::abs(x) + std::abs(y);
  }
  ASSERT_LT(std::abs(lowest), static_cast<long double>(std::numeric_limits<double>::max()));
  constexpr double kUlps = 8.0;
  const double core = minPressure(triangle, p);
  // (in long double: the terms, 4.5e309, are beyond double's range)
  EXPECT_LE(std::abs(static_cast<long double>(core) - lowest), kUlps * kEps * terms)
      << core << " vs " << static_cast<double>(lowest);
}

// 62. nearestAdmissibleLoads on a disk not centred at O maximised each
// boundary ray's gain |y|^2 - d^2 (y the scaled loads, d the distance to
// the ray), which loses d below sqrt(eps) |y|: loads 3e-9 of their size
// outside the set (a 0.5 m disk with O on its rim, rho = 1.2e8) had every
// sample's gain equal to the last bit, and the answer was 33% farther than
// the nearest ray (and farther than the uniform pressure: found by the
// pressure target), and on a 5.4e9 m disk with loads of 1e146 2.2 times.
// Now the rays are ranked by d itself. Checked against a dense scan of the
// boundary rays (pressures vanishing at one rim point, 200,000 of them,
// their loads by loadsOf): the answer is admissible and as near as the
// nearest scanned ray to kScan (the scan's own step, with room; measured
// to 1e-12 of it).
TEST(FuzzRound8, NearestAdmissibleLoadsOnADiskIsTheNearestBoundaryRay) {
  struct Case {
    double R;
    Vec2 centre;
    PatchLoads loads;
    double rho;
  };
  const std::vector<Case> cases = {
      {0.5, {0.5000005187294978, -0.0015335067838567222},
       {6.008148193359375e-05, 1e-300, -6.2008168049345967e-49}, 116391936.0},
      {5368184832.0, {2154373347.0781322, -642361449.92492497}, {3.770163170556893e+146, 0.5, 0.5},
       4044283405.5980945}};
  constexpr double kScan = 1e-6;
  for (const Case& c : cases) {
    const PatchShape disk = PatchShape::disk(c.R, c.centre);
    const PatchLoads near = nearestAdmissibleLoads(disk, c.loads, c.rho);
    EXPECT_TRUE(isAdmissible(disk, near, 1e-6));
    const Vec3 y(c.loads.Pz, c.loads.Tx / c.rho, c.loads.Ty / c.rho);
    auto scaled = [&](const PatchLoads& l) { return Vec3(l.Pz, l.Tx / c.rho, l.Ty / c.rho); };
    double nearest = y.norm();  // the zero load
    constexpr int kRays = 200000;
    for (int i = 0; i < kRays; ++i) {
      const double th = 2.0 * kPi * i / kRays;
      const Vec2 n(std::cos(th), std::sin(th));
      const Vec3 u = scaled(loadsOf(disk, LinearPressure{1.0 + n.dot(c.centre) / c.R, -n.x() / c.R, -n.y() / c.R}));
      const double t = std::max(0.0, u.dot(y) / u.squaredNorm());
      nearest = std::min(nearest, (t * u - y).norm());
    }
    EXPECT_LE((scaled(near) - y).norm(), nearest * (1.0 + kScan)) << "R = " << c.R;
  }
}
