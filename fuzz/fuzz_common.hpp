// Shared pieces of the fuzz targets: a tiny byte reader (no FuzzedDataProvider,
// so gcc compiles the targets for the corpus replay), shape construction from
// the input, a failure reporter and bounds on the pressure field.
//
// Contract of every target: each input either makes the core throw
// patchspin::Error with a non-empty message, or gives finite output within the
// bounds the law implies. Anything else (NaN, Inf, a bound broken, another
// exception type) prints what happened and aborts.
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>

#include "../tests/support/convex_hull.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace patchspin::fuzz {

// What the current input decoded to, printed when a check fails.
inline std::string& context() {
  static std::string text;
  return text;
}

// Appends to the context (printf-style).
inline void note(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  context() += buffer;
  context() += '\n';
  static const bool verbose = std::getenv("PATCHSPIN_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "%s\n", buffer);
}

// Prints the broken check and aborts (libFuzzer records the input).
[[noreturn]] inline void fail(const char* format, ...) {
  std::fprintf(stderr, "input:\n%s", context().c_str());
  std::fputs("patchspin fuzz check failed: ", stderr);
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
  std::fputc('\n', stderr);
  std::abort();
}

inline void check(bool ok, const char* what) {
  if (!ok) fail("%s", what);
}

inline void checkFinite(double v, const char* what) {
  if (!std::isfinite(v)) fail("%s is not finite: %.17g", what, v);
}

template <typename Derived>
void checkFinite(const Eigen::MatrixBase<Derived>& m, const char* what) {
  const auto value = m.eval();
  if (!value.allFinite()) fail("%s is not finite (first entry %.17g)", what, value(0, 0));
}

// An Error must say what is wrong.
inline void checkErrorMessage(const Error& e) {
  if (std::strlen(e.what()) == 0) fail("patchspin::Error with an empty message");
}

// Reads the fuzzer's bytes front to back; past the end every read gives 0.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }

  uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }

  // A double, in one of three encodings chosen by a tag byte:
  //   tag <  64: the next 8 bytes taken raw (NaN, Inf, denormals, -0, huge);
  //   tag < 128: a special value (zero, -0, NaN, +-Inf, extremes);
  //   else     : a plain value m 2^e, m a 16-bit integer, e in [-44, 19],
  //              so that ordinary magnitudes are easy to reach.
  double number() {
    const uint8_t tag = byte();
    if (tag < 64) {
      uint8_t raw[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      for (uint8_t& b : raw) b = byte();
      double value;
      std::memcpy(&value, raw, sizeof value);
      return value;
    }
    if (tag < 128) {
      constexpr double kInf = std::numeric_limits<double>::infinity();
      const double specials[16] = {0.0,
                                   -0.0,
                                   std::numeric_limits<double>::quiet_NaN(),
                                   kInf,
                                   -kInf,
                                   std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::min(),
                                   std::numeric_limits<double>::max(),
                                   -std::numeric_limits<double>::max(),
                                   std::numeric_limits<double>::epsilon(),
                                   1e-300,
                                   1e300,
                                   1.0,
                                   -1.0,
                                   0.5,
                                   1e-8};
      return specials[tag % 16];
    }
    const int16_t mantissa =
        static_cast<int16_t>(static_cast<uint16_t>(byte()) | static_cast<uint16_t>(byte()) << 8);
    return std::ldexp(static_cast<double>(mantissa), (tag & 63) - 44);
  }

  Vec2 vec2() {
    const double x = number();
    return Vec2(x, number());
  }
  Vec3 vec3() {
    const double x = number(), y = number();
    return Vec3(x, y, number());
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

using patchspin::testing::convexHull;

// Largest number of polygon vertices read from one input.
constexpr int kMaxVertices = 12;

// 3 to kMaxVertices points from the input; `finite` false if one is not.
inline std::vector<Vec2> takePoints(ByteReader& in, bool& finite) {
  const int n = 3 + in.byte() % (kMaxVertices - 2);
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    v.push_back(in.vec2());
    finite = finite && v.back().allFinite();
  }
  return v;
}

// An arc region (PatchShape::arcRegion) from the input: `pick` 0 a disk cut
// by the convex hull of given points (diskPolygonIntersection; points that
// are not finite go to PatchShape::polygon, which refuses them), 1 a lens
// (diskDiskIntersection), 2 boundary pieces as given (often invalid: the
// constructor must say why).
inline PatchShape takeArcRegion(ByteReader& in, int pick) {
  if (pick == 0) {
    const double R = in.number();
    const Vec2 c = in.vec2();
    bool finite = true;
    const std::vector<Vec2> v = takePoints(in, finite);
    if (!finite) return PatchShape::polygon(v);
    return PatchShape::arcRegion(diskPolygonIntersection(c, R, convexHull(v)));
  }
  if (pick == 1) {
    const double r1 = in.number();
    const Vec2 c1 = in.vec2();
    const double r2 = in.number();
    return PatchShape::arcRegion(diskDiskIntersection(c1, r1, in.vec2(), r2));
  }
  const int n = 1 + in.byte() % 6;
  std::vector<BoundaryPiece> pieces;
  for (int i = 0; i < n; ++i) {
    if (in.byte() & 1) {
      const Vec2 c = in.vec2();
      const double r = in.number(), t0 = in.number();
      pieces.push_back(BoundaryPiece::arc(c, r, t0, in.number()));
    } else {
      const Vec2 a = in.vec2();
      pieces.push_back(BoundaryPiece::segment(a, in.vec2()));
    }
  }
  return PatchShape::arcRegion(pieces);
}

// The points of an arc region where a linear function with gradient
// (gx, gy) takes its extremes: the pieces' start points and, on each arc,
// its points of outward normal +-(gx, gy) / |(gx, gy)| where the arc reaches
// them (the harness's own computation, not the core's).
inline std::vector<Vec2> arcRegionExtremePoints(const PatchShape& shape, double gx, double gy) {
  constexpr double kTwoPi = 6.283185307179586476925286766559;
  std::vector<Vec2> points;
  for (const BoundaryPiece& p : shape.boundary()) {
    points.push_back(p.start());
    if (p.kind != BoundaryPiece::Kind::Arc) continue;
    for (const double t : {std::atan2(gy, gx), std::atan2(-gy, -gx)}) {
      double d = std::fmod(t - p.angle0, kTwoPi);
      if (d < 0.0) d += kTwoPi;
      if (d <= p.angle1 - p.angle0)
        points.push_back(p.centre + p.radius * Vec2(std::cos(t), std::sin(t)));
    }
  }
  return points;
}

// A patch shape from the input: a disk, a rectangle, a polygon with the
// vertices as given (often invalid: the constructor must say why), the convex
// hull of given points (valid unless degenerate), a regular polygon, or an
// arc region (where the regular polygon's count byte says n <= 0, which the
// counts 1 and 2 still show refused); optionally moved to another frame.
// Throws Error for invalid shapes.
inline PatchShape takeShape(ByteReader& in) {
  const uint8_t kind = in.byte();
  PatchShape shape = PatchShape::disk(1.0);
  switch (kind % 5) {
    case 0: {
      const double R = in.number();
      shape = PatchShape::disk(R, in.vec2());
      break;
    }
    case 1: {
      const double lx = in.number(), ly = in.number();
      const Vec2 c = in.vec2();
      shape = PatchShape::rectangle(lx, ly, c, in.number());
      break;
    }
    case 2:
    case 3: {
      bool finite = true;
      std::vector<Vec2> v = takePoints(in, finite);
      if (kind % 5 == 3 && finite) {
        const std::vector<Vec2> hull = convexHull(v);
        if (hull.size() >= 3) v = hull;
      }
      shape = PatchShape::polygon(v);
      break;
    }
    default: {
      const int n = static_cast<int>(in.byte() % 40) - 2;
      if (n <= 0) {
        shape = takeArcRegion(in, n + 2);
        break;
      }
      const double radius = in.number();
      const Vec2 c = in.vec2();
      shape = PatchShape::regularPolygon(n, radius, c, in.number());
      break;
    }
  }
  if (kind & 0x80) {
    const Vec2 origin = in.vec2();
    shape = shape.inFrame(origin, in.number());
  }
  if (shape.isDisk()) {
    note("disk R = %.17g, centre (%.17g, %.17g)", shape.radius(), shape.centre().x(),
         shape.centre().y());
  } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
    note("arc region of %zu pieces:", shape.boundary().size());
    for (const BoundaryPiece& p : shape.boundary()) {
      if (p.kind == BoundaryPiece::Kind::Arc) {
        note("  arc centre (%.17g, %.17g) R %.17g angles %.17g to %.17g", p.centre.x(),
             p.centre.y(), p.radius, p.angle0, p.angle1);
      } else {
        note("  segment (%.17g, %.17g) to (%.17g, %.17g)", p.a.x(), p.a.y(), p.b.x(), p.b.y());
      }
    }
  } else {
    note("polygon with %zu vertices:", shape.vertices().size());
    for (const Vec2& v : shape.vertices()) note("  (%.17g, %.17g)", v.x(), v.y());
  }
  return shape;
}

// p0 + cx x + cy y in long double (x87: 64-bit mantissa, range to 1e4932):
// the harness's reference value, without the intermediate overflow of
// LinearPressure::at (p0 ~ cy ~ 1e308 at y = -2 overflowed to -inf while the
// pressure itself, -1.2e308, is finite; found by fuzzing)
inline long double pressureAt(const LinearPressure& p, const Vec2& point) {
  return static_cast<long double>(p.p0) + static_cast<long double>(p.cx) * point.x() +
         static_cast<long double>(p.cy) * point.y();
}

// |p0| + |cx x| + |cy y|: the size of the terms whose double sum (the core's
// own evaluation) rounds to ~eps times it
inline long double pressureTerms(const LinearPressure& p, const Vec2& point) {
  return std::abs(static_cast<long double>(p.p0)) +
         std::abs(static_cast<long double>(p.cx) * point.x()) +
         std::abs(static_cast<long double>(p.cy) * point.y());
}

// Largest |p| of a linear pressure over the closed patch (at a vertex, at
// p(C) +- R |grad p| on a disk, at an arc region's extreme points).
inline double maxAbsPressure(const PatchShape& shape, const LinearPressure& p) {
  if (shape.isDisk()) {
    return std::abs(p.at(shape.centre())) + shape.radius() * std::hypot(p.cx, p.cy);
  }
  double m = 0.0;
  if (shape.kind() == PatchShape::Kind::ArcRegion) {
    for (const Vec2& v : arcRegionExtremePoints(shape, p.cx, p.cy))
      m = std::max(m, std::abs(p.at(v)));
    return m;
  }
  for (const Vec2& v : shape.vertices()) m = std::max(m, std::abs(p.at(v)));
  return m;
}

// Upper bound of ∫|p| dA: Pz when p >= 0 on the patch, A max|p| otherwise.
inline double absPressureIntegral(const PatchShape& shape, const LinearPressure& p, double Pz) {
  return minPressure(shape, p) >= 0.0 ? Pz : shape.area() * maxAbsPressure(shape, p);
}

// One fuzz input through a target's run(): either the core throws
// patchspin::Error with a message, or run()'s checks pass; any other
// exception fails. Every target's LLVMFuzzerTestOneInput calls this.
inline int runInput(const uint8_t* data, size_t size, void (*run)(ByteReader&)) {
  ByteReader in(data, size);
  context().clear();
  try {
    run(in);
  } catch (const Error& e) {
    checkErrorMessage(e);
  } catch (const std::exception& e) {
    fail("exception other than patchspin::Error: %s", e.what());
  }
  return 0;
}

}  // namespace patchspin::fuzz
