// The memory guard (CollisionModelOptions::max_surface_voxels): building an environment or a link
// tree whose estimated size exceeds the limit fails early, before any voxel is allocated, with an
// octomotion::Error naming the object and suggesting a coarser resolution. The limit is settable
// from the scene file (octree.max_surface_voxels), from SceneOverrides and from the command line
// (--max-surface-voxels), and it applies to every kind of environment object: primitives and
// meshes by the surface of their box, point clouds by their point count (one voxel per point at
// most, so a sparse scan over a large region is not rejected), OctoMaps by their box.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "octomotion/error.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kSource = OCTOMOTION_SOURCE_DIR;

fs::path scratchDir() {
  const fs::path dir = fs::temp_directory_path() / "octomotion_memory_limit_test";
  fs::create_directories(dir);
  return dir;
}

// A rigid sphere flying in the given box.
RobotModel ball() {
  CollisionElement e;
  e.geometry = Primitive{Sphere{0.02}};  // 150 surface voxels at 1 cm
  return RobotModel::rigidBody("ball", {e});
}

std::string expectRejected(const std::function<void()>& build) {
  try {
    build();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "built past the memory limit";
  return "";
}

TEST(MemoryLimit, SceneFileKeyFailsEarly) {
  const fs::path scene = scratchDir() / "fine_wall.yaml";
  std::ofstream(scene) << "robot: {mesh: " << kSource << "/robots/meshes/rigid/l_piece.stl}\n"
                       << "environment:\n"
                       << "  - {name: wall, box: {size: [0.05, 1.2, 1.2]}}\n"
                       << "octree: {resolution: 0.002, max_surface_voxels: 100000}\n"
                       << "problem: {bounds: {min: [-1, -1, -1], max: [1, 1, 1]}}\n";
  const std::string what = expectRejected([&] { loadPlanningScene(scene.string()); });
  EXPECT_THAT(what, HasSubstr("limit 100000"));
  EXPECT_THAT(what, HasSubstr("coarser resolution"));
  // A coarser resolution fits under the same limit: the guard is an estimate, not a ban.
  SceneOverrides coarser;
  coarser.resolution = 0.02;
  EXPECT_NO_THROW(loadPlanningScene(scene.string(), coarser));
  // The key is validated like every other field.
  try {
    parseSceneYaml("robot: {mesh: a.stl}\noctree: {max_surface_voxels: -5}\n", "/s/bad.yaml");
    ADD_FAILURE() << "a negative limit was accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("octree.max_surface_voxels"));
  }
}

TEST(MemoryLimit, OverrideAndCommandLine) {
  const std::string bookshelf = kSource + "/robots/scenes/bookshelf.yaml";
  SceneOverrides overrides;
  overrides.max_surface_voxels = 1500;  // link0 (18 x 18 x 14 cm) has about 1,860 at 1 cm
  const std::string what = expectRejected([&] { loadPlanningScene(bookshelf, overrides); });
  EXPECT_THAT(what, HasSubstr("link link0"));
  EXPECT_THAT(what, HasSubstr("limit 1500"));

  const fs::path err = scratchDir() / "stderr.txt";
  const std::string cmd = std::string(OCTOMOTION_CLI) + " info " + bookshelf +
                          " --max-surface-voxels 1500 >/dev/null 2>" + err.string();
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0);
  std::stringstream text;
  text << std::ifstream(err).rdbuf();
  const std::string message = text.str();
  EXPECT_THAT(message, HasSubstr("limit 1500"));
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
}

TEST(MemoryLimit, PointCloudsCountPointsNotTheirBox) {
  // 1,000 points over a 60 m region: its box would have 2e8 surface voxels at 1 cm, its tree has
  // at most 1,000 voxels.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-30.f, 30.f);
  std::vector<Eigen::Vector3f> points(1000);
  for (auto& p : points) p = {coord(rng), coord(rng), coord(rng)};
  const fs::path file = scratchDir() / "sparse_scan.xyz";
  pointcloud::saveXyz(file.string(), points);
  EnvironmentObject cloud;
  cloud.name = "scan";
  cloud.kind = EnvironmentObject::Kind::kPointCloud;
  cloud.file = file.string();
  const EnvironmentGeometry env = EnvironmentGeometry::load({cloud});
  CollisionModelOptions options;
  options.resolution = 0.01;
  options.base_position_bounds =
      Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-30), Eigen::Vector3d::Constant(30));
  const OctreeCollisionModel model(ball(), env, options);
  EXPECT_LE(model.environment().blackLeafCount(), 1000u);
  options.max_surface_voxels = 500;
  options.link_resolution = 0.01;  // the ball fits at 1 cm (at the default 1/4 cm it would not)
  const std::string what = expectRejected([&] { OctreeCollisionModel(ball(), env, options); });
  EXPECT_THAT(what, HasSubstr("scan"));
  EXPECT_THAT(what, HasSubstr("coarser resolution"));
}

TEST(MemoryLimit, OctoMapImportsAreGuarded) {
  // A solid 2.56 m block written as a .bt: about 400,000 surface voxels at 1 cm.
  const WorldGrid grid(Eigen::Vector3d::Zero(), 0.01, 8);
  const fs::path file = scratchDir() / "block.bt";
  exportOctoMap(Octree::full(grid), file.string());
  EnvironmentObject map;
  map.name = "the_map";
  map.kind = EnvironmentObject::Kind::kOctomap;
  map.file = file.string();
  const EnvironmentGeometry env = EnvironmentGeometry::load({map});
  CollisionModelOptions options;
  options.resolution = 0.01;
  options.base_position_bounds =
      Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(3));
  options.max_surface_voxels = 100000;
  const std::string what = expectRejected([&] { OctreeCollisionModel(ball(), env, options); });
  EXPECT_THAT(what, HasSubstr("the_map"));
  options.max_surface_voxels = 1e6;
  const OctreeCollisionModel model(ball(), env, options);
  EXPECT_FALSE(model.environment().empty());
}

}  // namespace
}  // namespace octomotion
