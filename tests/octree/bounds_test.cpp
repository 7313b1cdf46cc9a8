// boundingBox of a placed primitive contains the shape and is tight, the inscribed box lies
// inside it; centerOnVertexMean centres.
#include <gtest/gtest.h>

#include <random>

#include "octomotion/octree/mesh.h"
#include "octomotion/octree/shapes.h"

namespace octomotion {
namespace {

TEST(Bounds, PrimitiveBoxContainsTheShapeAndIsTight) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  const Primitive shapes[] = {Box{Eigen::Vector3d(0.3, 0.1, 0.2)}, Sphere{0.25},
                              Cylinder{0.1, 0.5}};
  for (const Primitive& shape : shapes) {
    for (int trial = 0; trial < 50; ++trial) {
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
      X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 5;
      const Eigen::AlignedBox3d box = boundingBox(shape, X);
      // Sample the shape (rejection in its own bounding cube) and the box's extreme coordinates.
      Eigen::Vector3d reached_min = Eigen::Vector3d::Constant(1e9);
      Eigen::Vector3d reached_max = Eigen::Vector3d::Constant(-1e9);
      for (int s = 0; s < 4000; ++s) {
        const Eigen::Vector3d p_S(u(rng) * 0.35, u(rng) * 0.35, u(rng) * 0.35);
        if (!containsPoint(shape, p_S)) continue;
        const Eigen::Vector3d p_W = X * p_S;
        ASSERT_TRUE(box.contains(p_W));
        reached_min = reached_min.cwiseMin(p_W);
        reached_max = reached_max.cwiseMax(p_W);
      }
      if (std::holds_alternative<Box>(shape)) {
        // A box reaches its bounding box with its corners.
        Eigen::Vector3d corner_min = Eigen::Vector3d::Constant(1e9);
        const Eigen::Vector3d h = std::get<Box>(shape).half_extents;
        for (int i = 0; i < 8; ++i) {
          const Eigen::Vector3d c_S((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                    (i & 4) ? h.z() : -h.z());
          corner_min = corner_min.cwiseMin(X * c_S);
        }
        EXPECT_TRUE(corner_min.isApprox(box.min(), 1e-12));
      }
      if (std::holds_alternative<Sphere>(shape)) {
        EXPECT_NEAR(box.sizes().x(), 0.5, 1e-12);
      }
      // Sampling gets within a few percent of the box on every side.
      EXPECT_LT((reached_min - box.min()).maxCoeff(), 0.1);
      EXPECT_LT((box.max() - reached_max).maxCoeff(), 0.1);
    }
  }
}

// The inscribed box (certain contacts' solid boxes) lies inside the shape, and is the largest
// of its form: grown by 1 % some corner leaves the shape. The shape's own box is the bounding
// box of the shape at its own frame.
TEST(Bounds, InscribedBoxIsInsideTheShapeAndTight) {
  const Primitive shapes[] = {Box{Eigen::Vector3d(0.3, 0.1, 0.2)}, Sphere{0.25}, Cylinder{0.1, 0.5},
                              Cylinder{0.012, 1.3}};
  for (const Primitive& shape : shapes) {
    const Eigen::Vector3d inner = inscribedBoxHalfSides(shape);
    const Eigen::Vector3d outer = boxHalfSides(shape);
    const Eigen::AlignedBox3d box = boundingBox(shape, Eigen::Isometry3d::Identity());
    EXPECT_TRUE(box.max().isApprox(outer, 1e-15));
    EXPECT_TRUE(box.min().isApprox(-outer, 1e-15));
    bool grown_leaves = false;
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
      const Eigen::Vector3d corner = sign.cwiseProduct(inner);
      EXPECT_TRUE(containsPoint(shape, corner * (1 - 1e-12))) << "corner " << i;
      grown_leaves = grown_leaves || !containsPoint(shape, corner * 1.01);
    }
    EXPECT_TRUE(grown_leaves);
    EXPECT_TRUE((inner.array() <= outer.array()).all());
  }
}

TEST(Bounds, CenterOnVertexMean) {
  TriangleMesh mesh;
  mesh.vertices = {{1, 2, 3}, {3, 2, 3}, {2, 5, 3}};
  mesh.triangles = {{0, 1, 2}};
  const Eigen::Vector3d shift = centerOnVertexMean(mesh);
  EXPECT_TRUE(shift.isApprox(Eigen::Vector3d(2, 3, 3)));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) mean += v;
  EXPECT_LT(mean.norm(), 1e-12);
  TriangleMesh empty;
  EXPECT_EQ(centerOnVertexMean(empty), Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace octomotion
