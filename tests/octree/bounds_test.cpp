// boundingBox of a placed primitive contains the shape and is tight; centerOnVertexMean centres.
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
