// A plain Sutherland-Hodgman clipper for tests: the convex polygon
// `subject` clipped by the convex counter-clockwise polygon `clip`. The
// n-gon references of the arc-region tests (a disk as a clipped n-gon);
// independent of the Bullet layer's clipConvex.
#pragma once

#include <patchspin/types.hpp>

#include <vector>

namespace patchspin::testing {

inline std::vector<Vec2> clipPolygon(std::vector<Vec2> subject, const std::vector<Vec2>& clip) {
  for (std::size_t i = 0; i < clip.size(); ++i) {
    const Vec2 a = clip[i], e = clip[(i + 1) % clip.size()] - a;
    auto side = [&](const Vec2& p) { return e.x() * (p - a).y() - e.y() * (p - a).x(); };
    std::vector<Vec2> out;
    for (std::size_t k = 0; k < subject.size(); ++k) {
      const Vec2 p = subject[k], q = subject[(k + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back(p + sp / (sp - sq) * (q - p));
    }
    subject = out;
  }
  return subject;
}

}  // namespace patchspin::testing
