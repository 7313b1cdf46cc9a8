// The environment: universe fitting, and the environment tree as the union of its objects.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "octomotion/error.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/octree/set_ops.h"
#include "octomotion/octree/voxelize.h"
#include "octomotion/planner/scene/environment_geometry.h"
#include "octomotion/pointcloud/environment.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion {
namespace {

TEST(FitGrid, CoversTheRegionWithTheFewestLevels) {
  const Eigen::AlignedBox3d region(Eigen::Vector3d(-1, -0.5, 0), Eigen::Vector3d(1.5, 0.5, 2));
  for (double res : {0.1, 0.02, 0.01, 0.005, 0.001}) {
    const WorldGrid g = fitGrid(region, res);
    EXPECT_EQ(g.origin(), region.min());
    EXPECT_DOUBLE_EQ(g.voxelSize(), res);
    EXPECT_GE(g.sideMetres(), 2.5);              // covers the longest side
    EXPECT_LT(g.sideMetres() / 2, 2.5 + 1e-12);  // one level fewer would not
  }
  EXPECT_EQ(fitGrid(region, 100.0).depth(), 1);
  try {
    fitGrid(Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(3000)), 1e-4);
    ADD_FAILURE();
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("coarser resolution"));
  }
  EXPECT_THROW(fitGrid(region, 0.0), InvalidArgument);
  EXPECT_THROW(fitGrid(region, std::nan("")), InvalidArgument);
  EXPECT_THROW(fitGrid(Eigen::AlignedBox3d(), 0.01), InvalidArgument);
}

TEST(Environment, IsTheUnionOfItsObjects) {
  std::vector<EnvironmentObject> objects(3);
  objects[0].name = "board";
  objects[0].primitive = Box{Eigen::Vector3d(0.4, 0.15, 0.01)};
  objects[0].X_WO.translation() = Eigen::Vector3d(0.6, 0, 0.4);
  objects[1].name = "ball";
  objects[1].primitive = Sphere{0.1};
  objects[1].X_WO.translation() = Eigen::Vector3d(0.2, 0.3, 0.5);
  objects[2].name = "post";
  objects[2].kind = EnvironmentObject::Kind::kMesh;
  objects[2].file = std::string(OCTOMOTION_SOURCE_DIR) + "/robots/meshes/octo6/base.stl";
  objects[2].X_WO.translation() = Eigen::Vector3d(-0.3, 0, 0);

  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  ASSERT_EQ(env.size(), 3u);
  const auto bounds = env.bounds();
  ASSERT_TRUE(bounds.has_value());
  EXPECT_NEAR(bounds->max().x(), 1.0, 1e-9);    // board reaches 0.6 + 0.4
  EXPECT_NEAR(bounds->min().x(), -0.38, 1e-6);  // base mesh radius 0.08 around -0.3
  EXPECT_NEAR(bounds->max().z(), 0.6, 1e-9);    // ball top

  const WorldGrid grid = fitGrid(*bounds, 0.02);
  for (Rounding rounding : {Rounding::kConservative, Rounding::kCenter}) {
    EnvironmentReport report;
    const Octree all = env.voxelize(grid, rounding, &report);
    Octree expected(grid);
    expected = unite(expected, voxelize(grid, objects[0].primitive, objects[0].X_WO, rounding));
    expected = unite(expected, voxelize(grid, objects[1].primitive, objects[1].X_WO, rounding));
    expected =
        unite(expected, voxelizeMesh(grid, loadMesh(objects[2].file), objects[2].X_WO, rounding));
    EXPECT_EQ(all, expected);
    ASSERT_EQ(report.objects.size(), 3u);
    EXPECT_EQ(report.objects[1].name, "ball");
    EXPECT_GT(report.objects[1].black_leaves, 0u);
    EXPECT_EQ(report.internal_nodes, all.internalNodeCount());
    EXPECT_EQ(report.bytes, all.bytes());
  }
}

TEST(Environment, OctoMapObjectsAndBadInput) {
  // An OctoMap written by our exporter on its native grid comes back as the same occupancy.
  const WorldGrid native = octomapNativeGrid(0.05);
  const Octree box =
      voxelize(native, Box{Eigen::Vector3d(0.2, 0.1, 0.1)},
               Eigen::Isometry3d(Eigen::Translation3d(1, 1, 0.5)), Rounding::kCenter);
  const std::string path =
      (std::filesystem::temp_directory_path() / "octomotion_env_test.bt").string();
  exportOctoMap(box, path);
  std::vector<EnvironmentObject> objects(1);
  objects[0].kind = EnvironmentObject::Kind::kOctomap;
  objects[0].file = path;
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  ASSERT_TRUE(env.bounds().has_value());
  EXPECT_NEAR(env.bounds()->min().x(), 0.8, 1e-9);
  EXPECT_NEAR(env.bounds()->max().x(), 1.2, 1e-9);
  const WorldGrid grid = fitGrid(*env.bounds(), 0.05);
  const Octree tree = env.voxelize(grid, Rounding::kCenter);
  EXPECT_EQ(tree.blackVoxelCount(), box.blackVoxelCount());
  std::filesystem::remove(path);

  objects[0].X_WO.translation() = Eigen::Vector3d(1, 0, 0);
  EXPECT_THROW(EnvironmentGeometry::load(objects), InvalidArgument);
  objects[0].kind = EnvironmentObject::Kind::kMesh;
  objects[0].file = "/no/such/mesh.stl";
  EXPECT_THROW(EnvironmentGeometry::load(objects), FileError);
  objects[0].kind = EnvironmentObject::Kind::kPrimitive;
  objects[0].primitive = Sphere{-1};
  EXPECT_THROW(EnvironmentGeometry::load(objects), InvalidArgument);
}

TEST(Environment, PointCloudObjectsMarkTheirVoxels) {
  // A scanned table top: points on a 1 m x 0.6 m plane at 0.7 m, plus legs.
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 60; ++j) points.emplace_back(0.01f * i, 0.01f * j, 0.7f);
  for (int k = 0; k < 70; ++k) points.emplace_back(0.02f, 0.02f, 0.01f * k);
  const std::string path =
      (std::filesystem::temp_directory_path() / "octomotion_env_cloud.pcd").string();
  pointcloud::savePcd(path, points, pointcloud::Encoding::kBinary);
  std::vector<EnvironmentObject> objects(1);
  objects[0].kind = EnvironmentObject::Kind::kPointCloud;
  objects[0].file = path;
  objects[0].X_WO.translation() = Eigen::Vector3d(1, 0, 0);  // the cloud is moved 1 m along x
  const EnvironmentGeometry env = EnvironmentGeometry::load(objects);
  ASSERT_TRUE(env.bounds().has_value());
  EXPECT_NEAR(env.bounds()->min().x(), 1.0, 1e-6);
  EXPECT_NEAR(env.bounds()->max().x(), 2.0, 1e-6);
  EXPECT_NEAR(env.bounds()->max().z(), 0.7, 1e-6);
  const WorldGrid grid = fitGrid(*env.bounds(), 0.02);
  for (Rounding rounding : {Rounding::kConservative, Rounding::kCenter}) {
    const Octree tree = env.voxelize(grid, rounding);
    std::vector<Eigen::Vector3f> moved;
    for (const auto& p : points) moved.push_back(p + Eigen::Vector3f(1, 0, 0));
    EXPECT_EQ(tree, pointcloud::environmentFromPoints(grid, moved));
    for (const auto& p : moved) EXPECT_TRUE(tree.occupiedAt(p.cast<double>()));
  }
  std::filesystem::remove(path);
  objects[0].file = "/no/such/cloud.pcd";
  EXPECT_THROW(EnvironmentGeometry::load(objects), FileError);
}

}  // namespace
}  // namespace octomotion
