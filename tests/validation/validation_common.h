// Shared by the validation tests (docs/validation.md): which scenes, at which resolution, and
// uniform random states of a scene's robot drawn with a fixed seed.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/util/Console.h>
#include <Eigen/Geometry>

#include "octomotion/planner/fcl_checker.h"
#include "octomotion/planner/planning_scene.h"

namespace octomotion::validation {

// Every scene in robots/scenes (the directory is listed, so scenes added later are validated
// too), plus the one-link-URDF rigid body of the test data.
inline std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(OCTOMOTION_SOURCE_DIR) + "/robots/scenes")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  files.push_back(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/l_piece_urdf.yaml");
  return files;
}

// The scenes with primitives among their obstacles (CollisionModelOptions::exact_primitives
// applies), and a table with meshes among its primitives.
inline std::vector<std::string> primitiveSceneFiles() {
  std::vector<std::string> files;
  for (const std::string& f : sceneFiles()) {
    const SceneSpec spec = loadScene(f);
    if (std::any_of(spec.environment.begin(), spec.environment.end(),
                    [](const EnvironmentObject& o) {
                      return o.kind == EnvironmentObject::Kind::kPrimitive;
                    })) {
      files.push_back(f);
    }
  }
  files.push_back(std::string(OCTOMOTION_TEST_DATA_DIR) + "/scenes/mixed_table.yaml");
  return files;
}

inline std::string sceneLabel(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

// gtest parameter names: letters, digits and underscores only.
inline std::string testName(const std::string& path) {
  std::string name = sceneLabel(path);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

// Arms at 2 cm (fast to build, and coarse enough that the margins matter); rigid bodies at
// their scene's resolution (auto when it has none), since they are small next to 2 cm.
inline PlanningScene loadValidationScene(const std::string& path, Rounding rounding,
                                         const std::string& checker = "octree-fused",
                                         std::optional<double> self_link_resolution = {},
                                         bool exact_primitives = false) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  SceneOverrides overrides;
  overrides.rounding = rounding;
  overrides.checker = checker;
  overrides.self_link_resolution = self_link_resolution;
  overrides.exact_primitives = exact_primitives;
  const SceneSpec spec = loadScene(path);
  bool arm = !spec.robot.urdf.empty();
  if (arm) {
    // A URDF without movable joints is a rigid body (loadPlanningScene makes it free-flying).
    RobotModelOptions options;
    options.package_paths = spec.robot.package_paths;
    arm = RobotModel::fromUrdfFile(spec.robot.urdf, options).variableCount() > 0;
  }
  if (arm) overrides.resolution = 0.02;
  return loadPlanningScene(path, overrides);
}

// One configuration: joint values (arms) or a base pose (free-flying bodies).
struct Sample {
  std::vector<double> q;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

// Uniform in the joint limits (continuous joints over [-pi, pi]); free-flying bodies uniform in
// the scene's position bounds with a uniformly random orientation (Shoemake's method).
inline std::vector<Sample> uniformSamples(const PlanningScene& scene, std::size_t count,
                                          std::uint64_t seed) {
  const RobotModel& robot = scene.model->robot();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Sample> samples(count);
  for (Sample& s : samples) {
    s.q.resize(static_cast<std::size_t>(robot.variableCount()));
    for (std::size_t k = 0; k < s.q.size(); ++k) {
      const Variable& v = robot.variables()[k];
      s.q[k] = v.lower + (v.upper - v.lower) * unit(rng);
    }
    if (robot.isFreeFlying()) {
      const Eigen::AlignedBox3d& bounds = *scene.spec.problem.bounds;
      const Eigen::Vector3d u(unit(rng), unit(rng), unit(rng));
      s.X_WB.translation() = bounds.min() + bounds.sizes().cwiseProduct(u);
      const double a = unit(rng), b = 2 * M_PI * unit(rng), c = 2 * M_PI * unit(rng);
      const Eigen::Quaterniond r(std::sqrt(a) * std::cos(c), std::sqrt(1 - a) * std::sin(b),
                                 std::sqrt(1 - a) * std::cos(b), std::sqrt(a) * std::sin(c));
      s.X_WB.linear() = r.normalized().toRotationMatrix();
    } else {
      s.X_WB = scene.model->baseMount();
    }
  }
  return samples;
}

// The exact reference of a scene: FCL on its primitives and meshes. Point clouds and OctoMaps
// are voxels by definition ("every voxel holding a point is an obstacle"), so their exact
// geometry is their own voxels on the octree model's grid, given to FCL as boxes.
inline std::shared_ptr<const FclCollisionModel> exactReference(const PlanningScene& scene) {
  bool voxel_objects = false;
  for (const auto& item : scene.environment->items()) {
    voxel_objects |= item.spec.kind == EnvironmentObject::Kind::kPointCloud ||
                     item.spec.kind == EnvironmentObject::Kind::kOctomap;
  }
  if (!voxel_objects) return scene.fcl_model;
  std::vector<EnvironmentObject> objects;
  const WorldGrid& grid = scene.model->grid();
  for (const auto& item : scene.environment->items()) {
    if (item.spec.kind != EnvironmentObject::Kind::kPointCloud &&
        item.spec.kind != EnvironmentObject::Kind::kOctomap) {
      objects.push_back(item.spec);
      continue;
    }
    const Octree voxels =
        EnvironmentGeometry::load({item.spec}).voxelize(grid, scene.spec.octree.rounding);
    voxels.forEachBlackLeaf([&](const Cube& c) {
      EnvironmentObject box;
      box.name = item.spec.name + " voxel";
      const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
      box.primitive = Box{(hi - lo) / 2};
      box.X_WO = Eigen::Translation3d((lo + hi) / 2) * Eigen::Isometry3d::Identity();
      objects.push_back(box);
    });
  }
  return std::make_shared<const FclCollisionModel>(
      scene.model->robot(), EnvironmentGeometry::load(objects),
      scene.spec.robot.keep_mesh_root_transform, scene.spec.robot.center_mesh_vertices);
}

// The octree model's voxel sizes, from which the margins of docs/validation.md follow.
struct Resolutions {
  double environment;  // r_e
  double link;         // r_l
  double self_link;    // r_s: the trees of the self pairs (r_l unless self_link_resolution)
};
inline Resolutions resolutionsOf(const OctreeCollisionModel& model) {
  return {model.grid().voxelSize(), model.report().link_resolution,
          model.report().self_link_resolution};
}

// Slack for floating-point ties in the voxelizers and FCL's distance (1 um, far below a voxel).
inline constexpr double kTieSlack = 1e-6;

}  // namespace octomotion::validation
