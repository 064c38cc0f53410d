// Exact model, Eq. (16), on a disk: linear pressure basis (exactDiskBasis)
// and Hertz pressure (57) (exactDiskHertz). F, dF and the kernel k(w; x, y)
// are defined in patchspin/internal/exact.hpp.
//
// Reduction (DESIGN item 3). Lengths in units of R about the disk centre C:
// q = (P - C)/R. With c' = (c - C)/R the ICR relative to C,
//   v ∝ s J (q - c'),   s = sign(w3),   J = [[0, -1], [1, 0]],
// so the kernel depends on w only through c' and s. Rotate so that
// c' = (delta, 0) and write d = q - c', u = J d / |d| (unit disk, s = +1):
//   a = ∫ u_y,  b = ∫ x u_y,  e = ∫ y u_x,  T0 = ∫ q x u,  T1 = ∫ x (q x u)
// (all other moments vanish by the symmetry y -> -y). With the radial
// potentials M_n(delta) = ∫ |d|^n dA and grad_c |d|^n = -n |d|^(n-2) d:
//   a = -M1',  b = M3''/3 - M1 - delta M1',  e = M1 - M3'/(3 delta),
//   T0 = b - e,  T1 = delta (b + e)          (identities, checked symbolically)
// and by the angular average of |d|^n (a Gauss hypergeometric series):
//   delta <= 1:  M1 = (2 pi/3) 2F1(-1/2, -3/2; 1; m),  m = delta^2
//                M3 = (2 pi/5) 2F1(-3/2, -5/2; 1; m)
//   delta >= 1:  M1 = pi delta 2F1(-1/2, -1/2; 2; p),  p = 1/delta^2
//                M3 = pi delta^3 2F1(-3/2, -3/2; 2; p)
// which reduce to the complete elliptic integrals K, E (cf. Eq. (52)-(53),
// which are the case C = O, pressure 1, of the same formulas).
//
// Smooth parametrisations (also what makes dF well defined everywhere):
//  * near (delta <= 1/sqrt(kFarSeriesP)): with A = a/delta, B = (b - e)/2,
//    C = (b + e)/(2 m), all analytic in m (also across the rim in value and
//    first derivative):
//      force(1) = s A J c',  force(q) = s [B J + C J (2 c' c'^T - m I)],
//      torque_C(1) = 2 s B,  torque_C(q) = 2 s m C c'^T.
//  * far (includes w3 = 0): n = (rho (-w2, w1) - w3 C)/R, c' = n / w3,
//    tau = w3/|n| (signed 1/delta), nh = n/|n|, p = tau^2, and the analytic
//    functions a(p), bt = b/|tau|, et = e/|tau|:
//      force(1) = a J nh,  force(q) = tau [(bt - et)/2 J + (bt + et)/2 J D],
//      D = 2 nh nh^T - I,  torque_C(1) = tau (bt - et),  torque_C(q) = (bt + et) nh^T.
// Each radial function has three evaluations: a power series in m (ICR near
// the centre, including pure spin), the elliptic closed form (ICR within a
// band around the rim), and a power series in p (ICR far, including pure
// translation). The closed forms' K terms all carry a factor (1 - m) (or
// (1 - p)), so they stay finite and accurate up to the rim, where K -> inf.
//
// Hertz pressure (57), p1 = 3/(2 pi) sqrt(1 - |q|^2) on the unit disk: the same
// reduction with p1 as weight needs only a_H = ∫ p1 u_y and T0_H = ∫ p1 q x u,
// which are Eq. (58)-(59) (verified): a_H = -P_eps(delta),
// T0_H = (3 pi/16) T_eps(delta), delta = eps.
//
// Jacobians: forward-mode dual numbers in w through the smooth
// parametrisations, with the radial functions' derivatives in closed form.
#include <algorithm>
#include <cmath>
#include <patchspin/internal/exact.hpp>
#include <type_traits>

#include "elliptic.hpp"

namespace patchspin::internal {
namespace {

constexpr double kPi = 3.14159265358979323846;
// ICR within sqrt(kInsideSeriesM) R of the centre -> power series in m. The
// closed form loses ~1/m^2 to cancellation near m = 0 (C has a 1/m^2
// prefactor), i.e. a factor 100 at the switch (~1e-14); the series needs
// ~16 terms there.
constexpr double kInsideSeriesM = 0.1;
// ICR beyond R / sqrt(kFarSeriesP) from the centre -> power series in p. The
// closed form loses ~delta^4 = 100 at the switch; the series needs ~16 terms.
constexpr double kFarSeriesP = 0.1;
// Series are stopped when a term (times its index, for the derivative) is
// below this, the coefficients being O(1): full double accuracy.
constexpr double kFullAccuracy = 1e-17;
// Series length cap (at m or p = 0.1, 1e-17 needs about 17 terms).
constexpr int kMaxTerms = 40;

// ---------------------------------------------------------------- duals
// Value and gradient with respect to the three components of w.
struct Dual3 {
  double v = 0.0;
  double d[3] = {0.0, 0.0, 0.0};
};

inline Dual3 operator+(const Dual3& a, const Dual3& b) {
  return {a.v + b.v, {a.d[0] + b.d[0], a.d[1] + b.d[1], a.d[2] + b.d[2]}};
}
inline Dual3 operator-(const Dual3& a, const Dual3& b) {
  return {a.v - b.v, {a.d[0] - b.d[0], a.d[1] - b.d[1], a.d[2] - b.d[2]}};
}
inline Dual3 operator-(const Dual3& a) {
  return {-a.v, {-a.d[0], -a.d[1], -a.d[2]}};
}
inline Dual3 operator*(const Dual3& a, const Dual3& b) {
  return {a.v * b.v,
          {a.d[0] * b.v + a.v * b.d[0], a.d[1] * b.v + a.v * b.d[1], a.d[2] * b.v + a.v * b.d[2]}};
}
inline Dual3 operator*(double s, const Dual3& a) {
  return {s * a.v, {s * a.d[0], s * a.d[1], s * a.d[2]}};
}
inline Dual3 operator*(const Dual3& a, double s) {
  return s * a;
}
inline Dual3 reciprocal(const Dual3& a) {
  const double r = 1.0 / a.v;
  const double h = -r * r;
  return {r, {h * a.d[0], h * a.d[1], h * a.d[2]}};
}
inline double reciprocal(double a) {
  return 1.0 / a;
}
inline Dual3 sqrt(const Dual3& a) {
  const double r = std::sqrt(a.v);
  const double h = 0.5 / r;
  return {r, {h * a.d[0], h * a.d[1], h * a.d[2]}};
}

inline double valueOf(double x) {
  return x;
}
inline double valueOf(const Dual3& x) {
  return x.v;
}
using std::sqrt;

// f(x) as T from its value f and derivative df at x.
inline double lift(double f, double /*df*/, double /*x*/) {
  return f;
}
inline Dual3 lift(double f, double df, const Dual3& x) {
  return {f, {df * x.d[0], df * x.d[1], df * x.d[2]}};
}

// ------------------------------------------------------ radial functions
// Three functions of one variable and their derivatives.
struct Radial3 {
  double f[3] = {0.0, 0.0, 0.0};
  double df[3] = {0.0, 0.0, 0.0};
};

// Power-series coefficients, computed once at compile time. Each table holds
// the coefficients c_j of f(x) = sum_j c_j x^j.
constexpr int kTerms = kMaxTerms;
struct SeriesTables {
  // near the centre (x = m = delta^2), from the 2F1's:
  //   A = -4 pi sum_{k>=1} k alpha_k / (3 - 2k) m^(k-1)
  //   B =    pi sum_{k>=0} alpha_k (1 - 2k) / (3 - 2k) m^k
  //   C =   -pi sum_{k>=0} (k+1)(2k+1) alpha_{k+1} / ((1 - 2k)(k + 2)) m^k
  // with alpha_k = ((-1/2)_k / k!)^2, alpha_{k+1} = alpha_k ((2k-1)/(2k+2))^2.
  double inA[kTerms] = {}, inB[kTerms] = {}, inC[kTerms] = {};
  // far (x = p = 1/delta^2):
  //   a  = pi sum_{k>=0} (2k-1) alpha_k / (k+1) p^k
  //   bt = pi sum_{k>=2} 2k (2k-2) alpha_k / ((2k-3)(k+1)) p^(k-1)
  //   et = pi sum_{k>=1} 2k alpha_k / ((2k-3)(k+1)) p^(k-1)
  double farA[kTerms] = {}, farBt[kTerms] = {}, farEt[kTerms] = {};
  // Hertz far: with asin t = sum c_k t^(2k+1), sqrt(1 - t^2) = sum s_k t^(2k)
  // (c_0 = s_0 = 1, c_k = c_{k-1} (2k-1)^2/(2k (2k+1)), s_k = s_{k-1} (k - 3/2)/k),
  // the t-expansions of (58)-(59) give
  //   aH   = -(3/16) sum_{k>=1} d_k p^(k-1),  d_k = 4c_{k-1} - c_k + s_k + 2s_{k-1}
  //   T0Ht = T0_H / |tau| = (3/64) sum_{k>=2} e_k p^(k-2),
  //          e_k = 3c_k - 8c_{k-1} + 8c_{k-2} + 6s_{k-1} - 3s_k
  double hzA[kTerms] = {}, hzT[kTerms] = {};

  constexpr SeriesTables() {
    double alpha[kTerms + 2] = {};
    alpha[0] = 1.0;
    for (int k = 0; k + 1 < kTerms + 2; ++k) {
      const double r = (2.0 * k - 1.0) / (2.0 * k + 2.0);
      alpha[k + 1] = alpha[k] * r * r;
    }
    for (int k = 0; k < kTerms; ++k) {
      const double kk = k;
      if (k >= 1) inA[k - 1] = -4.0 * kPi * kk * alpha[k] / (3.0 - 2.0 * kk);
      inB[k] = kPi * alpha[k] * (1.0 - 2.0 * kk) / (3.0 - 2.0 * kk);
      inC[k] =
          -kPi * (kk + 1.0) * (2.0 * kk + 1.0) * alpha[k + 1] / ((1.0 - 2.0 * kk) * (kk + 2.0));
      farA[k] = kPi * (2.0 * kk - 1.0) * alpha[k] / (kk + 1.0);
      if (k >= 2)
        farBt[k - 1] =
            kPi * 2.0 * kk * (2.0 * kk - 2.0) * alpha[k] / ((2.0 * kk - 3.0) * (kk + 1.0));
      if (k >= 1) farEt[k - 1] = kPi * 2.0 * kk * alpha[k] / ((2.0 * kk - 3.0) * (kk + 1.0));
    }
    double c[kTerms + 2] = {}, sq[kTerms + 2] = {};
    c[0] = 1.0;
    sq[0] = 1.0;
    for (int k = 1; k < kTerms + 2; ++k) {
      const double kk = k;
      c[k] = c[k - 1] * (2.0 * kk - 1.0) * (2.0 * kk - 1.0) / (2.0 * kk * (2.0 * kk + 1.0));
      sq[k] = sq[k - 1] * (kk - 1.5) / kk;
    }
    for (int k = 1; k <= kTerms; ++k) {
      hzA[k - 1] = -3.0 / 16.0 * (4.0 * c[k - 1] - c[k] + sq[k] + 2.0 * sq[k - 1]);
    }
    for (int k = 2; k < kTerms + 2; ++k) {
      hzT[k - 2] = 3.0 / 64.0 *
                   (3.0 * c[k] - 8.0 * c[k - 1] + 8.0 * c[k - 2] + 6.0 * sq[k - 1] - 3.0 * sq[k]);
    }
  }
};
constexpr SeriesTables kSeries{};

// sum_j c_i[j] x^j and its derivative for N tables at once, stopped when the
// next terms (times j, for the derivative) are below relTol; x <= 0.1 here
// and the coefficients are O(1), so relTol is an absolute bound on O(1) values.
template <int N, bool kDeriv>
void sumSeries(const double* const (&c)[N], double x, double relTol, double* f, double* df) {
  for (int i = 0; i < N; ++i) {
    f[i] = c[i][0];
    df[i] = 0.0;
  }
  double xj1 = 1.0;  // x^(j-1)
  for (int j = 1; j < kTerms; ++j) {
    const double xj = xj1 * x;
    double size = 0.0;
    for (int i = 0; i < N; ++i) {
      f[i] += c[i][j] * xj;
      if (kDeriv) df[i] += j * c[i][j] * xj1;
      size += std::fabs(c[i][j]);
    }
    if (j >= 2 && (kDeriv ? j + 1 : 1) * size * xj <= relTol) {
      break;
    }
    xj1 = xj;
  }
}

template <bool kDeriv>
Radial3 insideSeries(double m, double relTol) {
  Radial3 r;
  const double* const c[3] = {kSeries.inA, kSeries.inB, kSeries.inC};
  sumSeries<3, kDeriv>(c, m, relTol, r.f, r.df);
  return r;
}

template <bool kDeriv>
Radial3 farSeries(double p, double relTol) {
  Radial3 r;
  const double* const c[3] = {kSeries.farA, kSeries.farBt, kSeries.farEt};
  sumSeries<3, kDeriv>(c, p, relTol, r.f, r.df);
  return r;
}

// ICR inside, closed form (m in (kInsideSeriesM, 1], mc = 1 - m), with
// mcK = (1 - m) K(m):
//   A = 4/(3m) [mcK - (1 + m) E]             dA/dm = 2/(3m^2) [(2 - m) E - 2 mcK]
//   B = 2/9 [2 (2 - m) E - mcK]              dB/dm = 1/(3m) [(1 - 2m) E - mcK]
//   C = 2/(15 m^2) [(2 - m) mcK - 2 (m^2 - m + 1) E]
//   dC/dm = 1/(15 m^3) [(8 - 3m - 2m^2) E - (m + 8) mcK]
template <bool kDeriv>
Radial3 insideClosedForm(double m, double mc, double relTol) {
  const EllipticKE ke = completeEllipticKE(m, mc, relTol);
  const double E = ke.E, K1 = mcK(ke, mc);
  const double im = 1.0 / m, im2 = im * im;
  Radial3 r;
  r.f[0] = 4.0 / 3.0 * im * (K1 - (1.0 + m) * E);
  r.f[1] = 2.0 / 9.0 * (2.0 * (2.0 - m) * E - K1);
  r.f[2] = 2.0 / 15.0 * im2 * ((2.0 - m) * K1 - 2.0 * (m * m - m + 1.0) * E);
  if (kDeriv) {
    r.df[0] = 2.0 / 3.0 * im2 * ((2.0 - m) * E - 2.0 * K1);
    r.df[1] = 1.0 / 3.0 * im * ((1.0 - 2.0 * m) * E - K1);
    r.df[2] = 1.0 / 15.0 * im2 * im * ((8.0 - 3.0 * m - 2.0 * m * m) * E - (m + 8.0) * K1);
  }
  return r;
}

// ICR outside, closed form in p = 1/m in (kFarSeriesP, 1), pc = 1 - p,
// pcK = (1 - p) K(p), sp = sqrt(p); returns A, B, C and d/dm = -p^2 d/dp:
//   A = 4/(3 sp) [pcK - (1 + p) E]           dA/dp = 2/(3 p sp) [(1 - 2p) E - pcK]
//   B = 2/(9 p sp) [2 (2p - 1) E + (2 - 3p) pcK]
//   dB/dp = 1/(3 p^2 sp) [(2 - p) E - 2 pcK]
//   C = 2/(15 sp) [(2 - p) pcK - 2 (p^2 - p + 1) E]
//   dC/dp = 1/(15 p sp) [(2 + 3p - 8p^2) E - 2 (2p + 1) pcK]
template <bool kDeriv>
Radial3 outsideClosedForm(double p, double pc, double relTol) {
  const EllipticKE ke = completeEllipticKE(p, pc, relTol);
  const double E = ke.E, K1 = mcK(ke, pc);
  const double sp = std::sqrt(p), isp = 1.0 / sp, ip = isp * isp;
  Radial3 r;
  r.f[0] = 4.0 / 3.0 * isp * (K1 - (1.0 + p) * E);
  r.f[1] = 2.0 / 9.0 * ip * isp * (2.0 * (2.0 * p - 1.0) * E + (2.0 - 3.0 * p) * K1);
  r.f[2] = 2.0 / 15.0 * isp * ((2.0 - p) * K1 - 2.0 * (p * p - p + 1.0) * E);
  if (kDeriv) {
    // d/dm = -p^2 d/dp
    r.df[0] = -2.0 / 3.0 * sp * ((1.0 - 2.0 * p) * E - K1);
    r.df[1] = -1.0 / 3.0 * isp * ((2.0 - p) * E - 2.0 * K1);
    r.df[2] = -1.0 / 15.0 * sp * ((2.0 + 3.0 * p - 8.0 * p * p) * E - 2.0 * (2.0 * p + 1.0) * K1);
  }
  return r;
}

// A, B, C and d/dm for the near parametrisation; nn = |n|^2, w33 = w3^2
// (m = nn / w33, passed separately for accurate 1 - m and 1 - 1/m).
template <bool kDeriv>
Radial3 nearRadial(double m, double nn, double w33, double relTol) {
  if (m <= kInsideSeriesM) {
    return insideSeries<kDeriv>(m, relTol);
  }
  if (nn <= w33) {
    return insideClosedForm<kDeriv>(m, 1.0 - m, relTol);
  }
  const double p = w33 / nn;
  return outsideClosedForm<kDeriv>(p, 1.0 - p, relTol);
}

// Hertz (57), unit load on the unit disk: AH = a_H / delta and T0H with d/dm.
//   m <= 1:  AH = -(3 pi/32)(4 - m),  T0H = (3 pi/128)(3 m^2 - 8 m + 8)       (58)-(59)
//   m > 1, S = asin(1/sqrt(m)), Q = sqrt(m - 1):
//     AH  = 3/16 [(m - 4) S - Q (1 + 2/m)],        dAH/dm  = 3/16 [S + Q (2 - m)/m^2]
//     T0H = 3/64 [(3m^2 - 8m + 8) S + Q (6 - 3m)], dT0H/dm = 3/32 [(3m - 4) S - Q (3m - 2)/m]
struct Radial2 {
  double f[2] = {0.0, 0.0};
  double df[2] = {0.0, 0.0};
};

Radial2 hertzNear(double m, double nn, double w33) {
  Radial2 r;
  if (nn <= w33) {
    r.f[0] = -3.0 * kPi / 32.0 * (4.0 - m);
    r.df[0] = 3.0 * kPi / 32.0;
    r.f[1] = 3.0 * kPi / 128.0 * ((3.0 * m - 8.0) * m + 8.0);
    r.df[1] = 3.0 * kPi / 128.0 * (6.0 * m - 8.0);
    return r;
  }
  // S = asin(1/delta) from the same Q, so that the sqrt-sensitive parts of
  // S and Q (Q ~ 1e-8 for delta^2 - 1 ~ 1e-16) cancel as they do exactly.
  const double Q = std::sqrt((nn - w33) / w33);
  const double S = std::atan2(1.0, Q);
  r.f[0] = 3.0 / 16.0 * ((m - 4.0) * S - Q * (1.0 + 2.0 / m));
  r.df[0] = 3.0 / 16.0 * (S + Q * (2.0 - m) / (m * m));
  r.f[1] = 3.0 / 64.0 * (((3.0 * m - 8.0) * m + 8.0) * S + Q * (6.0 - 3.0 * m));
  r.df[1] = 3.0 / 32.0 * ((3.0 * m - 4.0) * S - Q * (3.0 * m - 2.0) / m);
  return r;
}

// Hertz far (p = 1/delta^2 <= kFarSeriesP): aH and T0Ht from the tables.
template <bool kDeriv>
Radial2 hertzFar(double p, double relTol) {
  Radial2 r;
  const double* const c[2] = {kSeries.hzA, kSeries.hzT};
  sumSeries<2, kDeriv>(c, p, relTol, r.f, r.df);
  return r;
}

// ------------------------------------------------------------- assembly
// radial derivatives are needed only when T carries a gradient
template <class T>
constexpr bool kDeriv = std::is_same<T, Dual3>::value;

// The slip direction reduced to the disk: vector g (c' near, nh far), and
// n = (rho (-w2, w1) - w3 C)/R.
template <class T>
struct Reduced {
  T nx, ny;
  double nn = 0.0, w33 = 0.0;
  bool far = false;
};

template <class T>
Reduced<T> reduce(const Vec2& centre, double R, double rho, const T* w) {
  Reduced<T> red;
  const double invR = 1.0 / R;
  red.nx = (-rho * w[1] - centre.x() * w[2]) * invR;
  red.ny = (rho * w[0] - centre.y() * w[2]) * invR;
  const double nx = valueOf(red.nx), ny = valueOf(red.ny), w3 = valueOf(w[2]);
  red.nn = nx * nx + ny * ny;
  red.w33 = w3 * w3;
  // far <=> delta^2 = nn / w33 > 1 / kFarSeriesP
  red.far = red.w33 < kFarSeriesP * red.nn;
  return red;
}

// F of exact.hpp (columns phi = 1, x, y) from w, as T.
template <class T>
void diskBasis(const Vec2& centre, double R, double rho, const T* w, double relTol, T F[3][3]) {
  const Reduced<T> red = reduce(centre, R, rho, w);
  T gx, gy;  // c' (near) or nh (far)
  T fa;      // force(1) = fa J g
  T Bq, Cq;  // force(q) = Bq J + Cq J (2 g g^T - |g|^2 I)
  T tqs;     // torque_C(q) = tqs g^T
  if (!red.far) {
    const double s = valueOf(w[2]) > 0.0 ? 1.0 : -1.0;
    const T invW3 = reciprocal(w[2]);
    gx = red.nx * invW3;
    gy = red.ny * invW3;
    const T m = gx * gx + gy * gy;
    const Radial3 r = nearRadial<kDeriv<T>>(valueOf(m), red.nn, red.w33, relTol);
    fa = s * lift(r.f[0], r.df[0], m);
    Bq = s * lift(r.f[1], r.df[1], m);
    Cq = s * lift(r.f[2], r.df[2], m);
    tqs = 2.0 * m * Cq;
  } else {
    const T invNorm = reciprocal(sqrt(red.nx * red.nx + red.ny * red.ny));
    gx = red.nx * invNorm;
    gy = red.ny * invNorm;
    const T tau = w[2] * invNorm;
    const T p = tau * tau;
    const Radial3 r = farSeries<kDeriv<T>>(valueOf(p), relTol);
    fa = lift(r.f[0], r.df[0], p);
    const T bt = lift(r.f[1], r.df[1], p);
    const T et = lift(r.f[2], r.df[2], p);
    Bq = 0.5 * (tau * (bt - et));
    Cq = 0.5 * (tau * (bt + et));
    tqs = bt + et;
  }
  // disk-centred wrench in physical units: force(1) ~ R^2, force(q), torque(1) ~ R^3, torque(q) ~
  // R^4
  const double R2 = R * R, R3 = R2 * R, R4 = R3 * R;
  const T f1x = -R2 * (fa * gy), f1y = R2 * (fa * gx);
  const T gxy = 2.0 * (gx * gy), gdd = gx * gx - gy * gy;
  const T fq[2][2] = {{-R3 * (Cq * gxy), R3 * (Cq * gdd - Bq)},
                      {R3 * (Bq + Cq * gdd), R3 * (Cq * gxy)}};
  const T t1 = 2.0 * R3 * Bq;
  const T tq[2] = {R4 * (tqs * gx), R4 * (tqs * gy)};
  // move to O: phi = (1, Cx + qx, Cy + qy), torque_O = torque_C + C x force
  const double cx = centre.x(), cy = centre.y(), invRho = 1.0 / rho;
  F[0][0] = f1x;
  F[1][0] = f1y;
  F[2][0] = (t1 + cx * f1y - cy * f1x) * invRho;
  for (int j = 0; j < 2; ++j) {
    const double cj = (j == 0) ? cx : cy;
    const T fx = cj * f1x + fq[0][j];
    const T fy = cj * f1y + fq[1][j];
    F[0][j + 1] = fx;
    F[1][j + 1] = fy;
    F[2][j + 1] = (cj * t1 + tq[j] + cx * fy - cy * fx) * invRho;
  }
}

// Hertz result of exact.hpp from w, as T.
template <class T>
void diskHertz(const Vec2& centre, double R, double rho, const T* w, double relTol, T out[3]) {
  const Reduced<T> red = reduce(centre, R, rho, w);
  T gx, gy, fa, t1;
  if (!red.far) {
    const double s = valueOf(w[2]) > 0.0 ? 1.0 : -1.0;
    const T invW3 = reciprocal(w[2]);
    gx = red.nx * invW3;
    gy = red.ny * invW3;
    const T m = gx * gx + gy * gy;
    const Radial2 r = hertzNear(valueOf(m), red.nn, red.w33);
    fa = s * lift(r.f[0], r.df[0], m);
    t1 = s * lift(r.f[1], r.df[1], m);
  } else {
    const T invNorm = reciprocal(sqrt(red.nx * red.nx + red.ny * red.ny));
    gx = red.nx * invNorm;
    gy = red.ny * invNorm;
    const T tau = w[2] * invNorm;
    const T p = tau * tau;
    const Radial2 r = hertzFar<kDeriv<T>>(valueOf(p), relTol);
    fa = lift(r.f[0], r.df[0], p);
    t1 = tau * lift(r.f[1], r.df[1], p);
  }
  // unit load: force dimensionless, torque ~ R
  const T fx = -(fa * gy), fy = fa * gx;
  out[0] = fx;
  out[1] = fy;
  out[2] = (R * t1 + centre.x() * fy - centre.y() * fx) * (1.0 / rho);
}

// Checks the inputs and returns the scale sigma = max |w_i| (w / sigma is
// used inside: the result is homogeneous of degree 0 in w).
double checkInputs(const Vec2& centre, double R, double rho, const Vec3& w, double tolerance) {
  const double sigma = w.cwiseAbs().maxCoeff();
  // fast path: everything valid (the sum is finite iff every term is)
  if (R > 0.0 && rho > 0.0 && tolerance >= 0.0 && sigma > 0.0 &&
      std::isfinite(centre.x() + centre.y() + R + rho + w.x() + w.y() + w.z() + tolerance)) {
    return sigma;
  }
  requireFinite(centre, "exact disk: centre");
  requirePositive(R, "exact disk: radius R");
  requirePositive(rho, "exact disk: rho");
  requireFinite(w, "exact disk: slip direction w");
  requireFinite(tolerance, "exact disk: tolerance");
  if (tolerance < 0.0) {
    throw Error("exact disk: tolerance must be >= 0: got " + formatDouble(tolerance));
  }
  if (sigma == 0.0) {
    throw Error("exact disk: slip direction w must be nonzero: got (0, 0, 0)");
  }
  return sigma;
}

double effectiveTol(double tolerance) {
  return tolerance > 0.0 ? tolerance : kFullAccuracy;
}

}  // namespace

void exactDiskBasis(const Vec2& centre, double R, double rho, const Vec3& w, bool wantJacobian,
                    ExactBasis& out, double tolerance) {
  const double invSigma = 1.0 / checkInputs(centre, R, rho, w, tolerance);
  const double relTol = effectiveTol(tolerance);
  if (!wantJacobian) {
    const double ws[3] = {w.x() * invSigma, w.y() * invSigma, w.z() * invSigma};
    double F[3][3];
    diskBasis(centre, R, rho, ws, relTol, F);
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        out.F(i, k) = F[i][k];
      }
    }
    return;
  }
  Dual3 ws[3];
  for (int j = 0; j < 3; ++j) {
    ws[j].v = w[j] * invSigma;
    ws[j].d[j] = 1.0;
  }
  Dual3 F[3][3];
  diskBasis(centre, R, rho, ws, relTol, F);
  // d/dw = (1/sigma) d/dws
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      out.F(i, k) = F[i][k].v;
      for (int j = 0; j < 3; ++j) {
        out.dF[k](i, j) = F[i][k].d[j] * invSigma;
      }
    }
  }
}

Vec3 exactDiskHertz(const Vec2& centre, double R, double rho, const Vec3& w, Mat3* jacobian,
                    double tolerance) {
  const double invSigma = 1.0 / checkInputs(centre, R, rho, w, tolerance);
  const double relTol = effectiveTol(tolerance);
  if (jacobian == nullptr) {
    const double ws[3] = {w.x() * invSigma, w.y() * invSigma, w.z() * invSigma};
    double r[3];
    diskHertz(centre, R, rho, ws, relTol, r);
    return Vec3(r[0], r[1], r[2]);
  }
  Dual3 ws[3];
  for (int j = 0; j < 3; ++j) {
    ws[j].v = w[j] * invSigma;
    ws[j].d[j] = 1.0;
  }
  Dual3 r[3];
  diskHertz(centre, R, rho, ws, relTol, r);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      (*jacobian)(i, j) = r[i].d[j] * invSigma;
    }
  }
  return Vec3(r[0].v, r[1].v, r[2].v);
}

}  // namespace patchspin::internal
