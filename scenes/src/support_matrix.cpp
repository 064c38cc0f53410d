// Support matrix scenes (support_matrix.hpp).
#include <patchspin/scenes/inertia.hpp>
#include <patchspin/scenes/support_matrix.hpp>
#include <patchspin/scenes/terrain.hpp>

#include <cmath>

namespace patchspin::scenes {
namespace {

constexpr double kSetDown = 1e-5;  // [m] into the support
constexpr double kHullMargin = 1e-4;

btTransform at(double x, double y, double z) {
  btTransform tr;
  tr.setIdentity();
  tr.setOrigin(bt(x, y, z));
  return tr;
}

}  // namespace

const std::vector<BodyShape>& allBodyShapes() {
  static const std::vector<BodyShape> all = {BodyShape::Box,        BodyShape::Cylinder,
                                             BodyShape::ConvexHull, BodyShape::Compound,
                                             BodyShape::Sphere,     BodyShape::Capsule};
  return all;
}

const std::vector<SupportShape>& allSupportShapes() {
  static const std::vector<SupportShape> all = {
      SupportShape::Plane,      SupportShape::Box,         SupportShape::CylinderCap,
      SupportShape::ConvexHull, SupportShape::DynamicBox,  SupportShape::TriangleMesh,
      SupportShape::ScaledMesh, SupportShape::Heightfield, SupportShape::Compound};
  return all;
}

std::string toString(BodyShape b) {
  switch (b) {
    case BodyShape::Box:
      return "box";
    case BodyShape::Cylinder:
      return "cylinder";
    case BodyShape::ConvexHull:
      return "convex hull";
    case BodyShape::Compound:
      return "compound";
    case BodyShape::Sphere:
      return "sphere";
    case BodyShape::Capsule:
      return "capsule";
  }
  return "?";
}

std::string toString(SupportShape s) {
  switch (s) {
    case SupportShape::Plane:
      return "plane";
    case SupportShape::Box:
      return "box";
    case SupportShape::CylinderCap:
      return "cylinder cap";
    case SupportShape::ConvexHull:
      return "convex hull";
    case SupportShape::DynamicBox:
      return "dynamic box";
    case SupportShape::TriangleMesh:
      return "triangle mesh";
    case SupportShape::ScaledMesh:
      return "scaled mesh";
    case SupportShape::Heightfield:
      return "heightfield";
    case SupportShape::Compound:
      return "compound";
  }
  return "?";
}

btRigidBody* addSupport(Scene& scene, SupportShape s) {
  const btVector3 half(0.5f, 0.5f, 0.05f);
  switch (s) {
    case SupportShape::Plane:
      return scene.addGroundPlane(1.0);
    case SupportShape::Box:
      return scene.addStaticBox(half, bt(0, 0, -0.05), 1.0);
    case SupportShape::CylinderCap:
      return scene.addCylinder(0.5, 0.1, 0.0, bt(0, 0, -0.05), 1.0);
    case SupportShape::ConvexHull: {
      // the hull's points one margin inside the box: its surface is the box
      auto hull = std::make_unique<btConvexHullShape>();
      hull->setMargin(btScalar(kHullMargin));
      for (int k = 0; k < 8; ++k) {
        const double m = kHullMargin;
        hull->addPoint(bt((k & 1 ? 1 : -1) * (0.5 - m), (k & 2 ? 1 : -1) * (0.5 - m),
                          (k & 4 ? 1 : -1) * (0.05 - m)),
                       k == 7);
      }
      return scene.addBody(std::move(hull), 0, btVector3(0, 0, 0), at(0, 0, -0.05), 1.0);
    }
    case SupportShape::DynamicBox:
      // (on the plane z = -0.1)
      scene.addBody(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(-0.1)), 0,
                    btVector3(0, 0, 0), at(0, 0, 0), 1.0);
      return scene.addBox(half, 10.0, bt(0, 0, -0.05), 1.0);
    case SupportShape::TriangleMesh:
    case SupportShape::ScaledMesh:
    case SupportShape::Heightfield: {
      GroundSpec g;
      g.kind = s == SupportShape::Heightfield ? Ground::Heightfield : Ground::TriangleMesh;
      if (s == SupportShape::ScaledMesh) g.meshScale = 2.5;
      return addGround(scene, g, 1.0);
    }
    case SupportShape::Compound: {
      std::vector<CompoundPart> parts(2);
      for (int i = 0; i < 2; ++i) {
        parts[std::size_t(i)].shape = std::make_unique<btBoxShape>(half);
        parts[std::size_t(i)].pose.setOrigin(bt(2.0 * i, 0, 0));
      }
      return scene.addCompound(std::move(parts), at(0, 0, -0.05), 1.0);
    }
  }
  throw Error("addSupport: unknown support shape");
}

btRigidBody* addBodyOnTop(Scene& scene, BodyShape b) {
  switch (b) {
    case BodyShape::Box:
      return scene.addBox(bt(0.05, 0.05, 0.025), 1.0, bt(0, 0, 0.025 - kSetDown), 0.3);
    case BodyShape::Cylinder:
      return scene.addCylinder(0.05, 0.01, 1.0, bt(0, 0, 0.005 - kSetDown), 0.3);
    case BodyShape::ConvexHull: {
      const double a = 0.05, h = 0.02, m = kHullMargin;
      auto hull = std::make_unique<btConvexHullShape>();
      hull->setMargin(btScalar(m));
      for (int k = 0; k < 6; ++k) {
        const double phi = M_PI / 3 * k;
        const double r = a - m / std::cos(M_PI / 6);  // the hull's sides one margin inside
        hull->addPoint(bt(r * std::cos(phi), r * std::sin(phi), -(h / 2 - m)), false);
        hull->addPoint(bt(r * std::cos(phi), r * std::sin(phi), h / 2 - m), k == 5);
      }
      return scene.addBody(std::move(hull), 1.0, hexagonalPrismInertia(1.0, a, h),
                           at(0, 0, h / 2 - kSetDown), 0.3);
    }
    case BodyShape::Compound: {
      // box 10 x 10 x 3 cm (0.8 kg) from z = 0 to 0.03, post R 2 cm, 6 cm
      // high (0.2 kg) on it; the compound frame at the base's bottom centre
      std::vector<CompoundPart> parts(2);
      auto box = std::make_unique<btBoxShape>(bt(0.05, 0.05, 0.015));
      box->setMargin(btScalar(1e-3));
      parts[0].shape = std::move(box);
      parts[0].pose.setOrigin(bt(0, 0, 0.015));
      parts[0].mass = 0.8;
      parts[0].inertia = boxInertia(0.8, 0.1, 0.1, 0.03);
      auto post = std::make_unique<btCylinderShapeZ>(bt(0.02, 0.02, 0.03));
      post->setMargin(btScalar(1e-3));
      parts[1].shape = std::move(post);
      parts[1].pose.setOrigin(bt(0, 0, 0.06));
      parts[1].mass = 0.2;
      parts[1].inertia = cylinderInertia(0.2, 0.02, 0.06);
      return scene.addCompound(std::move(parts), at(0, 0, -kSetDown), 0.3);
    }
    case BodyShape::Sphere:
      return scene.addSphere(0.05, 1.0, bt(0, 0, 0.05 - kSetDown), 0.3);
    case BodyShape::Capsule: {
      const double r = 0.02, len = 0.1;
      // the inertia of a ball of the capsule's half length (not the
      // capsule's: the body only has to rest on the support)
      const btVector3 inertia = sphereInertia(1.0, r + len / 2);
      return scene.addBody(std::make_unique<btCapsuleShapeX>(btScalar(r), btScalar(len)), 1.0,
                           inertia, at(0, 0, r - kSetDown), 0.3);
    }
  }
  throw Error("addBodyOnTop: unknown body shape");
}

}  // namespace patchspin::scenes
