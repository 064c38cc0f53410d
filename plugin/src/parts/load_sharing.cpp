// Load sharing part (load_sharing.hpp).
#include <patchspin/parts/load_sharing.hpp>
#include <patchspin/pressure.hpp>

#include <Eigen/Dense>

#include <cmath>

namespace patchspin::parts {
namespace {

// The first moment (int x p, int y p) in the patch frame of impulses lamN.
Vec2 firstMoment(const Vec3& lamN) {
  return Vec2(-lamN[2], lamN[1]);
}

}  // namespace

bool shareLoads(std::vector<SharedPatch>& patches) {
  if (patches.size() < 2) return false;
  // the union's moments and the group's totals, about the reference origin
  double area = 0.0, total = 0.0;
  Vec2 s1 = Vec2::Zero(), couple = Vec2::Zero();
  Mat2 s2 = Mat2::Zero();
  for (const SharedPatch& p : patches) {
    const AreaMoments& m = p.shape->areaMoments();
    const Vec2 f = p.R * m.first;
    Mat2 j;
    j << m.xx, m.xy, m.xy, m.yy;
    area += m.area;
    s1 += m.area * p.origin + f;
    s2 += m.area * p.origin * p.origin.transpose() + p.origin * f.transpose() +
          f * p.origin.transpose() + p.R * j * p.R.transpose();
    total += p.lamN[0];
    couple += p.lamN[0] * p.origin + p.R * firstMoment(p.lamN);
  }
  if (!(total > 0.0)) return false;
  // (p0, g): [[A, s1^T], [s1, s2]] (p0, g) = (total, couple)
  Mat3 g3;
  g3 << area, s1.x(), s1.y(), s1.x(), s2(0, 0), s2(0, 1), s1.y(), s2(1, 0), s2(1, 1);
  const Eigen::FullPivLU<Mat3> lu(g3);
  if (!lu.isInvertible()) return false;
  const Vec3 field = lu.solve(Vec3(total, couple.x(), couple.y()));
  if (!field.allFinite()) return false;
  const Vec2 g = field.tail<2>();
  // each patch's pressure q0 + h . rho in its frame; none may be negative
  std::vector<Vec3> shared(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const SharedPatch& p = patches[i];
    const double q0 = field[0] + g.dot(p.origin);
    const Vec2 h = p.R.transpose() * g;
    const PatchShape& shape = *p.shape;
    if (shape.isDisk()) {
      if (q0 + h.dot(shape.centre()) - h.norm() * shape.radius() < 0.0) return false;
    } else if (shape.kind() == PatchShape::Kind::ArcRegion) {
      if (minPressure(shape, LinearPressure{q0, h.x(), h.y()}) < 0.0) return false;
    } else {
      for (const Vec2& v : shape.vertices())
        if (q0 + h.dot(v) < 0.0) return false;
    }
    const AreaMoments& m = shape.areaMoments();
    const double pz = q0 * m.area + h.dot(m.first);
    const Vec2 first(q0 * m.first.x() + m.xx * h.x() + m.xy * h.y(),
                     q0 * m.first.y() + m.xy * h.x() + m.yy * h.y());
    shared[i] = Vec3(pz, first.y(), -first.x());
  }
  for (std::size_t i = 0; i < patches.size(); ++i) patches[i].lamN = shared[i];
  return true;
}

}  // namespace patchspin::parts
