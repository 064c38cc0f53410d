// Shared pieces of the stress tests (issue 6): the opt-in switch for the full
// runs, geometry probes (lowest point of a box or cylinder, for
// penetration), and a plain-text table that is printed and, if
// PATCHSPIN_STRESS_TABLE names a file, appended to it (scripts/stress.sh
// collects the tables that way). Worlds, bodies and friction laws come from
// the scene library (scenes/).
#pragma once

#include <patchspin/bullet/patch_friction_solver.hpp>
#include <patchspin/scenes/catalogue.hpp>
#include <patchspin/scenes/scene.hpp>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace patchspin::bullet::stress {

using scenes::bt;
using scenes::Friction;
using scenes::optIn;
using scenes::precisionName;
using scenes::Scene;
using scenes::toString;
constexpr bool kDouble = scenes::kDoublePrecision;

// PATCHSPIN_STRESS_FULL=1 (any value but "0" or empty) runs the full matrix
// and the full-size scenes; otherwise the fast subset of the default suite.
inline bool stressFull() {
  const char* v = std::getenv("PATCHSPIN_STRESS_FULL");
  return v && *v && std::string(v) != "0";
}

inline bool isFinite(const btVector3& v) {
  return std::isfinite(double(v.x())) && std::isfinite(double(v.y())) &&
         std::isfinite(double(v.z()));
}
inline bool isFinite(const btRigidBody* b) {
  const btTransform& t = b->getWorldTransform();
  return isFinite(t.getOrigin()) && isFinite(t.getBasis().getColumn(0)) &&
         isFinite(t.getBasis().getColumn(2)) && isFinite(b->getLinearVelocity()) &&
         isFinite(b->getAngularVelocity());
}

// Lowest / highest z of the body's real outline (boxes: corners with margin;
// Z cylinders: the lowest rim point of a cap; convex hulls: the extreme
// point plus the margin), for penetration and stacks.
inline double extremeZ(const btRigidBody* b, bool lowest) {
  const btCollisionShape* s = b->getCollisionShape();
  const btTransform& t = b->getWorldTransform();
  const double sign = lowest ? 1.0 : -1.0;
  if (s->getShapeType() == BOX_SHAPE_PROXYTYPE) {
    const btVector3 h = static_cast<const btBoxShape*>(s)->getHalfExtentsWithMargin();
    double best = sign * 1e300;
    for (int i = 0; i < 8; ++i) {
      const btVector3 c = t * btVector3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                        (i & 4) ? h.z() : -h.z());
      best = lowest ? std::min(best, double(c.z())) : std::max(best, double(c.z()));
    }
    return best;
  }
  if (s->getShapeType() == CYLINDER_SHAPE_PROXYTYPE) {
    const auto* c = static_cast<const btCylinderShape*>(s);
    const btVector3 h = c->getHalfExtentsWithMargin();
    const int axis = c->getUpAxis();
    const double R = double(c->getRadius()), H = double(h[axis]);
    const double az = double(t.getBasis().getColumn(axis).z());
    const double reach = std::abs(az) * H + R * std::sqrt(std::max(0.0, 1.0 - az * az));
    return double(t.getOrigin().z()) - sign * reach;
  }
  if (s->getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE) {
    // a hull's outline is its points plus the margin all round
    const auto* h = static_cast<const btConvexHullShape*>(s);
    double best = sign * 1e300;
    for (int i = 0; i < h->getNumPoints(); ++i) {
      const double z = double((t * h->getScaledPoint(i)).z());
      best = lowest ? std::min(best, z) : std::max(best, z);
    }
    return best - sign * double(h->getMargin());
  }
  btVector3 lo, hi;
  s->getAabb(t, lo, hi);
  return lowest ? double(lo.z()) : double(hi.z());
}

// Table printed to stdout and appended to $PATCHSPIN_STRESS_TABLE.
class Table {
 public:
  Table(std::string title, std::vector<std::string> header)
      : title_(std::move(title)), header_(std::move(header)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string str() const {
    std::vector<size_t> w(header_.size(), 0);
    for (size_t i = 0; i < header_.size(); ++i) w[i] = header_[i].size();
    for (const auto& r : rows_)
      for (size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], r[i].size());
    auto line = [&](const std::vector<std::string>& r) {
      std::string s = "|";
      for (size_t i = 0; i < w.size(); ++i) {
        const std::string c = i < r.size() ? r[i] : "";
        s += " " + c + std::string(w[i] - c.size(), ' ') + " |";
      }
      return s + "\n";
    };
    std::string out = "\n### " + title_ + " (" + precisionName() + " Bullet)\n\n" + line(header_);
    std::string sep = "|";
    for (size_t i = 0; i < w.size(); ++i) sep += std::string(w[i] + 2, '-') + "|";
    out += sep + "\n";
    for (const auto& r : rows_) out += line(r);
    return out;
  }
  void emit() const {
    const std::string s = str();
    std::fputs(s.c_str(), stdout);
    std::fflush(stdout);
    if (const char* path = std::getenv("PATCHSPIN_STRESS_TABLE"); path && *path) {
      if (FILE* f = std::fopen(path, "a")) {
        std::fputs(s.c_str(), f);
        std::fclose(f);
      }
    }
  }

 private:
  std::string title_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

inline std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
inline const char* passFail(bool ok) {
  return ok ? "ok" : "FAIL";
}

}  // namespace patchspin::bullet::stress
